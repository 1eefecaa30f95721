/* zscan tools — what `zscan walk`'s frame loop (cmd_walk.c) hands its
 * reports (cmd_walk_report.c): the sums of every method and mode over the walk, and
 * the CSV's rows as the loop writes them. */
#ifndef ZS_TOOLS_CMD_WALK_H
#define ZS_TOOLS_CMD_WALK_H

#include <stdint.h>
#include <stdio.h>

#include "cull/cull.h"
#include "raster/raster.h"

/* Per method, the sums over the walk. */
typedef struct zs_cmd_walk_method {
  zs_cull_method m;
  zs_culler *culler;
  zs_device *dev;
  double modelled_ms, stall_ms, wall_ms, queries, faces, objects, nodes;
  double gpu_ms[4];       /* the GPU's split: draw, query, switch, idle */
  uint64_t diff_pixels, frames_with_diff;
  uint64_t chose_queries; /* auto: frames it ran with queries */
  /* ideal-box: its set against the last frame's, summed over frames */
  double set_size, entered, entered_outside, left, left_outside, known_ms, ranked_ms;
} zs_cmd_walk_method;

/* A hidden-surface mode drawing everything (--algos), against none. */
typedef struct zs_cmd_walk_algo {
  zs_algo a;
  zs_device *dev;
  double modelled_ms, wall_ms, faces;
  uint64_t diff_pixels;
} zs_cmd_walk_algo;

/* A finished walk. */
typedef struct zs_cmd_walk_result {
  const char *scene;
  int width, height, frames, step, objects;
  uint64_t faces;
  int has_reference; /* none ran as the reference: diff_pixels mean something */
  const zs_cmd_walk_method *runs;
  int nmethods;
  const zs_cmd_walk_algo *algos;
  int nalgos;
  const double *frame_ms; /* [frame * nmethods + method]: modelled ms */
  double *frame_wall;     /* [row * frames + frame], methods then modes: wall ms
                             (the tradeoff's medians sort each row in place) */
} zs_cmd_walk_result;

/* The GPU's split of the device's frame, in ms: draw, query, switch, idle. */
void zs_cmd_walk_gpu_split_ms(const zs_device *d, double ms[4]);

/* The CSV: its header, and one row per frame for a method or a mode
 * (diff: pixels against none, not written without a reference). */
void zs_cmd_walk_csv_header(FILE *f);
void zs_cmd_walk_csv_method(FILE *f, int frame, const zs_cmd_walk_method *r,
                            const zs_cull_stats *cs, double modelled, double stall, double wall,
                            const double split[4], int has_reference, uint64_t diff);
void zs_cmd_walk_csv_algo(FILE *f, int frame, const zs_cmd_walk_algo *r, double modelled,
                          double wall, uint64_t faces, int objects, uint64_t diff);

/* The summary on f: the table of means per frame, the GPU's share, and
 * ideal-box's churn when it ran. */
void zs_cmd_walk_report(FILE *f, const zs_cmd_walk_result *r);
/* The outputs named on the command line (NULL: not asked for): --md,
 * --tradeoff and --plot; an error names its option. */
zs_status zs_cmd_walk_outputs(const zs_cmd_walk_result *r, const char *md, const char *tradeoff,
                              const char *plot, zs_error *err);

#endif
