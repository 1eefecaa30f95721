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
 * five constants by least squares on relative error, and prints every
 * workload's measured and predicted time.
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
#include "raster/grow.h"
#include "scene/generate.h"
#include "scene/camera.h"
#include "tools/clockfile.h"
#include "lib/outfile.h"
#include "tools/cli.h"
#include "lib/frame.h"

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
    double t0 = zs_wall_ms();
    st = fn(d, ctx, err);
    times[r] = zs_wall_ms() - t0;
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
  zs_device_config cfg = {SIDE, SIDE, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, 1, 0, 0};
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
  zs_device_config cfg = {SIDE, SIDE, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, 1, 0, 0};
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

/* Least squares on relative error: minimise sum ((c . x - t) / t)^2 over
 * the terms in `use`, by the normal equations and Gaussian elimination
 * with partial pivoting.  Returns 0 when singular. */
static int fit(const workload *w, int nw, const int use[NTERMS], double x[NTERMS]) {
  double a[NTERMS][NTERMS + 1];
  memset(a, 0, sizeof a);
  for (int k = 0; k < nw; k++) {
    double wt = 1.0 / (w[k].ms * w[k].ms);
    for (int i = 0; i < NTERMS; i++) {
      double ci = use[i] ? w[k].counts[i] : 0.0;
      for (int j = 0; j < NTERMS; j++) a[i][j] += wt * ci * (use[j] ? w[k].counts[j] : 0.0);
      a[i][NTERMS] += wt * ci * w[k].ms;
    }
  }
  for (int i = 0; i < NTERMS; i++)
    if (!use[i]) a[i][i] = 1.0, a[i][NTERMS] = 0.0;
  for (int c = 0; c < NTERMS; c++) {
    int p = c;
    for (int r = c + 1; r < NTERMS; r++)
      if (fabs(a[r][c]) > fabs(a[p][c])) p = r;
    if (fabs(a[p][c]) < 1e-300) return 0;
    for (int j = 0; j <= NTERMS; j++) {
      double t = a[c][j];
      a[c][j] = a[p][j];
      a[p][j] = t;
    }
    for (int r = 0; r < NTERMS; r++) {
      if (r == c) continue;
      double f = a[r][c] / a[c][c];
      for (int j = c; j <= NTERMS; j++) a[r][j] -= f * a[c][j];
    }
  }
  for (int i = 0; i < NTERMS; i++) x[i] = a[i][NTERMS] / a[i][i];
  return 1;
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

  /* Fit; a negative constant is no cost: drop it and fit the rest. */
  int use[NTERMS] = {1, 1, 1, 1, 1, 1, 1};
  double x[NTERMS];
  for (int round = 0; round < NTERMS; round++) {
    if (!fit(w, nw, use, x)) {
      zs_error_set(&err, ZS_ERR_ARG, "calibrate: the workloads do not determine the constants");
      goto fail;
    }
    int neg = -1;
    for (int i = 0; i < NTERMS; i++)
      if (use[i] && x[i] < 0 && (neg < 0 || x[i] < x[neg])) neg = i;
    if (neg < 0) break;
    use[neg] = 0;
  }

  printf("%-17s %6s %8s %8s %8s %9s %9s %9s %8s %8s %7s\n", "workload", "calls", "vertices",
         "polygons", "spans", "tested", "written", "query_px", "ms", "model_ms", "error");
  double worst = 0.0, sum2 = 0.0;
  for (int k = 0; k < nw; k++) {
    double pred = 0.0;
    for (int i = 0; i < NTERMS; i++) pred += x[i] * w[k].counts[i];
    double e = (pred - w[k].ms) / w[k].ms;
    if (fabs(e) > worst) worst = fabs(e);
    sum2 += e * e;
    printf("%-17s %6.0f %8.0f %8.0f %8.0f %9.0f %9.0f %9.0f %8.3f %8.3f %+6.1f%%\n", w[k].name,
           w[k].counts[0], w[k].counts[1], w[k].counts[2], w[k].counts[3], w[k].counts[4],
           w[k].counts[5], w[k].counts[6], w[k].ms, pred, 100.0 * e);
  }
  printf("fit error: rms %.1f %%, worst %.1f %% over %d workloads\n", 100.0 * sqrt(sum2 / nw),
         100.0 * worst, nw);

  zs_clock_params p;
  zs_clock_params_default(&p);
  p.per_call_ns = x[0] * 1e6;
  p.per_vertex_ns = x[1] * 1e6;
  p.per_polygon_ns = x[2] * 1e6;
  p.per_span_ns = x[3] * 1e6;
  p.per_pixel_ns = x[4] * 1e6;
  p.per_write_ns = x[5] * 1e6;
  p.per_query_pixel_ns = x[6] * 1e6;
  unsigned char measured[sizeof(zs_clock_params) / sizeof(double)] = {0};
  for (int f = 0; f < zs_clock_nfields; f++)
    for (int i = 0; i < NTERMS; i++)
      measured[f] |= strcmp(zs_clock_fields[f].name, term_names[i]) == 0;
  for (int f = 0; f < zs_clock_nfields; f++)
    printf("%-22s %12.4f ns  %s\n", zs_clock_fields[f].name,
           *(const double *)((const char *)&p + zs_clock_fields[f].offset),
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
