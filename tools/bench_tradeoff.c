/* `zscan bench tradeoff [--out DIR] [--quick] [--size WxH]`: run time
 * against error, the whole suite in one command.
 *
 * Each generated scene's walk (teapots, city, plant) runs through `zscan
 * walk` with every culling method and, beside the z-buffer, the scanline
 * and depth-sort modes.  Per walk DIR gets its CSV (one row per frame and
 * method), its table in Markdown and its plot of time against pixels wrong
 * (one point per method and mode); DIR/tradeoff.md gathers the tables with
 * the command of each; then the tuning outcomes (tools/bench_tuning.h)
 * and the scenes' load times on stdout.  --quick takes smaller scenes and every 60th to 80th
 * frame: a look in seconds, not the figures of docs/RESULTS.md. */
#include "tools/bench_tradeoff.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "raster/raster.h"
#include "tools/cli.h"
#include "lib/outfile.h"
#include "tools/bench_load.h"
#include "tools/bench_tuning.h"
#include "tools/commands.h"

static const char usage[] =
    "usage: zscan bench tradeoff [--out DIR] [--quick] [--size WxH] [--quiet]\n"
    "  --out DIR   where the CSVs, tables and plots go (default bench-tradeoff)\n"
    "  --quick     smaller scenes, a few frames of each walk\n"
    "  --size WxH  image size (default: each scene's)\n"
    "  --quiet     no progress on stderr (else each walk's name, then its frames\n"
    "              as zscan walk shows them)\n";

static const char methods[] = "vfc,vfc-box,hsw,chc,chc-prob,chcpp,chcpp-prob,nohc,hzb,ideal-box,ideal,auto";
static const char modes[] = "scanline,depthsort";

typedef struct walk_case {
  const char *name, *scene, *step;
} walk_case;

static const walk_case full[] = {
    {"teapots", "builtin:teapots,count=6000", "10"},
    {"city", "builtin:city", "8"},
    {"plant", "builtin:plant,detail=1", "8"},
};
static const walk_case quick[] = {
    {"teapots", "builtin:teapots,count=500", "60"},
    {"city", "builtin:city", "80"},
    {"plant", "builtin:plant,detail=0.25", "80"},
};
enum { NWALKS = sizeof full / sizeof full[0] };

int zs_cmd_bench_tradeoff(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, NULL)) return 0;
  const char *dir = "bench-tradeoff", *size = NULL;
  int is_quick = 0, quiet = 0, w, h;
  zs_error err;
  zs_error_clear(&err);
  int parsing = 1; /* a usage error exits 2 (tools/cli.h) */
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (strcmp(a, "--quick") == 0) {
      is_quick = 1;
    } else if (strcmp(a, "--quiet") == 0) {
      quiet = 1;
    } else if (strcmp(a, "--out") == 0) {
      if (zs_cli_value(argc, argv, &i, &dir, &err)) goto fail;
    } else if (strcmp(a, "--size") == 0) {
      if (zs_cli_value(argc, argv, &i, &size, &err) ||
          zs_cli_size(a, size, ZS_MAX_IMAGE_SIDE, &w, &h, &err))
        goto fail;
    } else {
      zs_error_set(&err, ZS_ERR_ARG, "unknown option '%s' (see zscan bench tradeoff --help)", a);
      goto fail;
    }
  }
  parsing = 0;
  if (zs_out_dir("--out", dir, &err)) goto fail;
  const walk_case *walks = is_quick ? quick : full;
  char path[NWALKS][3][4200];
  for (int k = 0; k < NWALKS; k++) {
    static const char *const ext[3] = {"csv", "md", "png"};
    for (int e = 0; e < 3; e++)
      snprintf(path[k][e], sizeof path[k][e], "%s/tradeoff-%s.%s", dir, walks[k].name, ext[e]);
    char *args[24];
    int n = 0;
    args[n++] = "walk";
    args[n++] = (char *)walks[k].scene;
    args[n++] = "--cull";
    args[n++] = (char *)methods;
    args[n++] = "--algos";
    args[n++] = (char *)modes;
    args[n++] = "--step";
    args[n++] = (char *)walks[k].step;
    args[n++] = "--csv";
    args[n++] = path[k][0];
    args[n++] = "--md";
    args[n++] = path[k][1];
    args[n++] = "--tradeoff";
    args[n++] = path[k][2];
    if (quiet) args[n++] = "--quiet";
    if (size) {
      args[n++] = "--size";
      args[n++] = (char *)size;
    }
    args[n] = NULL;
    if (!quiet) fprintf(stderr, "bench tradeoff: walk %d/%d, %s\n", k + 1, NWALKS, walks[k].name);
    if (zs_cmd_walk(n, args) != 0) return 1; /* walk said why */
  }
  /* the tables together, each under its command */
  char summary[4200];
  snprintf(summary, sizeof summary, "%s/tradeoff.md", dir);
  zs_out out;
  if (zs_out_open(&out, summary, &err)) goto fail;
  FILE *f = out.fp;
  for (int k = 0; k < NWALKS; k++) {
    fprintf(f, "%s### %s\n\n```\n$ zscan walk \"%s\" --cull %s --algos %s --step %s%s%s\n```\n\n",
            k ? "\n" : "", walks[k].name, walks[k].scene, methods, modes, walks[k].step,
            size ? " --size " : "", size ? size : "");
    if (zs_append_file(f, path[k][1], &err)) {
      zs_out_discard(&out);
      goto fail;
    }
    fprintf(f, "\n![run time against error: %s](tradeoff-%s.png)\n", walks[k].name, walks[k].name);
  }
  if (zs_out_commit(&out, &err)) goto fail;
  /* the comparisons the tests once pinned, as figures, and the time the
   * walks' scenes take to build */
  const char *specs[NWALKS];
  for (int k = 0; k < NWALKS; k++) specs[k] = walks[k].scene;
  if (zs_bench_tuning_report(stdout, &err) || zs_bench_load_report(stdout, specs, NWALKS, &err))
    goto fail;
  printf("wrote %s and, per walk, tradeoff-NAME.csv, .md and .png\n", summary);
  return 0;
fail:
  return zs_cli_fail("zscan bench tradeoff", &err, parsing);
}
