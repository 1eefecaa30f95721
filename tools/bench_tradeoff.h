/* zscan tools — `zscan bench tradeoff`: run time against error on every walk. */
#ifndef ZS_TOOLS_BENCH_TRADEOFF_H
#define ZS_TOOLS_BENCH_TRADEOFF_H

int zs_cmd_bench_tradeoff(int argc, char **argv);

#endif
