/* The device: its context, and the commands clear, draw and finish.
 *
 * zbuffer mode (immediate): each draw is transformed, clipped, set up into
 * a batch and walked at once into full-frame depth, id and colour buffers.
 * scanline mode: draws are set up into one batch for the whole frame, and
 * zs_device_finish walks it with buffers one row long, handing each row
 * out as soon as it is complete; the device then holds O(width) pixels.
 * Both walk with the same code and the same total order on (depth, id), so
 * their images are the same to the byte.
 * depthsort mode collects the frame like scanline mode, then orders its
 * faces (depthsort.c) and walks it with painter's depths.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "raster/internal.h"
#include "raster/pool.h"

#define ZS_DEFAULT_RGB 0xB4B4B4u /* faces without a colour: light grey */

static const char *const algo_names[] = {"zbuffer", "scanline", "depthsort"};

const char *zs_algo_name(zs_algo a) {
  return (unsigned)a < sizeof algo_names / sizeof algo_names[0] ? algo_names[a] : "?";
}

int zs_algo_parse(const char *name) {
  for (int i = 0; i < (int)(sizeof algo_names / sizeof algo_names[0]); i++)
    if (strcmp(name, algo_names[i]) == 0) return i;
  return -1;
}

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
  if (cfg->threads < 1 || cfg->threads > 64)
    return zs_error_set(err, ZS_ERR_ARG, "threads must be 1 to 64");
  zs_device *d = calloc(1, sizeof *d);
  if (!d) return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  d->cfg = *cfg;
  /* the span fill, chosen once: BEST and AVX2 take what the CPU has */
  d->simd = zs_span_simd_level(cfg->spans == ZS_SPANS_SCALAR ? ZS_SIMD_SCALAR
                               : cfg->spans == ZS_SPANS_SSE2 ? ZS_SIMD_SSE2
                                                             : ZS_SIMD_AVX2);
  size_t w = (size_t)cfg->width, px = w * (size_t)cfg->height;
  int ok = 1;
  if (cfg->algo == ZS_ALGO_ZBUFFER) { /* else scanline or depthsort: one row */
    d->depth = alloc_u32(px);
    d->id = alloc_u32(px);
    d->rgb = alloc_u32(px);
    ok = d->depth && d->id && d->rgb;
    if (ok && cfg->shade == ZS_SHADE_OVERDRAW) ok = (d->count = alloc_u32(px)) != NULL;
  } else {
    d->row_depth = alloc_u32(w);
    d->row_id = alloc_u32(w);
    d->row_rgb = alloc_u32(w);
    d->row_count = alloc_u32(w);
    ok = d->row_depth && d->row_id && d->row_rgb && d->row_count;
  }
  if (ok) ok = (d->row_out = alloc_u32(w)) != NULL;
  if (!ok) {
    zs_device_destroy(d);
    return zs_error_set(err, ZS_ERR_NOMEM,
                        "image size %dx%d: not enough memory for the buffers",
                        cfg->width, cfg->height);
  }
  if (ok && cfg->threads > 1 && cfg->algo == ZS_ALGO_ZBUFFER) {
    d->pool = zs_pool_create(cfg->threads);
    d->band_scratch = calloc(64, sizeof *d->band_scratch); /* one per band */
    d->setup_parts = calloc((size_t)cfg->threads, sizeof *d->setup_parts);
    ok = d->pool && d->band_scratch && d->setup_parts;
    d->prefetch_write = zs_cpu_has_prefetchw();
    if (!ok) {
      zs_device_destroy(d);
      return zs_error_set(err, ZS_ERR_NOMEM, "threads: cannot start %d threads", cfg->threads);
    }
  }
  d->gx = 1.0 + (double)(1 << 15) / cfg->width;
  d->gy = 1.0 + (double)(1 << 15) / cfg->height;
  zs_mat_identity(d->view);
  zs_mat_identity(d->proj);
  d->znear = 1.0;
  d->zfar = 100.0;
  zs_clock_params defaults;
  zs_clock_params_default(&defaults);
  zs_device_set_clock(d, &defaults, NULL);
  zs_device_clear(d);
  *out = d;
  return ZS_OK;
}

void zs_device_destroy(zs_device *d) {
  if (!d) return;
  free(d->depth);
  free(d->id);
  free(d->rgb);
  free(d->count);
  free(d->row_depth);
  free(d->row_id);
  free(d->row_rgb);
  free(d->row_count);
  free(d->row_out);
  free(d->runs);
  zs_batch_free(&d->batch);
  zs_walk_scratch_free(&d->scratch);
  zs_depthsort_free(&d->depthsort);
  zs_pool_destroy(d->pool);
  if (d->band_scratch)
    for (int i = 0; i < 64; i++) zs_walk_scratch_free(&d->band_scratch[i]);
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
void zs_device_set_trace(zs_device *d, const zs_trace_observer *obs) { d->trace = obs; }
const zs_depthsort_stats *zs_device_depthsort_stats(const zs_device *d) {
  return &d->depthsort.stats;
}
double zs_device_depthsort_ms(const zs_device *d) { return d->depthsort.ms; }
void zs_device_depthsort_reset(zs_device *d) { d->depthsort.has_prev = 0; }
const uint32_t *zs_device_depth_buffer(const zs_device *d) { return d->depth; }
const uint32_t *zs_device_id_buffer(const zs_device *d) { return d->id; }

void zs_device_set_camera(zs_device *d, const double view[16],
                          const double proj[16]) {
  memcpy(d->view, view, sizeof d->view);
  memcpy(d->proj, proj, sizeof d->proj);
  /* view = [R | t] with R a rotation: the eye is -R^T t. */
  for (int i = 0; i < 3; i++)
    d->eye[i] = -(view[i] * view[3] + view[4 + i] * view[7] + view[8 + i] * view[11]);
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
  /* Where the view axis lands in NDC: (-P02, -P12) under a perspective
   * (x_ndc = (P00 x + P02 z) / -z), (P03, P13) under a parallel
   * projection; the image plane's units are NDC over P00 and P11. */
  d->sort_cx = d->perspective ? -proj[2] : proj[3];
  d->sort_cy = d->perspective ? -proj[6] : proj[7];
  d->sort_sx = proj[0] != 0.0 ? 1.0 / proj[0] : 0.0;
  d->sort_sy = proj[5] != 0.0 ? 1.0 / proj[5] : 0.0;
  d->sort_r2 = 0.0;
  for (int corner = 0; corner < 4; corner++) { /* the farthest corner */
    double u = ((corner & 1 ? 1.0 : -1.0) - d->sort_cx) * d->sort_sx;
    double v = ((corner & 2 ? 1.0 : -1.0) - d->sort_cy) * d->sort_sy;
    if (u * u + v * v > d->sort_r2) d->sort_r2 = u * u + v * v;
  }
}

static void fill_u32(uint32_t *p, size_t n, uint32_t v) {
  for (size_t i = 0; i < n; i++) p[i] = v;
}

/* Clears the full-frame buffers' part `part` of nparts (whole rows). */
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
  fill_u32(d->depth + off, px, ZS_DEPTH_FAR);
  fill_u32(d->id + off, px, ZS_ID_NONE);
  fill_u32(d->rgb + off, px, d->cfg.background);
  if (d->count) memset(d->count + off, 0, px * sizeof *d->count);
}

void zs_device_clear(zs_device *d) {
  zs_defer_discard(d); /* drawn and cleared away: the same frame */
  memset(&d->stats, 0, sizeof d->stats);
  d->nruns = 0;
  d->nomem_runs = 0;
  zs_clock_reset(d);
  zs_batch_reset(&d->batch);
  d->depthsort.nfaces = 0;
  if (d->cfg.algo == ZS_ALGO_ZBUFFER) {
    /* 12 bytes a pixel or more: worth the threads at any size that has them */
    clear_job j = {d, d->pool ? d->cfg.threads : 1};
    if (d->pool) zs_pool_run(d->pool, clear_part, &j, j.nparts);
    else clear_part(&j, 0);
  }
}

int zs_vert_scratch_reserve(zs_vert_scratch *v, int32_t n) {
  if (n <= v->cap) return 1;
  zs_clip_vert *c = realloc(v->clip, (size_t)n * sizeof *c);
  if (!c) return 0;
  v->clip = c;
  double *e = realloc(v->eyepos, (size_t)n * 3 * sizeof *e);
  if (!e) return 0;
  v->eyepos = e;
  unsigned *o = realloc(v->outcode, (size_t)n * sizeof *o);
  if (!o) return 0;
  v->outcode = o;
  zs_snap_vert *s = realloc(v->snap, (size_t)n * sizeof *s);
  if (!s) return 0;
  v->snap = s;
  v->cap = n;
  return 1;
}

void zs_vert_scratch_free(zs_vert_scratch *v) {
  free(v->clip);
  free(v->eyepos);
  free(v->outcode);
  free(v->snap);
  memset(v, 0, sizeof *v);
}

size_t zs_vert_scratch_bytes(const zs_vert_scratch *v) {
  return (size_t)v->cap *
         (sizeof(zs_clip_vert) + 3 * sizeof(double) + sizeof(unsigned) + sizeof(zs_snap_vert));
}

zs_target zs_device_frame_target(zs_device *d) {
  zs_target t = {d->depth, d->id, d->rgb, d->count, d->cfg.width, d->cfg.width, d->simd};
  return t;
}

/* A batch walked in bands of rows, one per thread: each band writes only
 * its rows and counts into its own counters; they are summed in band
 * order, so images, counters and modelled times are the same for every
 * number of threads. */
typedef struct band_job {
  zs_device *d;
  zs_kernel k;
  zs_target t;
  zs_walk_counts counts[64];
  int ok[64];
  int nbands, row0, rows;  /* the bands split rows [row0, row0 + rows) */
} band_job;

static void walk_band(void *ctx, int band) {
  band_job *j = ctx;
  int y0 = j->row0 + (int)zs_part_start(j->rows, band, j->nbands);
  int y1 = j->row0 + (int)zs_part_start(j->rows, band + 1, j->nbands);
  j->counts[band] = (zs_walk_counts){0, 0, 0};
  j->ok[band] = zs_scan_batch(&j->d->batch, j->k, &j->t, y0, y1, NULL, NULL,
                              &j->d->band_scratch[band], &j->counts[band]);
}

/* Walks the batch into the full frame; in bands when threads pay. */
static int walk_full_frame(zs_device *d, zs_kernel k, zs_walk_counts *out) {
  zs_target t = zs_device_frame_target(d);
  /* below a thousand polygons, waking the threads costs more than it saves:
   * a teapot's 688 faces are walked on one thread (zscan render
   * builtin:teapots --cull vfc --repeat 11, drawing object by object, with
   * --threads 2 against --threads 1 measures it) */
  if (!d->pool || d->batch.npolys < 1024)
    return zs_scan_batch(&d->batch, k, &t, 0, d->cfg.height, NULL, NULL, &d->scratch, out);
  /* The rows the batch covers: bands over the whole frame would leave
   * most of them idle for an object that covers a few rows, and each band
   * still reads every polygon. */
  int32_t lo, hi;
  zs_batch_rows(&d->batch, 0, d->batch.npolys, d->cfg.height, &lo, &hi);
  int rows = hi - lo + 1, nbands = zs_band_count(d->cfg.threads, rows);
  if (nbands < 2)
    return zs_scan_batch(&d->batch, k, &t, 0, d->cfg.height, NULL, NULL, &d->scratch, out);
  band_job j;
  j.d = d;
  j.k = k;
  j.t = t;
  j.nbands = nbands;
  j.row0 = lo;
  j.rows = rows;
  zs_pool_run(d->pool, walk_band, &j, nbands);
  *out = (zs_walk_counts){0, 0, 0};
  int ok = 1;
  for (int b = 0; b < nbands; b++) {
    ok &= j.ok[b];
    zs_walk_counts_add(out, &j.counts[b]);
  }
  return ok;
}

void zs_add_walk_counts(zs_raster_stats *s, const zs_walk_counts *c) {
  s->spans += c->spans;
  s->pixels_tested += c->tested;
  s->pixels_written += c->written;
}

void zs_draw_prepare(const zs_device *d, const double model[16], zs_kernel k, zs_draw_prep *p) {
  if (model) zs_mat_mul(p->mv, d->view, model);
  else memcpy(p->mv, d->view, sizeof p->mv);
  zs_mat_mul(p->mvp, d->proj, p->mv);
  p->flat = d->cfg.shade == ZS_SHADE_FLAT && k == ZS_KERNEL_DRAW;
  p->need_eye = p->flat || d->cfg.algo == ZS_ALGO_DEPTHSORT;
  p->sp = (zs_setup_params){d->cfg.width, d->cfg.height, d->cfg.cull_back && k != ZS_KERNEL_QUERY,
                            0, 0, k == ZS_KERNEL_QUERY ? ZS_QUERY_DEPTH_BIAS : 0,
                            d->prefetch_write};
}

/* Vertices [i0, i1): to eye space (for the normals of flat shading and
 * the painter's keys) and to clip space, with the outcode, snapped when
 * inside every plane. */
void zs_draw_transform(const zs_device *d, const zs_draw_prep *pr, const zs_mesh *mesh,
                       zs_vert_scratch *v, int32_t i0, int32_t i1) {
  for (int32_t i = i0; i < i1; i++) {
    const double *p = &mesh->pos[3 * i];
    double c[4];
    zs_mat_apply(pr->mvp, p, c);
    v->clip[i] = (zs_clip_vert){c[0], c[1], c[2], c[3]};
    v->outcode[i] = zs_clip_outcode(&v->clip[i], d->gx, d->gy);
    /* snapped once here for all the faces that share it (set-up snaps
     * the vertices of a clipped face itself) */
    if (v->outcode[i] == 0) zs_snap_vertex(&pr->sp, &v->clip[i], &v->snap[i]);
    if (pr->need_eye) {
      double e[4];
      zs_mat_apply(pr->mv, p, e);
      memcpy(&v->eyepos[3 * i], e, 3 * sizeof e[0]);
    }
  }
}

/* Whether the polygon p[0..n-1] (clip space, w > 0) meets depth sort's
 * circle around the window: some edge passes within its radius (a corner
 * inside is an edge's end inside), or the polygon holds its centre (by
 * the crossings of the ray from the centre along +u). */
static int meets_sort_circle(const zs_device *d, const zs_clip_vert *p, int n) {
  double u0 = (p[n - 1].x / p[n - 1].w - d->sort_cx) * d->sort_sx;
  double v0 = (p[n - 1].y / p[n - 1].w - d->sort_cy) * d->sort_sy;
  int inside = 0;
  for (int i = 0; i < n; i++) {
    double u = (p[i].x / p[i].w - d->sort_cx) * d->sort_sx;
    double v = (p[i].y / p[i].w - d->sort_cy) * d->sort_sy;
    /* the point of the edge (u0, v0)-(u, v) nearest the centre */
    double du = u - u0, dv = v - v0, len2 = du * du + dv * dv;
    double t = len2 > 0.0 ? -(u0 * du + v0 * dv) / len2 : 0.0;
    t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
    double nu = u0 + t * du, nv = v0 + t * dv;
    if (nu * nu + nv * nv <= d->sort_r2) return 1;
    if ((v0 > 0.0) != (v > 0.0) && u0 - v0 * du / dv > 0.0) inside = !inside;
    u0 = u;
    v0 = v;
  }
  return inside;
}

/* Whether a face that set-up found turned away or without area may be
 * turned to the eye after all: its area in pixels from the unsnapped
 * corners is at most what snapping to 1/256 pixel can move it by (half a
 * subpixel a coordinate: under 1/256 of the lengths of the corners'
 * neighbour chords, which no rotation changes).  Set-up's back test is on
 * snapped corners, so a face far off or seen edge-on turns from drawn to
 * back or to no area as the view rolls; this test does not. */
static int nearly_turned_to_eye(const zs_setup_params *sp, const zs_clip_vert *p, int n) {
  double X[ZS_CLIP_MAX_VERTS], Y[ZS_CLIP_MAX_VERTS];
  for (int i = 0; i < n; i++) { /* window pixels, y down, as snapped */
    zs_window_xy(sp->width, sp->height, &p[i], &X[i], &Y[i]);
    Y[i] = sp->height - Y[i];
  }
  double area2 = 0.0, chords = 0.0;
  for (int i = 0, j = n - 1, k = n - 2; i < n; k = j, j = i++) {
    area2 += X[j] * Y[i] - X[i] * Y[j];
    double cx = X[i] - X[k], cy = Y[i] - Y[k]; /* the chord around corner j */
    chords += sqrt(cx * cx + cy * cy);
  }
  return area2 <= chords / 256.0 + n / 65536.0; /* back faces: area2 > 0 */
}

/* Whether depth sort orders a face set-up has seen (result r): whether
 * it meets the circle, and, where back faces are culled, is or may be
 * turned to the eye.  An unclipped face (clipped NULL; its corners fv,
 * snapped in v->snap) drawn with a corner in the window does, and one
 * plainly turned away does not; else the tests run on the clipped polygon
 * or on the corners copied to scratch. */
static int ordered_by_painter(const zs_device *d, const zs_setup_params *sp,
                              zs_setup_result r, const zs_vert_scratch *v, const int32_t *fv,
                              const zs_clip_vert *clipped, int n, zs_clip_vert *scratch) {
  const zs_clip_vert *poly = clipped;
  if (!clipped) {
    const zs_snap_vert *sn = v->snap; /* corner i at sn[fv[i]] */
    if (r == ZS_SETUP_BACK && sp->cull_back) {
      /* Most back faces are plainly so: twice their snapped area (in
       * subpixels) beyond four times their L1 perimeter (which bounds
       * twice the chords) plus the corners, more than snapping can take
       * away and nearly_turned_to_eye allow. */
      int64_t area2 = 0, perimeter = 0;
      for (int i = 0, j = n - 1; i < n; j = i++) {
        const zs_snap_vert *si = &sn[fv[i]], *sj = &sn[fv[j]];
        area2 += (int64_t)sj->x * si->y - (int64_t)si->x * sj->y;
        perimeter += llabs((int64_t)si->x - sj->x) + llabs((int64_t)si->y - sj->y);
      }
      if (area2 > 4 * perimeter + n + 1) return 0;
    }
    if (r == ZS_SETUP_DRAWN) {
      const int64_t wx = (int64_t)sp->width * ZS_SUBPIXEL_ONE;
      const int64_t wy = (int64_t)sp->height * ZS_SUBPIXEL_ONE;
      for (int i = 0; i < n; i++) {
        const zs_snap_vert *si = &sn[fv[i]];
        if (si->x >= 0 && si->x <= wx && si->y >= 0 && si->y <= wy) return 1;
      }
    }
    for (int i = 0; i < n; i++) scratch[i] = v->clip[fv[i]];
    poly = scratch;
  }
  if ((r == ZS_SETUP_BACK || r == ZS_SETUP_DEGENERATE) && sp->cull_back &&
      !nearly_turned_to_eye(sp, poly, n))
    return 0;
  return meets_sort_circle(d, poly, n);
}

/* Faces [f0, f1): trivial reject, flat colour, clipping where a face
 * crosses a plane. */
zs_status zs_draw_setup(const zs_device *d, const zs_draw_prep *pr, const zs_vert_scratch *v,
                        const zs_mesh *mesh, int32_t f0, int32_t f1, uint32_t id_base,
                        uint32_t rgb, zs_depthsort *ds, zs_batch *b, zs_face_counts *fc,
                        zs_error *err) {
  zs_clip_vert in[ZS_MAX_POLY_VERTS], clipped[ZS_CLIP_MAX_VERTS];
  zs_setup_params sp = pr->sp;
  for (int32_t f = f0; f < f1; f++) {
    /* nv: the face's vertices; n: its polygon's, once clipped */
    const int32_t s = mesh->face_start[f], nv = mesh->face_start[f + 1] - s;
    int32_t n = nv;
    fc->in++;
    if (n < 3 || n > ZS_MAX_POLY_VERTS) {
      fc->degenerate++;
      continue;
    }
    const int32_t *fv = &mesh->face_vert[s];
    unsigned and_code = ~0u, or_code = 0;
    for (int i = 0; i < n; i++) {
      if (fv[i] < 0 || fv[i] >= mesh->nverts)
        return zs_error_set(err, ZS_ERR_ARG,
                            "draw: face %d uses vertex %d of %d", (int)f,
                            (int)fv[i], (int)mesh->nverts);
      and_code &= v->outcode[fv[i]];
      or_code |= v->outcode[fv[i]];
    }
    if (and_code) {
      fc->outside++;
      continue;
    }
    sp.id = id_base + (uint32_t)(mesh->face_id ? mesh->face_id[f] : f);
    sp.rgb = rgb != ZS_RGB_MESH ? rgb
             : mesh->face_rgb ? mesh->face_rgb[f] : ZS_DEFAULT_RGB;
    const int32_t first_poly = b->npolys;
    zs_setup_result r;
    if (or_code) {
      for (int i = 0; i < n; i++) in[i] = v->clip[fv[i]];
      fc->clipped++;
      n = zs_clip_polygon(in, n, or_code, d->gx, d->gy, clipped);
      if (n == 0) {
        fc->outside++;
        continue;
      }
      r = zs_setup_polygon(b, &sp, clipped, n);
    } else {
      r = zs_setup_snapped(b, &sp, v->snap, fv, n);
    }
    if (pr->flat && b->npolys > first_poly) {
      /* Flat shading, for the faces that became polygons only (not the
       * ones culled, off the window or too small to hold a pixel centre):
       * Newell's normal of the face in eye space gives their colour */
      double nrm[3];
      if (nv == 3)
        zs_newell_normal(v->eyepos, 3, fv, 3, nrm);
      else if (nv == 4)
        zs_newell_normal(v->eyepos, 3, fv, 4, nrm);
      else
        zs_newell_normal(v->eyepos, 3, fv, nv, nrm);
      const uint32_t shaded = zs_shade_flat(sp.rgb, nrm);
      for (int32_t i = first_poly; i < b->npolys; i++) b->polys[i].rgb = shaded;
    }
    /* The painter orders the faces that meet the circle around the
     * window, drawn or not, turned to the eye or nearly: a roll keeps that
     * set whole, so the faces that turn into the window are in the old
     * order already.  A face drawn outside it (its box met a pixel centre,
     * the face does not) covers no pixel and is painted farthest. */
    if (ds && r != ZS_SETUP_NOMEM) {
      if (ordered_by_painter(d, &sp, r, v, fv, or_code ? clipped : NULL, n, in)) {
        /* the sort key: distance along the view axis of the centroid of
         * the face's vertices */
        double zsum = 0.0;
        for (int i = 0; i < nv; i++) zsum += v->eyepos[3 * fv[i] + 2];
        if (!zs_depthsort_note(ds, sp.id, -zsum / nv))
          return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
      }
    }
    switch (r) {
      case ZS_SETUP_DRAWN: fc->rasterized++; break;
      case ZS_SETUP_BACK: fc->culled_back++; break;
      case ZS_SETUP_DEGENERATE: fc->degenerate++; break;
      case ZS_SETUP_OFFSCREEN: fc->offscreen++; break;
      case ZS_SETUP_NOMEM: return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
    }
  }
  return ZS_OK;
}

void zs_add_face_counts(zs_raster_stats *s, const zs_face_counts *fc) {
  s->polygons_in += fc->in;
  s->polygons_outside += fc->outside;
  s->polygons_clipped += fc->clipped;
  s->polygons_culled_back += fc->culled_back;
  s->polygons_degenerate += fc->degenerate;
  s->polygons_offscreen += fc->offscreen;
  s->polygons_rasterized += fc->rasterized;
}

/* A large draw in zbuffer mode, split over the threads: the vertices in
 * ranges, then the faces in ranges, each set up into a batch of its own;
 * the batches are joined in face order, so the walk, the picture and the
 * counters are those of one thread. */
typedef struct setup_job {
  zs_device *d;
  const zs_mesh *mesh;
  const zs_draw_prep *prep;
  int nparts;
  uint32_t id_base, rgb;
  zs_batch *batch[64];
  zs_face_counts fc[64];
  zs_status st[64];
  zs_error err[64];
} setup_job;

static void transform_part(void *ctx, int part) {
  setup_job *j = ctx;
  int64_t n = j->mesh->nverts;
  zs_draw_transform(j->d, j->prep, j->mesh, &j->d->verts, (int32_t)zs_part_start(n, part, j->nparts),
                    (int32_t)zs_part_start(n, part + 1, j->nparts));
}

static void setup_part(void *ctx, int part) {
  setup_job *j = ctx;
  int64_t n = j->mesh->nfaces;
  j->fc[part] = (zs_face_counts){0, 0, 0, 0, 0, 0, 0};
  zs_error_clear(&j->err[part]);
  j->st[part] = zs_draw_setup(j->d, j->prep, &j->d->verts, j->mesh,
                              (int32_t)zs_part_start(n, part, j->nparts),
                              (int32_t)zs_part_start(n, part + 1, j->nparts), j->id_base, j->rgb, NULL,
                              j->batch[part], &j->fc[part], &j->err[part]);
}

static int parallel_setup(const zs_device *d, const zs_mesh *mesh) {
  return d->setup_parts && mesh->nfaces >= ZS_PARALLEL_SETUP_FACES;
}

zs_status zs_device_draw_with(zs_device *d, const zs_mesh *mesh,
                              const double model[16], uint32_t id_base,
                              uint32_t rgb, zs_kernel k, zs_walk_counts *out,
                              zs_error *err) {
  if (mesh->nverts < 0 || mesh->nfaces < 0)
    return zs_error_set(err, ZS_ERR_ARG, "draw: negative mesh size");
  if (!zs_vert_scratch_reserve(&d->verts, mesh->nverts > 0 ? mesh->nverts : 1))
    return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
  d->stats.draws++;
  d->stats.vertices += (uint64_t)mesh->nverts;

  zs_draw_prep prep;
  zs_draw_prepare(d, model, k, &prep);
  if (parallel_setup(d, mesh)) {
    /* (threads exist in zbuffer mode only, so never the painter) */
    setup_job *j = malloc(sizeof *j);
    if (!j) return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
    *j = (setup_job){d, mesh, &prep, d->cfg.threads, id_base, rgb,
                     {NULL}, {{0, 0, 0, 0, 0, 0, 0}}, {ZS_OK}, {{0, {0}}}};
    j->batch[0] = &d->batch;
    for (int t = 1; t < j->nparts; t++) j->batch[t] = &d->setup_parts[t];
    zs_pool_run(d->pool, transform_part, j, j->nparts);
    zs_pool_run(d->pool, setup_part, j, j->nparts);
    zs_status st = ZS_OK;
    for (int t = 0; t < j->nparts; t++) {
      if (st == ZS_OK) { /* as one thread would: counted up to the first error */
        zs_add_face_counts(&d->stats, &j->fc[t]);
        if ((st = j->st[t]) != ZS_OK) zs_error_set(err, st, "%s", j->err[t].msg);
        else if (t > 0 && !zs_batch_append(&d->batch, j->batch[t]))
          st = zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
      }
      if (t > 0) zs_batch_reset(j->batch[t]);
    }
    free(j);
    if (st != ZS_OK) return st;
  } else {
    zs_draw_transform(d, &prep, mesh, &d->verts, 0, mesh->nverts);
    zs_face_counts fc = {0, 0, 0, 0, 0, 0, 0};
    zs_status st = zs_draw_setup(d, &prep, &d->verts, mesh, 0, mesh->nfaces, id_base, rgb,
                                 d->cfg.algo == ZS_ALGO_DEPTHSORT ? &d->depthsort : NULL,
                                 &d->batch, &fc, err);
    zs_add_face_counts(&d->stats, &fc);
    if (st != ZS_OK) return st;
  }

  *out = (zs_walk_counts){0, 0, 0};
  if (d->cfg.algo == ZS_ALGO_ZBUFFER) {
    if (!walk_full_frame(d, k, out)) return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
    d->stats.spans += out->spans;
    if (k == ZS_KERNEL_DRAW || k == ZS_KERNEL_OVERDRAW) {
      d->stats.pixels_tested += out->tested;
      d->stats.pixels_written += out->written;
    }
    zs_batch_reset(&d->batch);
  }
  return ZS_OK;
}

zs_status zs_device_draw(zs_device *d, const zs_mesh *mesh,
                         const double model[16], uint32_t id_base, uint32_t rgb,
                         zs_error *err) {
  zs_kernel k = zs_draw_kernel(d);
  if (zs_defer_wanted(d, mesh, k)) return zs_defer_push(d, mesh, model, id_base, rgb, k, err);
  /* a draw set up in parallel on its own, or one that cannot wait: the
   * queue goes first, so that the draws land in the order issued */
  zs_status st = zs_device_flush(d, err);
  if (st != ZS_OK) return st;
  uint64_t polygons = zs_polygons_set_up(&d->stats);
  zs_walk_counts c;
  zs_clock_cpu(d, d->costs.cpu_per_call);
  st = zs_device_draw_with(d, mesh, model, id_base, rgb, k, &c, err);
  if (st != ZS_OK) return st;
  /* In scanline mode the pixels are walked in finish; the clock charges
   * them there. */
  int64_t cost = zs_clock_command_cost(d, mesh->nverts, zs_polygons_set_up(&d->stats) - polygons,
                                       &c, 0);
  int64_t end = zs_clock_gpu_command(d, cost, 0);
  if (d->query_open) {
    zs_query_rec *q = &d->queries[d->nqueries - 1];
    q->samples += c.written;
    q->gpu_end_ps = end;
  }
  return ZS_OK;
}

/* Scanline mode: the one-row buffers are cleared before each row and
 * shaded and handed out after it. */
typedef struct row_emit {
  zs_device *d;
  zs_row_sink sink;
  void *user;
} row_emit;

static void emit_row(zs_device *d, int y, const uint32_t *depth,
                     const uint32_t *id, const uint32_t *rgb,
                     const uint32_t *count, zs_row_sink sink, void *user) {
  if (!sink) return;
  const uint32_t *colours = rgb;
  if (d->cfg.shade != ZS_SHADE_FLAT) {
    zs_shade_row(d->cfg.shade, d->cfg.width, depth, id, count,
                 d->cfg.background, d->znear, d->zfar, d->perspective,
                 d->row_out);
    colours = d->row_out;
  }
  zs_row row = {y, d->cfg.width, colours, depth, id,
                d->cfg.shade == ZS_SHADE_OVERDRAW ? count : NULL};
  sink(user, &row);
}

static void scanline_begin_row(void *user, int y) {
  (void)y;
  zs_device *d = ((row_emit *)user)->d;
  size_t w = (size_t)d->cfg.width;
  fill_u32(d->row_depth, w, ZS_DEPTH_FAR);
  fill_u32(d->row_id, w, ZS_ID_NONE);
  fill_u32(d->row_rgb, w, d->cfg.background);
  memset(d->row_count, 0, w * sizeof *d->row_count);
}

static void scanline_end_row(void *user, int y) {
  row_emit *e = user;
  zs_device *d = e->d;
  emit_row(d, y, d->row_depth, d->row_id, d->row_rgb, d->row_count, e->sink,
           e->user);
}

zs_status zs_device_finish(zs_device *d, zs_row_sink sink, void *user,
                           zs_error *err) {
  const int w = d->cfg.width, h = d->cfg.height;
  zs_status st = zs_device_flush(d, err);
  if (st != ZS_OK) return st;
  if (d->cfg.algo != ZS_ALGO_ZBUFFER) {
    if (d->cfg.algo == ZS_ALGO_DEPTHSORT && !zs_depthsort_order(&d->depthsort, &d->batch, d->view))
      return zs_error_set(err, ZS_ERR_NOMEM, "finish: out of memory");
    row_emit e = {d, sink, user};
    zs_row_hooks hooks = {scanline_begin_row, scanline_end_row, &e};
    zs_target t = {d->row_depth, d->row_id, d->row_rgb, d->row_count, 0, w, d->simd};
    zs_walk_counts c = {0, 0, 0};
    if (!zs_scan_batch(&d->batch, zs_draw_kernel(d), &t, 0, h, &hooks, d->trace, &d->scratch, &c))
      return zs_error_set(err, ZS_ERR_NOMEM, "finish: out of memory");
    zs_add_walk_counts(&d->stats, &c);
    zs_clock_gpu_command(d, zs_clock_command_cost(d, 0, 0, &c, 0) - d->costs.per_call, 0);
    zs_batch_reset(&d->batch);
    return ZS_OK;
  }
  for (int y = 0; y < h; y++) {
    size_t off = (size_t)y * (size_t)w;
    emit_row(d, y, d->depth + off, d->id + off, d->rgb + off,
             d->count ? d->count + off : NULL, sink, user);
  }
  return ZS_OK;
}

static size_t scratch_bytes(const zs_walk_scratch *s) {
  return (size_t)s->cap_rows * sizeof *s->bucket_head +
         (size_t)s->cap_polys * (sizeof *s->next + sizeof *s->active + sizeof *s->cross);
}

zs_device_memory zs_device_memory_of(const zs_device *d) {
  zs_device_memory m = {0, 0, 0};
  size_t w = (size_t)d->cfg.width, px = w * (size_t)d->cfg.height;
  if (d->depth) m.pixel_buffers += 3 * px * sizeof(uint32_t);
  if (d->count) m.pixel_buffers += px * sizeof(uint32_t);
  if (d->row_depth) m.pixel_buffers += 4 * w * sizeof(uint32_t);
  m.pixel_buffers += w * sizeof(uint32_t); /* the shaded row */
  m.tables = (size_t)d->batch.cap_polys * sizeof(zs_poly) +
             (size_t)d->batch.cap_edges * sizeof(zs_edge) + scratch_bytes(&d->scratch);
  if (d->band_scratch)
    for (int i = 0; i < 64; i++) m.tables += scratch_bytes(&d->band_scratch[i]);
  m.tables += zs_defer_bytes(d);
  m.vertices = zs_vert_scratch_bytes(&d->verts);
  return m;
}

zs_simd zs_device_simd(const zs_device *dev) { return dev->simd; }
