/* zscan raster — the traversals of a batch into a target: which pixels a
 * polygon covers (the row scan of the lecture's scanline z-buffer,
 * scanline.c, or a polygon at a time, polyorder.c: the same pixels, in
 * the same order per pixel) and what its spans do there (the kernel).
 *
 * Each traversal is compiled once per kernel and SIMD level, the two
 * constants in its loop, and the device picks its copies once, at
 * create, into a zs_traversal (zs_scan_choose, zs_polyorder_choose):
 * no row, span or batch asks which kernel or level it runs. */
#ifndef ZS_RASTER_TRAVERSAL_H
#define ZS_RASTER_TRAVERSAL_H

#include <stdint.h>
#include <string.h>

#include "raster/abuffer.h"
#include "raster/table.h"

static inline void zs_fill_u32(uint32_t *p, size_t n, uint32_t v) {
  for (size_t i = 0; i < n; i++) p[i] = v;
}

/* n pixels of a target's buffers cleared: the far depth, no id, the
 * background, no fragments (count may be NULL: no counts kept).  Every
 * clear of the project's buffers, a frame's, a row's or a band's. */
static inline void zs_clear_pixels(uint32_t *depth, uint32_t *id, uint32_t *rgb, uint32_t *count,
                                   size_t n, uint32_t background) {
  zs_fill_u32(depth, n, ZS_DEPTH_FAR);
  zs_fill_u32(id, n, ZS_ID_NONE);
  zs_fill_u32(rgb, n, background);
  if (count) memset(count, 0, n * sizeof *count);
}

/* What a span does to the pixels it covers. */
typedef enum zs_kernel {
  ZS_KERNEL_DRAW,      /* less-with-id test; write depth, id, colour */
  ZS_KERNEL_OVERDRAW,  /* count every fragment, no test */
  ZS_KERNEL_QUERY,     /* less-or-equal test, no writes: count passes */
  ZS_KERNEL_FRAGMENT,  /* less-with-id test, no writes: keep the fragment
                        * in its row of the A-buffer (abuffer.h) */
  ZS_KERNELS
} zs_kernel;


/* Where spans land: full-frame buffers (row_stride = width) or one row
 * (row_stride = 0).  Any pointer may be NULL when its kernel does not use
 * it. */
typedef struct zs_target {
  uint32_t *depth, *id, *rgb, *count;
  int64_t row_stride;
  int width;
  int32_t row0;  /* the first row the buffers hold (bands of rows) */
  /* Full-frame buffers cleared lazily: a row y with fresh[y] set holds
   * nothing yet and is cleared (to the far depth, no id, the background,
   * no count) when a scan first reaches it; NULL: every row is ready. */
  uint8_t *fresh;
  uint32_t background;
  zs_fragment_row *frags; /* the fragment kernel's rows, by image row y */
} zs_target;

typedef struct zs_scan_counts {
  uint64_t spans, tested, written;
} zs_scan_counts;

/* sum += c: the bands of a traversal summed in band order. */
static inline void zs_scan_counts_add(zs_scan_counts *sum, const zs_scan_counts *c) {
  sum->spans += c->spans;
  sum->tested += c->tested;
  sum->written += c->written;
}

/* Called before each row in [row_begin, row_end) starts (begin_row) and
 * after it is complete (end_row): scanline mode clears and hands out its
 * one-row buffers there.  Either may be NULL. */
typedef struct zs_row_hooks {
  void (*begin_row)(void *user, int y);
  void (*end_row)(void *user, int y);
  void *user;
} zs_row_hooks;

/* Rows [row_begin, row_end) of batch b, sorted into table, into target t;
 * the spans, pixels tested and pixels written added to counts.  0 when
 * out of memory. */
typedef int (*zs_scan_rows_fn)(const zs_batch *b, const zs_target *t, int row_begin, int row_end,
                               const zs_row_hooks *hooks, const zs_trace_observer *obs,
                               const zs_table *table, zs_scan_scratch *s, zs_scan_counts *counts);
typedef int (*zs_scan_sorted_fn)(const zs_batch *b, const zs_target *t, int row_begin,
                                 int row_end, const zs_table *table, zs_scan_scratch *s,
                                 zs_scan_counts *counts);
typedef void (*zs_by_polygon_fn)(const zs_batch *b, const zs_target *t, int row_begin,
                                 int row_end, const zs_table *table, const zs_scan_scratch *s,
                                 zs_scan_counts *counts);

/* One kernel's traversals at one SIMD level. */
typedef struct zs_traversal {
  zs_scan_rows_fn scan_rows;          /* the row scan, with hooks and observer */
  zs_scan_sorted_fn scan_sorted;      /* the same without: drawing and querying */
  zs_by_polygon_fn by_polygon_mesh;   /* a polygon at a time: a mesh */
  zs_by_polygon_fn by_polygon_soup;   /* and a soup (polyorder.c says which is which) */
} zs_traversal;

/* scanline.c and polyorder.c: their copies for kernel k at level simd. */
void zs_scan_choose(zs_kernel k, zs_simd simd, zs_traversal *out);
void zs_polyorder_choose(zs_kernel k, zs_simd simd, zs_traversal *out);

/* scanline.c: rows [row_begin, row_end) of the batch by the lecture's
 * scanline z-buffer: the sorted polygon table, the active lists, spans
 * filled with the kernel.  0 when out of memory. */
int zs_scan_batch(const zs_traversal *tr, const zs_batch *b, const zs_target *t, int row_begin,
                  int row_end, const zs_row_hooks *hooks, const zs_trace_observer *obs,
                  zs_scan_scratch *s, zs_scan_counts *counts);

/* polyorder.c: the z-buffer mode's traversal of a batch into a full-frame
 * target: the same pixels, depths, writes and counters as zs_scan_batch,
 * a polygon at a time in the sorted table's order, or by the row scan for
 * a mesh laid out in order over a quarter of the frame or more.  0 when
 * out of memory. */
int zs_polyorder_batch(const zs_traversal *tr, const zs_batch *b, const zs_target *t,
                       int row_begin, int row_end, zs_scan_scratch *s, zs_scan_counts *counts);

#endif
