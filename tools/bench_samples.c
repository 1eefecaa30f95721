/* `zscan bench samples [--quick] [--size WxH] [--md FILE]`
 *
 * What anti-aliasing costs and how its coverage compares: bench raster's
 * scenes on one thread in zbuffer mode (flat shading), each frame drawn
 * with one sample a pixel and with four (zscan render --samples 4: the
 * frame drawn at each standard position, then resolved), the two in
 * turn, each the median of MAX_REPEAT frames; and, where zscan has Mesa's
 * llvmpipe (OSMesa), the
 * faces each shows at every one of the four positions, told apart into
 * coverage and depth ties as bench raster --mesa does.  OSMesa has no
 * multisampled buffer, so llvmpipe's sample k is its frame with the pixel
 * centres moved onto position k by the same projection zscan draws sample
 * k with: its coverage rule evaluated at the standard positions.  The
 * figures: docs/RESULTS.md, from `zscan bench samples`. */
#include "tools/bench_samples.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/frame.h"
#include "lib/frame_camera.h"
#include "lib/image.h"
#include "lib/input.h"
#include "lib/samples.h"
#include "tools/bench_raster.h"
#include "tools/bench_report.h"
#include "tools/cli.h"
#include "util/os.h"
#include "tools/crosscheck.h"
#include "tools/mesa.h"

static const char usage[] =
    "usage: zscan bench samples [--quick] [--size WxH] [--md FILE]\n"
    "  bench raster's scenes with one sample a pixel and with four (render\n"
    "  --samples 4), frames in turn, one thread, zbuffer mode, medians of 11;\n"
    "  with OSMesa, each sample's faces against llvmpipe's at the same position\n"
    "  --quick      one small scene, 3 times: a check that it runs\n"
    "  --size WxH   the image size (default 1024x768)\n"
    "  --md FILE    the table in Markdown\n";

enum { SAMPLES = 4, MAX_REPEAT = 11, MAX_CASES = 16 };

typedef struct samples_row {
  char name[64];
  double one_ms, many_ms;
  int compared;         /* the faces were compared with llvmpipe's */
  zs_crosscheck faces;  /* summed over the samples: pixels = samples compared */
} samples_row;

typedef struct samples_table {
  samples_row rows[MAX_CASES];
  int n;
} samples_table;

static zs_status measure(const char *input, int w, int h, int repeat, samples_row *row,
                         zs_error *err) {
  zs_scene s;
  if (zs_input_load_scene(input, &s, err)) return err->code;
  double view[16], proj[16], t[2][MAX_REPEAT];
  zs_device *dev = NULL;
  zs_image im = {0, 0, NULL};
  zs_device_config cfg = {w, h, ZS_ALGO_ZBUFFER, ZS_SHADE_FLAT, 0, 1, 0, ZS_SPANS_BEST, 0};
  zs_status st = zs_frame_camera(&s, &s.camera, w, h, view, proj, err);
  if (!st) st = zs_device_create(&cfg, &dev, err);
  if (!st) st = zs_device_set_lights(dev, s.lights, s.nlights, err);
  if (!st) st = zs_image_alloc(&im, w, h, err);
  for (int r = 0; r < repeat && !st; r++) { /* in turn: the same machine for both */
    double t0 = zs_os_monotonic_ms();
    if ((st = zs_frame_render_on(dev, &s, view, proj, NULL, &im, NULL, err))) break;
    double t1 = zs_os_monotonic_ms();
    if ((st = zs_frame_render_samples(dev, &s, view, proj, NULL, SAMPLES, 0, &im, NULL, err)))
      break;
    t[0][r] = t1 - t0;
    t[1][r] = zs_os_monotonic_ms() - t1;
  }
  memset(row, 0, sizeof *row);
  snprintf(row->name, sizeof row->name, "%s", input);
  if (!st) {
    row->one_ms = zs_median(t[0], repeat);
    row->many_ms = zs_median(t[1], repeat);
  }
  zs_mesa *mesa = NULL;
  uint32_t *ids = NULL;
  if (!st && zs_mesa_available()) {
    if (!(ids = malloc((size_t)w * (size_t)h * sizeof *ids)))
      st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
    if (!st) st = zs_mesa_create(w, h, &mesa, err);
    const int8_t *pos = zs_sample_positions(SAMPLES);
    for (int k = 0; k < SAMPLES && !st; k++) {
      double pk[16];
      zs_crosscheck c;
      zs_sample_projection(proj, w, h, pos[2 * k], pos[2 * k + 1], pk);
      if ((st = zs_mesa_ids(mesa, &s, view, pk, ids, err)) ||
          (st = zs_crosscheck_faces(&s, view, pk, w, h, ids, NULL, &c, err)))
        break;
      row->faces.pixels += c.pixels, row->faces.covered += c.covered;
      row->faces.differ += c.differ, row->faces.ties += c.ties;
    }
    row->compared = !st;
  }
  zs_mesa_destroy(mesa);
  free(ids);
  zs_image_free(&im);
  zs_device_destroy(dev);
  zs_scene_free(&s);
  return st;
}

static void write_rows(FILE *f, const void *p, int md) {
  const samples_table *t = p;
  if (md)
    fprintf(f, "| case | 1 sample ms | 4 samples ms | 4 / 1 | samples differing from "
               "llvmpipe's in 10,000 | of them, depth ties | coverage differing in 10,000 "
               "samples |\n|---|---|---|---|---|---|---|\n");
  else
    fprintf(f, "%-36s %8s %9s %6s %10s %9s %12s\n", "case", "1_ms", "4_ms", "ratio",
            "differ_10k", "ties_10k", "coverage_10k");
  for (int i = 0; i < t->n; i++) {
    const samples_row *r = &t->rows[i];
    const zs_crosscheck *c = &r->faces;
    char d[3][32] = {"-", "-", "-"};
    if (r->compared && c->pixels) {
      snprintf(d[0], sizeof d[0], "%.2f", 1e4 * (double)c->differ / (double)c->pixels);
      snprintf(d[1], sizeof d[1], "%.2f", 1e4 * (double)c->ties / (double)c->pixels);
      snprintf(d[2], sizeof d[2], "%.2f", 1e4 * (double)(c->differ - c->ties) / (double)c->pixels);
    }
    if (md)
      fprintf(f, "| `%s` | %.2f | %.2f | %.2f | %s | %s | %s |\n", r->name, r->one_ms, r->many_ms,
              r->many_ms / r->one_ms, d[0], d[1], d[2]);
    else
      fprintf(f, "%-36s %8.2f %9.2f %6.2f %10s %9s %12s\n", r->name, r->one_ms, r->many_ms,
              r->many_ms / r->one_ms, d[0], d[1], d[2]);
  }
}

int zs_cmd_bench_samples(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, NULL)) return 0;
  zs_error err;
  zs_error_clear(&err);
  int w = 1024, h = 768, parsing = 1;
  const char *md = NULL;
  const int quick = zs_bench_take_flag(&argc, argv, "--quick"), repeat = quick ? 3 : MAX_REPEAT;
  zs_status st = zs_bench_size_md_args(argc, argv, "samples", &w, &h, &md, &err);
  if (!st) parsing = 0;
  samples_table t;
  t.n = 0;
  const int n = quick ? 1 : zs_bench_nscenes;
  for (int i = 0; i < n && i < MAX_CASES && !st; i++) {
    const char *input = quick ? "builtin:teapots,count=4" : zs_bench_scenes[i];
    st = measure(input, w, h, repeat, &t.rows[t.n++], &err);
  }
  if (!st) {
    char title[128];
    snprintf(title, sizeof title, "one sample and four at %dx%d, one thread, zbuffer mode%s", w, h,
             zs_mesa_available() ? "; each sample's faces against llvmpipe's" : "");
    st = zs_bench_report(md, title, write_rows, &t, &err);
  }
  return st ? zs_cli_fail("zscan bench samples", &err, parsing) : 0;
}
