/* zscan cull — an axis-aligned box and the few things done with one, for
 * the octree's tight bounds (octree.c) and the parts of an object
 * (parts.c).  The public API passes boxes as lo/hi arrays; this type is
 * internal to cull/.
 *
 * The empty box has lo = +inf and hi = -inf, so that adding a box to it
 * gives that box, and it is the only box with lo > hi. */
#ifndef ZS_CULL_BOX_H
#define ZS_CULL_BOX_H

#include <math.h>

typedef struct zs_box {
  double lo[3], hi[3];
} zs_box;

static inline zs_box zs_box_empty(void) {
  return (zs_box){{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
}

static inline int zs_box_is_empty(const zs_box *b) { return b->lo[0] > b->hi[0]; }

static inline zs_box zs_box_of(const double lo[3], const double hi[3]) {
  return (zs_box){{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}};
}

/* Grows b to hold lo .. hi (a point: lo = hi). */
static inline void zs_box_add(zs_box *b, const double lo[3], const double hi[3]) {
  for (int k = 0; k < 3; k++) {
    if (lo[k] < b->lo[k]) b->lo[k] = lo[k];
    if (hi[k] > b->hi[k]) b->hi[k] = hi[k];
  }
}

static inline void zs_box_add_box(zs_box *b, const zs_box *o) { zs_box_add(b, o->lo, o->hi); }

static inline int zs_box_eq(const zs_box *a, const zs_box *b) {
  for (int k = 0; k < 3; k++)
    if (a->lo[k] != b->lo[k] || a->hi[k] != b->hi[k]) return 0;
  return 1;
}

static inline double zs_box_volume(const zs_box *b) {
  return zs_box_is_empty(b) ? 0.0
                            : (b->hi[0] - b->lo[0]) * (b->hi[1] - b->lo[1]) * (b->hi[2] - b->lo[2]);
}

/* Whether box lo .. hi lies inside blo .. bhi (closed). */
static inline int zs_box_inside(const double lo[3], const double hi[3], const double blo[3],
                                const double bhi[3]) {
  for (int k = 0; k < 3; k++)
    if (!(lo[k] >= blo[k] && hi[k] <= bhi[k])) return 0;
  return 1;
}

#endif
