/* The hierarchical depth buffer (raster.h, "hzb.c"): Greene, Kass and
 * Miller's z-pyramid, as the two-phase culling of GPU-driven pipelines
 * builds it from the depth buffer and tests boxes against it.
 *
 * Level 0 is the depth buffer itself; texel (x, y) of level k holds the
 * farthest of texels (2x .. 2x + 1, 2y .. 2y + 1) of level k - 1 (those
 * inside it at the odd edges), so it is the farthest depth of the pixels
 * it covers, exactly, in the buffer's 32-bit units.
 *
 * A box is "maybe visible" unless every texel over the pixels its query
 * box could reach is nearer than any depth that query could test.  The
 * pixels: the window rectangle of the box's corners, grown by the query
 * margin (zs_device_query_margin) and one more pixel on every side
 * (snapping moves a corner by at most 1/512 pixel).  The depth: the
 * nearest corner's window depth, less what a query box is brought nearer
 * by (ZS_QUERY_DEPTH_BIAS units and 1/16 pixel of its face's depth slope),
 * less as much again for snapping (the plane of a snapped face strays
 * from its corners by at most the same 1/16 pixel of slope, the bound the
 * query boxes rest on) and 64 units for the fixed-point plane's rounding.
 * A box that the near plane cuts, or that holds the eye, is maybe
 * visible.  The level read is the first at which the rectangle spans at
 * most 2x2 texels.  tests/test_hzb.c holds this against exact box queries
 * on thousands of random boxes, scenes and cameras. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "raster/grow.h"
#include "raster/internal.h"

/* ---- the pyramid ---- */

/* Level k from level k - 1 (src, sw x sh): the farthest of each 2x2. */
static void reduce_level(const uint32_t *src, int sw, int sh, uint32_t *dst, int dw, int dh) {
  for (int y = 0; y < dh; y++) {
    const uint32_t *r0 = src + (size_t)(2 * y) * (size_t)sw;
    const uint32_t *r1 = 2 * y + 1 < sh ? r0 + sw : r0;
    uint32_t *out = dst + (size_t)y * (size_t)dw;
    for (int x = 0; x < dw; x++) {
      const int x0 = 2 * x, x1 = 2 * x + 1 < sw ? 2 * x + 1 : 2 * x;
      uint32_t a = r0[x0] > r0[x1] ? r0[x0] : r0[x1];
      uint32_t b = r1[x0] > r1[x1] ? r1[x0] : r1[x1];
      out[x] = a > b ? a : b;
    }
  }
}

zs_status zs_device_hzb_build(zs_device *d, zs_error *err) {
  if (!d->depth)
    return zs_error_set(err, ZS_ERR_UNSUPPORTED, "the depth pyramid needs the z-buffer mode");
  zs_status st = zs_device_flush(d, err); /* the pyramid is of what is drawn */
  if (st != ZS_OK) return st;
  zs_frame_clear_fresh(d);
  zs_hzb *h = &d->hzb;
  /* the levels' sizes and offsets, once for the device's size */
  if (h->levels == 0) {
    int w = d->cfg.width, ht = d->cfg.height, k = 0;
    int64_t total = 0;
    h->w[0] = w;
    h->h[0] = ht;
    while ((w > 1 || ht > 1) && k + 1 < ZS_HZB_MAX_LEVELS) {
      w = (w + 1) / 2;
      ht = (ht + 1) / 2;
      k++;
      h->w[k] = w;
      h->h[k] = ht;
      h->offset[k] = total;
      total += (int64_t)w * ht;
    }
    h->levels = k + 1;
    h->texels = total;
    if (!zs_grow((void **)&h->texel, &h->cap, total > 0 ? total : 1, sizeof *h->texel))
      return zs_error_set(err, ZS_ERR_NOMEM, "depth pyramid: out of memory");
  }
  const uint32_t *src = d->depth;
  for (int k = 1; k < h->levels; k++) {
    uint32_t *dst = h->texel + h->offset[k];
    reduce_level(src, h->w[k - 1], h->h[k - 1], dst, h->w[k], h->h[k]);
    src = dst;
  }
  h->built = 1;
  /* a compute pass: issued by the CPU, run on the GPU after the draws */
  zs_clock_cpu(d, d->costs.cpu_per_call);
  zs_clock_gpu_command(d, d->costs.hzb_pass + d->costs.hzb_per_texel * h->texels, 0);
  d->clock.hzb_texels += (uint64_t)h->texels;
  return ZS_OK;
}

/* The texels of level k over pixels [x0, x1] x [y0, y1]: the farthest. */
static uint32_t farthest_over(const zs_device *d, int k, int x0, int y0, int x1, int y1) {
  const zs_hzb *h = &d->hzb;
  const uint32_t *lv = k == 0 ? d->depth : h->texel + h->offset[k];
  const int w = h->w[k];
  uint32_t far = 0;
  for (int y = y0 >> k; y <= y1 >> k; y++)
    for (int x = x0 >> k; x <= x1 >> k; x++) {
      uint32_t t = lv[(size_t)y * (size_t)w + (size_t)x];
      if (t > far) far = t;
    }
  return far;
}

/* ---- one box ---- */

/* The largest depth change per pixel (|dz/dx| + |dz/dy|, window depth
 * units) of the face through window points a, b, c; infinite when the
 * face is seen edge-on. */
static double face_slope(const double *a, const double *b, const double *c) {
  const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const double det = ux * vy - vx * uy;
  if (det == 0.0) return INFINITY;
  return fabs((uz * vy - vz * uy) / det) + fabs((ux * vz - vx * uz) / det);
}

/* Whether the box lo..hi may show a sample to a query (1) or is hidden
 * behind the pyramid (0). */
static int box_maybe_visible(const zs_device *d, const double mvp[16], const double lo[3],
                             const double hi[3]) {
  const double m = zs_device_query_margin(d, lo, hi);
  const double blo[3] = {lo[0] - m, lo[1] - m, lo[2] - m};
  const double bhi[3] = {hi[0] + m, hi[1] + m, hi[2] + m};
  int inside = 1;
  for (int a = 0; a < 3; a++)
    if (d->eye[a] < blo[a] || d->eye[a] > bhi[a]) inside = 0;
  if (inside) return 1;
  /* the corners in the window: x right, y down, z the window depth */
  double win[8][3];
  double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY, zmin = INFINITY;
  for (int b = 0; b < 8; b++) {
    const double p[3] = {b & 1 ? bhi[0] : blo[0], b & 2 ? bhi[1] : blo[1],
                         b & 4 ? bhi[2] : blo[2]};
    double o[4];
    zs_mat_apply(mvp, p, o);
    const zs_clip_vert v = {o[0], o[1], o[2], o[3]};
    if (!(v.w > 0.0) || !(v.z + v.w >= 0.0)) return 1; /* the near plane cuts it */
    zs_window_xy(d->cfg.width, d->cfg.height, &v, &win[b][0], &win[b][1]);
    win[b][1] = d->cfg.height - win[b][1];
    win[b][2] = zs_window_depth(&v);
    xmin = fmin(xmin, win[b][0]);
    xmax = fmax(xmax, win[b][0]);
    ymin = fmin(ymin, win[b][1]);
    ymax = fmax(ymax, win[b][1]);
    zmin = fmin(zmin, win[b][2]);
  }
  /* the pixels whose centres the query box could cover, within the window */
  if (!(xmax >= -1.0 && ymax >= -1.0 && xmin <= d->cfg.width + 1.0 && ymin <= d->cfg.height + 1.0))
    return 0; /* no pixel of the window: the query counts none */
  int x0 = (int)fmax(floor(xmin) - 1.0, 0.0), x1 = (int)fmin(floor(xmax) + 1.0, d->cfg.width - 1.0);
  int y0 = (int)fmax(floor(ymin) - 1.0, 0.0), y1 = (int)fmin(floor(ymax) + 1.0, d->cfg.height - 1.0);
  if (x0 > x1 || y0 > y1) return 0;
  /* the steepest face the query would draw: those turned to the eye */
  static const int quad[6][3] = {{0, 4, 2}, {1, 3, 5}, {0, 1, 4}, {2, 6, 3}, {0, 2, 1}, {4, 5, 6}};
  double slope = 0.0;
  for (int f = 0; f < 6; f++) {
    const int a = f / 2;
    if (!((f % 2) ? d->eye[a] > bhi[a] : d->eye[a] < blo[a])) continue;
    slope = fmax(slope, face_slope(win[quad[f][0]], win[quad[f][1]], win[quad[f][2]]));
  }
  const double near = zmin * 4294967296.0 - ZS_QUERY_DEPTH_BIAS - slope * 4294967296.0 / 8.0 - 64.0;
  if (!(near > 0.0)) return 1; /* NaN too */
  /* the level at which the rectangle spans at most 2x2 texels */
  const int span = (x1 - x0 > y1 - y0 ? x1 - x0 : y1 - y0) + 1;
  int k = 0;
  while ((1 << k) < span >> 1 && k + 1 < d->hzb.levels) k++;
  const uint32_t far = farthest_over(d, k, x0, y0, x1, y1);
  return !((double)far < near);
}

zs_status zs_device_hzb_test(zs_device *d, const double (*lo)[3], const double (*hi)[3], int n,
                             uint8_t *maybe_visible, zs_error *err) {
  if (!d->hzb.built)
    return zs_error_set(err, ZS_ERR_ARG, "hzb_test: no depth pyramid built this frame");
  if (n < 1) return ZS_OK;
  double mvp[16];
  zs_mat_mul(mvp, d->proj, d->view);
  for (int i = 0; i < n; i++) maybe_visible[i] = (uint8_t)box_maybe_visible(d, mvp, lo[i], hi[i]);
  zs_clock_cpu(d, d->costs.cpu_per_call);
  zs_clock_gpu_command(d, d->costs.hzb_pass + d->costs.hzb_per_box * n, 0);
  d->clock.hzb_boxes += (uint64_t)n;
  return ZS_OK;
}

void zs_hzb_free(zs_hzb *h) {
  free(h->texel);
  memset(h, 0, sizeof *h);
}

size_t zs_hzb_bytes(const zs_hzb *h) { return (size_t)h->cap * sizeof *h->texel; }
