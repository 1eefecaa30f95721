/* Lines and points with a width (zscan.h, "Lines and points"). */
#include <math.h>

#include "raster/device.h"
#include "raster/setup.h"
#include "util/compiler.h"

/* a / b rounded down, b > 0 */
static int64_t floor_div(int64_t a, int64_t b) {
  int64_t q = a / b;
  return q * b > a ? q - 1 : q;
}

/* a / b rounded up, b > 0 */
static int64_t ceil_div(int64_t a, int64_t b) { return -floor_div(-a, b); }

/* A fragment (z, id) at pixel (x, y).  In zbuffer mode tested against
 * the full frame by the depth test of every draw (raster.h, DEPTH) and
 * written when it is in front: 1; in scanline mode kept for its row,
 * which finish tests it against (prim_rows.h): 0, counted there.  rows
 * is a constant where this is inlined: each mode gets its own loops. */
ZS_ALWAYS_INLINE int put(zs_device *d, const int rows, int64_t x, int64_t y, uint32_t z,
                         uint32_t id, uint32_t rgb) {
  if (rows) {
    zs_prim_rows_keep(&d->prim_rows, (uint32_t)x, (uint32_t)y, z, id, rgb);
    return 0;
  }
  const size_t i = (size_t)y * (size_t)d->cfg.width + (size_t)x;
  if (d->count) d->count[i]++;
  if (z > d->depth[i] || (z == d->depth[i] && id >= d->id[i])) return 0;
  d->depth[i] = z;
  d->id[i] = id;
  d->rgb[i] = rgb;
  return 1;
}

/* A vertex of the mesh in clip space. */
static zs_clip_vert clip_of(const double mvp[16], const double *pos) {
  double o[4];
  zs_mat_apply(mvp, pos, o);
  return (zs_clip_vert){o[0], o[1], o[2], o[3]};
}

/* Window depth as the depth buffer holds it (raster.h, DEPTH). */
static uint32_t depth_word(double z) {
  double q = z * 4294967296.0;
  return q <= 0.0 ? 0u : q >= 4294967295.0 ? ZS_DEPTH_FAR : (uint32_t)q;
}

/* ---- lines ----
 *
 * A line p-q, snapped to 1/256 pixel, is x-major when |dx| >= |dy|.  It
 * draws one fragment in each column (row, for a y-major line) from the
 * pixel that holds p to the one that holds q: the pixel the exact line
 * crosses the column's centre in, as GL's diamond-exit rule gives it.
 * That rule draws a pixel when the line leaves its diamond |x - xc| +
 * |y - yc| < 1/2; for a line of slope at most 1 this is exact, in
 * integers, as: every column between the ends'; the start's column when
 * p is at or before the column's centre (the line crosses it) or inside
 * its pixel's diamond; the end's column when q is past the column's
 * centre and outside its pixel's diamond (one column: both).  So a strip
 * of lines draws each shared end once.  At each drawn column, a line of
 * width w covers the w pixels across it whose centres lie within w/2 of
 * the exact line, by the top-left rule (raster.h, COVERAGE): x from x -
 * w/2 inclusive to x + w/2 exclusive, image y from y - w/2 exclusive to y
 * + w/2 inclusive.  That is GL's wide line: the width-1 line's fragment
 * replaced by a column of w, its ends square to the major axis (butt
 * caps, never square to the line).  The depth is the line's at the column
 * centre, interpolated in integers from the ends' depth words. */

typedef struct line_px {
  int64_t a0, da, m0, dm; /* major and minor start (1/256 px) and extents */
  int64_t z0, dz;         /* depth words */
  int major_x;
} line_px;

/* Whether the point (a, m) lies strictly inside the diamond of the pixel
 * it is in, |a - ac| + |m - mc| < 1/2 with (ac, mc) the pixel's centre. */
static int in_diamond(int64_t a, int64_t m) {
  const int64_t one = ZS_SUBPIXEL_ONE, half = ZS_SUBPIXEL_ONE / 2;
  int64_t ea = a - (one * floor_div(a, one) + half), em = m - (one * floor_div(m, one) + half);
  return (ea < 0 ? -ea : ea) + (em < 0 ? -em : em) < half;
}

ZS_ALWAYS_INLINE uint64_t draw_line(zs_device *d, const int rows, const zs_snap_vert *p,
                                    const zs_snap_vert *q, int w, uint32_t id, uint32_t rgb) {
  const int64_t dx = (int64_t)q->x - p->x, dy = (int64_t)q->y - p->y;
  if (dx == 0 && dy == 0) return 0;
  const int major_x = (dx < 0 ? -dx : dx) >= (dy < 0 ? -dy : dy);
  line_px L = {major_x ? p->x : p->y, major_x ? dx : dy, major_x ? p->y : p->x,
               major_x ? dy : dx, depth_word(p->z), (int64_t)depth_word(q->z) - depth_word(p->z),
               major_x};
  const int64_t one = ZS_SUBPIXEL_ONE, half = ZS_SUBPIXEL_ONE / 2;
  const int64_t a_end = L.a0 + L.da, m_end = L.m0 + L.dm;
  /* the pixels of the ends along the major axis, and whether each end's
   * fragment is drawn: the diamond-exit rule, exact (see above) */
  const int64_t s = L.da > 0 ? 1 : -1;
  const int64_t ks = floor_div(L.a0, one), ke = floor_div(a_end, one);
  const int start_in = s * (L.a0 - (one * ks + half)) <= 0 || in_diamond(L.a0, L.m0);
  const int end_in = s * (a_end - (one * ke + half)) > 0 && !in_diamond(a_end, m_end);
  int64_t k0, k1; /* the drawn pixels, first to last along the line */
  if (ks == ke) {
    if (!(start_in && end_in)) return 0;
    k0 = k1 = ks;
  } else {
    k0 = start_in ? ks : ks + s;
    k1 = end_in ? ke : ke - s;
  }
  if (s < 0) { /* walked in increasing order below */
    const int64_t t = k0;
    k0 = k1;
    k1 = t;
  }
  const int64_t major_n = major_x ? d->cfg.width : d->cfg.height;
  const int64_t minor_n = major_x ? d->cfg.height : d->cfg.width;
  if (k0 < 0) k0 = 0;
  if (k1 > major_n - 1) k1 = major_n - 1;
  /* with da > 0: the minor coordinate at centre c is N(c) / da, N(c) =
   * m0 da + dm (c - a0) */
  const int64_t da = s * L.da, dm = s * L.dm;
  const int64_t hw = half * w;
  uint64_t written = 0;
  for (int64_t k = k0; k <= k1; k++) {
    const int64_t c = one * k + half;
    const int64_t n = L.m0 * da + dm * (c - L.a0);
    int64_t lo, hi; /* minor pixels lo .. hi */
    if (major_x) { /* minor y, image down: y - w/2 < centre <= y + w/2 */
      lo = floor_div(n - (half + hw) * da, one * da) + 1;
      hi = floor_div(n - (half - hw) * da, one * da);
    } else { /* minor x: x - w/2 <= centre < x + w/2 */
      lo = ceil_div(n - (half + hw) * da, one * da);
      hi = ceil_div(n - (half - hw) * da, one * da) - 1;
    }
    if (lo < 0) lo = 0;
    if (hi > minor_n - 1) hi = minor_n - 1;
    /* (a start inside its diamond but past the column's centre puts the
     * centre before the line: its depth, extrapolated, kept in range) */
    const int64_t zc = L.z0 + floor_div(L.dz * (c - L.a0) * s, da);
    const uint32_t z = zc < 0 ? 0u : zc > (int64_t)ZS_DEPTH_FAR ? ZS_DEPTH_FAR : (uint32_t)zc;
    for (int64_t j = lo; j <= hi; j++)
      written += (uint64_t)(major_x ? put(d, rows, k, j, z, id, rgb) : put(d, rows, j, k, z, id, rgb));
  }
  return written;
}

/* ---- points ----
 *
 * A point of size s, snapped to 1/256 pixel, covers the pixels whose
 * centres lie in the square of side s about it, the square's right and
 * (window y up) top sides included and its left and bottom sides not:
 * GL's aliased point, an odd size centred on the pixel the point is in
 * and an even one on the pixel corner floor(x + 1/2), floor(y + 1/2).  A
 * disc covers the pixels of that square whose centres lie strictly within
 * s/2 of the point.  Its depth is the point's. */
ZS_ALWAYS_INLINE uint64_t draw_point(zs_device *d, const int rows, const zs_snap_vert *p, int s,
                                     zs_point_shape shape, uint32_t id, uint32_t rgb) {
  const int64_t one = ZS_SUBPIXEL_ONE, half = ZS_SUBPIXEL_ONE / 2, hs = half * s;
  /* centres in (x - s/2, x + s/2] and, image y down, [y - s/2, y + s/2) */
  int64_t x0 = floor_div(p->x - hs - half, one) + 1, x1 = floor_div(p->x + hs - half, one);
  int64_t y0 = ceil_div(p->y - hs - half, one), y1 = ceil_div(p->y + hs - half, one) - 1;
  if (x0 < 0) x0 = 0;
  if (y0 < 0) y0 = 0;
  if (x1 > d->cfg.width - 1) x1 = d->cfg.width - 1;
  if (y1 > d->cfg.height - 1) y1 = d->cfg.height - 1;
  const uint32_t z = depth_word(p->z);
  uint64_t written = 0;
  for (int64_t y = y0; y <= y1; y++)
    for (int64_t x = x0; x <= x1; x++) {
      const int64_t ex = one * x + half - p->x, ey = one * y + half - p->y;
      if (shape == ZS_POINT_DISC && ex * ex + ey * ey >= hs * hs) continue;
      written += (uint64_t)put(d, rows, x, y, z, id, rgb);
    }
  return written;
}

/* ---- the draws ---- */

/* Each of the two, for the full frame and for scanline mode's rows. */
static uint64_t line_into_frame(zs_device *d, const zs_snap_vert *p, const zs_snap_vert *q,
                                int w, uint32_t id, uint32_t rgb) {
  return draw_line(d, 0, p, q, w, id, rgb);
}
static uint64_t line_into_rows(zs_device *d, const zs_snap_vert *p, const zs_snap_vert *q,
                               int w, uint32_t id, uint32_t rgb) {
  return draw_line(d, 1, p, q, w, id, rgb);
}
static uint64_t point_into_frame(zs_device *d, const zs_snap_vert *p, int s,
                                 zs_point_shape shape, uint32_t id, uint32_t rgb) {
  return draw_point(d, 0, p, s, shape, id, rgb);
}
static uint64_t point_into_rows(zs_device *d, const zs_snap_vert *p, int s,
                                zs_point_shape shape, uint32_t id, uint32_t rgb) {
  return draw_point(d, 1, p, s, shape, id, rgb);
}

/* What a draw of lines or points needs of the device, checked; in
 * zbuffer mode the queued faces painted first, so that these test
 * against them. */
static zs_status begin_prims(zs_device *d, const char *what, const double model[16],
                             double mvp[16], zs_error *err) {
  if (d->cfg.algo == ZS_ALGO_DEPTHSORT)
    return zs_error_set(err, ZS_ERR_UNSUPPORTED, "%s need the zbuffer or scanline mode", what);
  zs_status st = zs_device_flush(d, err);
  if (st != ZS_OK) return st;
  if (d->cfg.algo == ZS_ALGO_ZBUFFER) zs_raster_clear_fresh(d);
  zs_mat_mul(mvp, d->view, model);
  zs_mat_mul(mvp, d->proj, mvp);
  return ZS_OK;
}

static uint32_t prim_rgb(const uint32_t *each, int32_t k, uint32_t rgb) {
  return (rgb != ZS_RGB_MESH ? rgb : each ? each[k] : ZS_DEFAULT_RGB) & 0xFFFFFFu;
}

zs_status zs_device_draw_lines(zs_device *d, const zs_mesh *mesh, const double model[16],
                               uint32_t id_base, uint32_t rgb, double width, zs_error *err) {
  const int w = zs_gl_rounded_size(width, ZS_MAX_LINE_WIDTH);
  if (!w)
    return zs_error_set(err, ZS_ERR_ARG, "lines: width %g: expected above 0 and at most %d",
                        width, ZS_MAX_LINE_WIDTH);
  if (mesh->nlines <= 0) return ZS_OK;
  double mvp[16];
  zs_status st = begin_prims(d, "lines", model, mvp, err);
  if (st != ZS_OK) return st;
  uint64_t (*const line)(zs_device *, const zs_snap_vert *, const zs_snap_vert *, int, uint32_t,
                         uint32_t) = d->cfg.algo == ZS_ALGO_ZBUFFER ? line_into_frame
                                                                    : line_into_rows;
  const zs_setup_params sp = {.width = d->cfg.width, .height = d->cfg.height};
  zs_command c = {.kind = ZS_CMD_EDGES, .issued_ps = -1};
  for (int32_t k = 0; k < mesh->nlines; k++) {
    const int32_t a = mesh->line_vert[2 * k], b = mesh->line_vert[2 * k + 1];
    if (a < 0 || a >= mesh->nverts || b < 0 || b >= mesh->nverts)
      return zs_error_set(err, ZS_ERR_ARG, "lines: line %d uses vertex %d of %d", (int)k,
                          (int)(a < 0 || a >= mesh->nverts ? a : b), (int)mesh->nverts);
    zs_clip_vert u = clip_of(mvp, &mesh->pos[3 * (size_t)a]), v = clip_of(mvp, &mesh->pos[3 * (size_t)b]);
    if (!zs_clip_segment(&u, &v, d->gx, d->gy)) continue;
    zs_snap_vert p, q;
    zs_snap_vertex(&sp, &u, &p);
    zs_snap_vertex(&sp, &v, &q);
    c.scan.written += line(d, &p, &q, w, id_base + (uint32_t)mesh->prim_id + (uint32_t)k,
                           prim_rgb(mesh->line_rgb, k, rgb));
  }
  zs_clock_charge(d, &c);
  if (d->prim_rows.nomem) return zs_error_set(err, ZS_ERR_NOMEM, "lines: out of memory");
  return ZS_OK;
}

zs_status zs_device_draw_points(zs_device *d, const zs_mesh *mesh, const double model[16],
                                uint32_t id_base, uint32_t rgb, double size,
                                zs_point_shape shape, zs_error *err) {
  const int s = zs_gl_rounded_size(size, ZS_MAX_POINT_SIZE);
  if (!s)
    return zs_error_set(err, ZS_ERR_ARG, "points: size %g: expected above 0 and at most %d",
                        size, ZS_MAX_POINT_SIZE);
  if (shape != ZS_POINT_SQUARE && shape != ZS_POINT_DISC)
    return zs_error_set(err, ZS_ERR_ARG, "points: shape %d: expected ZS_POINT_SQUARE or _DISC",
                        (int)shape);
  if (mesh->npoints <= 0) return ZS_OK;
  double mvp[16];
  zs_status st = begin_prims(d, "points", model, mvp, err);
  if (st != ZS_OK) return st;
  uint64_t (*const point)(zs_device *, const zs_snap_vert *, int, zs_point_shape, uint32_t,
                          uint32_t) = d->cfg.algo == ZS_ALGO_ZBUFFER ? point_into_frame
                                                                     : point_into_rows;
  const zs_setup_params sp = {.width = d->cfg.width, .height = d->cfg.height};
  zs_command c = {.kind = ZS_CMD_EDGES, .issued_ps = -1};
  const uint32_t first = id_base + (uint32_t)mesh->prim_id + (uint32_t)mesh->nlines;
  for (int32_t k = 0; k < mesh->npoints; k++) {
    const int32_t v = mesh->point_vert[k];
    if (v < 0 || v >= mesh->nverts)
      return zs_error_set(err, ZS_ERR_ARG, "points: point %d uses vertex %d of %d", (int)k,
                          (int)v, (int)mesh->nverts);
    const zs_clip_vert u = clip_of(mvp, &mesh->pos[3 * (size_t)v]);
    /* GL clips a point by its centre: drawn whole when that is inside
     * every plane, else not at all */
    if (!(u.w > 0.0) || u.z < -u.w || u.z > u.w || u.x < -u.w || u.x > u.w || u.y < -u.w ||
        u.y > u.w)
      continue;
    zs_snap_vert p;
    zs_snap_vertex(&sp, &u, &p);
    c.scan.written += point(d, &p, s, shape, first + (uint32_t)k,
                            prim_rgb(mesh->point_rgb, k, rgb));
  }
  zs_clock_charge(d, &c);
  if (d->prim_rows.nomem) return zs_error_set(err, ZS_ERR_NOMEM, "points: out of memory");
  return ZS_OK;
}
