/* Triangle and polygon set-up: snapping, the fixed-point depth plane, and
 * the left and right edge chains of the sorted tables.
 *
 * Snapping.  Window coordinates are rounded to 1/256 pixel (ties to even,
 * the default rounding mode).  Image y is height - window y, computed after
 * rounding in window coordinates so that snapping is the same as OpenGL's.
 *
 * Orientation.  In image coordinates (y down) the shoelace sum
 *   area2 = sum X_i Y_{i+1} - X_{i+1} Y_i
 * is negative for a face counter-clockwise in window coordinates: a front
 * face.  It is exact in 64-bit integers (|X|,|Y| < 2^24).
 *
 * The depth plane (the lecture's ax + by + cz + d = 0, solved for z).  From
 * three snapped vertices, dz/dx and dz/dy per pixel are computed in double
 * (Cramer's rule on exact integer differences), then quantized with
 * 32 + zshift fraction bits.  zshift is the largest of 20 .. 0 for which
 *   (|dzdx| (W + 1/2) + |dzdy| (H + 1/2) + |z_a| + 1) 2^(32 + zshift) < 2^61,
 * W, H the polygon's extent in pixels plus 2, z_a the depth of the plane's
 * vertex, so that no sum over the polygon's box can overflow 64 bits.  Only
 * slivers far thinner than a pixel with nearly the whole depth range
 * across them need fewer bits; past even zshift = 0 their gradient is
 * scaled down to fit (they cover at most a few pixels, and still
 * deterministically).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "raster/setup.h"
#include "util/compiler.h"
#include "raster/tuning.h"
#include "util/exactmath.h"

/* Asks for the cache line at p, to be written (PREFETCHW).  With two
 * threads or more a batch's lines were last read by the other cores, which
 * scanned the chunk set up in it before; a store to such a line waits for
 * them to give it up, and set-up, which writes a polygon and its edges a
 * face, would stall on it (zscan bench raster --case builtin:plant
 * --threads 2 --speedup measures it). */
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
static inline void prefetch_write(const void *p) {
  __asm__ volatile("prefetchw %0" : : "m"(*(const char *)p));
}
#else
static inline void prefetch_write(const void *p) { (void)p; } /* never asked for */
#endif

typedef struct plane {
  int32_t ox, oy;
  int64_t zc, dzdx, dzdy;
  uint8_t zshift;
} plane;

/* The fixed-point plane through vertices a, b, c (indices into X, Y, Z),
 * whose doubled area det must be non-zero; box is the polygon's extent in
 * pixels.  Inlined: called, it would return the plane through memory,
 * two 8-byte stores read back by one 16-byte load that must wait for the
 * store queue to drain (zscan bench raster --case builtin:plant measures
 * it). */
ZS_ALWAYS_INLINE plane
make_plane(const int32_t *X, const int32_t *Y, const double *Z, int a, int b, int c,
           double box_w, double box_h, int *no_depth) {
  double dx1 = (double)X[b] - X[a], dy1 = (double)Y[b] - Y[a];
  double dx2 = (double)X[c] - X[a], dy2 = (double)Y[c] - Y[a];
  double dz1 = Z[b] - Z[a], dz2 = Z[c] - Z[a];
  double det = dx1 * dy2 - dx2 * dy1;
  /* per subpixel, then per pixel */
  double A = (dz1 * dy2 - dz2 * dy1) / det * ZS_SUBPIXEL_ONE;
  double B = (dx1 * dz2 - dx2 * dz1) / det * ZS_SUBPIXEL_ONE;
  plane p;
  p.ox = zs_floordiv256(X[a]);
  p.oy = zs_floordiv256(Y[a]);
  /* Offsets of the origin pixel's centre from vertex a, in pixels (< 1). */
  double cx = ((double)p.ox * 256 + 128 - X[a]) / 256.0;
  double cy = ((double)p.oy * 256 + 128 - Y[a]) / 256.0;
  /* Everything the scan adds up stays below this, in depth units: zc is
   * within half a pixel of vertex a. */
  double bound = fabs(A) * (box_w + 0.5) + fabs(B) * (box_h + 0.5) + fabs(Z[a]) + 1.0;
  /* NaN when a corner has no depth (w = 0, the eye, which a projection
   * may put inside every plane): the face has no plane */
  *no_depth = bound != bound;
  /* bound = m 2^e with m in [0.5, 1): bound 2^(32 + shift) < 2^61 holds
   * exactly when shift <= 29 - e. */
  int e = zs_binary_exponent(bound);
  int shift = 29 - e < 20 ? 29 - e : 20;
  if (shift < 0) {
    double f = ldexp(1.0, 27) / bound; /* fit the gradient to zshift 0 */
    A *= f;
    B *= f;
    shift = 0;
  }
  double zc = Z[a] + A * cx + B * cy;
  double scale = (double)((uint64_t)1 << (32 + shift)); /* 2^(32 + shift), exact */
  p.zshift = (uint8_t)shift;
  p.dzdx = llrint(A * scale);
  p.dzdy = llrint(B * scale);
  p.zc = llrint(zc * scale);
  return p;
}

/* Whether the scan may skip, for every span of p, the clamp to the
 * window's columns and the test of its depths against the planes (the
 * zs_poly's inner).  The exact DDA keeps each span to the columns whose
 * centres lie in [xmin, xmax], p's extent in subpixels, and each row to
 * row0 .. row1; the plane, linear, takes its extremes at the corners of
 * that box, where make_plane's bound keeps it within 64 bits.  One test a
 * polygon instead of two a span. */
static uint8_t spans_inner(int width, const zs_poly *p, int32_t xmin, int32_t xmax) {
  const int32_t c0 = zs_floordiv256((int64_t)xmin + 127); /* first centre >= xmin */
  const int32_t c1 = zs_floordiv256((int64_t)xmax - 128); /* last centre <= xmax */
  if (c0 < 0 || c1 >= width || c0 > c1) return 0;
  const int64_t x0 = p->dzdx * (c0 - p->ox), x1 = p->dzdx * (c1 - p->ox);
  const int64_t y0 = p->dzdy * (p->row0 - p->oy), y1 = p->dzdy * (p->row1 - p->oy);
  const int64_t zmin = p->zc + (x0 < x1 ? x0 : x1) + (y0 < y1 ? y0 : y1);
  const int64_t zmax = p->zc + (x0 < x1 ? x1 : x0) + (y0 < y1 ? y1 : y0);
  return zmin > 0 && zmax < ((int64_t)ZS_DEPTH_FAR << p->zshift);
}

/* Appends the polygon (X, Y)[0..n-1] (convex, y-monotone, area2 != 0) with
 * the given plane; [xmin, xmax] holds its corners' X (the whole face's,
 * for a piece of a fan).  Returns 0 when out of memory. */
static int append_polygon(zs_batch *b, const zs_setup_params *sp, const plane *pl,
                const int32_t *X, const int32_t *Y, int n,
                int64_t area2, int32_t xmin, int32_t xmax) {
  int top = 0, bot = 0;
  for (int i = 1; i < n; i++) {
    if (Y[i] < Y[top]) top = i;
    if (Y[i] > Y[bot]) bot = i;
  }
  int32_t row0 = zs_first_row(Y[top]), row1 = zs_last_row(Y[bot]);
  if (row0 > row1) return 1; /* between two rows of pixel centres */
  /* (the room tested here, a call only to grow it: a face costs less) */
  if ((b->npolys >= b->cap_polys || (int64_t)b->nedges + n > b->cap_edges) &&
      !zs_batch_reserve(b, 1, n))
    return 0;
  if (sp->prefetch_write) { /* a few faces ahead */
    if (b->npolys + ZS_SETUP_PREFETCH_POLYS < b->cap_polys)
      prefetch_write(&b->polys[b->npolys + ZS_SETUP_PREFETCH_POLYS]);
    if (b->nedges + ZS_SETUP_PREFETCH_EDGES < b->cap_edges)
      prefetch_write(&b->edges[b->nedges + ZS_SETUP_PREFETCH_EDGES]);
  }

  zs_poly *p = &b->polys[b->npolys];
  p->id = sp->id;
  p->rgb = sp->rgb;
  p->row0 = row0;
  p->row1 = row1;
  p->ox = pl->ox;
  p->oy = pl->oy;
  p->zc = pl->zc - ((int64_t)sp->depth_bias << pl->zshift);
  if (sp->depth_bias) { /* and by the depth change over 1/16 pixel (raster.h, queries) */
    const int64_t ax = pl->dzdx < 0 ? -pl->dzdx : pl->dzdx, ay = pl->dzdy < 0 ? -pl->dzdy : pl->dzdy;
    p->zc -= (ax + ay) >> ZS_QUERY_SLOPE_SHIFT;
  }
  p->dzdx = pl->dzdx;
  p->dzdy = pl->dzdy;
  p->zshift = pl->zshift;
  p->edge0 = b->nedges;
  /* a polygon of a few rows would pay more for the test than it saves */
  p->inner = row1 - row0 >= ZS_INNER_MIN_ROWS && spans_inner(sp->width, p, xmin, xmax);

  /* Going forward (increasing index) from the top vertex runs down the
   * right side when area2 > 0 (clockwise on the screen), else the left. */
  int forward_is_left = area2 < 0;
  int counts[2] = {0, 0};
  for (int side = 0; side < 2; side++) { /* 0: left chain, 1: right chain */
    int step = ((side == 0) == forward_is_left) ? 1 : n - 1;
    for (int i = top, j; i != bot; i = j) {
      j = i + step < n ? i + step : i + step - n; /* (i + step) mod n */
      zs_edge e = {X[i], Y[i], X[j], Y[j]};
      if (zs_first_row(e.Y0) > zs_last_row(e.Y1)) continue; /* horizontal, or between rows */
      b->edges[b->nedges++] = e;
      counts[side]++;
    }
  }
  p->nleft = (uint8_t)counts[0];
  p->nright = (uint8_t)counts[1];
  b->npolys++;
  return 1;
}

static int64_t cross3(const int32_t *X, const int32_t *Y, int a, int b, int c) {
  return ((int64_t)X[b] - X[a]) * ((int64_t)Y[c] - Y[b]) -
         ((int64_t)Y[b] - Y[a]) * ((int64_t)X[c] - X[b]);
}

static int64_t dot3(const int32_t *X, const int32_t *Y, int a, int b, int c) {
  return ((int64_t)X[b] - X[a]) * ((int64_t)X[c] - X[b]) +
         ((int64_t)Y[b] - Y[a]) * ((int64_t)Y[c] - Y[b]);
}

/* Convex (every turn the way of area2, or straight on) and y-monotone:
 * one left and one right chain, one span per row.  Local turns alone
 * would let a star that winds twice through; monotony catches it.  A
 * turn straight back (no turn, the path reversed) would let a fold hide
 * a reflex corner, whose edge's line then cuts the polygon: the scan's
 * spans would follow the edges in force and the polygon-order
 * traversal's edge functions every edge (polyorder.c), so it goes to the fan. */
static int convex_monotone(const int32_t *X, const int32_t *Y, int n, int64_t area2) {
  /* (neighbours by comparison, not %: a division per vertex costs more
   * than the test on the teapots, whose quads all come here; zscan bench
   * raster --case builtin:teapots --callgrind measures it) */
  for (int i = 0, prev = n - 1; i < n; prev = i++) {
    int next = i + 1 < n ? i + 1 : 0;
    int64_t t = cross3(X, Y, prev, i, next);
    if ((t > 0 && area2 < 0) || (t < 0 && area2 > 0)) return 0;
    if (t == 0 && dot3(X, Y, prev, i, next) < 0) return 0; /* straight back */
  }
  /* Four corners that turn one way wind once: each turns less than half
   * a turn, so the four less than two whole turns; a polygon that winds
   * once and turns one way is convex, and so monotone.  A quad, most
   * faces of a mesh, skips the count below (zscan bench raster --algo
   * zbuffer --case builtin:teapots --callgrind counts what it saves). */
  if (n == 4) return 1;
  /* Going round, the vertical direction may change only at the top and
   * at the bottom vertex. */
  int changes = 0, first = 0, last = 0;
  for (int i = 0; i < n; i++) {
    int next = i + 1 < n ? i + 1 : 0;
    int64_t d = (int64_t)Y[next] - Y[i];
    int s = (d > 0) - (d < 0);
    if (!s) continue;
    if (!first) first = s;
    if (last && s != last) changes++;
    last = s;
  }
  if (first && last && first != last) changes++;
  return changes <= 2;
}

zs_setup_result zs_setup_polygon(zs_batch *b, const zs_setup_params *sp,
                                 const zs_clip_vert *v, int n) {
  zs_snap_vert s[ZS_CLIP_MAX_VERTS];
  int32_t in_order[ZS_CLIP_MAX_VERTS];
  for (int i = 0; i < n; i++) {
    zs_snap_vertex(sp, &v[i], &s[i]);
    in_order[i] = i;
  }
  return zs_setup_snapped(b, sp, s, in_order, n);
}

/* The face (X, Y, Z)[0..m-1] set up: no corner on its predecessor, but
 * for a triangle, whose two corners on one point leave it no area (the
 * area test returns it degenerate).  Inlined three times, so that for a
 * triangle and a quad, m a constant, the loops over the corners unroll;
 * Newell's normal is inlined the same way (draw.c).  Both save
 * instructions a face (zscan bench raster --case "triangles 10x10"
 * --callgrind measures it). */
ZS_ALWAYS_INLINE zs_setup_result
setup_face(zs_batch *b, const zs_setup_params *sp, const int32_t *X, const int32_t *Y,
           const double *Z, const int m) {
  int64_t area2 = 0;
  int32_t xmin = X[0], xmax = X[0], ymin = Y[0], ymax = Y[0];
  for (int i = 0; i < m; i++) {
    int j = i + 1 < m ? i + 1 : 0;
    area2 += (int64_t)X[i] * Y[j] - (int64_t)X[j] * Y[i];
    if (X[i] < xmin) xmin = X[i];
    if (X[i] > xmax) xmax = X[i];
    if (Y[i] < ymin) ymin = Y[i];
    if (Y[i] > ymax) ymax = Y[i];
  }
  if (area2 == 0) return ZS_SETUP_DEGENERATE;
  if (sp->cull_back && area2 > 0) return ZS_SETUP_BACK;
  /* Clipping stops at the guard band, far outside the window: a face
   * whose box holds no pixel centre of the window would only scan its
   * edges down rows it never fills.  The test is on the box, inclusive
   * at both ends, so it never drops a face that covers a pixel. */
  if (xmax < ZS_SUBPIXEL_ONE / 2 || ymax < ZS_SUBPIXEL_ONE / 2 ||
      xmin > (int64_t)sp->width * ZS_SUBPIXEL_ONE - ZS_SUBPIXEL_ONE / 2 ||
      ymin > (int64_t)sp->height * ZS_SUBPIXEL_ONE - ZS_SUBPIXEL_ONE / 2)
    return ZS_SETUP_OFFSCREEN;
  /* No pixel centre in its box (inclusive): it covers no pixel, so it is
   * not entered in the tables, and counts as drawn, as a polygon between
   * two rows of centres always did.  Most faces of the million-triangle
   * teapot field are such specks: they skip the plane, the edges and the
   * scan. */
  if (zs_first_row(ymin) > zs_last_row(ymax) ||
      zs_floordiv256((int64_t)xmin - 129) + 1 > zs_floordiv256((int64_t)xmax - 128))
    return ZS_SETUP_DRAWN;

  /* The plane from the fan triangle (0, k, k+1) of largest area: the best
   * conditioned choice, and the same for every piece of the face. */
  int best = 1;
  int64_t best_area = 0;
  for (int k = 1; k + 1 < m && m > 3; k++) { /* (a triangle has one) */
    int64_t a = llabs(cross3(X, Y, 0, k, k + 1));
    if (a > best_area) {
      best_area = a;
      best = k;
    }
  }
  double box_w = (double)(xmax - xmin) / 256.0 + 2.0;
  double box_h = (double)(ymax - ymin) / 256.0 + 2.0;
  int no_depth;
  plane pl = make_plane(X, Y, Z, 0, best, best + 1, box_w, box_h, &no_depth);
  if (no_depth) return ZS_SETUP_DEGENERATE;

  /* (a triangle of non-zero area always is) */
  if (m == 3 || convex_monotone(X, Y, m, area2))
    return append_polygon(b, sp, &pl, X, Y, m, area2, xmin, xmax) ? ZS_SETUP_DRAWN
                                                 : ZS_SETUP_NOMEM;
  /* Snapping bent the polygon: draw it as a fan of triangles that share its
   * plane; their common edges split the pixels between them exactly. */
  for (int k = 1; k + 1 < m; k++) {
    int64_t a = cross3(X, Y, 0, k, k + 1);
    if (a == 0) continue;
    const int32_t tx[3] = {X[0], X[k], X[k + 1]}, ty[3] = {Y[0], Y[k], Y[k + 1]};
    if (!append_polygon(b, sp, &pl, tx, ty, 3, a, xmin, xmax)) return ZS_SETUP_NOMEM;
  }
  return ZS_SETUP_DRAWN;
}

zs_setup_result zs_setup_snapped(zs_batch *b, const zs_setup_params *sp,
                                 const zs_snap_vert *v, const int32_t *vi, int n) {
  int32_t X[ZS_CLIP_MAX_VERTS], Y[ZS_CLIP_MAX_VERTS];
  double Z[ZS_CLIP_MAX_VERTS];
  if (n == 3) {
    /* Two corners snapped together leave no area: degenerate below, as
     * dropping one would have made it. */
    for (int i = 0; i < 3; i++) {
      X[i] = v[vi[i]].x;
      Y[i] = v[vi[i]].y;
      Z[i] = v[vi[i]].z;
    }
    return setup_face(b, sp, X, Y, Z, 3);
  }
  int m = 0;
  for (int i = 0; i < n; i++) {
    X[m] = v[vi[i]].x;
    Y[m] = v[vi[i]].y;
    Z[m] = v[vi[i]].z;
    /* drop a vertex that snapped onto its predecessor */
    if (m > 0 && X[m] == X[m - 1] && Y[m] == Y[m - 1]) continue;
    m++;
  }
  while (m > 1 && X[m - 1] == X[0] && Y[m - 1] == Y[0]) m--;
  if (m < 3) return ZS_SETUP_DEGENERATE;
  return m == 4 ? setup_face(b, sp, X, Y, Z, 4) : setup_face(b, sp, X, Y, Z, m);
}
