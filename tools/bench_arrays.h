/* zscan tools — `zscan bench arrays`: a scene built from arrays beside the
 * same mesh loaded from its OBJ file (bench_arrays.c). */
#ifndef ZS_TOOLS_BENCH_ARRAYS_H
#define ZS_TOOLS_BENCH_ARRAYS_H

/* argv[0] is "arrays".  Returns the process exit status. */
int zs_cmd_bench_arrays(int argc, char **argv);

#endif
