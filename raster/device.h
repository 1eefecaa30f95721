/* zscan raster — the device's context (device.c's private header): what
 * the device's commands share (device.c, now.c, defer.c, finish.c,
 * query.c, clock.c, lines.c) and no stage sees.  The stages take what
 * they need as arguments: a batch, a target, a zs_draw_prep. */
#ifndef ZS_RASTER_DEVICE_H
#define ZS_RASTER_DEVICE_H

#include "raster/clock.h"
#include "raster/hzb.h"
#include "raster/prim_rows.h"
#include "raster/surface.h"
#include "raster/tuning.h"

typedef struct zs_deferred zs_deferred; /* defer.c */

/* What a draw of one kernel runs, fixed at create: its draw stage's
 * fixed part and its traversals. */
typedef struct zs_kernel_state {
  zs_draw_prep prep;
  zs_traversal traversal;
} zs_kernel_state;

struct zs_device {
  zs_device_config cfg;
  zs_simd simd;                   /* the span fill, from cfg.spans and the CPU */
  double view[16], proj[16];
  double shade_proj[16];   /* zs_device_set_shading_projection's, when has_shade_proj */
  int has_shade_proj;
  double eye[3];                  /* world position of the eye */
  double znear, zfar;
  int perspective;
  double gx, gy;                  /* guard band half-widths, NDC units */
  zs_raster_stats stats;

  uint32_t *depth, *id, *rgb, *count;  /* full frame (zbuffer mode) */
  uint8_t *fresh;                      /* per row: not cleared yet (zs_target) */
  uint32_t *blank;                     /* a cleared row: depth, id, colour, count */
  uint32_t *row_depth, *row_id, *row_rgb, *row_count; /* scanline mode */
  uint32_t *row_out;                   /* one shaded row */
  float *row_normal;                   /* its normals (zs_device_set_normals), else NULL */
  uint32_t *band_rows;                 /* scanline mode on threads: each thread's
                                        * band of rows, four buffers (finish.c) */
  int band_max_rows;

  zs_batch batch;
  zs_scan_scratch scratch;
  zs_vert_scratch verts;          /* per mesh vertex, this draw */

  /* queries and the clock */
  zs_clock_params clock_params;
  zs_clock_costs costs;
  zs_clock_stats clock;
  zs_query_rec *queries;
  uint32_t nqueries;
  int32_t cap_queries;
  int query_open;                 /* a query is between begin and end */
  const zs_trace_observer *trace; /* scanline mode's observer, or NULL */
  zs_depthsort *depthsort;
  zs_hzb *hzb;                    /* made at the first build */
  /* threads: zbuffer mode scans large batches in bands of rows */
  struct zs_pool *pool;
  int prefetch_write;             /* threads, and the CPU has PREFETCHW (setup.c) */
  zs_scan_scratch *band_scratch;  /* one per band */
  zs_batch *setup_parts;          /* a large draw's faces set up by thread
                                   * t > 0 (thread 0 uses batch) */
  int last_was_query;             /* the GPU's last command was a query box */
  /* Chosen once, at create, from the mode, the shading and the threads
   * (device.c, choose_stages; draw again when deferral is switched), so
   * that no command asks which mode it is in. */
  zs_kernel_state state_of[ZS_KERNELS];
  const zs_kernel_state *drawing; /* a draw's: DRAW, or OVERDRAW in overdraw shading */
  zs_depthsort *painter;          /* depthsort in depthsort mode, else NULL */
  int clear_counts;               /* the draw kernel counts fragments */
  zs_status (*draw)(zs_device *d, const zs_mesh *mesh, const double model[16],
                    uint32_t id_base, uint32_t rgb, zs_error *err);
  zs_status (*set_up)(zs_device *d, const zs_mesh *mesh, const zs_draw_prep *prep,
                      uint32_t id_base, uint32_t rgb, zs_face_counts *fc, zs_error *err);
  int (*rasterize)(zs_device *d, const zs_traversal *tr, zs_scan_counts *out);
  void (*clear_buffers)(zs_device *d);
  zs_status (*finish)(zs_device *d, zs_row_sink sink, void *user, zs_error *err);
  zs_row_shader shade_row;        /* and with the projection (set_camera) */
  void (*emit)(zs_device *d, int y, const uint32_t *depth, const uint32_t *id,
               const uint32_t *rgb, const uint32_t *count, zs_row_sink sink, void *user);
  zs_deferred *deferred;          /* zs_device_defer_draws: the queued draws */
  /* the shadings that read attributes (surface.h): the frame's records */
  int reads_attrs;
  zs_surfaces surf;
  /* transparent faces: their fragments (abuffer.h), and the batch they
   * are set up into, apart from the opaque faces' */
  zs_abuffer abuf;
  zs_batch frag_batch;
  /* scanline mode: the lines' and points' fragments, put into their rows
   * at finish (prim_rows.h) */
  zs_prim_rows prim_rows;
  /* zs_device_keep_line_runs: the hidden lines as vectors (lines.c) */
  int keep_runs;
  int nomem_runs;                 /* a run could not be kept */
  zs_line_run *runs;
  int32_t nruns, cap_runs;
};

/* device.c: the full-frame buffers of zbuffer mode as a traversal's
 * target; the rows of the full frame not cleared yet cleared, for a
 * reader of the whole frame (the buffers' getters, the pyramid, the
 * hidden lines). */
zs_target zs_raster_frame_target(const zs_device *d);
void zs_raster_clear_fresh(const zs_device *d);

/* now.c: drawing at once.  A draw through the draw stage into the batch
 * (set_up: whole on one thread, or split over the pool when large), then
 * the batch rasterized (into the full frame, on one thread or in bands,
 * or kept for finish in scanline and depthsort modes).  Shared by
 * zs_device_draw and the query boxes; fills c for zs_clock_charge. */
zs_status zs_set_up_whole(zs_device *d, const zs_mesh *mesh, const zs_draw_prep *prep,
                          uint32_t id_base, uint32_t rgb, zs_face_counts *fc, zs_error *err);
zs_status zs_set_up_split(zs_device *d, const zs_mesh *mesh, const zs_draw_prep *prep,
                          uint32_t id_base, uint32_t rgb, zs_face_counts *fc, zs_error *err);
int zs_rasterize_frame(zs_device *d, const zs_traversal *tr, zs_scan_counts *out);
int zs_rasterize_banded(zs_device *d, const zs_traversal *tr, zs_scan_counts *out);
int zs_rasterize_later(zs_device *d, const zs_traversal *tr, zs_scan_counts *out);
zs_status zs_draw_at_once(zs_device *d, const zs_mesh *mesh, const double model[16],
                          uint32_t id_base, uint32_t rgb, const zs_kernel_state *ks,
                          zs_command *c, zs_error *err);
/* The bands a traversal of `rows` rows takes on `threads` threads (0 or
 * 1: one traversal). */
static inline int zs_band_count(int threads, int rows) {
  int n = ZS_BANDS_PER_THREAD * threads < ZS_MAX_BANDS ? ZS_BANDS_PER_THREAD * threads
                                                       : ZS_MAX_BANDS;
  return n < rows / ZS_BAND_MIN_ROWS ? n : rows / ZS_BAND_MIN_ROWS;
}

/* finish.c: sets d->finish and d->emit for the mode, the shading, the
 * threads and the trace; zs_finish_bands_alloc gives scanline and
 * depthsort modes on threads their bands of rows (0: out of memory). */
void zs_finish_choose(zs_device *d);
int zs_finish_bands_alloc(zs_device *d);
size_t zs_finish_bands_bytes(const zs_device *d);

/* defer.c: draws queued while zs_device_defer_draws is on (raster.h), and
 * rendered together at the next flush: set up in parallel, traversed in
 * bands of rows, each band taking the draws in order; each draw charged
 * in issue order, so everything is what immediate drawing gives.
 * zs_defer_start makes the queue (0: no memory for it). */
int zs_defer_start(zs_device *d);
zs_status zs_defer_push(zs_device *d, const zs_mesh *mesh, const double model[16],
                        uint32_t id_base, uint32_t rgb, zs_error *err);
void zs_defer_discard(zs_device *d);
void zs_defer_free(zs_device *d);
size_t zs_defer_bytes(const zs_device *d);

#endif
