/* `zscan bench WHAT [options]`: dispatches to the benchmarks.  Each
 * measures and reports (a table on stdout, --csv, --plot); none asserts. */
#include "tools/commands.h"

static const zs_command benchmarks[] = {
    {"octree", "", "loose vs plain octree update with moving spheres", zs_cmd_bench_octree},
    {"depthsort", "[INPUT]", "depth sort with and without frame coherence, four motions",
     zs_cmd_bench_depthsort},
    {"colours", "", "unlit vertex colours and textures beside llvmpipe's, pixel by pixel",
     zs_cmd_bench_colours},
    {"arrays", "", "a mesh built from arrays beside the same mesh loaded from its OBJ file",
     zs_cmd_bench_arrays},
    {"lines", "", "wide lines and points beside llvmpipe's, pixel by pixel", zs_cmd_bench_lines},
    {"raster", "", "throughput: triangles of 4 to 500 pixels and whole scenes", zs_cmd_bench_raster},
    {"samples", "", "anti-aliasing: one sample and four, and each sample beside llvmpipe's",
     zs_cmd_bench_samples},
    {"tradeoff", "", "run time against error: every method and mode on every walk",
     zs_cmd_bench_tradeoff},
    {"suite", "", "all of them, every file in one directory", zs_cmd_bench_suite},
};

int zs_cmd_bench(int argc, char **argv) {
  return zs_command_dispatch("zscan bench", benchmarks,
                             (int)(sizeof benchmarks / sizeof benchmarks[0]), argc, argv);
}
