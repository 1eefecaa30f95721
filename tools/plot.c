#include "tools/plot.h"

#include "tools/spawn.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int zs_plot_available(void) { return zs_program_available("gnuplot"); }

/* s as a gnuplot single-quoted string: quotes doubled. */
static void quoted(FILE *f, const char *s) {
  fputc('\'', f);
  for (; *s; s++) {
    if (*s == '\'') fputc('\'', f);
    fputc(*s, f);
  }
  fputc('\'', f);
}

zs_status zs_plot_run(const char *png, const char *script, zs_error *err) {
  if (!zs_plot_available())
    return zs_error_set(err, ZS_ERR_IO, "%s: gnuplot is not installed (apt-get install gnuplot-nox)",
                        png);
  char tmp_png[4200], tmp_gp[4200];
  snprintf(tmp_png, sizeof tmp_png, "%s.tmp.png", png);
  snprintf(tmp_gp, sizeof tmp_gp, "%s.tmp.gp", png);
  FILE *f = fopen(tmp_gp, "w");
  if (!f) return zs_error_set(err, ZS_ERR_IO, "%s: cannot write: %s", tmp_gp, strerror(errno));
  fputs("OUT = ", f);
  quoted(f, tmp_png);
  fputs("\n", f);
  fputs(script, f);
  if (fclose(f) != 0) {
    unlink(tmp_gp);
    return zs_error_set(err, ZS_ERR_IO, "%s: cannot write", tmp_gp);
  }
  char *args[] = {"gnuplot", tmp_gp, NULL};
  int rc = zs_spawn_wait(args, NULL, NULL);
  unlink(tmp_gp);
  if (rc != 0) {
    unlink(tmp_png);
    return zs_error_set(err, ZS_ERR_IO, "%s: gnuplot failed", png);
  }
  if (rename(tmp_png, png) != 0) {
    unlink(tmp_png);
    return zs_error_set(err, ZS_ERR_IO, "%s: cannot write: %s", png, strerror(errno));
  }
  return ZS_OK;
}

zs_status zs_plot_series(const char *png, const char *title, const char *xlabel,
                         const char *ylabel, const double *y, int n, int nseries,
                         const char *const *names, double x0, double dx, int logy, zs_error *err) {
  char dat[4200];
  snprintf(dat, sizeof dat, "%s.tmp.dat", png);
  FILE *f = fopen(dat, "w");
  if (!f) return zs_error_set(err, ZS_ERR_IO, "%s: cannot write: %s", dat, strerror(errno));
  for (int i = 0; i < n; i++) {
    fprintf(f, "%.9g", x0 + i * dx);
    for (int j = 0; j < nseries; j++) fprintf(f, " %.9g", y[(size_t)i * (size_t)nseries + (size_t)j]);
    fputc('\n', f);
  }
  fclose(f);
  size_t cap = 4096 + (size_t)nseries * 256;
  char *script = malloc(cap);
  if (!script) {
    unlink(dat);
    return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  }
  int len = snprintf(script, cap,
                     "set terminal pngcairo size 1000,560 noenhanced\n"
                     "set output OUT\nset title '%s'\nset xlabel '%s'\nset ylabel '%s'\n"
                     "set key outside right\nset grid\n%splot ",
                     title, xlabel, ylabel, logy ? "set logscale y\n" : "");
  /* gnuplot's own palette has 8 colours and repeats them; walks compare
   * more methods than that.  12 distinct colours, then dashes. */
  static const char *const colour[12] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                         "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
                                         "#bcbd22", "#17becf", "#000000", "#aec7e8"};
  for (int j = 0; j < nseries && len > 0 && (size_t)len < cap; j++)
    len += snprintf(script + len, cap - (size_t)len,
                    "%s'%s' using 1:%d with lines lw 2 lc rgb '%s' dt %d title '%s'",
                    j ? ", " : "", dat, j + 2, colour[j % 12], 1 + j / 12, names[j]);
  if (len > 0 && (size_t)len < cap) snprintf(script + len, cap - (size_t)len, "\n");
  zs_status st = zs_plot_run(png, script, err);
  free(script);
  unlink(dat);
  return st;
}
