/* zscan raster — the row scan's own pieces: an edge stepped by the exact
 * integer DDA (edge_dda.h) and an entry of the active polygon and edge
 * lists; shared by the row scan (scanline.c), the polygon-order traversal
 * (polyorder.c), the spans (span.h) and the trace (trace.c). */
#ifndef ZS_RASTER_SCAN_H
#define ZS_RASTER_SCAN_H

#include "raster/table.h"

/* An edge being scanned: the exact integer DDA (edge_dda.h), 24 bytes. */
typedef struct zs_edge_dda {
  int32_t x, q;
  uint32_t rem, rs, d;
  int32_t last;  /* the last row it covers (the lecture's dy: last - y) */
} zs_edge_dda;

/* An entry of the active lists: a polygon and its current edge pair, with
 * the polygon's fields the rows read copied in (one place to read per row,
 * not two).  Small: the scan streams the whole list every row and moves
 * each entry after the first polygon that ends on it. */
typedef struct zs_active {
  zs_edge_dda l, r;
  uint64_t zrow; /* depth plane at (0, y), modulo 2^64 (zs_plane_at) */
  int64_t dzdx, dzdy;
  uint32_t id, rgb;
  int32_t row1;
  int32_t poly;
  int32_t left, right;  /* the current edges */
  uint8_t zshift, inner; /* the polygon's */
} zs_active;

/* The depth plane at column x of a row whose plane at column 0 is zrow.
 * The sum is taken modulo 2^64: column 0 may lie far outside the polygon,
 * where the plane does not fit 64 bits, but at a column of the polygon's
 * box it does (setup.c, make_plane), and there the wrapped sum is exact.
 * One multiply a span; going down a row adds dzdy to zrow. */
static inline int64_t zs_plane_at(uint64_t zrow, int64_t dzdx, int64_t x) {
  return (int64_t)(zrow + (uint64_t)dzdx * (uint64_t)x);
}

/* trace.c: the sorted tables handed to obs; one active entry as a pair. */
void zs_trace_tables(const zs_batch *b, const zs_trace_observer *obs);
void zs_trace_pair_of(const zs_active *a, const zs_poly *p, int32_t y, zs_trace_pair *out);

#endif
