/* zscan raster — a small pool of worker threads (pthreads) for running the
 * bands of a scan in parallel.  Deterministic by construction: each task
 * writes only its own rows and counters, and the caller sums the counters
 * in task order. */
#ifndef ZS_RASTER_POOL_H
#define ZS_RASTER_POOL_H

#include <stdint.h>

typedef struct zs_pool zs_pool;

/* A pool of nthreads - 1 workers (the caller is the last); NULL when out of
 * memory or nthreads < 2. */
zs_pool *zs_pool_create(int nthreads);
void zs_pool_destroy(zs_pool *p);

/* Runs fn(ctx, task) for task = 0 .. ntasks - 1 on the workers and the
 * caller, and returns when every task is done. */
void zs_pool_run(zs_pool *p, void (*fn)(void *ctx, int task), void *ctx, int ntasks);

/* Parts that split n items evenly and in order: part p of k holds items
 * zs_part_start(n, p, k) .. zs_part_start(n, p + 1, k) - 1. */
static inline int64_t zs_part_start(int64_t n, int part, int nparts) {
  return n * part / nparts;
}

#endif
