/* zscan raster — set-up (setup.c): a clipped or unclipped polygon snapped
 * to the sub-pixel grid (raster.h, FIXED POINT), its fixed-point depth
 * plane and its left and right edge chains appended to a batch. */
#ifndef ZS_RASTER_SETUP_H
#define ZS_RASTER_SETUP_H

#include <math.h>

#include "raster/batch.h"
#include "raster/clip.h"

typedef struct zs_setup_params {
  int width, height;
  int cull_back;
  uint32_t id, rgb;
  uint32_t depth_bias;  /* depth units (2^-32) to pull the plane nearer */
  int prefetch_write;   /* ask for the batch's lines ahead of the writes (setup.c) */
} zs_setup_params;

typedef enum zs_setup_result {
  ZS_SETUP_DRAWN,
  ZS_SETUP_BACK,
  ZS_SETUP_DEGENERATE,
  ZS_SETUP_OFFSCREEN, /* no pixel centre of the window in its box */
  ZS_SETUP_NOMEM
} zs_setup_result;

/* Snaps the clipped polygon to the sub-pixel grid, computes its depth plane
 * and edge chains, and appends it (or, if snapping left it not convex, a
 * fan of triangles with the same plane) to the batch. */
zs_setup_result zs_setup_polygon(zs_batch *b, const zs_setup_params *p,
                                 const zs_clip_vert *v, int n);

/* A vertex snapped: window x and image y in 1/256 pixel, window depth in
 * [0, 1].  zs_setup_polygon snaps each vertex with zs_snap_vertex; a draw
 * snaps each vertex of its mesh once and hands an unclipped face's
 * vertex indices to zs_setup_snapped, which gives the same result. */
typedef struct zs_snap_vert {
  int32_t x, y;
  double z;
} zs_snap_vert;

/* Where a vertex (w > 0) lands in a width x height window, in pixels: x
 * from the left, y from the bottom (the image's rows run down from
 * height - y). */
static inline void zs_window_xy(int width, int height, const zs_clip_vert *v, double *xw,
                                double *yw) {
  *xw = (v->x / v->w + 1.0) * (0.5 * width);
  *yw = (v->y / v->w + 1.0) * (0.5 * height);
}
/* Its window depth, in [0, 1] inside the near and far planes. */
static inline double zs_window_depth(const zs_clip_vert *v) { return (v->z / v->w + 1.0) * 0.5; }

static inline void zs_snap_vertex(const zs_setup_params *sp, const zs_clip_vert *v,
                                  zs_snap_vert *out) {
  const int64_t h_sub = (int64_t)sp->height * ZS_SUBPIXEL_ONE;
  double xw, yw;
  zs_window_xy(sp->width, sp->height, v, &xw, &yw);
  double zw = zs_window_depth(v);
  out->x = (int32_t)llrint(xw * ZS_SUBPIXEL_ONE);
  /* The difference wraps, as the vector stage's does (vertex_simd.c): a
   * vertex inside every plane at w = 0 (the eye, under a projection that
   * allows it) has no window position, and llrint gives its NaN the
   * integer indefinite, which subtracted in signed arithmetic would
   * overflow.  (llrint, not lrint: 64 bits where long has 32, on Windows
   * and i686, so that the indefinite, and the vector stage, agree.) */
  out->y = (int32_t)(uint32_t)((uint64_t)h_sub - (uint64_t)llrint(yw * ZS_SUBPIXEL_ONE));
  out->z = zw < 0.0 ? 0.0 : zw > 1.0 ? 1.0 : zw;
}
/* The polygon v[vi[0]], .., v[vi[n - 1]]. */
zs_setup_result zs_setup_snapped(zs_batch *b, const zs_setup_params *p,
                                 const zs_snap_vert *v, const int32_t *vi, int n);


#endif
