/* zscan cull — the screen coverage that nohc accumulates front to back.
 *
 * A grid of ZS_COVERAGE_CELL-pixel cells over the image.  Each cell holds
 * d, the projected areas (in cells) of what was drawn into it this frame;
 * a cell is covered with probability 1 - e^-d (drawn boxes fall on it as a
 * Poisson process).  Estimates only: they choose what to ask, never what
 * to draw. */
#ifndef ZS_CULL_COVERAGE_H
#define ZS_CULL_COVERAGE_H

#include <stdint.h>

enum { ZS_COVERAGE_CELL = 16 };

typedef struct zs_coverage {
  double *cell;
  int32_t w, h, cap;       /* cells across and down; capacity */
  double width, height;    /* the image, pixels */
  double mvp[16];          /* world to clip */
} zs_coverage;

/* An empty grid for a width x height image seen through proj * view;
 * returns 0 when out of memory. */
int zs_coverage_reset(zs_coverage *c, int width, int height, const double view[16],
                      const double proj[16]);
void zs_coverage_free(zs_coverage *c);

/* The window rectangle x0, y0, x1, y1 of a box's projection, clamped to
 * the image; the whole image when a corner lies behind the eye. */
void zs_coverage_rect(const zs_coverage *c, const double lo[3], const double hi[3], double r[4]);

/* Adds fill times the overlap of rectangle r to the cells it meets. */
void zs_coverage_add(zs_coverage *c, const double r[4], double fill);

/* The chance that what was added covers all of rectangle r: every cell it
 * meets covered, each with probability 1 - e^-d. */
double zs_coverage_covered(const zs_coverage *c, const double r[4]);

#endif
