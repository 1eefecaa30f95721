#include "lib/input.h"

#include <string.h>

#include "scene/load_assimp.h"
#include "scene/generate.h"
#include "scene/load_obj.h"
#include "scene/load_scenefile.h"

static int has_suffix(const char *s, const char *suffix) {
  size_t n = strlen(s), k = strlen(suffix);
  if (n < k) return 0;
  for (size_t i = 0; i < k; i++) {
    char c = s[n - k + i];
    if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
    if (c != suffix[i]) return 0;
  }
  return 1;
}

zs_status zs_input_load_scene(const char *spec, zs_scene *out, zs_error *err) {
  return zs_input_load(spec, 0, out, err);
}

zs_status zs_input_load(const char *spec, int flags, zs_scene *out, zs_error *err) {
  zs_scene_init(out);
  zs_status st;
  const int skip = (flags & ZS_INPUT_SKIP_MISSING_TEXTURES) != 0;
  if (!spec) return zs_gen_scene("default", out, err);
  if (strncmp(spec, "builtin:", 8) == 0) return zs_gen_scene(spec + 8, out, err);
  if (has_suffix(spec, ".json"))
    return zs_scenefile_load_flags(spec, skip ? ZS_SCENEFILE_SKIP_MISSING_TEXTURES : 0, out, err);
  zs_model m;
  if (has_suffix(spec, ".obj"))
    st = zs_obj_load_flags(spec, skip ? ZS_OBJ_SKIP_MISSING_TEXTURES : 0, &m, err);
  else st = zs_assimp_load_flags(spec, skip ? ZS_ASSIMP_SKIP_MISSING_TEXTURES : 0, &m, err);
  if (st != ZS_OK) return st;
  if (!zs_model_drawable(&m) && !(flags & ZS_INPUT_ALLOW_EMPTY)) {
    /* an empty file, or vertices only: nothing would be drawn */
    zs_model_free(&m);
    return zs_error_set(err, ZS_ERR_PARSE, "%s: no faces, lines or points", spec);
  }
  if ((st = zs_scene_from_model(out, &m, err)) == ZS_OK) st = zs_scene_finish(out, err);
  if (st != ZS_OK) zs_scene_free(out);
  return st;
}
