/* zscan raster — the device's private structures, shared by its stages:
 *   the draw stage (draw.c: transform.c's matrices, clip.c, setup.c's
 *   snapping and set-up) -> sorted tables, active lists, spans
 *   (scanline.c) -> rows out (finish.c, shade.c).
 * device.c holds the context and the commands and chooses each stage
 * once; defer.c and immediate.c run the draw stage. */
#ifndef ZS_RASTER_INTERNAL_H
#define ZS_RASTER_INTERNAL_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "raster/raster.h"

/* x86-64 under gcc or clang: the SIMD paths (SSE2, AVX2, AVX-512) are
 * built, each taken at run time where the CPU has it (span_simd.c,
 * zs_span_simd_level).  ZS_AVX512_TARGET: what the device's AVX-512
 * level asks of the CPU (F, VL, BW, DQ), for every AVX-512 path (the
 * span fill, the painter, the vertex stage, the flat levels). */
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define ZS_HAVE_X86_PATHS 1
#define ZS_AVX512_TARGET __attribute__((target("avx512f,avx512vl,avx512bw,avx512dq")))
#define ZS_AVX512_INLINE ZS_AVX512_TARGET __attribute__((always_inline)) static inline
#endif

/* Threads a device may have, and bands of rows a walk is cut into: the
 * fixed sizes of the per-thread and per-band records. */
enum { ZS_MAX_THREADS = 64, ZS_MAX_BANDS = 64 };

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

/* A polygon may gain one vertex per clip plane (6 planes). */
enum { ZS_CLIP_MAX_VERTS = ZS_MAX_POLY_VERTS + 6 };

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

/* One polygon of the sorted polygon table, ready for the scanline walk.
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
   * planes: the walk neither clamps its spans nor tests their depths
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

/* A vertex after transformation: clip coordinates and eye coordinates. */
typedef struct zs_clip_vert {
  double x, y, z, w;
} zs_clip_vert;

/* ---- clip.c ---- */
/* Outcode bits of a clip-space vertex against near, far and the guard
 * band (gx, gy: the band's half-widths in NDC units). */
enum {
  ZS_CLIP_NEAR = 1, ZS_CLIP_FAR = 2,
  ZS_CLIP_LEFT = 4, ZS_CLIP_RIGHT = 8, ZS_CLIP_BOTTOM = 16, ZS_CLIP_TOP = 32
};
/* The signed distance of v from a plane, inside when >= 0.  Inline, with
 * the outcode and zs_snap_vertex below: a draw calls them once per vertex,
 * where a call costs more than the work it does (zscan bench raster --case
 * builtin:teapots --callgrind measures it). */
static inline double zs_clip_plane_dist(const zs_clip_vert *v, int plane, double gx, double gy) {
  switch (plane) {
    case ZS_CLIP_NEAR: return v->z + v->w;
    case ZS_CLIP_FAR: return v->w - v->z;
    case ZS_CLIP_LEFT: return gx * v->w + v->x;
    case ZS_CLIP_RIGHT: return gx * v->w - v->x;
    case ZS_CLIP_BOTTOM: return gy * v->w + v->y;
    default: return gy * v->w - v->y;
  }
}
static inline unsigned zs_clip_outcode(const zs_clip_vert *v, double gx, double gy) {
  unsigned code = 0;
  for (int p = ZS_CLIP_NEAR; p <= ZS_CLIP_TOP; p <<= 1)
    if (!(zs_clip_plane_dist(v, p, gx, gy) >= 0.0)) code |= (unsigned)p; /* NaN: out */
  return code;
}
/* Clips the convex polygon in[0..n-1] against every plane set in mask;
 * writes the result to out (ZS_CLIP_MAX_VERTS entries) and returns its
 * vertex count (0 when nothing is left). */
int zs_clip_polygon(const zs_clip_vert *in, int n, unsigned mask, double gx,
                    double gy, zs_clip_vert *out);
/* Clips the segment a-b to the same planes (all six); returns 0 when
 * nothing is left (hidden-line edges, lines.c). */
int zs_clip_segment(zs_clip_vert *a, zs_clip_vert *b, double gx, double gy);

/* ---- setup.c ---- */
typedef struct zs_setup_params {
  int width, height;
  int cull_back;
  uint32_t id, rgb;
  uint32_t depth_bias;  /* depth units (2^-32) to pull the plane nearer */
  int prefetch_write;   /* ask for the batch's lines ahead of the writes (setup.c) */
} zs_setup_params;

/* Whether the CPU has PREFETCHW (cpuid): set-up asks for the batch's lines
 * with it when the device has threads. */
int zs_cpu_has_prefetchw(void);

typedef enum zs_setup_result {
  ZS_SETUP_DRAWN,
  ZS_SETUP_BACK,
  ZS_SETUP_DEGENERATE,
  ZS_SETUP_OFFSCREEN, /* no pixel centre of the window in its box */
  ZS_SETUP_NOMEM
} zs_setup_result;

/* Snaps the clipped polygon to the sub-pixel grid, computes its depth plane
 * and edge chains, and appends it (or, if snapping left it not convex, a
 * fan of triangles with the same plane) to the batch. */
zs_setup_result zs_setup_polygon(zs_batch *b, const zs_setup_params *p,
                                 const zs_clip_vert *v, int n);

/* A vertex snapped: window x and image y in 1/256 pixel, window depth in
 * [0, 1].  zs_setup_polygon snaps each vertex with zs_snap_vertex; a draw
 * snaps each vertex of its mesh once and hands an unclipped face's
 * vertex indices to zs_setup_snapped, which gives the same result. */
typedef struct zs_snap_vert {
  int32_t x, y;
  double z;
} zs_snap_vert;

/* Where a vertex (w > 0) lands in a width x height window, in pixels: x
 * from the left, y from the bottom (the image's rows run down from
 * height - y). */
static inline void zs_window_xy(int width, int height, const zs_clip_vert *v, double *xw,
                                double *yw) {
  *xw = (v->x / v->w + 1.0) * (0.5 * width);
  *yw = (v->y / v->w + 1.0) * (0.5 * height);
}
/* Its window depth, in [0, 1] inside the near and far planes. */
static inline double zs_window_depth(const zs_clip_vert *v) { return (v->z / v->w + 1.0) * 0.5; }

static inline void zs_snap_vertex(const zs_setup_params *sp, const zs_clip_vert *v,
                                  zs_snap_vert *out) {
  const int64_t h_sub = (int64_t)sp->height * ZS_SUBPIXEL_ONE;
  double xw, yw;
  zs_window_xy(sp->width, sp->height, v, &xw, &yw);
  double zw = zs_window_depth(v);
  out->x = (int32_t)lrint(xw * ZS_SUBPIXEL_ONE);
  /* The difference wraps, as the vector stage's does (vertex_simd.c): a
   * vertex inside every plane at w = 0 (the eye, under a projection that
   * allows it) has no window position, and lrint gives its NaN the
   * integer indefinite, which subtracted in signed arithmetic would
   * overflow. */
  out->y = (int32_t)(uint32_t)((uint64_t)h_sub - (uint64_t)lrint(yw * ZS_SUBPIXEL_ONE));
  out->z = zw < 0.0 ? 0.0 : zw > 1.0 ? 1.0 : zw;
}
/* The polygon v[vi[0]], .., v[vi[n - 1]]. */
zs_setup_result zs_setup_snapped(zs_batch *b, const zs_setup_params *p,
                                 const zs_snap_vert *v, const int32_t *vi, int n);

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

/* ---- span_simd.c: the draw kernel's span fill with SSE2 or AVX2 ----
 * For a span whose depths z .. z + (x1 - x0 - 1) dz all lie strictly
 * inside the depth range: the scalar loop's test and writes, eight (AVX2)
 * or four (SSE2) pixels at a time, as far as whole steps go; adds the
 * pixels written to *written and returns the column where the scalar loop
 * takes over (x0 at ZS_SIMD_SCALAR, and at ZS_SIMD_AVX512, whose kernel
 * span.h takes from span_avx512.h itself, inline where it can). */
int zs_fill_span_simd(zs_simd level, uint32_t *zr, uint32_t *ir, uint32_t *cr, int x0, int x1,
                      int64_t z, int64_t dz, int shift, uint32_t id, uint32_t rgb,
                      uint64_t *written);

/* ---- scanline.c ---- */
typedef enum zs_kernel {
  ZS_KERNEL_DRAW,      /* less-with-id test; write depth, id, colour */
  ZS_KERNEL_OVERDRAW,  /* count every fragment, no test */
  ZS_KERNEL_QUERY      /* less-or-equal test, no writes: count passes */
} zs_kernel;

/* Where spans land: full-frame buffers (row_stride = width) or one row
 * (row_stride = 0).  Any pointer may be NULL when its kernel does not use
 * it. */
typedef struct zs_target {
  uint32_t *depth, *id, *rgb, *count;
  int64_t row_stride;
  int width;
  zs_simd simd;  /* the device's span fill */
  int32_t row0;  /* the first row the buffers hold (bands of rows) */
  /* Full-frame buffers cleared lazily: a row y with fresh[y] set holds
   * nothing yet and is cleared (to the far depth, no id, the background,
   * no count) when a walk first reaches it; NULL: every row is ready. */
  uint8_t *fresh;
  uint32_t background;
} zs_target;

typedef struct zs_walk_counts {
  uint64_t spans, tested, written;
} zs_walk_counts;

/* sum += c: the bands of a walk summed in band order. */
static inline void zs_walk_counts_add(zs_walk_counts *sum, const zs_walk_counts *c) {
  sum->spans += c->spans;
  sum->tested += c->tested;
  sum->written += c->written;
}

/* Called after each row in [row_begin, row_end) is complete, and before it
 * starts (begin_row) — scanline mode clears and emits its one-row buffers
 * there.  Either may be NULL. */
typedef struct zs_row_hooks {
  void (*begin_row)(void *user, int y);
  void (*end_row)(void *user, int y);
  void *user;
} zs_row_hooks;

/* An edge being walked: the exact integer DDA (edge_dda.h), 24 bytes. */
typedef struct zs_edge_dda {
  int32_t x, q;
  uint32_t rem, rs, d;
  int32_t last;  /* the last row it covers (the lecture's dy: last - y) */
} zs_edge_dda;

/* An entry of the active lists: a polygon and its current edge pair, with
 * the polygon's fields the rows read copied in (one place to read per row,
 * not two).  Small: the walk streams the whole list every row and moves
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

/* Per-walk scratch, kept by the device so walks do not allocate. */
typedef struct zs_walk_scratch {
  int32_t *bucket_start;        /* the sorted polygon table (table.c, zs_table) */
  int32_t *order;
  int32_t cap_rows, cap_polys;
  zs_active *active;            /* the active polygon / edge-pair list */
  int32_t cap_active;
  zs_trace_pair *trace_pairs;   /* a traced row (trace.c) */
  zs_trace_span *trace_spans;
  int64_t *cross;               /* polygons begun above a band, to order */
  int32_t cap_cross;
} zs_walk_scratch;

/* trace.c: the sorted tables handed to obs; one active entry as a pair. */
void zs_trace_tables(const zs_batch *b, const zs_trace_observer *obs);
void zs_trace_pair_of(const zs_active *a, const zs_poly *p, int32_t y, zs_trace_pair *out);

/* table.c: the sorted polygon table of rows [row_begin, row_end) of b,
 * in s: each polygon bucketed under its first row, each bucket in batch
 * order; polygons begun above the first row head its bucket, by first
 * row, then batch order, as a walk from the top would hold them.  Bucket
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
int zs_table_sort(const zs_batch *b, int row_begin, int row_end, zs_walk_scratch *s,
                  zs_table *table);
void zs_walk_scratch_free(zs_walk_scratch *s);

/* scanline.c: walks rows [row_begin, row_end) of the batch, the
 * lecture's scanline z-buffer: the sorted polygon table, the active
 * lists, spans filled with the kernel.  Returns 0 when out of memory. */
int zs_scan_batch(const zs_batch *b, zs_kernel k, const zs_target *t,
                  int row_begin, int row_end, const zs_row_hooks *hooks,
                  const zs_trace_observer *obs, zs_walk_scratch *s,
                  zs_walk_counts *counts);

/* scanline.c: the walk of a table already sorted, into a full-frame
 * target, no hooks, no observer (0: out of memory). */
int zs_walk_sorted(const zs_batch *b, zs_kernel k, const zs_target *t, int row_begin,
                   int row_end, const zs_table *table, zs_walk_scratch *s,
                   zs_walk_counts *counts);

/* paint.c: the z-buffer mode's traversal of a batch into a full-frame
 * target: the same pixels, depths, writes and counters as zs_scan_batch,
 * a polygon at a time in the sorted table's order, or by the scanline
 * walk for a mesh laid out in order over a quarter of the frame or more.
 * Returns 0 when out of memory. */
int zs_paint_batch(const zs_batch *b, zs_kernel k, const zs_target *t, int row_begin,
                   int row_end, zs_walk_scratch *s, zs_walk_counts *counts);

/* ---- shade.c ---- */
/* The flat level of a face, q = round(255 I) (shade.c), from its
 * eye-space normal n (need not be unit) against the fixed light. */
static inline uint32_t zs_flat_level(const double n[3]) {
  const double l[3] = {0.2672612419124244, 0.5345224838248488,
                       0.8017837257372732}; /* (1,2,3)/sqrt(14) */
  double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  double cosine = len > 0.0 ? fabs(n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / len : 0.0;
  /* past 1 where the squares are subnormal (|n| near 1e-162) and round
   * coarsely: up to 1.015, a level of 258 without the clamp */
  if (cosine > 1.0) cosine = 1.0;
  return (uint32_t)lrint(255.0 * (0.25 + 0.75 * cosine));
}

/* rgb at level q: each channel times q / 255, rounded. */
static inline uint32_t zs_flat_tint(uint32_t rgb, uint32_t q) {
  uint32_t r = (rgb >> 16) & 0xFF, g = (rgb >> 8) & 0xFF, b = rgb & 0xFF;
  r = (r * q + 127) / 255;
  g = (g * q + 127) / 255;
  b = (b * q + 127) / 255;
  return r << 16 | g << 8 | b;
}

/* The levels q[0 .. n) of n faces whose normals are (nx, ny, nz)[k]:
 * eight at a time with AVX-512 where simd is, the same bits as
 * zs_flat_level (shade.c). */
void zs_flat_levels(zs_simd simd, const double *nx, const double *ny, const double *nz, int n,
                    uint32_t *q);

/* The colours of one finished row (out) for a shading mode other than
 * flat; chosen with the projection, when the camera is set (device.c). */
typedef void (*zs_row_shader)(int width, const uint32_t *depth, const uint32_t *id,
                              const uint32_t *count, double znear, double zfar, uint32_t *out);
zs_row_shader zs_row_shader_for(zs_shade shade, int perspective);

/* ---- depthsort.c ---- */
typedef struct zs_depthsort {
  uint32_t *face_ids;    /* this frame's faces in view, as drawn */
  double *face_keys;     /* and their sort keys */
  uint32_t nfaces, cap_faces;
  uint32_t *noted_ids;   /* the last frame's face_ids and face_keys */
  double *noted_keys;
  uint32_t nnoted, cap_noted;
  /* per face id (dense, grown to the largest id seen) */
  double *key_of, *prev_key;
  int32_t *rank_of;      /* this frame's place, back to front */
  uint32_t *seen;        /* frame stamp: present this frame */
  uint32_t *was;         /* frame stamp: kept in this frame's old queue */
  uint32_t cap_ids;
  uint32_t *order, *prev_order, *tmp, *fresh;  /* ids */
  uint32_t n_prev, cap_order;
  uint32_t frame;
  uint32_t ordered_frame; /* the seen stamp of the faces in prev_order */
  double drift;           /* the depth shift since prev_key was written */
  double prev_view[16];
  int has_prev;
  zs_depthsort_stats stats;
  double ms;
} zs_depthsort;

/* Records a face in view (whether or not it covers a pixel centre). */
int zs_depthsort_note(zs_depthsort *ds, uint32_t id, double key);
/* Orders the batch's faces and gives each polygon its painter's depth. */
int zs_depthsort_order(zs_depthsort *ds, zs_batch *b, const double view[16]);
void zs_depthsort_free(zs_depthsort *ds);

/* ---- the device (device.c, defer.c, immediate.c, draw.c, query.c, clock.c, hzb.c) ---- */

/* A draw's vertices after transformation (draw.c): clip coordinates,
 * eye coordinates (flat shading, the painter's keys), outcodes, and the
 * snapped window position of each vertex inside every plane. */
typedef struct zs_vert_scratch {
  zs_clip_vert *clip;
  double *eyepos;
  unsigned *outcode;
  zs_snap_vert *snap;
  int32_t cap;
} zs_vert_scratch;

int zs_vert_scratch_reserve(zs_vert_scratch *v, int32_t n); /* 0: out of memory */
void zs_vert_scratch_free(zs_vert_scratch *v);
size_t zs_vert_scratch_bytes(const zs_vert_scratch *v);

/* What a draw fixes before its vertices and faces are processed. */
typedef struct zs_draw_prep {
  double mv[16], mvp[16];
  zs_setup_params sp;
  int flat, need_eye;
} zs_draw_prep;

/* depthsort.c: whether the painter orders a face that set-up has seen
 * (result r): it meets the circle around the window and, where back faces
 * are culled, is or may be turned to the eye.  An unclipped face
 * (clipped NULL; corners fv, snapped in v->snap) or the clipped polygon
 * of n corners; scratch holds n corners. */
int zs_depthsort_selects(const zs_device *d, const zs_setup_params *sp, zs_setup_result r,
                         const zs_vert_scratch *v, const int32_t *fv, const zs_clip_vert *clipped,
                         int n, zs_clip_vert *scratch);

/* The counters the set-up of a range of faces adds. */
typedef struct zs_face_counts {
  uint64_t in, outside, clipped, culled_back, degenerate, offscreen, rasterized;
} zs_face_counts;

typedef struct zs_deferred zs_deferred; /* defer.c */

/* A query: its samples so far, and when the GPU finished its last command
 * (ps); the result is ready a latency later. */
typedef struct zs_query_rec {
  uint64_t samples;
  int64_t gpu_end_ps;
} zs_query_rec;

/* The clock's costs in integer picoseconds (from zs_clock_params). */
typedef struct zs_clock_costs {
  int64_t per_call, per_vertex, per_polygon, per_span, per_pixel, per_write, per_query_pixel;
  int64_t switch_cost, latency;
  int64_t cpu_per_call, cpu_per_query, cpu_per_node, cpu_per_frustum, cpu_per_cost_eval;
  int64_t hzb_pass, hzb_per_texel, hzb_per_box, hzb_per_read;
} zs_clock_costs;

/* hzb.c: the depth pyramid's levels 1 .. levels - 1 (level 0 is the depth
 * buffer), level k at texel + offset[k], w[k] x h[k]. */
enum { ZS_HZB_MAX_LEVELS = 24 };
typedef struct zs_hzb {
  uint32_t *texel;
  int32_t cap;
  int levels;
  int w[ZS_HZB_MAX_LEVELS], h[ZS_HZB_MAX_LEVELS];
  int64_t offset[ZS_HZB_MAX_LEVELS];
  int64_t texels;                 /* in levels 1 .. levels - 1 */
  int built;                      /* built since the last clear */
} zs_hzb;
void zs_hzb_free(zs_hzb *h);
size_t zs_hzb_bytes(const zs_hzb *h);

struct zs_device {
  zs_device_config cfg;
  zs_simd simd;                   /* the span fill, from cfg.spans and the CPU */
  double view[16], proj[16];
  double eye[3];                  /* world position of the eye */
  double znear, zfar;
  int perspective;
  double gx, gy;                  /* guard band half-widths, NDC units */
  /* Depth sort orders the faces that meet the circle around the window,
   * centred where the view axis meets the image plane: a roll keeps that
   * set whole.  A point's place on the image plane is u = (x_ndc - cx) *
   * sx, v = (y_ndc - cy) * sy; the circle is u^2 + v^2 <= r2. */
  double sort_cx, sort_cy, sort_sx, sort_sy, sort_r2;
  zs_raster_stats stats;

  uint32_t *depth, *id, *rgb, *count;  /* full frame (zbuffer mode) */
  uint8_t *fresh;                      /* per row: not cleared yet (zs_target) */
  uint32_t *blank;                     /* a cleared row: depth, id, colour, count */
  uint32_t *row_depth, *row_id, *row_rgb, *row_count; /* scanline mode */
  uint32_t *row_out;                   /* one shaded row */
  uint32_t *band_rows;                 /* scanline mode on threads: each thread's
                                        * band of rows, four buffers (finish.c) */
  int band_max_rows;

  zs_batch batch;
  zs_walk_scratch scratch;
  zs_vert_scratch verts;          /* per mesh vertex, this draw */

  /* queries and the clock */
  zs_clock_params clock_params;
  zs_clock_costs costs;
  zs_clock_stats clock;
  zs_query_rec *queries;
  uint32_t nqueries, cap_queries;
  int query_open;                 /* a query is between begin and end */
  const zs_trace_observer *trace; /* scanline mode's observer, or NULL */
  zs_depthsort depthsort;
  zs_hzb hzb;
  /* threads: zbuffer mode walks large batches in bands of rows */
  struct zs_pool *pool;
  int prefetch_write;             /* threads, and the CPU has PREFETCHW (setup.c) */
  zs_walk_scratch *band_scratch;  /* one per band */
  zs_batch *setup_parts;          /* a large draw's faces set up by thread
                                   * t > 0 (thread 0 uses batch) */
  int last_was_query;             /* the GPU's last command was a query box */
  /* Chosen once, at create, from the mode, the shading and the threads
   * (device.c, choose_stages; draw again when deferral is switched), so
   * that no command asks which mode it is in. */
  zs_kernel kernel;               /* what a draw's pixels do: DRAW or OVERDRAW */
  zs_draw_prep prep_of[3];        /* a draw's fixed part, per kernel */
  zs_depthsort *painter;          /* &depthsort in depthsort mode, else NULL */
  zs_status (*draw)(zs_device *d, const zs_mesh *mesh, const double model[16],
                    uint32_t id_base, uint32_t rgb, zs_error *err);
  zs_status (*set_up)(zs_device *d, const zs_mesh *mesh, const zs_draw_prep *prep,
                      uint32_t id_base, uint32_t rgb, zs_error *err);
  int (*walk)(zs_device *d, zs_kernel k, zs_walk_counts *out);
  void (*clear_buffers)(zs_device *d);
  zs_status (*finish)(zs_device *d, zs_row_sink sink, void *user, zs_error *err);
  zs_row_shader shade_row;        /* and with the projection (set_camera) */
  void (*emit)(zs_device *d, int y, const uint32_t *depth, const uint32_t *id,
               const uint32_t *rgb, const uint32_t *count, zs_row_sink sink, void *user);
  zs_deferred *deferred;          /* zs_device_defer_draws: the queued draws */
  /* zs_device_keep_line_runs: the hidden lines as vectors (lines.c) */
  int keep_runs;
  int nomem_runs;                 /* a run could not be kept */
  zs_line_run *runs;
  int32_t nruns, cap_runs;
};

/* draw.c, the draw stage: a draw's preparation (its fixed part per
 * kernel, chosen at create, and its matrices), its vertices [i0, i1)
 * transformed into v, its faces [f0, f1) set up into b (the painter's
 * keys to ds, NULL when not the painter); a face with a vertex out of
 * range stops it with an error. */
void zs_draw_prep_fixed(const zs_device *d, zs_kernel k, zs_draw_prep *p);
void zs_draw_prepare(const zs_device *d, const double model[16], zs_kernel k, zs_draw_prep *p);
void zs_draw_transform(const zs_device *d, const zs_draw_prep *p, const zs_mesh *mesh,
                       zs_vert_scratch *v, int32_t i0, int32_t i1);
/* vertex_simd.c: the vertex stage of vertices [i0, i1) eight at a time
 * with AVX-512, the same bits as draw.c's loop; returns the first vertex
 * left to that loop (gx, gy: the guard band, as zs_clip_outcode takes it).
 * Only on a device whose level is ZS_SIMD_AVX512. */
int32_t zs_vertex_stage_avx512(const zs_draw_prep *p, const zs_mesh *mesh, zs_vert_scratch *v,
                               int32_t i0, int32_t i1, double gx, double gy);
zs_status zs_draw_setup(const zs_device *d, const zs_draw_prep *p, const zs_vert_scratch *v,
                        const zs_mesh *mesh, int32_t f0, int32_t f1, uint32_t id_base,
                        uint32_t rgb, zs_depthsort *ds, zs_batch *b, zs_face_counts *fc,
                        zs_error *err);
void zs_add_face_counts(zs_raster_stats *s, const zs_face_counts *fc);
/* A drawn walk's counts into the device's counters. */
void zs_add_walk_counts(zs_raster_stats *s, const zs_walk_counts *c);
/* The full-frame buffers of zbuffer mode as a walk's target. */
zs_target zs_draw_frame_target(zs_device *d);

/* Drawing at once, a draw from ZS_PARALLEL_SETUP_FACES faces is
 * transformed and set up in parts over the threads; below, handing the
 * work over costs more than it saves.  Deferred, draws below
 * ZS_DEFER_MAX_FACES are queued (the queue is shared out by faces, so a
 * draw of a few thousand faces balances with the rest).  A queued draw is
 * set up whole by one thread, so a larger one is drawn at once in parts.
 * Below the limit a draw is better queued than drawn at once in parts,
 * whose parts are copied into one batch before the walk and read back
 * from memory by it (zscan bench raster --case 'builtin:default?level=42'
 * --threads 2 measures it on nine teapots of 69,868 faces). */
enum { ZS_PARALLEL_SETUP_FACES = 4096, ZS_DEFER_MAX_FACES = 262144 };
/* The bands a walk of `rows` rows takes on `threads` threads: four a
 * thread, taken in turn (the rows of a picture do not hold equal work: the
 * objects sit where they sit), at least 16 rows a band, at most
 * ZS_MAX_BANDS; 0 or 1 means one walk. */
static inline int zs_band_count(int threads, int rows) {
  int n = 4 * threads < ZS_MAX_BANDS ? 4 * threads : ZS_MAX_BANDS;
  return n < rows / 16 ? n : rows / 16;
}

/* immediate.c: drawing at once.  A draw through the draw stage into the
 * batch (set_up: whole on one thread, or split over the pool when large),
 * then the batch walked (walk: into the full frame, on one thread or in
 * bands, or kept for finish in scanline and depthsort modes); the walk's
 * counts go to out.  Shared by zs_device_draw and the query boxes. */
zs_status zs_set_up_whole(zs_device *d, const zs_mesh *mesh, const zs_draw_prep *prep,
                          uint32_t id_base, uint32_t rgb, zs_error *err);
zs_status zs_set_up_split(zs_device *d, const zs_mesh *mesh, const zs_draw_prep *prep,
                          uint32_t id_base, uint32_t rgb, zs_error *err);
int zs_walk_frame(zs_device *d, zs_kernel k, zs_walk_counts *out);
int zs_walk_frame_banded(zs_device *d, zs_kernel k, zs_walk_counts *out);
int zs_walk_kept(zs_device *d, zs_kernel k, zs_walk_counts *out);
zs_status zs_draw_at_once(zs_device *d, const zs_mesh *mesh, const double model[16],
                          uint32_t id_base, uint32_t rgb, zs_kernel k, zs_walk_counts *out,
                          zs_error *err);

/* draw.c: clears the rows of the full frame not cleared yet, for a
 * reader of the whole frame (the buffers' getters, the pyramid, the
 * hidden lines). */
void zs_frame_clear_fresh(const zs_device *d);

/* finish.c: sets d->finish and d->emit for the mode, the shading, the
 * threads and the trace; zs_finish_bands_alloc gives scanline and
 * depthsort modes on threads their bands of rows (0: out of memory). */
void zs_finish_choose(zs_device *d);
int zs_finish_bands_alloc(zs_device *d);
size_t zs_finish_bands_bytes(const zs_device *d);

/* defer.c: draws queued while zs_device_defer_draws is on, and rendered
 * together at the next flush: set up in parallel, walked in bands of rows,
 * each band taking the draws in order; counters and clock settled draw by
 * draw in issue order, so everything is what immediate drawing gives.
 * zs_defer_start makes the queue (0: no memory for it). */
int zs_defer_start(zs_device *d);
zs_status zs_defer_push(zs_device *d, const zs_mesh *mesh, const double model[16],
                        uint32_t id_base, uint32_t rgb, zs_kernel k, zs_error *err);
void zs_defer_discard(zs_device *d);
void zs_defer_free(zs_device *d);
size_t zs_defer_bytes(const zs_device *d);

/* clock.c: the GPU time (ps) of a draw or query box with these counts. */
int64_t zs_clock_command_cost(const zs_device *d, int32_t vertices, uint64_t polygons,
                              const zs_walk_counts *c, int is_query);
/* The GPU executes a command of the given cost (ps), issued by the CPU
 * now; returns the GPU time at which it ends. */
int64_t zs_clock_gpu_command(zs_device *d, int64_t cost, int is_query);
/* The same for a command the CPU issued at cpu_ps (a deferred draw). */
int64_t zs_clock_gpu_command_at(zs_device *d, int64_t cost, int is_query, int64_t cpu_ps);
void zs_clock_cpu(zs_device *d, int64_t cost);
void zs_clock_reset(zs_device *d);

#endif
