/* Deferred drawing (raster.h, zs_device_defer_draws; device.h).
 *
 * With two threads or more, a draw of a few hundred faces is too small to
 * split: waking the threads for its set-up or its scan costs more than it
 * saves (the plant's draws average 165 faces, a teapot's 688).  So while
 * deferral is on, zs_device_draw only queues the draw, and the next flush
 * renders the whole queue at once:
 *
 *   1. set-up in chunks: the queue is cut into runs of consecutive draws
 *      of about equal faces; each chunk transforms and sets up its draws
 *      into a batch, and every draw remembers where its polygons lie
 *      (batch, first, count) and the rows they cover;
 *   2. the scan in bands of rows: each band takes the chunks in order,
 *      and in each every draw in issue order, and scans that draw's
 *      polygons over the band's rows.  A pixel lies in one band, so it
 *      sees the fragments of the draws in the order they were issued,
 *      exactly as with immediate drawing: the same depth tests, the same
 *      writes, the same overwrites counted;
 *   3. settling, draw by draw in issue order: its set-up counters, its
 *      scan counters summed over the bands, and the clock: its GPU command
 *      charged as if issued when the CPU issued it (the CPU clock read at
 *      queueing time), so the modelled frame is also unchanged.
 *
 * Steps 1 and 2 overlap: a band scans a chunk as soon as the chunk is set
 * up and the band is through the chunk before it, and a free thread takes
 * such a scan before a new set-up, so a chunk's polygons are read while
 * still in the caches.  The chunks share ZS_DEFER_SLOTS_PER_THREAD batches a
 * thread in turn: a chunk is set up only when every band is through the
 * chunk that last used its batch, so the same few megabytes are written
 * over and over instead of the whole frame's polygons.  Setting up the
 * whole queue first and scanning it after would leave the scan reading
 * every polygon back from memory, a slower flush (zscan bench raster
 * --case builtin:plant --threads 2 measures it).
 *
 * The counters and the clock lag the queue until the flush, so deferral is
 * for callers that read them after zs_device_finish (a whole scene drawn,
 * lib/frame.c), not for culling, which reads the pixels of each draw.
 * A query, hidden-line edges, a draw of ZS_DEFER_MAX_FACES faces or more
 * (set up in parallel on its own) and finish flush first; clear drops the
 * queue (those draws would be cleared away with the frame).  An error in
 * a draw's set-up is reported at the flush, with the draws before it
 * rendered and the ones after it neither drawn nor counted, as when
 * drawing at once the caller would have stopped there. */
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "raster/device.h"
#include "raster/pool.h"
#include "util/grow.h"

/* The chunks a flush cuts its queue into, at most (the records' size). */
enum { MAX_CHUNKS = 64 };

typedef struct queued_draw {
  const zs_mesh *mesh;
  zs_draw_prep prep;
  uint32_t id_base, rgb;
  int64_t cpu_ps;          /* the CPU clock when it was issued */
  /* filled by the set-up */
  int32_t slot, poly0, npolys; /* slot: the batch its chunk was set up in */
  int32_t row0, row1;      /* rows its polygons cover (row0 > row1: none) */
  zs_face_counts fc;
  uint8_t set_up;          /* set up whole (else its chunk stopped at or before it) */
} queued_draw;

struct zs_deferred {
  queued_draw *q;
  int32_t n, cap;
  int64_t pending_ps;              /* the queued draws' CPU cost, charged at the flush */
  int32_t first[MAX_CHUNKS + 1];   /* chunk c: draws first[c] .. first[c + 1] - 1 */
  zs_batch batch[MAX_CHUNKS];      /* slot s: chunks c with c % nslots == s, in turn */
  zs_vert_scratch verts[MAX_CHUNKS];  /* the same, for their transformed vertices */
  zs_error err[MAX_CHUNKS];        /* per chunk, as st */
  zs_status st[MAX_CHUNKS];
  zs_scan_counts *counts;          /* [band][draw] */
  int32_t cap_counts;
  int32_t rows0, rows1;            /* rows the last flush's draws covered (rows1 < rows0: none yet) */
  pthread_mutex_t lock;            /* guards the flow of a flush (below) */
  pthread_cond_t changed;
  zs_status (*flush)(zs_device *d, zs_error *err); /* zbuffer or scanline mode's */
};

zs_status zs_defer_push(zs_device *d, const zs_mesh *mesh, const double model[16],
                        uint32_t id_base, uint32_t rgb, zs_error *err) {
  zs_deferred *q = d->deferred;
  if (mesh->nverts < 0 || mesh->nfaces < 0)
    return zs_error_set(err, ZS_ERR_ARG, "draw: negative mesh size");
  if (!zs_grow((void **)&q->q, &q->cap, q->n + 1, sizeof *q->q))
    return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
  /* When the CPU issues it: the draws queued before it charge the CPU's
   * clock only at the flush, each in turn as it settles */
  q->pending_ps += d->costs.cpu_per_call;
  queued_draw *e = &q->q[q->n++];
  memset(e, 0, sizeof *e);
  e->mesh = mesh;
  zs_draw_prepare(&d->drawing->prep, d->view, d->proj, model, &e->prep);
  e->id_base = id_base;
  e->rgb = rgb;
  e->cpu_ps = d->clock.cpu_ps + q->pending_ps;
  return ZS_OK;
}

/* ---- the flow of a flush ----
 *
 * Two kinds of task: set-up of a chunk (a run of consecutive draws), and
 * the scan of one band over one chunk.  Band b scans chunk c once chunk c
 * is set up and band b has scanned chunk c - 1, so every pixel still sees
 * the draws in issue order.  Each band has an owner, the task (thread)
 * that takes its scans first: task t owns a run of nbands / threads
 * bands in a row, so a band's rows of the frame stay in one core's caches
 * from chunk to chunk.  A free task takes, in turn of preference, a ready
 * scan of a band it owns (the chunk's polygons are still in the caches),
 * a set-up, a ready scan of another task's band; it waits (polling, then
 * asleep: ZS_FLUSH_SPINS) only while every task it could take waits on one
 * running.  Were any task to take any ready band, a band's rows would go
 * back and forth between the cores, and the span fill would wait on the
 * old depth it loads from the other core's cache (zscan bench raster
 * --case builtin:plant --threads 2 --speedup measures it). */

typedef struct flush_job {
  zs_device *d;
  zs_deferred *q;
  const zs_traversal *tr;
  zs_target t;
  int nbands, row0, rows;      /* bands split rows row0 .. row0 + rows - 1 */
  int nslots;                   /* chunk c is set up in batch c % nslots */
  int ok[ZS_MAX_BANDS];
  /* the flow, under q->lock */
  int next_setup;               /* the next chunk to set up */
  int last_chunk;               /* the last chunk to scan: a failed set-up ends the queue */
  int bands_left;               /* bands not through last_chunk */
  uint8_t set_up[MAX_CHUNKS];   /* chunk set up (whole, or up to its failed draw) */
  int band_next[ZS_MAX_BANDS];     /* the next chunk each band scans */
  uint8_t band_busy[ZS_MAX_BANDS];
  _Atomic uint32_t changes;     /* bumped under q->lock at each change of the flow */
} flush_job;

static void setup_chunk(flush_job *j, int c) {
  zs_deferred *q = j->q;
  /* a local copy of the chunk's batch and counters: the chunks' records
   * sit side by side, and a counter written per face beside another
   * thread's would bounce the cache line between the cores */
  int slot = c % j->nslots;
  zs_batch b = q->batch[slot];
  zs_vert_scratch v = q->verts[slot];
  zs_status st = ZS_OK;
  zs_error err;
  zs_error_clear(&err);
  zs_batch_reset(&b);
  for (int32_t i = q->first[c]; i < q->first[c + 1] && st == ZS_OK; i++) {
    queued_draw *e = &q->q[i];
    const zs_mesh *m = e->mesh;
    if (!zs_vert_scratch_reserve(&v, m->nverts > 0 ? m->nverts : 1)) {
      st = zs_error_set(&err, ZS_ERR_NOMEM, "draw: out of memory");
      break;
    }
    zs_draw_transform(&e->prep, m, &v, 0, m->nverts);
    zs_face_counts fc = {0, 0, 0, 0, 0, 0, 0};
    int32_t poly0 = b.npolys;
    st = zs_draw_setup(&e->prep, &v, m, 0, m->nfaces, e->id_base, e->rgb, NULL, &b, &fc, &err);
    e->fc = fc;
    /* a failed draw's polygons too: drawing at once leaves those set up
     * before its bad face in scanline mode's batch */
    e->slot = slot;
    e->poly0 = poly0;
    e->npolys = b.npolys - poly0;
    if (st != ZS_OK) break;
    zs_batch_rows(&b, poly0, e->npolys, j->d->cfg.height, &e->row0, &e->row1);
    e->set_up = 1;
  }
  q->batch[slot] = b;
  q->verts[slot] = v;
  q->st[c] = st;
  q->err[c] = err;
}

/* Cuts the queue into nfull runs of about equal weight (faces, plus one
 * per draw for its fixed work) followed by nsmall runs of a quarter of
 * that.  Small chunks last, so that the thread that runs out of work
 * first waits on a short scan or set-up, not on a whole chunk's, at the
 * end of the flush (zscan bench raster --case builtin:plant --threads 2
 * --speedup measures it). */
static void cut_chunks(zs_deferred *q, int nfull, int nsmall) {
  const int nchunks = nfull + nsmall;
  const uint64_t quarters = 4 * (uint64_t)nfull + (uint64_t)nsmall;
  uint64_t total = 0;
  for (int32_t i = 0; i < q->n; i++) total += (uint64_t)q->q[i].mesh->nfaces + 1;
  uint64_t acc = 0, done = 0; /* weight so far; quarters in the chunks cut */
  int c = 0;
  q->first[0] = 0;
  for (int32_t i = 0; i < q->n && c < nchunks - 1; i++) {
    acc += (uint64_t)q->q[i].mesh->nfaces + 1;
    const uint64_t next = done + (c < nfull ? 4 : 1);
    if (acc * quarters >= total * next) {
      q->first[++c] = i + 1;
      done = next;
    }
  }
  while (c < nchunks) q->first[++c] = q->n;
}

/* The first row of band b (b = nbands: the window's end).  The bands
 * split the rows the last flush covered, the first and the last reaching
 * out to the window's edges: which draw lands in which band changes no
 * pixel and no counter, only how evenly the threads share the scan, and
 * this flush's rows are known only once its draws are set up. */
static int flush_band_first_row(const flush_job *j, int b) {
  if (b == 0) return 0;
  if (b == j->nbands) return j->d->cfg.height;
  return j->row0 + (int)zs_part_start(j->rows, b, j->nbands);
}

/* Scans band over chunk c's draws; returns 0 when it met a draw not set
 * up (the queue ends there). */
static int scan_chunk(flush_job *j, int band, int c) {
  zs_deferred *q = j->q;
  int y0 = flush_band_first_row(j, band), y1 = flush_band_first_row(j, band + 1);
  zs_scan_counts *counts = &q->counts[(size_t)band * (size_t)q->n];
  for (int32_t i = q->first[c]; i < q->first[c + 1]; i++) {
    const queued_draw *e = &q->q[i];
    if (!e->set_up) return 0;
    counts[i] = (zs_scan_counts){0, 0, 0};
    int r0 = e->row0 > y0 ? e->row0 : y0, r1 = e->row1 + 1 < y1 ? e->row1 + 1 : y1;
    if (e->npolys == 0 || r0 >= r1) continue;
    const zs_batch *b = &q->batch[e->slot];
    /* the draw's polygons: their edges are indexed in the chunk's batch */
    zs_batch view = {b->polys + e->poly0, e->npolys, e->npolys, b->edges, b->nedges,
                     b->nedges};
    j->ok[band] &= zs_polyorder_batch(j->tr, &view, &j->t, r0, r1, &j->d->band_scratch[band],
                                      &counts[i]);
  }
  return 1;
}

/* Whether chunk c may be set up: every band has scanned the chunk that
 * held its batch before. */
static int slot_free(const flush_job *j, int c) {
  for (int b = 0; b < j->nbands; b++)
    if (j->band_next[b] <= c - j->nslots) return 0;
  return 1;
}

/* The task that owns band b: runs of bands in a row, one a task. */
static int band_owner(const flush_job *j, int b) {
  return (int)((int64_t)b * j->d->cfg.threads / j->nbands);
}

/* A band free to scan its next chunk, or -1: among the bands task owns
 * when own is set, else among the others. */
static int ready_band(const flush_job *j, int task, int own) {
  for (int b = 0; b < j->nbands; b++) {
    int c = j->band_next[b];
    if ((band_owner(j, b) == task) == own && !j->band_busy[b] && c <= j->last_chunk &&
        j->set_up[c])
      return b;
  }
  return -1;
}

/* One step of a poll: PAUSE tells the core the loop spins. */
static inline void cpu_relax(void) {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

/* One thread's share of the flush: tasks until every band is through. */
static void flush_worker(void *ctx, int task) {
  flush_job *j = ctx;
  zs_deferred *q = j->q;
  pthread_mutex_lock(&q->lock);
  while (j->bands_left > 0) {
    int band = ready_band(j, task, 1);
    /* a set-up only when none of its own bands is ready */
    int setup = band < 0 && j->next_setup <= j->last_chunk && slot_free(j, j->next_setup);
    if (band < 0 && !setup) band = ready_band(j, task, 0);
    if (band >= 0) {
      int c = j->band_next[band];
      j->band_busy[band] = 1;
      pthread_mutex_unlock(&q->lock);
      int more = scan_chunk(j, band, c);
      pthread_mutex_lock(&q->lock);
      j->band_busy[band] = 0;
      j->band_next[band] = c + 1;
      if (!more || c + 1 > j->last_chunk) {
        j->band_next[band] = MAX_CHUNKS; /* through */
        j->bands_left--;
      }
    } else if (setup) {
      int c = j->next_setup++;
      pthread_mutex_unlock(&q->lock);
      setup_chunk(j, c);
      pthread_mutex_lock(&q->lock);
      j->set_up[c] = 1;
      if (q->st[c] != ZS_OK && c < j->last_chunk) j->last_chunk = c;
    } else {
      /* Nothing to take until the other tasks change the flow: poll a
       * while before sleeping, as the pool does (pool.c), as a wait here
       * is often shorter than waking a sleeping thread on a virtual
       * machine, and each wake is a system call for the waker. */
      const uint32_t seen = atomic_load_explicit(&j->changes, memory_order_relaxed);
      pthread_mutex_unlock(&q->lock);
      for (int i = 0; i < ZS_FLUSH_SPINS &&
                      atomic_load_explicit(&j->changes, memory_order_acquire) == seen;
           i++)
        cpu_relax();
      pthread_mutex_lock(&q->lock);
      if (atomic_load_explicit(&j->changes, memory_order_relaxed) == seen)
        pthread_cond_wait(&q->changed, &q->lock);
      continue;
    }
    atomic_fetch_add_explicit(&j->changes, 1, memory_order_release);
    pthread_cond_broadcast(&q->changed); /* a system call only when a task sleeps */
  }
  pthread_mutex_unlock(&q->lock);
}

/* The first draw not set up ends the queue (its index, or q->n); its
 * chunk holds the error, set in *st and err. */
static int32_t first_failure(const zs_deferred *q, zs_status *st, zs_error *err) {
  for (int32_t i = 0; i < q->n; i++)
    if (!q->q[i].set_up) {
      int c = 0;
      while (q->first[c + 1] <= i) c++;
      *st = zs_error_set(err, q->st[c], "%s", q->err[c].msg);
      return i;
    }
  return q->n;
}

/* Settles draws 0 .. ndraw - 1 in the order issued, each charged as the
 * draw it is (zs_clock_charge): its set-up counters, its scan counters
 * summed over nbands bands (none: the pixels are scanned and charged at
 * finish), and its GPU command as issued when the CPU queued it.  After a
 * failed draw (st), its set-up counters, as zs_device_draw would have
 * added; the draws queued behind it are never charged, as a caller
 * drawing at once would have stopped there. */
static void settle(zs_device *d, const zs_deferred *q, int32_t ndraw, zs_status st, int nbands) {
  for (int32_t i = 0; i < ndraw + (st != ZS_OK); i++) {
    const queued_draw *e = &q->q[i];
    zs_command c = {.kind = ZS_CMD_DRAW, .issued_ps = e->cpu_ps, .vertices = e->mesh->nverts,
                    .faces = e->fc, .reached = i < ndraw ? ZS_COMPLETED : ZS_COUNTED};
    for (int b = 0; b < nbands; b++)
      zs_scan_counts_add(&c.scan, &q->counts[(size_t)b * (size_t)q->n + (size_t)i]);
    zs_clock_charge(d, &c);
  }
}

/* Sets up and scans the queue; returns the status of the first failed
 * draw (its set-up or, for all of them, memory for the scan). */
static zs_status flush_queue(zs_device *d, flush_job *j, zs_error *err) {
  zs_deferred *q = j->q;
  /* sixteen chunks' weight a thread, so that the last one to finish does
   * not keep the others waiting long (with a few large chunks a thread,
   * the others sit idle through the last one), the last of them in
   * quarters */
  int nsmall = ZS_DEFER_SMALL_CHUNKS_PER_THREAD * d->cfg.threads,
      nfull = ZS_DEFER_FULL_CHUNKS_PER_THREAD * d->cfg.threads;
  if (nfull + nsmall > MAX_CHUNKS) {
    nsmall = MAX_CHUNKS / 4;
    nfull = MAX_CHUNKS - nsmall;
  }
  if (nfull + nsmall > q->n) { /* a chunk a draw */
    nfull = q->n;
    nsmall = 0;
  }
  const int nchunks = nfull + nsmall;
  cut_chunks(q, nfull, nsmall);
  if (q->rows1 < q->rows0) { /* no flush yet: the whole window */
    q->rows0 = 0;
    q->rows1 = d->cfg.height - 1;
  }
  j->row0 = q->rows0;
  j->rows = q->rows1 - q->rows0 + 1;
  int nbands = zs_band_count(d->cfg.threads, j->rows);
  j->nslots = ZS_DEFER_SLOTS_PER_THREAD * d->cfg.threads;
  if (j->nslots > MAX_CHUNKS) j->nslots = MAX_CHUNKS;
  j->nbands = nbands < 1 ? 1 : nbands;
  if (!zs_grow((void **)&q->counts, &q->cap_counts, (int64_t)j->nbands * q->n,
               sizeof *q->counts))
    return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
  j->next_setup = 0;
  j->last_chunk = nchunks - 1;
  j->bands_left = j->nbands;
  for (int b = 0; b < j->nbands; b++) j->ok[b] = 1;
  zs_pool_run(d->pool, flush_worker, j, d->cfg.threads);

  zs_status st = ZS_OK;
  const int32_t ndraw = first_failure(q, &st, err);
  for (int b = 0; b < j->nbands; b++)
    if (!j->ok[b]) return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");

  /* the rows covered, for the next flush's bands */
  int lo = d->cfg.height, hi = -1;
  for (int32_t i = 0; i < ndraw; i++)
    if (q->q[i].npolys > 0) {
      if (q->q[i].row0 < lo) lo = q->q[i].row0;
      if (q->q[i].row1 > hi) hi = q->q[i].row1;
    }
  if (hi >= lo) {
    q->rows0 = lo > 0 ? lo : 0;
    q->rows1 = hi < d->cfg.height - 1 ? hi : d->cfg.height - 1;
  }
  settle(d, q, ndraw, st, j->nbands);
  return st;
}

/* zbuffer mode: the queue set up and scanned into the frame. */
static zs_status flush_scanning(zs_device *d, zs_error *err) {
  zs_deferred *q = d->deferred;
  flush_job j;
  memset(&j, 0, sizeof j);
  atomic_init(&j.changes, 0);
  j.d = d;
  j.q = q;
  j.tr = &d->drawing->traversal;
  j.t = zs_raster_frame_target(d);
  return flush_queue(d, &j, err);
}

/* ---- scanline mode: the queue set up into the frame's batch ----
 *
 * The frame is scanned at finish, in bands (finish.c); what its draws
 * leave to the threads before is their set-up: chunks of draws set up in
 * parallel, each into its own batch, then appended to the frame's batch
 * in issue order, so the batch, and with it every pixel and counter, is
 * the one drawing at once builds. */

typedef struct setup_round {
  zs_device *d;
  zs_deferred *q;
  int nchunks;
  flush_job *slots;    /* setup_chunk's view: chunk c in batch c */
  _Atomic int next;    /* the next chunk to take */
} setup_round;

/* Each task takes the next chunk not taken: chunks of equal faces need
 * not take equal time (faces off the window cost little), and a chunk
 * fixed to each task in turn left one waiting on the other (zscan bench
 * raster --case builtin:plant --algo scanline --threads 2 --speedup
 * measures it). */
static void setup_task(void *ctx, int task) {
  (void)task;
  setup_round *r = ctx;
  for (int c; (c = atomic_fetch_add_explicit(&r->next, 1, memory_order_relaxed)) < r->nchunks;)
    setup_chunk(r->slots, c);
}

/* The chunks' batches copied into the frame's, each at its place: a
 * chunk's draws lie together in its batch, in issue order, so the
 * frame's batch is the one drawing at once builds, and the copies, a
 * frame's polygons and edges, go over the threads. */
typedef struct append_job {
  zs_device *d;
  zs_deferred *q;
  int nchunks;
  int32_t polys[MAX_CHUNKS], at_poly[MAX_CHUNKS], at_edge[MAX_CHUNKS];
} append_job;

static void append_task(void *ctx, int task) {
  append_job *a = ctx;
  for (int c = task; c < a->nchunks; c += a->d->cfg.threads)
    zs_batch_place(&a->d->batch, a->at_poly[c], a->at_edge[c], &a->q->batch[c], 0, a->polys[c]);
}

static zs_status flush_setting_up(zs_device *d, zs_error *err) {
  zs_deferred *q = d->deferred;
  /* sixteen chunks a thread, taken as the threads come free: the one
   * to finish last waits on a short chunk (zscan bench raster --case
   * builtin:plant --algo scanline --threads 2 --speedup measures it) */
  int nchunks = ZS_SETUP_CHUNKS_PER_THREAD * d->cfg.threads < MAX_CHUNKS
                    ? ZS_SETUP_CHUNKS_PER_THREAD * d->cfg.threads
                    : MAX_CHUNKS;
  if (nchunks > q->n) nchunks = q->n;
  cut_chunks(q, nchunks, 0);
  flush_job j;
  memset(&j, 0, sizeof j);
  j.d = d;
  j.q = q;
  j.nslots = MAX_CHUNKS; /* chunk c in batch c */
  setup_round r = {d, q, nchunks, &j, 0};
  zs_pool_run(d->pool, setup_task, &r, d->cfg.threads);
  zs_status st = ZS_OK;
  const int32_t ndraw = first_failure(q, &st, err);
  /* the draws taken: those set up, and a failed one's polygons before its
   * bad face; each chunk's from its first polygon to its last taken */
  const int32_t taken = ndraw + (st != ZS_OK);
  append_job a;
  a.d = d;
  a.q = q;
  a.nchunks = nchunks;
  int64_t polys = d->batch.npolys, edges = d->batch.nedges;
  for (int c = 0; c < nchunks; c++) {
    const int32_t last = (q->first[c + 1] < taken ? q->first[c + 1] : taken) - 1;
    a.polys[c] = last >= q->first[c] ? q->q[last].poly0 + q->q[last].npolys : 0;
    a.at_poly[c] = (int32_t)polys;
    a.at_edge[c] = (int32_t)edges;
    polys += a.polys[c];
    edges += zs_batch_edges_of(&q->batch[c], 0, a.polys[c]);
  }
  if (polys > INT32_MAX || edges > INT32_MAX ||
      !zs_batch_reserve(&d->batch, (int32_t)(polys - d->batch.npolys),
                        (int32_t)(edges - d->batch.nedges)))
    return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
  zs_pool_run(d->pool, append_task, &a, d->cfg.threads);
  d->batch.npolys = (int32_t)polys;
  d->batch.nedges = (int32_t)edges;
  settle(d, q, ndraw, st, 0);
  return st;
}

int zs_defer_start(zs_device *d) {
  if (d->deferred) return 1;
  zs_deferred *q = calloc(1, sizeof *q);
  if (!q) return 0;
  if (pthread_mutex_init(&q->lock, NULL) != 0) {
    free(q);
    return 0;
  }
  if (pthread_cond_init(&q->changed, NULL) != 0) {
    pthread_mutex_destroy(&q->lock);
    free(q);
    return 0;
  }
  q->rows1 = -1; /* no rows covered yet */
  /* what a flush does, for the mode: chosen once */
  q->flush = d->cfg.algo == ZS_ALGO_ZBUFFER ? flush_scanning : flush_setting_up;
  d->deferred = q;
  return 1;
}

zs_status zs_device_flush(zs_device *d, zs_error *err) {
  zs_deferred *q = d->deferred;
  if (!q || q->n == 0) return ZS_OK;
  zs_status st = q->flush(d, err);
  q->n = 0;
  q->pending_ps = 0;
  for (int c = 0; c < MAX_CHUNKS; c++) zs_batch_reset(&q->batch[c]);
  return st;
}

void zs_defer_discard(zs_device *d) {
  if (d->deferred) {
    d->deferred->n = 0;
    d->deferred->pending_ps = 0;
  }
}

void zs_defer_free(zs_device *d) {
  zs_deferred *q = d->deferred;
  if (!q) return;
  free(q->q);
  for (int c = 0; c < MAX_CHUNKS; c++) {
    zs_batch_free(&q->batch[c]);
    zs_vert_scratch_free(&q->verts[c]);
  }
  free(q->counts);
  pthread_cond_destroy(&q->changed);
  pthread_mutex_destroy(&q->lock);
  free(q);
  d->deferred = NULL;
}

size_t zs_defer_bytes(const zs_device *d) {
  const zs_deferred *q = d->deferred;
  if (!q) return 0;
  size_t n = (size_t)q->cap * sizeof *q->q + (size_t)q->cap_counts * sizeof *q->counts;
  for (int c = 0; c < MAX_CHUNKS; c++)
    n += (size_t)q->batch[c].cap_polys * sizeof(zs_poly) +
         (size_t)q->batch[c].cap_edges * sizeof(zs_edge) + zs_vert_scratch_bytes(&q->verts[c]);
  return n;
}
