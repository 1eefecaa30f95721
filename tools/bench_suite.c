/* `zscan bench suite [--out DIR] [--quick]`: the documented suite, one
 * command, every file in DIR:
 *   raster.csv, .md, .png   bench raster: triangles of 4 to 500 pixels and
 *                           the whole scenes in both modes, one thread,
 *                           beside Mesa's llvmpipe on one thread when zscan
 *                           has it (--mesa), with the instructions per
 *                           frame when valgrind is there (--callgrind);
 *   raster-threads.csv, .md, .png, .txt   the same on every thread of the
 *                           machine, zscan and llvmpipe both, and zscan's
 *                           speed-up over one thread, frames in turn
 *                           (--speedup) (with --mesa and 2 threads or
 *                           more: a child process, as llvmpipe reads
 *                           LP_NUM_THREADS when it starts);
 *   tradeoff*.csv, .md, .png  bench tradeoff: run time against error, every
 *                           method and mode on every walk;
 *   depthsort.csv           bench depthsort: the depth-sort paper's Table 1;
 *   octree.csv, .png        bench octree: loose against plain octree updates.
 * --quick: one frame per raster case and no scenes or instruction counts,
 * the quick walks, fewer frames elsewhere: a check that it all runs. */
#include "tools/bench_suite.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "raster/raster.h"
#include "tools/bench_depthsort.h"
#include "tools/bench_octree.h"
#include "tools/bench_raster.h"
#include "tools/bench_tradeoff.h"
#include "tools/callgrind.h"
#include "tools/cli.h"
#include "tools/mesa.h"
#include "tools/outfile.h"
#include "tools/spawn.h"

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

/* bench raster on n threads beside llvmpipe on n, in a child process
 * (LP_NUM_THREADS=n), its output into path[9] and then here. */
static int run_all_threads(int n, char path[][4200], const char *size, zs_error *err) {
  char self[4096], threads[16];
  if (!zs_self_path(self, sizeof self))
    return zs_error_set(err, ZS_ERR_IO, "cannot find this program's path");
  snprintf(threads, sizeof threads, "%d", n);
  char *args[20] = {self,    "bench", "raster", "--threads", threads, "--mesa", "--speedup",
                    "--csv", path[6], "--md",     path[7], "--plot",  path[8]};
  int k = 13;
  if (size) {
    args[k++] = "--size";
    args[k++] = (char *)size;
  }
  args[k] = NULL;
  printf("\n$ LP_NUM_THREADS=%s zscan bench raster --threads %s --mesa --speedup ...\n", threads,
         threads);
  fflush(stdout);
  setenv("LP_NUM_THREADS", threads, 1);
  int rc = zs_spawn_wait(args, path[9], path[9]);
  setenv("LP_NUM_THREADS", "1", 1);
  zs_error_clear(err);
  zs_append_file(stdout, path[9], err); /* what it printed, here too */
  if (rc != 0) return zs_error_set(err, ZS_ERR_IO, "bench raster --threads %s failed (%s)", threads, path[9]);
  return 0;
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
  char path[10][4200];
  static const char *const names[10] = {
      "raster.csv",         "raster.md",         "raster.png",         "depthsort.csv",
      "octree.csv",         "octree.png",        "raster-threads.csv", "raster-threads.md",
      "raster-threads.png", "raster-threads.txt"};
  for (int k = 0; k < 10; k++) snprintf(path[k], sizeof path[k], "%s/%s", dir, names[k]);
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
  /* llvmpipe on one thread beside zscan's one */
  if (mesa && !quick) setenv("LP_NUM_THREADS", "1", 1);
  if (run(zs_cmd_bench_raster, raster)) return 1; /* the benchmark said why */
  long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
  if (ncpu > 64) ncpu = 64;
  const int all_threads = mesa && !quick && ncpu >= 2;
  if (all_threads && run_all_threads((int)ncpu, path, size, &err)) goto fail;
  if (run(zs_cmd_bench_tradeoff, tradeoff) || run(zs_cmd_bench_depthsort, depthsort) ||
      run(zs_cmd_bench_octree, octree))
    return 1;
  printf("\nwrote %s: raster, tradeoff (per walk), depthsort and octree files%s%s%s\n", dir,
         mesa && !quick ? "; llvmpipe beside zscan" : "",
         all_threads ? ", on one thread and on all" : "",
         callgrind ? "; instructions per frame under callgrind" : "");
  return 0;
fail:
  fprintf(stderr, "zscan bench suite: %s\n", err.msg);
  return 1;
}
