/* The sorted polygon table of the scanline z-buffer: a batch's polygons
 * bucketed by their first row, each bucket in batch order, which every
 * traversal of a batch takes in order (scanline.c row by row,
 * polyorder.c polygon by polygon); and the traversals' scratch that holds
 * it. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "util/grow.h"
#include "raster/scan.h"
#include "raster/tuning.h"

static int cmp_int64(const void *a, const void *b) {
  int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
  return (x > y) - (x < y);
}

static int reserve(zs_scan_scratch *s, int32_t rows, int32_t polys) {
  return zs_grow((void **)&s->bucket_start, &s->cap_rows, (int64_t)rows + 1,
                 sizeof *s->bucket_start) &&
         zs_grow((void **)&s->order, &s->cap_polys, polys, sizeof *s->order);
}

size_t zs_scan_scratch_bytes(const zs_scan_scratch *s) {
  return (size_t)s->cap_rows * sizeof *s->bucket_start +
         (size_t)s->cap_polys * sizeof *s->order + (size_t)s->cap_cross * sizeof *s->cross +
         (size_t)s->cap_active * sizeof *s->active;
}

void zs_scan_scratch_free(zs_scan_scratch *s) {
  free(s->bucket_start);
  free(s->order);
  free(s->active);
  free(s->trace_pairs);
  free(s->trace_spans);
  free(s->cross);
  memset(s, 0, sizeof *s);
}

/* A counting sort, stable, so that each bucket keeps batch order: the
 * table is an array read in order, not a linked list, so the records a
 * traversal reads next are known ahead and fetched together, where a
 * list's next link waits for the last record (zscan bench raster --case
 * "random 10x10 back to front" measures it).  Each bucket's count, summed
 * up to it, is where it ends; placing its polygons from the last one
 * back leaves where it begins.  Only the buckets in use are summed: a
 * small draw costs its polygons, not the frame's rows (zscan calibrate's
 * "draw calls"). */
int zs_table_sort(const zs_batch *b, int row_begin, int row_end, zs_scan_scratch *s,
                  zs_table *table) {
  const int32_t nrows = row_end - row_begin;
  if (!reserve(s, nrows, b->npolys > 0 ? b->npolys : 1)) return 0;
  int32_t *start = s->bucket_start, *order = s->order;
  memset(start, 0, (size_t)(nrows + 1) * sizeof *start);
  int32_t first = nrows, last = -1, ncross = 0, last_row = row_begin - 1, polys = 0, jumps = 0;
  int32_t prev_row0 = INT32_MIN, x0 = INT32_MAX, x1 = INT32_MIN;
  /* each bucket's count; the polygons begun above */
  for (int32_t i = 0; i < b->npolys; i++) {
    const zs_poly *p = &b->polys[i];
    if (p->row1 < row_begin || p->row0 >= row_end) continue;
    if (p->row1 > last_row) last_row = p->row1 < row_end ? p->row1 : row_end - 1;
    polys++;
    jumps += p->row0 > prev_row0 + ZS_SOUP_ROW_JUMP || p->row0 < prev_row0 - ZS_SOUP_ROW_JUMP;
    prev_row0 = p->row0;
    if (p->ox < x0) x0 = p->ox;
    if (p->ox > x1) x1 = p->ox;
    if (p->row0 < row_begin) { /* begun above the scan: ordered below */
      if (!zs_grow((void **)&s->cross, &s->cap_cross, ncross + 1, sizeof *s->cross)) return 0;
      s->cross[ncross++] = (int64_t)p->row0 * ((int64_t)1 << 32) + i;
      continue;
    }
    const int32_t r = p->row0 - row_begin;
    start[r]++;
    if (r < first) first = r;
    if (r > last) last = r;
  }
  if (ncross > 0) { /* they head bucket 0 */
    if (first > 0) first = 0;
    if (last < 0) last = 0;
  }
  if (last < 0) {
    *table = (zs_table){nrows, -1, last_row, 0, 0, 0, 0};
    return 1;
  }
  /* where each bucket ends (bucket 0's after the polygons begun above) */
  start[first] += ncross;
  for (int32_t r = first + 1; r <= last; r++) start[r] += start[r - 1];
  for (int32_t i = b->npolys - 1; i >= 0; i--) {
    const zs_poly *p = &b->polys[i];
    if (p->row1 < row_begin || p->row0 >= row_end || p->row0 < row_begin) continue;
    order[--start[p->row0 - row_begin]] = i;
  }
  /* now where each begins; and the end of the last */
  start[last + 1] = polys;
  if (ncross > 0) {
    /* A scan that starts mid-frame (a band of rows) takes first the
     * polygons begun above it, in the order a scan from the top would hold
     * them.  The spans of a row are then filled in the same order in every
     * band layout, and so are counters that depend on it (pixels written,
     * overwrites included). */
    qsort(s->cross, (size_t)ncross, sizeof *s->cross, cmp_int64);
    for (int32_t k = 0; k < ncross; k++) order[k] = (int32_t)(s->cross[k] & 0xFFFFFFFF);
    start[0] = 0;
  }
  *table = (zs_table){first, last, last_row, polys, jumps, x0, x1};
  return 1;
}
