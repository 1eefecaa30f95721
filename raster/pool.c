/* A small pool of worker threads (pool.h).
 *
 * A job is published as one 64-bit word, state = generation << 32 |
 * ntasks << 16 | next: a worker claims task `next` with a compare-and-swap
 * that succeeds only while the word still names the job it joined, so a
 * worker that comes late can never take a task of the following job with
 * the previous job's function.  Workers and the caller spin a little
 * before they sleep on a condition variable: a frame runs its jobs in
 * quick succession, and waking a sleeping thread costs more than a short
 * wait (zscan bench raster --threads 2 --speedup measures it). */
#include "raster/pool.h"

#include "raster/tuning.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>


struct zs_pool {
  pthread_t *workers;
  int nworkers;
  pthread_mutex_t lock;
  pthread_cond_t work, done;
  void (*fn)(void *ctx, int task);
  void *ctx;
  _Atomic uint64_t state;   /* generation, ntasks, next: see above */
  _Atomic int finished;     /* tasks of the current job done */
  _Atomic int quit;
};

static uint32_t generation_of(uint64_t s) { return (uint32_t)(s >> 32); }
static int ntasks_of(uint64_t s) { return (int)((s >> 16) & 0xFFFF); }
static int next_of(uint64_t s) { return (int)(s & 0xFFFF); }

/* Takes tasks of job gen until there are none left; returns how many it
 * ran. */
static int take_tasks(zs_pool *p, uint32_t gen) {
  int ran = 0;
  uint64_t s = atomic_load_explicit(&p->state, memory_order_acquire);
  for (;;) {
    if (generation_of(s) != gen || next_of(s) >= ntasks_of(s)) return ran;
    if (!atomic_compare_exchange_weak_explicit(&p->state, &s, s + 1, memory_order_acq_rel,
                                               memory_order_acquire))
      continue; /* s now holds the current word */
    p->fn(p->ctx, next_of(s));
    ran++;
    s = atomic_load_explicit(&p->state, memory_order_acquire);
  }
}

static void *worker(void *arg) {
  zs_pool *p = arg;
  uint32_t seen = 0;
  for (;;) {
    uint32_t gen = seen;
    for (int i = 0; i < ZS_POOL_SPINS && gen == seen; i++) {
      if (atomic_load_explicit(&p->quit, memory_order_relaxed)) return NULL;
      gen = generation_of(atomic_load_explicit(&p->state, memory_order_acquire));
    }
    if (gen == seen) {
      pthread_mutex_lock(&p->lock);
      while (!atomic_load(&p->quit) &&
             (gen = generation_of(atomic_load(&p->state))) == seen)
        pthread_cond_wait(&p->work, &p->lock);
      pthread_mutex_unlock(&p->lock);
      if (atomic_load(&p->quit)) return NULL;
    }
    seen = gen;
    int ran = take_tasks(p, gen);
    if (ran > 0) {
      uint64_t s = atomic_load_explicit(&p->state, memory_order_acquire);
      int total = atomic_fetch_add_explicit(&p->finished, ran, memory_order_acq_rel) + ran;
      if (total == ntasks_of(s)) {
        pthread_mutex_lock(&p->lock);
        pthread_cond_signal(&p->done);
        pthread_mutex_unlock(&p->lock);
      }
    }
  }
}

zs_pool *zs_pool_create(int nthreads) {
  if (nthreads < 2) return NULL;
  zs_pool *p = calloc(1, sizeof *p);
  if (!p) return NULL;
  p->workers = calloc((size_t)nthreads - 1, sizeof *p->workers);
  if (!p->workers) {
    free(p);
    return NULL;
  }
  atomic_init(&p->state, 0);
  atomic_init(&p->finished, 0);
  atomic_init(&p->quit, 0);
  pthread_mutex_init(&p->lock, NULL);
  pthread_cond_init(&p->work, NULL);
  pthread_cond_init(&p->done, NULL);
  for (int i = 0; i < nthreads - 1; i++) {
    if (pthread_create(&p->workers[i], NULL, worker, p) != 0) break;
    p->nworkers++;
  }
  return p;
}

void zs_pool_destroy(zs_pool *p) {
  if (!p) return;
  pthread_mutex_lock(&p->lock);
  atomic_store(&p->quit, 1);
  pthread_cond_broadcast(&p->work);
  pthread_mutex_unlock(&p->lock);
  for (int i = 0; i < p->nworkers; i++) pthread_join(p->workers[i], NULL);
  pthread_cond_destroy(&p->work);
  pthread_cond_destroy(&p->done);
  pthread_mutex_destroy(&p->lock);
  free(p->workers);
  free(p);
}

void zs_pool_run(zs_pool *p, void (*fn)(void *ctx, int task), void *ctx, int ntasks) {
  if (ntasks < 1) return;
  /* the job word holds 16 bits of tasks (callers run at most 64): any
   * beyond run here first, so that none is dropped */
  for (int t = 0xFFFF; t < ntasks; t++) fn(ctx, t);
  if (ntasks > 0xFFFF) ntasks = 0xFFFF;
  /* The previous job is finished, so no worker reads fn or ctx now. */
  p->fn = fn;
  p->ctx = ctx;
  atomic_store_explicit(&p->finished, 0, memory_order_relaxed);
  uint32_t gen = generation_of(atomic_load(&p->state)) + 1;
  atomic_store_explicit(&p->state, (uint64_t)gen << 32 | (uint64_t)ntasks << 16,
                        memory_order_release);
  /* sleepers check the word under the lock: none can miss this */
  pthread_mutex_lock(&p->lock);
  pthread_cond_broadcast(&p->work);
  pthread_mutex_unlock(&p->lock);
  int ran = take_tasks(p, gen);
  int total = ran > 0 ? atomic_fetch_add_explicit(&p->finished, ran, memory_order_acq_rel) + ran
                      : atomic_load_explicit(&p->finished, memory_order_acquire);
  for (int i = 0; i < ZS_POOL_SPINS && total < ntasks; i++)
    total = atomic_load_explicit(&p->finished, memory_order_acquire);
  if (total < ntasks) {
    pthread_mutex_lock(&p->lock);
    while (atomic_load(&p->finished) < ntasks) pthread_cond_wait(&p->done, &p->lock);
    pthread_mutex_unlock(&p->lock);
  }
}
