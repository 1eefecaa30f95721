/* zscan tools — plots through gnuplot (Debian's gnuplot-nox).
 *
 * gnuplot draws into a private scratch folder; the PNG reaches its path
 * through the output primitive (lib/outfile.h) only when gnuplot
 * succeeded: no half-written plot is ever left. */
#ifndef ZS_TOOLS_PLOT_H
#define ZS_TOOLS_PLOT_H

#include "zscan/error.h"

/* Whether gnuplot can be run (found on PATH). */
int zs_plot_available(void);

/* Lines: y[i * nseries + j] is series j at x = x0 + i dx (i = 0 .. n-1);
 * logy: a logarithmic y axis. */
zs_status zs_plot_series(const char *png, const char *title, const char *xlabel,
                         const char *ylabel, const double *y, int n, int nseries,
                         const char *const *names, double x0, double dx, int logy, zs_error *err);

/* Run time against error, one labelled point per row i (a method or a
 * mode), in two panels: wall[i] and model[i] (ms per frame, log scale)
 * against wrong[i] (pixels wrong per frame); scene names the title.  At
 * most ZS_PLOT_TRADEOFF_MAX rows. */
#define ZS_PLOT_TRADEOFF_MAX 32
zs_status zs_plot_tradeoff(const char *png, const char *scene, const char *const *names,
                           const double *wall, const double *model, const double *wrong, int n,
                           zs_error *err);

/* Runs gnuplot on script, which must `set output` to the path it is given
 * as its %s-free variable OUT (the temporary PNG): the script text is
 * prefixed with `OUT = '...'`.  The result is written to png. */
zs_status zs_plot_run(const char *png, const char *script, zs_error *err);

#endif
