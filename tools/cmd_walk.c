/* `zscan walk SCENE --cull M1,M2,... [options]`: every culling method over
 * the scene's camera path, with its moving objects, frame by frame.
 *
 * The methods run in lockstep: each frame the scene moves once, the octree
 * is brought up to date once, and then every method draws that frame on a
 * device of its own (each keeps its culler's state from frame to frame).
 * Both are the library's frame step (lib/walk.h), the one zs_walk_next
 * takes for a single method.
 * Each method's face ids are compared with those of `none` in the same
 * frame: diff_pixels.  The modelled times come from the device clock and
 * are the same on every run; wall times are measured and are not.
 */
#include "tools/commands.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cull/cull.h"
#include "cull/octree.h"
#include "raster/raster.h"
#include "scene/paths.h"
#include "scene/scene.h"
#include "tools/cli.h"
#include "util/os.h"
#include "tools/costset.h"
#include "lib/frame.h"
#include "lib/frame_camera.h"
#include "lib/image.h"
#include "lib/input.h"
#include "lib/outfile.h"
#include "lib/walk.h"
#include "tools/cmd_walk.h"

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

/* --cull LIST: each method once, after none (the reference). */
static zs_status parse_methods(const char *v, walk_opts *o, int *none_listed, zs_error *err) {
  char buf[256];
  snprintf(buf, sizeof buf, "%s", v);
  for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
    int m = zs_cull_method_parse(tok);
    *none_listed |= m == ZS_CULL_NONE;
    if (m < 0)
      return zs_error_set(err, ZS_ERR_ARG, "--cull: unknown method '%s' (" ZS_CULL_METHOD_LIST ")",
                          tok);
    int dup = 0;
    for (int k = 0; k < o->nmethods; k++) dup |= o->methods[k] == m;
    if (!dup) o->methods[o->nmethods++] = m;
  }
  return ZS_OK;
}

/* --algos LIST: scanline and/or depthsort, each once. */
static zs_status parse_algos(const char *v, walk_opts *o, zs_error *err) {
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
  return ZS_OK;
}

/* Whether v is one of zs_path_names ("static, translate, ..."). */
static int named_path_known(const char *v) {
  char names[128];
  snprintf(names, sizeof names, "%s", zs_path_names);
  int known = 0;
  for (char *t = strtok(names, ", "); t; t = strtok(NULL, ", ")) known |= strcmp(t, v) == 0;
  return known;
}

/* What the options ask together: --reference off against what needs
 * none, the frames' folder, and the one stream standard output carries. */
static zs_status check_outputs(walk_opts *o, int none_listed, zs_error *err) {
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

/* --csv, --md, --plot and --tradeoff: a file each (or - for standard
 * output).  1: taken; 0: not one of them; -1: an error, in err. */
static int output_option(int argc, char **argv, int *i, walk_opts *o, zs_error *err) {
  const struct {
    const char *name;
    const char **path;
  } outputs[] = {{"--csv", &o->csv}, {"--md", &o->md}, {"--plot", &o->plot}, {"--tradeoff", &o->tradeoff}};
  for (size_t k = 0; k < sizeof outputs / sizeof outputs[0]; k++)
    if (strcmp(argv[*i], outputs[k].name) == 0)
      return zs_cli_output_value(argc, argv, i, outputs[k].path, err) ? -1 : 1;
  return 0;
}

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
    int taken = zs_cull_option(argc, argv, &i, &o->clock, &o->cost, &o->bounds, err);
    if (!taken) taken = output_option(argc, argv, &i, o, err);
    if (taken < 0) return err->code;
    if (taken) continue;
    if (strcmp(a, "--cull") == 0) {
      VALUE();
      have_cull = 1;
      if (parse_methods(v, o, &none_listed, err)) return err->code;
    } else if (strcmp(a, "--frames") == 0) {
      VALUE();
      if (zs_cli_int(a, v, 1, 1000000, &o->frames, err)) return err->code;
    } else if (strcmp(a, "--algos") == 0) {
      VALUE();
      if (parse_algos(v, o, err)) return err->code;
    } else if (strcmp(a, "--step") == 0) {
      VALUE();
      if (zs_cli_int(a, v, 1, 10000, &o->step, err)) return err->code;
    } else if (strcmp(a, "--size") == 0) {
      VALUE();
      if (zs_cli_size(a, v, ZS_MAX_IMAGE_SIDE, &o->width, &o->height, err)) return err->code;
    } else if (strcmp(a, "--frames-dir") == 0) {
      VALUE();
      o->frames_dir = v; /* created (with its parents) when the walk starts */
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
      if (!named_path_known(v))
        return zs_error_set(err, ZS_ERR_ARG, "--named: expected %s, got '%s'", zs_path_names, v);
      o->named = v;
    } else if (zs_cli_operand(a, "zscan walk", "SCENE", &o->scene, err)) {
      return err->code;
    }
#undef VALUE
  }
  if (!o->scene) return zs_error_set(err, ZS_ERR_ARG, "missing SCENE (see zscan walk --help)");
  if (!have_cull) return zs_error_set(err, ZS_ERR_ARG, "missing --cull (see zscan walk --help)");
  return check_outputs(o, none_listed, err);
}

/* A method's frame as the device finished it: the rows into an image. */
static void keep_rows(void *user, const zs_row *row) {
  zs_image *im = user;
  memcpy(im->rgb + (size_t)row->y * (size_t)row->width, row->rgb,
         (size_t)row->width * sizeof *row->rgb);
}

static zs_status write_frame(const walk_opts *o, const zs_cmd_walk_method *r, const zs_image *im,
                             int f, zs_error *err) {
  char path[4200];
  snprintf(path, sizeof path, "%s/%s-%05d.png", o->frames_dir, zs_cull_method_name(r->m), f);
  zs_status st = zs_png_write_shaded(path, im, o->frames_shade, err);
  return st ? zs_out_error_option(err, "--frames-dir") : ZS_OK;
}

/* The rows of a mode that keeps no full-frame buffers, as they come. */
static void keep_ids(void *user, const zs_row *row) {
  uint32_t *ids = user;
  memcpy(ids + (size_t)row->y * (size_t)row->width, row->id, (size_t)row->width * sizeof *row->id);
}

/* The walk under way: the scene as it moves, its octree, every method's
 * and mode's device, and the buffers the comparisons read. */
typedef struct walk {
  zs_scene s;
  zs_octree tree;
  int w, h, frames;
  zs_cmd_walk_method runs[ZS_CULL_METHODS];
  zs_cmd_walk_algo algos[2];
  uint32_t *ref_ids, *algo_ids;
  zs_image frame_image; /* a method's frame, for --frames-dir */
  double *frame_ms;     /* per frame and method, for the plot */
  double *frame_wall;   /* per row (methods, then modes) and frame: the medians */
  zs_out csv_out;
  FILE *csv;            /* csv_out.fp while the CSV is open */
} walk;

/* --latency-frames: the query latency as a multiple of none's modelled
 * time of the first frame, set on every method's clock. */
static zs_status set_latency(const walk_opts *o, walk *wk, zs_clock_params *clock, zs_error *err) {
  double view[16], proj[16];
  zs_cull_stats cs;
  const zs_cmd_walk_method *none = &wk->runs[0];
  if (zs_walk_step_scene(&wk->s, &wk->tree, 0, o->step, wk->w, wk->h, view, proj, err) ||
      zs_walk_step_method(none->culler, none->dev, &wk->s, &wk->tree, view, proj, &cs, NULL,
                          NULL, err))
    return err->code;
  clock->query_latency_ns = o->latency_frames * (double)zs_device_frame_ps(none->dev) * 1e-3;
  for (int k = 0; k < o->nmethods; k++)
    if (zs_device_set_clock(wk->runs[k].dev, clock, err)) return err->code;
  fprintf(o->report, "query latency: %.3f ms (%.2f frames of none)\n",
          clock->query_latency_ns * 1e-6, o->latency_frames);
  return ZS_OK;
}

/* Each method's culler and device, each mode's device. */
static zs_status make_devices(const walk_opts *o, walk *wk, zs_error *err) {
  zs_clock_params clock = o->clock;
  for (int k = 0; k < o->nmethods; k++) {
    zs_cmd_walk_method *r = &wk->runs[k];
    r->m = (zs_cull_method)o->methods[k];
    /* id shading, which the comparisons read; flat when --frames-dir shows
     * the frames shaded (the ids are kept either way, the clock the same) */
    zs_shade shade = o->frames_dir ? o->frames_shade : ZS_SHADE_ID;
    zs_device_config cfg = {wk->w, wk->h, ZS_ALGO_ZBUFFER, shade, 0, 1, ZS_BACKGROUND_RGB, 0, 0};
    if (zs_device_create(&cfg, &r->dev, err) ||
        zs_culler_create(r->m, &o->cost, &r->culler, err) ||
        zs_culler_set_bounds(r->culler, o->bounds, err) ||
        zs_device_set_clock(r->dev, &clock, err))
      return err->code;
  }
  if (o->latency_frames >= 0 && set_latency(o, wk, &clock, err)) return err->code;
  for (int k = 0; k < o->nalgos; k++) {
    zs_device_config cfg = {wk->w, wk->h, o->algos[k], ZS_SHADE_ID, 0, 1, 0, 0, 0};
    wk->algos[k].a = o->algos[k];
    if (zs_device_create(&cfg, &wk->algos[k].dev, err) ||
        zs_device_set_clock(wk->algos[k].dev, &clock, err))
      return err->code;
  }
  return ZS_OK;
}

/* The scene, its size, frames and octree, the devices, the buffers and
 * the CSV, before the first frame. */
static zs_status start(const walk_opts *o, walk *wk, zs_error *err) {
  if (zs_input_load_scene(o->scene, &wk->s, err)) return err->code;
  const zs_scene *s = &wk->s;
  zs_frame_size(s, o->width, o->height, &wk->w, &wk->h);
  if (o->named &&
      zs_frame_named_path(&wk->s, o->named, o->frames ? o->frames : 100, wk->w, wk->h, err))
    return err->code;
  wk->frames = o->frames ? o->frames : zs_walk_step_count(s, o->step);
  zs_octree_params tp;
  zs_octree_params_default(&tp, ZS_OCTREE_LOOSE);
  tp.max_depth = o->depth;
  tp.looseness = o->looseness;
  if (zs_octree_build(&wk->tree, &wk->s, &tp, err) || make_devices(o, wk, err)) return err->code;
  const size_t pixels = (size_t)wk->w * (size_t)wk->h, nrows = (size_t)(o->nmethods + o->nalgos);
  if (o->frames_dir && zs_image_alloc(&wk->frame_image, wk->w, wk->h, err)) return err->code;
  if (!(wk->ref_ids = malloc(pixels * sizeof *wk->ref_ids)) ||
      !(wk->algo_ids = malloc(pixels * sizeof *wk->algo_ids)) ||
      !(wk->frame_wall = calloc((size_t)wk->frames * nrows, sizeof *wk->frame_wall)) ||
      !(wk->frame_ms = calloc((size_t)wk->frames * (size_t)o->nmethods, sizeof *wk->frame_ms)))
    return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  if (o->csv) {
    if (zs_out_open(&wk->csv_out, o->csv, err)) return zs_out_error_option(err, "--csv");
    wk->csv = wk->csv_out.fp;
    zs_cmd_walk_csv_header(wk->csv);
  }
  return ZS_OK;
}

/* Method k's draw of frame f, added to its sums, compared with none's. */
static zs_status method_frame(const walk_opts *o, walk *wk, int k, int f, const double *view,
                              const double *proj, zs_error *err) {
  zs_cmd_walk_method *r = &wk->runs[k];
  zs_cull_stats cs;
  double t0 = zs_os_monotonic_ms();
  if (zs_walk_step_method(r->culler, r->dev, &wk->s, &wk->tree, view, proj, &cs,
                          o->frames_dir ? keep_rows : NULL, &wk->frame_image, err))
    return err->code;
  double wall = zs_os_monotonic_ms() - t0;
  const zs_clock_stats *ck = zs_device_clock(r->dev);
  double modelled = zs_device_frame_ps(r->dev) * 1e-9, stall = ck->stall_ps * 1e-9;
  double split[4];
  zs_cmd_walk_gpu_split_ms(r->dev, split);
  for (int i = 0; i < 4; i++) r->gpu_ms[i] += split[i];
  const uint32_t *ids = zs_device_id_buffer(r->dev);
  const size_t pixels = (size_t)wk->w * (size_t)wk->h;
  uint64_t diff = 0;
  if (o->no_reference) {
    /* nothing to compare with */
  } else if (k == 0) {
    memcpy(wk->ref_ids, ids, pixels * sizeof *ids);
  } else {
    for (size_t i = 0; i < pixels; i++) diff += ids[i] != wk->ref_ids[i];
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
  wk->frame_ms[(size_t)f * (size_t)o->nmethods + (size_t)k] = modelled;
  wk->frame_wall[(size_t)k * (size_t)wk->frames + (size_t)f] = wall;
  if (wk->csv)
    zs_cmd_walk_csv_method(wk->csv, f * o->step, r, &cs, modelled, stall, wall, split,
                           !o->no_reference, diff);
  return o->frames_dir ? write_frame(o, r, &wk->frame_image, f, err) : ZS_OK;
}

/* Mode k's draw of everything in frame f, against none's. */
static zs_status algo_frame(const walk_opts *o, walk *wk, int k, int f, const double *view,
                            const double *proj, zs_error *err) {
  zs_cmd_walk_algo *r = &wk->algos[k];
  double t0 = zs_os_monotonic_ms();
  if (zs_frame_draw_all(r->dev, &wk->s, view, proj, err) ||
      zs_device_finish(r->dev, keep_ids, wk->algo_ids, err))
    return err->code;
  double wall = zs_os_monotonic_ms() - t0, modelled = zs_device_frame_ps(r->dev) * 1e-9;
  uint64_t diff = 0;
  for (size_t i = 0; i < (size_t)wk->w * (size_t)wk->h; i++)
    diff += wk->algo_ids[i] != wk->ref_ids[i];
  /* every face, counted as the methods count theirs: as drawn, after
   * the split of non-planar ones */
  uint64_t faces = zs_device_stats(r->dev)->polygons_in;
  r->faces += (double)faces;
  r->modelled_ms += modelled;
  r->wall_ms += wall;
  r->diff_pixels += diff;
  wk->frame_wall[(size_t)(o->nmethods + k) * (size_t)wk->frames + (size_t)f] = wall;
  if (wk->csv)
    zs_cmd_walk_csv_algo(wk->csv, f * o->step, r, modelled, wall, faces, (int)wk->s.ninst, diff);
  return ZS_OK;
}

/* Every frame: the scene moves, the octree follows, every method and
 * mode draws it. */
static zs_status walk_frames(const walk_opts *o, walk *wk, zs_error *err) {
  zs_progress progress;
  zs_progress_start(&progress, "walk", "frame", wk->frames, o->quiet);
  for (int f = 0; f < wk->frames; f++) {
    double view[16], proj[16];
    if (zs_walk_step_scene(&wk->s, &wk->tree, f, o->step, wk->w, wk->h, view, proj, err))
      return err->code;
    for (int k = 0; k < o->nmethods; k++)
      if (method_frame(o, wk, k, f, view, proj, err)) return err->code;
    for (int k = 0; k < o->nalgos; k++) /* everything, in another mode */
      if (algo_frame(o, wk, k, f, view, proj, err)) return err->code;
    zs_progress_step(&progress, f + 1);
  }
  return ZS_OK;
}

static void walk_free(walk *wk) {
  if (wk->csv) zs_out_discard(&wk->csv_out);
  zs_image_free(&wk->frame_image);
  free(wk->ref_ids);
  free(wk->algo_ids);
  free(wk->frame_ms);
  free(wk->frame_wall);
  for (int k = 0; k < 2; k++) zs_device_destroy(wk->algos[k].dev);
  for (int k = 0; k < ZS_CULL_METHODS; k++) {
    zs_culler_destroy(wk->runs[k].culler);
    zs_device_destroy(wk->runs[k].dev);
  }
  zs_octree_free(&wk->tree);
  zs_scene_free(&wk->s);
}

static zs_status run(const walk_opts *o, zs_error *err) {
  walk *wk = calloc(1, sizeof *wk);
  if (!wk) return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  zs_status st = start(o, wk, err);
  if (!st) st = walk_frames(o, wk, err);
  if (!st && wk->csv) {
    wk->csv = NULL; /* committed or removed, either way */
    if ((st = zs_out_commit(&wk->csv_out, err))) zs_out_error_option(err, "--csv");
  }
  if (!st) {
    zs_cmd_walk_result res = {o->scene,    wk->w,         wk->h,         wk->frames,
                              o->step,     (int)wk->s.ninst, zs_scene_faces(&wk->s),
                              !o->no_reference, wk->runs, o->nmethods, wk->algos, o->nalgos,
                              wk->frame_ms, wk->frame_wall};
    zs_cmd_walk_report(o->report, &res);
    st = zs_cmd_walk_outputs(&res, o->md, o->tradeoff, o->plot, err);
  }
  walk_free(wk);
  free(wk);
  return st;
}

int zs_cmd_walk(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, NULL)) return 0;
  walk_opts o;
  zs_error err;
  zs_error_clear(&err);
  if (parse(argc, argv, &o, &err)) return zs_cli_fail("zscan walk", &err, 1);
  return run(&o, &err) ? zs_cli_fail("zscan walk", &err, 0) : 0;
}
