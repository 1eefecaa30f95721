/* zscan tools — `zscan bench suite`: every benchmark in one command. */
#ifndef ZS_TOOLS_BENCH_SUITE_H
#define ZS_TOOLS_BENCH_SUITE_H

int zs_cmd_bench_suite(int argc, char **argv);

#endif
