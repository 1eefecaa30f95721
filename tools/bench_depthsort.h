/* zscan tools — `zscan bench depthsort`: the depth-sort paper's Table 1. */
#ifndef ZS_TOOLS_BENCH_DEPTHSORT_H
#define ZS_TOOLS_BENCH_DEPTHSORT_H

int zs_cmd_bench_depthsort(int argc, char **argv);

#endif
