/* zscan scene — generated meshes and generated scenes.
 *
 * SPECS
 *   A generated thing is named by a spec "NAME" or "NAME,key=value,key=value"
 *   (on the command line behind "builtin:", e.g. builtin:teapots,count=600;
 *   the prefix is accepted here too).  "NAME?key=value&key=value" is the
 *   same spec, in the form of a URL query; the commas need no quoting in a
 *   shell.  Values are strict: a whole number is
 *   digits with an optional '-', a real is a plain decimal number (no hex,
 *   no inf or nan, no spaces), a key may be given once.  Errors name the
 *   spec and the key, e.g.
 *     teapots?count=x: count: expected a whole number, got 'x'
 *     teapots?count=7000: count: 7000 is outside 1 .. 6000
 *     teapots?colour=red: unknown parameter 'colour' (count, level, moving, seed, frames)
 *     x: unknown generated scene 'x' (teapots, spheres, city, plant, cubes, default)
 *
 * DETERMINISM
 *   Every random choice draws from one zs_rng (util/rng.h) seeded with
 *   the spec's seed (default ZS_GEN_DEFAULT_SEED), and every angle goes
 *   through zs_sincos_turns (util/exactmath.h), from + - * / only: the
 *   same spec gives the same bytes (vertices, matrices, colours, path keys)
 *   on every run, compiler, optimisation level and C library.
 *   Two draws never share one expression: C leaves the order in which a
 *   call's arguments are evaluated open, and gcc and clang differ.
 *
 * COMMON PARAMETERS
 *   seed    0 .. 2^64 - 1, default 1 (ZS_GEN_DEFAULT_SEED)
 *   frames  the length of the fly-through path (zs_path), 16 .. 100000
 *           (plant: 32 ..); keys are spread over it by distance travelled
 *   moving  how many objects move (the first ones), where there is motion
 *
 * MESHES (zs_gen_mesh): one model, one object named after the mesh, grey.
 *   Closed (but for the teapot, open by its data, and a cylinder without
 *   caps), shared vertices, faces counter-clockwise seen from outside
 *   (OpenGL front faces).  y is up.
 *     teapot?level=6                 Utah teapot (scene/teapot.h), standing
 *                                    on y = 0; level 1 .. 64
 *     sphere?slices=24&stacks=24     radius 1 at the origin; slices x stacks
 *                                    faces (24 x 24 = 576: the paper's
 *                                    sphere), the pole rows are triangles
 *     box?x=1&y=1&z=1                sides x, y, z, centred on the origin
 *     cube?size=1                    the same with equal sides
 *     cylinder?segments=16&caps=1&radius=1&height=2
 *                                    axis y, centred on the origin; caps=0
 *                                    leaves it open (not closed)
 *     cone?segments=16&caps=1&radius=1&height=2
 *                                    base at y = -height/2, apex above
 *     torus?major=1&minor=0.25&segments=32&sides=16
 *                                    around the y axis, centred on the origin
 *   A cap is one polygon when it has at most ZS_MAX_POLY_VERTS corners,
 *   else a fan of triangles around a centre vertex.
 *
 * SCENES (zs_gen_scene): meshes shared by instances (one instance = one
 *   object), a camera for 1024 x 768, bounds, a fly-through path and, for
 *   spheres (and teapots and city cars when asked), moving objects.  Counts
 *   below are objects / faces (source faces, the ids) / triangles (a face
 *   of n corners counts n - 2), exact at the default seed; the tests
 *   (tests/test_generate.c) check them and a hash of every byte.
 *   Generation is quick next to rendering (`zscan render builtin:NAME
 *   --stats` reports it as ms_load).  Each generator's file tells its
 *   layout and the order of its random draws.
 *
 *   teapots?count=600&level=4&moving=0&seed=1&frames=300   (scene/gen_teapots.c)
 *     The CHC paper's Teapot scene: ONE teapot mesh (32 level^2 faces;
 *     level 4: 512 faces, 1,024 triangles, every curved quad split in two)
 *     instanced count (1 .. 6000) times, and a ground slab.  Seven in eight
 *     teapots stand in columns of 4 .. 12 in uniformly random poses, on a
 *     grid of cells about three teapots apart with a quarter of the cells
 *     empty; the rest sit upright on the ground between the columns.
 *     Random palette colours.  moving = N: the first N move along their
 *     local x axis.  View and path: from the side (open: most columns in
 *     sight), into the field between two rows of columns (seen through
 *     gaps and handles), above it, down across it.
 *       count 600:   601 objects,   307,206 faces,   614,412 triangles
 *       count 6000: 6,001 objects, 3,072,006 faces, 6,144,012 triangles
 *
 *   spheres?count=5000&moving=COUNT&slices=24&stacks=24&seed=1&frames=300
 *     The CHC paper's experiment 1 (scene/gen_spheres.c): count (1 .. 5000)
 *     spheres of slices x stacks faces (576), radius 8 .. 16, inside the
 *     1,000-unit cube [0, 1000]^3 (the scene's bounds), random
 *     orientations; the first `moving` (default all) move along their local
 *     x axis at 0.5 .. 2.5 units a frame and bounce off the cube's walls.
 *     The path circles the cube and flies through the cloud.
 *       count 5000: 5,000 objects, 2,880,000 faces, 5,520,000 triangles
 *
 *   city?blocks=2&moving=0&seed=1&frames=400   (scene/gen_city.c)
 *     The conservative-culling paper's city: blocks x blocks (1 .. 8) city
 *     blocks of four buildings each (3 .. 12 floors, window boxes, roof
 *     structures), 2 blocks^2 cars, one "streets" object (road, pavements,
 *     lane marks, street lights).  moving = N: the first N cars drive.  The
 *     camera stands in a street; the path walks the streets at eye height
 *     (open views along streets, closed ones at the corners), then rises.
 *       blocks 2: 25 objects, 11,470 faces, 23,596 triangles (23,419 on
 *                 average over seeds 1 .. 200; the paper: 25, 23,400)
 *       blocks 8: 385 objects, 184,462 faces, 379,660 triangles
 *
 *   plant?detail=0.25&seed=1&frames=400   (scene/gen_plant.c)
 *     A stand-in for UNC's Powerplant (1,185 objects, 12.7 M triangles): a
 *     walled power-station hall in three bays (four boilers with platforms;
 *     two turbine sets under a crane; an auxiliary bay with two decks of
 *     pumps, tanks and exchangers, stairs and railings), pipe runs with
 *     elbows, flanges with bolts, and valves between the equipment; outside
 *     a stack, two cooling towers, a tank farm over a pipe rack,
 *     transformers.  The same objects at every detail (0.05 .. 1), which
 *     scales the tessellation; detail = 1 is the full size.  Other seeds
 *     give 1,109 .. 1,223 objects (mean 1,174 over seeds 1 .. 50).  The path
 *     comes in from outside (open), through the halls (heavy occlusion:
 *     walls, decks, equipment), up the stairs, out along the pipe rack, and
 *     up to look back.
 *       detail 0.25: 1,223 objects,   201,738 faces,   425,668 triangles
 *       detail 1:    1,223 objects, 1,998,586 faces, 4,072,508 triangles
 *
 *   cubes?n=4&frames=200   (scene/gen_cubes.c)
 *     n x n x n unit cubes (1 .. 64), centres 2 apart, the block centred on
 *     the origin: one cube mesh instanced n^3 times.  The path circles the
 *     block and flies through it along a gap.
 *       n 4: 64 objects, 384 faces, 768 triangles
 *
 *   default?level=6&frames=200   (scene/gen_default.c)
 *     The default scene of `zscan render`: nine teapots in a 3 x 3 field
 *     and a ground slab, as instances of one teapot mesh and one box.  Its
 *     camera is left to be framed from the bounds.
 *       10 objects, 10,374 faces, 20,748 triangles
 */
#ifndef ZS_SCENE_GENERATE_H
#define ZS_SCENE_GENERATE_H

#include <stdint.h>

#include "zscan/error.h"
#include "scene/model.h"
#include "scene/scene.h"

#define ZS_GEN_DEFAULT_SEED 1u /* the seed of a spec without seed= */

enum {
  ZS_GEN_SPEC_MAX = 1024,    /* longest spec accepted, in bytes */
  ZS_GEN_TEAPOTS_MAX = 6000,
  ZS_GEN_SPHERES_MAX = 5000
};

/* One mesh from a spec (see MESHES above) into *out, which is initialised
 * here; on failure *out is left empty. */
zs_status zs_gen_mesh(const char *spec, zs_model *out, zs_error *err);

/* One scene from a spec (see SCENES above) into *out, which is initialised
 * here and finished (zs_scene_finish); on failure *out is left empty. */
zs_status zs_gen_scene(const char *spec, zs_scene *out, zs_error *err);

/* Counts of a scene, over its instances. */
typedef struct zs_gen_counts {
  int64_t objects;    /* instances */
  int64_t faces;      /* source faces (ids), zs_scene_faces */
  int64_t triangles;  /* sum over mesh faces of (corners - 2) */
  int64_t vertices;   /* sum over instances of their mesh's vertices */
} zs_gen_counts;

void zs_gen_count(const zs_scene *s, zs_gen_counts *out);

/* ---- primitives (scene/gen_mesh.c) -------------------------------------
 * Each appends to m, colour rgb, object obj (-1: none), every vertex
 * placed by xform (NULL: identity; affine with a positive determinant, so
 * the winding stays counter-clockwise outside).  Closed, vertices shared
 * between faces.  Return ZS_OK, ZS_ERR_ARG (a count or size out of range),
 * ZS_ERR_NOMEM. */

/* A six-sided solid from its 8 corners: corner b (b = 0 .. 7) is on the
 * +x side when bit 0 of b is set, +y with bit 1, +z with bit 2; 6 quads in
 * the order -x, +x, -y, +y, -z, +z, counter-clockwise outward (right for
 * any convex hexahedron of that shape: a box with a narrower top, say). */
zs_status zs_gen_hexahedron(zs_model *m, const double c[8][3], uint32_t rgb, int32_t obj);

/* The box lo .. hi: a hexahedron of 8 vertices and 6 quads.  ZS_ERR_ARG,
 * adding nothing, when lo > hi on some axis (or a bound is NaN); lo == hi
 * on an axis is allowed (the faces across it have zero area). */
zs_status zs_gen_box(zs_model *m, const double lo[3], const double hi[3],
                     const double xform[16], uint32_t rgb, int32_t obj);

/* A solid of revolution about the y axis: the profile is n points (r, y),
 * r >= 0, listed so that the solid lies to the left of the direction of
 * travel in the (r, y) plane (for a convex solid: from the bottom up).  A
 * point with r = 0 becomes one vertex on the axis (a pole), others a ring of
 * `segments` vertices.  With caps, an end of the profile off the axis is
 * closed by a cap.  A profile whose last point repeats its first (all
 * r > 0) is a closed loop: the solid is ring-shaped (a hollow shell), the
 * last ring is the first, and there are no caps.  Rings are at angles k /
 * segments turns from +x towards -z.  Faces: segments per profile step,
 * plus the caps. */
zs_status zs_gen_lathe(zs_model *m, const double *profile, int n, int segments,
                       int caps, const double xform[16], uint32_t rgb, int32_t obj);

/* The crease angle of the smooth generated surfaces' normals (the
 * sphere's; model.h, zs_model_compute_normals). */
#define ZS_GEN_SMOOTH_CREASE_DEG 60.0

/* The unit sphere: a lathe of stacks + 1 points, slices x stacks faces. */
zs_status zs_gen_sphere(zs_model *m, int slices, int stacks,
                        const double xform[16], uint32_t rgb, int32_t obj);

/* A cylinder (or cone frustum) on the y axis from y = 0, radius r0, to
 * y = 1, radius r1 (r1 = 0: a cone). */
zs_status zs_gen_cylinder(zs_model *m, double r0, double r1, int segments,
                          int caps, const double xform[16], uint32_t rgb,
                          int32_t obj);

/* A tube of radius minor swept along a circular arc of radius major by
 * sweep turns (0 < sweep <= 1).  The arc starts at the origin heading +y
 * and bends towards +x about the centre (major, 0, 0): a quarter turn is a
 * pipe elbow from +y into +x ending at (major, major, 0).  sweep = 1 is a
 * whole torus (no caps); otherwise caps close the two ends.  segments
 * steps along the arc, sides around the tube. */
zs_status zs_gen_torus(zs_model *m, double major, double minor, double sweep,
                       int segments, int sides, int caps,
                       const double xform[16], uint32_t rgb, int32_t obj);

#endif
