/* zscan raster — lines' and points' fragments kept for the rows of
 * scanline mode (prim_rows.c).
 *
 * In zbuffer mode a line or a point writes its pixels into the full frame
 * as it is drawn (prims.c).  Scanline mode has no full frame: its rows
 * are scanned at finish.  So there each fragment is kept, in the order
 * drawn, and at finish each row gets its own after the row's faces are
 * scanned and before it is shaded, by the same depth test.  The test is a
 * total order (raster.h, DEPTH), so the pixels are those of zbuffer
 * mode; and each pixel meets its fragments in the order drawn, after the
 * faces, so where the faces are drawn first (as every frame of lib/ draws
 * them) the count of pixels written is zbuffer mode's too. */
#ifndef ZS_RASTER_PRIM_ROWS_H
#define ZS_RASTER_PRIM_ROWS_H

#include <stddef.h>
#include <stdint.h>

typedef struct zs_prim_rows {
  uint32_t *x, *y, *z, *id, *rgb; /* a fragment: its pixel, depth word, id, colour */
  int32_t n, cap;
  int nomem;                       /* a fragment could not be kept */
  int32_t *row_first;              /* by row (zs_prim_rows_sort): row y's fragments */
  int32_t *order;                  /*   are order[row_first[y] .. row_first[y + 1]) */
  int32_t rows, cap_order;
} zs_prim_rows;

/* Keeps the fragment (x, y, z, id, rgb); on failing memory sets nomem. */
void zs_prim_rows_keep(zs_prim_rows *p, uint32_t x, uint32_t y, uint32_t z, uint32_t id,
                       uint32_t rgb);

/* Groups the fragments kept by row, each row's in the order drawn, for
 * rows 0 .. height - 1; 0 when out of memory. */
int zs_prim_rows_sort(zs_prim_rows *p, int height);

/* Row y's fragments (after zs_prim_rows_sort) tested against and written
 * into the row's buffers, count (NULL: not counted) taking one for each;
 * returns the pixels written. */
uint64_t zs_prim_rows_apply(const zs_prim_rows *p, int y, uint32_t *depth, uint32_t *id,
                            uint32_t *rgb, uint32_t *count);

/* Forgets the fragments (a new frame); frees them; their bytes. */
void zs_prim_rows_clear(zs_prim_rows *p);
void zs_prim_rows_free(zs_prim_rows *p);
size_t zs_prim_rows_bytes(const zs_prim_rows *p);

#endif
