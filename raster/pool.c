#include "raster/pool.h"

#include <pthread.h>
#include <stdlib.h>

struct zs_pool {
  pthread_t *workers;
  int nworkers;
  pthread_mutex_t lock;
  pthread_cond_t work, done;
  void (*fn)(void *ctx, int task);
  void *ctx;
  int ntasks, next, finished;
  unsigned generation;  /* a new job */
  int quit;
};

/* Takes tasks until there are none left; returns how many it ran. */
static int take_tasks(zs_pool *p) {
  int ran = 0;
  for (;;) {
    pthread_mutex_lock(&p->lock);
    int t = p->next < p->ntasks ? p->next++ : -1;
    pthread_mutex_unlock(&p->lock);
    if (t < 0) return ran;
    p->fn(p->ctx, t);
    ran++;
  }
}

static void *worker(void *arg) {
  zs_pool *p = arg;
  unsigned seen = 0;
  for (;;) {
    pthread_mutex_lock(&p->lock);
    while (!p->quit && p->generation == seen) pthread_cond_wait(&p->work, &p->lock);
    if (p->quit) {
      pthread_mutex_unlock(&p->lock);
      return NULL;
    }
    seen = p->generation;
    pthread_mutex_unlock(&p->lock);
    int ran = take_tasks(p);
    pthread_mutex_lock(&p->lock);
    p->finished += ran;
    if (p->finished == p->ntasks) pthread_cond_signal(&p->done);
    pthread_mutex_unlock(&p->lock);
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
  p->quit = 1;
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
  pthread_mutex_lock(&p->lock);
  p->fn = fn;
  p->ctx = ctx;
  p->ntasks = ntasks;
  p->next = 0;
  p->finished = 0;
  p->generation++;
  pthread_cond_broadcast(&p->work);
  pthread_mutex_unlock(&p->lock);
  int ran = take_tasks(p);
  pthread_mutex_lock(&p->lock);
  p->finished += ran;
  while (p->finished < p->ntasks) pthread_cond_wait(&p->done, &p->lock);
  pthread_mutex_unlock(&p->lock);
}
