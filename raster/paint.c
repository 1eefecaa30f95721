/* The z-buffer mode's traversal of a batch: each polygon painted whole,
 * row by row from its top, in the sorted table's order, with the scanline
 * walk's own pieces (span.h): the same exact edge DDA, the same depth
 * plane, the same span kernels; or, for a mesh laid out in order over a
 * large part of the frame, the scanline walk itself.
 *
 * Why the two are equal, to the counter.  On any row the walk's active
 * list holds its polygons in the order they entered it: by first row,
 * then batch order (table.c).  Painting whole polygons in that same
 * order, the fragments of every pixel arrive in the same order as in the
 * walk, so each depth test sees what it saw there: the same image, the
 * same pixels written (overwrites included), spans and pixels tested
 * (tests/test_raster.c, painted_and_walked_agree_to_the_counter, and
 * every golden image and clock hash).
 *
 * Why paint: a polygon's edge pair and plane stay in registers from its
 * first row to its last, where the walk keeps an active entry per
 * polygon in memory and reads, steps, writes and moves it every row; in a
 * soup of small polygons the walk's list is thousands long.  Why walk a
 * mesh laid out in order over much of the frame: the walk's rows stream
 * through the caches, where painting fetches each polygon's rows apart,
 * a stride of a whole row between them (zscan bench raster measures
 * both: the random triangles and the tilings).
 */
#include "raster/span.h"

/* Clears the rows [y0, y1] a lazy target holds nothing in yet. */
static void clear_fresh(const zs_target *t, int32_t y0, int32_t y1) {
  if (!t->fresh) return;
  for (int32_t y = y0; y <= y1; y++)
    if (t->fresh[y]) zs_clear_row(t, y);
}

/* The table's polygons, each whole, in the table's order. */
__attribute__((always_inline)) static inline void paint(const zs_batch *b, const zs_kernel k,
                                                        const zs_simd simd, const int vector_from,
                                                        const zs_target *t, int row_begin,
                                                        int row_end, const zs_table *table,
                                                        const zs_walk_scratch *s,
                                                        zs_walk_counts *counts) {
  const zs_poly *polys = b->polys;
  const zs_edge *edges = b->edges;
  const int32_t *start = s->bucket_start, *order = s->order;
  uint64_t spans = 0, tested = 0, written = 0;
  for (int32_t r = table->first; r <= table->last; r++) {
    const int32_t y0 = row_begin + r;
    for (int32_t j = start[r]; j < start[r + 1]; j++) {
      zs_table_prefetch(b, order, j, table->polys);
      const int32_t i = order[j];
      const zs_poly *p = &polys[i];
      zs_active a;
      zs_activate(&a, i, p, edges, y0, 0);
      const int32_t y1 = p->row1 < row_end - 1 ? p->row1 : row_end - 1;
      for (int32_t y = y0;; y++) {
        const zs_row_ptrs row = zs_row_of(t, y);
        int64_t x0, x1;
        zs_row_span(k, &row, t->width, &a, simd, vector_from, &spans, &tested, &written, &x0,
                    &x1);
        if (y == y1) break;
        zs_step_down(&a, edges, y, 0);
      }
    }
  }
  counts->spans += spans;
  counts->tested += tested;
  counts->written += written;
}

#ifdef ZS_HAVE_AVX512_SPANS
/* The draw kernel's copy for a device with AVX-512, its span fill
 * inlined: a soup's spans of any length in masked steps of sixteen, with
 * no branch on their pixels; a mesh's from 10 pixels, as in the walk
 * (span.h: the masked load of a span cannot take its bytes from the
 * masked store of its neighbour on the row, which a mesh's faces have and
 * a soup's mostly not).  zscan bench raster --case "random 10x10 back to
 * front" and --case builtin:teapots measure both. */
__attribute__((target("avx512f,avx512vl,avx512bw,avx512dq"))) static void
paint_avx512(const zs_batch *b, const zs_target *t, int row_begin, int row_end,
             const zs_table *table, const zs_walk_scratch *s, zs_walk_counts *counts) {
  paint(b, ZS_KERNEL_DRAW, ZS_SIMD_AVX512, 1, t, row_begin, row_end, table, s, counts);
}
#endif

int zs_paint_batch(const zs_batch *b, zs_kernel k, const zs_target *t, int row_begin,
                   int row_end, zs_walk_scratch *s, zs_walk_counts *counts) {
  if (row_end <= row_begin) return 1;
  zs_table table;
  if (!zs_table_sort(b, row_begin, row_end, s, &table)) return 0;
  /* A mesh laid out in order over a quarter of the frame or more is
   * walked: its rows stream through the caches, where a polygon at a time
   * would fetch each of its rows apart.  A soup, most of whose polygons
   * begin far from the one before, and a draw over a smaller part of the
   * frame are painted (zscan bench raster measures all three: the
   * tilings, the random triangles, the scenes and small models). */
  const int64_t rows = (int64_t)table.last_row - (row_begin + table.first) + 1;
  const int64_t cols = (int64_t)(table.x1 < t->width ? table.x1 : t->width - 1) -
                       (table.x0 > 0 ? table.x0 : 0) + 1;
  if (2 * (int64_t)table.jumps <= table.polys &&
      4 * rows * cols >= (int64_t)(row_end - row_begin) * t->width)
    return zs_walk_sorted(b, k, t, row_begin, row_end, &table, s, counts);
  clear_fresh(t, row_begin + table.first, table.last_row);
  /* a copy of the loop per kernel, k a constant in each */
  switch (k) {
    case ZS_KERNEL_DRAW:
#ifdef ZS_HAVE_AVX512_SPANS
      if (t->simd == ZS_SIMD_AVX512 && 2 * (int64_t)table.jumps > table.polys) {
        paint_avx512(b, t, row_begin, row_end, &table, s, counts);
        break;
      }
#endif
      paint(b, ZS_KERNEL_DRAW, t->simd, zs_simd_min_span(t->simd), t, row_begin, row_end, &table,
            s, counts);
      break;
    case ZS_KERNEL_OVERDRAW:
      paint(b, ZS_KERNEL_OVERDRAW, ZS_SIMD_SCALAR, INT_MAX, t, row_begin, row_end, &table, s,
            counts);
      break;
    case ZS_KERNEL_QUERY:
      paint(b, ZS_KERNEL_QUERY, ZS_SIMD_SCALAR, INT_MAX, t, row_begin, row_end, &table, s, counts);
      break;
  }
  return 1;
}
