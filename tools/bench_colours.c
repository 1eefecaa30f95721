/* `zscan bench colours [--size WxH] [--md FILE]`
 *
 * The colour half of the cross-check with Mesa's llvmpipe
 * (tools/crosscheck_colours.h): each case's covered pixels, the share
 * within its bound a channel, the share exact and the largest difference,
 * as a table on stdout and in Markdown (--md) for docs/RESULTS.md.  The
 * figures are counts, the same on every run; tests/test_mesa.c asserts
 * the bounds.  Inputs are named relative to the source tree: run it
 * there.  A case whose model is not installed is a row saying so. */
#include "tools/bench_colours.h"

#include <stdio.h>
#include <string.h>

#include "util/os.h"

#include "tools/bench_report.h"
#include "tools/cli.h"
#include "tools/crosscheck_colours.h"
#include "tools/mesa.h"

static const char usage[] =
    "usage: zscan bench colours [--size WxH] [--md FILE]\n"
    "  zscan's unlit shading beside llvmpipe's (OSMesa) on vertex-coloured and\n"
    "  textured scenes at each filter: of the pixels zscan covers, the share\n"
    "  within the case's bound a channel, the share exact, the largest difference.\n"
    "  Run it in the source tree (the cases name its files).\n"
    "  --size WxH   the image size (default 512x384)\n"
    "  --md FILE    the table in Markdown\n";

typedef struct row {
  const zs_colour_case *c;
  int missing; /* the model is not installed (or needs assimp) */
  char why[160];
  zs_colour_check x;
} row;

static double pct(uint64_t part, uint64_t whole) {
  return whole ? 100.0 * (double)part / (double)whole : 0.0;
}

static void write_table(FILE *f, const row *rows, int n, int md) {
  if (md) {
    fprintf(f, "| input | filter | pixels covered | within | share within | share exact | "
               "largest difference |\n|---|---|---|---|---|---|---|\n");
  } else {
    fprintf(f, "%-58s %-9s %8s %6s %9s %9s %7s\n", "input", "filter", "covered", "within",
            "share_%", "exact_%", "largest");
  }
  for (int i = 0; i < n; i++) {
    const row *r = &rows[i];
    const char *filter = zs_filter_name(r->c->filter);
    if (r->missing) {
      if (md) fprintf(f, "| `%s` | %s | %s | | | | |\n", r->c->input, filter, r->why);
      else fprintf(f, "%-58s %-9s %s\n", r->c->input, filter, r->why);
      continue;
    }
    const double within = pct(r->x.close, r->x.covered), exact = pct(r->x.exact, r->x.covered);
    if (md)
      fprintf(f, "| `%s` | %s | %llu | %d | %.3f %% | %.3f %% | %d |\n", r->c->input, filter,
              (unsigned long long)r->x.covered, r->c->max_diff, within, exact, r->x.worst);
    else
      fprintf(f, "%-58s %-9s %8llu %6d %9.3f %9.3f %7d\n", r->c->input, filter,
              (unsigned long long)r->x.covered, r->c->max_diff, within, exact, r->x.worst);
  }
}

typedef struct table_of {
  const row *rows;
  int n;
} table_of;

static void write_rows(FILE *f, const void *t, int md) {
  const table_of *tt = t;
  write_table(f, tt->rows, tt->n, md);
}

int zs_cmd_bench_colours(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, NULL)) return 0;
  zs_error err;
  zs_error_clear(&err);
  int w = 512, h = 384, parsing = 1;
  const char *md = NULL;
  zs_status st = zs_bench_size_md_args(argc, argv, "colours", &w, &h, &md, &err);
  if (!st && !zs_mesa_available())
    st = zs_error_set(&err, ZS_ERR_UNSUPPORTED,
                      "zscan was built without OSMesa (install libosmesa6-dev, rebuild)");
  if (!st) parsing = 0;
  row rows[32];
  const int n = zs_ncolour_cases < 32 ? zs_ncolour_cases : 32;
  for (int i = 0; i < n && !st; i++) {
    row *r = &rows[i];
    memset(r, 0, sizeof *r);
    r->c = &zs_colour_cases[i];
    if (r->c->input[0] == '/' && !zs_os_readable(r->c->input)) {
      r->missing = 1;
      snprintf(r->why, sizeof r->why, "not installed");
      continue;
    }
    zs_error e;
    zs_error_clear(&e);
    const zs_status cs = zs_crosscheck_colours(r->c, r->c->input, w, h, &r->x, &e);
    if (cs == ZS_ERR_UNSUPPORTED && strstr(e.msg, "assimp")) {
      r->missing = 1;
      snprintf(r->why, sizeof r->why, "needs assimp");
    } else if (cs) {
      st = cs;
      err = e;
    }
  }
  if (!st) {
    char title[96];
    snprintf(title, sizeof title, "zscan unlit and llvmpipe at %dx%d, pixels zscan covers", w, h);
    const table_of t = {rows, n};
    st = zs_bench_report(md, title, write_rows, &t, &err);
  }
  return st ? zs_cli_fail("zscan bench colours", &err, parsing) : 0;
}
