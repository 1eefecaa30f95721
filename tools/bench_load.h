/* zscan tools — how long the generated scenes take to build: the load
 * times bench tradeoff reports for its walks' scenes. */
#ifndef ZS_TOOLS_BENCH_LOAD_H
#define ZS_TOOLS_BENCH_LOAD_H

#include <stdio.h>

#include "zscan/error.h"

/* Loads each of specs[0..n-1] (INPUT forms: builtin:NAME,k=v) once and
 * prints its wall time with its objects and triangles. */
zs_status zs_bench_load_report(FILE *f, const char *const *specs, int n, zs_error *err);

#endif
