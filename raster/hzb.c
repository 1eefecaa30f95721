/* The hierarchical depth buffer (raster.h, "hzb.c"): Greene, Kass and
 * Miller's z-pyramid, as the two-phase culling of GPU-driven pipelines
 * builds it from the depth buffer and tests boxes against it.
 *
 * Level 0 is the depth buffer itself; texel (x, y) of level k holds the
 * farthest of texels (2x .. 2x + 1, 2y .. 2y + 1) of level k - 1 (those
 * inside it at the odd edges), so it is the farthest depth of the pixels
 * it covers, exactly, in the buffer's 32-bit units.
 *
 * A box is "maybe visible" unless every sample its query box could count
 * lies behind the pyramid.  The pixels: the window rectangle of the box's
 * corners, grown by the query margin (box.h, zs_box_margin) and one
 * more pixel on every side (snapping moves a corner by at most 1/512
 * pixel).  The depth: what a query box is brought nearer by
 * (ZS_QUERY_DEPTH_BIAS units and 1/16 pixel of its face's depth slope),
 * as much again for snapping (the plane of a snapped face strays from its
 * corners by at most the same 1/16 pixel of slope, the bound the query
 * boxes rest on), and 64 units for the fixed-point plane's rounding.  Two
 * stages, both at first at the level where the rectangle spans at most
 * three texels a side:
 *   coarse  the nearest corner's depth against the farthest texels over
 *           the rectangle (the classic test);
 *   fine    each texel against the faces of the box turned to the eye
 *           that reach its pixels' centres, each face's plane at its
 *           nearest over those pixels; where a face may show, the
 *           texel's four children are asked, down to the pixels.  The
 *           texels round the box's outline and the far parts of a long
 *           box so no longer count against it, and the test reads texels
 *           only where the pyramid cannot tell at a coarser level (the
 *           clock charges each one read).
 * A box that the near plane cuts, or that holds the eye, is maybe
 * visible.  tests/test_hzb.c holds this against exact box queries on
 * thousands of random boxes, scenes and cameras.  What the descent to
 * the pixels saves: zscan scan builtin:plant,detail=1 --cull
 * hzb,ideal-box,ideal --frames 60, objects drawn a frame against a
 * descent that stops at 17x17 texels (docs/CULLING.md). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "raster/hzb.h"

#include "raster/box.h"
#include "raster/clip.h"
#include "raster/setup.h"
#include "util/grow.h"

/* The levels 1 .. levels - 1 (level 0 is the depth buffer), level k at
 * texel + offset[k], w[k] x h[k]. */
enum { ZS_HZB_MAX_LEVELS = 24 };
struct zs_hzb {
  uint32_t *texel;
  int32_t cap;
  int levels;
  int w[ZS_HZB_MAX_LEVELS], h[ZS_HZB_MAX_LEVELS];
  int64_t offset[ZS_HZB_MAX_LEVELS];
  int64_t texels;                 /* in levels 1 .. levels - 1 */
  int built;                      /* built since the last clear */
};

zs_hzb *zs_hzb_create(void) { return calloc(1, sizeof(zs_hzb)); }

void zs_hzb_destroy(zs_hzb *h) {
  if (!h) return;
  free(h->texel);
  free(h);
}

void zs_hzb_invalidate(zs_hzb *h) { h->built = 0; }
int zs_hzb_built(const zs_hzb *h) { return h->built; }
size_t zs_hzb_bytes(const zs_hzb *h) { return (size_t)h->cap * sizeof *h->texel; }
int zs_hzb_levels(const zs_hzb *h) { return h->levels; }

const uint32_t *zs_hzb_level(const zs_hzb *h, int k, int *w, int *h_out) {
  *w = h->w[k];
  *h_out = h->h[k];
  return h->texel + h->offset[k];
}

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

int zs_hzb_build(zs_hzb *h, const uint32_t *depth, int width, int height, int64_t *texels) {
  /* the levels' sizes and offsets, once for the buffer's size */
  if (h->levels == 0) {
    int w = width, ht = height, k = 0;
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
    if (!zs_grow((void **)&h->texel, &h->cap, total > 0 ? total : 1, sizeof *h->texel)) return 0;
    h->levels = k + 1;
    h->texels = total;
  }
  const uint32_t *src = depth;
  for (int k = 1; k < h->levels; k++) {
    uint32_t *dst = h->texel + h->offset[k];
    reduce_level(src, h->w[k - 1], h->h[k - 1], dst, h->w[k], h->h[k]);
    src = dst;
  }
  h->built = 1;
  *texels = h->texels;
  return 1;
}

/* The texels of level k over pixels [x0, x1] x [y0, y1]: the farthest. */
static uint32_t farthest_over(const zs_hzb *h, const uint32_t *depth, int k, int x0, int y0,
                              int x1, int y1) {
  const uint32_t *lv = k == 0 ? depth : h->texel + h->offset[k];
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

/* A face of a box in the window: its corners (x right, y down, pixels),
 * its plane z = a x + b y + c (window depth), and what a query brings it
 * nearer by, in the buffer's units (the bias and slope of a query box,
 * as much again for snapping, 64 for the plane's rounding). */
typedef struct face_plane {
  double x[4], y[4];
  double xmin, xmax, ymin, ymax; /* the corners' box */
  double a, b, c;
  double slack;
  double orient; /* the sign of the corners' winding */
} face_plane;

/* The plane through corners q[0], q[1], q[3] of win; 0 when the face is
 * seen edge-on. */
static int face_plane_of(const double (*win)[3], const int32_t q[4], face_plane *f) {
  const double *p0 = win[q[0]], *p1 = win[q[1]], *p3 = win[q[3]];
  const double ux = p1[0] - p0[0], uy = p1[1] - p0[1], uz = p1[2] - p0[2];
  const double vx = p3[0] - p0[0], vy = p3[1] - p0[1], vz = p3[2] - p0[2];
  const double det = ux * vy - vx * uy;
  if (!(det != 0.0)) return 0;
  f->a = (uz * vy - vz * uy) / det;
  f->b = (ux * vz - vx * uz) / det;
  f->c = p0[2] - f->a * p0[0] - f->b * p0[1];
  f->slack = ZS_QUERY_DEPTH_BIAS + (fabs(f->a) + fabs(f->b)) * 4294967296.0 / 8.0 + 64.0;
  f->orient = det > 0.0 ? 1.0 : -1.0;
  for (int i = 0; i < 4; i++) {
    f->x[i] = win[q[i]][0];
    f->y[i] = win[q[i]][1];
  }
  f->xmin = fmin(fmin(f->x[0], f->x[1]), fmin(f->x[2], f->x[3]));
  f->xmax = fmax(fmax(f->x[0], f->x[1]), fmax(f->x[2], f->x[3]));
  f->ymin = fmin(fmin(f->y[0], f->y[1]), fmin(f->y[2], f->y[3]));
  f->ymax = fmax(fmax(f->y[0], f->y[1]), fmax(f->y[2], f->y[3]));
  return 1;
}

/* Whether the rectangle [X0, X1] x [Y0, Y1] meets the face's quadrilateral
 * (convex: a parallelogram seen in perspective): no edge of the quad has
 * the whole rectangle outside it, and the boxes overlap. */
static int rect_meets_face(const face_plane *f, double X0, double Y0, double X1, double Y1) {
  if (f->xmax < X0 || f->xmin > X1 || f->ymax < Y0 || f->ymin > Y1) return 0;
  for (int i = 0, j = 3; i < 4; j = i++) {
    const double ex = f->x[i] - f->x[j], ey = f->y[i] - f->y[j];
    const double cx[4] = {X0, X1, X0, X1}, cy[4] = {Y0, Y0, Y1, Y1};
    int outside = 0;
    for (int c = 0; c < 4; c++)
      outside += f->orient * (ex * (cy[c] - f->y[j]) - ey * (cx[c] - f->x[j])) < 0.0;
    if (outside == 4) return 0;
  }
  return 1;
}

/* The pixels a box's test looks at, and what the faces it would draw
 * reach there. */
typedef struct box_test {
  int x0, y0, x1, y1;     /* the pixels, within the window */
  const face_plane *fp;   /* the faces turned to the eye */
  int nf;
  uint64_t *reads;        /* texels read, counted on */
} box_test;

/* Whether texel (tx, ty) of level k, over the pixels of the box's test
 * it covers, may show a query of the faces a sample: the texel's farthest
 * depth against each face that reaches those pixels' centres (with 1/64
 * pixel to spare for snapping), the face's plane at its nearest over
 * them.  Where a face may show, a texel above level 0 cannot tell: its
 * farthest depth may be one pixel's, so its four children are asked in
 * turn, down to the depth buffer's own pixels.  A box hidden everywhere
 * but at its outline's pixels is so found hidden, which a test at one
 * level is not; a visible box stops at the first pixel that shows it. */
static int texel_maybe_visible(const zs_hzb *h, const uint32_t *depth, box_test *t, int k, int tx,
                               int ty) {
  const uint32_t *lv = k == 0 ? depth : h->texel + h->offset[k];
  const double e = 1.0 / 64.0;
  const int r0 = ty << k > t->y0 ? ty << k : t->y0;
  const int r1 = ((ty + 1) << k) - 1 < t->y1 ? ((ty + 1) << k) - 1 : t->y1;
  const int c0 = tx << k > t->x0 ? tx << k : t->x0;
  const int c1 = ((tx + 1) << k) - 1 < t->x1 ? ((tx + 1) << k) - 1 : t->x1;
  const double Y0 = r0 + 0.5 - e, Y1 = r1 + 0.5 + e, X0 = c0 + 0.5 - e, X1 = c1 + 0.5 + e;
  const double far = lv[(size_t)ty * (size_t)h->w[k] + (size_t)tx];
  ++*t->reads;
  int shows = 0;
  for (int i = 0; i < t->nf && !shows; i++) {
    const face_plane *f = &t->fp[i];
    if (!rect_meets_face(f, X0, Y0, X1, Y1)) continue;
    const double z = fmin(fmin(f->a * X0 + f->b * Y0, f->a * X1 + f->b * Y0),
                          fmin(f->a * X0 + f->b * Y1, f->a * X1 + f->b * Y1)) + f->c;
    const double bound = z * 4294967296.0 - f->slack;
    shows = !(far < bound); /* NaN too */
  }
  if (!shows || k == 0) return shows;
  /* the children over the test's pixels: the texel's first pixel row and
   * column lie in them (c0, r0), its last ones may not */
  for (int cy = 2 * ty; cy <= 2 * ty + 1 && cy << (k - 1) <= r1; cy++)
    for (int cx = 2 * tx; cx <= 2 * tx + 1 && cx << (k - 1) <= c1; cx++)
      if (((cx + 1) << (k - 1)) > c0 && ((cy + 1) << (k - 1)) > r0 &&
          texel_maybe_visible(h, depth, t, k - 1, cx, cy))
        return 1;
  return 0;
}

/* Whether the box lo..hi may show a sample to a query (1) or is hidden
 * behind the pyramid (0); adds the texels it read to *reads. */
static int box_maybe_visible(const zs_hzb *h, const uint32_t *depth, const zs_hzb_view *v,
                             const double lo[3], const double hi[3], uint64_t *reads) {
  const double m = zs_box_margin(v->view, v->proj, v->perspective, v->width, v->height, lo, hi);
  const double blo[3] = {lo[0] - m, lo[1] - m, lo[2] - m};
  const double bhi[3] = {hi[0] + m, hi[1] + m, hi[2] + m};
  if (zs_box_holds(blo, bhi, v->eye)) return 1;
  /* the corners in the window: x right, y down, z the window depth */
  double win[8][3];
  double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY, zmin = INFINITY;
  for (int b = 0; b < 8; b++) {
    double p[3], o[4];
    zs_box_corner(blo, bhi, b, p);
    zs_mat_apply(v->mvp, p, o);
    const zs_clip_vert c = {o[0], o[1], o[2], o[3]};
    if (!(c.w > 0.0) || !(c.z + c.w >= 0.0)) return 1; /* the near plane cuts it */
    zs_window_xy(v->width, v->height, &c, &win[b][0], &win[b][1]);
    win[b][1] = v->height - win[b][1];
    win[b][2] = zs_window_depth(&c);
    xmin = fmin(xmin, win[b][0]);
    xmax = fmax(xmax, win[b][0]);
    ymin = fmin(ymin, win[b][1]);
    ymax = fmax(ymax, win[b][1]);
    zmin = fmin(zmin, win[b][2]);
  }
  /* the pixels whose centres the query box could cover, within the window */
  if (!(xmax >= -1.0 && ymax >= -1.0 && xmin <= v->width + 1.0 && ymin <= v->height + 1.0))
    return 0; /* no pixel of the window: the query counts none */
  box_test t = {(int)fmax(floor(xmin) - 1.0, 0.0), (int)fmax(floor(ymin) - 1.0, 0.0),
                (int)fmin(floor(xmax) + 1.0, v->width - 1.0),
                (int)fmin(floor(ymax) + 1.0, v->height - 1.0), NULL, 0, reads};
  if (t.x0 > t.x1 || t.y0 > t.y1) return 0;
  /* the faces the query would draw: those turned to the eye */
  face_plane fp[3];
  double slope = 0.0;
  for (int f = 0; f < 6; f++) {
    if (!zs_box_face_turned_to(blo, bhi, v->eye, f)) continue;
    if (!face_plane_of(win, zs_box_faces[f], &fp[t.nf])) return 1; /* seen edge-on: no bound */
    slope = fmax(slope, fabs(fp[t.nf].a) + fabs(fp[t.nf].b));
    t.nf++;
  }
  t.fp = fp;
  /* First, coarsely: the rectangle's farthest texels (at most 3x3) against
   * the nearest depth of the whole box. */
  const double near = zmin * 4294967296.0 - ZS_QUERY_DEPTH_BIAS - slope * 4294967296.0 / 8.0 - 64.0;
  if (!(near > 0.0)) return 1; /* NaN too */
  const int span = (t.x1 - t.x0 > t.y1 - t.y0 ? t.x1 - t.x0 : t.y1 - t.y0) + 1;
  int k = 0;
  while ((1 << k) < span >> 1 && k + 1 < h->levels) k++;
  *reads += (uint64_t)(((t.x1 >> k) - (t.x0 >> k) + 1) * ((t.y1 >> k) - (t.y0 >> k) + 1));
  if ((double)farthest_over(h, depth, k, t.x0, t.y0, t.x1, t.y1) < near) return 0;
  /* Then finely: the same texels, each against the nearest depth of the
   * faces that reach it, over its own pixels, and where that cannot tell,
   * its children, down to the pixels. */
  int shows = 0;
  for (int ty = t.y0 >> k; ty <= t.y1 >> k && !shows; ty++)
    for (int tx = t.x0 >> k; tx <= t.x1 >> k && !shows; tx++)
      shows = texel_maybe_visible(h, depth, &t, k, tx, ty);
  return shows;
}

uint64_t zs_hzb_test(const zs_hzb *h, const uint32_t *depth, const zs_hzb_view *v,
                     const double (*lo)[3], const double (*hi)[3], int n, uint8_t *maybe_visible) {
  uint64_t reads = 0;
  for (int i = 0; i < n; i++)
    maybe_visible[i] = (uint8_t)box_maybe_visible(h, depth, v, lo[i], hi[i], &reads);
  return reads;
}
