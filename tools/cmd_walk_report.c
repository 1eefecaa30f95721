/* `zscan walk`'s reports: the CSV's rows, the summary (the paper's Table 2
 * per frame on average, the GPU's share, ideal-box's churn), and the
 * Markdown table and plots asked for. */
#include "tools/cmd_walk.h"

#include <string.h>

#include "lib/outfile.h"
#include "tools/cli.h"
#include "tools/plot.h"

_Static_assert(ZS_CULL_METHODS + 2 <= ZS_PLOT_TRADEOFF_MAX, "a walk's rows fit the tradeoff plot");

void zs_cmd_walk_gpu_split_ms(const zs_device *d, double ms[4]) {
  const zs_gpu_split g = zs_clock_gpu_split(d);
  ms[0] = g.draw_ps * 1e-9;
  ms[1] = g.query_ps * 1e-9;
  ms[2] = g.switch_ps * 1e-9;
  ms[3] = g.idle_ps * 1e-9;
}

void zs_cmd_walk_csv_header(FILE *f) {
  fprintf(f, "frame,method,chosen,modelled_ms,stall_ms,wall_ms,queries,queries_hidden,"
             "faces_drawn,objects_drawn,nodes_visited,diff_pixels,"
             "gpu_draw_ms,gpu_query_ms,gpu_switch_ms,gpu_idle_ms,"
             "hzb_phase1,hzb_phase2,hzb_stale,hzb_boxes,hzb_texels,hzb_reads\n");
}

void zs_cmd_walk_csv_method(FILE *f, int frame, const zs_cmd_walk_method *r,
                            const zs_cull_stats *cs, double modelled, double stall, double wall,
                            const double split[4], int has_reference, uint64_t diff) {
  char diff_text[32] = ""; /* empty without a reference */
  if (has_reference) snprintf(diff_text, sizeof diff_text, "%llu", (unsigned long long)diff);
  const zs_clock_stats *clock = zs_device_clock(r->dev);
  fprintf(f,
          "%d,%s,%s,%.6f,%.6f,%.3f,%llu,%llu,%llu,%llu,%llu,%s,%.6f,%.6f,%.6f,%.6f,%llu,%llu,%llu,"
          "%llu,%llu,%llu\n",
          frame, zs_cull_method_name(r->m), zs_cull_method_name(cs->chosen), modelled, stall, wall,
          (unsigned long long)cs->queries, (unsigned long long)cs->queries_hidden,
          (unsigned long long)cs->faces_drawn, (unsigned long long)cs->objects_drawn,
          (unsigned long long)cs->nodes_visited, diff_text, split[0], split[1], split[2],
          split[3], (unsigned long long)cs->hzb_phase1, (unsigned long long)cs->hzb_phase2,
          (unsigned long long)cs->hzb_stale, (unsigned long long)clock->hzb_boxes,
          (unsigned long long)clock->hzb_texels, (unsigned long long)clock->hzb_reads);
}

void zs_cmd_walk_csv_algo(FILE *f, int frame, const zs_cmd_walk_algo *r, double modelled,
                          double wall, uint64_t faces, int objects, uint64_t diff) {
  double split[4];
  zs_cmd_walk_gpu_split_ms(r->dev, split);
  fprintf(f, "%d,%s,-,%.6f,0,%.3f,0,0,%llu,%d,0,%llu,%.6f,%.6f,%.6f,%.6f,0,0,0,0,0,0\n", frame,
          zs_algo_name(r->a), modelled, wall, (unsigned long long)faces, objects,
          (unsigned long long)diff, split[0], split[1], split[2], split[3]);
}

/* One line of the summary: a method's or a mode's means per frame. */
typedef struct summary_row {
  const char *name;
  double queries, faces, objects, modelled_ms, stall_ms, wall_ms;
  uint64_t diff_pixels; /* over all frames */
} summary_row;

/* The rows of the summary: the methods, then the modes; the ideal's
 * modelled ms a frame into *ideal_ms (0 when it did not run). */
static int summary_rows(const zs_cmd_walk_result *w, summary_row *rows, double *ideal_ms) {
  const double frames = w->frames;
  *ideal_ms = 0.0;
  for (int k = 0; k < w->nmethods; k++) {
    const zs_cmd_walk_method *r = &w->runs[k];
    rows[k] = (summary_row){zs_cull_method_name(r->m), r->queries / frames, r->faces / frames,
                            r->objects / frames, r->modelled_ms / frames, r->stall_ms / frames,
                            r->wall_ms / frames, r->diff_pixels};
    if (r->m == ZS_CULL_IDEAL) *ideal_ms = r->modelled_ms / frames;
  }
  for (int k = 0; k < w->nalgos; k++) {
    const zs_cmd_walk_algo *r = &w->algos[k];
    rows[w->nmethods + k] = (summary_row){zs_algo_name(r->a), 0.0, r->faces / frames,
                                          (double)w->objects, r->modelled_ms / frames, 0.0,
                                          r->wall_ms / frames, r->diff_pixels};
  }
  return w->nmethods + w->nalgos;
}

/* ideal_ms > 0: the ideal ran, and a column gives each row's modelled
 * time over the ideal's.  The columns have the CSV's names in the table
 * and in Markdown alike: means per frame, but diff_pixels over all
 * frames. */
static void write_summary(FILE *f, int md, const summary_row *rows, int n, double ideal_ms,
                          int has_reference) {
  const int x = ideal_ms > 0;
  if (md)
    fprintf(f, "| method | queries | faces_drawn | objects_drawn | modelled_ms | %s"
               "modelled_fps | stall_ms | wall_ms | diff_pixels |\n"
               "|---|---|---|---|---|%s---|---|---|---|\n",
            x ? "x_ideal | " : "", x ? "---|" : "");
  else
    fprintf(f, "%-13s %9s %12s %13s %11s %s%12s %9s %9s %11s\n", "method", "queries",
            "faces_drawn", "objects_drawn", "modelled_ms", x ? "  x_ideal " : "", "modelled_fps",
            "stall_ms", "wall_ms", "diff_pixels");
  for (int k = 0; k < n; k++) {
    const summary_row *r = &rows[k];
    double fps = r->modelled_ms > 0 ? 1000.0 / r->modelled_ms : 0.0;
    char ratio[32] = "";
    if (x) snprintf(ratio, sizeof ratio, md ? "%.3f | " : "%9.3f ", r->modelled_ms / ideal_ms);
    char diff[32] = "-"; /* no reference, no comparison */
    if (has_reference) snprintf(diff, sizeof diff, "%llu", (unsigned long long)r->diff_pixels);
    fprintf(f,
            md ? "| %s | %.1f | %.0f | %.1f | %.3f | %s%.1f | %.3f | %.3f | %s |\n"
               : "%-13s %9.1f %12.0f %13.1f %11.3f %s%12.1f %9.3f %9.3f %11s\n",
            r->name, r->queries, r->faces, r->objects, r->modelled_ms, ratio, fps, r->stall_ms,
            r->wall_ms, diff);
  }
}

/* What carrying visibility over from the last frame must cost at the
 * least a method that finds each change with a query (cull/churn.h). */
static void write_churn(FILE *f, const zs_cmd_walk_method *r, int frames) {
  const double n = frames - 1;
  fprintf(f, "\nideal-box's set against the frame before, objects a frame (frames 2 to %d)\n"
             "  in the set %.1f; entered %.1f (%.1f from outside the frustum); "
             "left %.1f (%.1f to outside the frustum)\n"
             "the least a method that learns from the last frame pays for it over ideal-box, "
             "ms a frame\n"
             "  a query's call for each change, asking nowhere else: %.3f\n"
             "  asking the last frame's set fewest pixels first, the best cut-off each frame: %.3f\n",
          frames, r->set_size / n, r->entered / n, r->entered_outside / n, r->left / n,
          r->left_outside / n, r->known_ms / n, r->ranked_ms / n);
}

void zs_cmd_walk_report(FILE *f, const zs_cmd_walk_result *w) {
  summary_row rows[ZS_CULL_METHODS + 2];
  double ideal_ms;
  const int n = summary_rows(w, rows, &ideal_ms);
  const int frames = w->frames;
  fprintf(f, "%s: %d frames at %dx%d, %d objects, %llu faces\n", w->scene, frames, w->width,
          w->height, w->objects, (unsigned long long)w->faces);
  write_summary(f, 0, rows, n, ideal_ms, w->has_reference);
  /* Where each method's modelled frame goes on the GPU: a method that
   * draws less but leaves the GPU idle, or pays in queries and switches,
   * shows it here. */
  fprintf(f, "\nthe GPU's share of the modelled frame, ms a frame\n%-13s %9s %9s %9s %9s\n",
          "method", "draw", "query", "switch", "idle");
  for (int k = 0; k < w->nmethods; k++) {
    const double *g = w->runs[k].gpu_ms;
    fprintf(f, "%-13s %9.3f %9.3f %9.3f %9.3f\n", zs_cull_method_name(w->runs[k].m),
            g[0] / frames, g[1] / frames, g[2] / frames, g[3] / frames);
  }
  for (int k = 0; k < w->nmethods && frames > 1; k++)
    if (w->runs[k].m == ZS_CULL_IDEAL_BOX) write_churn(f, &w->runs[k], frames);
}

static zs_status write_md(const char *path, const zs_cmd_walk_result *w, zs_error *err) {
  summary_row rows[ZS_CULL_METHODS + 2];
  double ideal_ms;
  const int n = summary_rows(w, rows, &ideal_ms);
  zs_out md;
  if (zs_out_open(&md, path, err)) return err->code;
  write_summary(md.fp, 1, rows, n, ideal_ms, w->has_reference);
  return zs_out_commit(&md, err);
}

/* Time against pixels wrong, one point per method and mode: wall
 * (median) and modelled ms per frame against the mean pixels wrong per
 * frame. */
static zs_status write_tradeoff(const char *path, const zs_cmd_walk_result *w, zs_error *err) {
  const char *names[ZS_CULL_METHODS + 2];
  double wall[ZS_CULL_METHODS + 2], model[ZS_CULL_METHODS + 2], wrong[ZS_CULL_METHODS + 2];
  const int frames = w->frames, nrows = w->nmethods + w->nalgos;
  for (int k = 0; k < nrows; k++) {
    const zs_cmd_walk_algo *al = k >= w->nmethods ? &w->algos[k - w->nmethods] : NULL;
    names[k] = al ? zs_algo_name(al->a) : zs_cull_method_name(w->runs[k].m);
    wall[k] = zs_median(w->frame_wall + (size_t)k * (size_t)frames, frames);
    model[k] = (al ? al->modelled_ms : w->runs[k].modelled_ms) / frames;
    wrong[k] = (double)(al ? al->diff_pixels : w->runs[k].diff_pixels) / frames;
  }
  return zs_plot_tradeoff(path, w->scene, names, wall, model, wrong, nrows, err);
}

static zs_status write_plot(const char *path, const zs_cmd_walk_result *w, zs_error *err) {
  const char *names[ZS_CULL_METHODS];
  for (int k = 0; k < w->nmethods; k++) names[k] = zs_cull_method_name(w->runs[k].m);
  char title[512];
  snprintf(title, sizeof title, "%s: modelled frame time (log scale)", w->scene);
  return zs_plot_series(path, title, "frame of the path", "modelled ms", w->frame_ms, w->frames,
                        w->nmethods, names, 0, w->step, 1, err);
}

zs_status zs_cmd_walk_outputs(const zs_cmd_walk_result *w, const char *md, const char *tradeoff,
                              const char *plot, zs_error *err) {
  if (md && write_md(md, w, err)) return zs_out_error_option(err, "--md");
  if (tradeoff && write_tradeoff(tradeoff, w, err))
    return zs_out_error_option(err, "--tradeoff");
  if (plot && write_plot(plot, w, err)) return zs_out_error_option(err, "--plot");
  return ZS_OK;
}
