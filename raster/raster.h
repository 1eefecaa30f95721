/* zscan raster — the emulated graphics device.
 *
 * The device takes meshes, model matrices and a camera, like a GPU, and
 * knows nothing of files, scenes or octrees.  Every convention it relies on
 * is stated here once and quoted where it is used.
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

#include <stdint.h>

#include "raster/error.h"

enum {
  ZS_SUBPIXEL_BITS = 8,
  ZS_SUBPIXEL_ONE = 1 << ZS_SUBPIXEL_BITS,
  ZS_GUARD_PIXELS = 1 << 15,   /* snapped |x|,|y| stay below this */
  ZS_MAX_IMAGE_SIDE = 16384,   /* width and height, each */
  ZS_MAX_POLY_VERTS = 64       /* per face, before clipping */
};

#define ZS_PI 3.14159265358979323846
#define ZS_DEPTH_FAR 0xFFFFFFFFu
#define ZS_ID_NONE 0xFFFFFFFFu
#define ZS_RGB_MESH 0xFF000000u /* draw with the mesh's own colours */

/* Geometry the device draws: owned by the caller, read only.
 * Faces are index lists into pos: face f uses face_vert[face_start[f] ..
 * face_start[f+1]-1].  face_id gives each face the id used for the depth
 * tie-break and --shade id (NULL: the face index); several mesh faces may
 * share an id when a loader split one face.  face_rgb is 0xRRGGBB per face
 * (NULL: grey). */
typedef struct zs_mesh {
  double *pos;          /* x, y, z per vertex */
  int32_t nverts;
  int32_t *face_start;  /* nfaces + 1 entries */
  int32_t *face_vert;
  int32_t nfaces;
  uint32_t *face_rgb;
  int32_t *face_id;
} zs_mesh;

typedef enum zs_algo {
  ZS_ALGO_ZBUFFER,  /* immediate mode: each draw into full-frame buffers */
  ZS_ALGO_SCANLINE, /* the whole frame at once, one row of buffers */
  ZS_ALGO_DEPTHSORT /* painter's algorithm with frame coherence (depthsort.c) */
} zs_algo;

/* "zbuffer", "scanline", "depthsort"; and back (-1 for another name). */
const char *zs_algo_name(zs_algo a);
int zs_algo_parse(const char *name);

typedef enum zs_shade {
  ZS_SHADE_FLAT,     /* material colour times a Lambert term, see shade.c */
  ZS_SHADE_ID,       /* RGB = id + 1 as 24 bits, background 0 */
  ZS_SHADE_DEPTH,    /* grey from the linear eye distance, near white */
  ZS_SHADE_OVERDRAW  /* fragments per pixel as a heat map, no depth test */
} zs_shade;

typedef struct zs_device_config {
  int width, height;       /* 1 .. ZS_MAX_IMAGE_SIDE */
  zs_algo algo;
  zs_shade shade;
  int cull_back;           /* drop faces clockwise in window coordinates */
  int threads;             /* 1 for now */
  uint32_t background;     /* 0xRRGGBB for flat shading */
} zs_device_config;

/* Counters of one frame (since the last zs_device_clear). */
typedef struct zs_raster_stats {
  uint64_t draws;
  uint64_t vertices;             /* vertices transformed */
  uint64_t polygons_in;          /* faces submitted */
  uint64_t polygons_outside;     /* dropped whole: outside a clip plane */
  uint64_t polygons_clipped;     /* crossed near, far or the guard band */
  uint64_t polygons_culled_back; /* back faces, when culling is on */
  uint64_t polygons_degenerate;  /* zero area after snapping */
  uint64_t polygons_offscreen;   /* in the guard band, but their window box holds
                                  * no pixel centre: dropped by set-up */
  uint64_t polygons_rasterized;  /* set up and walked by the scanline code */
  uint64_t spans;                /* non-empty spans filled */
  uint64_t pixels_tested;        /* fragments depth-tested */
  uint64_t pixels_written;       /* fragments that passed and were written */
} zs_raster_stats;

/* The faces the clock charges a draw for: those that reached set-up and
 * were not culled as back faces or degenerate.  A face dropped there for
 * lying off the window counts, as a GPU sets it up before its scissor. */
static inline uint64_t zs_polygons_set_up(const zs_raster_stats *s) {
  return s->polygons_rasterized + s->polygons_offscreen;
}

/* One finished row of the image, handed to a zs_row_sink in order y = 0,
 * 1, ..., height-1.  rgb is 0xRRGGBB per pixel as shaded; depth and id are
 * the raw buffers (id ZS_ID_NONE for background); count is the fragment
 * count per pixel in ZS_SHADE_OVERDRAW, else NULL.  The pointers are valid
 * only during the call. */
typedef struct zs_row {
  int y, width;
  const uint32_t *rgb;
  const uint32_t *depth;
  const uint32_t *id;
  const uint32_t *count;
} zs_row;

typedef void (*zs_row_sink)(void *user, const zs_row *row);

typedef struct zs_device zs_device;

zs_status zs_device_create(const zs_device_config *cfg, zs_device **out,
                           zs_error *err);
void zs_device_destroy(zs_device *dev);
const zs_device_config *zs_device_config_of(const zs_device *dev);

/* The camera for the following draws: view (world to eye) and projection
 * (eye to clip).  near/far are read from proj for the depth shading. */
void zs_device_set_camera(zs_device *dev, const double view[16],
                          const double proj[16]);

/* Starts a frame: clears colour, depth and id, and the counters. */
void zs_device_clear(zs_device *dev);

/* Draws every face of mesh, placed by model (NULL: identity); face f gets
 * id id_base + face_id[f] and the colour rgb, or its mesh colour when rgb
 * is ZS_RGB_MESH.  In zbuffer mode the faces are rasterized now; in scanline
 * mode they are set up and kept for zs_device_finish. */
zs_status zs_device_draw(zs_device *dev, const zs_mesh *mesh,
                         const double model[16], uint32_t id_base, uint32_t rgb,
                         zs_error *err);

/* Ends the frame (scanline mode rasterizes it now) and hands every row to
 * sink, top to bottom.  sink may be NULL. */
zs_status zs_device_finish(zs_device *dev, zs_row_sink sink, void *user,
                           zs_error *err);

const zs_raster_stats *zs_device_stats(const zs_device *dev);

/* Deferred drawing (defer.c), for a whole scene drawn on two threads or
 * more in zbuffer mode: while on, zs_device_draw queues each draw of fewer
 * than 262,144 faces, and the next flush renders the queue at once, set up
 * in parallel and walked in bands of rows with the draws in issue order.
 * The image, the counters and the modelled clock come out the same as
 * drawing at once, but they lag the queue: they hold after a flush, which
 * zs_device_flush, zs_device_finish, a query, zs_device_fill_color,
 * hidden-line edges or a large draw make.  Meshes must stay valid until then; a draw's error is
 * reported by the flush.  Off by default; no effect on one thread. */
void zs_device_defer_draws(zs_device *dev, int on);
zs_status zs_device_flush(zs_device *dev, zs_error *err);

/* The full-frame buffers of zbuffer mode (NULL in scanline mode), row 0 at
 * the top, width * height entries. */
const uint32_t *zs_device_depth_buffer(const zs_device *dev);
const uint32_t *zs_device_id_buffer(const zs_device *dev);

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
 * a face is seen edge-on or through a wide lens: fuzz_cull found three
 * objects sharing one quad, seen through a 152-degree lens, where 16 units
 * alone let hsw cull the copy with the lowest id).  And the box is grown
 * by zs_device_query_margin on every side, so that its picture holds the
 * snapped picture of whatever lies in it (snapping may move a face's
 * corner on the box's side out past the box's own snapped outline).  A
 * box cut by the near plane counts only what lies beyond the plane: callers
 * treat such boxes as visible without asking.  Queries need the full-frame
 * depth buffer: zbuffer mode only.  Several queries may be in flight while
 * draws go on, as on a GPU; ids count from 0 each frame. */
enum { ZS_QUERY_DEPTH_BIAS = 16, ZS_QUERY_SLOPE_SHIFT = 4 };
typedef uint32_t zs_query;

zs_status zs_device_query_begin(zs_device *dev, zs_query *q, zs_error *err);
/* How far a query box lo..hi grows on every side, in world units, with
 * the camera set now: 1/32 pixel at its farthest point.  Callers that
 * keep boxes cut by the near plane from being asked grow them as much. */
double zs_device_query_margin(const zs_device *dev, const double lo[3], const double hi[3]);
zs_status zs_device_query_end(zs_device *dev, zs_error *err);
zs_status zs_device_query_box(zs_device *dev, const double lo[3],
                              const double hi[3], zs_error *err);
/* n boxes (lo[i], hi[i]) as one draw call, as a multiquery draws them. */
zs_status zs_device_query_boxes(zs_device *dev, const double (*lo)[3],
                                const double (*hi)[3], int n, zs_error *err);
/* Whether the result of q is available at the CPU's current modelled time
 * (never advances the clock). */
int zs_device_query_ready(const zs_device *dev, zs_query q);
/* The samples of q.  When the result is not ready, the CPU waits: its clock
 * moves to the result's ready time and the wait counts as a stall. */
uint64_t zs_device_query_result(zs_device *dev, zs_query q);

/* The memory a device holds now, in bytes: pixel buffers (full-frame in
 * zbuffer mode; one row in scanline and depthsort modes), the polygon and
 * edge tables with the walk's scratch (which grow with the polygons of a
 * draw, or of the whole frame in scanline mode, and one entry per row),
 * and the per-vertex arrays of the largest mesh drawn. */
typedef struct zs_device_memory {
  size_t pixel_buffers, tables, vertices;
} zs_device_memory;
zs_device_memory zs_device_memory_of(const zs_device *dev);

/* The draw kernel's span fill (span_simd.c): long spans eight pixels at
 * a time with AVX2 where the CPU has it, else four at a time with SSE2
 * (every x86-64 CPU), else the scalar loop.  zs_raster_set_simd caps the
 * level for the whole program (default ZS_SIMD_AVX2: the best there is)
 * and returns the level now in use.  The images and counters are the same
 * at every level. */
typedef enum zs_simd { ZS_SIMD_SCALAR = 0, ZS_SIMD_SSE2 = 1, ZS_SIMD_AVX2 = 2 } zs_simd;
zs_simd zs_raster_set_simd(zs_simd most);
/* "scalar", "sse2" or "avx2". */
const char *zs_simd_name(zs_simd level);

/* ---- clock.c: the modelled clock ----
 *
 * Real queries answer after a latency, and a CPU that waits for an answer
 * stalls.  The device models both sides with clocks that advance by costs
 * computed from counts, never from wall time, so modelled times are the
 * same on every run, build and thread count:
 *   GPU: a command starts when both the GPU is free and the CPU has issued
 *        it, and takes  per_call + vertices * per_vertex
 *        + polygons * per_polygon + spans * per_span
 *        + pixels tested * per_pixel + pixels written * per_write  (draws)
 *        or the same with pixels * per_query_pixel for the pixel terms
 *        (query boxes); a change between drawing and querying costs
 *        switch_ns; a query's result is ready query_latency after the GPU
 *        finished its last command inside the query (its GPU end).
 *   CPU: issuing a draw or a query costs cpu_per_call / cpu_per_query; the
 *        caller reports its own work (node visits, frustum tests, cost-model
 *        evaluations) with zs_device_cpu_work; asking for a result not yet
 *        ready moves the CPU clock to the ready time.  That wait has two
 *        parts, counted apart: up to the query's GPU end the CPU waits for
 *        queued GPU work (sync: the GPU is the bottleneck), after it for
 *        the latency (a stall: what CHC-style methods hide).  With latency
 *        0 nothing ever stalls.
 *   A frame's modelled time is the later of the two clocks at its end.
 *   The GPU's part of it is split four ways: drawing commands (clears and
 *   draws), query boxes, switches, and idle (waiting for the CPU to issue
 *   the next command, or at the end for the CPU to finish); the four add
 *   up to the frame (zs_clock_gpu_split).
 * Times are kept in integer picoseconds; parameters are nanoseconds. */
typedef struct zs_clock_params {
  double per_call_ns;         /* GPU: fixed cost of a draw or query box */
  double per_vertex_ns;       /* GPU: per vertex transformed */
  double per_polygon_ns;      /* GPU: per polygon set up */
  double per_span_ns;         /* GPU: per span (a polygon's run on one row) */
  double per_pixel_ns;        /* GPU: per pixel depth-tested by a draw */
  double per_write_ns;        /* GPU: per pixel written */
  double per_query_pixel_ns;  /* GPU: per pixel tested by a query box */
  double switch_ns;           /* GPU: per change between drawing and querying */
  double query_latency_ns;    /* GPU: from a query's end to its result */
  double cpu_per_call_ns;     /* CPU: issuing a draw */
  double cpu_per_query_ns;    /* CPU: issuing a query (begin, box, end) */
  double cpu_per_node_ns;     /* CPU: visiting a hierarchy node */
  double cpu_per_frustum_ns;  /* CPU: one box-frustum test */
  double cpu_per_cost_eval_ns;/* CPU: one cost-model evaluation */
} zs_clock_params;

typedef enum zs_cpu_work {
  ZS_CPU_NODE, ZS_CPU_FRUSTUM_TEST, ZS_CPU_COST_EVAL
} zs_cpu_work;

typedef struct zs_clock_stats {
  uint64_t queries;           /* queries issued this frame */
  uint64_t query_waits;       /* results asked for before they were ready */
  uint64_t stalls;            /* of those, waits that reached into the latency */
  uint64_t query_pixels;      /* pixels tested by query boxes */
  uint64_t switches;          /* changes between drawing and querying */
  int64_t sync_ps;            /* CPU waiting for queued GPU work */
  int64_t stall_ps;           /* CPU waiting for query latency */
  int64_t gpu_ps, cpu_ps;     /* the two clocks now */
  /* GPU time so far: drawing commands, query boxes, switches (the rest of
   * the frame it waited for the CPU: zs_clock_gpu_split) */
  int64_t draw_ps, query_ps, switch_ps;
} zs_clock_stats;

/* The frame so far on the GPU, in picoseconds: draw + query + switch + idle
 * = zs_device_frame_ps, idle counting the gaps and the time the CPU runs
 * on after the GPU's last command. */
typedef struct zs_gpu_split {
  int64_t draw_ps, query_ps, switch_ps, idle_ps;
} zs_gpu_split;

/* The documented defaults (clock.c). */
void zs_clock_params_default(zs_clock_params *p);
/* Returns ZS_ERR_ARG when a parameter is negative or not finite. */
zs_status zs_device_set_clock(zs_device *dev, const zs_clock_params *p,
                              zs_error *err);
void zs_device_cpu_work(zs_device *dev, zs_cpu_work kind, uint64_t count);
const zs_clock_stats *zs_device_clock(const zs_device *dev);
const zs_clock_params *zs_device_clock_params(const zs_device *dev);
/* The frame's modelled time so far: the later of the two clocks. */
int64_t zs_device_frame_ps(const zs_device *dev);
zs_gpu_split zs_clock_gpu_split(const zs_device *dev);

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
 * 2^-32.  Edges are walked one pixel per step along their major axis,
 * through the pixel the exact edge crosses at that column's (row's)
 * centre. */
enum { ZS_EDGE_DEPTH_UNITS = 1024 };
zs_status zs_device_fill_color(zs_device *dev, uint32_t rgb, zs_error *err);
/* The twelve edges of the world box lo..hi in colour rgb, over everything
 * (no depth test): for pictures of bounding volumes. */
zs_status zs_device_draw_box_lines(zs_device *dev, const double lo[3], const double hi[3],
                                   uint32_t rgb, zs_error *err);
zs_status zs_device_draw_edges(zs_device *dev, const zs_mesh *mesh,
                               const double model[16], uint32_t rgb, zs_error *err);

/* ---- depthsort.c: the painter's algorithm with frame coherence ----
 *
 * In ZS_ALGO_DEPTHSORT the faces of a frame are ordered back to front by
 * the key: the eye-space distance along the view axis of the centroid of
 * the face's vertices (ties: the higher id first, so the lower id is
 * painted last and wins, as in the z-buffer).  They are then painted in
 * that order, without a depth test: the walk gives each polygon the
 * constant depth n - 1 - rank, and its "less" test then keeps the face
 * painted last.  The depth buffer therefore holds ranks in this mode.
 *
 * Frame coherence (the depth-sort paper): each face keeps its place from
 * the previous frame.  The camera's motion between frames is classified
 * from the two view matrices:
 *   static, translation in the view plane, translation along the view
 *     axis (a dolly), roll about the view axis: depths are unchanged or
 *     shift all by the same amount, so the old order is kept as it is;
 *     only new faces are sorted and merged in (a few among many gallop
 *     to their places: O(log gap) comparisons each);
 *   slow rotation (about an axis off the view axis, under 2 degrees): the
 *     old order is nearly right: re-sorted by insertion sort with a
 *     galloping search (O(log d) comparisons for a face d places out),
 *     then the new faces merged in;
 *   fast rotation, or more than half the faces new: a full sort.
 * A kept face whose depth did not change as the camera's motion says (an
 * object that moved) is taken out and sorted in as new. */
typedef enum zs_motion_class {
  ZS_MOTION_FIRST,        /* no previous frame */
  ZS_MOTION_STATIC,
  ZS_MOTION_TRANSLATE,    /* translation in the view plane */
  ZS_MOTION_ROLL,         /* roll about the view axis (and translation) */
  ZS_MOTION_SLOW_ROTATE,  /* slow pitch / yaw */
  ZS_MOTION_FAST,         /* anything else: a full sort */
  ZS_MOTION_DOLLY         /* translation with a part along the view axis */
} zs_motion_class;

typedef struct zs_depthsort_stats {
  zs_motion_class motion;
  uint64_t faces;         /* faces ordered this frame */
  uint64_t reused;        /* kept their place from the last frame */
  uint64_t inserted;      /* new (or moved) faces sorted in */
  uint64_t comparisons;   /* key comparisons of the sort */
  int full_sort;          /* whether the whole list was sorted */
} zs_depthsort_stats;

const zs_depthsort_stats *zs_device_depthsort_stats(const zs_device *dev);
/* Wall time of the last frame's ordering, in ms (a measurement). */
double zs_device_depthsort_ms(const zs_device *dev);
/* Forget the previous frame's order: the next frame sorts from scratch. */
void zs_device_depthsort_reset(zs_device *dev);
const char *zs_motion_class_name(zs_motion_class m);

/* ---- trace: watching the scanline walk (scanline.c) ----
 *
 * For teaching, the scanline mode can report its data structures: once per
 * frame the sorted polygon and edge tables, then after each row the active
 * edge list (one pair per active polygon, as it stood for that row) and the
 * spans filled.  Coordinates are image coordinates (y down) with pixel
 * centres at whole numbers ("pixel-centre units": column c has centre
 * x = c), so the lecture's x values read directly.  Each value is given in
 * the fixed point the walk uses and in real units beside it. */
typedef struct zs_trace_poly {
  uint32_t id, rgb;
  int32_t row0, row1;    /* first and last row covered (dy = row1 - row0) */
  int32_t ox, oy;        /* plane origin pixel */
  int zshift;            /* fraction bits beyond the 32 of the depth */
  int64_t zc, dzdx, dzdy;/* fixed-point plane (raster.h, DEPTH) */
  double z0, dzx, dzy;   /* the same in window depth: z at (ox, oy), per
                            pixel right (the lecture's -a/c), per row down */
  int32_t first_edge, nleft, nright;
} zs_trace_poly;

typedef struct zs_trace_edge {
  uint32_t id;
  int side;              /* 0: left chain, 1: right chain */
  int32_t row0, row1;    /* rows covered */
  int32_t X0, Y0, X1, Y1;/* end points, 1/256 pixel, image coordinates */
  double x_top;          /* x at the centre of row0, pixel-centre units */
  double dx;             /* x per row down (the lecture's -1/k) */
} zs_trace_edge;

typedef struct zs_trace_pair {
  uint32_t id;
  int32_t dy;            /* the polygon's rows left after this one */
  int64_t xl, xr;        /* first column at or right of each edge */
  int64_t reml, dl, remr, dr;  /* edge x = xl - reml / dl (exact) */
  double xl_real, xr_real;     /* edge x at the row centre */
  double dxl, dxr;       /* per row down */
  int64_t dxl_num, dxr_num;    /* dxl = dxl_num / dl exactly, likewise dxr */
  int32_t dyl, dyr;      /* rows left on each edge after this one */
  int64_t zl;            /* fixed-point depth at (xl, y) */
  double zl_real, dzx, dzy;
  int zshift;
} zs_trace_pair;

typedef struct zs_trace_span {
  int32_t x0, x1;        /* columns, x1 inclusive, clipped to the image */
  uint32_t id;
} zs_trace_span;

typedef struct zs_trace_row {
  int y;
  const zs_trace_pair *pairs;
  int npairs;
  const zs_trace_span *spans;
  int nspans;
} zs_trace_row;

typedef struct zs_trace_observer {
  void (*tables)(void *user, const zs_trace_poly *polys, int npolys,
                 const zs_trace_edge *edges, int nedges);
  void (*row)(void *user, const zs_trace_row *row); /* before the row's sink */
  void *user;
} zs_trace_observer;

/* Watch the scanline walk of the following frames (scanline mode only);
 * NULL stops.  The observer must outlive the frames. */
void zs_device_set_trace(zs_device *dev, const zs_trace_observer *obs);

/* ---- transform.c: matrices and the camera (OpenGL conventions) ---- */
void zs_mat_identity(double m[16]);
void zs_mat_mul(double out[16], const double a[16], const double b[16]);
void zs_mat_translate(double m[16], double x, double y, double z);
void zs_mat_scale(double m[16], double x, double y, double z);
/* Rotation by deg degrees about the axis (x,y,z), right-handed. */
void zs_mat_rotate(double m[16], double deg, double x, double y, double z);
/* gluLookAt; returns 0 when eye == target or up is parallel to the view. */
int zs_mat_look_at(double m[16], const double eye[3], const double target[3],
                   const double up[3]);
/* gluPerspective: fovy in degrees, aspect = width / height. */
void zs_mat_perspective(double m[16], double fovy_deg, double aspect,
                        double znear, double zfar);
/* glOrtho. */
void zs_mat_ortho(double m[16], double left, double right, double bottom,
                  double top, double znear, double zfar);
/* out = m (p, 1): inline, as set-up calls it once or twice per vertex. */
static inline void zs_mat_apply(const double m[16], const double p[3], double out[4]) {
  for (int i = 0; i < 4; i++)
    out[i] = m[4 * i] * p[0] + m[4 * i + 1] * p[1] + m[4 * i + 2] * p[2] + m[4 * i + 3];
}

#endif
