/* The modelled clock of the device and its counters (clock.h; the
 * model: zscan/clock.h).
 *
 * Defaults.  The constants describe, to an order of magnitude, a desktop GPU
 * of the cost-model paper's time behind a driver with per-call overhead;
 * `zscan calibrate` measures the same constants for zscan's own raster
 * code, and a user can enter any GPU's.
 *   per_call            2 us      a draw call's fixed GPU cost
 *   per_vertex          0         (a GPU's vertex work is in per_polygon)
 *   per_polygon         20 ns     set-up: 50 M polygons/s
 *   per_span            0         (a GPU rasterizes in tiles, not spans)
 *   per_pixel           0.5 ns    depth test: 2 G pixels/s
 *   per_write           0.5 ns    colour + depth write
 *   per_query_pixel     0.25 ns   depth-only test of a query box
 *   switch              1 us      pipeline change between drawing and querying
 *   query_latency       200 us    from a query's last pixel to its result
 *   cpu_per_call        5 us      driver cost of issuing a draw
 *   cpu_per_query       1 us      issuing a query
 *   cpu_per_node        100 ns    visiting a hierarchy node
 *   cpu_per_frustum     50 ns     one box-frustum test
 *   cpu_per_cost_eval   50 ns     one cost-model evaluation
 *   hzb_pass            5 us      a depth-pyramid pass: a compute dispatch
 *                                 per level, with a barrier between levels
 *   hzb_per_texel       0.1 ns    a pyramid texel: read four, write one
 *   hzb_per_box         1 ns      a box against the pyramid: eight corners
 *                                 projected, its faces' planes set up
 *   hzb_per_read        0.1 ns    a texel a box's test reads, as many as it
 *                                 takes (raster/hzb.c), priced as a texel
 *                                 written
 */
#include <math.h>
#include <string.h>

#include "raster/device.h"

void zs_clock_params_default(zs_clock_params *p) {
  *p = (zs_clock_params){
      .per_call_ns = 2000.0,
      .per_vertex_ns = 0.0,
      .per_polygon_ns = 20.0,
      .per_span_ns = 0.0,
      .per_pixel_ns = 0.5,
      .per_write_ns = 0.5,
      .per_query_pixel_ns = 0.25,
      .switch_ns = 1000.0,
      .query_latency_ns = 200000.0,
      .cpu_per_call_ns = 5000.0,
      .cpu_per_query_ns = 1000.0,
      .cpu_per_node_ns = 100.0,
      .cpu_per_frustum_ns = 50.0,
      .cpu_per_cost_eval_ns = 50.0,
      .hzb_pass_ns = 5000.0,
      .hzb_per_texel_ns = 0.1,
      .hzb_per_box_ns = 1.0,
      .hzb_per_read_ns = 0.1,
  };
}

/* Nanoseconds to whole picoseconds; -1 for a value that is no cost. */
static int64_t to_ps(double ns) {
  if (!isfinite(ns) || ns < 0.0 || ns > 1e12) return -1;
  return (int64_t)llround(ns * 1000.0);
}

zs_status zs_device_set_clock(zs_device *d, const zs_clock_params *p, zs_error *err) {
  const double v[] = {p->per_call_ns,        p->per_vertex_ns,       p->per_polygon_ns,
                      p->per_span_ns,        p->per_pixel_ns,        p->per_write_ns,
                      p->per_query_pixel_ns, p->switch_ns,           p->query_latency_ns,
                      p->cpu_per_call_ns,    p->cpu_per_query_ns,    p->cpu_per_node_ns,
                      p->cpu_per_frustum_ns, p->cpu_per_cost_eval_ns, p->hzb_pass_ns,
                      p->hzb_per_texel_ns,   p->hzb_per_box_ns,      p->hzb_per_read_ns};
  int64_t ps[sizeof v / sizeof v[0]];
  for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
    if ((ps[i] = to_ps(v[i])) < 0)
      return zs_error_set(err, ZS_ERR_ARG, "clock parameter %g: must be a finite number of "
                                           "nanoseconds from 0 to 1e12", v[i]);
  d->clock_params = *p;
  d->costs = (zs_clock_costs){ps[0], ps[1], ps[2],  ps[3],  ps[4],  ps[5],  ps[6],  ps[7],
                              ps[8], ps[9], ps[10], ps[11], ps[12], ps[13], ps[14], ps[15],
                              ps[16], ps[17]};
  return ZS_OK;
}

void zs_clock_reset(zs_device *d) {
  memset(&d->stats, 0, sizeof d->stats);
  memset(&d->clock, 0, sizeof d->clock);
  d->nqueries = 0;
  d->query_open = 0;
  d->last_was_query = 0;
}

/* The GPU runs a command of the given cost (ps), issued by the CPU at
 * cpu_ps; returns the GPU time at which it ends. */
static int64_t gpu_command(zs_device *d, int64_t cost, int is_query, int64_t cpu_ps) {
  /* The GPU cannot start a command before the CPU has issued it. */
  if (d->clock.gpu_ps < cpu_ps) d->clock.gpu_ps = cpu_ps;
  if (is_query != d->last_was_query) {
    d->clock.switches++;
    d->clock.gpu_ps += d->costs.switch_cost;
    d->clock.switch_ps += d->costs.switch_cost;
    d->last_was_query = is_query;
  }
  d->clock.gpu_ps += cost;
  *(is_query ? &d->clock.query_ps : &d->clock.draw_ps) += cost;
  return d->clock.gpu_ps;
}

/* The GPU time of a draw or query box with these counts. */
static int64_t command_cost(const zs_clock_costs *k, const zs_command *c, int is_query) {
  const zs_scan_counts *s = &c->scan;
  const int64_t pixels =
      is_query ? k->per_query_pixel * (int64_t)s->tested
               : k->per_pixel * (int64_t)s->tested + k->per_write * (int64_t)s->written;
  const int64_t polygons = (int64_t)zs_face_counts_set_up(&c->faces);
  return k->per_call + k->per_vertex * c->vertices + k->per_polygon * polygons +
         k->per_span * (int64_t)s->spans + pixels;
}

static void add_faces(zs_raster_stats *s, const zs_face_counts *fc) {
  s->polygons_in += fc->in;
  s->polygons_outside += fc->outside;
  s->polygons_clipped += fc->clipped;
  s->polygons_culled_back += fc->culled_back;
  s->polygons_degenerate += fc->degenerate;
  s->polygons_offscreen += fc->offscreen;
  s->polygons_rasterized += fc->rasterized;
}

/* A query waits for its result: the CPU first for the GPU to finish the
 * query's last command (a sync), then for the latency (a stall). */
static void wait_for(zs_device *d, const zs_query_rec *r) {
  zs_clock_stats *ck = &d->clock;
  const int64_t ready = r->gpu_end_ps + d->costs.latency;
  if (ck->cpu_ps >= ready) return;
  ck->query_waits++;
  if (ck->cpu_ps < r->gpu_end_ps) {
    ck->sync_ps += r->gpu_end_ps - ck->cpu_ps;
    ck->cpu_ps = r->gpu_end_ps;
  }
  if (ck->cpu_ps < ready) {
    ck->stalls++;
    ck->stall_ps += ready - ck->cpu_ps;
    ck->cpu_ps = ready;
  }
}

int64_t zs_clock_charge(zs_device *d, const zs_command *c) {
  const zs_clock_costs *k = &d->costs;
  zs_raster_stats *s = &d->stats;
  zs_clock_stats *ck = &d->clock;
  switch (c->kind) {
    case ZS_CMD_DRAW:
    case ZS_CMD_QUERY_BOXES: {
      const int query = c->kind == ZS_CMD_QUERY_BOXES;
      ck->cpu_ps += query ? k->cpu_per_query : k->cpu_per_call;
      if (c->reached < ZS_COUNTED) return ck->gpu_ps;
      s->draws++;
      s->vertices += (uint64_t)c->vertices;
      add_faces(s, &c->faces);
      if (c->reached < ZS_COMPLETED) return ck->gpu_ps;
      s->spans += c->scan.spans;
      /* a query box tests pixels; the clock counts them */
      if (query) ck->query_pixels += c->scan.tested;
      else {
        s->pixels_tested += c->scan.tested;
        s->pixels_written += c->scan.written;
      }
      const int64_t end = gpu_command(d, command_cost(k, c, query), query,
                                      c->issued_ps < 0 ? ck->cpu_ps : c->issued_ps);
      if (d->query_open || query) { /* the open query counts its samples */
        zs_query_rec *q = &d->queries[d->nqueries - 1];
        q->samples += c->scan.written;
        q->gpu_end_ps = end;
      }
      return end;
    }
    case ZS_CMD_FRAME_SCAN: /* the pixels of the frame's draws, their calls charged */
      s->spans += c->scan.spans;
      s->pixels_tested += c->scan.tested;
      s->pixels_written += c->scan.written;
      return gpu_command(d, command_cost(k, c, 0) - k->per_call, 0, ck->cpu_ps);
    case ZS_CMD_QUERY_BEGIN:
      ck->cpu_ps += k->cpu_per_query;
      ck->queries++;
      return ck->gpu_ps > ck->cpu_ps ? ck->gpu_ps : ck->cpu_ps;
    case ZS_CMD_QUERY_RESULT:
      wait_for(d, &d->queries[c->query]);
      return ck->gpu_ps;
    case ZS_CMD_HZB_BUILD:
      ck->cpu_ps += k->cpu_per_call;
      ck->hzb_texels += c->texels;
      return gpu_command(d, k->hzb_pass + k->hzb_per_texel * (int64_t)c->texels, 0, ck->cpu_ps);
    case ZS_CMD_HZB_TEST:
      ck->cpu_ps += k->cpu_per_call;
      ck->hzb_boxes += c->boxes;
      ck->hzb_reads += c->reads;
      return gpu_command(d,
                         k->hzb_pass + k->hzb_per_box * (int64_t)c->boxes +
                             k->hzb_per_read * (int64_t)c->reads,
                         0, ck->cpu_ps);
    case ZS_CMD_EDGES:
      s->pixels_written += c->scan.written;
      return ck->gpu_ps;
    case ZS_CMD_CPU_WORK:
      ck->cpu_ps += c->cpu_cost;
      return ck->gpu_ps;
  }
  return ck->gpu_ps;
}

void zs_device_cpu_work(zs_device *d, zs_cpu_work kind, uint64_t count) {
  int64_t each = kind == ZS_CPU_NODE ? d->costs.cpu_per_node
                 : kind == ZS_CPU_FRUSTUM_TEST ? d->costs.cpu_per_frustum
                                               : d->costs.cpu_per_cost_eval;
  const zs_command c = {.kind = ZS_CMD_CPU_WORK, .issued_ps = -1,
                        .cpu_cost = each * (int64_t)count};
  zs_clock_charge(d, &c);
}

const zs_clock_stats *zs_device_clock(const zs_device *d) { return &d->clock; }
const zs_clock_params *zs_device_clock_params(const zs_device *d) { return &d->clock_params; }

int64_t zs_device_frame_ps(const zs_device *d) {
  return d->clock.gpu_ps > d->clock.cpu_ps ? d->clock.gpu_ps : d->clock.cpu_ps;
}

/* The GPU clock starts the frame at 0 and moves only by the three sums and
 * by waiting for the CPU, so idle is what the sums leave of the frame. */
zs_gpu_split zs_clock_gpu_split(const zs_device *d) {
  const zs_clock_stats *c = &d->clock;
  int64_t busy = c->draw_ps + c->query_ps + c->switch_ps;
  return (zs_gpu_split){c->draw_ps, c->query_ps, c->switch_ps, zs_device_frame_ps(d) - busy};
}
