/* zscan raster — what the traversals of a batch share: the span kernels
 * (what a polygon's run of pixels on one row does to the target, one loop
 * per kernel: draw, overdraw, query, inlined into each traversal with the
 * kernel and the SIMD level constants), and a polygon being traversed
 * (zs_active: its entry at its first row, its span on a row, its step
 * down a row).  The row scan (scanline.c) and the polygon-order traversal
 * (polyorder.c) both use them, so both test and write the same pixels
 * the same way. */
#ifndef ZS_RASTER_SPAN_H
#define ZS_RASTER_SPAN_H

#include <limits.h>
#include <string.h>

#include "raster/edge_dda.h"
#include "util/compiler.h"
#include "raster/span_simd.h"
#include "raster/traversal.h"

static inline uint32_t zs_depth_of(int64_t z, int shift, int64_t zfar) {
  if (z <= 0) return 0;
  if (z >= zfar) return ZS_DEPTH_FAR;
  return (uint32_t)(z >> shift);
}

/* One row of the target: where a row's spans land. */
typedef struct zs_row_ptrs {
  uint32_t *depth, *id, *rgb, *count;
  zs_fragment_row *frags; /* the fragment kernel's */
} zs_row_ptrs;

static inline zs_row_ptrs zs_row_of(const zs_target *t, int32_t y) {
  const int64_t off = t->row_stride * (y - t->row0);
  zs_row_ptrs r = {t->depth ? t->depth + off : NULL, t->id ? t->id + off : NULL,
                   t->rgb ? t->rgb + off : NULL, t->count ? t->count + off : NULL,
                   t->frags ? &t->frags[y] : NULL};
  return r;
}

/* Clears row y of a lazily cleared target, the first time a scan reaches
 * it (zs_target.fresh). */
static inline void zs_clear_row(const zs_target *t, int32_t y) {
  const zs_row_ptrs r = zs_row_of(t, y);
  zs_clear_pixels(r.depth, r.id, r.rgb, r.count, (size_t)t->width, t->background);
  t->fresh[y] = 0;
}

/* The span kernels, one loop per kernel: each traversal is inlined into
 * a copy per kernel and SIMD level with k and simd constants, chosen once
 * per device (traversal.h).  The span [x0, x1) of a's polygon, z its
 * depth plane at x0. */
static inline void zs_fill_span(const zs_kernel k, const zs_row_ptrs *row, int x0, int x1,
                                int64_t z, const zs_active *a, const zs_simd simd,
                                const int vector_from,
                                uint64_t *written) {
  if (k == ZS_KERNEL_OVERDRAW) {
    uint32_t *cnt = row->count;
    for (int x = x0; x < x1; x++) cnt[x]++;
    *written += (uint64_t)(x1 - x0);
    return;
  }
  const int64_t dz = a->dzdx, zfar = (int64_t)ZS_DEPTH_FAR << a->zshift;
  const int shift = a->zshift;
  uint64_t w = 0;
  if (k == ZS_KERNEL_QUERY) {
    const uint32_t *zr = row->depth;
    if (a->inner)
      for (int x = x0; x < x1; x++, z += dz) w += (uint32_t)(z >> shift) <= zr[x];
    else
      for (int x = x0; x < x1; x++, z += dz) w += zs_depth_of(z, shift, zfar) <= zr[x];
    *written += w;
    return;
  }
  if (k == ZS_KERNEL_FRAGMENT) {
    const uint32_t *zr = row->depth, *ir = row->id;
    zs_fragment_row *fr = row->frags;
    if (!zs_fragment_reserve(fr, x1 - x0)) return;
    zs_fragment *f = fr->f + fr->n;
    for (int x = x0; x < x1; x++, z += dz) {
      const uint32_t d = zs_depth_of(z, shift, zfar), zb = zr[x];
      if (d < zb || (d == zb && a->id < ir[x])) *f++ = (zs_fragment){x, d, a->id, a->rgb};
    }
    w = (uint64_t)(f - (fr->f + fr->n));
    fr->n += (int32_t)w;
    *written += w;
    return;
  }
  uint32_t *zr = row->depth, *ir = row->id, *cr = row->rgb;
  const uint32_t id = a->id, rgb = a->rgb;
  /* z is linear along the span: when both ends lie strictly between the
   * planes (0 < z < zfar, as one unsigned compare), so does every pixel,
   * and depth_of is a shift; an inner polygon's spans all do */
  if (a->inner || ((uint64_t)z - 1u < (uint64_t)zfar - 1u &&
                   (uint64_t)(z + dz * (x1 - 1 - x0)) - 1u < (uint64_t)zfar - 1u)) {
    if (x1 - x0 >= vector_from) { /* whole vector steps, the rest below */
      int xs = zs_fill_span_wide(simd, zr, ir, cr, x0, x1, z, dz, shift, id, rgb, written);
      z += dz * (xs - x0);
      x0 = xs;
    }
    for (int x = x0; x < x1; x++, z += dz) {
      uint32_t d = (uint32_t)(z >> shift), zb = zr[x];
      if (d < zb || (d == zb && id < ir[x])) {
        zr[x] = d;
        ir[x] = id;
        cr[x] = rgb;
        w++;
      }
    }
    *written += w;
    return;
  }
  for (int x = x0; x < x1; x++, z += dz) {
    uint32_t d = zs_depth_of(z, shift, zfar);
    uint32_t zb = zr[x];
    if (d < zb || (d == zb && id < ir[x])) {
      zr[x] = d;
      ir[x] = id;
      cr[x] = rgb;
      w++;
    }
  }
  *written += w;
}

/* Asks for the table's records the traversal reads a few polygons on
 * (tuning.h): order[j] is about to be read; the polygon record some
 * places on and the edges of one nearer (whose record has arrived by
 * then) are fetched ahead.  In a soup each record is a cache miss, and
 * without it the traversal waits on each in turn.  Inlined by force: a
 * function whose only work is a prefetch has no effect gcc must keep, and
 * gcc drops its calls where it does not inline it first. */
ZS_ALWAYS_INLINE void
zs_table_prefetch(const zs_batch *b, const int32_t *order, int32_t j, int32_t n) {
  if (j + ZS_TABLE_PREFETCH_POLYS < n)
    ZS_PREFETCH(&b->polys[order[j + ZS_TABLE_PREFETCH_POLYS]]);
  if (j + ZS_TABLE_PREFETCH_EDGES < n)
    ZS_PREFETCH(&b->edges[b->polys[order[j + ZS_TABLE_PREFETCH_EDGES]].edge0]);
}

/* Index of the edge of chain [first, last] that covers row. */
static inline int32_t zs_edge_at(const zs_edge *edges, int32_t first, int32_t last,
                                 int32_t row) {
  int32_t i = first;
  while (i < last && zs_last_row(edges[i].Y1) < row) i++;
  return i;
}

/* p's depth plane at (0, y), modulo 2^64 (zs_plane_at). */
static inline uint64_t zs_plane_row(const zs_poly *p, int32_t y) {
  return (uint64_t)p->zc - (uint64_t)p->dzdx * (uint64_t)(int64_t)p->ox +
         (uint64_t)p->dzdy * (uint64_t)((int64_t)y - p->oy);
}

/* Polygon i enters at row y: its edge pair on that row and zl; the
 * edges' steps down a row always (steps), or only where taken
 * (zs_edge_dda_begin). */
static inline void zs_activate(zs_active *a, int32_t i, const zs_poly *p, const zs_edge *edges,
                               int32_t y, const int steps) {
  const int32_t left_end = p->edge0 + p->nleft - 1, right_end = left_end + p->nright;
  a->poly = i;
  a->left = zs_edge_at(edges, p->edge0, left_end, y);
  a->right = zs_edge_at(edges, left_end + 1, right_end, y);
  zs_edge_dda_begin(&a->l, &edges[a->left], y, steps);
  zs_edge_dda_begin(&a->r, &edges[a->right], y, steps);
  a->zrow = zs_plane_row(p, y);
  a->dzdx = p->dzdx;
  a->dzdy = p->dzdy;
  a->id = p->id;
  a->rgb = p->rgb;
  a->row1 = p->row1;
  a->zshift = p->zshift;
  a->inner = p->inner;
}

/* a's span on the row, clamped to the target's width, filled with kernel
 * k; [*x0, *x1) is what was filled (empty when *x0 >= *x1). */
static inline void zs_row_span(const zs_kernel k, const zs_row_ptrs *row, int width,
                               const zs_active *a, const zs_simd simd, const int vector_from,
                               uint64_t *spans, uint64_t *tested, uint64_t *written,
                               int64_t *x0_out, int64_t *x1_out) {
  int64_t x0 = a->l.x, x1 = a->r.x;
  if (!a->inner) {
    if (x0 < 0) x0 = 0;
    if (x1 > width) x1 = width;
  }
  if (x0 < x1) {
    int64_t z = zs_plane_at(a->zrow, a->dzdx, x0);
    zs_fill_span(k, row, (int)x0, (int)x1, z, a, simd, vector_from, written);
    ++*spans;
    *tested += (uint64_t)(x1 - x0);
  }
  *x0_out = x0;
  *x1_out = x1;
}

/* Down one row from y: step both edges, or replace an edge that ran out
 * with the next of its chain; the plane at column 0 moves by dzdy. */
ZS_ALWAYS_INLINE void zs_step_down(zs_active *a, const zs_edge *edges, int32_t y, const int steps) {
  if (y < a->l.last) zs_edge_dda_step(&a->l);
  else zs_edge_dda_begin(&a->l, &edges[++a->left], y + 1, steps);
  if (y < a->r.last) zs_edge_dda_step(&a->r);
  else zs_edge_dda_begin(&a->r, &edges[++a->right], y + 1, steps);
  a->zrow += (uint64_t)a->dzdy;
}

#endif
