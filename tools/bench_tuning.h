/* zscan tools — the tuning outcomes of bench tradeoff: comparisons of
 * culling methods on small walks, printed with their figures. */
#ifndef ZS_TOOLS_BENCH_TUNING_H
#define ZS_TOOLS_BENCH_TUNING_H

#include <stdio.h>

#include "zscan/error.h"

zs_status zs_bench_tuning_report(FILE *f, zs_error *err);

#endif
