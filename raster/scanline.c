/* The scanline z-buffer scan of the lecture, in integers.
 *
 * Sorted polygon table: the batch's polygons bucketed by their first row
 * (clamped to the scan's first row), each bucket in batch order
 * (table.c).
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

#include "util/grow.h"
#include "util/compiler.h"
#include "raster/span.h"

/* The scanline z-buffer of the lecture: row by row, with the active
 * polygon and edge lists, over the sorted table.  Rows in order stream
 * through the buffers, one row in the caches at a time: for a mesh laid
 * out in order the fastest traversal (polyorder.c says when it is not).
 * Returns 0 when out of memory. */
ZS_ALWAYS_INLINE int
scan(const zs_batch *b, const zs_kernel k, const zs_simd simd, const zs_target *t, int row_begin,
     int row_end, const zs_row_hooks *hooks, const zs_trace_observer *obs, const zs_table *table,
     zs_scan_scratch *s, zs_scan_counts *counts) {
  const zs_poly *polys = b->polys;
  const zs_edge *edges = b->edges;
  /* the active list grows as the scan needs it, checked once a row
   * (bucket_start): most polygons of a large batch are never active at
   * once */
  if (s->cap_active == 0 && !zs_grow((void **)&s->active, &s->cap_active, 64, sizeof *s->active))
    return 0;
  zs_active *act = s->active;
  /* the shortest span the vector fill takes (one compare a span) */
  const int vector_from = zs_simd_min_span(simd);
  const int32_t first_bucket = table->first, last_bucket = table->last;
  const int32_t *start = s->bucket_start, *order = s->order;

  if (obs) zs_trace_tables(b, obs);
  int32_t nact = 0;
  uint64_t spans = 0, tested = 0, written = 0;
  int32_t y = hooks ? row_begin : row_begin + first_bucket;
  for (; y < row_end; y++) {
    if (hooks && hooks->begin_row) hooks->begin_row(hooks->user, y);

    /* New polygons join the active lists with their edge pair. */
    const int32_t r = y - row_begin;
    if (r >= first_bucket && r <= last_bucket) {
      const int32_t j0 = start[r], j1 = start[r + 1];
      if (nact + (j1 - j0) > s->cap_active) {
        if (!zs_grow((void **)&s->active, &s->cap_active, nact + (j1 - j0), sizeof *s->active))
          return 0;
        act = s->active;
      }
      for (int32_t j = j0; j < j1; j++) {
        zs_table_prefetch(b, order, j, table->polys);
        zs_activate(&act[nact++], order[j], &polys[order[j]], edges, y, 1);
      }
    }

    if (t->fresh && t->fresh[y]) zs_clear_row(t, y);
    const zs_row_ptrs row = zs_row_of(t, y);
    int32_t kept = 0, ntrace_spans = 0;
    for (int32_t j = 0; j < nact; j++) {
      zs_active *a = &act[j];
      if (obs) zs_trace_pair_of(a, &polys[a->poly], y, &s->trace_pairs[j]);
      int64_t x0, x1;
      zs_row_span(k, &row, t->width, a, simd, vector_from, &spans, &tested, &written, &x0, &x1);
      if (obs && x0 < x1)
        s->trace_spans[ntrace_spans++] = (zs_trace_span){(int32_t)x0, (int32_t)x1 - 1, a->id};
      if (y == a->row1) continue; /* the polygon ends on this row */
      zs_step_down(a, edges, y, 1);
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
      /* Nothing active: jump to the next row that has a bucket, or past
       * the last. */
      int32_t next = r + 1;
      while (next <= last_bucket && start[next] == start[next + 1]) next++;
      if (next > last_bucket) break;
      y = row_begin + next - 1;
    }
  }
  counts->spans += spans;
  counts->tested += tested;
  counts->written += written;
  return 1;
}

/* The copies of the row scan: per kernel and SIMD level, with hooks and
 * observer (zs_scan_batch's) and without (drawing and querying, their
 * tests folded away); only the draw kernel fills spans with SIMD. */
#define ZS_SCAN_COPIES(name, k, simd)                                                             \
  static int name##_rows(const zs_batch *b, const zs_target *t, int row_begin, int row_end,      \
                         const zs_row_hooks *hooks, const zs_trace_observer *obs,                \
                         const zs_table *table, zs_scan_scratch *s, zs_scan_counts *counts) {    \
    return scan(b, k, simd, t, row_begin, row_end, hooks, obs, table, s, counts);                \
  }                                                                                              \
  static int name##_sorted(const zs_batch *b, const zs_target *t, int row_begin, int row_end,    \
                           const zs_table *table, zs_scan_scratch *s, zs_scan_counts *counts) {  \
    return scan(b, k, simd, t, row_begin, row_end, NULL, NULL, table, s, counts);                \
  }
ZS_SCAN_COPIES(draw_scalar, ZS_KERNEL_DRAW, ZS_SIMD_SCALAR)
ZS_SCAN_COPIES(draw_sse2, ZS_KERNEL_DRAW, ZS_SIMD_SSE2)
ZS_SCAN_COPIES(draw_avx2, ZS_KERNEL_DRAW, ZS_SIMD_AVX2)
ZS_SCAN_COPIES(draw_avx512, ZS_KERNEL_DRAW, ZS_SIMD_AVX512)
ZS_SCAN_COPIES(draw_neon, ZS_KERNEL_DRAW, ZS_SIMD_NEON)
ZS_SCAN_COPIES(overdraw, ZS_KERNEL_OVERDRAW, ZS_SIMD_SCALAR)
ZS_SCAN_COPIES(query, ZS_KERNEL_QUERY, ZS_SIMD_SCALAR)
ZS_SCAN_COPIES(fragment, ZS_KERNEL_FRAGMENT, ZS_SIMD_SCALAR)

void zs_scan_choose(zs_kernel k, zs_simd simd, zs_traversal *out) {
  static const zs_scan_rows_fn rows[ZS_KERNELS][ZS_SIMD_LEVELS] = {
      {draw_scalar_rows, draw_sse2_rows, draw_avx2_rows, draw_avx512_rows, draw_neon_rows},
      {overdraw_rows, overdraw_rows, overdraw_rows, overdraw_rows, overdraw_rows},
      {query_rows, query_rows, query_rows, query_rows, query_rows},
      {fragment_rows, fragment_rows, fragment_rows, fragment_rows, fragment_rows}};
  static const zs_scan_sorted_fn sorted[ZS_KERNELS][ZS_SIMD_LEVELS] = {
      {draw_scalar_sorted, draw_sse2_sorted, draw_avx2_sorted, draw_avx512_sorted, draw_neon_sorted},
      {overdraw_sorted, overdraw_sorted, overdraw_sorted, overdraw_sorted, overdraw_sorted},
      {query_sorted, query_sorted, query_sorted, query_sorted, query_sorted},
      {fragment_sorted, fragment_sorted, fragment_sorted, fragment_sorted, fragment_sorted}};
  out->scan_rows = rows[k][simd];
  out->scan_sorted = sorted[k][simd];
}

int zs_scan_batch(const zs_traversal *tr, const zs_batch *b, const zs_target *t, int row_begin,
                  int row_end, const zs_row_hooks *hooks, const zs_trace_observer *obs,
                  zs_scan_scratch *s, zs_scan_counts *counts) {
  if (row_end <= row_begin) return 1;
  zs_table table;
  if (!zs_table_sort(b, row_begin, row_end, s, &table)) return 0;
  if (obs) {
    /* one pair and at most one span per active polygon and row */
    size_t n = (size_t)(b->npolys > 0 ? b->npolys : 1);
    void **const arrays[] = {(void **)&s->trace_pairs, (void **)&s->trace_spans};
    const size_t sizes[] = {sizeof *s->trace_pairs, sizeof *s->trace_spans};
    if (!zs_resize_each(arrays, sizes, 2, n)) return 0;
  }
  if (!hooks && !obs) return tr->scan_sorted(b, t, row_begin, row_end, &table, s, counts);
  return tr->scan_rows(b, t, row_begin, row_end, hooks, obs, &table, s, counts);
}
