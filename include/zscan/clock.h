/* zscan — the device's modelled clock: what a frame would cost on a GPU
 * whose queries answer after a latency.  An extra to zscan.h. */
#ifndef ZSCAN_CLOCK_H
#define ZSCAN_CLOCK_H

#include <stdint.h>

#include "zscan/zscan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- clock.c: the modelled clock ----
 *
 * Real queries answer after a latency, and a CPU that waits for an answer
 * stalls.  The device models both sides with clocks that advance by costs
 * computed from counts, never from wall time, so modelled times are the
 * same on every run, build and thread count:
 *   GPU: a command starts when both the GPU is free and the CPU has issued
 *        it, and takes  per_call + vertices * per_vertex
 *        + polygons * per_polygon + spans * per_span
 *        + pixels tested * per_pixel + pixels written * per_write  (draws)
 *        or the same with pixels * per_query_pixel for the pixel terms
 *        (query boxes); a change between drawing and querying costs
 *        switch_ns; a query's result is ready query_latency after the GPU
 *        finished its last command inside the query (its GPU end).
 *   CPU: issuing a draw or a query costs cpu_per_call / cpu_per_query; the
 *        caller reports its own work (node visits, frustum tests, cost-model
 *        evaluations) with zs_device_cpu_work; asking for a result not yet
 *        ready moves the CPU clock to the ready time.  That wait has two
 *        parts, counted apart: up to the query's GPU end the CPU waits for
 *        queued GPU work (sync: the GPU is the bottleneck), after it for
 *        the latency (a stall: what CHC-style methods hide).  With latency
 *        0 nothing ever stalls.
 *   The depth pyramid (raster.h, hzb.c): a build costs hzb_pass + texels
 *        written * hzb_per_texel, a test of n boxes hzb_pass + n *
 *        hzb_per_box + texels read * hzb_per_read, both GPU commands counted with the drawing commands,
 *        each issued for cpu_per_call; their results stay on the GPU
 *        (they drive the next draws), so no latency and no stall.
 *   A frame's modelled time is the later of the two clocks at its end.
 *   The GPU's part of it is split four ways: drawing commands (clears and
 *   draws), query boxes, switches, and idle (waiting for the CPU to issue
 *   the next command, or at the end for the CPU to finish); the four add
 *   up to the frame (zs_clock_gpu_split).
 * Times are kept in integer picoseconds; parameters are nanoseconds. */
typedef struct zs_clock_params {
  double per_call_ns;         /* GPU: fixed cost of a draw or query box */
  double per_vertex_ns;       /* GPU: per vertex transformed */
  double per_polygon_ns;      /* GPU: per polygon set up */
  double per_span_ns;         /* GPU: per span (a polygon's run on one row) */
  double per_pixel_ns;        /* GPU: per pixel depth-tested by a draw */
  double per_write_ns;        /* GPU: per pixel written */
  double per_query_pixel_ns;  /* GPU: per pixel tested by a query box */
  double switch_ns;           /* GPU: per change between drawing and querying */
  double query_latency_ns;    /* GPU: from a query's end to its result */
  double cpu_per_call_ns;     /* CPU: issuing a draw */
  double cpu_per_query_ns;    /* CPU: issuing a query (begin, box, end) */
  double cpu_per_node_ns;     /* CPU: visiting a hierarchy node */
  double cpu_per_frustum_ns;  /* CPU: one box-frustum test */
  double cpu_per_cost_eval_ns;/* CPU: one cost-model evaluation */
  double hzb_pass_ns;         /* GPU: fixed cost of a depth-pyramid pass (build or test) */
  double hzb_per_texel_ns;    /* GPU: per pyramid texel written */
  double hzb_per_box_ns;      /* GPU: per box tested against the pyramid */
  double hzb_per_read_ns;     /* GPU: per pyramid texel a box test reads */
} zs_clock_params;

typedef enum zs_cpu_work {
  ZS_CPU_NODE, ZS_CPU_FRUSTUM_TEST, ZS_CPU_COST_EVAL
} zs_cpu_work;

typedef struct zs_clock_stats {
  uint64_t queries;           /* queries issued this frame */
  uint64_t query_waits;       /* results asked for before they were ready */
  uint64_t stalls;            /* of those, waits that reached into the latency */
  uint64_t query_pixels;      /* pixels tested by query boxes */
  uint64_t switches;          /* changes between drawing and querying */
  int64_t sync_ps;            /* CPU waiting for queued GPU work */
  int64_t stall_ps;           /* CPU waiting for query latency */
  int64_t gpu_ps, cpu_ps;     /* the two clocks now */
  /* GPU time so far: drawing commands, query boxes, switches (the rest of
   * the frame it waited for the CPU: zs_clock_gpu_split) */
  int64_t draw_ps, query_ps, switch_ps;
  uint64_t hzb_texels;        /* depth-pyramid texels written */
  uint64_t hzb_boxes;         /* boxes tested against the pyramid */
  uint64_t hzb_reads;         /* pyramid texels those tests read */
} zs_clock_stats;

/* The frame so far on the GPU, in picoseconds: draw + query + switch + idle
 * = zs_device_frame_ps, idle counting the gaps and the time the CPU runs
 * on after the GPU's last command. */
typedef struct zs_gpu_split {
  int64_t draw_ps, query_ps, switch_ps, idle_ps;
} zs_gpu_split;

/* The documented defaults (clock.c). */
void zs_clock_params_default(zs_clock_params *p);
/* Returns ZS_ERR_ARG when a parameter is negative or not finite. */
zs_status zs_device_set_clock(zs_device *dev, const zs_clock_params *p,
                              zs_error *err);
void zs_device_cpu_work(zs_device *dev, zs_cpu_work kind, uint64_t count);
const zs_clock_stats *zs_device_clock(const zs_device *dev);
const zs_clock_params *zs_device_clock_params(const zs_device *dev);
/* The frame's modelled time so far: the later of the two clocks. */
int64_t zs_device_frame_ps(const zs_device *dev);
zs_gpu_split zs_clock_gpu_split(const zs_device *dev);

#ifdef __cplusplus
}
#endif

#endif
