/* `zscan bench depthsort [SCENE] [--frames N] [--size WxH] [--csv FILE]`:
 * the depth-sort paper's Table 1 on our scenes.  For each of the four
 * camera motions (translate, roll, yaw, fast: scene/paths.h) the scene is
 * walked twice in depthsort mode, once sorting from scratch every frame
 * and once with frame coherence, and once in zbuffer mode for the error;
 * back faces are culled first, as in the paper's pipeline, so the faces
 * sorted are those turned to the eye.
 * Per motion: the faces per frame, the share of faces that kept their
 * place (reused), the sort time per frame of both (median, wall time: a
 * measurement), the comparisons of both (exact), and the pixels whose face
 * differs from the z-buffer's. */
#include "tools/bench_depthsort.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "raster/raster.h"
#include "scene/paths.h"
#include "scene/scene.h"
#include "tools/cli.h"
#include "lib/frame.h"
#include "lib/frame_camera.h"
#include "lib/input.h"
#include "lib/outfile.h"

static const char usage[] =
    "usage: zscan bench depthsort [SCENE] [--frames N] [--size WxH] [--far F] [--csv FILE]\n"
    "  SCENE   default builtin:city (the paper's city walk)\n"
    "  --far F the back clipping plane (default: the scene's, which may hold it all)\n";

static const char *const motions[4] = {"translate", "roll", "yaw", "fast"};

typedef struct motion_row {
  double faces, reused_pct, full_ms, coherent_ms, full_cmp, coherent_cmp, diff;
} motion_row;

typedef struct id_sink {
  uint32_t *ids;
} id_sink;

static void keep_ids(void *user, const zs_row *row) {
  id_sink *k = user;
  memcpy(k->ids + (size_t)row->y * (size_t)row->width, row->id,
         (size_t)row->width * sizeof *row->id);
}

static zs_status run_motion(const zs_scene *s, const char *motion, int frames, int w, int h,
                            double far, motion_row *out, zs_error *err) {
  memset(out, 0, sizeof *out);
  /* the motions start where the scene's own walk starts (the city's at
   * street level, as the paper's), else from its camera */
  zs_camera key = s->camera, base;
  if (s->path.nkeys > 0) zs_path_camera(s, 0, &key);
  if (far > 0) {
    key.zfar = far;
    key.has_far = 1;
  }
  zs_frame_complete_camera(s, &key, w, h, &base);
  if (far > 0 && base.znear >= far) base.znear = far * 1e-3;
  zs_path path;
  if (zs_path_named(motion, &base, frames, &path, err)) return err->code;
  zs_device *full = NULL, *coherent = NULL, *zbuf = NULL;
  /* back faces culled, as the paper's pipeline does before it sorts */
  zs_device_config cfg = {w, h, ZS_ALGO_DEPTHSORT, ZS_SHADE_ID, 1, 1, 0, 0, 0};
  zs_device_config zc = {w, h, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 1, 1, 0, 0, 0};
  size_t npx = (size_t)w * (size_t)h;
  uint32_t *ids = malloc(npx * sizeof *ids);
  double *full_ms = malloc((size_t)frames * sizeof *full_ms);
  double *coh_ms = malloc((size_t)frames * sizeof *coh_ms);
  zs_status st = ZS_OK;
  if (!ids || !full_ms || !coh_ms) st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  if (st == ZS_OK && !(st = zs_device_create(&cfg, &full, err)) &&
      !(st = zs_device_create(&cfg, &coherent, err)))
    st = zs_device_create(&zc, &zbuf, err);
  id_sink sink = {ids};
  for (int f = 0; f < frames && st == ZS_OK; f++) {
    zs_keyframe k = path.keys[f];
    zs_camera cam = base;
    memcpy(cam.eye, k.eye, sizeof cam.eye);
    memcpy(cam.target, k.target, sizeof cam.target);
    memcpy(cam.up, k.up, sizeof cam.up);
    double view[16], proj[16];
    if ((st = zs_camera_matrices(&cam, (double)w / h, view, proj, err))) break;
    /* from scratch */
    zs_device_depthsort_reset(full);
    if ((st = zs_frame_draw_all(full, s, view, proj, err)) ||
        (st = zs_device_finish(full, NULL, NULL, err)))
      break;
    full_ms[f] = zs_device_depthsort_ms(full);
    if (f > 0) out->full_cmp += (double)zs_device_depthsort_stats(full)->comparisons;
    /* with coherence, and its picture */
    if ((st = zs_frame_draw_all(coherent, s, view, proj, err)) ||
        (st = zs_device_finish(coherent, keep_ids, &sink, err)))
      break;
    const zs_depthsort_stats *ds = zs_device_depthsort_stats(coherent);
    coh_ms[f] = zs_device_depthsort_ms(coherent);
    /* the first frame has no order to keep: the sort figures count the
     * frames after it, as the medians of the times do */
    if (f > 0) out->coherent_cmp += (double)ds->comparisons;
    out->faces += (double)ds->faces;
    /* the first frame has nothing to reuse: the table counts the others */
    if (f > 0) out->reused_pct += ds->faces ? 100.0 * (double)ds->reused / (double)ds->faces : 0;
    /* the z-buffer's picture */
    if ((st = zs_frame_draw_all(zbuf, s, view, proj, err)) ||
        (st = zs_device_finish(zbuf, NULL, NULL, err)))
      break;
    const uint32_t *zids = zs_device_id_buffer(zbuf);
    for (size_t i = 0; i < npx; i++) out->diff += ids[i] != zids[i];
  }
  if (st == ZS_OK) {
    out->faces /= frames;
    out->reused_pct /= frames > 1 ? frames - 1 : 1;
    out->full_cmp /= frames > 1 ? frames - 1 : 1;
    out->coherent_cmp /= frames > 1 ? frames - 1 : 1;
    out->diff /= frames;
    /* medians over the frames after the first */
    out->full_ms = zs_median(full_ms + 1, frames > 1 ? frames - 1 : 1);
    out->coherent_ms = zs_median(coh_ms + 1, frames > 1 ? frames - 1 : 1);
  }
  free(ids);
  free(full_ms);
  free(coh_ms);
  zs_device_destroy(full);
  zs_device_destroy(coherent);
  zs_device_destroy(zbuf);
  zs_path_free(&path);
  return st;
}

int zs_cmd_bench_depthsort(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, NULL)) return 0;
  const char *spec = "builtin:city", *csv_path = NULL;
  int frames = 60, w = 1024, h = 768;
  double far = 0;
  zs_error err;
  zs_error_clear(&err);
  int parsing = 1; /* a usage error exits 2 (tools/cli.h) */
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v;
    if (strcmp(a, "--frames") == 0) {
      if (zs_cli_int_value(argc, argv, &i, 2, 100000, &frames, &err)) goto fail;
    } else if (strcmp(a, "--size") == 0) {
      if (zs_cli_size_value(argc, argv, &i, ZS_MAX_IMAGE_SIDE, &w, &h, &err)) goto fail;
    } else if (strcmp(a, "--far") == 0) {
      if (zs_cli_value(argc, argv, &i, &v, &err) || zs_cli_double(a, v, &far, &err)) goto fail;
      if (!(far > 0)) {
        zs_error_set(&err, ZS_ERR_ARG, "--far: must be greater than 0");
        goto fail;
      }
    } else if (strcmp(a, "--csv") == 0) {
      if (zs_cli_output_value(argc, argv, &i, &csv_path, &err)) goto fail;
    } else if (a[0] == '-' && a[1]) {
      zs_error_set(&err, ZS_ERR_ARG, "unknown option '%s' (see zscan bench depthsort --help)", a);
      goto fail;
    } else {
      spec = a;
    }
  }
  parsing = 0;
  zs_scene s;
  if (zs_input_load_scene(spec, &s, &err)) goto fail;
  motion_row rows[4];
  for (int m = 0; m < 4; m++)
    if (run_motion(&s, motions[m], frames, w, h, far, &rows[m], &err)) {
      zs_scene_free(&s);
      goto fail;
    }
  zs_scene_free(&s);
  FILE *report = csv_path && zs_out_is_stdout(csv_path) ? stderr : stdout;
  fprintf(report, "depth sort with frame coherence: %s, %d frames per motion at %dx%d\n", spec, frames, w, h);
  fprintf(report, "%-10s %8s %10s %14s %18s %14s %18s %12s\n", "motion", "faces", "reused_pct",
         "full_sort_ms", "coherent_sort_ms", "full_cmp", "coherent_cmp", "diff_pixels");
  for (int m = 0; m < 4; m++)
    fprintf(report, "%-10s %8.0f %10.2f %14.3f %18.3f %14.0f %18.0f %12.1f\n", motions[m], rows[m].faces,
           rows[m].reused_pct, rows[m].full_ms, rows[m].coherent_ms, rows[m].full_cmp,
           rows[m].coherent_cmp, rows[m].diff);
  if (csv_path) {
    zs_out out;
    if (zs_out_open(&out, csv_path, &err)) {
      zs_out_error_option(&err, "--csv");
      goto fail;
    }
    FILE *f = out.fp;
    fprintf(f, "motion,faces,reused_pct,full_sort_ms,coherent_sort_ms,full_comparisons,"
               "coherent_comparisons,diff_pixels\n");
    for (int m = 0; m < 4; m++)
      fprintf(f, "%s,%.0f,%.2f,%.4f,%.4f,%.0f,%.0f,%.1f\n", motions[m], rows[m].faces,
              rows[m].reused_pct, rows[m].full_ms, rows[m].coherent_ms, rows[m].full_cmp,
              rows[m].coherent_cmp, rows[m].diff);
    if (zs_out_commit(&out, &err)) goto fail;
    if (report == stdout) fprintf(report, "wrote %s\n", csv_path);
  }
  return 0;
fail:
  return zs_cli_fail("zscan bench depthsort", &err, parsing);
}
