/* Occlusion queries (raster.h, "query.c: occlusion queries").
 *
 * The emulation rasterizes at once, so a query's samples are known when
 * its last box or draw is done; what the clock models is when the answer
 * may be read: query_latency after the GPU finished the query's last
 * command.  Reading earlier makes the CPU wait (a stall). */
#include <math.h>
#include <stdlib.h>

#include "raster/internal.h"

zs_status zs_device_query_begin(zs_device *d, zs_query *q, zs_error *err) {
  if (d->cfg.algo != ZS_ALGO_ZBUFFER)
    return zs_error_set(err, ZS_ERR_UNSUPPORTED, "occlusion queries need --algo zbuffer");
  if (d->query_open) return zs_error_set(err, ZS_ERR_ARG, "query_begin: a query is already open");
  zs_status st = zs_device_flush(d, err); /* the query counts what is drawn before it */
  if (st != ZS_OK) return st;
  if (d->nqueries == d->cap_queries) {
    uint32_t cap = d->cap_queries ? 2 * d->cap_queries : 256;
    zs_query_rec *r = realloc(d->queries, (size_t)cap * sizeof *r);
    if (!r) return zs_error_set(err, ZS_ERR_NOMEM, "query_begin: out of memory");
    d->queries = r;
    d->cap_queries = cap;
  }
  zs_clock_cpu(d, d->costs.cpu_per_query);
  /* Until a command lands in it, the query ends where the GPU is now. */
  int64_t now = d->clock.gpu_ps > d->clock.cpu_ps ? d->clock.gpu_ps : d->clock.cpu_ps;
  d->queries[d->nqueries] = (zs_query_rec){0, now};
  *q = d->nqueries++;
  d->query_open = 1;
  d->clock.queries++;
  return ZS_OK;
}

zs_status zs_device_query_end(zs_device *d, zs_error *err) {
  if (!d->query_open) return zs_error_set(err, ZS_ERR_ARG, "query_end: no query is open");
  d->query_open = 0;
  return ZS_OK;
}

/* The 8 corners of a box: bit 0 of the index picks x, bit 1 y, bit 2 z. */
static void corner(const double lo[3], const double hi[3], int b, double *out) {
  out[0] = (b & 1) ? hi[0] : lo[0];
  out[1] = (b & 2) ? hi[1] : lo[1];
  out[2] = (b & 4) ? hi[2] : lo[2];
}

/* raster.h.  1/32 of a pixel at the box's farthest point: under a
 * perspective a pixel spans more of the world the farther it is, so the
 * margin is at least that everywhere in the box.  Snapping moves each vertex of a face by up to 1/512 pixel along
 * each axis, the box's corners as much: without the margin, a face whose
 * vertex lies on the box could cover a pixel centre just outside the
 * box's snapped picture (fuzz_cull: a world-flat triangle, its box a
 * segment with no pixel, that snapping turned into a sliver holding one). */
double zs_device_query_margin(const zs_device *d, const double lo[3], const double hi[3]) {
  const double *v = d->view, *p = d->proj;
  double sx = 2.0 / (fabs(p[0]) * d->cfg.width), sy = 2.0 / (fabs(p[5]) * d->cfg.height);
  double pixel = sx > sy ? sx : sy; /* world units a pixel spans, at view depth 1 if perspective */
  if (d->perspective) {
    double far = 0.0;
    for (int b = 0; b < 8; b++) {
      double c[3];
      corner(lo, hi, b, c);
      double z = -(v[8] * c[0] + v[9] * c[1] + v[10] * c[2] + v[11]);
      if (z > far) far = z;
    }
    pixel *= far;
  }
  return pixel / 32.0;
}

zs_status zs_device_query_boxes(zs_device *d, const double (*lo)[3], const double (*hi)[3],
                                int n, zs_error *err) {
  if (!d->query_open) return zs_error_set(err, ZS_ERR_ARG, "query_box: no query is open");
  if (n < 1) return ZS_OK;
  /* The faces as seen from outside, counter-clockwise; face 2a is the low
   * side of axis a, 2a+1 the high side. */
  static const int32_t faces[6][4] = {
      {0, 4, 6, 2}, {1, 3, 7, 5},  /* x low, x high */
      {0, 1, 5, 4}, {2, 6, 7, 3},  /* y low, y high */
      {0, 2, 3, 1}, {4, 5, 7, 6}}; /* z low, z high */
  double *pos = malloc((size_t)n * 24 * sizeof *pos);
  int32_t *start = malloc(((size_t)n * 6 + 1) * sizeof *start);
  int32_t *vert = malloc((size_t)n * 24 * sizeof *vert);
  if (!pos || !start || !vert) {
    free(pos);
    free(start);
    free(vert);
    return zs_error_set(err, ZS_ERR_NOMEM, "query_box: out of memory");
  }
  int32_t nf = 0;
  for (int i = 0; i < n; i++) {
    const double m = zs_device_query_margin(d, lo[i], hi[i]);
    const double blo[3] = {lo[i][0] - m, lo[i][1] - m, lo[i][2] - m};
    const double bhi[3] = {hi[i][0] + m, hi[i][1] + m, hi[i][2] + m};
    for (int b = 0; b < 8; b++) corner(blo, bhi, b, &pos[24 * i + 3 * b]);
    int inside = 1;
    for (int a = 0; a < 3; a++)
      if (d->eye[a] < blo[a] || d->eye[a] > bhi[a]) inside = 0;
    /* Only the faces turned to the eye: over a convex box they cover each
     * pixel of its outline once.  From inside, every face, seen from within. */
    for (int f = 0; f < 6; f++) {
      int a = f / 2;
      int facing = (f % 2) ? d->eye[a] > bhi[a] : d->eye[a] < blo[a];
      if (!facing && !inside) continue;
      start[nf] = 4 * nf;
      for (int k = 0; k < 4; k++) vert[4 * nf + k] = 8 * i + faces[f][inside ? 3 - k : k];
      nf++;
    }
  }
  start[nf] = 4 * nf;
  zs_mesh boxes = {pos, 8 * n, start, vert, nf, NULL, NULL};
  uint64_t polygons = zs_polygons_set_up(&d->stats);
  zs_walk_counts c;
  zs_clock_cpu(d, d->costs.cpu_per_query);
  zs_status st = zs_draw_at_once(d, &boxes, NULL, 0, 0, ZS_KERNEL_QUERY, &c, err);
  free(pos);
  free(start);
  free(vert);
  if (st != ZS_OK) return st;
  d->clock.query_pixels += c.tested;
  int64_t cost = zs_clock_command_cost(d, 8 * n, zs_polygons_set_up(&d->stats) - polygons, &c, 1);
  zs_query_rec *q = &d->queries[d->nqueries - 1];
  q->gpu_end_ps = zs_clock_gpu_command(d, cost, 1);
  q->samples += c.written;
  return ZS_OK;
}

zs_status zs_device_query_box(zs_device *d, const double lo[3], const double hi[3],
                              zs_error *err) {
  return zs_device_query_boxes(d, (const double(*)[3])lo, (const double(*)[3])hi, 1, err);
}

int zs_device_query_ready(const zs_device *d, zs_query q) {
  if (q >= d->nqueries || (d->query_open && q == d->nqueries - 1)) return 0;
  return d->clock.cpu_ps >= d->queries[q].gpu_end_ps + d->costs.latency;
}

uint64_t zs_device_query_result(zs_device *d, zs_query q) {
  if (q >= d->nqueries) return 0;
  const zs_query_rec *r = &d->queries[q];
  int64_t ready = r->gpu_end_ps + d->costs.latency;
  if (d->clock.cpu_ps < ready) {
    d->clock.query_waits++;
    if (d->clock.cpu_ps < r->gpu_end_ps) {
      d->clock.sync_ps += r->gpu_end_ps - d->clock.cpu_ps;
      d->clock.cpu_ps = r->gpu_end_ps;
    }
    if (d->clock.cpu_ps < ready) {
      d->clock.stalls++;
      d->clock.stall_ps += ready - d->clock.cpu_ps;
      d->clock.cpu_ps = ready;
    }
  }
  return r->samples;
}
