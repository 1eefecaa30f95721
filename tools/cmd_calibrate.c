/* `zscan calibrate [-o clock.json] [--repeat K]`
 *
 * The clock models a command's GPU time as
 *   t = per_call calls + per_vertex vertices + per_polygon polygons
 *       + per_span spans + per_pixel tested + per_write written
 *       + per_query_pixel query_pixels.
 * Calibration runs workloads on the real device, each built so that one
 * term dominates (many draw calls of one tiny triangle; one draw of many
 * vertices and one face; one draw of many sub-pixel triangles; tall
 * triangles one pixel wide, a span per row; screen-sized quads hidden
 * behind a first one, so tested but not written; quads drawn back to
 * front, all written; query boxes), plus whole scenes to check the fit on
 * mixed work.  It times each
 * (median of K runs of the commands, the buffer clear excluded), fits the
 * seven constants by least squares on relative error, and prints every
 * workload's measured and predicted time.  The depth pyramid's four
 * (a pass, a texel written, a box tested, a texel a test reads) are
 * fitted the same way from builds at four image sizes and box tests of
 * two kinds (below, "the depth pyramid").
 *
 * What cannot be measured keeps its modelled default: zscan's CPU raster
 * answers a query at once, so it shows no query latency and no switch
 * cost, but a walk run with a latency of 0 would be another experiment
 * (the stall that hierarchical culling is about would vanish).  The
 * CPU-side constants (node visits, frustum tests) keep their defaults
 * too.  The output and the file say which constant is which ("source").
 */
#include "tools/commands.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "raster/raster.h"
#include "util/grow.h"
#include "util/rng.h"
#include "scene/generate.h"
#include "scene/camera.h"
#include "tools/clockfile.h"
#include "lib/outfile.h"
#include "tools/cli.h"
#include "util/os.h"
#include "lib/frame.h"
#include "lib/frame_camera.h"

enum { NTERMS = 7, SIDE = 512 };
static const char *term_names[NTERMS] = {"per_call_ns",  "per_vertex_ns", "per_polygon_ns",
                                         "per_span_ns",  "per_pixel_ns",  "per_write_ns",
                                         "per_query_pixel_ns"};

typedef struct workload {
  const char *name;
  double counts[NTERMS]; /* calls, vertices, polygons, spans, tested, written, query px */
  double ms;             /* measured median */
} workload;

/* A growing mesh (positions, quads or triangles), enough for the
 * synthetic workloads. */
typedef struct gen_mesh {
  zs_mesh m;
  int32_t cap_pos, cap_fv, cap_fs;
} gen_mesh;

static int gm_poly(gen_mesh *g, const double *xyz, int n) {
  /* each array its own capacity: a failed growth leaves the mesh whole */
  if (!zs_grow((void **)&g->m.pos, &g->cap_pos, (int64_t)g->m.nverts + n, 3 * sizeof *g->m.pos) ||
      !zs_grow((void **)&g->m.face_vert, &g->cap_fv, (int64_t)g->m.nverts + n,
               sizeof *g->m.face_vert) ||
      !zs_grow((void **)&g->m.face_start, &g->cap_fs, (int64_t)g->m.nfaces + 2,
               sizeof *g->m.face_start))
    return 0;
  if (g->m.nfaces == 0) g->m.face_start[0] = 0;
  for (int i = 0; i < n; i++) {
    memcpy(&g->m.pos[3 * (g->m.nverts + i)], &xyz[3 * i], 3 * sizeof(double));
    g->m.face_vert[g->m.nverts + i] = g->m.nverts + i;
  }
  g->m.nverts += n;
  g->m.nfaces++;
  g->m.face_start[g->m.nfaces] = g->m.nverts;
  return 1;
}

static void gm_free(gen_mesh *g) {
  free(g->m.pos);
  free(g->m.face_vert);
  free(g->m.face_start);
  memset(g, 0, sizeof *g);
}

/* A screen-sized quad at eye distance dist (orthographic camera). */
static int screen_quad(gen_mesh *g, double dist) {
  double q[12] = {0, 0, -dist, SIDE, 0, -dist, SIDE, SIDE, -dist, 0, SIDE, -dist};
  return gm_poly(g, q, 4);
}

typedef enum { W_CALLS, W_VERTICES, W_SETUP, W_SPANS, W_TESTED, W_WRITTEN, W_QUERY } synthetic;
enum { NSYNTHETIC = W_QUERY + 1 };

/* Runs one synthetic workload's commands on a cleared device. */
static zs_status run_synthetic(zs_device *d, synthetic kind, gen_mesh *meshes, int nmeshes,
                               zs_error *err) {
  for (int i = 0; i < nmeshes; i++) {
    if (kind == W_QUERY) {
      zs_query q;
      double lo[3] = {0, 0, -60.0 - i}, hi[3] = {SIDE, SIDE, -59.5 - i};
      if (zs_device_query_begin(d, &q, err) || zs_device_query_box(d, lo, hi, err) ||
          zs_device_query_end(d, err))
        return err->code;
    } else if (zs_device_draw(d, &meshes[i].m, NULL, (uint32_t)i * 1000000u, ZS_RGB_MESH, err)) {
      return err->code;
    }
  }
  return ZS_OK;
}

/* One run of a workload's commands on a cleared device. */
typedef zs_status (*workload_fn)(zs_device *d, void *ctx, zs_error *err);

/* The counts of the device's last frame. */
static void frame_counts(const zs_device *d, double c[NTERMS]) {
  const zs_raster_stats *s = zs_device_stats(d);
  const zs_clock_stats *k = zs_device_clock(d);
  c[0] = (double)s->draws;
  c[1] = (double)s->vertices;
  c[2] = (double)zs_polygons_set_up(s);
  c[3] = (double)s->spans;
  c[4] = (double)s->pixels_tested;
  c[5] = (double)s->pixels_written;
  c[6] = (double)k->query_pixels;
}

/* Times fn on d: the median over repeat runs of the commands alone (the
 * clear before each run is not timed), and the counts of the last run. */
static zs_status time_workload(zs_device *d, int repeat, workload_fn fn, void *ctx, workload *w,
                               zs_error *err) {
  double *times = malloc((size_t)repeat * sizeof *times);
  if (!times) return zs_error_set(err, ZS_ERR_NOMEM, "calibrate: out of memory");
  zs_status st = ZS_OK;
  for (int r = 0; r < repeat && st == ZS_OK; r++) {
    zs_device_clear(d);
    double t0 = zs_os_monotonic_ms();
    st = fn(d, ctx, err);
    times[r] = zs_os_monotonic_ms() - t0;
  }
  if (st == ZS_OK) {
    frame_counts(d, w->counts);
    w->ms = zs_median(times, repeat);
  }
  free(times);
  return st;
}

typedef struct synthetic_run {
  synthetic kind;
  gen_mesh *meshes;
  int n;
} synthetic_run;

static zs_status synthetic_fn(zs_device *d, void *ctx, zs_error *err) {
  synthetic_run *r = ctx;
  return run_synthetic(d, r->kind, r->meshes, r->n, err);
}

typedef struct scene_run {
  const zs_scene *m;
  double view[16], proj[16];
} scene_run;

static zs_status scene_fn(zs_device *d, void *ctx, zs_error *err) {
  scene_run *r = ctx;
  zs_device_set_camera(d, r->view, r->proj);
  return zs_frame_draw_scene(d, r->m, err);
}

static zs_status measure_synthetic(synthetic kind, int repeat, workload *w, zs_error *err) {
  zs_device_config cfg = {SIDE, SIDE, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, 1, 0, 0, 0};
  zs_device *d = NULL;
  if (zs_device_create(&cfg, &d, err)) return err->code;
  double view[16], proj[16];
  zs_mat_identity(view);
  zs_mat_ortho(proj, 0, SIDE, 0, SIDE, 0, 1000);
  zs_device_set_camera(d, view, proj);

  enum { MAXM = 3000 };
  gen_mesh *meshes = calloc(MAXM, sizeof *meshes);
  int n = 0, ok = meshes != NULL;
  if (ok && kind == W_CALLS) {
    /* 3,000 draws of one triangle of about one pixel */
    for (n = 0; n < 3000 && ok; n++) {
      double x = 1 + (n % 500), y = 1 + (n / 500) * 3;
      double t[9] = {x, y, -1, x + 1, y, -1, x, y + 1, -1};
      ok = gm_poly(&meshes[n], t, 3);
    }
  } else if (ok && kind == W_VERTICES) {
    /* one draw of 300,000 vertices used by a single triangle */
    n = 1;
    double t[9] = {1, 1, -1, 2, 1, -1, 1, 2, -1};
    ok = gm_poly(&meshes[0], t, 3);
    for (int i = 0; i < 100000 && ok; i++) ok = gm_poly(&meshes[0], t, 3);
    if (ok) meshes[0].m.nfaces = 1;
  } else if (ok && kind == W_SPANS) {
    /* 1,000 triangles one pixel wide and 500 rows tall: a span per row */
    n = 1;
    for (int i = 0; i < 1000 && ok; i++) {
      double x = 1.0 + (i % 500);
      double t[9] = {x, 2, -1, x + 1, 2, -1, x + 0.5, 502, -1};
      ok = gm_poly(&meshes[0], t, 3);
    }
  } else if (ok && kind == W_SETUP) {
    /* one draw of 200,000 triangles between pixel centres: set up, and
     * (almost) no pixel covered */
    n = 1;
    for (int i = 0; i < 200000 && ok; i++) {
      double x = 0.55 + (i % 500), y = 0.55 + (i / 500) % 500;
      double t[9] = {x, y, -1, x + 0.3, y, -1, x, y + 0.3, -1};
      ok = gm_poly(&meshes[0], t, 3);
    }
  } else if (ok && (kind == W_TESTED || kind == W_WRITTEN)) {
    /* 40 screen quads: front to back (only the first is written) or back
     * to front (all written) */
    for (n = 0; n < 40 && ok; n++)
      ok = screen_quad(&meshes[n], kind == W_TESTED ? 10.0 + n : 100.0 - n);
  } else if (ok) {
    n = 40; /* query boxes behind one screen quad drawn first */
  }
  if (!ok) {
    for (int i = 0; i < MAXM && meshes; i++) gm_free(&meshes[i]);
    free(meshes);
    zs_device_destroy(d);
    return zs_error_set(err, ZS_ERR_NOMEM, "calibrate: out of memory");
  }
  synthetic_run run = {kind, meshes, n};
  zs_status st = time_workload(d, repeat, synthetic_fn, &run, w, err);
  for (int i = 0; i < MAXM; i++) gm_free(&meshes[i]);
  free(meshes);
  zs_device_destroy(d);
  return st;
}

static zs_status measure_scene(const zs_scene *m, int repeat, workload *w, zs_error *err) {
  zs_device_config cfg = {SIDE, SIDE, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, 1, 0, 0, 0};
  zs_device *d = NULL;
  if (zs_device_create(&cfg, &d, err)) return err->code;
  zs_camera cam;
  zs_camera_default(&cam);
  scene_run run;
  run.m = m;
  zs_status st = zs_frame_camera(m, &cam, SIDE, SIDE, run.view, run.proj, err);
  if (st == ZS_OK) st = time_workload(d, repeat, scene_fn, &run, w, err);
  zs_device_destroy(d);
  return st;
}

/* ---- the depth pyramid ----
 * A build costs hzb_pass + texels written * hzb_per_texel; a test of n
 * boxes hzb_pass + n * hzb_per_box + texels read * hzb_per_read (clock.h).
 * Builds at four image sizes fix the first two.  The tests: random boxes
 * of three sizes against the plant's depth, most of them answered in a
 * few texels; and boxes each just behind a wall that hides it, which the
 * test proves only at the pixels round the box's outline, tens to
 * hundreds of texels a box: the two kinds tell a box's cost from a
 * texel's. */
enum { NHZB_TERMS = 4, NHZB_BUILDS = 4, NHZB_TESTS = 5, HZB_BOXES = 4000, HZB_BUILDS_RUN = 10 };
static const char *hzb_term_names[NHZB_TERMS] = {"hzb_pass_ns", "hzb_per_texel_ns",
                                                 "hzb_per_box_ns", "hzb_per_read_ns"};

typedef struct hzb_run {
  const double (*lo)[3], (*hi)[3];
  int n; /* boxes to test; 0: build HZB_BUILDS_RUN times */
} hzb_run;

static zs_status hzb_fn(zs_device *d, const hzb_run *r, uint8_t *maybe, zs_error *err) {
  if (r->n > 0) return zs_device_hzb_test(d, r->lo, r->hi, r->n, maybe, err);
  for (int k = 0; k < HZB_BUILDS_RUN; k++)
    if (zs_device_hzb_build(d, err)) return err->code;
  return ZS_OK;
}

/* Times run's pyramid commands after sc drawn from (view, proj) on a
 * side x side device (the draw and a first build are not timed); the
 * counts from the clock. */
static zs_status time_hzb(const zs_scene *sc, const double view[16], const double proj[16],
                          int side, int repeat, const hzb_run *run, workload *w, zs_error *err) {
  zs_device_config cfg = {side, side, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, 1, 0, 0, 0};
  zs_device *d = NULL;
  if (zs_device_create(&cfg, &d, err)) return err->code;
  double *times = malloc((size_t)repeat * sizeof *times);
  uint8_t *maybe = malloc(run->n > 0 ? (size_t)run->n : 1);
  zs_status st = times && maybe ? ZS_OK
                                : zs_error_set(err, ZS_ERR_NOMEM, "calibrate: out of memory");
  for (int r = 0; r < repeat && st == ZS_OK; r++) {
    st = zs_frame_draw_all(d, sc, view, proj, err);
    if (st == ZS_OK) st = zs_device_hzb_build(d, err);
    const zs_clock_stats before = *zs_device_clock(d);
    double t0 = zs_os_monotonic_ms();
    if (st == ZS_OK) st = hzb_fn(d, run, maybe, err);
    times[r] = zs_os_monotonic_ms() - t0;
    const zs_clock_stats *after = zs_device_clock(d);
    w->counts[0] = run->n ? 1 : HZB_BUILDS_RUN;
    w->counts[1] = (double)(after->hzb_texels - before.hzb_texels);
    w->counts[2] = (double)(after->hzb_boxes - before.hzb_boxes);
    w->counts[3] = (double)(after->hzb_reads - before.hzb_reads);
  }
  if (st == ZS_OK) w->ms = zs_median(times, repeat);
  free(times);
  free(maybe);
  zs_device_destroy(d);
  return st;
}

/* Random boxes of `size` times the scene's extent about random points of
 * it, n of them into lo, hi. */
static void random_boxes(const zs_scene *sc, double size, uint64_t seed, int n, double (*lo)[3],
                         double (*hi)[3]) {
  zs_rng rng;
  zs_rng_seed(&rng, seed);
  for (int i = 0; i < n; i++)
    for (int a = 0; a < 3; a++) {
      const double ext = sc->hi[a] - sc->lo[a];
      const double c = zs_rng_range(&rng, sc->lo[a], sc->hi[a]);
      const double half = zs_rng_range(&rng, 0.25, 1.0) * size * ext;
      lo[i][a] = c - half;
      hi[i][a] = c + half;
    }
}

/* A grid of g x g boxes, each behind a wall (in walls) that covers its
 * picture and a quarter pixel more, seen from the origin down -z on a
 * side x side device; the boxes repeated into n.  0: out of memory. */
static int walled_boxes(int g, int side, const double proj[16], zs_scene *walls, int n,
                        double (*lo)[3], double (*hi)[3]) {
  zs_model m;
  zs_model_init(&m);
  const double f = proj[5]; /* cot(fovy / 2) */
  int ok = 1;
  for (int c = 0; c < g * g && ok; c++) {
    const double cx = ((c % g) + 0.5) * 2.0 / g - 1.0, cy = ((c / g) + 0.5) * 2.0 / g - 1.0;
    const double h = 0.6 * 12.0 / (g * f); /* the near face 0.6 of the cell */
    double blo[3] = {cx * 13.0 / f - h, cy * 13.0 / f - h, -14.0};
    double bhi[3] = {cx * 13.0 / f + h, cy * 13.0 / f + h, -12.0};
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (int k = 0; k < 8; k++) { /* the box's picture, window pixels */
      const double p[3] = {k & 1 ? bhi[0] : blo[0], k & 2 ? bhi[1] : blo[1],
                           k & 4 ? bhi[2] : blo[2]};
      double o[4];
      zs_mat_apply(proj, p, o);
      const double xw = (o[0] / o[3] + 1.0) * 0.5 * side, yw = (o[1] / o[3] + 1.0) * 0.5 * side;
      /* compares, not fmin and fmax: gcc 12's loop vectorizer for aarch64
       * fails on their reduction at -O3 (an internal compiler error) */
      if (xw < x0) x0 = xw;
      if (xw > x1) x1 = xw;
      if (yw < y0) y0 = yw;
      if (yw > y1) y1 = yw;
    }
    /* the wall at z = -10 over those pixels, a quarter pixel more */
    const double u0 = ((x0 - 0.25) * 2.0 / side - 1.0) * 10.0 / f;
    const double u1 = ((x1 + 0.25) * 2.0 / side - 1.0) * 10.0 / f;
    const double v0 = ((y0 - 0.25) * 2.0 / side - 1.0) * 10.0 / f;
    const double v1 = ((y1 + 0.25) * 2.0 / side - 1.0) * 10.0 / f;
    const int32_t q[4] = {zs_model_add_vertex(&m, u0, v0, -10.0), zs_model_add_vertex(&m, u1, v0, -10.0),
                          zs_model_add_vertex(&m, u1, v1, -10.0), zs_model_add_vertex(&m, u0, v1, -10.0)};
    ok = q[0] >= 0 && q[1] >= 0 && q[2] >= 0 && q[3] >= 0 &&
         zs_model_add_polygon(&m, q, 4, 0x808080, -1) == ZS_OK;
    for (int i = c; i < n && ok; i += g * g) {
      memcpy(lo[i], blo, sizeof blo);
      memcpy(hi[i], bhi, sizeof bhi);
    }
  }
  zs_error err;
  ok = ok && zs_scene_add_mesh(walls, &m) >= 0 &&
       zs_scene_add_instance(walls, 0, NULL, 0x808080, "walls") >= 0 &&
       zs_scene_finish(walls, &err) == ZS_OK;
  zs_model_free(&m);
  return ok;
}

static zs_status measure_hzb(int repeat, workload *w, zs_error *err) {
  static const int sides[NHZB_BUILDS] = {256, 512, 1024, 2048};
  static const char *const names[NHZB_BUILDS + NHZB_TESTS] = {
      "pyramid 256^2", "pyramid 512^2", "pyramid 1024^2", "pyramid 2048^2", "boxes small",
      "boxes medium",  "boxes large",   "boxes walled 8", "boxes walled 32"};
  static const double sizes[3] = {0.01, 0.05, 0.25}; /* random, of the scene's extent */
  static const int grids[2] = {8, 32};               /* walled: g x g boxes */
  zs_scene plant;
  zs_scene_init(&plant);
  double(*lo)[3] = malloc(HZB_BOXES * sizeof *lo), (*hi)[3] = malloc(HZB_BOXES * sizeof *hi);
  zs_status st = lo && hi ? zs_gen_scene("plant", &plant, err)
                          : zs_error_set(err, ZS_ERR_NOMEM, "calibrate: out of memory");
  for (int k = 0; k < NHZB_BUILDS + NHZB_TESTS && st == ZS_OK; k++) {
    memset(&w[k], 0, sizeof w[k]);
    w[k].name = names[k];
    const int side = k < NHZB_BUILDS ? sides[k] : 512;
    double view[16], proj[16];
    if (k < NHZB_BUILDS + 3) { /* the plant from its camera */
      zs_camera cam;
      zs_camera_default(&cam);
      if ((st = zs_frame_camera(&plant, &cam, side, side, view, proj, err))) break;
      if (k >= NHZB_BUILDS) random_boxes(&plant, sizes[k - NHZB_BUILDS], 0xB0A5u + (uint64_t)k,
                                         HZB_BOXES, lo, hi);
      const hzb_run run = {(const double(*)[3])lo, (const double(*)[3])hi,
                           k < NHZB_BUILDS ? 0 : HZB_BOXES};
      st = time_hzb(&plant, view, proj, side, repeat, &run, &w[k], err);
      continue;
    }
    zs_mat_identity(view);
    zs_mat_perspective(proj, 60.0, 1.0, 1.0, 100.0);
    zs_scene walls;
    zs_scene_init(&walls);
    if (!walled_boxes(grids[k - NHZB_BUILDS - 3], side, proj, &walls, HZB_BOXES, lo, hi)) {
      st = zs_error_set(err, ZS_ERR_NOMEM, "calibrate: out of memory");
    } else {
      const hzb_run run = {(const double(*)[3])lo, (const double(*)[3])hi, HZB_BOXES};
      st = time_hzb(&walls, view, proj, side, repeat, &run, &w[k], err);
    }
    zs_scene_free(&walls);
  }
  free(lo);
  free(hi);
  zs_scene_free(&plant);
  return st;
}

/* Least squares on relative error: minimise sum ((c . x - t) / t)^2 over
 * the first nt terms, those in `use`, by the normal equations and
 * Gaussian elimination with partial pivoting.  Returns 0 when singular. */
static int fit(const workload *w, int nw, int nt, const int *use, double *x) {
  double a[NTERMS][NTERMS + 1];
  memset(a, 0, sizeof a);
  for (int k = 0; k < nw; k++) {
    double wt = 1.0 / (w[k].ms * w[k].ms);
    for (int i = 0; i < nt; i++) {
      double ci = use[i] ? w[k].counts[i] : 0.0;
      for (int j = 0; j < nt; j++) a[i][j] += wt * ci * (use[j] ? w[k].counts[j] : 0.0);
      a[i][nt] += wt * ci * w[k].ms;
    }
  }
  for (int i = 0; i < nt; i++)
    if (!use[i]) a[i][i] = 1.0, a[i][nt] = 0.0;
  for (int c = 0; c < nt; c++) {
    int p = c;
    for (int r = c + 1; r < nt; r++)
      if (fabs(a[r][c]) > fabs(a[p][c])) p = r;
    if (fabs(a[p][c]) < 1e-300) return 0;
    for (int j = 0; j <= nt; j++) {
      double t = a[c][j];
      a[c][j] = a[p][j];
      a[p][j] = t;
    }
    for (int r = 0; r < nt; r++) {
      if (r == c) continue;
      double f = a[r][c] / a[c][c];
      for (int j = c; j <= nt; j++) a[r][j] -= f * a[c][j];
    }
  }
  for (int i = 0; i < nt; i++) x[i] = a[i][nt] / a[i][i];
  return 1;
}

/* Fits the first nt terms; a negative constant is no cost: it is dropped
 * and the rest fitted again.  0 when the workloads do not determine them. */
static int fit_nonnegative(const workload *w, int nw, int nt, double *x) {
  int use[NTERMS];
  for (int i = 0; i < nt; i++) use[i] = 1;
  for (int round = 0; round < nt; round++) {
    if (!fit(w, nw, nt, use, x)) return 0;
    int neg = -1;
    for (int i = 0; i < nt; i++)
      if (use[i] && x[i] < 0 && (neg < 0 || x[i] < x[neg])) neg = i;
    if (neg < 0) break;
    use[neg] = 0;
  }
  return 1;
}

/* Prints each workload's first nt counts, its measured and modelled
 * time; returns nothing, the table is the point. */
static void print_fit(const workload *w, int nw, int nt, const char *const *heads,
                      const double *x) {
  printf("%-17s", "workload");
  for (int i = 0; i < nt; i++) printf(" %9s", heads[i]);
  printf(" %8s %8s %7s\n", "ms", "model_ms", "error");
  double worst = 0.0, sum2 = 0.0;
  for (int k = 0; k < nw; k++) {
    double pred = 0.0;
    for (int i = 0; i < nt; i++) pred += x[i] * w[k].counts[i];
    double e = (pred - w[k].ms) / w[k].ms;
    if (fabs(e) > worst) worst = fabs(e);
    sum2 += e * e;
    printf("%-17s", w[k].name);
    for (int i = 0; i < nt; i++) printf(" %9.0f", w[k].counts[i]);
    printf(" %8.3f %8.3f %+6.1f%%\n", w[k].ms, pred, 100.0 * e);
  }
  printf("fit error: rms %.1f %%, worst %.1f %% over %d workloads\n", 100.0 * sqrt(sum2 / nw),
         100.0 * worst, nw);
}

int zs_cmd_calibrate(int argc, char **argv) {
  if (zs_cli_help(argc, argv, "usage: zscan calibrate [-o clock.json] [--repeat K]\n", NULL))
    return 0;
  const char *out = "clock.json";
  int repeat = 9;
  zs_error err;
  zs_error_clear(&err);
  int parsing = 1; /* a usage error exits 2 (tools/cli.h) */
  for (int i = 1; i < argc; i++) {
    const char *v;
    if (strcmp(argv[i], "-o") == 0) {
      if (zs_cli_value(argc, argv, &i, &v, &err)) goto fail;
      out = v;
    } else if (strcmp(argv[i], "--repeat") == 0) {
      if (zs_cli_int_value(argc, argv, &i, 1, 1000, &repeat, &err)) goto fail;
    } else {
      zs_error_set(&err, ZS_ERR_ARG, "unknown option '%s'", argv[i]);
      goto fail;
    }
  }
  if (zs_cli_output_path("-o", out, &err)) goto fail;

  parsing = 0;
  workload w[NSYNTHETIC + 4] = {
      {"draw calls", {0}, 0},     {"vertices", {0}, 0},       {"set-up", {0}, 0},
      {"spans", {0}, 0},          {"pixels tested", {0}, 0},  {"pixels written", {0}, 0},
      {"query pixels", {0}, 0},   {"teapot field", {0}, 0},   {"teapot field L12", {0}, 0},
      {"cubes 10^3", {0}, 0},     {"teapot field L2", {0}, 0}};
  for (int k = 0; k < NSYNTHETIC; k++)
    if (measure_synthetic((synthetic)k, repeat, &w[k], &err)) goto fail;
  static const char *const scenes[4] = {"default", "default?level=12", "cubes?n=10",
                                         "default?level=2"};
  for (int k = 0; k < 4; k++) {
    zs_scene sc;
    zs_scene_init(&sc);
    zs_status st = zs_gen_scene(scenes[k], &sc, &err);
    if (st == ZS_OK) st = measure_scene(&sc, repeat, &w[NSYNTHETIC + k], &err);
    zs_scene_free(&sc);
    if (st) goto fail;
  }
  int nw = NSYNTHETIC + 4;

  double x[NTERMS];
  if (!fit_nonnegative(w, nw, NTERMS, x)) {
    zs_error_set(&err, ZS_ERR_ARG, "calibrate: the workloads do not determine the constants");
    goto fail;
  }
  static const char *const heads[NTERMS] = {"calls",  "vertices", "polygons", "spans",
                                            "tested", "written",  "query_px"};
  print_fit(w, nw, NTERMS, heads, x);

  /* The depth pyramid's own constants, from its builds and box tests. */
  workload hw[NHZB_BUILDS + NHZB_TESTS];
  if (measure_hzb(repeat, hw, &err)) goto fail;
  double hx[NHZB_TERMS];
  if (!fit_nonnegative(hw, NHZB_BUILDS + NHZB_TESTS, NHZB_TERMS, hx)) {
    zs_error_set(&err, ZS_ERR_ARG, "calibrate: the pyramid's workloads do not determine its constants");
    goto fail;
  }
  static const char *const hheads[NHZB_TERMS] = {"passes", "texels", "boxes", "reads"};
  printf("\n");
  print_fit(hw, NHZB_BUILDS + NHZB_TESTS, NHZB_TERMS, hheads, hx);
  printf("\n");

  zs_clock_params p;
  zs_clock_params_default(&p);
  p.per_call_ns = x[0] * 1e6;
  p.per_vertex_ns = x[1] * 1e6;
  p.per_polygon_ns = x[2] * 1e6;
  p.per_span_ns = x[3] * 1e6;
  p.per_pixel_ns = x[4] * 1e6;
  p.per_write_ns = x[5] * 1e6;
  p.per_query_pixel_ns = x[6] * 1e6;
  p.hzb_pass_ns = hx[0] * 1e6;
  p.hzb_per_texel_ns = hx[1] * 1e6;
  p.hzb_per_box_ns = hx[2] * 1e6;
  p.hzb_per_read_ns = hx[3] * 1e6;
  unsigned char measured[sizeof(zs_clock_params) / sizeof(double)] = {0};
  for (int f = 0; f < zs_clockfile_nfields; f++) {
    for (int i = 0; i < NTERMS; i++)
      measured[f] |= strcmp(zs_clockfile_fields[f].name, term_names[i]) == 0;
    for (int i = 0; i < NHZB_TERMS; i++)
      measured[f] |= strcmp(zs_clockfile_fields[f].name, hzb_term_names[i]) == 0;
  }
  for (int f = 0; f < zs_clockfile_nfields; f++)
    printf("%-22s %12.4f ns  %s\n", zs_clockfile_fields[f].name,
           *(const double *)((const char *)&p + zs_clockfile_fields[f].offset),
           measured[f] ? "measured" : "default (modelled: this device cannot show it)");
  if (zs_clockfile_write(out, &p, measured, &err)) {
    zs_out_error_option(&err, "-o");
    goto fail;
  }
  printf("wrote %s\n", out);
  return 0;
fail:
  return zs_cli_fail("zscan calibrate", &err, parsing);
}
