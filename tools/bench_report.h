/* zscan tools — the shape the cross-check benchmarks share (bench
 * colours, bench lines): `[--size WxH] [--md FILE]`, a table on stdout
 * and the same table in Markdown. */
#ifndef ZS_TOOLS_BENCH_REPORT_H
#define ZS_TOOLS_BENCH_REPORT_H

#include <stdio.h>

#include "zscan/error.h"

/* Reads argv[1..] of `zscan bench NAME`: --size into *w, *h, --md into
 * *md; anything else is an error naming NAME's --help. */
zs_status zs_bench_size_md_args(int argc, char **argv, const char *name, int *w, int *h,
                                const char **md, zs_error *err);

/* Whether argv[1..] holds flag; each one is taken out (argc lessened), so
 * the rest reads as zs_bench_size_md_args reads it. */
int zs_bench_take_flag(int *argc, char **argv, const char *flag);

/* Prints title and table(f, rows, 0) on stdout (standard error when md is
 * "-"), then writes table(f, rows, 1) to md (when not NULL) safely,
 * saying so; an error in err names --md. */
zs_status zs_bench_report(const char *md, const char *title,
                          void (*table)(FILE *f, const void *rows, int md), const void *rows,
                          zs_error *err);

#endif
