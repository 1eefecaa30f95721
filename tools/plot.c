#include "tools/plot.h"

#include "lib/outfile.h"
#include "util/exactmath.h"
#include "util/os.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int zs_plot_available(void) { return zs_os_program_available("gnuplot"); }

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
  char dir[4096], tmp_png[4200], tmp_gp[4200];
  int e = zs_os_scratch_dir("zscan-plot", dir, sizeof dir);
  if (e != 0)
    return zs_error_set(err, ZS_ERR_IO, "%s: cannot create a scratch folder: %s", png, strerror(e));
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
    if (zs_os_spawn_wait(args, NULL, NULL) != 0) st = zs_error_set(err, ZS_ERR_IO, "%s: gnuplot failed", png);
  }
  zs_out out;
  if (st == ZS_OK && (st = zs_out_open(&out, png, err)) == ZS_OK) {
    st = zs_append_file(out.fp, tmp_png, err);
    if (st == ZS_OK) st = zs_out_commit(&out, err);
    else zs_out_discard(&out);
  }
  remove(tmp_gp);
  remove(tmp_png);
  zs_os_rmdir(dir);
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

/* Labels "name value" for the points (x[i], v[i]) of a log-y panel whose
 * y range is [ylo, yhi]: points sorted by height, each label raised until
 * it clears the one below it in the same column (x within 15 % of the
 * range), so labels keep the points' order and carry their values.
 * gnuplot places text where it is told, so close points (several exact
 * methods at zero error) would otherwise print over each other. */
static void add_labels(char *script, size_t cap, size_t *len, const char *const *names,
                       const double *x, const double *v, int n, double xspan, double ylo,
                       double yhi) {
  int order[ZS_PLOT_TRADEOFF_MAX];
  double lab[ZS_PLOT_TRADEOFF_MAX];
  for (int i = 0; i < n; i++) order[i] = i;
  for (int i = 1; i < n; i++) /* insertion sort by height, then name order */
    for (int j = i; j > 0 && v[order[j]] < v[order[j - 1]]; j--) {
      int t = order[j];
      order[j] = order[j - 1];
      order[j - 1] = t;
    }
  const double gap = 0.05 * (zs_log10(yhi) - zs_log10(ylo));
  for (int a = 0; a < n; a++) {
    int i = order[a];
    double l = zs_log10(v[i] > 0 ? v[i] : ylo);
    for (int b = 0; b < a; b++) {
      int j = order[b];
      if (fabs(x[j] - x[i]) < 0.15 * xspan && l < lab[j] + gap) l = lab[j] + gap;
    }
    lab[i] = l;
  }
  for (int i = 0; i < n; i++)
    *len += (size_t)snprintf(script + *len, *len < cap ? cap - *len : 0,
                             "set label %d \"%s  %.3g\" at %.6g,%.6g offset 1.2,0 left font ',9'\n",
                             i + 1, names[i], v[i], x[i], zs_exp10(lab[i]));
}

zs_status zs_plot_tradeoff(const char *png, const char *scene, const char *const *names,
                           const double *wall, const double *model, const double *wrong, int n,
                           zs_error *err) {
  if (n > ZS_PLOT_TRADEOFF_MAX) return zs_error_set(err, ZS_ERR_ARG, "tradeoff plot: too many points");
  char script[16384];
  size_t len = 0;
#define ADD(...) len += (size_t)snprintf(script + len, len < sizeof script ? sizeof script - len : 0, __VA_ARGS__)
  ADD("$data << EOD\n");
  for (int i = 0; i < n; i++) ADD("\"%s\" %.3f %.6f %.6f\n", names[i], wrong[i], wall[i], model[i]);
  ADD("EOD\nset terminal pngcairo size 1200,560 font 'sans,11'\nset output OUT\n");
  ADD("set multiplot layout 1,2 title '%s: run time against error (one point per method)'\n",
      scene);
  double xmax = 1.0;
  for (int i = 0; i < n; i++) xmax = wrong[i] > xmax ? wrong[i] : xmax;
  const double xlo = -0.05 * xmax, xhi = 1.4 * xmax;
  ADD("set grid\nset key off\nset xlabel 'pixels wrong per frame (against none)'\n"
      "set xrange [%.3f:%.3f]\nset format x '%%.0s%%c'\nset logscale y\n", xlo, xhi);
  for (int panel = 0; panel < 2; panel++) {
    const double *v = panel ? model : wall;
    double lo = v[0], hi = v[0];
    for (int i = 0; i < n; i++) {
      lo = v[i] > 0 && v[i] < lo ? v[i] : lo;
      hi = v[i] > hi ? v[i] : hi;
    }
    if (!(lo > 0)) lo = 1e-3;
    lo /= 1.5;
    hi *= 2.5; /* room above for raised labels */
    ADD("unset label\nset yrange [%.6g:%.6g]\n", lo, hi);
    add_labels(script, sizeof script, &len, names, wrong, v, n, xhi - xlo, lo, hi);
    ADD("set ylabel '%s ms per frame'\nplot $data using 2:%d with points pt 7 ps 1.2\n",
        panel ? "modelled" : "median wall", panel ? 4 : 3);
  }
  ADD("unset multiplot\n");
#undef ADD
  if (len >= sizeof script) return zs_error_set(err, ZS_ERR_ARG, "tradeoff plot: too many points");
  return zs_plot_run(png, script, err);
}
