/* Finishing a frame: its rows handed out, shaded, in order.
 *
 * zbuffer mode hands out the rows of the full frame it has drawn.
 * scanline mode scans the frame's batch now, with buffers one row long,
 * handing each row out as soon as it is complete; depthsort mode orders
 * the batch's faces first (depthsort.c).  Which finish and which row
 * shading a device uses is chosen once, at create (zs_finish_choose). */
#include <stdlib.h>
#include <string.h>

#include "raster/device.h"
#include "raster/pool.h"

/* ---- a row handed out ---- */

typedef void (*emit_fn)(zs_device *d, int y, const uint32_t *depth, const uint32_t *id,
                        const uint32_t *rgb, const uint32_t *count, zs_row_sink sink,
                        void *user);

static void emit_as_drawn(zs_device *d, int y, const uint32_t *depth, const uint32_t *id,
                          const uint32_t *rgb, const uint32_t *count, zs_row_sink sink,
                          void *user) {
  (void)count;
  zs_row row = {y, d->cfg.width, rgb, depth, id, NULL, NULL};
  sink(user, &row);
}

/* depth, id and overdraw shading: the colours from the row's buffers;
 * the counts go out with the row (out_count) in overdraw shading only */
static void emit_colours_of(zs_device *d, int y, const uint32_t *depth, const uint32_t *id,
                            const uint32_t *count, const uint32_t *out_count, zs_row_sink sink,
                            void *user) {
  d->shade_row(d->cfg.width, depth, id, count, d->znear, d->zfar, d->row_out);
  zs_row row = {y, d->cfg.width, d->row_out, depth, id, out_count, NULL};
  sink(user, &row);
}

static void emit_shaded(zs_device *d, int y, const uint32_t *depth, const uint32_t *id,
                        const uint32_t *rgb, const uint32_t *count, zs_row_sink sink,
                        void *user) {
  (void)rgb;
  emit_colours_of(d, y, depth, id, count, NULL, sink, user);
}

/* The shadings that read attributes: the words naming records shaded
 * (surface.h), and their normals once zs_device_set_normals asks; a
 * frame without any records goes out as drawn. */
static void emit_surfaces(zs_device *d, int y, const uint32_t *depth, const uint32_t *id,
                          const uint32_t *rgb, const uint32_t *count, zs_row_sink sink,
                          void *user) {
  (void)count;
  if (d->row_normal) zs_surface_normal_row(&d->surf, 0, y, rgb, d->row_normal);
  const uint32_t *out = rgb;
  if (d->surf.nrecs > 0) {
    zs_surface_shade_row(&d->surf, 0, y, rgb, d->row_out);
    zs_abuffer_resolve_row(&d->abuf, &d->surf, 0, y, depth, id, d->row_out);
    out = d->row_out;
  }
  zs_row row = {y, d->cfg.width, out, depth, id, NULL, d->row_normal};
  sink(user, &row);
}

static void emit_overdraw(zs_device *d, int y, const uint32_t *depth, const uint32_t *id,
                          const uint32_t *rgb, const uint32_t *count, zs_row_sink sink,
                          void *user) {
  (void)rgb;
  emit_colours_of(d, y, depth, id, count, count, sink, user);
}

/* ---- scanline and depthsort: the scan, row by row ---- */

typedef struct row_emit {
  zs_device *d;
  zs_row_sink sink;
  void *user;
  uint64_t prims_written; /* pixels the lines and points wrote */
} row_emit;

/* The one-row buffers are cleared before each row and shaded and handed
 * out after it. */
static void begin_row(void *user, int y) {
  (void)y;
  zs_device *d = ((row_emit *)user)->d;
  zs_clear_pixels(d->row_depth, d->row_id, d->row_rgb, d->row_count, (size_t)d->cfg.width,
                  d->cfg.background);
}

/* The row's lines and points go in after its faces, before it is shaded
 * (prim_rows.h). */
static void end_row(void *user, int y) {
  row_emit *e = user;
  zs_device *d = e->d;
  e->prims_written +=
      zs_prim_rows_apply(&d->prim_rows, y, d->row_depth, d->row_id, d->row_rgb,
                         d->clear_counts ? d->row_count : NULL); /* counted for overdraw only */
  if (e->sink) d->emit(d, y, d->row_depth, d->row_id, d->row_rgb, d->row_count, e->sink, e->user);
}

static zs_status finish_scan(zs_device *d, zs_row_sink sink, void *user, zs_error *err) {
  row_emit e = {d, sink, user, 0};
  if (d->prim_rows.n > 0 && !zs_prim_rows_sort(&d->prim_rows, d->cfg.height))
    return zs_error_set(err, ZS_ERR_NOMEM, "finish: out of memory");
  zs_row_hooks hooks = {begin_row, end_row, &e};
  zs_target t = {d->row_depth, d->row_id, d->row_rgb, d->row_count, 0, d->cfg.width, 0, NULL, 0,
                 NULL};
  zs_command c = {.kind = ZS_CMD_FRAME_SCAN, .issued_ps = -1};
  if (!zs_scan_batch(&d->drawing->traversal, &d->batch, &t, 0, d->cfg.height, &hooks, d->trace,
                     &d->scratch, &c.scan))
    return zs_error_set(err, ZS_ERR_NOMEM, "finish: out of memory");
  c.scan.written += e.prims_written;
  zs_clock_charge(d, &c);
  zs_batch_reset(&d->batch);
  return ZS_OK;
}

/* ---- scanline and depthsort on threads: bands of rows ----
 *
 * The rows of a frame are independent in the row scan, so the
 * frame's batch is scanned in bands, one a thread, each into its thread's
 * buffers of a band's rows; then the rows are handed out in order.  The
 * counts are summed in band order: the same bytes and counters as one
 * scan.  One band a thread, not more in rounds: each band sorts the whole
 * batch into its rows' buckets, so more bands scan it more often (zscan
 * bench raster --case builtin:plant --algo scanline --threads 2 --speedup
 * measures it; docs/RESULTS.md).  So on threads the device holds the
 * frame's rows, in bands, not one row. */
static int finish_band_count(const zs_device *d) {
  const int n = d->cfg.height / ZS_BAND_MIN_ROWS;
  return d->cfg.threads < n ? d->cfg.threads : n;
}

size_t zs_finish_bands_bytes(const zs_device *d) {
  return 4 * (size_t)d->cfg.threads * (size_t)d->band_max_rows * (size_t)d->cfg.width *
         sizeof *d->band_rows;
}

int zs_finish_bands_alloc(zs_device *d) {
  const int h = d->cfg.height, nbands = finish_band_count(d);
  d->band_max_rows = nbands > 1 ? (h + nbands - 1) / nbands : h;
  d->band_rows = malloc(zs_finish_bands_bytes(d));
  return d->band_rows != NULL;
}

typedef struct band_round {
  zs_device *d;
  int nbands, first;          /* this round: bands first .. first + threads - 1 */
  zs_scan_counts counts[ZS_MAX_BANDS];
  int ok[ZS_MAX_BANDS];
} band_round;

static int finish_band_first_row(const band_round *j, int b) {
  return (int)zs_part_start(j->d->cfg.height, b, j->nbands);
}

/* Thread t's buffers: depth, id, colour, count, a band's rows each. */
static zs_target band_target(const zs_device *d, int t, int row0) {
  const size_t n = (size_t)d->band_max_rows * (size_t)d->cfg.width;
  uint32_t *base = d->band_rows + 4 * n * (size_t)t;
  return (zs_target){base, base + n, base + 2 * n, base + 3 * n, d->cfg.width, d->cfg.width,
                     row0, NULL, 0, NULL};
}

/* A band's row is cleared just before the scan reaches it, not the band
 * at once before the scan: the row's lines are then in the caches when
 * its spans land, where clearing a band's megabytes first evicts them
 * before the scan comes back (zscan bench raster --case builtin:plant
 * --algo scanline --threads 2 --speedup measures it).  The counts only
 * where the overdraw kernel fills them. */
typedef struct band_clear {
  const zs_target *t;
  uint32_t background;
  int counts;
} band_clear;

static void clear_band_row(void *user, int y) {
  const band_clear *c = user;
  const zs_target *t = c->t;
  const size_t off = (size_t)(y - t->row0) * (size_t)t->row_stride;
  zs_clear_pixels(t->depth + off, t->id + off, t->rgb + off, c->counts ? t->count + off : NULL,
                  (size_t)t->width, c->background);
}

static void scan_band_rows(void *ctx, int t) {
  band_round *j = ctx;
  zs_device *d = j->d;
  const int b = j->first + t;
  if (b >= j->nbands) return;
  const int y0 = finish_band_first_row(j, b), y1 = finish_band_first_row(j, b + 1);
  zs_target tg = band_target(d, t, y0);
  band_clear clear = {&tg, d->cfg.background, d->clear_counts};
  const zs_row_hooks hooks = {clear_band_row, NULL, &clear};
  j->counts[b] = (zs_scan_counts){0, 0, 0};
  j->ok[b] = zs_scan_batch(&d->drawing->traversal, &d->batch, &tg, y0, y1, &hooks, NULL,
                           &d->band_scratch[b], &j->counts[b]);
  /* the rows' lines and points, after their faces (prim_rows.h) */
  for (int y = y0; j->ok[b] && d->prim_rows.n > 0 && y < y1; y++) {
    const size_t off = (size_t)(y - y0) * (size_t)d->cfg.width;
    j->counts[b].written += zs_prim_rows_apply(&d->prim_rows, y, tg.depth + off, tg.id + off,
                                               tg.rgb + off, d->clear_counts ? tg.count + off : NULL);
  }
  /* the band's pixels shaded here, on its thread, in place (not when
   * their normals go out too: the rows keep their records for that) */
  if (j->ok[b] && d->surf.nrecs > 0 && !d->row_normal)
    for (int y = y0; y < y1; y++) {
      const size_t off = (size_t)(y - y0) * (size_t)d->cfg.width;
      zs_surface_shade_row(&d->surf, t, y, tg.rgb + off, tg.rgb + off);
      zs_abuffer_resolve_row(&d->abuf, &d->surf, t, y, tg.depth + off, tg.id + off,
                             tg.rgb + off);
    }
}

static zs_status finish_bands(zs_device *d, zs_row_sink sink, void *user, zs_error *err) {
  band_round j;
  j.d = d;
  j.nbands = finish_band_count(d);
  if (j.nbands < 2) return finish_scan(d, sink, user, err);
  if (d->prim_rows.n > 0 && !zs_prim_rows_sort(&d->prim_rows, d->cfg.height))
    return zs_error_set(err, ZS_ERR_NOMEM, "finish: out of memory");
  const int threads = d->cfg.threads, w = d->cfg.width;
  /* the bands' rows come shaded (scan_band_rows) */
  const emit_fn emit = d->surf.nrecs > 0 && !d->row_normal ? emit_as_drawn : d->emit;
  zs_command c = {.kind = ZS_CMD_FRAME_SCAN, .issued_ps = -1};
  for (j.first = 0; j.first < j.nbands; j.first += threads) {
    zs_pool_run(d->pool, scan_band_rows, &j, threads);
    for (int t = 0; t < threads && j.first + t < j.nbands; t++) {
      const int b = j.first + t;
      const int y0 = finish_band_first_row(&j, b), y1 = finish_band_first_row(&j, b + 1);
      if (!j.ok[b]) return zs_error_set(err, ZS_ERR_NOMEM, "finish: out of memory");
      zs_scan_counts_add(&c.scan, &j.counts[b]);
      if (!sink) continue;
      const zs_target tg = band_target(d, t, y0);
      for (int y = y0; y < y1; y++) {
        const size_t off = (size_t)(y - y0) * (size_t)w;
        emit(d, y, tg.depth + off, tg.id + off, tg.rgb + off, tg.count + off, sink, user);
      }
    }
  }
  zs_clock_charge(d, &c);
  zs_batch_reset(&d->batch);
  return ZS_OK;
}

static zs_status finish_painter(zs_device *d, zs_row_sink sink, void *user, zs_error *err) {
  if (!zs_depthsort_order(d->depthsort, &d->batch, d->view))
    return zs_error_set(err, ZS_ERR_NOMEM, "finish: out of memory");
  return finish_scan(d, sink, user, err);
}

static zs_status finish_painter_bands(zs_device *d, zs_row_sink sink, void *user,
                                      zs_error *err) {
  if (!zs_depthsort_order(d->depthsort, &d->batch, d->view))
    return zs_error_set(err, ZS_ERR_NOMEM, "finish: out of memory");
  return finish_bands(d, sink, user, err);
}

/* ---- zbuffer: the drawn frame's rows ---- */

/* On threads, the frame's pixels that name records shaded in place, a
 * band of rows a thread (each with its own cache); the rows then go out
 * as drawn. */
typedef struct shade_job {
  zs_device *d;
  int nparts;
} shade_job;

static void shade_part(void *ctx, int part) {
  const shade_job *j = ctx;
  zs_device *d = j->d;
  const int y0 = (int)zs_part_start(d->cfg.height, part, j->nparts),
            y1 = (int)zs_part_start(d->cfg.height, part + 1, j->nparts);
  for (int y = y0; y < y1; y++)
    if (!d->fresh[y]) {
      const size_t off = (size_t)y * (size_t)d->cfg.width;
      zs_surface_shade_row(&d->surf, part, y, d->rgb + off, d->rgb + off);
      zs_abuffer_resolve_row(&d->abuf, &d->surf, part, y, d->depth + off, d->id + off,
                             d->rgb + off);
    }
}

static zs_status finish_frame(zs_device *d, zs_row_sink sink, void *user, zs_error *err) {
  (void)err;
  if (!sink) return ZS_OK;
  emit_fn emit = d->emit;
  if (d->pool && d->surf.nrecs > 0 && !d->row_normal) {
    shade_job j = {d, d->cfg.threads};
    zs_pool_run(d->pool, shade_part, &j, j.nparts);
    emit = emit_as_drawn;
  }
  const size_t w = (size_t)d->cfg.width;
  const uint32_t *blank = d->blank; /* rows no draw reached: cleared, not stored */
  for (int y = 0; y < d->cfg.height; y++) {
    size_t off = (size_t)y * w;
    if (d->fresh[y])
      emit(d, y, blank, blank + w, blank + 2 * w, d->count ? blank + 3 * w : NULL, sink, user);
    else
      emit(d, y, d->depth + off, d->id + off, d->rgb + off, d->count ? d->count + off : NULL,
           sink, user);
  }
  return ZS_OK;
}

void zs_finish_choose(zs_device *d) {
  /* the trace follows one scan; threads scan bands of rows */
  const int bands = d->band_rows && !d->trace;
  d->finish = d->cfg.algo == ZS_ALGO_ZBUFFER     ? finish_frame
              : d->cfg.algo == ZS_ALGO_DEPTHSORT ? (bands ? finish_painter_bands : finish_painter)
              : bands                            ? finish_bands
                                                 : finish_scan;
  d->emit = zs_shade_reads_attrs(d->cfg.shade)  ? emit_surfaces
            : zs_shade_is_surface(d->cfg.shade) ? emit_as_drawn
            : d->cfg.shade == ZS_SHADE_OVERDRAW ? emit_overdraw
                                                : emit_shaded;
}

zs_status zs_device_finish(zs_device *d, zs_row_sink sink, void *user, zs_error *err) {
  zs_status st = zs_device_flush(d, err);
  if (st != ZS_OK) return st;
  return d->finish(d, sink, user, err);
}
