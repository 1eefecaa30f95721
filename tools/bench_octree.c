/* `zscan bench octree [--count N] [--frames F] [--depth D] [--looseness K]
 *                     [--split S] [--csv FILE] [--plot FILE.png]`
 *
 * Experiment 1 of the CHC cost-model paper: N spheres (default 5,000) in
 * the 1,000-unit cube, of which M move along their local x axis; for
 * M = N/10, 2N/10, ..., N (500 .. 5,000) the time one frame's update takes
 * in the loose octree and in the plain one.  For each M: generate
 * spheres?count=N&moving=M&seed=1, build both trees, then F times (default
 * 50) advance the scene one frame and time zs_octree_update of each tree.
 * The times are medians over the frames (wall clock, monotonic); the work
 * counters are per-frame means, and deterministic.
 *
 * Output: a table on stdout, the trees' shape after the last run (depth,
 * nodes, objects per level), a CSV (--csv) and a PNG plot drawn by gnuplot
 * (--plot): update time per frame and per moved object against M.  Files
 * are written under a temporary name and renamed when complete.
 */
#include "tools/bench_octree.h"
#include "tools/plot.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cull/octree.h"
#include "scene/generate.h"
#include "tools/cli.h"
#include "util/os.h"
#include "lib/outfile.h"


enum { STEPS = 10 };

typedef struct bench_row {
  int moving;
  double ms[2];            /* median update time per frame: loose, plain */
  double build_ms[2];
  zs_octree_work work[2];  /* summed over the frames */
  zs_octree_stats stats[2];
} bench_row;

typedef struct bench_opts {
  int count, frames, depth, split;
  double looseness;
  const char *csv, *plot;
} bench_opts;

static const char usage[] =
    "usage: zscan bench octree [--count N] [--frames F] [--depth D] [--looseness K]\n"
    "                          [--split S] [--csv FILE] [--plot FILE.png]\n"
    "  N spheres (default 5000), M = N/10 .. N of them moving (10 steps); per M the\n"
    "  median update time over F frames (default 50) of a loose octree (looseness K,\n"
    "  default 2) and a plain one, both of depth D (default 4) and split policy S\n"
    "  (default 0: every object at its own level)\n";

/* ---- measuring ------------------------------------------------------------ */

static zs_status run_one(const bench_opts *o, int moving, bench_row *row, zs_error *err) {
  char spec[128];
  snprintf(spec, sizeof spec, "spheres?count=%d&moving=%d&seed=1", o->count, moving);
  zs_scene s;
  if (zs_gen_scene(spec, &s, err)) return err->code;
  memset(row, 0, sizeof *row);
  row->moving = moving;

  zs_octree tree[2];
  memset(tree, 0, sizeof tree);
  zs_status st = ZS_OK;
  double *ms = malloc(2 * (size_t)o->frames * sizeof *ms);
  if (!ms) st = zs_error_set(err, ZS_ERR_NOMEM, "bench octree: out of memory");
  for (int k = 0; k < 2 && st == ZS_OK; k++) {
    zs_octree_params p;
    zs_octree_params_default(&p, k == 0 ? ZS_OCTREE_LOOSE : ZS_OCTREE_PLAIN);
    p.max_depth = o->depth;
    p.looseness = o->looseness;
    p.split = o->split;
    double t0 = zs_os_monotonic_ms();
    st = zs_octree_build(&tree[k], &s, &p, err);
    row->build_ms[k] = zs_os_monotonic_ms() - t0;
  }
  for (int f = 0; f < o->frames && st == ZS_OK; f++) {
    zs_scene_advance(&s);
    for (int k = 0; k < 2 && st == ZS_OK; k++) {
      double t0 = zs_os_monotonic_ms();
      st = zs_octree_update(&tree[k], &s, &row->work[k], err);
      ms[k * o->frames + f] = zs_os_monotonic_ms() - t0;
    }
  }
  if (st == ZS_OK) {
    for (int k = 0; k < 2; k++) {
      row->ms[k] = zs_median(ms + k * o->frames, o->frames);
      zs_octree_stats_get(&tree[k], &row->stats[k]);
    }
  }
  free(ms);
  zs_octree_free(&tree[0]);
  zs_octree_free(&tree[1]);
  zs_scene_free(&s);
  return st;
}

/* ---- output --------------------------------------------------------------- */

static double per_frame(int64_t v, int frames) { return (double)v / frames; }

static double us_per_object(const bench_row *r, int k) {
  return r->moving > 0 ? 1000.0 * r->ms[k] / r->moving : 0.0;
}

static void print_row(FILE *report, const bench_row *r, int frames) {
  fprintf(report, "%6d %9.4f %9.4f %8.4f %8.4f %10.1f %10.1f %8.1f %8.1f %7.1f\n", r->moving, r->ms[0],
         r->ms[1], us_per_object(r, 0), us_per_object(r, 1),
         per_frame(zs_octree_work_nodes(&r->work[0]), frames),
         per_frame(zs_octree_work_nodes(&r->work[1]), frames),
         per_frame(r->work[0].scanned, frames), per_frame(r->work[1].scanned, frames),
         r->work[0].moved > 0 ? 100.0 * (double)r->work[0].same_cell / (double)r->work[0].moved
                              : 0.0);
  fflush(stdout);
}

static void print_shape(FILE *report, const bench_row *r, const bench_opts *o) {
  static const char *names[2] = {"loose", "plain"};
  fprintf(report, "\ntrees after %d frames with %d of %d spheres moving (depth limit %d, split %d):\n",
         o->frames, r->moving, o->count, o->depth, o->split);
  fprintf(report, "%-6s %5s %6s %6s %11s  objects per level (nodes)\n", "tree", "depth", "nodes",
         "leaves", "max/node");
  for (int k = 0; k < 2; k++) {
    const zs_octree_stats *st = &r->stats[k];
    fprintf(report, "%-6s %5d %6d %6d %11d ", names[k], st->depth, st->nodes, st->leaves,
           st->max_objects);
    for (int l = 0; l <= o->depth; l++)
      fprintf(report, " L%d: %d (%d)", l, st->objects_per_level[l], st->nodes_per_level[l]);
    if (st->outside) fprintf(report, "  outside: %d", st->outside);
    fprintf(report, "\n");
  }
}

static zs_status write_csv(const char *path, const bench_row *rows, int n, int frames,
                           zs_error *err) {
  zs_out out;
  if (zs_out_open(&out, path, err)) return err->code;
  FILE *f = out.fp;
  fprintf(f,
          "moving,loose_ms,plain_ms,loose_us_per_object,plain_us_per_object,"
          "loose_nodes_touched,plain_nodes_touched,loose_scanned,plain_scanned,"
          "loose_rebounds,plain_rebounds,loose_same_cell,loose_reinserts,plain_reinserts,"
          "loose_nodes_created,plain_nodes_created,loose_nodes,plain_nodes,"
          "loose_depth,plain_depth,loose_build_ms,plain_build_ms\n");
  for (int i = 0; i < n; i++) {
    const bench_row *r = &rows[i];
    fprintf(f, "%d,%.6f,%.6f,%.6f,%.6f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,"
               "%d,%d,%d,%d,%.3f,%.3f\n",
            r->moving, r->ms[0], r->ms[1], us_per_object(r, 0), us_per_object(r, 1),
            per_frame(zs_octree_work_nodes(&r->work[0]), frames),
            per_frame(zs_octree_work_nodes(&r->work[1]), frames),
            per_frame(r->work[0].scanned, frames), per_frame(r->work[1].scanned, frames),
            per_frame(r->work[0].rebounds, frames), per_frame(r->work[1].rebounds, frames),
            per_frame(r->work[0].same_cell, frames), per_frame(r->work[0].inserts, frames),
            per_frame(r->work[1].inserts, frames), per_frame(r->work[0].nodes_created, frames),
            per_frame(r->work[1].nodes_created, frames), r->stats[0].nodes, r->stats[1].nodes,
            r->stats[0].depth, r->stats[1].depth, r->build_ms[0], r->build_ms[1]);
  }
  return zs_out_commit(&out, err);
}

/* The plot: update time per frame and per moved object, both trees, drawn
 * by gnuplot through tools/plot.c. */
static zs_status write_plot(const char *path, const bench_row *rows, int n, const bench_opts *o,
                            zs_error *err) {
  size_t cap = 4096 + (size_t)n * 128;
  char *script = malloc(cap);
  if (!script) return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  size_t len = 0;
#define ADD(...) len += (size_t)snprintf(script + len, len < cap ? cap - len : 0, __VA_ARGS__)
  ADD("$data << EOD\n");
  for (int i = 0; i < n; i++)
    ADD("%d %.6f %.6f %.6f %.6f\n", rows[i].moving, rows[i].ms[0], rows[i].ms[1],
        us_per_object(&rows[i], 0), us_per_object(&rows[i], 1));
  ADD("EOD\nset terminal pngcairo size 1200,500 font 'sans,11'\nset output OUT\n");
  ADD("set multiplot layout 1,2 title 'Octree update with moving spheres "
      "(%d spheres, depth %d, loose k = %g, split %d; median of %d frames)'\n",
      o->count, o->depth, o->looseness, o->split, o->frames);
  ADD("set grid\nset key top left\nset xlabel 'moving objects'\nset xrange [0:*]\n"
      "set yrange [0:*]\n"
      "set ylabel 'update time per frame (ms)'\n"
      "plot $data using 1:2 with linespoints pt 7 lw 2 title 'loose octree', \\\n"
      "     $data using 1:3 with linespoints pt 5 lw 2 title 'plain octree'\n"
      "set key bottom right\n"
      "set ylabel 'update time per moved object (microseconds)'\n"
      "plot $data using 1:4 with linespoints pt 7 lw 2 title 'loose octree', \\\n"
      "     $data using 1:5 with linespoints pt 5 lw 2 title 'plain octree'\n"
      "unset multiplot\n");
#undef ADD
  zs_status st = len < cap ? zs_plot_run(path, script, err)
                           : zs_error_set(err, ZS_ERR_NOMEM, "--plot: script too long");
  free(script);
  return st;
}

/* ---- the command ------------------------------------------------------------ */

int zs_cmd_bench_octree(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, NULL)) return 0;
  bench_opts o = {ZS_GEN_SPHERES_MAX, 50, ZS_OCTREE_DEFAULT_DEPTH, 0,
                  ZS_OCTREE_DEFAULT_LOOSENESS, NULL, NULL};
  bench_row rows[STEPS];
  zs_error err;
  zs_error_clear(&err);
  int parsing = 1; /* a usage error exits 2 (tools/cli.h) */
  for (int i = 1; i < argc; i++) {
    const char *v;
    const char *a = argv[i];
    if (strcmp(a, "--csv") == 0 || strcmp(a, "--plot") == 0) {
      if (zs_cli_value(argc, argv, &i, &v, &err)) goto fail;
      *(a[2] == 'c' ? &o.csv : &o.plot) = v;
    } else if (strcmp(a, "--count") == 0) {
      if (zs_cli_int_value(argc, argv, &i, STEPS, ZS_GEN_SPHERES_MAX, &o.count, &err)) goto fail;
    } else if (strcmp(a, "--frames") == 0) {
      if (zs_cli_int_value(argc, argv, &i, 1, 100000, &o.frames, &err)) goto fail;
    } else if (strcmp(a, "--depth") == 0) {
      if (zs_cli_int_value(argc, argv, &i, 0, ZS_OCTREE_MAX_DEPTH, &o.depth, &err)) goto fail;
    } else if (strcmp(a, "--split") == 0) {
      if (zs_cli_int_value(argc, argv, &i, 0, 1000000, &o.split, &err)) goto fail;
    } else if (strcmp(a, "--looseness") == 0) {
      if (zs_cli_value(argc, argv, &i, &v, &err) || zs_cli_double(a, v, &o.looseness, &err))
        goto fail;
      if (!(o.looseness > 1.0 && o.looseness <= ZS_OCTREE_MAX_LOOSENESS)) {
        zs_error_set(&err, ZS_ERR_ARG, "--looseness: %s is outside (1, %g]", v,
                     ZS_OCTREE_MAX_LOOSENESS);
        goto fail;
      }
    } else {
      zs_error_set(&err, ZS_ERR_ARG, "unknown option '%s'", a);
      goto fail;
    }
  }
  if (o.csv && zs_cli_output_path("--csv", o.csv, &err)) goto fail;
  if (o.plot && zs_cli_output_path("--plot", o.plot, &err)) goto fail;
  FILE *report;
  const char *outs[] = {o.csv, o.plot};
  if (zs_out_report(outs, 2, "--csv and --plot", &report, &err)) goto fail;
  parsing = 0;
  if (o.plot && !zs_plot_available()) {
    zs_error_set(&err, ZS_ERR_UNSUPPORTED,
                 "--plot: gnuplot is not installed (apt-get install gnuplot-nox)");
    goto fail;
  }

  fprintf(report, "octree update, %d spheres (spheres?count=%d&seed=1), depth %d, looseness %g, "
         "split %d, median of %d frames\n",
         o.count, o.count, o.depth, o.looseness, o.split, o.frames);
  fprintf(report, "%6s %9s %9s %8s %8s %10s %10s %8s %8s %7s\n", "moving", "loose_ms", "plain_ms",
         "loose_us", "plain_us", "loose_node", "plain_node", "l_scan", "p_scan", "same%");
  fprintf(report, "%6s %9s %9s %8s %8s %10s %10s %8s %8s %7s\n", "", "/frame", "/frame", "/object",
         "/object", "s/frame", "s/frame", "/frame", "/frame", "cell");
  for (int j = 0; j < STEPS; j++) {
    if (run_one(&o, o.count * (j + 1) / STEPS, &rows[j], &err)) goto fail;
    print_row(report, &rows[j], o.frames);
  }
  print_shape(report, &rows[STEPS - 1], &o);
  if (o.csv) {
    if (write_csv(o.csv, rows, STEPS, o.frames, &err)) {
      zs_out_error_option(&err, "--csv");
      goto fail;
    }
    if (!zs_out_is_stdout(o.csv)) fprintf(report, "wrote %s\n", o.csv);
  }
  if (o.plot) {
    if (write_plot(o.plot, rows, STEPS, &o, &err)) {
      zs_out_error_option(&err, "--plot");
      goto fail;
    }
    if (!zs_out_is_stdout(o.plot)) fprintf(report, "wrote %s\n", o.plot);
  }
  return 0;
fail:
  return zs_cli_fail("zscan bench octree", &err, parsing);
}
