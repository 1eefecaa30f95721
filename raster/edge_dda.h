/* zscan raster — the exact integer DDA of an edge (scanline.c's header
 * comment derives it), inline for the scan's inner loop and shared with
 * the trace, which reports the scan's own integers. */
#ifndef ZS_RASTER_EDGE_DDA_H
#define ZS_RASTER_EDGE_DDA_H

#include "raster/scan.h"

/* floor(a / d) for d > 0: C's quotient truncates, so one less where
 * the remainder is negative.  Without a branch on a's sign, which the
 * scan's edges take either way at random. */
static inline int64_t zs_floor_div(int64_t a, int64_t d) {
  const int64_t q = a / d;
  return q - (a - q * d < 0);
}

/* The edge's DDA on row `row`: x the first column whose centre lies at or
 * right of the edge, rem = x D - num.  Worked in 64 bits, kept in 32: the
 * guard band keeps |X|, |Y| below 2^23 subpixels (raster.h), so
 * D = 256 (Y1 - Y0) < 2^32, rem and rs lie in [0, D), and |x|, |q| are
 * below 2^24.  The step down a row (q, rs) only where it is taken, when
 * steps is 0: on the edge's last row none is, and the division it costs
 * is saved (the polygon-order traversal, which reports no steps; the scan keeps them all,
 * as the trace reports them). */
static inline void zs_edge_dda_begin(zs_edge_dda *s, const zs_edge *e, int32_t row,
                                     const int steps) {
  const int64_t dy = (int64_t)e->Y1 - e->Y0, dx = (int64_t)e->X1 - e->X0, d = 256 * dy;
  const int64_t num = ((int64_t)e->X0 - 128) * dy + ((int64_t)row * 256 + 128 - e->Y0) * dx;
  const int64_t x = zs_floor_div(num + d - 1, d); /* ceil */
  s->x = (int32_t)x;
  s->d = (uint32_t)d;
  s->rem = (uint32_t)(x * d - num);
  s->last = zs_last_row(e->Y1);
  if (steps || row < s->last) {
    const int64_t q = zs_floor_div(256 * dx, d);
    s->q = (int32_t)q;
    s->rs = (uint32_t)(256 * dx - q * d);
  } else {
    s->q = 0;
    s->rs = 0;
  }
}

static inline void zs_edge_dda_start(zs_edge_dda *s, const zs_edge *e, int32_t row) {
  zs_edge_dda_begin(s, e, row, 1);
}

/* One row down: num grows by q D + rs.  The carry without a branch: its
 * pattern follows the edge's slope, which the branch predictor cannot
 * learn across thousands of small edges.  rem - rs + D lies in [0, D),
 * so the sum wraps back to it in 32 bits. */
static inline void zs_edge_dda_step(zs_edge_dda *s) {
  const uint32_t carry = s->rem < s->rs;
  s->rem = s->rem - s->rs + (s->d & -carry);
  s->x += s->q + (int32_t)carry;
}

#endif
