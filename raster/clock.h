/* zscan raster — the modelled clock and the counters (clock.c; the
 * model: zscan/clock.h).  One function charges them: every command the
 * device runs (a draw, a query's begin and boxes, a frame's scan at
 * finish, the depth pyramid's build and test, hidden-line edges, the
 * culler's CPU work) reaches the counters and both clocks through
 * zs_clock_charge, and a clear resets them through zs_clock_reset.
 * Nothing else writes them. */
#ifndef ZS_RASTER_CLOCK_H
#define ZS_RASTER_CLOCK_H

#include "raster/draw.h"

/* The clock's costs in integer picoseconds (from zs_clock_params). */
typedef struct zs_clock_costs {
  int64_t per_call, per_vertex, per_polygon, per_span, per_pixel, per_write, per_query_pixel;
  int64_t switch_cost, latency;
  int64_t cpu_per_call, cpu_per_query, cpu_per_node, cpu_per_frustum, cpu_per_cost_eval;
  int64_t hzb_pass, hzb_per_texel, hzb_per_box, hzb_per_read;
} zs_clock_costs;

/* A query: its samples so far, and when the GPU finished its last command
 * (ps); the result is ready a latency later. */
typedef struct zs_query_rec {
  uint64_t samples;
  int64_t gpu_end_ps;
} zs_query_rec;

typedef enum zs_command_kind {
  ZS_CMD_DRAW,          /* a draw: CPU per call, GPU its set-up and pixels */
  ZS_CMD_QUERY_BEGIN,   /* CPU per query */
  ZS_CMD_QUERY_BOXES,   /* CPU per query, GPU the boxes' depth tests */
  ZS_CMD_QUERY_RESULT,  /* the CPU waits until the query's result is ready */
  ZS_CMD_FRAME_SCAN,    /* scanline and depthsort modes at finish: the pixels */
  ZS_CMD_HZB_BUILD,     /* a compute pass: the pyramid's texels */
  ZS_CMD_HZB_TEST,      /* a compute pass: boxes and the texels they read */
  ZS_CMD_EDGES,         /* hidden-line edges, lines and points: the pixels
                         * written, no clock */
  ZS_CMD_CPU_WORK       /* the culler's own work on the CPU */
} zs_command_kind;

/* What one command did. */
typedef struct zs_command {
  zs_command_kind kind;
  /* a draw or boxes: 0 when it stopped before the device took it (a bad
   * argument); 1 when counted; 2 when it also ran to its end */
  int reached;
  int64_t issued_ps;          /* the CPU clock when issued: a deferred draw's; -1: now */
  int32_t vertices;
  zs_face_counts faces;
  zs_scan_counts scan;
  uint64_t texels, boxes, reads;  /* the pyramid's */
  int64_t cpu_cost;           /* ZS_CMD_CPU_WORK */
  uint32_t query;             /* ZS_CMD_QUERY_RESULT */
} zs_command;
enum { ZS_COUNTED = 1, ZS_COMPLETED = 2 };

/* Charges command c to the counters and the clocks; returns the GPU time
 * at which it ends (ps), and for a draw or boxes counts its samples into
 * the open query. */
int64_t zs_clock_charge(zs_device *d, const zs_command *c);
/* A clear: the counters, the clocks and the queries start again. */
void zs_clock_reset(zs_device *d);
/* The faces a draw's GPU command is charged for (raster.h,
 * zs_polygons_set_up). */
static inline uint64_t zs_face_counts_set_up(const zs_face_counts *fc) {
  return fc->rasterized + fc->offscreen;
}

#endif
