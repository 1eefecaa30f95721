/* `zscan bench suite [--out DIR] [--quick]`: the documented suite, one
 * command, every file in DIR:
 *   raster.csv, .md, .png   bench raster: triangles of 4 to 500 pixels and
 *                           the whole scenes in both modes, beside Mesa's
 *                           llvmpipe when zscan has it (--mesa), with the
 *                           instructions per frame when valgrind is there
 *                           (--callgrind);
 *   tradeoff*.csv, .md, .png  bench tradeoff: run time against error, every
 *                           method and mode on every walk;
 *   depthsort.csv           bench depthsort: the depth-sort paper's Table 1;
 *   octree.csv, .png        bench octree: loose against plain octree updates.
 * --quick: one frame per raster case and no scenes or instruction counts,
 * the quick walks, fewer frames elsewhere: a check that it all runs. */
#include "tools/bench_suite.h"

#include <stdio.h>
#include <string.h>

#include "raster/raster.h"
#include "tools/bench_depthsort.h"
#include "tools/bench_octree.h"
#include "tools/bench_raster.h"
#include "tools/bench_tradeoff.h"
#include "tools/callgrind.h"
#include "tools/cli.h"
#include "tools/mesa.h"
#include "tools/outfile.h"

static const char usage[] =
    "usage: zscan bench suite [--out DIR] [--quick] [--size WxH]\n"
    "  --out DIR   where every benchmark's files go (default bench-suite)\n"
    "  --quick     a few frames of each: a check that it all runs\n"
    "  --size WxH  the image size of raster, tradeoff and depthsort (raster needs\n"
    "              500x500 or more; default each one's own, 1024x768)\n";

/* Runs one benchmark's command with args (NULL-terminated, the command's
 * name first); returns its exit status. */
static int run(int (*cmd)(int, char **), char **args) {
  int n = 0;
  while (args[n]) n++;
  printf("\n$ zscan bench");
  for (int i = 0; i < n; i++) printf(" %s", args[i]);
  printf("\n");
  fflush(stdout);
  return cmd(n, args);
}

int zs_cmd_bench_suite(int argc, char **argv) {
  if (zs_cli_help_asked(argc, argv)) {
    fputs(usage, stdout);
    return 0;
  }
  const char *dir = "bench-suite", *size = NULL;
  int quick = 0, w, h;
  zs_error err;
  zs_error_clear(&err);
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--quick") == 0) {
      quick = 1;
    } else if (strcmp(argv[i], "--out") == 0) {
      if (zs_cli_value(argc, argv, &i, &dir, &err)) goto fail;
    } else if (strcmp(argv[i], "--size") == 0) {
      if (zs_cli_value(argc, argv, &i, &size, &err) ||
          zs_cli_size(argv[i - 1], size, ZS_MAX_IMAGE_SIDE, &w, &h, &err))
        goto fail;
    } else {
      zs_error_set(&err, ZS_ERR_ARG, "unknown option '%s' (see zscan bench suite --help)", argv[i]);
      goto fail;
    }
  }
  if (zs_out_dir("--out", dir, &err)) goto fail;
  char path[6][4200];
  static const char *const names[6] = {"raster.csv", "raster.md", "raster.png",
                                       "depthsort.csv", "octree.csv", "octree.png"};
  for (int k = 0; k < 6; k++) snprintf(path[k], sizeof path[k], "%s/%s", dir, names[k]);
  zs_error probe;
  zs_error_clear(&probe);
  const int mesa = zs_mesa_available(), callgrind = !quick && zs_callgrind_available(&probe);

  char *raster[20];
  int n = 0;
  raster[n++] = "raster";
  raster[n++] = "--csv";
  raster[n++] = path[0];
  raster[n++] = "--md";
  raster[n++] = path[1];
  raster[n++] = "--plot";
  raster[n++] = path[2];
  if (mesa && !quick) raster[n++] = "--mesa";
  if (callgrind) raster[n++] = "--callgrind";
  if (quick) {
    raster[n++] = "--repeat";
    raster[n++] = "1";
    raster[n++] = "--no-scenes";
  }
  if (size) {
    raster[n++] = "--size";
    raster[n++] = (char *)size;
  }
  raster[n] = NULL;
  char *tradeoff[8] = {"tradeoff", "--out", (char *)dir}, *depthsort[8] = {"depthsort"};
  int nt = 3, nd = 1;
  if (quick) tradeoff[nt++] = "--quick";
  depthsort[nd++] = "--frames";
  depthsort[nd++] = quick ? "4" : "40";
  depthsort[nd++] = "--csv";
  depthsort[nd++] = path[3];
  if (size) {
    tradeoff[nt++] = "--size";
    tradeoff[nt++] = (char *)size;
    depthsort[nd++] = "--size";
    depthsort[nd++] = (char *)size;
  }
  char *octree[] = {"octree", "--count", quick ? "500" : "5000", "--frames", quick ? "3" : "50",
                    "--csv", path[4], "--plot", path[5], NULL};
  if (run(zs_cmd_bench_raster, raster) || run(zs_cmd_bench_tradeoff, tradeoff) ||
      run(zs_cmd_bench_depthsort, depthsort) || run(zs_cmd_bench_octree, octree))
    return 1; /* the benchmark said why */
  printf("\nwrote %s: raster, tradeoff (per walk), depthsort and octree files%s%s\n", dir,
         mesa && !quick ? "; llvmpipe beside zscan" : "",
         callgrind ? "; instructions per frame under callgrind" : "");
  return 0;
fail:
  fprintf(stderr, "zscan bench suite: %s\n", err.msg);
  return 1;
}
