/* zscan scene — generated scenes.
 *
 * Every function appends to a model initialised with zs_model_init (usually
 * empty: object and face numbers below assume so).  They are deterministic:
 * the only randomness is a zs_rng seeded with ZS_BUILTIN_SEED, so the same
 * call gives the same bytes on every run.  All faces are quads,
 * counter-clockwise seen from outside (OpenGL front faces).  y is up.
 *
 * PALETTE
 *   Colours come from a fixed palette of ZS_BUILTIN_PALETTE_SIZE soft,
 *   distinct hues (zs_builtin_palette); the ground is ZS_BUILTIN_GROUND_RGB.
 *
 * DEFAULT SCENE (zs_builtin_default, what `zscan render` draws without input)
 *   A 3 x 3 field of teapots (scene/teapot.h) at level 6 and native size,
 *   centres on the ground at x, z in {-8, 0, 8}; teapot_(3 r + c) stands at
 *   x = 8 (c - 1), z = 8 (r - 1).  Each is turned about +y by a whole
 *   number of degrees in [0, 360) and has its own palette colour: the rng
 *   first shuffles the palette (Fisher-Yates) and teapot t takes entry t,
 *   then draws the nine yaw angles in teapot order.  The ground is a slab
 *   x, z in [-12, 12], y in [-0.25, 0]; the teapots stand on its top.
 *     objects   10: teapot_0 .. teapot_8 (objects 0 .. 8), then "ground" (9)
 *     vertices  9 * 1568 + 8 = 14120
 *     faces     9 * 1152 + 6 = 10374 source faces (zs_model may split
 *               non-planar teapot quads, so mesh.nfaces may be larger)
 *   Bounds: x, z in [-12, 12], y in [-0.25, 3.15].
 *
 * CUBES (zs_builtin_cubes)
 *   n x n x n axis-aligned unit cubes (side 1), centres 2 apart, the block
 *   centred on the origin: cube (i, j, k), 0 <= i, j, k < n, has its centre
 *   at (2i - (n-1), 2j - (n-1), 2k - (n-1)), is object (i n + j) n + k named
 *   "cube_i_j_k", and has palette colour ((i n + j) n + k) mod
 *   ZS_BUILTIN_PALETTE_SIZE.  Each cube has its own 8 vertices and 6 quads:
 *   n^3 objects, 8 n^3 vertices, 6 n^3 faces (n = 3: 27, 216, 162).
 */
#ifndef ZS_SCENE_BUILTIN_H
#define ZS_SCENE_BUILTIN_H

#include <stdint.h>

#include "raster/error.h"
#include "scene/model.h"

#define ZS_BUILTIN_SEED 0x7EA907u /* the default scene's rng seed */
#define ZS_BUILTIN_GROUND_RGB 0x9C968Cu /* warm grey */

enum {
  ZS_BUILTIN_PALETTE_SIZE = 12,
  ZS_BUILTIN_TEAPOTS_SIDE = 3,    /* default scene: 3 x 3 teapots */
  ZS_BUILTIN_TEAPOT_LEVEL = 6,
  ZS_BUILTIN_DEFAULT_OBJECTS = 10,
  ZS_BUILTIN_DEFAULT_VERTICES = 14120,
  ZS_BUILTIN_DEFAULT_FACES = 10374,
  ZS_BUILTIN_CUBES_MAX = 64       /* n of zs_builtin_cubes: 1 .. 64 */
};

/* Colour i (0 .. ZS_BUILTIN_PALETTE_SIZE-1) of the palette, 0xRRGGBB. */
uint32_t zs_builtin_palette(int i);

/* The default scene, see above.  Returns ZS_OK or ZS_ERR_NOMEM. */
zs_status zs_builtin_default(zs_model *m, zs_error *err);

/* The default scene with its teapots tessellated at level 1 ..
 * ZS_TEAPOT_MAX_LEVEL (the default scene is level 6): 9 * 32 level^2
 * patch quads, for benchmarks on more faces of the same picture. */
zs_status zs_builtin_teapot_field(zs_model *m, int level, zs_error *err);

/* The layout of the default scene's teapots, drawn from the rng exactly as
 * zs_builtin_teapot_field draws it: for teapot t (0 .. 8), place[t] is its
 * model matrix (the turn about +y, then the move) and rgb[t] its colour.
 * scene/gen_default.c builds the same field from instances. */
void zs_builtin_teapot_field_layout(
    double place[ZS_BUILTIN_TEAPOTS_SIDE * ZS_BUILTIN_TEAPOTS_SIDE][16],
    uint32_t rgb[ZS_BUILTIN_TEAPOTS_SIDE * ZS_BUILTIN_TEAPOTS_SIDE]);

/* The default scene's ground slab, lo .. hi. */
void zs_builtin_ground(double lo[3], double hi[3]);

/* n x n x n cubes, see above.  Returns ZS_OK; ZS_ERR_ARG when n is not in
 * 1 .. ZS_BUILTIN_CUBES_MAX; ZS_ERR_NOMEM. */
zs_status zs_builtin_cubes(zs_model *m, int n, zs_error *err);

/* An axis-aligned box from lo to hi: 8 vertices (vertex b, b = 0 .. 7, has
 * x from hi when bit 0 of b is set, else from lo; y likewise with bit 1, z
 * with bit 2) and 6 quads in the order -x, +x, -y, +y, -z, +z, all colour
 * rgb, in object obj (-1: none).  Returns ZS_OK; ZS_ERR_ARG when lo > hi on
 * some axis (or a bound is NaN), adding nothing; ZS_ERR_NOMEM.  lo == hi on
 * an axis is allowed (the faces across it have zero area). */
/* A six-sided solid from its 8 corners, numbered as the box's (corner b:
 * bit 0 the +x side, bit 1 +y, bit 2 +z), with the box's 6 quads,
 * counter-clockwise outward: right for any convex hexahedron of that shape
 * (a box with a narrower top, say). */
zs_status zs_builtin_hexahedron(zs_model *m, const double c[8][3], uint32_t rgb, int32_t obj);

zs_status zs_builtin_box(zs_model *m, const double lo[3], const double hi[3],
                         uint32_t rgb, int32_t obj);

#endif
