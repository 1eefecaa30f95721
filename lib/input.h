/* zscan lib — what INPUT names on the command line. */
#ifndef ZS_LIB_INPUT_H
#define ZS_LIB_INPUT_H

#include "zscan/error.h"
#include "scene/model.h"
#include "scene/scene.h"

/* INPUT as a scene (scene/scene.h), finished and ready to draw:
 *   (none)                 the default generated scene
 *   FILE.json              a scene file (scene/load_scenefile.h)
 *   FILE.obj               one instance per object (o/g) of the file
 *   FILE.ply, .stl, ...    through assimp, likewise
 *   builtin:NAME[,k=v,..]  a generated scene (scene/generate.h): default,
 *                          teapots, spheres, city, plant, cubes
 * A model file without a face, a line or a point (empty, or vertices
 * only) is refused with "FILE: no faces, lines or points". */
zs_status zs_input_load_scene(const char *spec, zs_scene *out, zs_error *err);

/* Flags of zs_input_load (0: as zs_input_load_scene). */
enum {
  /* a model without faces loads too (its frame is the background alone) */
  ZS_INPUT_ALLOW_EMPTY = 1,
  /* a texture that cannot be opened or read is left out, and the scene's
   * notes say which (ZS_OBJ_, ZS_ASSIMP_, ZS_SCENEFILE_SKIP_MISSING_TEXTURES) */
  ZS_INPUT_SKIP_MISSING_TEXTURES = 2
};

/* The same with flags (ZS_INPUT_*). */
zs_status zs_input_load(const char *spec, int flags, zs_scene *out, zs_error *err);

#endif
