/* What the OBJ-fed fuzz targets share: a fuzzed OBJ file read as a scene. */
#ifndef ZS_FUZZ_OBJ_SCENE_H
#define ZS_FUZZ_OBJ_SCENE_H

#include <stddef.h>
#include <stdint.h>

#include "scene/load_obj.h"
#include "scene/scene.h"

/* The scene of the OBJ text data[0 .. size - 1], its objects and groups as
 * its instances; 0 (with nothing to free) when the reader refuses it. */
static inline int fuzz_obj_scene(const uint8_t *data, size_t size, zs_scene *s) {
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  if (zs_obj_parse((const char *)data, size, "fuzz.obj", NULL, &m, &err) != ZS_OK) return 0;
  zs_scene_init(s);
  if (zs_scene_from_model(s, &m, &err) != ZS_OK || zs_scene_finish(s, &err) != ZS_OK) {
    zs_scene_free(s);
    return 0;
  }
  return 1;
}

#endif
