/* zscan raster — the batch: the polygons and edges that set-up writes and
 * the traversals read (the lecture's sorted polygon and edge tables before
 * sorting), with the fixed-point row conventions they share.  One draw in
 * zbuffer mode, the whole frame in scanline and depthsort modes. */
#ifndef ZS_RASTER_BATCH_H
#define ZS_RASTER_BATCH_H

#include <stdint.h>

/* floor(v / 256): an arithmetic shift, which gcc and clang give signed
 * values (C leaves it to the implementation; tests/test_raster.c checks
 * it on negative coordinates). */
static inline int32_t zs_floordiv256(int64_t v) { return (int32_t)(v >> 8); }

/* First and last pixel row whose centre yc satisfies ytop < yc <= ybot. */
static inline int32_t zs_first_row(int32_t ytop) { return zs_floordiv256((int64_t)ytop - 128) + 1; }
static inline int32_t zs_last_row(int32_t ybot) { return zs_floordiv256((int64_t)ybot - 128); }

/* One edge of a polygon's left or right chain: snapped end points in
 * subpixels, image coordinates (y down), Y0 < Y1.  It covers the pixel rows
 * whose centre yc has Y0 < yc <= Y1: rows zs_first_row(Y0) ..
 * zs_last_row(Y1), taken from the end points when needed (16 bytes an
 * edge: a frame's tables are written and read back through the caches). */
typedef struct zs_edge {
  int32_t X0, Y0, X1, Y1;
} zs_edge;

/* One polygon of the sorted polygon table, ready for the row scan.
 * The lecture's (a, b, c, d) plane is held as the fixed-point depth plane
 *   Z(px, py) = zc + dzdx (px - ox) + dzdy (py - oy)
 * in units of 2^-(32 + zshift) of the window depth, evaluated at pixel
 * centres.  Its edges are edges[edge0 .. edge0 + nleft - 1] (the left chain,
 * top to bottom) followed by nright edges of the right chain. */
typedef struct zs_poly {
  uint32_t id;
  uint32_t rgb;         /* shaded colour */
  int32_t row0, row1;   /* rows covered, inclusive, before the viewport */
  int32_t ox, oy;       /* the plane's origin pixel */
  int64_t zc, dzdx, dzdy;
  int32_t edge0;
  uint8_t nleft, nright;
  uint8_t zshift;
  /* Every span in columns [0, width) and every depth strictly between the
   * planes: the scan neither clamps its spans nor tests their depths
   * (setup.c, spans_inner; width is the device's, every target's). */
  uint8_t inner;
} zs_poly;

/* The polygons and edges of a batch: one draw in zbuffer mode, the whole
 * frame in scanline mode. */
typedef struct zs_batch {
  zs_poly *polys;
  int32_t npolys, cap_polys;
  zs_edge *edges;
  int32_t nedges, cap_edges;
} zs_batch;


void zs_batch_reset(zs_batch *b);
/* The rows polygons first .. first + count - 1 of b cover, within rows
 * 0 .. height - 1 (*lo > *hi when none). */
void zs_batch_rows(const zs_batch *b, int32_t first, int32_t count, int height, int32_t *lo,
                   int32_t *hi);
/* Appends src's polygons and edges to dst, in order (0: out of memory);
 * or its polygons first .. first + count - 1 with their edges. */
int zs_batch_append(zs_batch *dst, const zs_batch *src);
int zs_batch_append_range(zs_batch *dst, const zs_batch *src, int32_t first, int32_t count);
/* The same in parts, for copies made at once over threads: the edges of
 * polygons first .. first + count - 1 of b; room for polys and edges
 * more (0: out of memory); those polygons and their edges written at
 * dst's polygon at_poly and edge at_edge, its counts left as they are. */
int32_t zs_batch_edges_of(const zs_batch *b, int32_t first, int32_t count);
int zs_batch_reserve(zs_batch *b, int32_t polys, int32_t edges);
void zs_batch_place(zs_batch *dst, int32_t at_poly, int32_t at_edge, const zs_batch *src,
                    int32_t first, int32_t count);
void zs_batch_free(zs_batch *b);

#endif
