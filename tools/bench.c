/* `zscan bench WHAT [options]`: dispatches to the benchmarks.  Each
 * measures and reports (a table on stdout, --csv, --plot); none asserts. */
#include "tools/bench.h"

#include <stdio.h>
#include <string.h>

#include "tools/bench_depthsort.h"
#include "tools/bench_octree.h"
#include "tools/bench_raster.h"
#include "tools/bench_suite.h"
#include "tools/bench_tradeoff.h"

static const char usage[] =
    "usage: zscan bench WHAT [options]\n"
    "  octree      loose vs plain octree update with moving spheres (zscan bench octree --help)\n"
    "  depthsort   depth sort with and without frame coherence, four camera motions\n"
    "  raster      throughput: triangles of 4 to 500 pixels and whole scenes, both modes\n"
    "  tradeoff    run time against error: every method and mode on every walk\n"
    "  suite       all of them, every file in one directory\n";

int zs_cmd_bench(int argc, char **argv) {
  if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
    fputs(usage, argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  if (strcmp(argv[1], "octree") == 0) return zs_cmd_bench_octree(argc - 1, argv + 1);
  if (strcmp(argv[1], "depthsort") == 0) return zs_cmd_bench_depthsort(argc - 1, argv + 1);
  if (strcmp(argv[1], "raster") == 0) return zs_cmd_bench_raster(argc - 1, argv + 1);
  if (strcmp(argv[1], "tradeoff") == 0) return zs_cmd_bench_tradeoff(argc - 1, argv + 1);
  if (strcmp(argv[1], "suite") == 0) return zs_cmd_bench_suite(argc - 1, argv + 1);
  fprintf(stderr, "zscan bench: unknown benchmark '%s'\n%s", argv[1], usage);
  return 2;
}
