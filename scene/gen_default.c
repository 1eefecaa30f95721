/* The default scene of `zscan render` as a generated scene: the teapot
 * field of zs_builtin_default, built from instances of one teapot mesh and
 * one ground box.  The layout comes from zs_builtin_teapot_field_layout, so
 * positions, turns and colours are those of the builtin; the ids are too
 * (teapot t's faces start at t * 32 level^2, the ground's after the nine).
 * The camera is left to be completed from the bounds, as for the builtin. */
#include "raster/raster.h"
#include "scene/builtin.h"
#include "scene/gen_internal.h"
#include "scene/teapot.h"

enum { FIELD = ZS_BUILTIN_TEAPOTS_SIDE * ZS_BUILTIN_TEAPOTS_SIDE };

static zs_status build_default(const zs_gen_args *a, zs_scene *s, zs_error *err) {
  int32_t teapot_mesh = zs_gen_teapot_mesh(s, zs_gen_int(a, "level"), err);
  if (teapot_mesh < 0) return err->code;

  double place[FIELD][16];
  uint32_t rgb[FIELD];
  zs_builtin_teapot_field_layout(place, rgb);
  for (int t = 0; t < FIELD; t++)
    if (zs_gen_add_instance(s, teapot_mesh, place[t], rgb[t], err, "teapot_%d", t) < 0)
      return err->code;
  double lo[3], hi[3];
  zs_builtin_ground(lo, hi);
  if (zs_gen_ground(s, lo, hi, a->spec, err) < 0) return err->code;

  /* The camera of the builtin: completed later from the bounds. */
  zs_camera_default(&s->camera);
  s->width = 1024;
  s->height = 768;

  /* Around the field at a distance, down between the teapots (each hides
   * the ones behind it), and out and up again. */
  static const zs_gen_key keys[] = {
      {{24.0, 10.0, 24.0}, {0.0, 1.0, 0.0}}, {{0.0, 7.0, 30.0}, {0.0, 1.0, 0.0}},
      {{-22.0, 4.0, 18.0}, {0.0, 1.0, 0.0}}, {{-8.0, 1.6, 4.0}, {4.0, 1.2, -4.0}},
      {{4.0, 1.6, 4.0}, {8.0, 1.2, -12.0}},  {{12.0, 1.8, -8.0}, {0.0, 1.0, -8.0}},
      {{20.0, 5.0, -20.0}, {0.0, 1.0, 0.0}}, {{30.0, 14.0, 4.0}, {0.0, 1.0, 0.0}},
      {{24.0, 10.0, 24.0}, {0.0, 1.0, 0.0}}};
  return zs_gen_path(s, keys, (int)(sizeof keys / sizeof keys[0]), zs_gen_int(a, "frames"),
                     err);
}

static const zs_gen_param default_params[] = {
    {"level", ZS_GEN_INT, 1, ZS_TEAPOT_MAX_LEVEL, ZS_BUILTIN_TEAPOT_LEVEL},
    {"frames", ZS_GEN_INT, 16, 100000, 200}};

const zs_gen_def zs_gen_default_def = {"default", default_params, 2, build_default, NULL};
