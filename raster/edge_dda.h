/* zscan raster — the exact integer DDA of an edge (scanline.c's header
 * comment derives it), inline for the walk's inner loop and shared with
 * the trace, which reports the walk's own integers. */
#ifndef ZS_RASTER_EDGE_DDA_H
#define ZS_RASTER_EDGE_DDA_H

#include "raster/internal.h"

static inline int64_t zs_floor_div(int64_t a, int64_t d) {
  return a >= 0 ? a / d : -((-a + d - 1) / d);
}

/* The edge's DDA on row `row`: x the first column whose centre lies at or
 * right of the edge, rem = x D - num. */
static inline void zs_edge_dda_start(zs_edge_dda *s, const zs_edge *e, int32_t row) {
  int64_t dy = (int64_t)e->Y1 - e->Y0, dx = (int64_t)e->X1 - e->X0;
  s->d = 256 * dy;
  int64_t num = ((int64_t)e->X0 - 128) * dy + ((int64_t)row * 256 + 128 - e->Y0) * dx;
  s->x = zs_floor_div(num + s->d - 1, s->d); /* ceil */
  s->rem = s->x * s->d - num;
  s->q = zs_floor_div(256 * dx, s->d);
  s->rs = 256 * dx - s->q * s->d;
  s->last = zs_last_row(e->Y1);
}

/* One row down.  The carry without a branch: its pattern follows the
 * edge's slope, which the branch predictor cannot learn across thousands
 * of small edges. */
static inline void zs_edge_dda_step(zs_edge_dda *s) {
  int64_t rem = s->rem - s->rs;
  int64_t carry = rem < 0;
  s->rem = rem + (s->d & -carry);
  s->x += s->q + carry;
}

#endif
