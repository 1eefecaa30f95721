/* The device: its context, and the commands clear, draw and finish.
 *
 * zbuffer mode (immediate): each draw is transformed, clipped, set up into
 * a batch and scanned at once into full-frame depth, id and colour buffers.
 * scanline mode: draws are set up into one batch for the whole frame, and
 * zs_device_finish scans it with buffers one row long, handing each row
 * out as soon as it is complete; the device then holds O(width) pixels.
 * Both scan with the same code and the same total order on (depth, id), so
 * their images are the same to the byte.
 * depthsort mode collects the frame like scanline mode, then orders its
 * faces (depthsort.c) and scans it with painter's depths.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "raster/device.h"
#include "util/lights.h"

#include "raster/cpu.h"
#include "raster/pool.h"

static const char *const algo_names[] = {"zbuffer", "scanline", "depthsort"};

static const char *const shade_names[] = {"auto",     "flat",  "id",      "depth", "overdraw",
                                         "unlit",    "gouraud", "phong", "normal"};

const char *zs_shade_name(zs_shade sh) {
  return (unsigned)sh < sizeof shade_names / sizeof *shade_names ? shade_names[sh] : "?";
}

int zs_shade_parse(const char *name) {
  for (int i = 0; i < (int)(sizeof shade_names / sizeof *shade_names); i++)
    if (name && strcmp(name, shade_names[i]) == 0) return i;
  return -1;
}

const char *zs_algo_name(zs_algo a) {
  return (unsigned)a < sizeof algo_names / sizeof algo_names[0] ? algo_names[a] : "?";
}

int zs_algo_parse(const char *name) {
  for (int i = 0; i < (int)(sizeof algo_names / sizeof algo_names[0]); i++)
    if (strcmp(name, algo_names[i]) == 0) return i;
  return -1;
}

static void choose_stages(zs_device *d);

static uint32_t *alloc_u32(size_t n) { return malloc(n * sizeof(uint32_t)); }

zs_status zs_device_create(const zs_device_config *given, zs_device **out,
                           zs_error *err) {
  *out = NULL;
  /* 0 means the default for every field (zscan/zscan.h) */
  static const zs_device_config none;
  zs_device_config filled = given ? *given : none;
  if (filled.width == 0) filled.width = ZS_DEVICE_DEFAULT_WIDTH;
  if (filled.height == 0) filled.height = ZS_DEVICE_DEFAULT_HEIGHT;
  if (filled.threads == 0) filled.threads = 1;
  const zs_device_config *cfg = &filled;
  if (cfg->width < 1 || cfg->height < 1 || cfg->width > ZS_MAX_IMAGE_SIDE ||
      cfg->height > ZS_MAX_IMAGE_SIDE)
    return zs_error_set(err, ZS_ERR_LIMIT,
                        "image size %dx%d: each side must be 1 to %d",
                        cfg->width, cfg->height, ZS_MAX_IMAGE_SIDE);
  if (cfg->threads < 1 || cfg->threads > ZS_MAX_THREADS)
    return zs_error_set(err, ZS_ERR_ARG, "threads must be 1 to %d", ZS_MAX_THREADS);
  zs_device *d = calloc(1, sizeof *d);
  if (!d) return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  d->cfg = *cfg;
  /* the SIMD level (span fill, vertex stage), chosen once: BEST and
   * AVX512 take the widest the CPU has */
  d->simd = zs_span_simd_level(cfg->spans == ZS_SPANS_SCALAR ? ZS_SIMD_SCALAR
                               : cfg->spans == ZS_SPANS_SSE2 ? ZS_SIMD_SSE2
                               : cfg->spans == ZS_SPANS_AVX2 ? ZS_SIMD_AVX2
                                                             : ZS_SIMD_AVX512);
  size_t w = (size_t)cfg->width, px = w * (size_t)cfg->height;
  int ok = 1;
  if (cfg->algo == ZS_ALGO_ZBUFFER) { /* else scanline or depthsort: one row */
    d->depth = alloc_u32(px);
    d->id = alloc_u32(px);
    d->rgb = alloc_u32(px);
    d->fresh = malloc((size_t)cfg->height);
    d->blank = alloc_u32(4 * w);
    ok = d->depth && d->id && d->rgb && d->fresh && d->blank;
    if (ok) {
      zs_clear_pixels(d->blank, d->blank + w, d->blank + 2 * w, d->blank + 3 * w, w,
                      cfg->background);
    }
    if (ok && cfg->shade == ZS_SHADE_OVERDRAW) ok = (d->count = alloc_u32(px)) != NULL;
  } else {
    d->row_depth = alloc_u32(w);
    d->row_id = alloc_u32(w);
    d->row_rgb = alloc_u32(w);
    d->row_count = alloc_u32(w);
    ok = d->row_depth && d->row_id && d->row_rgb && d->row_count;
  }
  if (ok) ok = (d->row_out = alloc_u32(w)) != NULL;
  if (ok) ok = (d->depthsort = zs_depthsort_create()) != NULL;
  if (!ok) {
    zs_device_destroy(d);
    return zs_error_set(err, ZS_ERR_NOMEM,
                        "image size %dx%d: not enough memory for the buffers",
                        cfg->width, cfg->height);
  }
  if (ok && cfg->threads > 1) {
    d->pool = zs_pool_create(cfg->threads);
    d->band_scratch = calloc(ZS_MAX_BANDS, sizeof *d->band_scratch); /* one per band */
    d->setup_parts = calloc((size_t)cfg->threads, sizeof *d->setup_parts);
    ok = d->pool && d->band_scratch && d->setup_parts;
    if (ok && cfg->algo != ZS_ALGO_ZBUFFER) ok = zs_finish_bands_alloc(d);
    d->prefetch_write = zs_cpu_has_prefetchw();
    if (!ok) {
      zs_device_destroy(d);
      return zs_error_set(err, ZS_ERR_NOMEM, "threads: cannot start %d threads", cfg->threads);
    }
  }
  zs_surfaces_init(&d->surf, cfg->width, cfg->height, (zs_filter)cfg->filter);
  zs_abuffer_init(&d->abuf, cfg->width, cfg->height, cfg->threads);
  d->reads_attrs = zs_shade_reads_attrs(cfg->shade);
  d->gx = 1.0 + (double)(1 << 15) / cfg->width;
  d->gy = 1.0 + (double)(1 << 15) / cfg->height;
  zs_mat_identity(d->view);
  zs_mat_identity(d->proj);
  d->znear = 1.0;
  d->zfar = 100.0;
  zs_clock_params defaults;
  zs_clock_params_default(&defaults);
  zs_device_set_clock(d, &defaults, NULL);
  choose_stages(d);
  zs_device_clear(d);
  *out = d;
  return ZS_OK;
}

zs_status zs_device_set_normals(zs_device *d, int on, zs_error *err) {
  if (on && !zs_shade_reads_attrs(d->cfg.shade))
    return zs_error_set(err, ZS_ERR_ARG,
                        "normals need a shading that reads attributes (auto, unlit, gouraud, "
                        "phong or normal), not %s", zs_shade_name(d->cfg.shade));
  if (on && !d->row_normal &&
      !(d->row_normal = malloc(3 * (size_t)d->cfg.width * sizeof *d->row_normal)))
    return zs_error_set(err, ZS_ERR_NOMEM, "normals: out of memory");
  if (!on) {
    free(d->row_normal);
    d->row_normal = NULL;
  }
  zs_surfaces_set_normals_out(&d->surf, on);
  return ZS_OK;
}

void zs_device_destroy(zs_device *d) {
  if (!d) return;
  zs_surfaces_free(&d->surf);
  zs_abuffer_free(&d->abuf);
  zs_prim_rows_free(&d->prim_rows);
  zs_batch_free(&d->frag_batch);
  free(d->depth);
  free(d->id);
  free(d->rgb);
  free(d->count);
  free(d->fresh);
  free(d->blank);
  free(d->row_depth);
  free(d->row_id);
  free(d->row_rgb);
  free(d->row_count);
  free(d->row_out);
  free(d->row_normal);
  free(d->band_rows);
  free(d->runs);
  zs_batch_free(&d->batch);
  zs_scan_scratch_free(&d->scratch);
  zs_depthsort_destroy(d->depthsort);
  zs_hzb_destroy(d->hzb);
  zs_pool_destroy(d->pool);
  if (d->band_scratch)
    for (int i = 0; i < ZS_MAX_BANDS; i++) zs_scan_scratch_free(&d->band_scratch[i]);
  free(d->band_scratch);
  if (d->setup_parts)
    for (int i = 0; i < d->cfg.threads; i++) zs_batch_free(&d->setup_parts[i]);
  free(d->setup_parts);
  zs_vert_scratch_free(&d->verts);
  zs_defer_free(d);
  free(d->queries);
  free(d);
}

const zs_device_config *zs_device_config_of(const zs_device *d) { return &d->cfg; }
const zs_raster_stats *zs_device_stats(const zs_device *d) { return &d->stats; }
void zs_device_set_trace(zs_device *d, const zs_trace_observer *obs) {
  d->trace = obs;
  zs_finish_choose(d); /* the trace follows one scan, row by row */
}
const zs_depthsort_stats *zs_device_depthsort_stats(const zs_device *d) {
  return zs_depthsort_stats_of(d->depthsort);
}
double zs_device_depthsort_ms(const zs_device *d) { return zs_depthsort_ms(d->depthsort); }
void zs_device_depthsort_reset(zs_device *d) { zs_depthsort_forget(d->depthsort); }

void zs_device_set_camera(zs_device *d, const double view[16],
                          const double proj[16]) {
  memcpy(d->view, view, sizeof d->view);
  memcpy(d->proj, proj, sizeof d->proj);
  zs_mat_eye_of_view(view, d->eye);
  /* A perspective matrix has -1 in its last row; recover near and far
   * from its third row for the depth shading. */
  double a = proj[10], b = proj[11];
  d->perspective = proj[14] != 0.0;
  if (d->perspective) {
    d->znear = b / (a - 1.0);
    d->zfar = b / (a + 1.0);
  } else {
    d->znear = (b + 1.0) / a;
    d->zfar = (b - 1.0) / a;
  }
  d->shade_row = zs_row_shader_for(d->cfg.shade, d->perspective);
  zs_depthsort_set_projection(d->depthsort, proj, d->perspective);
  d->surf.sets_stale = 1;
}

zs_status zs_device_set_lights(zs_device *d, const zs_light *lights, int n, zs_error *err) {
  if (n > 0 && !lights) return zs_error_set(err, ZS_ERR_ARG, "lights: NULL with n = %d", n);
  zs_status st = zs_lights_check(lights, n, err);
  if (st != ZS_OK) return st;
  if (n > 0) {
    memcpy(d->surf.lights, lights, (size_t)n * sizeof *lights);
    d->surf.nlights = n;
  } else {
    d->surf.nlights = zs_lights_default(d->surf.lights);
  }
  d->surf.lights_given = n > 0;
  d->surf.sets_stale = 1;
  zs_surfaces_set_shadow_maps(&d->surf, NULL, 0); /* they were the old lights' */
  return ZS_OK;
}

void zs_device_set_shading_projection(zs_device *d, const double proj[16]) {
  d->has_shade_proj = proj != NULL;
  if (proj) memcpy(d->shade_proj, proj, sizeof d->shade_proj);
}

static int finite16(const double m[16]) {
  for (int k = 0; k < 16; k++)
    if (!isfinite(m[k])) return 0;
  return 1;
}

zs_status zs_device_set_shadow_maps(zs_device *d, const zs_shadow_map *maps, int n,
                                    zs_error *err) {
  if (n < 0 || n > ZS_MAX_SHADOW_MAPS)
    return zs_error_set(err, ZS_ERR_ARG, "shadow maps: %d maps: 0 to %d may be set", n,
                        ZS_MAX_SHADOW_MAPS);
  if (n > 0 && !maps) return zs_error_set(err, ZS_ERR_ARG, "shadow maps: NULL with n = %d", n);
  if (d->surf.ndraws > 0)
    return zs_error_set(err, ZS_ERR_ARG, "shadow maps: set before a frame's first draw (after "
                        "zs_device_clear), not between its draws");
  if (n > 0 && d->cfg.shade != ZS_SHADE_AUTO && d->cfg.shade != ZS_SHADE_PHONG)
    return zs_error_set(err, ZS_ERR_ARG, "shadow maps need the Phong shading (auto or phong), "
                        "not %s", zs_shade_name(d->cfg.shade));
  for (int j = 0; j < n; j++) {
    const zs_shadow_map *m = &maps[j];
    const int l = m->light;
    if (l < 0 || l >= d->surf.nlights || !d->surf.lights_given ||
        (d->surf.lights[l].kind != ZS_LIGHT_DIRECTIONAL && d->surf.lights[l].kind != ZS_LIGHT_SPOT))
      return zs_error_set(err, ZS_ERR_ARG, "maps[%d].light: %d is not a directional or spot "
                          "light of those set", j, l);
    for (int i = 0; i < j; i++)
      if (maps[i].light == l)
        return zs_error_set(err, ZS_ERR_ARG, "maps[%d].light: light %d has maps[%d] already",
                            j, l, i);
    if (m->width < 1 || m->height < 1 || m->width > ZS_MAX_IMAGE_SIDE ||
        m->height > ZS_MAX_IMAGE_SIDE)
      return zs_error_set(err, ZS_ERR_ARG, "maps[%d]: %d x %d texels: 1 to %d a side", j,
                          m->width, m->height, ZS_MAX_IMAGE_SIDE);
    if (!m->depth) return zs_error_set(err, ZS_ERR_ARG, "maps[%d].depth: NULL", j);
    if (!finite16(m->view) || !finite16(m->proj))
      return zs_error_set(err, ZS_ERR_ARG, "maps[%d].%s: not finite", j,
                          finite16(m->view) ? "proj" : "view");
    if (!(m->bias_units >= 0.0 && m->bias_units <= 4294967296.0))
      return zs_error_set(err, ZS_ERR_ARG, "maps[%d].bias_units: %g: 0 to 2^32", j,
                          m->bias_units);
    if (!(m->bias_slope >= 0.0 && m->bias_slope <= 1e6))
      return zs_error_set(err, ZS_ERR_ARG, "maps[%d].bias_slope: %g: 0 to 1e6", j,
                          m->bias_slope);
  }
  zs_surfaces_set_shadow_maps(&d->surf, maps, n);
  return ZS_OK;
}

/* ---- clear ---- */

/* zbuffer mode clears lazily: a clear marks every row fresh, and a row is
 * cleared when a scan first reaches it (zs_target.fresh) or a reader of
 * the whole frame asks (zs_raster_clear_fresh); finish hands out a blank
 * row for a row no draw reached.  A small model's frame so clears only
 * the rows it covers (zscan bench raster --case models measures it). */
static void mark_rows_fresh(zs_device *d) { memset(d->fresh, 1, (size_t)d->cfg.height); }

/* scanline and depthsort modes clear their one-row buffers row by row */
static void clear_rows_later(zs_device *d) { (void)d; }

/* Eager clearing, for a caller that holds the buffers' pointers: it may
 * read them at any time.  Part `part` of nparts (whole rows). */
typedef struct clear_job {
  zs_device *d;
  int nparts;
} clear_job;

static void clear_part(void *ctx, int part) {
  const clear_job *j = ctx;
  zs_device *d = j->d;
  size_t w = (size_t)d->cfg.width;
  size_t y0 = (size_t)zs_part_start(d->cfg.height, part, j->nparts);
  size_t y1 = (size_t)zs_part_start(d->cfg.height, part + 1, j->nparts);
  size_t off = y0 * w, px = (y1 - y0) * w;
  zs_clear_pixels(d->depth + off, d->id + off, d->rgb + off, d->count ? d->count + off : NULL, px,
                  d->cfg.background);
}

static void clear_frame(zs_device *d) {
  clear_job j = {d, 1};
  clear_part(&j, 0);
}

/* 12 bytes a pixel or more: worth the threads at any size that has them */
static void clear_frame_in_parts(zs_device *d) {
  clear_job j = {d, d->cfg.threads};
  zs_pool_run(d->pool, clear_part, &j, j.nparts);
}

zs_target zs_raster_frame_target(const zs_device *d) {
  zs_target t = {d->depth, d->id,  d->rgb,  d->count, d->cfg.width,
                 d->cfg.width, 0, d->fresh, d->cfg.background, d->abuf.rows};
  return t;
}

void zs_raster_clear_fresh(const zs_device *d) {
  if (!d->fresh) return;
  const size_t w = (size_t)d->cfg.width;
  for (int y = 0; y < d->cfg.height; y++)
    if (d->fresh[y]) {
      const size_t off = (size_t)y * w;
      zs_clear_pixels(d->depth + off, d->id + off, d->rgb + off, d->count ? d->count + off : NULL,
                      w, d->cfg.background);
      d->fresh[y] = 0;
    }
}

/* The buffers handed out: cleared now, and eagerly from now on.  (The
 * device is the caller's own, never a const object: only the view is.) */
static const uint32_t *hand_out(const zs_device *cd, const uint32_t *buffer) {
  zs_device *d = (zs_device *)cd;
  zs_raster_clear_fresh(d);
  d->clear_buffers = d->pool ? clear_frame_in_parts : clear_frame;
  return buffer;
}

const uint32_t *zs_device_depth_buffer(const zs_device *d) { return hand_out(d, d->depth); }
const uint32_t *zs_device_id_buffer(const zs_device *d) { return hand_out(d, d->id); }

void zs_device_clear(zs_device *d) {
  zs_defer_discard(d); /* drawn and cleared away: the same frame */
  d->nruns = 0;
  d->nomem_runs = 0;
  zs_clock_reset(d);
  zs_batch_reset(&d->batch);
  zs_depthsort_clear(d->depthsort);
  if (d->hzb) zs_hzb_invalidate(d->hzb);
  zs_surfaces_clear(&d->surf);
  zs_abuffer_clear(&d->abuf);
  zs_prim_rows_clear(&d->prim_rows);
  d->clear_buffers(d);
}

/* ---- draw ---- */

/* Draws at once.  A draw set up in parallel on its own, or one that
 * cannot wait, lands after the queue: the queue goes first, so that the
 * draws land in the order issued. */
static zs_status draw_now(zs_device *d, const zs_mesh *mesh, const double model[16],
                          uint32_t id_base, uint32_t rgb, zs_error *err) {
  zs_status st = zs_device_flush(d, err);
  if (st != ZS_OK) return st;
  /* In scanline mode the pixels are scanned at finish; the clock charges
   * them there. */
  zs_command c = {.kind = ZS_CMD_DRAW, .issued_ps = -1};
  st = zs_draw_at_once(d, mesh, model, id_base, rgb, d->drawing, &c, err);
  zs_clock_charge(d, &c);
  return st;
}

/* Deferring: a draw is queued unless a query counts its pixels now or it
 * is large enough to be set up in parallel on its own (defer.c). */
static zs_status draw_queued(zs_device *d, const zs_mesh *mesh, const double model[16],
                             uint32_t id_base, uint32_t rgb, zs_error *err) {
  if (d->query_open || mesh->nfaces >= ZS_DEFER_MAX_FACES ||
      (d->reads_attrs && zs_surface_reads(&d->surf, d->cfg.shade, mesh)))
    return draw_now(d, mesh, model, id_base, rgb, err);
  return zs_defer_push(d, mesh, model, id_base, rgb, err);
}

int zs_shade_draws_transparent(zs_shade shade, const zs_mesh *mesh) {
  /* a shading that reads attributes reads a transparent mesh's (auto
   * included: zs_surface_reads), but for the normals, drawn opaque */
  return zs_shade_reads_attrs(shade) && shade != ZS_SHADE_NORMAL && zs_mesh_transparent(mesh);
}

int zs_device_draws_transparent(const zs_device *d, const zs_mesh *mesh) {
  return zs_shade_draws_transparent(d->cfg.shade, mesh);
}

zs_status zs_device_draw(zs_device *d, const zs_mesh *mesh, const double model[16],
                         uint32_t id_base, uint32_t rgb, zs_error *err) {
  return d->draw(d, mesh, model, id_base, rgb, err);
}

/* Deferral pays where there are threads: zbuffer mode sets the queue up
 * and scans it in parallel (defer.c), scanline mode sets it up in
 * parallel and scans the frame in bands at finish (finish.c); depth sort
 * notes its faces in one list, so its draws stay immediate.  Without
 * memory for the queue, drawing stays immediate.  Turned off, the queue is
 * drawn at the next command that flushes (a draw does). */
void zs_device_defer_draws(zs_device *d, int on) {
  d->draw = on && d->pool && !d->painter && zs_defer_start(d) ? draw_queued : draw_now;
}

/* ---- the stages, chosen once ---- */

/* Sets every function and fixed value that the mode, the shading and the
 * threads decide, so that no command asks again. */
static void choose_stages(zs_device *d) {
  const int zbuffer = d->cfg.algo == ZS_ALGO_ZBUFFER;
  /* each kernel's draw stage and traversals at the device's SIMD level */
  for (int k = 0; k < ZS_KERNELS; k++) {
    zs_kernel_state *ks = &d->state_of[k];
    zs_draw_prep_fixed(&d->cfg, d->simd, d->gx, d->gy, d->prefetch_write, (zs_kernel)k,
                       &ks->prep);
    zs_scan_choose((zs_kernel)k, d->simd, &ks->traversal);
    zs_polyorder_choose((zs_kernel)k, d->simd, &ks->traversal);
  }
  const int overdraw = d->cfg.shade == ZS_SHADE_OVERDRAW;
  d->drawing = &d->state_of[overdraw ? ZS_KERNEL_OVERDRAW : ZS_KERNEL_DRAW];
  d->clear_counts = overdraw;
  d->painter = d->cfg.algo == ZS_ALGO_DEPTHSORT ? d->depthsort : NULL;
  /* the painter notes its faces' keys in one list: set up whole */
  d->set_up = d->pool && !d->painter ? zs_set_up_split : zs_set_up_whole;
  d->rasterize = !zbuffer ? zs_rasterize_later : d->pool ? zs_rasterize_banded : zs_rasterize_frame;
  d->clear_buffers = zbuffer ? mark_rows_fresh : clear_rows_later;
  d->draw = draw_now;
  d->shade_row = zs_row_shader_for(d->cfg.shade, d->perspective);
  zs_finish_choose(d);
}

zs_device_memory zs_device_memory_of(const zs_device *d) {
  zs_device_memory m = {0, 0, 0};
  size_t w = (size_t)d->cfg.width, px = w * (size_t)d->cfg.height;
  if (d->depth) /* and the blank row's four buffers, and a flag a row */
    m.pixel_buffers += 3 * px * sizeof(uint32_t) + 4 * w * sizeof(uint32_t) + (size_t)d->cfg.height;
  if (d->count) m.pixel_buffers += px * sizeof(uint32_t);
  if (d->row_depth) m.pixel_buffers += 4 * w * sizeof(uint32_t);
  if (d->band_rows) m.pixel_buffers += zs_finish_bands_bytes(d);
  m.pixel_buffers += w * sizeof(uint32_t); /* the shaded row */
  m.pixel_buffers += zs_abuffer_bytes(&d->abuf) + zs_prim_rows_bytes(&d->prim_rows);
  m.tables = (size_t)d->batch.cap_polys * sizeof(zs_poly) +
             (size_t)d->batch.cap_edges * sizeof(zs_edge) + zs_scan_scratch_bytes(&d->scratch);
  if (d->band_scratch)
    for (int i = 0; i < ZS_MAX_BANDS; i++) m.tables += zs_scan_scratch_bytes(&d->band_scratch[i]);
  m.tables += zs_defer_bytes(d) + (d->hzb ? zs_hzb_bytes(d->hzb) : 0) + zs_surfaces_bytes(&d->surf);
  m.tables += (size_t)d->frag_batch.cap_polys * sizeof(zs_poly) +
              (size_t)d->frag_batch.cap_edges * sizeof(zs_edge);
  m.vertices = zs_vert_scratch_bytes(&d->verts);
  return m;
}

zs_simd zs_device_simd(const zs_device *dev) { return dev->simd; }
