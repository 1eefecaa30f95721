/* The modelled clock of the device (raster.h, "clock.c: the modelled
 * clock").
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

#include "raster/internal.h"

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
  memset(&d->clock, 0, sizeof d->clock);
  d->nqueries = 0;
  d->query_open = 0;
  d->last_was_query = 0;
}

void zs_clock_cpu(zs_device *d, int64_t cost) { d->clock.cpu_ps += cost; }

int64_t zs_clock_command_cost(const zs_device *d, int32_t vertices, uint64_t polygons,
                              const zs_walk_counts *c, int is_query) {
  const zs_clock_costs *k = &d->costs;
  int64_t pixels = is_query ? k->per_query_pixel * (int64_t)c->tested
                            : k->per_pixel * (int64_t)c->tested + k->per_write * (int64_t)c->written;
  return k->per_call + k->per_vertex * vertices + k->per_polygon * (int64_t)polygons +
         k->per_span * (int64_t)c->spans + pixels;
}

int64_t zs_clock_gpu_command(zs_device *d, int64_t cost, int is_query) {
  return zs_clock_gpu_command_at(d, cost, is_query, d->clock.cpu_ps);
}

int64_t zs_clock_gpu_command_at(zs_device *d, int64_t cost, int is_query, int64_t cpu_ps) {
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

void zs_device_cpu_work(zs_device *d, zs_cpu_work kind, uint64_t count) {
  int64_t each = kind == ZS_CPU_NODE ? d->costs.cpu_per_node
                 : kind == ZS_CPU_FRUSTUM_TEST ? d->costs.cpu_per_frustum
                                               : d->costs.cpu_per_cost_eval;
  zs_clock_cpu(d, each * (int64_t)count);
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
