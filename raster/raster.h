/* zscan raster — the emulated graphics device, as the code base sees it:
 * the public API (zscan/zscan.h and its extras) and what only zscan's own
 * layers use (deferred drawing, memory, the SIMD level, the query bias).
 *
 * The device takes meshes, model matrices and a camera, like a GPU, and
 * knows nothing of files, scenes or octrees.  Every convention it relies on
 * is stated here in full and quoted where it is used.
 *
 * COORDINATES
 *   Matrices are double[16], row-major, acting on column vectors:
 *   p' = M p, element (row r, column c) at m[4*r + c].  The camera follows
 *   gluLookAt / gluPerspective: the eye looks down -z, clip space is
 *   OpenGL's (-w <= x,y,z <= w).  Window coordinates follow glViewport with
 *   pixel centres at (x + 0.5, y + 0.5).  The written image has row 0 at the
 *   top, so image y = height - window y.  The rasterizer works in image
 *   coordinates (y down).
 *
 * FIXED POINT (raster/setup.c)
 *   Vertices are snapped to 1/256 pixel (ZS_SUBPIXEL_BITS = 8), rounding to
 *   nearest, ties to even, in window coordinates.  The guard band keeps every
 *   snapped coordinate within +-ZS_GUARD_PIXELS pixels, so coordinates fit
 *   in 24 bits and every edge product in 64.  A face inside the band whose
 *   snapped box holds no pixel centre of the window is dropped at set-up
 *   (polygons_offscreen); the clock still charges it (zs_polygons_set_up).
 *   A face whose box holds no pixel centre at all (a speck between the
 *   centres) covers no pixel: it is counted in polygons_rasterized, as set
 *   up, but never enters the polygon table.
 *
 * COVERAGE
 *   A pixel belongs to a polygon when its centre lies inside; a centre
 *   exactly on an edge belongs to the polygon for which that edge is a left
 *   or a bottom edge in the written image (row 0 at the top).  This is
 *   OpenGL's top-left rule in window coordinates (y up) as Mesa's llvmpipe
 *   applies it, and it gives a centre on an edge shared by two faces to
 *   exactly one of them.  In scanline terms: a polygon covers rows whose
 *   centre yc has ytop < yc <= ybottom, and on a row the columns whose centre
 *   xc has xleft <= xc < xright, both tests exact in integers.
 *
 * DEPTH
 *   Window depth z in [0,1] (0 at the near plane) is stored as a 32-bit
 *   unsigned integer, z * 2^32 saturated to 0xFFFFFFFF; the buffer clears to
 *   0xFFFFFFFF, "farthest".  Each polygon carries a fixed-point plane
 *   Z(px,py) = C + A (px - ox) + B (py - oy) with a per-polygon number of
 *   fraction bits, so stepping by A along a row and by B across rows gives
 *   exactly what evaluating at the pixel gives.
 *   The test is "less": a fragment (z, id) replaces the pixel's (zb, idb)
 *   when z < zb, or z == zb and id < idb.  This is a total order, so the
 *   image never depends on the order of draws or faces.
 *
 * POLYGONS
 *   Faces are convex polygons (loaders split concave ones).  Front faces are
 *   counter-clockwise in window coordinates (OpenGL's default).  Back-face
 *   culling is off unless asked for.  Zero-area faces produce nothing.
 */
#ifndef ZS_RASTER_H
#define ZS_RASTER_H

#include <math.h>
#include <stdint.h>

#include "util/matrix.h"
#include "zscan/error.h"
#include "zscan/clock.h"
#include "zscan/depthsort.h"
#include "zscan/trace.h"
#include "zscan/zscan.h"

enum {
  ZS_SUBPIXEL_BITS = 8,
  ZS_SUBPIXEL_ONE = 1 << ZS_SUBPIXEL_BITS,
  ZS_GUARD_PIXELS = 1 << 15    /* snapped |x|,|y| stay below this */
};

#define ZS_DEFAULT_RGB 0xB4B4B4u /* a face without a colour: light grey */

/* The faces the clock charges a draw for: those that reached set-up and
 * were not culled as back faces or degenerate.  A face dropped there for
 * lying off the window counts, as a GPU sets it up before its scissor. */
static inline uint64_t zs_polygons_set_up(const zs_raster_stats *s) {
  return s->polygons_rasterized + s->polygons_offscreen;
}


/* Deferred drawing (defer.c), for a whole scene drawn on two threads or
 * more in zbuffer mode: while on, zs_device_draw queues each draw of fewer
 * than 262,144 faces, and the next flush renders the queue at once, set up
 * in parallel and scanned in bands of rows with the draws in issue order.
 * The image, the counters and the modelled clock come out the same as
 * drawing at once, but they lag the queue: they hold after a flush, which
 * zs_device_flush, zs_device_finish, a query, zs_device_fill_color,
 * hidden-line edges or a large draw make.  Meshes must stay valid until then; a draw's error is
 * reported by the flush.  Off by default; no effect on one thread. */
void zs_device_defer_draws(zs_device *dev, int on);
zs_status zs_device_flush(zs_device *dev, zs_error *err);


/* ---- query.c: occlusion queries ----
 *
 * Between zs_device_query_begin and zs_device_query_end, every pixel that
 * passes the depth test adds one sample to the query: pixels written by
 * draws, and pixels of query boxes.  A query box (zs_device_query_box)
 * draws the faces of an axis-aligned world box that face the eye (all six,
 * turned inwards, when the eye is inside) with the test "less or equal"
 * and no writes, so a box touching geometry already drawn (a cube's own
 * faces) counts as visible, and each pixel of its outline counts once.
 * The box is brought towards the eye by ZS_QUERY_DEPTH_BIAS depth units
 * (2^-28 of the depth range) plus its faces' depth change over 1/16 pixel
 * (|dz/dx| + |dz/dy| >> ZS_QUERY_SLOPE_SHIFT), as glPolygonOffset(factor,
 * units) does: a box flush with geometry reaches the same depth through
 * different rounding, and a visible node must never test as hidden.  The
 * constant covers the transforms (model x view on the mesh, view on the
 * box's world corners); the slope covers snapping, which moves each corner
 * of both planes by up to 1/256 pixel and so each plane's depth by up to
 * a few hundredths of a pixel's depth change (more than the constant where
 * a face is seen edge-on or through a wide lens).  And the box is grown
 * by zs_device_query_margin on every side, so that its picture holds the
 * snapped picture of whatever lies in it (snapping may move a face's
 * corner on the box's side out past the box's own snapped outline).  A
 * box cut by the near plane counts only what lies beyond the plane: callers
 * treat such boxes as visible without asking.  Queries need the full-frame
 * depth buffer: zbuffer mode only.  Several queries may be in flight while
 * draws go on, as on a GPU; ids count from 0 each frame. */
enum { ZS_QUERY_DEPTH_BIAS = 16, ZS_QUERY_SLOPE_SHIFT = 4 };
typedef uint32_t zs_query;

/* ---- hzb.c: the hierarchical depth buffer (its commands: query.c) ----
 *
 * zs_device_hzb_build builds the depth pyramid of what is drawn so far
 * (level k: the farthest depth of each 2x2 texels of level k - 1, level 0
 * the depth buffer); zs_device_hzb_test tests n boxes against the last
 * pyramid built this frame, setting maybe_visible[i] to 0 only for a box
 * whose query box (above) would count no sample against that depth
 * buffer, and so against any drawn over it later.  A box the near plane
 * cuts, or that holds the eye, is maybe visible.  Costs: clock.h.  The
 * full-frame depth buffer: zbuffer mode only. */
zs_status zs_device_hzb_build(zs_device *dev, zs_error *err);
zs_status zs_device_hzb_test(zs_device *dev, const double (*lo)[3], const double (*hi)[3], int n,
                             uint8_t *maybe_visible, zs_error *err);


/* Whether a draw of mesh on dev would keep transparent fragments: the
 * device's shading reads attributes, not as normals, and a face of the
 * mesh may be transparent (zscan.h, Transparency).  The oracles of
 * culling draw such meshes apart: they occlude nothing. */
int zs_device_draws_transparent(const zs_device *dev, const zs_mesh *mesh);
/* The same for a device of shading shade: the one rule both follow. */
int zs_shade_draws_transparent(zs_shade shade, const zs_mesh *mesh);

/* The memory a device holds now, in bytes: pixel buffers (full-frame in
 * zbuffer mode; one row in scanline and depthsort modes), the polygon and
 * edge tables with the scan's scratch (which grow with the polygons of a
 * draw, or of the whole frame in scanline mode, and one entry per row;
 * with them the surface shadings' records, one per triangle drawn),
 * and the per-vertex arrays of the largest mesh drawn. */
typedef struct zs_device_memory {
  size_t pixel_buffers, tables, vertices;
} zs_device_memory;
zs_device_memory zs_device_memory_of(const zs_device *dev);

/* The draw kernel's span fill (span_simd.c): long spans sixteen pixels at
 * a time with AVX-512 where the CPU has it (F, VL, BW, DQ), else eight at
 * a time with AVX2, else four with SSE2 (every x86-64 CPU), else the
 * scalar loop (span.h, zs_simd_min_span: how long a span each takes);
 * on aarch64 four at a time with NEON, else the scalar loop; at
 * AVX-512 the vertex stage also takes eight vertices at a time
 * (vertex_simd.c).  zs_span_simd_level gives the widest level the CPU has
 * up to most; a device takes its level once, from its config's spans.
 * The images and counters are the same at every level. */
typedef enum zs_simd {
  ZS_SIMD_SCALAR = 0, ZS_SIMD_SSE2 = 1, ZS_SIMD_AVX2 = 2, ZS_SIMD_AVX512 = 3,
  ZS_SIMD_NEON = 4, /* aarch64's only level: every cap but scalar takes it */
  ZS_SIMD_LEVELS
} zs_simd;
zs_simd zs_span_simd_level(zs_simd most);
/* The level a device fills its spans with (fixed at its creation). */
zs_simd zs_device_simd(const zs_device *dev);
/* "scalar", "sse2", "avx2" or "avx512". */
const char *zs_simd_name(zs_simd level);


/* ---- lines.c: hidden-line output ----
 *
 * The lecture's hidden-line removal on the z-buffer: after the faces are
 * drawn (zbuffer mode), zs_device_fill_color paints the colour buffer with
 * one colour (keeping depth and ids), and zs_device_draw_edges draws the
 * edges of the front faces (V . N >= 0: the face turned to the eye) in a
 * line colour wherever the edge is not behind the depth buffer.  An edge
 * lies on its own face, so it is tested with a bias towards the eye, as
 * glPolygonOffset(1, units) does: its face's largest depth slope per pixel
 * (|dz/dx| or |dz/dy| in window depth) plus ZS_EDGE_DEPTH_UNITS units of
 * 2^-32.  Edges are scanned one pixel per step along their major axis,
 * through the pixel the exact edge crosses at that column's (row's)
 * centre. */
enum { ZS_EDGE_DEPTH_UNITS = 1024 };

/* GL's rounding of an aliased line width or point size: to the nearest
 * integer, halves up, at least 1; 0 for a value out of range (not
 * finite, not above 0, above most).  Lines and points (prims.c), the
 * edges (lines.c) and their vectors (lib/svg.h) take their widths so. */
static inline int zs_gl_rounded_size(double v, int most) {
  if (!(v > 0.0) || !(v <= most)) return 0;
  int n = (int)floor(v + 0.5);
  return n < 1 ? 1 : n;
}

/* zs_device_draw_edges with edges width pixels wide (rounded as a line's,
 * zscan.h, and in the same range): at each step along the major axis the
 * width pixels across it centred on the one a width-1 edge paints (an
 * even width: on the pixel boundary nearest the exact edge), each tested
 * at the edge's depth there.  Width 1 is zs_device_draw_edges. */
zs_status zs_device_draw_wide_edges(zs_device *d, const zs_mesh *mesh, const double model[16],
                                    uint32_t rgb, double width, zs_error *err);

/* A visible piece of an edge as zs_device_draw_edges painted it, for
 * vector output: in window coordinates (pixels, x right, y down), from the
 * first painted pixel's outer side to the last one's, along the exact edge.
 * Consecutive painted pixels of one edge make one run. */
typedef struct zs_line_run {
  double x0, y0, x1, y1;
} zs_line_run;

/* keep = 1: zs_device_draw_edges also records its runs (0, the default:
 * it does not); zs_device_clear empties them. */
void zs_device_keep_line_runs(zs_device *d, int keep);
/* The runs recorded since the last clear, n of them (NULL when none; n
 * is -1 when one could not be kept for want of memory). */
const zs_line_run *zs_device_line_runs(const zs_device *d, int32_t *n);

#endif
