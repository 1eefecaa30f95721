/* zscan tools — the Gouraud intensities of `zscan trace` (cmd_trace.c):
 * each corner's intensity I, stepped along the active edges and across
 * the span as the textbook's scanline algorithm does, in exact fractions.
 *
 * I is the corner's vertex colour, red channel (0 .. 255): the value
 * `--shade unlit` interpolates.  The trace's edges are the corners
 * snapped to 1/256 pixel, and an edge's end takes the intensity of the
 * corner of its polygon snapped there (none: the polygon was clipped).
 * Under an orthographic view zscan's perspective-correct interpolation is
 * linear on the screen, so these are the values it computes, to the
 * rounding of a byte and the 1/512 pixel of the snapping. */
#ifndef ZS_TOOLS_CMD_TRACE_GOURAUD_H
#define ZS_TOOLS_CMD_TRACE_GOURAUD_H

#include <stddef.h>
#include <stdint.h>

#include "scene/scene.h"
#include "zscan/trace.h"

/* A rational n / d (d > 0, reduced); where it would not fit 64 bits,
 * only v, the value in double, holds (exact 0). */
typedef struct zs_q {
  int64_t n, d;
  int exact;
  double v;
} zs_q;

/* "n", "n/d", or v to 9 digits when not exact. */
void zs_q_str(char *buf, size_t size, zs_q q);

typedef struct zs_gouraud_corner {
  uint32_t id;     /* the polygon's */
  int32_t X, Y;    /* snapped, 1/256 pixel, image coordinates */
  int32_t I;       /* 0 .. 255 */
  int32_t order;   /* its place among them all, for a stable sort */
} zs_gouraud_corner;

typedef struct zs_gouraud {
  zs_gouraud_corner *corner; /* sorted by id */
  int32_t ncorners;
  zs_trace_edge *edges;      /* the tables' edges, batch order */
  int32_t (*edge_I)[2];      /* per edge: I at (X0, Y0) and at (X1, Y1), -1: none */
  int32_t nedges;
  uint32_t bent_id;          /* the first polygon whose corners' I are not on one
                              * plane (zscan shades it as a fan), if nbent */
  int32_t nbent;
} zs_gouraud;

/* The intensities of an active edge pair on row y. */
typedef struct zs_gouraud_pair {
  zs_q Il, dIl, Ir, dIr; /* at the edges' crossings of the row centre, per row down */
  zs_q dIx;              /* per column right: (Ir - Il) / (xr - xl) */
  int has_dIx;           /* 0 where xr = xl */
} zs_gouraud_pair;

/* Whether any mesh of scene has vertex colours. */
int zs_gouraud_scene_has(const zs_scene *scene);
/* The corners of every face with vertex colours in scene, seen through
 * view and proj in a width x height image (0: out of memory). */
int zs_gouraud_corners(zs_gouraud *g, const zs_scene *scene, const double view[16],
                       const double proj[16], int width, int height);
/* Whether any face has them. */
static inline int zs_gouraud_any(const zs_gouraud *g) { return g->ncorners > 0; }
/* The tables' polygons and edges as the walk handed them (0: out of
 * memory): each edge's ends given their intensities, a polygon's edges
 * all or none. */
int zs_gouraud_edges(zs_gouraud *g, const zs_trace_poly *polys, int npolys,
                     const zs_trace_edge *edges, int nedges);
/* Edge k's intensity at the centre of row y and per row down (0: none). */
int zs_gouraud_edge_at(const zs_gouraud *g, int32_t k, int32_t y, zs_q *I, zs_q *dI);
/* The pair p's on row y (0: none). */
int zs_gouraud_pair_of(const zs_gouraud *g, const zs_trace_pair *p, int32_t y,
                       zs_gouraud_pair *out);
/* The intensity at column x of the pair's span: Il + (x - xl) dIx. */
double zs_gouraud_at(const zs_gouraud_pair *gp, const zs_trace_pair *p, int64_t x);
void zs_gouraud_free(zs_gouraud *g);

#endif
