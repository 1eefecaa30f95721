/* zscan tools — the commands of `zscan` (zs_commands, in commands.c) and
 * of `zscan bench` (in cmd_bench.c), in one table each: name, arguments,
 * one line of summary, and the function that runs it (zscan's: zs_cmd_NAME
 * in tools/cmd_NAME.c; the benchmarks': in tools/bench_NAME.c).  A run
 * function takes argv[0] = its own name and returns the process exit
 * status: 0 success, 1 bad input (or, for diff, images that differ), 2 a
 * usage error. */
#ifndef ZS_TOOLS_COMMANDS_H
#define ZS_TOOLS_COMMANDS_H

typedef struct zs_command {
  const char *name;
  const char *args;    /* as the usage line shows them */
  const char *summary;
  int (*run)(int argc, char **argv);
} zs_command;

/* zscan's commands, in the order its usage lists them. */
extern const zs_command zs_commands[];
extern const int zs_ncommands;

int zs_cmd_render(int argc, char **argv);
int zs_cmd_diff(int argc, char **argv);
int zs_cmd_composite(int argc, char **argv);
int zs_cmd_golden(int argc, char **argv);
int zs_cmd_trace(int argc, char **argv);
int zs_cmd_teach(int argc, char **argv);
int zs_cmd_walk(int argc, char **argv);
int zs_cmd_path(int argc, char **argv);
int zs_cmd_query(int argc, char **argv);
int zs_cmd_calibrate(int argc, char **argv);
int zs_cmd_bench(int argc, char **argv);
int zs_cmd_bench_octree(int argc, char **argv);
int zs_cmd_bench_depthsort(int argc, char **argv);
int zs_cmd_bench_raster(int argc, char **argv);
int zs_cmd_bench_colours(int argc, char **argv);
int zs_cmd_bench_lines(int argc, char **argv);
int zs_cmd_bench_arrays(int argc, char **argv);
int zs_cmd_bench_samples(int argc, char **argv);
int zs_cmd_bench_tradeoff(int argc, char **argv);
int zs_cmd_bench_suite(int argc, char **argv);

/* Runs the command of table[0..n-1] that argv[1] names, with argv + 1;
 * prog ("zscan", "zscan bench") heads the usage, which goes to standard
 * output for --help and to standard error with exit 2 when the command is
 * missing or unknown. */
int zs_command_dispatch(const char *prog, const zs_command *table, int n, int argc, char **argv);

#endif
