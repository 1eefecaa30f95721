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
 *   in 24 bits and every edge product in 64.
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
  ZS_ALGO_SCANLINE  /* the whole frame at once, one row of buffers */
} zs_algo;

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
  uint64_t polygons_in;          /* faces submitted */
  uint64_t polygons_outside;     /* dropped whole: outside a clip plane */
  uint64_t polygons_clipped;     /* crossed near, far or the guard band */
  uint64_t polygons_culled_back; /* back faces, when culling is on */
  uint64_t polygons_degenerate;  /* zero area after snapping */
  uint64_t polygons_rasterized;  /* set up and walked by the scanline code */
  uint64_t spans;                /* non-empty spans filled */
  uint64_t pixels_tested;        /* fragments depth-tested */
  uint64_t pixels_written;       /* fragments that passed and were written */
} zs_raster_stats;

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
 * id id_base + face_id[f].  In zbuffer mode the faces are rasterized now; in
 * scanline mode they are set up and kept for zs_device_finish. */
zs_status zs_device_draw(zs_device *dev, const zs_mesh *mesh,
                         const double model[16], uint32_t id_base,
                         zs_error *err);

/* Ends the frame (scanline mode rasterizes it now) and hands every row to
 * sink, top to bottom.  sink may be NULL. */
zs_status zs_device_finish(zs_device *dev, zs_row_sink sink, void *user,
                           zs_error *err);

const zs_raster_stats *zs_device_stats(const zs_device *dev);

/* The full-frame buffers of zbuffer mode (NULL in scanline mode), row 0 at
 * the top, width * height entries. */
const uint32_t *zs_device_depth_buffer(const zs_device *dev);
const uint32_t *zs_device_id_buffer(const zs_device *dev);

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
void zs_mat_apply(const double m[16], const double p[3], double out[4]);

#endif
