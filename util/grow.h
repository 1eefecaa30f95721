/* zscan raster — growing an array by doubling.
 *
 * One helper for every growable array of the project (the raster's batch,
 * the culler's queues, the calibration meshes): the capacity doubles from
 * a first 64 until it holds need elements of size bytes.  On failure the
 * array and its capacity are left as they were. */
#ifndef ZS_RASTER_GROW_H
#define ZS_RASTER_GROW_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

static inline int zs_grow(void **p, int32_t *cap, int64_t need, size_t size) {
  if (need <= *cap) return 1;
  if (need > INT32_MAX) return 0;
  int64_t n = *cap > 0 ? *cap : 64;
  while (n < need) n *= 2;
  if (n > INT32_MAX) n = INT32_MAX;
  void *q = realloc(*p, (size_t)n * size);
  if (!q) return 0;
  *p = q;
  *cap = (int32_t)n;
  return 1;
}

/* Resizes n parallel arrays to cap elements each: *arrays[i], of
 * sizes[i] bytes an element.  On failure (0) every array is still valid
 * (some at the new size); the caller keeps its old capacity. */
static inline int zs_resize_each(void **const arrays[], const size_t sizes[], int n,
                                 size_t cap) {
  int ok = 1;
  for (int i = 0; i < n; i++) {
    void *q = realloc(*arrays[i], cap * sizes[i]);
    if (q) *arrays[i] = q;
    else ok = 0;
  }
  return ok;
}

#endif
