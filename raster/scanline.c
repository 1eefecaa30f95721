/* The scanline z-buffer walk of the lecture, in integers.
 *
 * Sorted polygon table: the batch's polygons bucketed by their first row
 * (clamped to the walk's first row), a linked list per row.
 * Sorted edge table: each polygon's edges, in two chains (left and right)
 * ordered by their top row; when an edge of a pair runs out, the next edge
 * of its chain replaces it, as the lecture's "find the new edge in the
 * sorted edge table".
 * Active polygon list / active edge list: one zs_active per polygon that
 * meets the current row, holding, as the lecture's active edge table
 * does, its edge pair (xl, dxl, dyl, xr, dxr, dyr), the depth on the row
 * (kept at column 0, zrow, where the lecture keeps zl at xl: a span's
 * first depth is one multiply from it and a row one add), dzx = dzdx,
 * dzy = dzdy and the id: a row reads the entry alone.
 *
 * Edges are stepped with an exact integer DDA.  For an edge from (X0, Y0)
 * to (X1, Y1) (subpixels, Y0 < Y1, D = 256 (Y1 - Y0)), the first column
 * whose centre lies at or right of the edge on row r is
 *   x(r) = ceil(num(r) / D),
 *   num(r) = (X0 - 128)(Y1 - Y0) + (256 r + 128 - Y0)(X1 - X0),
 * kept as x and a remainder rem = x D - num in [0, D).  Going down a row
 * adds 256 (X1 - X0) to num: a whole part q and a remainder part rs, and a
 * carry when rem would go negative.  No division per row, no error that
 * accumulates: x(r) is exact on every row.  The span of a row is
 * [x_left, x_right): a centre on the left edge is in, on the right edge
 * out (raster.h, COVERAGE).
 */
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "raster/edge_dda.h"
#include "raster/grow.h"
#include "raster/internal.h"

/* Index of the edge of chain [first, last] that covers row. */
static int32_t edge_at(const zs_edge *edges, int32_t first, int32_t last,
                       int32_t row) {
  int32_t i = first;
  while (i < last && zs_last_row(edges[i].Y1) < row) i++;
  return i;
}

static inline uint32_t depth_of(int64_t z, int shift, int64_t zfar) {
  if (z <= 0) return 0;
  if (z >= zfar) return ZS_DEPTH_FAR;
  return (uint32_t)(z >> shift);
}

/* Spans shorter than this stay with the scalar loop (raster.h, the span
 * fill): below 16 pixels AVX2 needs masked stores for the last pixels,
 * slow on AMD CPUs, or full-width stores that write back what lies past
 * the span, no faster than the loop; and SSE2 from 8 costs more
 * instructions a triangle than from 16 (zscan bench raster --case
 * "triangles 25x25" --callgrind measures both). */
enum { ZS_SIMD_MIN_SPAN = 16 };

/* One row of the target: where a row's spans land. */
typedef struct row_ptrs {
  uint32_t *depth, *id, *rgb, *count;
} row_ptrs;

static inline row_ptrs row_of(const zs_target *t, int32_t y) {
  const int64_t off = t->row_stride * (y - t->row0);
  row_ptrs r = {t->depth ? t->depth + off : NULL, t->id ? t->id + off : NULL,
                t->rgb ? t->rgb + off : NULL, t->count ? t->count + off : NULL};
  return r;
}

/* Room for n active polygons (0: out of memory). */
static int grow_active(zs_walk_scratch *s, int32_t n) {
  return zs_grow((void **)&s->active, &s->cap_active, n, sizeof *s->active);
}

/* Clears row y of a lazily cleared target, the first time a walk reaches
 * it (zs_target.fresh). */
static void clear_row(const zs_target *t, int32_t y) {
  const row_ptrs r = row_of(t, y);
  const size_t w = (size_t)t->width;
  zs_fill_u32(r.depth, w, ZS_DEPTH_FAR);
  zs_fill_u32(r.id, w, ZS_ID_NONE);
  zs_fill_u32(r.rgb, w, t->background);
  if (r.count) memset(r.count, 0, w * sizeof *r.count);
  t->fresh[y] = 0;
}

/* The span kernels, one loop per kernel, chosen once per batch: the walk
 * below is inlined into a copy per kernel with k a constant.  The span
 * [x0, x1) of a's polygon, z its depth plane at x0. */
static inline void fill_span(zs_kernel k, const row_ptrs *row, int x0, int x1, int64_t z,
                             const zs_active *a, zs_simd simd, int vector_from,
                             uint64_t *written) {
  if (k == ZS_KERNEL_OVERDRAW) {
    uint32_t *cnt = row->count;
    for (int x = x0; x < x1; x++) cnt[x]++;
    *written += (uint64_t)(x1 - x0);
    return;
  }
  const int64_t dz = a->dzdx, zfar = a->zfar;
  const int shift = a->zshift;
  uint64_t w = 0;
  if (k == ZS_KERNEL_QUERY) {
    const uint32_t *zr = row->depth;
    if (a->inner)
      for (int x = x0; x < x1; x++, z += dz) w += (uint32_t)(z >> shift) <= zr[x];
    else
      for (int x = x0; x < x1; x++, z += dz) w += depth_of(z, shift, zfar) <= zr[x];
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
      int xs = zs_fill_span_simd(simd, zr, ir, cr, x0, x1, z, dz, shift, id, rgb, written);
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
    uint32_t d = depth_of(z, shift, zfar);
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

static int cmp_int64(const void *a, const void *b) {
  int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
  return (x > y) - (x < y);
}

static int reserve_scratch(zs_walk_scratch *s, int32_t rows, int32_t polys) {
  if (rows > s->cap_rows) {
    void **const arrays[] = {(void **)&s->bucket_head, (void **)&s->bucket_count};
    const size_t sizes[] = {sizeof *s->bucket_head, sizeof *s->bucket_count};
    if (!zs_resize_each(arrays, sizes, 2, (size_t)rows)) return 0;
    s->cap_rows = rows;
  }
  if (polys > s->cap_polys) {
    void **const arrays[] = {(void **)&s->next, (void **)&s->cross};
    const size_t sizes[] = {sizeof *s->next, sizeof *s->cross};
    if (!zs_resize_each(arrays, sizes, 2, (size_t)polys)) return 0;
    s->cap_polys = polys;
  }
  /* the active list grows as the walk needs it, checked once a row
   * (bucket_count): most polygons of a large batch are never active at
   * once */
  if (s->cap_active == 0 && !zs_grow((void **)&s->active, &s->cap_active, 64, sizeof *s->active))
    return 0;
  return 1;
}

void zs_walk_scratch_free(zs_walk_scratch *s) {
  free(s->bucket_head);
  free(s->bucket_count);
  free(s->next);
  free(s->active);
  free(s->trace_pairs);
  free(s->trace_spans);
  free(s->cross);
  memset(s, 0, sizeof *s);
}

/* The sorted polygon table: each polygon of rows [row_begin, row_end)
 * bucketed under its first row, a linked list per row in batch order.
 * Polygons begun above the first row go to its bucket, ordered as a walk
 * from the top would hold them: by first row, then batch order.  Returns
 * the first bucket in use (nrows when none). */
static int32_t bucket_polys(const zs_batch *b, int row_begin, int row_end, zs_walk_scratch *s) {
  int32_t *head = s->bucket_head, *next = s->next, *count = s->bucket_count;
  int32_t nrows = row_end - row_begin;
  for (int32_t i = 0; i < nrows; i++) head[i] = -1, count[i] = 0;
  int32_t first_bucket = nrows, ncross = 0;
  /* backwards, so that each list comes out in batch order */
  for (int32_t i = b->npolys - 1; i >= 0; i--) {
    const zs_poly *p = &b->polys[i];
    if (p->row1 < row_begin || p->row0 >= row_end) continue;
    if (p->row0 < row_begin) { /* begun above the walk: ordered below */
      s->cross[ncross++] = (int64_t)p->row0 * ((int64_t)1 << 32) + i;
      continue;
    }
    int32_t r = p->row0 - row_begin;
    next[i] = head[r];
    head[r] = i;
    count[r]++;
    if (r < first_bucket) first_bucket = r;
  }
  if (ncross > 0) {
    /* A walk that starts mid-frame (a band of rows) takes first the
     * polygons begun above it, in the order a walk from the top would hold
     * them.  The spans of a row are then filled in the same order in every
     * band layout, and so are counters that depend on it (pixels written,
     * overwrites included). */
    qsort(s->cross, (size_t)ncross, sizeof *s->cross, cmp_int64);
    for (int32_t k = ncross - 1; k >= 0; k--) {
      int32_t i = (int32_t)(s->cross[k] & 0xFFFFFFFF);
      next[i] = head[0];
      head[0] = i;
    }
    count[0] += ncross;
    first_bucket = 0;
  }
  return first_bucket;
}

/* Polygon i enters at row y: its edge pair on that row and zl. */
static inline void activate(zs_active *a, int32_t i, const zs_poly *p, const zs_edge *edges,
                            int32_t y) {
  a->poly = i;
  a->left_end = p->edge0 + p->nleft - 1;
  a->right_end = a->left_end + p->nright;
  a->left = edge_at(edges, p->edge0, a->left_end, y);
  a->right = edge_at(edges, a->left_end + 1, a->right_end, y);
  zs_edge_dda_start(&a->l, &edges[a->left], y);
  zs_edge_dda_start(&a->r, &edges[a->right], y);
  a->zrow = (uint64_t)p->zc - (uint64_t)p->dzdx * (uint64_t)(int64_t)p->ox +
            (uint64_t)p->dzdy * (uint64_t)((int64_t)y - p->oy);
  a->dzdx = p->dzdx;
  a->dzdy = p->dzdy;
  a->id = p->id;
  a->rgb = p->rgb;
  a->row1 = p->row1;
  a->zshift = p->zshift;
  a->zfar = (int64_t)ZS_DEPTH_FAR << p->zshift;
  a->inner = p->inner;
}

/* a's span on the row, clamped to the target's width, filled with kernel
 * k; [*x0, *x1) is what was filled (empty when *x0 >= *x1). */
static inline void row_span(zs_kernel k, const row_ptrs *row, int width, const zs_active *a,
                            zs_simd simd, int vector_from, uint64_t *spans, uint64_t *tested,
                            uint64_t *written, int64_t *x0_out, int64_t *x1_out) {
  int64_t x0 = a->l.x, x1 = a->r.x;
  if (!a->inner) {
    if (x0 < 0) x0 = 0;
    if (x1 > width) x1 = width;
  }
  if (x0 < x1) {
    int64_t z = zs_plane_at(a->zrow, a->dzdx, x0);
    fill_span(k, row, (int)x0, (int)x1, z, a, simd, vector_from, written);
    ++*spans;
    *tested += (uint64_t)(x1 - x0);
  }
  *x0_out = x0;
  *x1_out = x1;
}

/* Down one row from y: step both edges, or replace an edge that ran out
 * with the next of its chain; the plane at column 0 moves by dzdy. */
__attribute__((always_inline)) static inline void step_down(zs_active *a, const zs_edge *edges, int32_t y) {
  if (y < a->l.last) zs_edge_dda_step(&a->l);
  else zs_edge_dda_start(&a->l, &edges[++a->left], y + 1);
  if (y < a->r.last) zs_edge_dda_step(&a->r);
  else zs_edge_dda_start(&a->r, &edges[++a->right], y + 1);
  a->zrow += (uint64_t)a->dzdy;
}

/* The scanline z-buffer of the lecture: row by row, with the active
 * polygon and edge lists.  A full-frame target (zbuffer mode) could take a
 * polygon at a time in the same order and get the same counters, but that
 * is slower: rows in order stream through the buffers, a polygon's rows
 * stride across pages (zscan bench raster --case "triangles 25x25"
 * measures it). */
__attribute__((always_inline)) static inline int walk(const zs_batch *b, const zs_kernel k,
                        const zs_target *t, int row_begin, int row_end,
                        const zs_row_hooks *hooks, const zs_trace_observer *obs,
                        zs_walk_scratch *s, zs_walk_counts *counts) {
  const zs_poly *polys = b->polys;
  const zs_edge *edges = b->edges;
  const int32_t *head = s->bucket_head, *next = s->next;
  zs_active *act = s->active;
  const zs_simd simd = k == ZS_KERNEL_DRAW ? t->simd : ZS_SIMD_SCALAR;
  /* the shortest span the vector fill takes (one compare a span) */
  const int vector_from = simd != ZS_SIMD_SCALAR ? ZS_SIMD_MIN_SPAN : INT_MAX;
  const int32_t nrows = row_end - row_begin;
  const int32_t first_bucket = bucket_polys(b, row_begin, row_end, s);

  if (obs) zs_trace_tables(b, obs);
  int32_t nact = 0;
  uint64_t spans = 0, tested = 0, written = 0;
  int32_t y = hooks ? row_begin : row_begin + first_bucket;
  for (; y < row_end; y++) {
    if (hooks && hooks->begin_row) hooks->begin_row(hooks->user, y);

    /* New polygons join the active lists with their edge pair. */
    if (nact + s->bucket_count[y - row_begin] > s->cap_active) {
      if (!grow_active(s, nact + s->bucket_count[y - row_begin])) return 0;
      act = s->active;
    }
    for (int32_t i = head[y - row_begin]; i >= 0; i = next[i])
      activate(&act[nact++], i, &polys[i], edges, y);

    if (t->fresh && t->fresh[y]) clear_row(t, y);
    const row_ptrs row = row_of(t, y);
    int32_t kept = 0, ntrace_spans = 0;
    for (int32_t j = 0; j < nact; j++) {
      zs_active *a = &act[j];
      if (obs) zs_trace_pair_of(a, &polys[a->poly], y, &s->trace_pairs[j]);
      int64_t x0, x1;
      row_span(k, &row, t->width, a, simd, vector_from, &spans, &tested, &written, &x0, &x1);
      if (obs && x0 < x1)
        s->trace_spans[ntrace_spans++] = (zs_trace_span){(int32_t)x0, (int32_t)x1 - 1, a->id};
      if (y == a->row1) continue; /* the polygon ends on this row */
      step_down(a, edges, y);
      if (kept != j) act[kept] = *a;
      kept++;
    }
    if (obs && obs->row) {
      zs_trace_row tr = {y, s->trace_pairs, nact, s->trace_spans, ntrace_spans};
      obs->row(obs->user, &tr);
    }
    nact = kept;

    if (hooks && hooks->end_row) hooks->end_row(hooks->user, y);
    if (!hooks && nact == 0) {
      /* Nothing active: jump to the next row that has a bucket. */
      int32_t r = y + 1 - row_begin;
      while (r < nrows && head[r] < 0) r++;
      y = row_begin + r - 1;
    }
  }
  counts->spans += spans;
  counts->tested += tested;
  counts->written += written;
  return 1;
}

int zs_scan_batch(const zs_batch *b, zs_kernel k, const zs_target *t,
                  int row_begin, int row_end, const zs_row_hooks *hooks,
                  const zs_trace_observer *obs, zs_walk_scratch *s,
                  zs_walk_counts *counts) {
  if (row_end <= row_begin) return 1;
  if (!reserve_scratch(s, row_end - row_begin, b->npolys > 0 ? b->npolys : 1))
    return 0;
  if (obs) {
    /* one pair and at most one span per active polygon and row */
    size_t n = (size_t)(b->npolys > 0 ? b->npolys : 1);
    void **const arrays[] = {(void **)&s->trace_pairs, (void **)&s->trace_spans};
    const size_t sizes[] = {sizeof *s->trace_pairs, sizeof *s->trace_spans};
    if (!zs_resize_each(arrays, sizes, 2, n)) return 0;
  }
  /* a copy of the walk per kernel, and per kernel a copy without hooks
   * and observer (drawing and querying): their tests fold away there */
#define ZS_WALK(K)                                                            \
  do {                                                                        \
    if (!hooks && !obs)                                                       \
      ok = walk(b, K, t, row_begin, row_end, NULL, NULL, s, counts);          \
    else                                                                      \
      ok = walk(b, K, t, row_begin, row_end, hooks, obs, s, counts);          \
  } while (0)
  int ok = 1;
  switch (k) {
    case ZS_KERNEL_DRAW: ZS_WALK(ZS_KERNEL_DRAW); break;
    case ZS_KERNEL_OVERDRAW: ZS_WALK(ZS_KERNEL_OVERDRAW); break;
    case ZS_KERNEL_QUERY: ZS_WALK(ZS_KERNEL_QUERY); break;
  }
#undef ZS_WALK
  return ok;
}
