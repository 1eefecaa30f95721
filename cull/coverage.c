/* The screen coverage that nohc accumulates (coverage.h). */
#include "cull/coverage.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/exactmath.h"
#include "util/grow.h"
#include "raster/raster.h"

int zs_coverage_reset(zs_coverage *c, int width, int height, const double view[16],
                      const double proj[16]) {
  c->w = (width + ZS_COVERAGE_CELL - 1) / ZS_COVERAGE_CELL;
  c->h = (height + ZS_COVERAGE_CELL - 1) / ZS_COVERAGE_CELL;
  if (!zs_grow((void **)&c->cell, &c->cap, (int64_t)c->w * c->h, sizeof *c->cell)) return 0;
  memset(c->cell, 0, (size_t)c->w * (size_t)c->h * sizeof *c->cell);
  c->width = width;
  c->height = height;
  zs_mat_mul(c->mvp, proj, view);
  return 1;
}

void zs_coverage_free(zs_coverage *c) {
  free(c->cell);
  memset(c, 0, sizeof *c);
}

void zs_coverage_rect(const zs_coverage *c, const double lo[3], const double hi[3], double r[4]) {
  const double *m = c->mvp;
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (int b = 0; b < 8; b++) {
    double p[3] = {(b & 1) ? hi[0] : lo[0], (b & 2) ? hi[1] : lo[1], (b & 4) ? hi[2] : lo[2]};
    double cw = m[12] * p[0] + m[13] * p[1] + m[14] * p[2] + m[15];
    if (!(cw > 1e-9)) {
      r[0] = r[1] = 0.0, r[2] = c->width, r[3] = c->height;
      return;
    }
    double x = 0.5 * ((m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3]) / cw + 1.0) * c->width;
    double y = 0.5 * ((m[4] * p[0] + m[5] * p[1] + m[6] * p[2] + m[7]) / cw + 1.0) * c->height;
    x0 = fmin(x0, x), x1 = fmax(x1, x), y0 = fmin(y0, y), y1 = fmax(y1, y);
  }
  r[0] = fmax(x0, 0.0), r[1] = fmax(y0, 0.0), r[2] = fmin(x1, c->width), r[3] = fmin(y1, c->height);
}

/* Runs body for every cell that rectangle r meets, with cell pointing at
 * its coverage and overlap the pixels they share. */
#define FOR_EACH_CELL(c, r, cell, overlap, body)                                                    \
  for (int32_t cy_ = (int32_t)((r)[1] / ZS_COVERAGE_CELL); cy_ * ZS_COVERAGE_CELL < (r)[3]; cy_++) \
    for (int32_t cx_ = (int32_t)((r)[0] / ZS_COVERAGE_CELL); cx_ * ZS_COVERAGE_CELL < (r)[2];      \
         cx_++) {                                                                                  \
      double *cell = &(c)->cell[cy_ * (c)->w + cx_];                                               \
      double overlap = (fmin((r)[2], (cx_ + 1) * ZS_COVERAGE_CELL) -                               \
                        fmax((r)[0], cx_ * ZS_COVERAGE_CELL)) *                                    \
                       (fmin((r)[3], (cy_ + 1) * ZS_COVERAGE_CELL) -                               \
                        fmax((r)[1], cy_ * ZS_COVERAGE_CELL));                                     \
      body                                                                                         \
    }

void zs_coverage_add(zs_coverage *c, const double r[4], double fill) {
  FOR_EACH_CELL(c, r, cell, overlap,
                { *cell += fill * overlap / (ZS_COVERAGE_CELL * ZS_COVERAGE_CELL); })
}

double zs_coverage_covered(const zs_coverage *c, const double r[4]) {
  double p = 1.0;
  FOR_EACH_CELL(c, r, cell, overlap, {
    (void)overlap;
    p *= 1.0 - zs_exp(-*cell);
    if (p < 1e-9) return 0.0;
  })
  return p;
}
