#include "tools/plot.h"

#include "lib/outfile.h"
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

/* gnuplot draws into a private scratch folder; the finished PNG is then
 * copied through the output primitive, so a plot's path is treated like
 * every other output (a link followed, a device written directly). */
zs_status zs_plot_run(const char *png, const char *script, zs_error *err) {
  if (!zs_plot_available())
    return zs_error_set(err, ZS_ERR_IO, "%s: gnuplot is not installed (apt-get install gnuplot-nox)",
                        png);
  const char *tmpdir = getenv("TMPDIR");
  char dir[4096], tmp_png[4200], tmp_gp[4200];
  snprintf(dir, sizeof dir, "%s/zscan-plot-XXXXXX", tmpdir && *tmpdir ? tmpdir : "/tmp");
  if (!mkdtemp(dir))
    return zs_error_set(err, ZS_ERR_IO, "%s: cannot create a scratch folder: %s", png,
                        strerror(errno));
  snprintf(tmp_png, sizeof tmp_png, "%s/plot.png", dir);
  snprintf(tmp_gp, sizeof tmp_gp, "%s/plot.gp", dir);
  zs_status st = ZS_OK;
  FILE *f = fopen(tmp_gp, "w");
  if (f) {
    fputs("OUT = ", f);
    quoted(f, tmp_png);
    fputs("\n", f);
    fputs(script, f);
  }
  if (!f || fclose(f) != 0) {
    st = zs_error_set(err, ZS_ERR_IO, "%s: cannot write the gnuplot script", png);
  } else {
    char *args[] = {"gnuplot", tmp_gp, NULL};
    if (zs_spawn_wait(args, NULL, NULL) != 0) st = zs_error_set(err, ZS_ERR_IO, "%s: gnuplot failed", png);
  }
  zs_out out;
  if (st == ZS_OK && (st = zs_out_open(&out, png, err)) == ZS_OK) {
    st = zs_append_file(out.fp, tmp_png, err);
    if (st == ZS_OK) st = zs_out_commit(&out, err);
    else zs_out_discard(&out);
  }
  unlink(tmp_gp);
  unlink(tmp_png);
  rmdir(dir);
  return st;
}

zs_status zs_plot_series(const char *png, const char *title, const char *xlabel,
                         const char *ylabel, const double *y, int n, int nseries,
                         const char *const *names, double x0, double dx, int logy, zs_error *err) {
  /* the data inline, as a datablock: no data file beside the plot */
  size_t cap = 4096 + (size_t)nseries * 256 + (size_t)n * (size_t)(nseries + 1) * 18;
  char *script = malloc(cap);
  if (!script) return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  int len = snprintf(script, cap, "$data << EOD\n");
  for (int i = 0; i < n && len > 0 && (size_t)len < cap; i++) {
    len += snprintf(script + len, cap - (size_t)len, "%.9g", x0 + i * dx);
    for (int j = 0; j < nseries && (size_t)len < cap; j++)
      len += snprintf(script + len, cap - (size_t)len, " %.9g",
                      y[(size_t)i * (size_t)nseries + (size_t)j]);
    if ((size_t)len < cap) len += snprintf(script + len, cap - (size_t)len, "\n");
  }
  if ((size_t)len < cap)
    len += snprintf(script + len, cap - (size_t)len,
                     "EOD\nset terminal pngcairo size 1000,560 noenhanced\n"
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
                    "%s$data using 1:%d with lines lw 2 lc rgb '%s' dt %d title '%s'",
                    j ? ", " : "", j + 2, colour[j % 12], 1 + j / 12, names[j]);
  zs_status st = len > 0 && (size_t)len + 1 < cap
                     ? (strcat(script, "\n"), zs_plot_run(png, script, err))
                     : zs_error_set(err, ZS_ERR_NOMEM, "%s: plot script too long", png);
  free(script);
  return st;
}
