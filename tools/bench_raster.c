/* `zscan bench raster`: raster throughput, in both hidden-surface modes.
 *
 * Two parts, each frame timed (wall clock, median of --repeat frames) from
 * clear to finish, with the device's own counters beside it:
 *   triangles  screens tiled with triangles of one size: the two halves of
 *              S x S pixel squares (S = 4, 10, 25, 100, 500), in layers
 *              drawn back to front so that every pixel of every layer is
 *              tested and written; enough layers that a frame fills at
 *              least 8 M pixels and draws at least 200,000 triangles (or
 *              64 layers);
 *   random     triangles of one size (right isosceles, legs of S pixels, S
 *              = 4, 10, 25, 100) at seeded random places and turns, each at
 *              its own depth, drawn back to front (every one written) and
 *              front to back (most of them hidden), as Masked Occlusion
 *              Culling's fill-rate test draws them: 200,000 a frame, or
 *              fewer for 16 M pixels;
 *   scenes     whole scenes from their own cameras: teapots, city, plant,
 *              a teapot field of about a million triangles, and small
 *              models of a few thousand triangles at full size.
 * It reports ms per frame, million triangles per second and million pixels
 * tested per second, and writes a CSV, a Markdown table and a plot. */
#define _GNU_SOURCE /* pthread_setaffinity_np, sched_getaffinity: the ceiling of --speedup */
#include "tools/bench_raster.h"

#include <math.h>
#include <pthread.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/exactmath.h"
#include "raster/raster.h"
#include "util/rng.h"
#include "scene/scene.h"
#include "tools/callgrind.h"
#include "tools/cli.h"
#include "util/os.h"
#include "tools/crosscheck.h"
#include "lib/frame.h"
#include "lib/frame_camera.h"
#include "lib/input.h"
#include "tools/mesa.h"
#include "lib/outfile.h"
#include "tools/plot.h"

static const char usage[] =
    "usage: zscan bench raster [options]\n"
    "  --repeat K        frames timed per case; the median is reported (default 11)\n"
    "  --threads N       render threads (default 1)\n"
    "  --size WxH        image size (default 1024x768)\n"
    "  --csv FILE        one row per case and mode\n"
    "  --md FILE         the table in Markdown\n"
    "  --plot FILE.png   Mtri/s and Mpix/s against triangle size, both modes\n"
    "  --no-scenes       the triangle sizes only\n"
    "  --no-tilings      the scenes only (no tilings or random triangles)\n"
    "  --simd LEVEL      cap the span fill and the vertex stage at scalar, sse2, avx2\n"
    "                    or avx512 (default: the best the CPU has; the same pixels at\n"
    "                    every level)\n"
    "  --no-simd         the same as --simd scalar\n"
    "  --mesa            also each case through Mesa's llvmpipe (OSMesa), frames taken\n"
    "                    in turn with zscan's zbuffer mode; llvmpipe's threads: LP_NUM_THREADS\n"
    "  --speedup         also the scenes on one thread and on --threads N, frames taken in\n"
    "                    turn: each pair's ratio, so that both see the same machine; and one\n"
    "                    thread on each of N CPUs at once, pinned: the speed-up's ceiling\n"
    "  --callgrind       also the instructions per frame of each case, one thread, counted\n"
    "                    by valgrind's callgrind (runs of 1 and 3 frames; the difference / 2)\n"
    "  --case NAME       only that case ('triangles 10x10', 'builtin:city', ...)\n"
    "  --shade MODE      the devices' shading: flat (default), auto, unlit, gouraud\n"
    "                    or phong (the scenes' own lights, else the headlight)\n"
    "  --algo MODE       only that mode: zbuffer or scanline\n";

static const int sides[] = {4, 10, 25, 100, 500};
enum { NSIDES = sizeof sides / sizeof sides[0] };
const char *const zs_bench_scenes[] = {"builtin:teapots", "builtin:city", "builtin:plant",
                                       "builtin:default,level=42", "builtin:teapots,count=4",
                                       "builtin:spheres,count=4",
                                       "scene/examples/teapot_textured.json"};
static const int random_sides[] = {4, 10, 25, 100};
enum { NRANDOM = 2 * sizeof random_sides / sizeof random_sides[0] };
enum { NSCENES = sizeof zs_bench_scenes / sizeof zs_bench_scenes[0] };
const int zs_bench_nscenes = NSCENES;
static const zs_algo algos[] = {ZS_ALGO_ZBUFFER, ZS_ALGO_SCANLINE};

typedef struct bench_opts {
  int repeat, threads, width, height, scenes, tilings;
  zs_simd simd; /* the cap asked for; after parsing, the level in use */
  int mesa, callgrind, speedup;
  int algo;               /* -1: both modes */
  zs_shade shade;         /* the devices' shading (default flat) */
  const char *only_case;  /* NULL: every case */
  const char *csv, *md, *plot;
} bench_opts;

typedef struct bench_row {
  char name[64];
  const char *algo;
  double triangles, pixels, ms;
  double table_bytes;   /* the polygon and edge tables and the walk's scratch, after a frame */
  double instructions;  /* per frame, under callgrind; 0: not counted */
} bench_row;

static double mtri(const bench_row *r) { return r->triangles / r->ms * 1e-3; }
static double mpix(const bench_row *r) { return r->pixels / r->ms * 1e-3; }
static double per(double a, double b) { return b > 0 ? a / b : 0.0; }

/* The devices' span fill: the level in use, as a config asks for it. */
static zs_span_fill spans_of(const bench_opts *o) { return (zs_span_fill)(ZS_SPANS_SCALAR + o->simd); }

static const char *simd_label(zs_simd level) {
  return level == ZS_SIMD_NEON     ? "NEON"
         : level == ZS_SIMD_AVX512 ? "AVX-512"
         : level == ZS_SIMD_AVX2 ? "AVX2"
         : level == ZS_SIMD_SSE2 ? "SSE2"
                                 : "scalar";
}

/* A tiling: each S x S square of the image as two triangles, in pixel
 * units, one mesh drawn as layers (instances) from the farthest to the
 * nearest, with an orthographic camera that puts the image in pixel units
 * and the layers between the planes.  A scene like the others, so that
 * zscan (time_scene) and llvmpipe (compare_mesa) draw it as they draw
 * those. */
typedef struct tiling {
  zs_scene scene;
  double view[16], proj[16];
} tiling;

static zs_status tiling_make(int side, int w, int h, tiling *t, zs_error *err) {
  zs_scene_init(&t->scene);
  int nx = w / side, ny = h / side;
  if (nx < 1 || ny < 1) return zs_error_set(err, ZS_ERR_ARG, "--size: smaller than %d pixels", side);
  zs_model m;
  zs_model_init(&m);
  zs_status st = ZS_OK;
  for (int j = 0; j <= ny && !st; j++)
    for (int i = 0; i <= nx && !st; i++)
      if (zs_model_add_vertex(&m, (double)i * side, (double)j * side, 0.0) < 0)
        st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  for (int j = 0; j < ny && !st; j++)
    for (int i = 0; i < nx && !st; i++) {
      int32_t a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
      const int32_t tri[2][3] = {{a, b, c}, {a, c, d}};
      for (int k = 0; k < 2 && !st; k++)
        if (zs_model_add_polygon(&m, tri[k], 3, 0x808080, -1))
          st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
    }
  int32_t mesh = st ? -1 : zs_scene_add_mesh(&t->scene, &m);
  zs_model_free(&m);
  if (!st && mesh < 0) st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  /* enough layers for 8 M pixels and 200,000 triangles a frame, at most 64 */
  double pixels = (double)nx * side * ny * side, faces = 2.0 * nx * ny;
  int by_pixels = (int)ceil(8e6 / pixels), by_tris = (int)ceil(2e5 / faces);
  int layers = by_pixels > by_tris ? by_pixels : by_tris;
  if (layers > 64) layers = 64;
  for (int l = 0; l < layers && !st; l++) {
    double model[16];
    char name[32];
    zs_mat_translate(model, 0.0, 0.0, -(double)(layers - l));
    snprintf(name, sizeof name, "layer %d", l);
    if (zs_scene_add_instance(&t->scene, mesh, model, 0x808080, name) < 0)
      st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  }
  if (!st) st = zs_scene_finish(&t->scene, err);
  if (st) {
    zs_scene_free(&t->scene);
    return st;
  }
  zs_mat_identity(t->view);
  zs_mat_ortho(t->proj, 0.0, w, 0.0, h, 0.5, layers + 1.0);
  return ZS_OK;
}

/* Random triangles: n right isosceles triangles with legs of `side`
 * pixels, each turned about its centroid by a random angle and placed at
 * a random point of the window (seeded: the same every run), triangle k
 * at depth k from the far plane (back to front) or from the near one
 * (front to back), all in one mesh drawn in order: the sorted tables are
 * walked across memory, not in the order the triangles lie. */
static zs_status random_make(int side, int front_to_back, int w, int h, tiling *t,
                             zs_error *err) {
  zs_scene_init(&t->scene);
  const double area = 0.5 * side * side;
  int n = (int)(16e6 / area);
  n = n > 200000 ? 200000 : n < 2000 ? 2000 : n;
  zs_rng rng;
  zs_rng_seed(&rng, 0x7A11u + (uint64_t)side);
  zs_model m;
  zs_model_init(&m);
  zs_status st = ZS_OK;
  /* the corners about the centroid, before the turn */
  const double corner[3][2] = {{-side / 3.0, -side / 3.0},
                               {2.0 * side / 3.0, -side / 3.0},
                               {-side / 3.0, 2.0 * side / 3.0}};
  for (int k = 0; k < n && !st; k++) {
    const double cx = zs_rng_range(&rng, 0.0, w), cy = zs_rng_range(&rng, 0.0, h);
    double s, c;
    zs_sincos_turns(zs_rng_uniform(&rng), &s, &c);
    const double z = front_to_back ? -(double)(k + 1) : -(double)(n - k);
    int32_t v[3];
    for (int i = 0; i < 3; i++) {
      const double x = corner[i][0] * c - corner[i][1] * s, y = corner[i][0] * s + corner[i][1] * c;
      if ((v[i] = zs_model_add_vertex(&m, cx + x, cy + y, z)) < 0) st = ZS_ERR_NOMEM;
    }
    if (!st && zs_model_add_polygon(&m, v, 3, 0x808080, -1)) st = ZS_ERR_NOMEM;
  }
  int32_t mesh = st ? -1 : zs_scene_add_mesh(&t->scene, &m);
  zs_model_free(&m);
  double model[16];
  zs_mat_identity(model);
  if (!st && (mesh < 0 || zs_scene_add_instance(&t->scene, mesh, model, 0x808080, "random") < 0))
    st = ZS_ERR_NOMEM;
  if (st) {
    zs_scene_free(&t->scene);
    return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  }
  if ((st = zs_scene_finish(&t->scene, err))) {
    zs_scene_free(&t->scene);
    return st;
  }
  zs_mat_identity(t->view);
  zs_mat_ortho(t->proj, 0.0, w, 0.0, h, 0.5, n + 1.0);
  return ZS_OK;
}

/* Times o->repeat frames of s from the camera (view, proj) on dev; the
 * counters of the last go to r. */
static zs_status time_scene(zs_device *dev, const zs_scene *s, const double view[16],
                            const double proj[16], const bench_opts *o, double *ms, bench_row *r,
                            zs_error *err) {
  for (int k = 0; k < o->repeat; k++) {
    double start = zs_os_monotonic_ms();
    zs_status st = zs_frame_render_on(dev, s, view, proj, 0, NULL, NULL, err);
    if (st) return st;
    ms[k] = zs_os_monotonic_ms() - start;
  }
  const zs_raster_stats *c = zs_device_stats(dev);
  r->triangles = (double)c->polygons_rasterized;
  r->pixels = (double)c->pixels_tested;
  r->ms = zs_median(ms, o->repeat);
  r->table_bytes = (double)zs_device_memory_of(dev).tables;
  return ZS_OK;
}

/* A case through zscan (zbuffer mode) and llvmpipe, frames in turn. */
typedef struct mesa_row {
  char name[64];
  double zscan_ms, mesa_ms;
  double triangles;    /* what llvmpipe is sent a frame: each face fanned */
  zs_crosscheck faces; /* zscan's faces against llvmpipe's (crosscheck.h) */
} mesa_row;

static zs_status compare_mesa(const bench_opts *o, const zs_scene *s, const char *name,
                              const double view[16], const double proj[16], double *ms,
                              mesa_row *r, zs_error *err) {
  const int w = o->width, h = o->height;
  double *mms = malloc((size_t)o->repeat * sizeof *mms);
  uint32_t *ids = malloc((size_t)w * h * sizeof *ids);
  zs_mesa *mesa = NULL;
  zs_device *dev = NULL;
  zs_device_config cfg = {w, h, ZS_ALGO_ZBUFFER, o->shade, 0, o->threads, 0, spans_of(o), 0};
  zs_status st = !mms || !ids ? zs_error_set(err, ZS_ERR_NOMEM, "out of memory") : ZS_OK;
  if (!st && !(st = zs_mesa_create(w, h, &mesa, err))) st = zs_device_create(&cfg, &dev, err);
  if (!st) st = zs_device_set_lights(dev, s->lights, s->nlights, err);
  for (int k = 0; k < o->repeat && !st; k++) { /* in turn: the same machine for both */
    double t0 = zs_os_monotonic_ms();
    if ((st = zs_frame_render_on(dev, s, view, proj, 0, NULL, NULL, err))) break;
    double t1 = zs_os_monotonic_ms();
    /* the same state: flat as one colour an instance, else the shading's */
    if ((st = o->shade == ZS_SHADE_FLAT
                  ? zs_mesa_frame(mesa, s, view, proj, err)
                  : zs_mesa_frame_shaded(mesa, s, view, proj, o->shade, ZS_FILTER_DEFAULT,
                                         s->lights, s->nlights, err)))
      break;
    ms[k] = t1 - t0;
    mms[k] = zs_os_monotonic_ms() - t1;
  }
  /* the faces each shows, told apart into coverage and depth ties */
  if (!st && !(st = zs_mesa_ids(mesa, s, view, proj, ids, err)))
    st = zs_crosscheck_faces(s, view, proj, w, h, ids, NULL, &r->faces, err);
  if (!st) {
    snprintf(r->name, sizeof r->name, "%s", name);
    r->zscan_ms = zs_median(ms, o->repeat);
    r->mesa_ms = zs_median(mms, o->repeat);
    r->triangles = (double)zs_scene_triangles(s);
  }
  zs_mesa_destroy(mesa);
  zs_device_destroy(dev);
  free(mms);
  free(ids);
  return st;
}

static void write_mesa_table(FILE *f, const mesa_row *rows, int n, const bench_opts *o, int md) {
  if (md) {
    fprintf(f, "\n| case | zscan ms | llvmpipe ms | zscan / llvmpipe | llvmpipe Mtri/s | faces "
               "differing in 10,000 pixels | of them, depth ties | coverage differing in 10,000 "
               "pixels |\n");
    fprintf(f, "|---|---|---|---|---|---|---|---|\n");
  } else {
    fprintf(f, "\nzscan (zbuffer, %d thread%s) and llvmpipe, frames in turn, median of %d\n",
            o->threads, o->threads > 1 ? "s" : "", o->repeat);
    fprintf(f, "%-28s %10s %12s %8s %14s %14s %12s %16s\n", "case", "zscan_ms", "llvmpipe_ms",
            "ratio", "llvmpipe_Mtri/s", "differ_per_10k", "ties_per_10k", "coverage_per_10k");
  }
  for (int i = 0; i < n; i++) {
    const mesa_row *r = &rows[i];
    const zs_crosscheck *c = &r->faces;
    double differ = 1e4 * (double)c->differ / (double)c->pixels;
    double ties = 1e4 * (double)c->ties / (double)c->pixels;
    double coverage = 1e4 * (double)(c->differ - c->ties) / (double)c->pixels;
    const double mtri_mesa = r->triangles / r->mesa_ms * 1e-3;
    if (md)
      fprintf(f, "| `%s` | %.2f | %.2f | %.2f | %.3g | %.2f | %.2f | %.2f |\n", r->name,
              r->zscan_ms, r->mesa_ms, r->zscan_ms / r->mesa_ms, mtri_mesa, differ, ties,
              coverage);
    else
      fprintf(f, "%-28s %10.3f %12.3f %8.3f %15.3g %14.2f %12.2f %16.2f\n", r->name,
              r->zscan_ms, r->mesa_ms, r->zscan_ms / r->mesa_ms, mtri_mesa, differ, ties,
              coverage);
  }
}

/* A scene on one thread and on o->threads, frames in turn: the run-long
 * slow spells of a shared machine fall on both sides of a pair alike, so
 * the pairs' ratios tell the speed-up where the medians of two separate
 * runs may not.
 *
 * The CPUs of a virtual machine need not be equal: one may share its core
 * with another guest's busy thread and run this frame far slower than the
 * other (--speedup reports the fastest and the slowest CPU's frame).  N
 * threads then cannot reach N times one thread.  So each round also
 * renders the frame on N one-thread devices at once, each pinned to one
 * of the first N CPUs the process may use: with t_i the
 * time on CPU i, the CPUs together do 1 / t_i frames a ms each, and a
 * speed-up of
 *   ceiling = t_one * sum_i 1 / t_i
 * is the most a perfect split of the frame could give that round, the
 * CPUs' interference with each other (caches, memory, a shared core)
 * included.  A speed-up near its ceiling leaves nothing to the code. */
typedef struct speedup_row {
  const char *name;
  const char *algo;
  double one_ms, many_ms;     /* medians */
  double ratio[3];            /* the pairs' ratios: lower quartile, median, upper quartile */
  int same;                   /* the same faces and depths in every pixel */
  int pinned;                 /* the ceiling was measured (the CPUs could be pinned) */
  double cpu_ms[2];           /* median frame on the fastest and the slowest CPU, pinned */
  double ceiling;             /* median of the rounds' ceilings */
  double share;               /* median of the rounds' speed-up / ceiling */
} speedup_row;

enum { MAX_PINNED = 64 }; /* the most threads a device takes */

typedef struct pinned_frame {
  zs_device *dev;
  const zs_scene *s;
  const double *view, *proj;
  int cpu, pinned;
  double ms;
  zs_status st;
  zs_error err;
} pinned_frame;

/* Pinning is Linux's (sched.h, pthread_setaffinity_np); elsewhere no
 * CPU is pinned and the table shows no ceiling. */
static void *render_pinned(void *arg) {
  pinned_frame *p = arg;
#ifdef __linux__
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(p->cpu, &set);
  p->pinned = pthread_setaffinity_np(pthread_self(), sizeof set, &set) == 0;
#else
  p->pinned = 0;
#endif
  double t0 = zs_os_monotonic_ms();
  p->st = zs_frame_render_on(p->dev, p->s, p->view, p->proj, 0, NULL, NULL, &p->err);
  p->ms = zs_os_monotonic_ms() - t0;
  return NULL;
}

/* The first n CPUs this process may run on, into cpus; 0 when it may use
 * fewer than n. */
static int first_cpus(int n, int *cpus) {
#ifdef __linux__
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) != 0) return 0;
  int k = 0;
  for (int c = 0; c < CPU_SETSIZE && k < n; c++)
    if (CPU_ISSET(c, &set)) cpus[k++] = c;
  return k == n;
#else
  (void)n, (void)cpus;
  return 0;
#endif
}

/* One frame on each of the pinned devices at once, its time into pf[i].ms;
 * *pinned is 0 when a thread could not be started or pinned (no
 * ceiling). */
static zs_status render_on_each_cpu(pinned_frame *pf, int n, int *pinned, zs_error *err) {
  pthread_t th[MAX_PINNED];
  int started = 0;
  for (; started < n; started++)
    if (pthread_create(&th[started], NULL, render_pinned, &pf[started]) != 0) break;
  for (int i = 0; i < started; i++) pthread_join(th[i], NULL);
  *pinned = started == n;
  for (int i = 0; i < started; i++) {
    if (pf[i].st) return zs_error_set(err, pf[i].st, "%s", pf[i].err.msg);
    *pinned &= pf[i].pinned;
  }
  return ZS_OK;
}

/* Whether the devices' last frames (rendered once more, into images with
 * depth) are the same to the byte. */
static zs_status same_frames(zs_device *dev[2], const zs_scene *s, const double view[16],
                             const double proj[16], int *same, zs_error *err) {
  const zs_device_config *cfg = zs_device_config_of(dev[0]);
  const size_t px = (size_t)cfg->width * (size_t)cfg->height;
  zs_image im[2] = {{0, 0, NULL}, {0, 0, NULL}};
  float *depth[2] = {malloc(px * sizeof(float)), malloc(px * sizeof(float))};
  zs_status st = depth[0] && depth[1] ? ZS_OK : zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  for (int d = 0; d < 2 && !st; d++)
    if (!(st = zs_image_alloc(&im[d], cfg->width, cfg->height, err)))
      st = zs_frame_render_on(dev[d], s, view, proj, 0, &im[d], depth[d], err);
  *same = !st && memcmp(im[0].rgb, im[1].rgb, px * sizeof *im[0].rgb) == 0 &&
          memcmp(depth[0], depth[1], px * sizeof(float)) == 0;
  for (int d = 0; d < 2; d++) {
    zs_image_free(&im[d]);
    free(depth[d]);
  }
  return st;
}

static zs_status compare_threads(const bench_opts *o, zs_algo algo, const zs_scene *s,
                                 const char *name, const double view[16], const double proj[16],
                                 double *ms, speedup_row *r, zs_error *err) {
  const int w = o->width, h = o->height, n = o->threads;
  double *many = malloc((size_t)o->repeat * sizeof *many);
  double *ratio = malloc((size_t)o->repeat * sizeof *ratio);
  double *ceiling = malloc((size_t)o->repeat * sizeof *ceiling);
  double *share = malloc((size_t)o->repeat * sizeof *share);
  double *cpu_ms = malloc((size_t)o->repeat * (size_t)n * sizeof *cpu_ms); /* [cpu][round] */
  zs_device *dev[2] = {NULL, NULL};
  pinned_frame pf[MAX_PINNED];
  memset(pf, 0, sizeof pf);
  int cpus[MAX_PINNED];
  int pinned = n <= MAX_PINNED && first_cpus(n, cpus);
  zs_status st = !many || !ratio || !ceiling || !share || !cpu_ms
                     ? zs_error_set(err, ZS_ERR_NOMEM, "out of memory")
                     : ZS_OK;
  for (int d = 0; d < 2 && !st; d++) {
    zs_device_config cfg = {w, h, algo, ZS_SHADE_FLAT, 0, d ? n : 1, 0, spans_of(o), 0};
    st = zs_device_create(&cfg, &dev[d], err);
  }
  for (int i = 0; i < n && pinned && !st; i++) {
    zs_device_config cfg = {w, h, algo, ZS_SHADE_FLAT, 0, 1, 0, spans_of(o), 0};
    st = zs_device_create(&cfg, &pf[i].dev, err);
    pf[i] = (pinned_frame){pf[i].dev, s, view, proj, cpus[i], 0, 0.0, ZS_OK, {0}};
  }
  for (int k = 0; k < o->repeat && !st; k++) {
    double t0 = zs_os_monotonic_ms();
    if ((st = zs_frame_render_on(dev[0], s, view, proj, 0, NULL, NULL, err))) break;
    double t1 = zs_os_monotonic_ms();
    if ((st = zs_frame_render_on(dev[1], s, view, proj, 0, NULL, NULL, err))) break;
    ms[k] = t1 - t0;
    many[k] = zs_os_monotonic_ms() - t1;
    ratio[k] = ms[k] / many[k];
    if (!pinned) continue;
    int ok = 0;
    if ((st = render_on_each_cpu(pf, n, &ok, err))) break;
    pinned = ok;
    double rate = 0.0;
    for (int i = 0; i < n; i++) {
      cpu_ms[(size_t)i * (size_t)o->repeat + (size_t)k] = pf[i].ms;
      rate += 1.0 / pf[i].ms;
    }
    ceiling[k] = ms[k] * rate;
    share[k] = ratio[k] / ceiling[k];
  }
  if (!st) st = same_frames(dev, s, view, proj, &r->same, err);
  if (!st) {
    r->name = name;
    r->algo = zs_algo_name(algo);
    r->one_ms = zs_median(ms, o->repeat);
    r->many_ms = zs_median(many, o->repeat);
    r->ratio[1] = zs_median(ratio, o->repeat); /* sorts ratio */
    r->ratio[0] = ratio[(o->repeat - 1) / 4];
    r->ratio[2] = ratio[o->repeat - 1 - (o->repeat - 1) / 4];
    r->pinned = pinned;
    if (pinned) {
      /* the CPUs by their median frame: the fastest and the slowest */
      for (int i = 0; i < n; i++) {
        double m = zs_median(&cpu_ms[(size_t)i * (size_t)o->repeat], o->repeat);
        if (i == 0 || m < r->cpu_ms[0]) r->cpu_ms[0] = m;
        if (i == 0 || m > r->cpu_ms[1]) r->cpu_ms[1] = m;
      }
      r->ceiling = zs_median(ceiling, o->repeat);
      r->share = zs_median(share, o->repeat);
    }
  }
  zs_device_destroy(dev[0]);
  zs_device_destroy(dev[1]);
  for (int i = 0; i < n && i < MAX_PINNED; i++) zs_device_destroy(pf[i].dev);
  free(many);
  free(ratio);
  free(ceiling);
  free(share);
  free(cpu_ms);
  return st;
}

static void write_speedup_table(FILE *f, const speedup_row *rows, int n, const bench_opts *o,
                                int md) {
  if (md) {
    fprintf(f, "\n| scene | algo | 1 thread ms | %d threads ms | speed-up, median of the pairs | "
               "lower and upper quartile | one thread on each CPU at once, ms: fastest, "
               "slowest | ceiling | speed-up / ceiling | the same image |\n",
            o->threads);
    fprintf(f, "|---|---|---|---|---|---|---|---|---|---|\n");
  } else {
    fprintf(f, "\nzscan on 1 thread and on %d, frames in turn, %d pairs; then one\n"
               "thread on each of %d CPUs at once: the ceiling of the speed-up\n",
            o->threads, o->repeat, o->threads);
    fprintf(f, "%-28s %-9s %10s %10s %8s %8s %8s %9s %9s %8s %8s %5s\n", "scene", "algo",
            "one_ms", "many_ms", "speedup", "q1", "q3", "cpu_fast", "cpu_slow", "ceiling", "share",
            "same");
  }
  for (int i = 0; i < n; i++) {
    const speedup_row *r = &rows[i];
    char fast[32] = "-", slow[32] = "-", ceil[32] = "-", share[32] = "-";
    if (r->pinned) {
      snprintf(fast, sizeof fast, "%.2f", r->cpu_ms[0]);
      snprintf(slow, sizeof slow, "%.2f", r->cpu_ms[1]);
      snprintf(ceil, sizeof ceil, md ? "%.2fx" : "%.3f", r->ceiling);
      snprintf(share, sizeof share, md ? "%.0f %%" : "%.3f", md ? 100.0 * r->share : r->share);
    }
    if (md)
      fprintf(f, "| `%s` | %s | %.2f | %.2f | %.2fx | %.2fx, %.2fx | %s, %s | %s | %s | %s |\n",
              r->name, r->algo, r->one_ms, r->many_ms, r->ratio[1], r->ratio[0], r->ratio[2], fast, slow,
              ceil, share, r->same ? "yes" : "no");
    else
      fprintf(f, "%-28s %-9s %10.3f %10.3f %8.3f %8.3f %8.3f %9s %9s %8s %8s %5s\n", r->name,
              r->algo, r->one_ms, r->many_ms, r->ratio[1], r->ratio[0], r->ratio[2], fast, slow, ceil,
              share, r->same ? "yes" : "no");
  }
}

/* The instructions per frame of one case and mode: this zscan runs the
 * case alone under callgrind for 1 and for 3 frames; loading and set-up
 * are the same in both, so half the difference is one frame. */
static zs_status count_instructions(const bench_opts *o, const char *name, zs_algo algo,
                                    double *per_frame, zs_error *err) {
  char size[64];
  snprintf(size, sizeof size, "%dx%d", o->width, o->height);
  uint64_t n[2];
  static const char *const frames[2] = {"1", "3"};
  for (int k = 0; k < 2; k++) {
    const char *args[] = {"bench",  "raster",          "--case",  name,
                          "--algo", zs_algo_name(algo), "--repeat", frames[k],
                          "--size", size,              "--simd",  zs_simd_name(o->simd),
                          "--shade", zs_shade_name(o->shade), NULL};
    zs_status st = zs_callgrind_count(args, &n[k], err);
    if (st) return st;
  }
  *per_frame = n[1] > n[0] ? (double)(n[1] - n[0]) / 2.0 : 0.0;
  return ZS_OK;
}

/* One case, the scene s from the camera (view, proj), in mode algos[a], on
 * a device of its own. */
static zs_status run_case(const bench_opts *o, int a, const char *name, const zs_scene *s,
                          const double view[16], const double proj[16], double *ms, bench_row *r,
                          zs_error *err) {
  zs_device_config cfg = {o->width, o->height, algos[a], o->shade, 0,
                          algos[a] == ZS_ALGO_ZBUFFER ? o->threads : 1, 0, spans_of(o), 0};
  zs_device *dev;
  zs_status st = zs_device_create(&cfg, &dev, err);
  if (st) return st;
  if ((st = zs_device_set_lights(dev, s->lights, s->nlights, err))) {
    zs_device_destroy(dev);
    return st;
  }
  snprintf(r->name, sizeof r->name, "%s", name);
  r->algo = zs_algo_name(algos[a]);
  st = time_scene(dev, s, view, proj, o, ms, r, err);
  zs_device_destroy(dev);
  r->instructions = 0;
  if (!st && o->callgrind) st = count_instructions(o, name, algos[a], &r->instructions, err);
  return st;
}

static void write_table(FILE *f, const bench_row *rows, int n, const bench_opts *o, int md) {
  if (md) {
    fprintf(f, "| case | algo | triangles | pixels tested | ms per frame | Mtri/s | Mpix/s | "
               "table bytes per triangle |%s\n",
            o->callgrind ? " instructions per frame | per triangle | per pixel tested |" : "");
    fprintf(f, "|---|---|---|---|---|---|---|---|%s\n", o->callgrind ? "---|---|---|" : "");
  } else {
    fprintf(f, "raster throughput at %dx%d, %d thread%s, %s spans, %s shading, median of %d "
            "frames\n", o->width, o->height, o->threads, o->threads > 1 ? "s" : "",
            simd_label(o->simd), zs_shade_name(o->shade), o->repeat);
    fprintf(f, "%-28s %-9s %10s %13s %10s %8s %8s %9s%s\n", "case", "algo", "triangles",
            "pixels_tested", "ms", "Mtri/s", "Mpix/s", "table_B/tri",
            o->callgrind ? "  instr/frame  instr/tri  instr/pix" : "");
  }
  for (int i = 0; i < n; i++) {
    const bench_row *r = &rows[i];
    if (md)
      fprintf(f, "| `%s` | %s | %.0f | %.0f | %.2f | %.3g | %.0f | %.0f |", r->name, r->algo,
              r->triangles, r->pixels, r->ms, mtri(r), mpix(r), per(r->table_bytes, r->triangles));
    else
      fprintf(f, "%-28s %-9s %10.0f %13.0f %10.3f %8.2f %8.1f %11.0f", r->name, r->algo,
              r->triangles, r->pixels, r->ms, mtri(r), mpix(r), per(r->table_bytes, r->triangles));
    if (o->callgrind)
      fprintf(f, md ? " %.0f | %.0f | %.1f |" : " %12.0f %10.0f %10.1f", r->instructions,
              per(r->instructions, r->triangles), per(r->instructions, r->pixels));
    fputc('\n', f);
  }
}

static zs_status write_csv(const char *path, const bench_row *rows, int n, const bench_opts *o,
                           zs_error *err) {
  zs_out out;
  if (zs_out_open(&out, path, err)) return err->code;
  FILE *f = out.fp;
  fprintf(f, "case,algo,threads,spans,width,height,triangles,pixels_tested,ms,mtri_per_s,"
             "mpix_per_s,table_bytes,instructions_per_frame\n");
  for (int i = 0; i < n; i++) {
    fprintf(f, "%s,%s,%d,%s,%d,%d,%.0f,%.0f,%.4f,%.3f,%.2f,%.0f,", rows[i].name, rows[i].algo,
            o->threads, zs_simd_name(o->simd), o->width, o->height, rows[i].triangles,
            rows[i].pixels, rows[i].ms, mtri(&rows[i]), mpix(&rows[i]), rows[i].table_bytes);
    if (o->callgrind) fprintf(f, "%.0f", rows[i].instructions);
    fputc('\n', f);
  }
  return zs_out_commit(&out, err);
}

static zs_status write_md(const char *path, const bench_row *rows, int n, const mesa_row *mrows,
                          int nm, const speedup_row *srows, int ns, const bench_opts *o,
                          zs_error *err) {
  zs_out out;
  if (zs_out_open(&out, path, err)) return err->code;
  FILE *f = out.fp;
  write_table(f, rows, n, o, 1);
  if (nm) write_mesa_table(f, mrows, nm, o, 1);
  if (ns) write_speedup_table(f, srows, ns, o, 1);
  return zs_out_commit(&out, err);
}

/* Mtri/s and Mpix/s against the triangles' side, both modes (rows: the
 * sides in order, zbuffer then scanline for each). */
static zs_status write_plot(const char *path, const bench_row *rows, const bench_opts *o,
                            zs_error *err) {
  char script[4096];
  size_t len = 0;
#define ADD(...) len += (size_t)snprintf(script + len, len < sizeof script ? sizeof script - len : 0, __VA_ARGS__)
  ADD("$data << EOD\n");
  for (int i = 0; i < NSIDES; i++)
    ADD("%d %.4f %.4f %.4f %.4f\n", sides[i], mtri(&rows[2 * i]), mtri(&rows[2 * i + 1]),
        mpix(&rows[2 * i]), mpix(&rows[2 * i + 1]));
  ADD("EOD\nset terminal pngcairo size 1200,500 font 'sans,11'\nset output OUT\n");
  ADD("set multiplot layout 1,2 title 'Raster throughput at %dx%d, %d thread%s, %s spans "
      "(triangles: halves of S x S squares; median of %d frames)'\n",
      o->width, o->height, o->threads, o->threads > 1 ? "s" : "", simd_label(o->simd),
      o->repeat);
  ADD("set grid\nset logscale xy\nset xlabel 'triangle side S (pixels)'\nset key top right\n"
      "set ylabel 'million triangles per second'\n"
      "plot $data using 1:2 with linespoints pt 7 lw 2 title 'zbuffer', \\\n"
      "     $data using 1:3 with linespoints pt 5 lw 2 title 'scanline'\n"
      "set key bottom right\nset ylabel 'million pixels tested per second'\n"
      "plot $data using 1:4 with linespoints pt 7 lw 2 title 'zbuffer', \\\n"
      "     $data using 1:5 with linespoints pt 5 lw 2 title 'scanline'\n"
      "unset multiplot\n");
#undef ADD
  if (len >= sizeof script) return zs_error_set(err, ZS_ERR_ARG, "plot script too long");
  return zs_plot_run(path, script, err);
}

static zs_status parse(int argc, char **argv, bench_opts *o, zs_error *err) {
  *o = (bench_opts){11, 1, 1024, 768, 1, 1, ZS_SIMD_AVX512, 0, 0, 0, -1, ZS_SHADE_FLAT, NULL,
                    NULL, NULL, NULL};
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = NULL;
    if (strcmp(a, "--no-scenes") == 0) {
      o->scenes = 0;
    } else if (strcmp(a, "--no-tilings") == 0) {
      o->tilings = 0;
    } else if (strcmp(a, "--no-simd") == 0) {
      o->simd = ZS_SIMD_SCALAR;
    } else if (strcmp(a, "--simd") == 0) {
      if (zs_cli_value(argc, argv, &i, &v, err)) return err->code;
      if (strcmp(v, "scalar") == 0) o->simd = ZS_SIMD_SCALAR;
      else if (strcmp(v, "sse2") == 0) o->simd = ZS_SIMD_SSE2;
      else if (strcmp(v, "avx2") == 0) o->simd = ZS_SIMD_AVX2;
      else if (strcmp(v, "avx512") == 0) o->simd = ZS_SIMD_AVX512;
      else return zs_error_set(err, ZS_ERR_ARG, "--simd: scalar, sse2, avx2 or avx512, not '%s'", v);
    } else if (strcmp(a, "--mesa") == 0) {
      if (!zs_mesa_available())
        return zs_error_set(err, ZS_ERR_UNSUPPORTED,
                            "--mesa: zscan was built without OSMesa (install libosmesa6-dev, rebuild)");
      o->mesa = 1;
    } else if (strcmp(a, "--speedup") == 0) {
      o->speedup = 1;
    } else if (strcmp(a, "--callgrind") == 0) {
      if (!zs_callgrind_available(err)) return err->code;
      o->callgrind = 1;
    } else if (strcmp(a, "--case") == 0) {
      if (zs_cli_value(argc, argv, &i, &o->only_case, err)) return err->code;
    } else if (strcmp(a, "--shade") == 0) {
      if (zs_cli_value(argc, argv, &i, &v, err)) return err->code;
      const int sh = zs_shade_parse(v);
      if (sh != ZS_SHADE_FLAT && sh != ZS_SHADE_UNLIT && sh != ZS_SHADE_GOURAUD &&
          sh != ZS_SHADE_PHONG && sh != ZS_SHADE_AUTO)
        return zs_error_set(err, ZS_ERR_ARG,
                            "--shade '%s': flat, auto, unlit, gouraud or phong", v);
      o->shade = (zs_shade)sh;
    } else if (strcmp(a, "--algo") == 0) {
      if (zs_cli_value(argc, argv, &i, &v, err)) return err->code;
      o->algo = zs_algo_parse(v);
      if (o->algo != ZS_ALGO_ZBUFFER && o->algo != ZS_ALGO_SCANLINE)
        return zs_error_set(err, ZS_ERR_ARG, "--algo '%s': zbuffer or scanline", v);
    } else if (strcmp(a, "--repeat") == 0) {
      if (zs_cli_int_value(argc, argv, &i, 1, 100000, &o->repeat, err)) return err->code;
    } else if (strcmp(a, "--threads") == 0) {
      if (zs_cli_int_value(argc, argv, &i, 1, 64, &o->threads, err)) return err->code;
    } else if (strcmp(a, "--size") == 0) {
      if (zs_cli_size_value(argc, argv, &i, ZS_MAX_IMAGE_SIDE, &o->width, &o->height, err))
        return err->code;
    } else if (strcmp(a, "--csv") == 0) {
      if (zs_cli_output_value(argc, argv, &i, &o->csv, err))
        return err->code;
    } else if (strcmp(a, "--md") == 0) {
      if (zs_cli_output_value(argc, argv, &i, &o->md, err))
        return err->code;
    } else if (strcmp(a, "--plot") == 0) {
      if (zs_cli_output_value(argc, argv, &i, &o->plot, err))
        return err->code;
    } else if (a[0] == '-' && a[1]) {
      return zs_error_set(err, ZS_ERR_ARG, "unknown option '%s' (see zscan bench raster --help)", a);
    } else {
      return zs_error_set(err, ZS_ERR_ARG, "unexpected argument '%s' (see zscan bench raster --help)", a);
    }
  }
  if (!o->scenes && !o->tilings)
    return zs_error_set(err, ZS_ERR_ARG, "--no-scenes and --no-tilings: no case left");
  if (!o->tilings && o->plot)
    return zs_error_set(err, ZS_ERR_ARG, "--plot draws the tilings: not with --no-tilings");
  if (o->speedup && o->threads < 2)
    return zs_error_set(err, ZS_ERR_ARG, "--speedup: against --threads N, N of 2 or more");
  if (o->width < sides[NSIDES - 1] || o->height < sides[NSIDES - 1])
    return zs_error_set(err, ZS_ERR_ARG, "--size: at least %dx%d (the largest triangles)",
                        sides[NSIDES - 1], sides[NSIDES - 1]);
  return ZS_OK;
}

int zs_cmd_bench_raster(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, NULL)) return 0;
  bench_opts o;
  zs_error err;
  zs_error_clear(&err);
  bench_row rows[2 * (NSIDES + NRANDOM + NSCENES)];
  mesa_row mrows[NSIDES + NRANDOM + NSCENES];
  speedup_row srows[2 * NSCENES];
  int n = 0, nm = 0, ns = 0;
  double *ms = NULL;
  zs_status st = parse(argc, argv, &o, &err);
  const int usage_error = st != ZS_OK; /* exits 2 (tools/cli.h) */
  o.simd = zs_span_simd_level(st ? ZS_SIMD_SCALAR : o.simd); /* what is in use */
  if (!st && !(ms = malloc((size_t)o.repeat * sizeof *ms)))
    st = zs_error_set(&err, ZS_ERR_NOMEM, "out of memory");
  for (int i = 0; i < NSIDES && o.tilings && !st; i++) {
    char name[64];
    snprintf(name, sizeof name, "triangles %dx%d", sides[i], sides[i]);
    if (o.only_case && strcmp(o.only_case, name) != 0) continue;
    tiling t;
    if ((st = tiling_make(sides[i], o.width, o.height, &t, &err))) break;
    for (int a = 0; a < 2 && !st; a++)
      if (o.algo < 0 || (int)algos[a] == o.algo)
        st = run_case(&o, a, name, &t.scene, t.view, t.proj, ms, &rows[n++], &err);
    if (!st && o.mesa) st = compare_mesa(&o, &t.scene, name, t.view, t.proj, ms, &mrows[nm++], &err);
    zs_scene_free(&t.scene);
  }
  for (int i = 0; i < NRANDOM && o.tilings && !st; i++) {
    char name[64];
    const int side = random_sides[i / 2], front = i % 2;
    snprintf(name, sizeof name, "random %dx%d %s", side, side,
             front ? "front to back" : "back to front");
    if (o.only_case && strcmp(o.only_case, name) != 0) continue;
    tiling t;
    if ((st = random_make(side, front, o.width, o.height, &t, &err))) break;
    for (int a = 0; a < 2 && !st; a++)
      if (o.algo < 0 || (int)algos[a] == o.algo)
        st = run_case(&o, a, name, &t.scene, t.view, t.proj, ms, &rows[n++], &err);
    if (!st && o.mesa) st = compare_mesa(&o, &t.scene, name, t.view, t.proj, ms, &mrows[nm++], &err);
    zs_scene_free(&t.scene);
  }
  for (int i = 0; i < NSCENES && o.scenes && !st; i++) {
    if (o.only_case && strcmp(o.only_case, zs_bench_scenes[i]) != 0) continue;
    zs_scene s;
    if ((st = zs_input_load_scene(zs_bench_scenes[i], &s, &err))) break;
    double view[16], proj[16];
    st = zs_frame_camera(&s, &s.camera, o.width, o.height, view, proj, &err);
    for (int a = 0; a < 2 && !st; a++)
      if (o.algo < 0 || (int)algos[a] == o.algo)
        st = run_case(&o, a, zs_bench_scenes[i], &s, view, proj, ms, &rows[n++], &err);
    if (!st && o.mesa) st = compare_mesa(&o, &s, zs_bench_scenes[i], view, proj, ms, &mrows[nm++], &err);
    for (int a = 0; a < 2 && o.speedup && !st; a++)
      if (o.algo < 0 || (int)algos[a] == o.algo)
        st = compare_threads(&o, algos[a], &s, zs_bench_scenes[i], view, proj, ms, &srows[ns++], &err);
    zs_scene_free(&s);
  }
  free(ms);
  if (!st && n == 0 && (!o.tilings || !o.scenes))
    st = zs_error_set(&err, ZS_ERR_ARG, "--case '%s': not among the %s (--no-%s)",
                      o.only_case ? o.only_case : "", o.tilings ? "tilings" : "scenes",
                      o.tilings ? "scenes" : "tilings");
  if (!st && n == 0)
    st = zs_error_set(&err, ZS_ERR_ARG,
                      "--case '%s': no such case (triangles SxS for S = 4, 10, 25, 100, 500; "
                      "random SxS back to front, random SxS front to back for S = 4, 10, 25, "
                      "100; builtin:teapots, builtin:city, builtin:plant, "
                      "builtin:default,level=42, builtin:teapots,count=4, "
                      "builtin:spheres,count=4, scene/examples/teapot_textured.json)",
                      o.only_case ? o.only_case : "");
  FILE *report = stdout;
  const char *outs[] = {o.csv, o.md, o.plot};
  if (!st) st = zs_out_report(outs, 3, "--csv, --md and --plot", &report, &err);
  if (!st) write_table(report, rows, n, &o, 0);
  if (!st && nm) write_mesa_table(report, mrows, nm, &o, 0);
  if (!st && ns) write_speedup_table(report, srows, ns, &o, 0);
  if (!st && o.csv && (st = write_csv(o.csv, rows, n, &o, &err))) zs_out_error_option(&err, "--csv");
  if (!st && o.md && (st = write_md(o.md, rows, n, mrows, nm, srows, ns, &o, &err)))
    zs_out_error_option(&err, "--md");
  if (!st && o.plot && (st = write_plot(o.plot, rows, &o, &err))) zs_out_error_option(&err, "--plot");
  for (int k = 0; k < 3 && !st; k++)
    if (outs[k] && !zs_out_is_stdout(outs[k])) fprintf(report, "wrote %s\n", outs[k]);
  if (st) {
    return zs_cli_fail("zscan bench raster", &err, usage_error);
  }
  return 0;
}
