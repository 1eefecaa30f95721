/* zscan scene — the Utah teapot, tessellated from Newell's Bézier patches.
 *
 * DATA
 *   Martin Newell's 1975 data set as Jim Blinn distributed it: 306 control
 *   points and 32 bicubic Bézier patches (4 rim, 8 body, 4 handle, 4 spout,
 *   8 lid, 4 bottom).  This 32-patch version has a bottom, so the pot is
 *   closed below; it is still not a closed surface: six open loops remain,
 *   the opening under the lid (inner edge of the rim), the lid's outer edge,
 *   the spout's tip and its base, and the handle's two ends (spout and handle
 *   only pierce the body, they are not stitched to it).
 *
 * PLACEMENT
 *   The data has z up; zs_teapot_add turns it to y up, (x, y, z) -> (x, z, -y),
 *   a proper rotation, so the teapot stands on the xz plane with the spout
 *   towards +x and the handle towards -x, in the data's units.  Before xform
 *   its bounds are
 *     x  -3.0 .. the spout's tip,
 *     y   0.0 .. 3.15,
 *     z  -2.0 .. 2.0,
 *   about 6.43 x 3.15 x 4.  All but the spout's tip are control points that
 *   lie on the surface (the handle's outer corner (-3, 1.8, 0); the poles of
 *   the bottom and of the lid knob; the body's widest circle, radius 2 at
 *   y = 0.9), so they are met exactly at every level.  The tip is the
 *   largest x on the lip's outer column, the cubic with control x 3.3,
 *   3.525, 3.45, 3.2, at the sampled v = j / level: 3.3 at level 1,
 *   92.6 / 27 = 3.42963 at level 6 (v = 1/3); its supremum is 3.43408 near
 *   v = 0.41.
 *
 * TESSELLATION
 *   Each patch is evaluated with the Bernstein basis in double on a grid of
 *   (level+1) x (level+1) points (parameters i/level), which become the
 *   patch's vertices, shared by its quads but not with other patches.  The
 *   level x level quads are added with zs_model_add_polygon, counter-clockwise
 *   seen from outside (front faces CCW, OpenGL).  At the poles of the lid knob
 *   and of the bottom a row of grid points coincides; the quads touching it
 *   are passed anyway (distinct indices, zero-length edge) and become
 *   triangles in effect.  Per teapot:
 *     vertices  32 * (level+1)^2   level 1: 128,   level 6: 1568
 *     faces     32 * level^2       level 1: 32,    level 6: 1152
 *   "faces" counts source faces (m->nsource_faces); zs_model may split a
 *   non-planar quad into triangles with the same face id, so m->mesh.nfaces
 *   can grow by up to twice that (with scene/model.c as written: level 1:
 *   34, level 6: 1560 mesh faces).
 */
#ifndef ZS_SCENE_TEAPOT_H
#define ZS_SCENE_TEAPOT_H

#include <stdint.h>

#include "zscan/error.h"
#include "scene/model.h"

enum {
  ZS_TEAPOT_PATCHES = 32,
  ZS_TEAPOT_CONTROL_POINTS = 306,
  ZS_TEAPOT_DEFAULT_LEVEL = 6,
  ZS_TEAPOT_MAX_LEVEL = 64  /* 32 * 65^2 = 135200 vertices */
};

/* The crease angle for the normals of the poles (model.h, compute_normals). */
#define ZS_TEAPOT_CREASE_DEG 60.0

/* Appends one teapot to m: its vertices, then its 32 * level^2 quads, patch
 * by patch in the order of the data, each in object obj (-1: none) with
 * colour rgb (0xRRGGBB).  Every vertex gets an attribute vertex: the
 * patch's normal there (du x dv, so the teapot is smooth across its
 * patches; at the poles, where a patch folds to a point, the normal of
 * the faces around it) and the patch parameters (u, v) as texture
 * coordinates.  xform places it (row-major, p' = M p, applied
 * after the z-up to y-up turn; it should be affine: its last row is
 * ignored; its linear part turns the normals, so it should be a rotation
 * times a uniform scale); NULL means identity.  Returns ZS_OK; ZS_ERR_ARG when level is
 * not in 1 .. ZS_TEAPOT_MAX_LEVEL; ZS_ERR_NOMEM, after which m may hold part
 * of the teapot (it stays valid for zs_model_free). */
zs_status zs_teapot_add(zs_model *m, int level, const double xform[16],
                        uint32_t rgb, int32_t obj, zs_error *err);

/* The control point c (0 .. 305) of the data set, z up, as published (the
 * published tables number them from 1).  For tests and tools. */
void zs_teapot_control_point(int c, double out[3]);

/* The 16 control point indices (0-based) of patch p (0 .. 31), row by row:
 * index 4 * r + s is row r (parameter v), column s (parameter u). */
void zs_teapot_patch(int p, int out[16]);

#endif
