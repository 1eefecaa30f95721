/* zscan tools — `zscan bench samples`: anti-aliasing's cost, and each
 * sample's coverage against llvmpipe's (bench_samples.c). */
#ifndef ZS_TOOLS_BENCH_SAMPLES_H
#define ZS_TOOLS_BENCH_SAMPLES_H

/* argv[0] is "samples".  Returns the process exit status. */
int zs_cmd_bench_samples(int argc, char **argv);

#endif
