/* zscan raster — the sorted polygon table (table.c): a batch's polygons
 * bucketed by their first row, and the scratch every traversal of a batch
 * keeps so that it does not allocate. */
#ifndef ZS_RASTER_TABLE_H
#define ZS_RASTER_TABLE_H

#include "raster/batch.h"
#include "raster/raster.h"

typedef struct zs_active zs_active; /* scan.h */

/* A traversal's scratch, kept by the device so traversals do not allocate. */
typedef struct zs_scan_scratch {
  int32_t *bucket_start;        /* the sorted polygon table (table.c, zs_table) */
  int32_t *order;
  int32_t cap_rows, cap_polys;
  zs_active *active;            /* the active polygon / edge-pair list */
  int32_t cap_active;
  zs_trace_pair *trace_pairs;   /* a traced row (trace.c) */
  zs_trace_span *trace_spans;
  int64_t *cross;               /* polygons begun above a band, to order */
  int32_t cap_cross;
} zs_scan_scratch;


/* table.c: the sorted polygon table of rows [row_begin, row_end) of b,
 * in s: each polygon bucketed under its first row, each bucket in batch
 * order; polygons begun above the first row head its bucket, by first
 * row, then batch order, as a scan from the top would hold them.  Bucket
 * r, for r from first to last, is order[bucket_start[r] ..
 * bucket_start[r + 1]); no polygon begins past last.  0 when out of
 * memory. */
typedef struct zs_table {
  int32_t first, last; /* the buckets in use (first > last: none) */
  int32_t last_row;  /* the last row any polygon covers */
  int32_t polys;     /* polygons in the table */
  int32_t jumps;     /* of them, how many begin more than two rows from
                      * the one before in batch order (a soup: most) */
  int32_t x0, x1;    /* the least and greatest of their planes' origin
                      * columns (a corner's), within the target's width:
                      * about the columns they cover */
} zs_table;
int zs_table_sort(const zs_batch *b, int row_begin, int row_end, zs_scan_scratch *s,
                  zs_table *table);
void zs_scan_scratch_free(zs_scan_scratch *s);
size_t zs_scan_scratch_bytes(const zs_scan_scratch *s);

#endif
