/* The polygon-order traversal, the z-buffer mode's: each polygon whole,
 * row by row from its top, in the sorted table's order, with the scanline
 * scan's own pieces (span.h): the same exact edge DDA, the same depth
 * plane, the same span kernels (with AVX-512, a soup's small polygons by
 * their edge functions instead of the DDA: the same spans, proved at
 * paint_small_avx512); or, for a mesh laid out in order over a large part
 * of the frame, the row scan itself.
 *
 * Why the two are equal, to the counter.  On any row the scan's active
 * list holds its polygons in the order they entered it: by first row,
 * then batch order (table.c).  Painting whole polygons in that same
 * order, the fragments of every pixel arrive in the same order as in the
 * scan, so each depth test sees what it saw there: the same image, the
 * same pixels written (overwrites included), spans and pixels tested
 * (tests/test_raster.c, by_polygon_and_scanned_agree_to_the_counter, and
 * every golden image and clock hash).
 *
 * Why paint: a polygon's edge pair and plane stay in registers from its
 * first row to its last, where the scan keeps an active entry per
 * polygon in memory and reads, steps, writes and moves it every row; in a
 * soup of small polygons the scan's list is thousands long.  Why scan a
 * mesh laid out in order over much of the frame: the scan's rows stream
 * through the caches, where painting fetches each polygon's rows apart,
 * a stride of a whole row between them (zscan bench raster measures
 * both: the random triangles and the tilings).
 */
#include "raster/span.h"
#include "util/compiler.h"
#include "raster/tuning.h"

/* Clears the rows [y0, y1] a lazy target holds nothing in yet. */
static void clear_fresh(const zs_target *t, int32_t y0, int32_t y1) {
  if (!t->fresh) return;
  for (int32_t y = y0; y <= y1; y++)
    if (t->fresh[y]) zs_clear_row(t, y);
}

#ifdef ZS_HAVE_AVX512_SPANS

/* A small polygon of a soup painted by its edge functions, sixteen
 * columns a row, where the scan would start and step each edge's DDA.
 *
 * Why the pixels are the DDA's.  On a row whose centres lie at yc, the
 * DDA's span begins at the first column whose centre xc lies at or right
 * of the left edge and ends before the first at or right of the right
 * edge; with
 *   E(xc, yc) = (xc - X0) dy - (yc - Y0) dx,   dy = Y1 - Y0 > 0,
 * the centre is at or right of the edge exactly when E >= 0, in integers.
 * A polygon of the table is convex (setup.c, convex_monotone), so on
 * each of its rows the line of every other edge of its chain lies at or
 * outside the edge in force there: a centre is in the DDA's span
 * exactly when it passes the test of every left edge (E >= 0) and of
 * every right edge (E < 0).  Its columns lie between its edges' lowest
 * and highest X.  Each pixel is
 * then tested and written as zs_fill_span does (the depth clamped to
 * [0, far] before its shift, as zs_depth_of does), and counted the same:
 * the same pixels, depths, ties and counters.
 *
 * Which polygons.  At most 16 columns (one vector) and ZS_SMALL_MAX_ROWS
 * rows, with at most ZS_SMALL_MAX_EDGES edges (tuning.h: past them the
 * DDA's starts cost less than the rows' tests of every edge), and less
 * than 128 pixels tall, so that E and its steps fit 32-bit lanes with no
 * wrap: a centre of the box and a corner both lie in the box, |E| <= 2
 * (xhi - xlo)(yhi - ylo) < 2 * 2^13 * 2^15.  A mesh's polygons stay with
 * the DDA: a masked load of one cannot take its bytes from the masked
 * store of its neighbour (span.h).  Returns 0, having painted nothing,
 * for a polygon it does not take. */


ZS_AVX512_INLINE int paint_small_n(const zs_poly *p, const zs_edge *e, const zs_target *t,
                                   int32_t y0, int32_t y1, const int n, uint64_t *spans,
                                   uint64_t *tested, uint64_t *written) {
  int32_t xlo = e[0].X0, xhi = e[0].X0, ylo = e[0].Y0, yhi = e[0].Y1;
  for (int i = 0; i < n; i++) {
    xlo = e[i].X0 < xlo ? e[i].X0 : xlo;
    xlo = e[i].X1 < xlo ? e[i].X1 : xlo;
    xhi = e[i].X0 > xhi ? e[i].X0 : xhi;
    xhi = e[i].X1 > xhi ? e[i].X1 : xhi;
    ylo = e[i].Y0 < ylo ? e[i].Y0 : ylo;
    yhi = e[i].Y1 > yhi ? e[i].Y1 : yhi;
  }
  /* the columns whose centres lie in [xlo, xhi] */
  const int32_t c0 = zs_floordiv256((int64_t)xlo + 127), c1 = zs_floordiv256((int64_t)xhi - 128);
  if (c1 - c0 >= 16 || (int64_t)yhi - ylo >= ((int64_t)1 << 15)) return 0;
  /* the lanes: columns cs .. cs + 15, from the first inside the window */
  const int32_t cs = c0 < 0 ? 0 : c0, ce = c1 < t->width ? c1 : t->width - 1;
  if (ce < cs) return 1; /* no centre in the window: no span on any row */
  const __mmask16 cols = (__mmask16)((2u << (ce - cs)) - 1u);
  const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  /* Each edge's test as F >= 0, its sign bit clear: F = E on the left,
   * -E - 1 on the right; F on row y0 across the lanes, and its change a
   * row down */
  __m512i f[ZS_SMALL_MAX_EDGES], down[ZS_SMALL_MAX_EDGES];
  for (int i = 0; i < n; i++) {
    const int32_t dy = e[i].Y1 - e[i].Y0, dx = e[i].X1 - e[i].X0;
    const int64_t e0 = ((int64_t)cs * 256 + 128 - e[i].X0) * dy -
                       ((int64_t)y0 * 256 + 128 - e[i].Y0) * dx;
    const int left = i < p->nleft;
    const int32_t across = left ? 256 * dy : -256 * dy; /* a column right */
    f[i] = _mm512_add_epi32(_mm512_set1_epi32((int32_t)(left ? e0 : -e0 - 1)),
                            _mm512_mullo_epi32(lane, _mm512_set1_epi32(across)));
    down[i] = _mm512_set1_epi32(left ? -256 * dx : 256 * dx);
  }
  /* the depth plane at the lanes' columns, in two halves of eight */
  const int64_t dz = p->dzdx;
  const uint64_t zrow = zs_plane_row(p, y0);
  const __m512i dzv = _mm512_set1_epi64(dz);
  __m512i za = _mm512_add_epi64(
      _mm512_set1_epi64((int64_t)(zrow + (uint64_t)dz * (uint64_t)(int64_t)cs)),
      _mm512_mullo_epi64(dzv, _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7)));
  __m512i zb = _mm512_add_epi64(za, _mm512_slli_epi64(dzv, 3));
  const __m512i zdown = _mm512_set1_epi64(p->dzdy), zero = _mm512_setzero_si512();
  const __m512i zfar = _mm512_set1_epi64((int64_t)ZS_DEPTH_FAR << p->zshift);
  const __m128i count = _mm_cvtsi32_si128(p->zshift);
  const __m512i idv = _mm512_set1_epi32((int)p->id), rgbv = _mm512_set1_epi32((int)p->rgb);
  uint64_t sp = 0, te = 0, w = 0;
  for (int32_t y = y0; y <= y1; y++) {
    __m512i any = f[0];
    for (int i = 1; i < n; i++) any = _mm512_or_si512(any, f[i]);
    const __mmask16 m = (__mmask16)(~_mm512_movepi32_mask(any) & cols);
    if (m) {
      const zs_row_ptrs row = zs_row_of(t, y);
      uint32_t *zr = row.depth + cs, *ir = row.id + cs, *cr = row.rgb + cs;
      const __m512i ca = _mm512_min_epi64(_mm512_max_epi64(za, zero), zfar);
      const __m512i cb = _mm512_min_epi64(_mm512_max_epi64(zb, zero), zfar);
      const __m512i d = zs_avx512_depths(ca, cb, count);
      const __mmask16 pass = zs_avx512_test_write(zr, ir, cr, m, d, idv, rgbv);
      sp++;
      te += (uint64_t)__builtin_popcount((unsigned)m);
      w += (uint64_t)__builtin_popcount((unsigned)pass);
    }
    for (int i = 0; i < n; i++) f[i] = _mm512_add_epi32(f[i], down[i]);
    za = _mm512_add_epi64(za, zdown);
    zb = _mm512_add_epi64(zb, zdown);
  }
  *spans += sp;
  *tested += te;
  *written += w;
  return 1;
}

/* n a constant for a triangle's three edges and a quad's four: the
 * edges' lanes then stay in registers, where a loop to a variable n
 * keeps them in memory (zscan bench raster --algo zbuffer --case "random
 * 4x4 back to front") */
ZS_AVX512_TARGET static int paint_small_avx512(const zs_poly *p, const zs_edge *e,
                                               const zs_target *t, int32_t y0, int32_t y1,
                                               uint64_t *spans, uint64_t *tested,
                                               uint64_t *written) {
  const int n = p->nleft + p->nright;
  if (n > ZS_SMALL_MAX_EDGES || y1 - y0 >= ZS_SMALL_MAX_ROWS) return 0;
  if (n == 3) return paint_small_n(p, e, t, y0, y1, 3, spans, tested, written);
  if (n == 4) return paint_small_n(p, e, t, y0, y1, 4, spans, tested, written);
  return paint_small_n(p, e, t, y0, y1, n, spans, tested, written);
}
#endif

/* The table's polygons, each whole, in the table's order; with small
 * (the AVX-512 draw kernel's copy for a soup), the small ones by their
 * edge functions. */
ZS_ALWAYS_INLINE void paint(const zs_batch *b, const zs_kernel k, const zs_simd simd,
                            const int vector_from, const int small, const zs_target *t,
                            int row_begin, int row_end, const zs_table *table,
                            const zs_scan_scratch *s, zs_scan_counts *counts) {
#ifndef ZS_HAVE_AVX512_SPANS
  (void)small; /* no edge-function copy without AVX-512 */
#endif
  const zs_poly *polys = b->polys;
  const zs_edge *edges = b->edges;
  /* The target by value: read through t, its buffers, stride and width
   * would be fetched again on every row, after each call of the span
   * fill, which might have changed them for all the compiler knows */
  const zs_target tl = *t;
  const int32_t *start = s->bucket_start, *order = s->order;
  uint64_t spans = 0, tested = 0, written = 0;
  for (int32_t r = table->first; r <= table->last; r++) {
    const int32_t y0 = row_begin + r;
    for (int32_t j = start[r]; j < start[r + 1]; j++) {
      zs_table_prefetch(b, order, j, table->polys);
      const int32_t i = order[j];
      const zs_poly *p = &polys[i];
      const int32_t y1 = p->row1 < row_end - 1 ? p->row1 : row_end - 1;
#ifdef ZS_HAVE_AVX512_SPANS
      if (small &&
          paint_small_avx512(p, &edges[p->edge0], t, y0, y1, &spans, &tested, &written))
        continue;
#endif
      zs_active a;
      zs_activate(&a, i, p, edges, y0, 0);
      for (int32_t y = y0;; y++) {
        const zs_row_ptrs row = zs_row_of(&tl, y);
        int64_t x0, x1;
        zs_row_span(k, &row, tl.width, &a, simd, vector_from, &spans, &tested, &written, &x0,
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

/* The copies, per kernel and SIMD level (traversal.h); only the draw
 * kernel fills spans with SIMD. */
#define ZS_BY_POLYGON_COPY(name, k, simd, vector_from, small)                                    \
  static void name(const zs_batch *b, const zs_target *t, int row_begin, int row_end,            \
                   const zs_table *table, const zs_scan_scratch *s, zs_scan_counts *counts) {    \
    paint(b, k, simd, vector_from, small, t, row_begin, row_end, table, s, counts);              \
  }
ZS_BY_POLYGON_COPY(draw_scalar, ZS_KERNEL_DRAW, ZS_SIMD_SCALAR, INT_MAX, 0)
ZS_BY_POLYGON_COPY(draw_sse2, ZS_KERNEL_DRAW, ZS_SIMD_SSE2, ZS_SIMD_MIN_SPAN, 0)
ZS_BY_POLYGON_COPY(draw_avx2, ZS_KERNEL_DRAW, ZS_SIMD_AVX2, ZS_SIMD_MIN_SPAN, 0)
ZS_BY_POLYGON_COPY(draw_avx512, ZS_KERNEL_DRAW, ZS_SIMD_AVX512, ZS_AVX512_MIN_SPAN, 0)
ZS_BY_POLYGON_COPY(draw_neon, ZS_KERNEL_DRAW, ZS_SIMD_NEON, ZS_SIMD_MIN_SPAN, 0)
ZS_BY_POLYGON_COPY(overdraw, ZS_KERNEL_OVERDRAW, ZS_SIMD_SCALAR, INT_MAX, 0)
ZS_BY_POLYGON_COPY(query, ZS_KERNEL_QUERY, ZS_SIMD_SCALAR, INT_MAX, 0)
ZS_BY_POLYGON_COPY(fragment, ZS_KERNEL_FRAGMENT, ZS_SIMD_SCALAR, INT_MAX, 0)

#ifdef ZS_HAVE_AVX512_SPANS
/* The draw kernel's copy for a soup on a device with AVX-512, built for
 * AVX-512 throughout, its span fill the AVX-512 kernel itself
 * (span_avx512.h): the small polygons by their edge functions, the others'
 * spans of any length in masked steps of sixteen, with no branch on
 * their pixels (a mesh's take the fill from ZS_AVX512_MIN_SPAN pixels, as
 * in the row scan: span.h).  zscan bench raster --case "random 10x10 back
 * to front" and --case builtin:teapots measure both. */
ZS_AVX512_TARGET static void draw_avx512_soup(const zs_batch *b, const zs_target *t,
                                              int row_begin, int row_end, const zs_table *table,
                                              const zs_scan_scratch *s, zs_scan_counts *counts) {
  paint(b, ZS_KERNEL_DRAW, ZS_SIMD_AVX512, 1, 1, t, row_begin, row_end, table, s, counts);
}
#else
#define draw_avx512_soup draw_avx512
#endif

void zs_polyorder_choose(zs_kernel k, zs_simd simd, zs_traversal *out) {
  static const zs_by_polygon_fn mesh[ZS_KERNELS][ZS_SIMD_LEVELS] = {
      {draw_scalar, draw_sse2, draw_avx2, draw_avx512, draw_neon},
      {overdraw, overdraw, overdraw, overdraw, overdraw},
      {query, query, query, query, query},
      {fragment, fragment, fragment, fragment, fragment}};
  static const zs_by_polygon_fn soup[ZS_KERNELS][ZS_SIMD_LEVELS] = {
      {draw_scalar, draw_sse2, draw_avx2, draw_avx512_soup, draw_neon},
      {overdraw, overdraw, overdraw, overdraw, overdraw},
      {query, query, query, query, query},
      {fragment, fragment, fragment, fragment, fragment}};
  out->by_polygon_mesh = mesh[k][simd];
  out->by_polygon_soup = soup[k][simd];
}

int zs_polyorder_batch(const zs_traversal *tr, const zs_batch *b, const zs_target *t,
                       int row_begin, int row_end, zs_scan_scratch *s, zs_scan_counts *counts) {
  if (row_end <= row_begin) return 1;
  zs_table table;
  if (!zs_table_sort(b, row_begin, row_end, s, &table)) return 0;
  /* A mesh laid out in order over a quarter of the frame or more is
   * scanned by rows: its rows stream through the caches, where a polygon
   * at a time would fetch each of its rows apart.  A soup, most of whose
   * polygons begin far from the one before, and a draw over a smaller
   * part of the frame go a polygon at a time (tuning.h). */
  const int64_t rows = (int64_t)table.last_row - (row_begin + table.first) + 1;
  const int64_t cols = (int64_t)(table.x1 < t->width ? table.x1 : t->width - 1) -
                       (table.x0 > 0 ? table.x0 : 0) + 1;
  const int soup = 2 * (int64_t)table.jumps > table.polys;
  if (!soup &&
      ZS_SCAN_FRAME_SHARE * rows * cols >= (int64_t)(row_end - row_begin) * t->width)
    return tr->scan_sorted(b, t, row_begin, row_end, &table, s, counts);
  clear_fresh(t, row_begin + table.first, table.last_row);
  (soup ? tr->by_polygon_soup : tr->by_polygon_mesh)(b, t, row_begin, row_end, &table, s, counts);
  return 1;
}
