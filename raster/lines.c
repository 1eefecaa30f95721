/* Hidden-line output (raster.h, "lines.c"). */
#include <math.h>
#include <string.h>

#include "util/grow.h"
#include "raster/box.h"
#include "raster/device.h"

zs_status zs_device_fill_color(zs_device *d, uint32_t rgb, zs_error *err) {
  zs_status st = zs_device_flush(d, err); /* queued faces paint before the fill */
  if (st != ZS_OK || !d->rgb) return st;
  zs_raster_clear_fresh(d);
  size_t n = (size_t)d->cfg.width * (size_t)d->cfg.height;
  for (size_t i = 0; i < n; i++) d->rgb[i] = rgb;
  return ZS_OK;
}

/* Window position of a clip-space point: x, y in pixels (image y down),
 * z the window depth. */
static void to_window(const zs_device *d, const zs_clip_vert *v, double out[3]) {
  zs_window_xy(d->cfg.width, d->cfg.height, v, &out[0], &out[1]);
  out[1] = d->cfg.height - out[1];
  out[2] = zs_window_depth(v);
}

void zs_device_keep_line_runs(zs_device *d, int keep) { d->keep_runs = keep; }

const zs_line_run *zs_device_line_runs(const zs_device *d, int32_t *n) {
  *n = d->nomem_runs ? -1 : d->nruns;
  return d->nruns && !d->nomem_runs ? d->runs : NULL;
}

/* Records the painted columns c0 .. c1 of the segment p-q (major axis
 * from a0, length len) as one run, the pixels' outer sides included. */
static void keep_run(zs_device *d, const double p[3], const double q[3], double a0, double len,
                     int c0, int c1) {
  if (!zs_grow((void **)&d->runs, &d->cap_runs, (int64_t)d->nruns + 1, sizeof *d->runs)) {
    d->nomem_runs = 1;
    return;
  }
  double t0 = (c0 - a0) / len, t1 = (c1 + 1 - a0) / len;
  if (t0 > t1) {
    double t = t0;
    t0 = t1;
    t1 = t;
  }
  t0 = t0 < 0.0 ? 0.0 : t0;
  t1 = t1 > 1.0 ? 1.0 : t1;
  d->runs[d->nruns++] = (zs_line_run){p[0] + t0 * (q[0] - p[0]), p[1] + t0 * (q[1] - p[1]),
                                      p[0] + t1 * (q[0] - p[0]), p[1] + t1 * (q[1] - p[1])};
}

/* Draws the segment p-q (window coordinates) with depth bias `bias`
 * (window depth units): at each column (or row) along the major axis, the
 * width pixels across it whose centres lie nearest the exact edge at that
 * column's centre (for width 1 the pixel whose area holds it; for an even
 * width the pixel boundary nearest it in their middle), all at the edge's
 * depth there; with d->keep_runs, each stretch of columns where some pixel
 * was painted is kept as a run. */
static uint64_t draw_segment(zs_device *d, const double p[3], const double q[3], double bias,
                             uint32_t rgb, int depth_test, int width) {
  const int w = d->cfg.width, h = d->cfg.height;
  double dx = q[0] - p[0], dy = q[1] - p[1];
  int major_x = fabs(dx) >= fabs(dy);
  double a0 = major_x ? p[0] : p[1], a1 = major_x ? q[0] : q[1];
  double len = a1 - a0;
  if (len == 0.0) return 0;
  int c0 = (int)ceil((a0 < a1 ? a0 : a1) - 0.5), c1 = (int)ceil((a0 < a1 ? a1 : a0) - 0.5) - 1;
  int limit = major_x ? w - 1 : h - 1;
  if (c0 < 0) c0 = 0;
  if (c1 > limit) c1 = limit;
  uint64_t written = 0;
  int run = -1; /* the first column of the painted stretch, or -1 */
  for (int c = c0; c <= c1; c++) {
    double t = (c + 0.5 - a0) / len;
    double minor = major_x ? p[1] + t * dy : p[0] + t * dx;
    /* the first of the width pixels: floor(minor) for width 1 */
    const int m0 = (int)floor(minor - 0.5 * (width - 1));
    double z = p[2] + t * (q[2] - p[2]) - bias;
    double zq = z * 4294967296.0;
    uint32_t zd = zq <= 0 ? 0 : zq >= 4294967295.0 ? ZS_DEPTH_FAR : (uint32_t)zq;
    int painted = 0;
    for (int m = m0; m < m0 + width; m++) {
      int x = major_x ? c : m, y = major_x ? m : c;
      if (x < 0 || y < 0 || x >= w || y >= h) continue;
      size_t i = (size_t)y * (size_t)w + (size_t)x;
      if (!depth_test || zd <= d->depth[i]) {
        d->rgb[i] = rgb;
        written++;
        painted = 1;
      }
    }
    if (painted && run < 0) run = c;
    if (!painted && run >= 0) {
      if (d->keep_runs) keep_run(d, p, q, a0, len, run, c - 1);
      run = -1;
    }
  }
  if (run >= 0 && d->keep_runs) keep_run(d, p, q, a0, len, run, c1);
  return written;
}

zs_status zs_device_draw_edges(zs_device *d, const zs_mesh *mesh, const double model[16],
                               uint32_t rgb, zs_error *err) {
  return zs_device_draw_wide_edges(d, mesh, model, rgb, 1.0, err);
}

zs_status zs_device_draw_wide_edges(zs_device *d, const zs_mesh *mesh, const double model[16],
                                    uint32_t rgb, double width, zs_error *err) {
  const int lw = zs_gl_rounded_size(width, ZS_MAX_LINE_WIDTH);
  if (!lw)
    return zs_error_set(err, ZS_ERR_ARG, "edges: width %g: expected above 0 and at most %d",
                        width, ZS_MAX_LINE_WIDTH);
  if (d->cfg.algo != ZS_ALGO_ZBUFFER)
    return zs_error_set(err, ZS_ERR_UNSUPPORTED, "hidden-line output needs the z-buffer mode");
  zs_status st = zs_device_flush(d, err); /* the edges test the faces' depths */
  if (st != ZS_OK) return st;
  zs_raster_clear_fresh(d);
  zs_draw_prep prep; /* the matrices a draw of the mesh uses */
  zs_draw_prepare(&d->drawing->prep, d->view, d->proj, model, &prep);
  const double *mv = prep.mv, *mvp = prep.mvp;
  zs_command edges = {.kind = ZS_CMD_EDGES, .issued_ps = -1};
  for (int32_t f = 0; f < mesh->nfaces; f++) {
    int32_t s = mesh->face_start[f], n = mesh->face_start[f + 1] - s;
    if (n < 3 || n > ZS_MAX_POLY_VERTS) continue;
    const int32_t *fv = &mesh->face_vert[s];
    double eye[ZS_MAX_POLY_VERTS][4], c[3] = {0, 0, 0}, nrm[3] = {0, 0, 0};
    for (int i = 0; i < n; i++) {
      if (fv[i] < 0 || fv[i] >= mesh->nverts)
        return zs_error_set(err, ZS_ERR_ARG, "edges: face %d uses vertex %d of %d", (int)f,
                            (int)fv[i], (int)mesh->nverts);
      zs_mat_apply(mv, &mesh->pos[3 * fv[i]], eye[i]);
      for (int k = 0; k < 3; k++) c[k] += eye[i][k] / n;
    }
    for (int i = 0; i < n; i++) zs_newell_add(nrm, eye[i], eye[(i + 1) % n]); /* eye space */
    /* V . N >= 0, V from the face to the eye (at the origin): a front face */
    if (-(c[0] * nrm[0] + c[1] * nrm[1] + c[2] * nrm[2]) < 0.0) continue;

    /* The face's depth slope for the bias, from its first three vertices
     * in window coordinates (when all are in front of the eye). */
    double bias = ZS_EDGE_DEPTH_UNITS / 4294967296.0;
    zs_clip_vert cv[3];
    double wv[3][3];
    int front = 1;
    for (int i = 0; i < 3; i++) {
      double o[4];
      zs_mat_apply(mvp, &mesh->pos[3 * fv[i]], o);
      cv[i] = (zs_clip_vert){o[0], o[1], o[2], o[3]};
      front &= o[3] > 0.0;
      if (front) to_window(d, &cv[i], wv[i]);
    }
    if (front) {
      double ux = wv[1][0] - wv[0][0], uy = wv[1][1] - wv[0][1], uz = wv[1][2] - wv[0][2];
      double vx = wv[2][0] - wv[0][0], vy = wv[2][1] - wv[0][1], vz = wv[2][2] - wv[0][2];
      double det = ux * vy - vx * uy;
      if (det != 0.0) {
        double sx = fabs((uz * vy - vz * uy) / det), sy = fabs((ux * vz - vx * uz) / det);
        bias += sx > sy ? sx : sy;
      }
    }
    for (int i = 0; i < n; i++) {
      double o[4];
      zs_mat_apply(mvp, &mesh->pos[3 * fv[i]], o);
      zs_clip_vert a = {o[0], o[1], o[2], o[3]};
      zs_mat_apply(mvp, &mesh->pos[3 * fv[(i + 1) % n]], o);
      zs_clip_vert b = {o[0], o[1], o[2], o[3]};
      if (!zs_clip_segment(&a, &b, d->gx, d->gy)) continue;
      double p[3], q[3];
      to_window(d, &a, p);
      to_window(d, &b, q);
      edges.scan.written += draw_segment(d, p, q, bias, rgb, 1, lw);
    }
  }
  zs_clock_charge(d, &edges);
  return ZS_OK;
}

zs_status zs_device_draw_box_lines(zs_device *d, const double lo[3], const double hi[3],
                                   uint32_t rgb, zs_error *err) {
  if (d->cfg.algo != ZS_ALGO_ZBUFFER)
    return zs_error_set(err, ZS_ERR_UNSUPPORTED, "box outlines need the z-buffer mode");
  zs_raster_clear_fresh(d);
  double mvp[16];
  zs_mat_mul(mvp, d->proj, d->view);
  /* corner b: bit 0 picks x, bit 1 y, bit 2 z; an edge joins corners one
   * bit apart */
  for (int a = 0; a < 8; a++)
    for (int bit = 1; bit < 8; bit <<= 1) {
      int b = a | bit;
      if (b == a) continue;
      double pa[3], pb[3], o[4];
      zs_box_corner(lo, hi, a, pa);
      zs_box_corner(lo, hi, b, pb);
      zs_mat_apply(mvp, pa, o);
      zs_clip_vert va = {o[0], o[1], o[2], o[3]};
      zs_mat_apply(mvp, pb, o);
      zs_clip_vert vb = {o[0], o[1], o[2], o[3]};
      if (!zs_clip_segment(&va, &vb, d->gx, d->gy)) continue;
      double p[3], q[3];
      to_window(d, &va, p);
      to_window(d, &vb, q);
      draw_segment(d, p, q, 0.0, rgb, 0, 1);
    }
  return ZS_OK;
}
