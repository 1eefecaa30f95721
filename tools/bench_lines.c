/* `zscan bench lines [--size WxH] [--md FILE]`
 *
 * The line and point half of the cross-check with Mesa's llvmpipe
 * (tools/crosscheck_prims.h): at each width, 300 lines and 300 squares
 * scattered by a seeded generator, the pixels zscan covers, the share
 * whose primitive differs, and of those the ones at a line's end or a
 * point, the ones where an edge passes within 1/64 pixel of the centre,
 * and the rest, differences in the rule.  The figures are counts, the
 * same on every run; tests/test_mesa.c asserts the bounds. */
#include "tools/bench_lines.h"

#include <stdio.h>
#include <string.h>

#include "tools/bench_report.h"
#include "tools/cli.h"
#include "tools/crosscheck_prims.h"
#include "tools/mesa.h"

static const char usage[] =
    "usage: zscan bench lines [--size WxH] [--md FILE]\n"
    "  zscan's wide lines and points beside llvmpipe's (OSMesa), 300 of each at\n"
    "  widths 1 to 8: the pixels whose primitive differs, at the ends, by rounding\n"
    "  (an edge within 1/64 pixel of the centre) and in the rule itself.\n"
    "  --size WxH   the image size (default 512x384)\n"
    "  --md FILE    the table in Markdown\n";

static const int widths[] = {1, 2, 3, 4, 5, 8};
enum { NWIDTHS = sizeof widths / sizeof widths[0], NPRIMS = 300 };

static void write_rows(FILE *f, const void *rows, int md) {
  const zs_prim_check *x = rows;
  if (md)
    fprintf(f, "| width and size | pixels covered | differ | at the ends | rounding | in the "
               "rule |\n|---|---|---|---|---|---|\n");
  else
    fprintf(f, "%-6s %8s %8s %9s %6s %9s %5s\n", "width", "covered", "differ", "differ_%",
            "ends", "rounding", "rule");
  for (int i = 0; i < NWIDTHS; i++) {
    const double share = x[i].covered ? 100.0 * (double)x[i].differ / (double)x[i].covered : 0;
    const unsigned long long rule = x[i].differ - x[i].at_ends - x[i].rounding;
    if (md)
      fprintf(f, "| %d | %llu | %llu (%.3f %%) | %llu | %llu | %llu |\n", widths[i],
              (unsigned long long)x[i].covered, (unsigned long long)x[i].differ, share,
              (unsigned long long)x[i].at_ends, (unsigned long long)x[i].rounding, rule);
    else
      fprintf(f, "%-6d %8llu %8llu %9.3f %6llu %9llu %5llu\n", widths[i],
              (unsigned long long)x[i].covered, (unsigned long long)x[i].differ, share,
              (unsigned long long)x[i].at_ends, (unsigned long long)x[i].rounding, rule);
  }
}

int zs_cmd_bench_lines(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, NULL)) return 0;
  zs_error err;
  zs_error_clear(&err);
  int w = 512, h = 384, parsing = 1;
  const char *md = NULL;
  zs_status st = zs_bench_size_md_args(argc, argv, "lines", &w, &h, &md, &err);
  if (!st && !zs_mesa_available())
    st = zs_error_set(&err, ZS_ERR_UNSUPPORTED,
                      "zscan was built without OSMesa (install libosmesa6-dev, rebuild)");
  if (!st) parsing = 0;
  zs_prim_check x[NWIDTHS];
  /* the seeds tests/test_mesa.c uses: the same scenes */
  for (int i = 0; i < NWIDTHS && !st; i++)
    st = zs_crosscheck_prims(w, h, 7 + (uint64_t)i, NPRIMS, NPRIMS, widths[i], widths[i], &x[i],
                             &err);
  if (!st) {
    char title[96];
    snprintf(title, sizeof title, "zscan and llvmpipe lines and points at %dx%d, %d of each", w,
             h, NPRIMS);
    st = zs_bench_report(md, title, write_rows, x, &err);
  }
  return st ? zs_cli_fail("zscan bench lines", &err, parsing) : 0;
}
