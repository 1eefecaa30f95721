/* The cross-check benchmarks' options and reports (bench_report.h). */
#include "tools/bench_report.h"

#include <string.h>

#include "lib/outfile.h"
#include "tools/cli.h"
#include "zscan/zscan.h"

zs_status zs_bench_size_md_args(int argc, char **argv, const char *name, int *w, int *h,
                                const char **md, zs_error *err) {
  zs_status st = ZS_OK;
  for (int i = 1; i < argc && !st; i++) {
    if (strcmp(argv[i], "--size") == 0)
      st = zs_cli_size_value(argc, argv, &i, ZS_MAX_IMAGE_SIDE, w, h, err);
    else if (strcmp(argv[i], "--md") == 0)
      st = zs_cli_output_value(argc, argv, &i, md, err);
    else
      st = zs_error_set(err, ZS_ERR_ARG, "%s '%s' (see zscan bench %s --help)",
                        argv[i][0] == '-' ? "unknown option" : "unexpected argument", argv[i],
                        name);
  }
  return st;
}

zs_status zs_bench_report(const char *md, const char *title,
                          void (*table)(FILE *f, const void *rows, int md), const void *rows,
                          zs_error *err) {
  FILE *report = stdout;
  const char *outs[] = {md};
  zs_status st = zs_out_report(outs, 1, "--md", &report, err);
  if (st) return st;
  fprintf(report, "%s\n", title);
  table(report, rows, 0);
  if (!md) return ZS_OK;
  zs_out out;
  if (!(st = zs_out_open(&out, md, err))) {
    table(out.fp, rows, 1);
    st = zs_out_commit(&out, err);
  }
  if (st) zs_out_error_option(err, "--md");
  else if (!zs_out_is_stdout(md)) fprintf(report, "wrote %s\n", md);
  return st;
}

int zs_bench_take_flag(int *argc, char **argv, const char *flag) {
  int found = 0;
  for (int i = 1; i < *argc; i++)
    if (strcmp(argv[i], flag) == 0) {
      found = 1;
      memmove(argv + i, argv + i + 1, (size_t)(*argc - i) * sizeof *argv);
      (*argc)--, i--;
    }
  return found;
}
