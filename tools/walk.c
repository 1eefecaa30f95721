/* `zscan walk SCENE --cull M1,M2,... [options]`: every culling method over
 * the scene's camera path, with its moving objects, frame by frame.
 *
 * The methods run in lockstep: each frame the scene moves once, the octree
 * is brought up to date once, and then every method draws that frame on a
 * device of its own (each keeps its culler's state from frame to frame).
 * Each method's face ids are compared with those of `none` in the same
 * frame: diff_pixels.  The modelled times come from the device clock and
 * are the same on every run; wall times are measured and are not.
 */
#include "tools/commands.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cull/cull.h"
#include "cull/octree.h"
#include "raster/exactmath.h"
#include "raster/raster.h"
#include "scene/paths.h"
#include "scene/scene.h"
#include "tools/cli.h"
#include "tools/clockfile.h"
#include "tools/costset.h"
#include "lib/frame.h"
#include "lib/image.h"
#include "lib/input.h"
#include "lib/outfile.h"
#include "tools/plot.h"

static const char usage[] =
    "usage: zscan walk SCENE --cull M1,M2,... [options]\n"
    "  SCENE               FILE.json, FILE.obj, or builtin:NAME[,k=v]\n"
    "  --cull LIST         methods, comma-separated; none runs too, as the\n"
    "                      reference (unless --reference off).  The methods:\n"
    "                      " ZS_CULL_METHOD_LIST "\n"
    "  --frames N          frames of the walk (default: the scene's path)\n"
    "  --reference none|off  none (default): also draw everything, and count each\n"
    "                      method's pixels that differ from it; off: neither (faster;\n"
    "                      diff_pixels shows -)\n"
    "  --named PATH        walk a named camera path instead of the scene's: static,\n"
    "                      translate, roll, yaw or fast (as zscan path); any model\n"
    "                      file can be walked so (default: 100 frames)\n"
    "  --step K            every K-th frame of the path (objects move K steps;\n"
    "                      default 1)\n"
    "  --size WxH          image size (default: the scene's, else 1024x768)\n"
    "  --csv FILE          one row per frame and method\n"
    "  --plot FILE.png     modelled frame time per frame, one line per method\n"
    "  --frames-dir DIR    each method's image of every frame, METHOD-FRAME.png\n"
    "  --shade flat|id     those images shaded (default flat) or by face id + 1\n"
    "  --clock FILE.json   the device clock's constants (default: the modelled ones)\n"
    "  --clock-set K=V     set one clock constant, ns\n"
    "  --cost-set K=V      set one parameter of the cost model (chc-prob, auto,\n"
    "                      chcpp-prob): w1, w2, ttri_ns, tcall_ns, t_ns, tq_ns, rho,\n"
    "                      learn (learn=K: w1 and w2 learnt from the method's query\n"
    "                      outcomes, starting from the given ones as K outcomes; auto\n"
    "                      always learns them), measure (1, the default: an object's\n"
    "                      P(V) from what its draw wrote; 0: from the prediction)\n"
    "  --latency-frames X  query latency as X times none's first frame (default: the\n"
    "                      clock's query_latency_ns)\n"
    "  --depth D --looseness K   the loose octree (default 4, 2; a scene of at most 16\n"
    "                      objects gets none: its root lists them)\n"
    "  --bounds parts|box  what queries ask about an object: the union of its\n"
    "                      parts' boxes (default), or its box\n"
    "  --algos LIST        also draw everything in these hidden-surface modes,\n"
    "                      scanline and/or depthsort, against none (zbuffer)\n"
    "  --tradeoff FILE.png time against pixels wrong, one point per method and mode\n"
    "  --md FILE           the table of means per frame in Markdown\n"
    "  --quiet             no progress on stderr (else a bar on a terminal, a line\n"
    "                      every 5 s in a log)\n"    "columns (the table, --md and --csv alike; means a frame, diff_pixels over all):\n"
    "  queries             occlusion queries issued (a multiquery counts once)\n"
    "  faces_drawn         polygons the draws submitted; objects_drawn: objects\n"
    "  modelled_ms         the frame on the device clock (the later of GPU and CPU);\n"
    "                      x_ideal: over the ideal's; modelled_fps: 1000 / it\n"
    "  stall_ms            the CPU waiting for query latency\n"
    "  wall_ms             the machine's time for the method's frame\n"
    "  diff_pixels         pixels whose visible face differs from none's\n"
    "With ideal: a column of each method's time over the ideal's.  With ideal-box:\n"
    "how its set changes from frame to frame, and the least that change costs a\n"
    "method that learns from the last frame (cull/churn.h).\n";

typedef struct walk_opts {
  const char *scene, *csv, *plot, *frames_dir, *tradeoff, *md;
  const char *named; /* --named: a camera path of zscan path's, not the scene's */
  FILE *report; /* the summary's stream: stdout, or stderr when an output is "-" */
  zs_shade frames_shade; /* --frames-dir's pictures: flat, or id */
  int no_reference;      /* --reference off: none is not run, no pixel compared */
  zs_algo algos[2];
  int nalgos;
  int methods[ZS_CULL_METHODS], nmethods;
  int frames, width, height, quiet, depth, step;
  double looseness, latency_frames;
  zs_clock_params clock;
  zs_cost_params cost;
  zs_query_bounds bounds;
} walk_opts;

/* Per method, the sums over the walk. */
typedef struct method_run {
  zs_cull_method m;
  zs_culler *culler;
  zs_device *dev;
  double modelled_ms, stall_ms, wall_ms, queries, faces, objects, nodes;
  double gpu_ms[4];       /* the GPU's split: draw, query, switch, idle */
  uint64_t diff_pixels, frames_with_diff;
  uint64_t chose_queries; /* auto: frames it ran with queries */
  /* ideal-box: its set against the last frame's, summed over frames */
  double set_size, entered, entered_outside, left, left_outside, known_ms, ranked_ms;
} method_run;

static zs_status parse(int argc, char **argv, walk_opts *o, zs_error *err) {
  memset(o, 0, sizeof *o);
  o->depth = ZS_OCTREE_DEFAULT_DEPTH;
  o->looseness = ZS_OCTREE_DEFAULT_LOOSENESS;
  o->latency_frames = -1;
  o->step = 1;
  zs_clock_params_default(&o->clock);
  zs_cost_params_default(&o->cost);
  o->methods[o->nmethods++] = ZS_CULL_NONE; /* the reference, unless --reference off */
  int have_cull = 0, none_listed = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = NULL;
#define VALUE() \
  if (zs_cli_value(argc, argv, &i, &v, err)) return err->code
    if (strcmp(a, "--cull") == 0) {
      VALUE();
      have_cull = 1;
      char buf[256];
      snprintf(buf, sizeof buf, "%s", v);
      for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        int m = zs_cull_method_parse(tok);
        none_listed |= m == ZS_CULL_NONE;
        if (m < 0)
          return zs_error_set(err, ZS_ERR_ARG,
                              "--cull: unknown method '%s' (" ZS_CULL_METHOD_LIST ")", tok);
        int dup = 0;
        for (int k = 0; k < o->nmethods; k++) dup |= o->methods[k] == m;
        if (!dup) o->methods[o->nmethods++] = m;
      }
    } else if (strcmp(a, "--frames") == 0) {
      VALUE();
      if (zs_cli_int(a, v, 1, 1000000, &o->frames, err)) return err->code;
    } else if (strcmp(a, "--algos") == 0) {
      VALUE();
      char buf[64];
      snprintf(buf, sizeof buf, "%s", v);
      for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        int al = zs_algo_parse(tok);
        if (al < 0 || al == ZS_ALGO_ZBUFFER) /* zbuffer is the reference, none */
          return zs_error_set(err, ZS_ERR_ARG, "--algos: expected scanline or depthsort, got '%s'", tok);
        int dup = 0;
        for (int k = 0; k < o->nalgos; k++) dup |= (int)o->algos[k] == al;
        if (!dup) o->algos[o->nalgos++] = (zs_algo)al;
      }
    } else if (strcmp(a, "--md") == 0) {
      if (zs_cli_output_value(argc, argv, &i, &o->md, err)) return err->code;
    } else if (strcmp(a, "--tradeoff") == 0) {
      if (zs_cli_output_value(argc, argv, &i, &o->tradeoff, err)) return err->code;
    } else if (strcmp(a, "--bounds") == 0) {
      VALUE();
      int b = zs_query_bounds_parse(v);
      if (b < 0) return zs_error_set(err, ZS_ERR_ARG, "--bounds: expected parts or box, got '%s'", v);
      o->bounds = (zs_query_bounds)b;
    } else if (strcmp(a, "--step") == 0) {
      VALUE();
      if (zs_cli_int(a, v, 1, 10000, &o->step, err)) return err->code;
    } else if (strcmp(a, "--size") == 0) {
      VALUE();
      if (zs_cli_size(a, v, ZS_MAX_IMAGE_SIDE, &o->width, &o->height, err)) return err->code;
    } else if (strcmp(a, "--csv") == 0) {
      if (zs_cli_output_value(argc, argv, &i, &o->csv, err)) return err->code;
    } else if (strcmp(a, "--plot") == 0) {
      if (zs_cli_output_value(argc, argv, &i, &o->plot, err)) return err->code;
    } else if (strcmp(a, "--frames-dir") == 0) {
      VALUE();
      o->frames_dir = v; /* created (with its parents) when the walk starts */
    } else if (strcmp(a, "--clock") == 0) {
      VALUE();
      if (zs_clockfile_load(v, &o->clock, err)) return err->code;
    } else if (strcmp(a, "--clock-set") == 0) {
      VALUE();
      if (zs_clock_set(v, &o->clock, err)) return err->code;
    } else if (strcmp(a, "--cost-set") == 0) {
      VALUE();
      if (zs_cost_set(v, &o->cost, err)) return err->code;
    } else if (strcmp(a, "--latency-frames") == 0) {
      VALUE();
      if (zs_cli_double(a, v, &o->latency_frames, err)) return err->code;
      if (o->latency_frames < 0 || o->latency_frames > 100)
        return zs_error_set(err, ZS_ERR_ARG, "--latency-frames: expected 0 to 100, got %s", v);
    } else if (strcmp(a, "--depth") == 0) {
      VALUE();
      if (zs_cli_int(a, v, 0, ZS_OCTREE_MAX_DEPTH, &o->depth, err)) return err->code;
    } else if (strcmp(a, "--looseness") == 0) {
      VALUE();
      if (zs_cli_double(a, v, &o->looseness, err)) return err->code;
    } else if (strcmp(a, "--quiet") == 0) {
      o->quiet = 1;
    } else if (strcmp(a, "--shade") == 0) {
      VALUE();
      if (strcmp(v, "flat") != 0 && strcmp(v, "id") != 0)
        return zs_error_set(err, ZS_ERR_ARG, "--shade: expected flat or id, got '%s'", v);
      o->frames_shade = v[0] == 'f' ? ZS_SHADE_FLAT : ZS_SHADE_ID;
    } else if (strcmp(a, "--reference") == 0) {
      VALUE();
      if (strcmp(v, "none") != 0 && strcmp(v, "off") != 0)
        return zs_error_set(err, ZS_ERR_ARG, "--reference: expected none or off, got '%s'", v);
      o->no_reference = strcmp(v, "off") == 0;
    } else if (strcmp(a, "--named") == 0) {
      VALUE();
      o->named = v;
      char names[128]; /* zs_path_names: "static, translate, ..." */
      snprintf(names, sizeof names, "%s", zs_path_names);
      int known = 0;
      for (char *t = strtok(names, ", "); t; t = strtok(NULL, ", ")) known |= strcmp(t, v) == 0;
      if (!known)
        return zs_error_set(err, ZS_ERR_ARG, "--named: expected %s, got '%s'", zs_path_names, v);
    } else if (a[0] == '-' && a[1]) {
      return zs_error_set(err, ZS_ERR_ARG, "unknown option '%s' (see zscan walk --help)", a);
    } else if (!o->scene) {
      o->scene = a;
    } else {
      return zs_error_set(err, ZS_ERR_ARG, "more than one SCENE: '%s' and '%s'", o->scene, a);
    }
#undef VALUE
  }
  if (!o->scene) return zs_error_set(err, ZS_ERR_ARG, "missing SCENE (see zscan walk --help)");
  if (!have_cull) return zs_error_set(err, ZS_ERR_ARG, "missing --cull (see zscan walk --help)");
  if (o->no_reference) {
    if (o->latency_frames >= 0 || o->nalgos || o->tradeoff)
      return zs_error_set(err, ZS_ERR_ARG, "--reference off: --latency-frames, --algos and "
                                           "--tradeoff measure against none");
    if (!none_listed) { /* none stays when --cull names it */
      memmove(o->methods, o->methods + 1, (size_t)(o->nmethods - 1) * sizeof o->methods[0]);
      o->nmethods--;
    }
    if (o->nmethods == 0)
      return zs_error_set(err, ZS_ERR_ARG, "--reference off: --cull names no method to run");
  }
  if (o->frames_dir && zs_out_dir("--frames-dir", o->frames_dir, err)) return err->code;
  /* Standard output carries one stream: the summary, or the one output
   * named "-" (the summary then goes to standard error). */
  const char *streams[] = {o->csv, o->md, o->plot, o->tradeoff};
  return zs_out_report(streams, 4, "--csv, --md, --plot and --tradeoff", &o->report, err);
}

/* A method's frame as the device finished it: the rows into an image. */
static void keep_rows(void *user, const zs_row *row) {
  zs_image *im = user;
  memcpy(im->rgb + (size_t)row->y * (size_t)row->width, row->rgb,
         (size_t)row->width * sizeof *row->rgb);
}

static zs_status write_frame(const walk_opts *o, const method_run *r, const zs_image *im, int f,
                             zs_error *err) {
  char path[4200];
  snprintf(path, sizeof path, "%s/%s-%05d.png", o->frames_dir, zs_cull_method_name(r->m), f);
  zs_status st = zs_png_write_shaded(path, im, o->frames_shade, err);
  return st ? zs_out_error_option(err, "--frames-dir") : ZS_OK;
}

/* The GPU's split of the device's frame, in ms: draw, query, switch, idle
 * (the last four columns of the CSV). */
static void gpu_split_ms(const zs_device *d, double ms[4]) {
  const zs_gpu_split g = zs_clock_gpu_split(d);
  ms[0] = g.draw_ps * 1e-9;
  ms[1] = g.query_ps * 1e-9;
  ms[2] = g.switch_ps * 1e-9;
  ms[3] = g.idle_ps * 1e-9;
}

/* A hidden-surface mode drawing everything (--algos), against none. */
typedef struct algo_run {
  zs_algo a;
  zs_device *dev;
  double modelled_ms, wall_ms, faces;
  uint64_t diff_pixels;
} algo_run;

/* The rows of a mode that keeps no full-frame buffers, as they come. */
static void keep_ids(void *user, const zs_row *row) {
  uint32_t *ids = user;
  memcpy(ids + (size_t)row->y * (size_t)row->width, row->id, (size_t)row->width * sizeof *row->id);
}

/* Time against pixels wrong, one labelled point per row: wall (median)
 * and modelled ms per frame against the mean pixels wrong per frame. */
/* Labels "name value" for the points (x[i], v[i]) of a log-y panel whose
 * y range is [ylo, yhi]: points sorted by height, each label raised until
 * it clears the one below it in the same column (x within 15 % of the
 * range), so labels keep the points' order and carry their values.
 * gnuplot places text where it is told, so close points (several exact
 * methods at zero error) would otherwise print over each other. */
static void add_labels(char *script, size_t cap, size_t *len, const char *const *names,
                       const double *x, const double *v, int n, double xspan, double ylo,
                       double yhi) {
  int order[ZS_CULL_METHODS + 2];
  double lab[ZS_CULL_METHODS + 2];
  for (int i = 0; i < n; i++) order[i] = i;
  for (int i = 1; i < n; i++) /* insertion sort by height, then name order */
    for (int j = i; j > 0 && v[order[j]] < v[order[j - 1]]; j--) {
      int t = order[j];
      order[j] = order[j - 1];
      order[j - 1] = t;
    }
  const double gap = 0.05 * (zs_log10(yhi) - zs_log10(ylo));
  for (int a = 0; a < n; a++) {
    int i = order[a];
    double l = zs_log10(v[i] > 0 ? v[i] : ylo);
    for (int b = 0; b < a; b++) {
      int j = order[b];
      if (fabs(x[j] - x[i]) < 0.15 * xspan && l < lab[j] + gap) l = lab[j] + gap;
    }
    lab[i] = l;
  }
  for (int i = 0; i < n; i++)
    *len += (size_t)snprintf(script + *len, *len < cap ? cap - *len : 0,
                             "set label %d \"%s  %.3g\" at %.6g,%.6g offset 1.2,0 left font ',9'\n",
                             i + 1, names[i], v[i], x[i], zs_exp10(lab[i]));
}

static zs_status write_tradeoff(const char *path, const char *scene, const char *const *names,
                                const double *wall, const double *model, const double *wrong,
                                int n, zs_error *err) {
  char script[16384];
  size_t len = 0;
#define ADD(...) len += (size_t)snprintf(script + len, len < sizeof script ? sizeof script - len : 0, __VA_ARGS__)
  ADD("$data << EOD\n");
  for (int i = 0; i < n; i++) ADD("\"%s\" %.3f %.6f %.6f\n", names[i], wrong[i], wall[i], model[i]);
  ADD("EOD\nset terminal pngcairo size 1200,560 font 'sans,11'\nset output OUT\n");
  ADD("set multiplot layout 1,2 title '%s: run time against error (one point per method)'\n",
      scene);
  double xmax = 1.0;
  for (int i = 0; i < n; i++) xmax = wrong[i] > xmax ? wrong[i] : xmax;
  const double xlo = -0.05 * xmax, xhi = 1.4 * xmax;
  ADD("set grid\nset key off\nset xlabel 'pixels wrong per frame (against none)'\n"
      "set xrange [%.3f:%.3f]\nset format x '%%.0s%%c'\nset logscale y\n", xlo, xhi);
  for (int panel = 0; panel < 2; panel++) {
    const double *v = panel ? model : wall;
    double lo = v[0], hi = v[0];
    for (int i = 0; i < n; i++) {
      lo = v[i] > 0 && v[i] < lo ? v[i] : lo;
      hi = v[i] > hi ? v[i] : hi;
    }
    if (!(lo > 0)) lo = 1e-3;
    lo /= 1.5;
    hi *= 2.5; /* room above for raised labels */
    ADD("unset label\nset yrange [%.6g:%.6g]\n", lo, hi);
    add_labels(script, sizeof script, &len, names, wrong, v, n, xhi - xlo, lo, hi);
    ADD("set ylabel '%s ms per frame'\nplot $data using 2:%d with points pt 7 ps 1.2\n",
        panel ? "modelled" : "median wall", panel ? 4 : 3);
  }
  ADD("unset multiplot\n");
#undef ADD
  if (len >= sizeof script) return zs_error_set(err, ZS_ERR_ARG, "tradeoff plot: too many points");
  return zs_plot_run(path, script, err);
}

/* One line of the summary: a method's or a mode's means per frame. */
typedef struct summary_row {
  const char *name;
  double queries, faces, objects, modelled_ms, stall_ms, wall_ms;
  uint64_t diff_pixels; /* over all frames */
} summary_row;

/* ideal_ms > 0: the ideal ran, and a column gives each row's modelled
 * time over the ideal's.  The columns have the CSV's names in the table
 * and in Markdown alike: means per frame, but diff_pixels over all
 * frames. */
static void write_summary(FILE *f, int md, const summary_row *rows, int n, double ideal_ms,
                          int has_reference) {
  const int x = ideal_ms > 0;
  if (md)
    fprintf(f, "| method | queries | faces_drawn | objects_drawn | modelled_ms | %s"
               "modelled_fps | stall_ms | wall_ms | diff_pixels |\n"
               "|---|---|---|---|---|%s---|---|---|---|\n",
            x ? "x_ideal | " : "", x ? "---|" : "");
  else
    fprintf(f, "%-13s %9s %12s %13s %11s %s%12s %9s %9s %11s\n", "method", "queries",
            "faces_drawn", "objects_drawn", "modelled_ms", x ? "  x_ideal " : "", "modelled_fps",
            "stall_ms", "wall_ms", "diff_pixels");
  for (int k = 0; k < n; k++) {
    const summary_row *r = &rows[k];
    double fps = r->modelled_ms > 0 ? 1000.0 / r->modelled_ms : 0.0;
    char ratio[32] = "";
    if (x) snprintf(ratio, sizeof ratio, md ? "%.3f | " : "%9.3f ", r->modelled_ms / ideal_ms);
    char diff[32] = "-"; /* no reference, no comparison */
    if (has_reference) snprintf(diff, sizeof diff, "%llu", (unsigned long long)r->diff_pixels);
    fprintf(f,
            md ? "| %s | %.1f | %.0f | %.1f | %.3f | %s%.1f | %.3f | %.3f | %s |\n"
               : "%-13s %9.1f %12.0f %13.1f %11.3f %s%12.1f %9.3f %9.3f %11s\n",
            r->name, r->queries, r->faces, r->objects, r->modelled_ms, ratio, fps, r->stall_ms,
            r->wall_ms, diff);
  }
}

static zs_status run(const walk_opts *o, zs_error *err) {
  zs_scene s;
  if (zs_input_load_scene(o->scene, &s, err)) return err->code;
  zs_status st = ZS_OK;
  zs_octree tree;
  memset(&tree, 0, sizeof tree);
  method_run runs[ZS_CULL_METHODS];
  memset(runs, 0, sizeof runs);
  FILE *csv = NULL; /* csv_out.fp while the CSV is open */
  zs_out csv_out;
  uint32_t *ref_ids = NULL, *algo_ids = NULL;
  zs_image frame_image = {0, 0, NULL}; /* a method's frame, for --frames-dir */
  double *frame_ms = NULL; /* per frame and method, for the plot */
  double *frame_wall = NULL; /* per row (methods, then modes) and frame: the medians */
  algo_run algos[2];
  memset(algos, 0, sizeof algos);
  const int nrows = o->nmethods + o->nalgos;

  int w = o->width ? o->width : s.width ? s.width : 1024;
  int h = o->height ? o->height : s.height ? s.height : 768;
  if (o->named && (st = zs_frame_named_path(&s, o->named, o->frames ? o->frames : 100, w, h, err)))
    goto done;
  int frames = o->frames ? o->frames
               : s.path.frames > 0 ? (s.path.frames + o->step - 1) / o->step : 1;

  zs_octree_params tp;
  zs_octree_params_default(&tp, ZS_OCTREE_LOOSE);
  tp.max_depth = o->depth;
  tp.looseness = o->looseness;
  if ((st = zs_octree_build(&tree, &s, &tp, err))) goto done;

  zs_clock_params clock = o->clock;
  for (int k = 0; k < o->nmethods; k++) {
    method_run *r = &runs[k];
    r->m = (zs_cull_method)o->methods[k];
    /* id shading, which the comparisons read; flat when --frames-dir shows
     * the frames shaded (the ids are kept either way, the clock the same) */
    zs_shade shade = o->frames_dir ? o->frames_shade : ZS_SHADE_ID;
    zs_device_config cfg = {w, h, ZS_ALGO_ZBUFFER, shade, 0, 1, ZS_BACKGROUND_RGB, 0};
    if ((st = zs_device_create(&cfg, &r->dev, err))) goto done;
    if ((st = zs_culler_create(r->m, &o->cost, &r->culler, err)) ||
        (st = zs_culler_set_bounds(r->culler, o->bounds, err)))
      goto done;
    if ((st = zs_device_set_clock(r->dev, &clock, err))) goto done;
  }
  if (o->latency_frames >= 0) {
    /* latency in frames: of none's modelled time of the first frame */
    double view[16], proj[16];
    zs_cull_stats cs;
    if ((st = zs_frame_path_camera(&s, 0, w, h, view, proj, err)) ||
        (st = zs_culler_frame(runs[0].culler, runs[0].dev, &s, &tree, view, proj, &cs, err)) ||
        (st = zs_device_finish(runs[0].dev, NULL, NULL, err)))
      goto done;
    clock.query_latency_ns = o->latency_frames * (double)zs_device_frame_ps(runs[0].dev) * 1e-3;
    for (int k = 0; k < o->nmethods; k++)
      if ((st = zs_device_set_clock(runs[k].dev, &clock, err))) goto done;
    fprintf(o->report, "query latency: %.3f ms (%.2f frames of none)\n", clock.query_latency_ns * 1e-6,
           o->latency_frames);
  }
  for (int k = 0; k < o->nalgos; k++) {
    zs_device_config cfg = {w, h, o->algos[k], ZS_SHADE_ID, 0, 1, 0, 0};
    algos[k].a = o->algos[k];
    if ((st = zs_device_create(&cfg, &algos[k].dev, err)) ||
        (st = zs_device_set_clock(algos[k].dev, &clock, err)))
      goto done;
  }
  if (o->frames_dir && (st = zs_image_alloc(&frame_image, w, h, err))) goto done;
  if (!(ref_ids = malloc((size_t)w * (size_t)h * sizeof *ref_ids)) ||
      !(algo_ids = malloc((size_t)w * (size_t)h * sizeof *algo_ids)) ||
      !(frame_wall = calloc((size_t)frames * (size_t)nrows, sizeof *frame_wall)) ||
      !(frame_ms = calloc((size_t)frames * (size_t)o->nmethods, sizeof *frame_ms))) {
    st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
    goto done;
  }
  if (o->csv) {
    if ((st = zs_out_open(&csv_out, o->csv, err))) {
      zs_out_error_option(err, "--csv");
      goto done;
    }
    csv = csv_out.fp;
    fprintf(csv, "frame,method,chosen,modelled_ms,stall_ms,wall_ms,queries,queries_hidden,"
                 "faces_drawn,objects_drawn,nodes_visited,diff_pixels,"
                 "gpu_draw_ms,gpu_query_ms,gpu_switch_ms,gpu_idle_ms\n");
  }

  zs_progress progress;
  zs_progress_start(&progress, "walk", "frame", frames, o->quiet);
  for (int f = 0; f < frames && st == ZS_OK; f++) {
    if (f > 0) {
      for (int k = 0; k < o->step; k++) zs_scene_advance(&s);
      if ((st = zs_octree_update(&tree, &s, NULL, err))) break;
    }
    double view[16], proj[16];
    if ((st = zs_frame_path_camera(&s, f * o->step, w, h, view, proj, err))) break;
    for (int k = 0; k < o->nmethods && st == ZS_OK; k++) {
      method_run *r = &runs[k];
      zs_cull_stats cs;
      double t0 = zs_wall_ms();
      if ((st = zs_culler_frame(r->culler, r->dev, &s, &tree, view, proj, &cs, err))) break;
      if ((st = zs_device_finish(r->dev, o->frames_dir ? keep_rows : NULL, &frame_image, err)))
        break;
      double wall = zs_wall_ms() - t0;
      const zs_clock_stats *ck = zs_device_clock(r->dev);
      double modelled = zs_device_frame_ps(r->dev) * 1e-9, stall = ck->stall_ps * 1e-9;
      double split[4];
      gpu_split_ms(r->dev, split);
      for (int i = 0; i < 4; i++) r->gpu_ms[i] += split[i];
      const uint32_t *ids = zs_device_id_buffer(r->dev);
      uint64_t diff = 0;
      if (o->no_reference) {
        /* nothing to compare with */
      } else if (k == 0) {
        memcpy(ref_ids, ids, (size_t)w * (size_t)h * sizeof *ids);
      } else {
        for (size_t i = 0; i < (size_t)w * (size_t)h; i++) diff += ids[i] != ref_ids[i];
      }
      r->modelled_ms += modelled;
      r->stall_ms += stall;
      r->wall_ms += wall;
      r->queries += (double)cs.queries;
      r->faces += (double)cs.faces_drawn;
      r->objects += (double)cs.objects_drawn;
      r->nodes += (double)cs.nodes_visited;
      r->diff_pixels += diff;
      r->frames_with_diff += diff > 0;
      r->chose_queries += cs.chosen == ZS_CULL_CHC_PROB;
      if (f > 0) { /* the churn compares with the frame before */
        r->set_size += (double)cs.objects_drawn;
        r->entered += (double)cs.set_entered;
        r->entered_outside += (double)cs.set_entered_outside;
        r->left += (double)cs.set_left;
        r->left_outside += (double)cs.set_left_outside;
        r->known_ms += cs.churn_known_ps * 1e-9;
        r->ranked_ms += cs.churn_ranked_ps * 1e-9;
      }
      frame_ms[(size_t)f * (size_t)o->nmethods + (size_t)k] = modelled;
      frame_wall[(size_t)k * (size_t)frames + (size_t)f] = wall;
      if (csv) {
        char diff_text[32] = ""; /* empty without a reference */
        if (!o->no_reference) snprintf(diff_text, sizeof diff_text, "%llu", (unsigned long long)diff);
        fprintf(csv, "%d,%s,%s,%.6f,%.6f,%.3f,%llu,%llu,%llu,%llu,%llu,%s,%.6f,%.6f,%.6f,%.6f\n",
                f * o->step, zs_cull_method_name(r->m), zs_cull_method_name(cs.chosen), modelled,
                stall, wall, (unsigned long long)cs.queries,
                (unsigned long long)cs.queries_hidden, (unsigned long long)cs.faces_drawn,
                (unsigned long long)cs.objects_drawn, (unsigned long long)cs.nodes_visited,
                diff_text, split[0], split[1], split[2], split[3]);
      }
      if (o->frames_dir && (st = write_frame(o, r, &frame_image, f, err))) break;
    }
    for (int k = 0; k < o->nalgos && st == ZS_OK; k++) { /* everything, in another mode */
      algo_run *r = &algos[k];
      double t0 = zs_wall_ms();
      zs_device_clear(r->dev);
      zs_device_set_camera(r->dev, view, proj);
      if ((st = zs_frame_draw_scene(r->dev, &s, err)) ||
          (st = zs_device_finish(r->dev, keep_ids, algo_ids, err)))
        break;
      double wall = zs_wall_ms() - t0, modelled = zs_device_frame_ps(r->dev) * 1e-9;
      uint64_t diff = 0;
      for (size_t i = 0; i < (size_t)w * (size_t)h; i++) diff += algo_ids[i] != ref_ids[i];
      /* every face, counted as the methods count theirs: as drawn, after
       * the split of non-planar ones */
      uint64_t faces = zs_device_stats(r->dev)->polygons_in;
      r->faces += (double)faces;
      r->modelled_ms += modelled;
      r->wall_ms += wall;
      r->diff_pixels += diff;
      frame_wall[(size_t)(o->nmethods + k) * (size_t)frames + (size_t)f] = wall;
      if (csv) {
        double split[4];
        gpu_split_ms(r->dev, split);
        fprintf(csv, "%d,%s,-,%.6f,0,%.3f,0,0,%llu,%d,0,%llu,%.6f,%.6f,%.6f,%.6f\n", f * o->step,
                zs_algo_name(r->a), modelled, wall, (unsigned long long)faces, (int)s.ninst,
                (unsigned long long)diff, split[0], split[1], split[2], split[3]);
      }
    }
    zs_progress_step(&progress, f + 1);
  }
  if (st) goto done;
  if (csv) {
    csv = NULL; /* committed or removed, either way */
    if ((st = zs_out_commit(&csv_out, err))) {
      zs_out_error_option(err, "--csv");
      goto done;
    }
  }

  /* The paper's Table 2, per frame on average. */
  summary_row rows[ZS_CULL_METHODS + 2];
  for (int k = 0; k < o->nmethods; k++) {
    const method_run *r = &runs[k];
    rows[k] = (summary_row){zs_cull_method_name(r->m), r->queries / frames, r->faces / frames,
                            r->objects / frames, r->modelled_ms / frames, r->stall_ms / frames,
                            r->wall_ms / frames, r->diff_pixels};
  }
  for (int k = 0; k < o->nalgos; k++) {
    const algo_run *r = &algos[k];
    rows[o->nmethods + k] = (summary_row){zs_algo_name(r->a), 0.0, r->faces / frames,
                                          (double)s.ninst, r->modelled_ms / frames, 0.0,
                                          r->wall_ms / frames, r->diff_pixels};
  }
  double ideal_ms = 0.0; /* the ideal's modelled ms a frame, when it ran */
  for (int k = 0; k < o->nmethods; k++)
    if (runs[k].m == ZS_CULL_IDEAL) ideal_ms = runs[k].modelled_ms / frames;
  fprintf(o->report, "%s: %d frames at %dx%d, %d objects, %llu faces\n", o->scene, frames, w, h, (int)s.ninst,
         (unsigned long long)zs_scene_faces(&s));
  write_summary(o->report, 0, rows, nrows, ideal_ms, !o->no_reference);
  /* Where each method's modelled frame goes on the GPU: a method that
   * draws less but leaves the GPU idle, or pays in queries and switches,
   * shows it here. */
  fprintf(o->report, "\nthe GPU's share of the modelled frame, ms a frame\n%-13s %9s %9s %9s %9s\n", "method",
         "draw", "query", "switch", "idle");
  for (int k = 0; k < o->nmethods; k++)
    fprintf(o->report, "%-13s %9.3f %9.3f %9.3f %9.3f\n", zs_cull_method_name(runs[k].m),
           runs[k].gpu_ms[0] / frames, runs[k].gpu_ms[1] / frames, runs[k].gpu_ms[2] / frames,
           runs[k].gpu_ms[3] / frames);
  for (int k = 0; k < o->nmethods && frames > 1; k++) {
    const method_run *r = &runs[k];
    if (r->m != ZS_CULL_IDEAL_BOX) continue;
    /* What carrying visibility over from the last frame must cost at the
     * least a method that finds each change with a query (cull/churn.h) */
    const double n = frames - 1;
    fprintf(o->report, "\nideal-box's set against the frame before, objects a frame (frames 2 to %d)\n"
           "  in the set %.1f; entered %.1f (%.1f from outside the frustum); "
           "left %.1f (%.1f to outside the frustum)\n"
           "the least a method that learns from the last frame pays for it over ideal-box, "
           "ms a frame\n"
           "  a query's call for each change, asking nowhere else: %.3f\n"
           "  asking the last frame's set fewest pixels first, the best cut-off each frame: %.3f\n",
           frames, r->set_size / n, r->entered / n, r->entered_outside / n, r->left / n,
           r->left_outside / n, r->known_ms / n, r->ranked_ms / n);
  }
  if (o->md) {
    zs_out md;
    if (!(st = zs_out_open(&md, o->md, err))) {
      write_summary(md.fp, 1, rows, nrows, ideal_ms, !o->no_reference);
      st = zs_out_commit(&md, err);
    }
    if (st) {
      zs_out_error_option(err, "--md");
      goto done;
    }
  }
  if (o->tradeoff) {
    const char *names[ZS_CULL_METHODS + 2];
    double wall[ZS_CULL_METHODS + 2], model[ZS_CULL_METHODS + 2], wrong[ZS_CULL_METHODS + 2];
    for (int k = 0; k < nrows; k++) {
      int alg = k >= o->nmethods;
      names[k] = alg ? zs_algo_name(algos[k - o->nmethods].a) : zs_cull_method_name(runs[k].m);
      wall[k] = zs_median(frame_wall + (size_t)k * (size_t)frames, frames);
      model[k] = (alg ? algos[k - o->nmethods].modelled_ms : runs[k].modelled_ms) / frames;
      wrong[k] = (double)(alg ? algos[k - o->nmethods].diff_pixels : runs[k].diff_pixels) / frames;
    }
    if ((st = write_tradeoff(o->tradeoff, o->scene, names, wall, model, wrong, nrows, err))) {
      zs_out_error_option(err, "--tradeoff");
      goto done;
    }
  }
  if (o->plot) {
    const char *names[ZS_CULL_METHODS];
    for (int k = 0; k < o->nmethods; k++) names[k] = zs_cull_method_name(runs[k].m);
    char title[512];
    snprintf(title, sizeof title, "%s: modelled frame time (log scale)", o->scene);
    if ((st = zs_plot_series(o->plot, title, "frame of the path", "modelled ms", frame_ms,
                             frames, o->nmethods, names, 0, o->step, 1, err)))
      zs_out_error_option(err, "--plot");
  }

done:
  if (csv) zs_out_discard(&csv_out);
  zs_image_free(&frame_image);
  free(ref_ids);
  free(algo_ids);
  free(frame_ms);
  free(frame_wall);
  for (int k = 0; k < 2; k++) zs_device_destroy(algos[k].dev);
  for (int k = 0; k < ZS_CULL_METHODS; k++) {
    zs_culler_destroy(runs[k].culler);
    zs_device_destroy(runs[k].dev);
  }
  zs_octree_free(&tree);
  zs_scene_free(&s);
  return st;
}

int zs_cmd_walk(int argc, char **argv) {
  if (zs_cli_help_asked(argc, argv)) {
    fputs(usage, stdout);
    return 0;
  }
  walk_opts o;
  zs_error err;
  zs_error_clear(&err);
  int parsing = 1;
  if (parse(argc, argv, &o, &err) || (parsing = 0) || run(&o, &err)) {
    fprintf(stderr, "zscan walk: %s\n", err.msg);
    return zs_cli_exit_status(&err, parsing);
  }
  return 0;
}
