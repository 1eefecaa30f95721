/* zscan raster — clipping (clip.c): clip-space vertices against the near
 * and far planes and the guard band (raster.h, FIXED POINT), so that
 * every snapped coordinate fits the integers set-up works in. */
#ifndef ZS_RASTER_CLIP_H
#define ZS_RASTER_CLIP_H

#include "raster/raster.h"

/* A polygon may gain one vertex per clip plane (6 planes). */
enum { ZS_CLIP_MAX_VERTS = ZS_MAX_POLY_VERTS + 6 };

/* A vertex after transformation: clip coordinates and eye coordinates. */
typedef struct zs_clip_vert {
  double x, y, z, w;
} zs_clip_vert;

/* Outcode bits of a clip-space vertex against near, far and the guard
 * band (gx, gy: the band's half-widths in NDC units). */
enum {
  ZS_CLIP_NEAR = 1, ZS_CLIP_FAR = 2,
  ZS_CLIP_LEFT = 4, ZS_CLIP_RIGHT = 8, ZS_CLIP_BOTTOM = 16, ZS_CLIP_TOP = 32
};
/* The signed distance of v from a plane, inside when >= 0.  Inline, with
 * the outcode and zs_snap_vertex below: a draw calls them once per vertex,
 * where a call costs more than the work it does (zscan bench raster --case
 * builtin:teapots --callgrind measures it). */
static inline double zs_clip_plane_dist(const zs_clip_vert *v, int plane, double gx, double gy) {
  switch (plane) {
    case ZS_CLIP_NEAR: return v->z + v->w;
    case ZS_CLIP_FAR: return v->w - v->z;
    case ZS_CLIP_LEFT: return gx * v->w + v->x;
    case ZS_CLIP_RIGHT: return gx * v->w - v->x;
    case ZS_CLIP_BOTTOM: return gy * v->w + v->y;
    default: return gy * v->w - v->y;
  }
}
static inline unsigned zs_clip_outcode(const zs_clip_vert *v, double gx, double gy) {
  unsigned code = 0;
  for (int p = ZS_CLIP_NEAR; p <= ZS_CLIP_TOP; p <<= 1)
    if (!(zs_clip_plane_dist(v, p, gx, gy) >= 0.0)) code |= (unsigned)p; /* NaN: out */
  return code;
}
/* Clips the convex polygon in[0..n-1] against every plane set in mask;
 * writes the result to out (ZS_CLIP_MAX_VERTS entries) and returns its
 * vertex count (0 when nothing is left). */
int zs_clip_polygon(const zs_clip_vert *in, int n, unsigned mask, double gx,
                    double gy, zs_clip_vert *out);
/* Clips the segment a-b to the same planes (all six); returns 0 when
 * nothing is left (hidden-line edges, lines.c). */
int zs_clip_segment(zs_clip_vert *a, zs_clip_vert *b, double gx, double gy);

#endif
