/* zscan scene — a scene: meshes, instances of them, a camera, a camera
 * path and moving objects.
 *
 * Meshes are zs_models (scene/model.h) held by the scene; an instance
 * places one mesh in the world with a model matrix and an optional colour
 * that replaces the mesh's face colours.  Instances are the scene's objects:
 * what the culling code puts into its octree, what `zscan query` reports,
 * what moves.
 *
 * Face ids.  Every face of every instance has a distinct id, used for the
 * depth tie-break and `--shade id`: instance i's face f has id
 *   inst[i].id_base + mesh.face_id[f]
 * where id_base is the number of source faces of all instances before it
 * (zs_scene_finish computes it).  A scene made from one OBJ file has one
 * instance per object (o/g), each with id_base 0 and the file's own face
 * numbers, so ids are the file's face numbers.
 *
 * Motion.  An instance may move along an axis of its own (local)
 * coordinates at a speed in world units per frame; when its world box would
 * leave the scene's bounds along that direction it turns back (bounces).
 * zs_scene_advance moves every moving instance by one frame; the same
 * number of calls gives the same positions to the bit on every run.
 *
 * Camera paths.  A path is a list of keyframes (eye, target, up) at frame
 * numbers; cameras between keyframes follow a Catmull-Rom spline through
 * them (eye and target; up is interpolated and re-normalised), so motion is
 * smooth and passes through every keyframe.
 */
#ifndef ZS_SCENE_SCENE_H
#define ZS_SCENE_SCENE_H

#include <stdint.h>

#include "zscan/error.h"
#include "scene/camera.h"
#include "scene/model.h"

/* ZS_RGB_MESH (raster/raster.h): an instance that keeps its mesh's colours */

typedef struct zs_motion {
  int moving;          /* 0: static */
  double axis[3];      /* direction in the instance's local coordinates */
  double speed;        /* world units per frame along the world direction */
} zs_motion;

typedef struct zs_instance {
  int32_t mesh;        /* index into zs_scene.meshes */
  double model[16];    /* local to world (raster.h conventions) */
  uint32_t rgb;        /* ZS_RGB_MESH, or one colour for all its faces */
  char *name;          /* owned */
  uint32_t id_base;    /* first face id (zs_scene_finish) */
  double lo[3], hi[3]; /* world-space bounding box (kept up to date) */
  zs_motion motion;
} zs_instance;

typedef struct zs_keyframe {
  int32_t frame;
  double eye[3], target[3], up[3];
} zs_keyframe;

typedef struct zs_path {
  zs_keyframe *keys;   /* owned, sorted by frame, frames distinct */
  int32_t nkeys;
  int32_t frames;      /* frames of the walk: 0 .. frames-1 */
} zs_path;

typedef struct zs_scene {
  zs_model *meshes;    /* owned */
  int32_t nmeshes, cap_meshes;
  zs_instance *inst;   /* owned */
  int32_t ninst, cap_inst;
  zs_camera camera;    /* as given (partial cameras are completed later) */
  int width, height;   /* image size the scene asks for, 0 if none */
  zs_path path;        /* nkeys 0: no path */
  double lo[3], hi[3]; /* the scene's bounds, for bouncing (zs_scene_finish
                          sets them to the instances' union unless given) */
  int has_bounds;
  zs_light lights[ZS_MAX_LIGHTS]; /* the scene file's lights (nlights 0: none,
                                   * the device's headlight) */
  int nlights;
  zs_notes notes;      /* of the load, its meshes' too (zs_scene_notes) */
} zs_scene;

void zs_scene_init(zs_scene *s);
void zs_scene_free(zs_scene *s);

/* Adds a mesh (moving *m into the scene, which then owns it, and its
 * notes onto the scene's; *m is left empty); returns its index or -1
 * when out of memory. */
int32_t zs_scene_add_mesh(zs_scene *s, zs_model *m);

/* Adds an instance of mesh with the model matrix (NULL: identity), colour
 * rgb (ZS_RGB_MESH to keep the mesh's), and name (copied); returns its index
 * or -1 when out of memory. */
int32_t zs_scene_add_instance(zs_scene *s, int32_t mesh, const double model[16],
                              uint32_t rgb, const char *name);

/* Computes id_base of every instance, their world boxes, and the scene
 * bounds when none were given.  Call once the scene is built. */
zs_status zs_scene_finish(zs_scene *s, zs_error *err);

/* A scene of one OBJ-style model: one instance per object of the model
 * (faces of no object form one instance named "(none)"), ids as in the
 * model, its notes the scene's.  *m is consumed (left empty). */
zs_status zs_scene_from_model(zs_scene *s, zs_model *m, zs_error *err);

/* Number of source faces (ids) of the whole scene: the sum over instances
 * of their mesh's nsource_faces. */
uint64_t zs_scene_faces(const zs_scene *s);

/* Number of triangles the scene's polygons make as fans (a face of n
 * corners, n - 2), summed over instances: what a triangle renderer is
 * sent a frame. */
uint64_t zs_scene_triangles(const zs_scene *s);

/* World box of instance i from its mesh and model matrix (exact box of the
 * transformed vertices). */
void zs_scene_instance_bounds(const zs_scene *s, int32_t i, double lo[3], double hi[3]);

/* Moves every moving instance by one frame (see Motion above). */
void zs_scene_advance(zs_scene *s);

/* The camera of frame f (0 <= f < path.frames) on the scene's path: the
 * scene's camera with eye, target and up from the path. */
void zs_path_camera(const zs_scene *s, int32_t f, zs_camera *out);

#endif
