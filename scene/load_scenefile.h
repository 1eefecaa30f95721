/* zscan scene — scene files: meshes, instances, a camera, a camera path
 * and moving objects, in JSON (read with cJSON).
 *
 * EXAMPLE (scene/examples/table.json)
 *   {
 *     "description": "a teapot on a table, a gem sliding past",
 *     "meshes": [
 *       {"name": "pot", "generator": "teapot", "level": 6},
 *       {"name": "box", "generator": "box"},
 *       {"name": "gem", "file": "gem.obj"}
 *     ],
 *     "instances": [
 *       {"mesh": "box", "name": "table",
 *        "transform": {"translate": [0, -0.5, 0], "scale": [6, 1, 4]},
 *        "color": "#8b5a2b"},
 *       {"mesh": "pot", "name": "teapot",
 *        "transform": {"rotate": [30, 0, 1, 0], "scale": 0.5},
 *        "color": [0.8, 0.3, 0.2]},
 *       {"mesh": "gem", "matrix": [0.5, 0, 0, 2,  0, 0.5, 0, 0.7,
 *                                  0, 0, 0.5, 1,  0, 0, 0, 1],
 *        "motion": {"axis": [1, 0, 0], "speed": 0.1}}
 *     ],
 *     "camera": {"eye": [0, 4, 9], "target": [0, 0.5, 0], "up": [0, 1, 0],
 *                "fovy": 45, "near": 0.1, "far": 100, "size": [640, 480]},
 *     "path": {"frames": 120, "keys": [
 *       {"frame": 0, "eye": [0, 4, 9], "target": [0, 0.5, 0]},
 *       {"frame": 119, "eye": [9, 4, 0], "target": [0, 0.5, 0], "up": [0, 1, 0]}]},
 *     "bounds": {"min": [-3, -1, -2], "max": [3, 4, 2]}
 *   }
 *
 * THE TOP LEVEL (an object; every key optional unless said otherwise)
 *   description  a string, ignored.
 *   meshes       an array of meshes, each an object with a unique
 *                non-empty "name" and exactly one of
 *                  "file": a path, relative to the scene file's directory
 *                          (absolute paths are taken as they are): .obj
 *                          through scene/load_obj.h, any other extension
 *                          through assimp (scene/load_assimp.h); at most
 *                          ZS_SCENEFILE_MAX_BYTES; the file must have faces.
 *                  "generator": a mesh of scene/generate.h; the object's
 *                          other keys are its parameters, numbers or strings,
 *                          passed on in the order written:
 *                          {"name": "s", "generator": "sphere", "slices": 12}
 *                          is the spec "sphere?slices=12".
 *   instances    an array of instances (required, at least one, unless
 *                "generator" is given), each an object:
 *                  "mesh"       the name of a mesh (required);
 *                  "name"       unique among instances; default MESH_I with
 *                               I the instance's index (e.g. "pot_3");
 *                  "transform"  {"translate": [x, y, z],
 *                                "rotate": [deg, ax, ay, az] or a list of
 *                                          them, applied in the order
 *                                          written (right-handed, degrees,
 *                                          about a non-zero axis),
 *                                "scale": s or [sx, sy, sz], non-zero};
 *                               each part optional; the model matrix is
 *                               T * Rn * ... * R1 * S (scale first);
 *                  "matrix"     instead of "transform": 16 numbers, row by
 *                               row (raster.h conventions: translation in
 *                               the last column), the last row 0 0 0 1, not
 *                               singular;
 *                  "color"      [r, g, b] each 0 .. 1, or "#rrggbb": one
 *                               colour for all the instance's faces
 *                               (default: the mesh's own colours);
 *                  "motion"     {"axis": [x, y, z] (non-zero, in the
 *                               instance's local coordinates), "speed": s
 *                               (world units per frame)}: the instance moves
 *                               and bounces at the scene's bounds (scene.h).
 *   generator    instead of meshes and instances, a whole generated scene:
 *                a spec of zs_gen_scene, e.g. "teapots?count=600&seed=1".
 *                The file's camera, path and bounds, when given, replace the
 *                generated ones (camera keys one by one).
 *   camera       {"eye": [..], "target": [..], "up": [..] (non-zero, not
 *                along the view), "fovy": degrees in (0, 180), "near": > 0,
 *                "far": > near, "size": [width, height] each 1 .. 16384};
 *                what is missing is completed from the scene's bounds when
 *                a frame is drawn (scene/camera.h).
 *   path         {"frames": N (1 .. ZS_PATH_MAX_FRAMES), and exactly one of
 *                  "keys": [{"frame": F, "eye": [..], "target": [..],
 *                            "up": [..] (default: the camera's up)}, ...]
 *                          at least one key, frames 0 .. N-1 in increasing
 *                          order; the camera follows a C1 spline through
 *                          them (scene.h),
 *                  "named": "static", "translate", "roll", "yaw" or "fast"
 *                          (scene/paths.h), starting from the camera
 *                          completed from the scene's bounds at the file's
 *                          size (square without one)}.
 *   bounds       {"min": [x, y, z], "max": [x, y, z]} (min <= max): where
 *                moving instances bounce; default: the box around all
 *                instances.
 *
 * Numbers must be finite (1e999 is refused), integers whole, arrays of the
 * stated length.  Keys are case-sensitive; an unknown or repeated key is an
 * error.
 *
 * ERRORS are one line, "FILE: json.path: reason", FILE the scene file as
 * named and json.path where the offending value is:
 *   scene.json: instances[12].transform.scale: expected number or array of 3 numbers
 *   scene.json: instances[3].colour: unknown key
 *   scene.json: meshes[0].file: dir/pot.obj: cannot open: No such file or directory
 *   scene.json:4:17: invalid JSON
 * A mesh file's own error follows the path (with its own file and line).
 * Syntax errors give the line and column (in bytes, from 1) where cJSON
 * stopped.
 */
#ifndef ZS_SCENE_LOAD_SCENEFILE_H
#define ZS_SCENE_LOAD_SCENEFILE_H

#include <stddef.h>

#include "zscan/error.h"
#include "scene/scene.h"

#define ZS_SCENEFILE_MAX_BYTES (256ll << 20) /* scene and mesh files: 256 MiB */

enum { ZS_SCENEFILE_MAX_MESHES = 1 << 16, ZS_SCENEFILE_MAX_INSTANCES = 1 << 20 };

/* Reads the scene file at path into out, which is initialised here (any
 * previous content is not freed) and finished (zs_scene_finish).  Mesh files
 * are looked up relative to the directory of path.  On failure out is left
 * empty and err says why. */
zs_status zs_scenefile_load(const char *path, zs_scene *out, zs_error *err);

/* Flags of zs_scenefile_load_flags (0: the defaults). */
enum {
  /* A texture that cannot be opened or read, of a mesh file (as
   * ZS_OBJ_SKIP_MISSING_TEXTURES and ZS_ASSIMP_SKIP_MISSING_TEXTURES
   * say) or of a mesh's "material", leaves its material untextured
   * instead of failing the load, and the scene's notes say so: the
   * message the load would have failed with and ": drawn without it",
   * e.g. "scene.json: meshes[0].material.texture: dir/wood.png: cannot
   * open: No such file or directory: drawn without it", or "scene.json:
   * meshes[1].file: dir/m.mtl:4: map_Kd wood.png: cannot open: ...:
   * drawn without it".  A corrupt image is still an error. */
  ZS_SCENEFILE_SKIP_MISSING_TEXTURES = 1
};

/* zs_scenefile_load with flags (ZS_SCENEFILE_*); the plain one passes 0. */
zs_status zs_scenefile_load_flags(const char *path, int flags, zs_scene *out, zs_error *err);

/* Parses the len bytes of text (not necessarily NUL-terminated) as a scene
 * file.  name is used in messages; dir is the directory mesh files are
 * relative to ("" or NULL: the current directory).  out as for
 * zs_scenefile_load. */
zs_status zs_scenefile_parse(const char *text, size_t len, const char *name, const char *dir,
                             zs_scene *out, zs_error *err);

#endif
