/* Occlusion queries (raster.h, "query.c: occlusion queries"), and their
 * GPU-driven twin, boxes tested against the depth pyramid (hzb.c).
 *
 * The emulation rasterizes at once, so a query's samples are known when
 * its last box or draw is done; what the clock models is when the answer
 * may be read: query_latency after the GPU finished the query's last
 * command.  Reading earlier makes the CPU wait (a stall). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "raster/box.h"
#include "raster/device.h"
#include "util/grow.h"

const int32_t zs_box_faces[6][4] = {
    {0, 4, 6, 2}, {1, 3, 7, 5},  /* x low, x high */
    {0, 1, 5, 4}, {2, 6, 7, 3},  /* y low, y high */
    {0, 2, 3, 1}, {4, 5, 7, 6}}; /* z low, z high */

zs_status zs_device_query_begin(zs_device *d, zs_query *q, zs_error *err) {
  if (d->cfg.algo != ZS_ALGO_ZBUFFER)
    return zs_error_set(err, ZS_ERR_UNSUPPORTED, "occlusion queries need --algo zbuffer");
  if (d->query_open) return zs_error_set(err, ZS_ERR_ARG, "query_begin: a query is already open");
  zs_status st = zs_device_flush(d, err); /* the query counts what is drawn before it */
  if (st != ZS_OK) return st;
  if (!zs_grow((void **)&d->queries, &d->cap_queries, (int64_t)d->nqueries + 1,
               sizeof *d->queries))
    return zs_error_set(err, ZS_ERR_NOMEM, "query_begin: out of memory");
  /* Until a command lands in it, the query ends where the GPU is now. */
  const zs_command c = {.kind = ZS_CMD_QUERY_BEGIN, .issued_ps = -1};
  d->queries[d->nqueries] = (zs_query_rec){0, zs_clock_charge(d, &c)};
  *q = (zs_query)d->nqueries++;
  d->query_open = 1;
  return ZS_OK;
}

zs_status zs_device_query_end(zs_device *d, zs_error *err) {
  if (!d->query_open) return zs_error_set(err, ZS_ERR_ARG, "query_end: no query is open");
  d->query_open = 0;
  return ZS_OK;
}

/* raster.h.  1/32 of a pixel at the box's farthest point: under a
 * perspective a pixel spans more of the world the farther it is, so the
 * margin is at least that everywhere in the box.  Snapping moves each
 * vertex of a face by up to 1/512 pixel along each axis, the box's
 * corners as much: without the margin, a face whose vertex lies on the
 * box could cover a pixel centre just outside the box's snapped picture
 * (fuzz_cull: a world-flat triangle, its box a segment with no pixel,
 * that snapping turned into a sliver holding one). */
double zs_box_margin(const double view[16], const double proj[16], int perspective, int width,
                     int height, const double lo[3], const double hi[3]) {
  const double *v = view, *p = proj;
  double sx = 2.0 / (fabs(p[0]) * width), sy = 2.0 / (fabs(p[5]) * height);
  double pixel = sx > sy ? sx : sy; /* world units a pixel spans, at view depth 1 if perspective */
  if (perspective) {
    double far = 0.0;
    for (int b = 0; b < 8; b++) {
      double c[3];
      zs_box_corner(lo, hi, b, c);
      double z = -(v[8] * c[0] + v[9] * c[1] + v[10] * c[2] + v[11]);
      if (z > far) far = z;
    }
    pixel *= far;
  }
  return pixel / 32.0;
}

double zs_device_query_margin(const zs_device *d, const double lo[3], const double hi[3]) {
  return zs_box_margin(d->view, d->proj, d->perspective, d->cfg.width, d->cfg.height, lo, hi);
}

zs_status zs_device_query_boxes(zs_device *d, const double (*lo)[3], const double (*hi)[3],
                                int n, zs_error *err) {
  if (!d->query_open) return zs_error_set(err, ZS_ERR_ARG, "query_box: no query is open");
  if (n < 1) return ZS_OK;
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
    for (int b = 0; b < 8; b++) zs_box_corner(blo, bhi, b, &pos[24 * i + 3 * b]);
    const int inside = zs_box_holds(blo, bhi, d->eye);
    /* Only the faces turned to the eye: over a convex box they cover each
     * pixel of its outline once.  From inside, every face, seen from within. */
    for (int f = 0; f < 6; f++) {
      if (!inside && !zs_box_face_turned_to(blo, bhi, d->eye, f)) continue;
      start[nf] = 4 * nf;
      for (int k = 0; k < 4; k++) vert[4 * nf + k] = 8 * i + zs_box_faces[f][inside ? 3 - k : k];
      nf++;
    }
  }
  start[nf] = 4 * nf;
  zs_mesh boxes = {.pos = pos, .nverts = 8 * n, .face_start = start, .face_vert = vert, .nfaces = nf};
  zs_command c = {.kind = ZS_CMD_QUERY_BOXES, .issued_ps = -1};
  zs_status st =
      zs_draw_at_once(d, &boxes, NULL, 0, 0, &d->state_of[ZS_KERNEL_QUERY], &c, err);
  free(pos);
  free(start);
  free(vert);
  zs_clock_charge(d, &c);
  return st;
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
  const zs_command c = {.kind = ZS_CMD_QUERY_RESULT, .issued_ps = -1, .query = q};
  zs_clock_charge(d, &c);
  return d->queries[q].samples;
}

uint32_t zs_device_queries(const zs_device *d) { return d->nqueries; }

/* ---- the depth pyramid's commands ---- */

zs_status zs_device_hzb_build(zs_device *d, zs_error *err) {
  if (!d->depth)
    return zs_error_set(err, ZS_ERR_UNSUPPORTED, "the depth pyramid needs the z-buffer mode");
  zs_status st = zs_device_flush(d, err); /* the pyramid is of what is drawn */
  if (st != ZS_OK) return st;
  zs_raster_clear_fresh(d);
  if (!d->hzb && !(d->hzb = zs_hzb_create()))
    return zs_error_set(err, ZS_ERR_NOMEM, "depth pyramid: out of memory");
  int64_t texels;
  if (!zs_hzb_build(d->hzb, d->depth, d->cfg.width, d->cfg.height, &texels))
    return zs_error_set(err, ZS_ERR_NOMEM, "depth pyramid: out of memory");
  /* a compute pass: issued by the CPU, run on the GPU after the draws */
  const zs_command c = {.kind = ZS_CMD_HZB_BUILD, .issued_ps = -1, .texels = (uint64_t)texels};
  zs_clock_charge(d, &c);
  return ZS_OK;
}

zs_status zs_device_hzb_test(zs_device *d, const double (*lo)[3], const double (*hi)[3], int n,
                             uint8_t *maybe_visible, zs_error *err) {
  if (!d->hzb || !zs_hzb_built(d->hzb))
    return zs_error_set(err, ZS_ERR_ARG, "hzb_test: no depth pyramid built this frame");
  if (n < 1) return ZS_OK;
  zs_hzb_view v;
  memcpy(v.view, d->view, sizeof v.view);
  memcpy(v.proj, d->proj, sizeof v.proj);
  zs_mat_mul(v.mvp, d->proj, d->view);
  memcpy(v.eye, d->eye, sizeof v.eye);
  v.perspective = d->perspective;
  v.width = d->cfg.width;
  v.height = d->cfg.height;
  const zs_command c = {.kind = ZS_CMD_HZB_TEST, .issued_ps = -1, .boxes = (uint64_t)n,
                        .reads = zs_hzb_test(d->hzb, d->depth, &v, lo, hi, n, maybe_visible)};
  zs_clock_charge(d, &c);
  return ZS_OK;
}
