/* zscan tools — `zscan bench colours`: zscan's unlit colours beside
 * llvmpipe's (bench_colours.c). */
#ifndef ZS_TOOLS_BENCH_COLOURS_H
#define ZS_TOOLS_BENCH_COLOURS_H

/* argv[0] is "colours".  Returns the process exit status. */
int zs_cmd_bench_colours(int argc, char **argv);

#endif
