/* zscan tools — `zscan bench lines`: zscan's lines and points beside
 * llvmpipe's (bench_lines.c). */
#ifndef ZS_TOOLS_BENCH_LINES_H
#define ZS_TOOLS_BENCH_LINES_H

/* argv[0] is "lines".  Returns the process exit status. */
int zs_cmd_bench_lines(int argc, char **argv);

#endif
