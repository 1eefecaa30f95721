/* zscan — watching the scanline walk, for teaching: the sorted tables, the
 * active edge pairs and the spans of every row.  An extra to zscan.h. */
#ifndef ZSCAN_TRACE_H
#define ZSCAN_TRACE_H

#include <stdint.h>

#include "zscan/zscan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- trace: watching the scanline walk (scanline.c) ----
 *
 * For teaching, the scanline mode can report its data structures: once per
 * frame the sorted polygon and edge tables, then after each row the active
 * edge list (one pair per active polygon, as it stood for that row) and the
 * spans filled.  Coordinates are image coordinates (y down) with pixel
 * centres at whole numbers ("pixel-centre units": column c has centre
 * x = c), so the lecture's x values read directly.  Each value is given in
 * the fixed point the walk uses and in real units beside it. */
typedef struct zs_trace_poly {
  uint32_t id, rgb;
  int32_t row0, row1;    /* first and last row covered (dy = row1 - row0) */
  int32_t ox, oy;        /* plane origin pixel */
  int zshift;            /* fraction bits beyond the 32 of the depth */
  int64_t zc, dzdx, dzdy;/* fixed-point plane (raster.h, DEPTH) */
  double z0, dzx, dzy;   /* the same in window depth: z at (ox, oy), per
                            pixel right (the lecture's -a/c), per row down */
  int32_t first_edge, nleft, nright;
} zs_trace_poly;

typedef struct zs_trace_edge {
  uint32_t id;
  int side;              /* 0: left chain, 1: right chain */
  int32_t row0, row1;    /* rows covered */
  int32_t X0, Y0, X1, Y1;/* end points, 1/256 pixel, image coordinates */
  double x_top;          /* x at the centre of row0, pixel-centre units */
  double dx;             /* x per row down (the lecture's -1/k) */
} zs_trace_edge;

typedef struct zs_trace_pair {
  uint32_t id;
  int32_t dy;            /* the polygon's rows left after this one */
  int64_t xl, xr;        /* first column at or right of each edge */
  int64_t reml, dl, remr, dr;  /* edge x = xl - reml / dl (exact) */
  double xl_real, xr_real;     /* edge x at the row centre */
  double dxl, dxr;       /* per row down */
  int64_t dxl_num, dxr_num;    /* dxl = dxl_num / dl exactly, likewise dxr */
  int32_t dyl, dyr;      /* rows left on each edge after this one */
  int64_t zl;            /* fixed-point depth at (xl, y) */
  double zl_real, dzx, dzy;
  int zshift;
  int32_t left, right;   /* the current edges: their places in the edges the
                            tables were handed (batch order, not sorted) */
} zs_trace_pair;

typedef struct zs_trace_span {
  int32_t x0, x1;        /* columns, x1 inclusive, clipped to the image */
  uint32_t id;
} zs_trace_span;

typedef struct zs_trace_row {
  int y;
  const zs_trace_pair *pairs;
  int npairs;
  const zs_trace_span *spans;
  int nspans;
} zs_trace_row;

typedef struct zs_trace_observer {
  void (*tables)(void *user, const zs_trace_poly *polys, int npolys,
                 const zs_trace_edge *edges, int nedges);
  void (*row)(void *user, const zs_trace_row *row); /* before the row's sink */
  void *user;
} zs_trace_observer;

/* Watch the scanline walk of the following frames (scanline mode only);
 * NULL stops.  The observer must outlive the frames. */
void zs_device_set_trace(zs_device *dev, const zs_trace_observer *obs);

#ifdef __cplusplus
}
#endif

#endif
