/* zscan tools — `zscan bench WHAT`: the benchmarks (octree, ...). */
#ifndef ZS_TOOLS_BENCH_H
#define ZS_TOOLS_BENCH_H

int zs_cmd_bench(int argc, char **argv);

#endif
