/* n x n x n unit cubes: one cube mesh (side 1) instanced n^3 times.  Cube
 * (i, j, k), 0 <= i, j, k < n, is instance number (i n + j) n + k, named
 * "cube_i_j_k", centred at (2i - (n-1), 2j - (n-1), 2k - (n-1)) (centres 2
 * apart, the block centred on the origin), with palette colour number mod
 * ZS_GEN_PALETTE_SIZE. */
#include "util/matrix.h"
#include "scene/gen_internal.h"

enum { CUBES_MAX = 64 }; /* n: 1 .. 64 */

static zs_status build_cubes(const zs_gen_args *a, zs_scene *s, zs_error *err) {
  int n = zs_gen_int(a, "n");
  zs_model cube;
  int32_t obj = zs_gen_model(&cube, "cube", err);
  if (obj < 0) return err->code;
  const double lo[3] = {-0.5, -0.5, -0.5}, hi[3] = {0.5, 0.5, 0.5};
  if (zs_gen_box(&cube, lo, hi, NULL, ZS_GREY, obj)) {
    zs_model_free(&cube);
    return ZS_GEN_NOMEM(err, a->spec);
  }
  int32_t mesh = zs_gen_add_mesh(s, &cube, err);
  if (mesh < 0) return err->code;

  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++)
      for (int k = 0; k < n; k++) {
        double place[16];
        zs_mat_translate(place, 2.0 * i - (n - 1), 2.0 * j - (n - 1), 2.0 * k - (n - 1));
        int number = (i * n + j) * n + k;
        uint32_t rgb = zs_gen_palette(number % ZS_GEN_PALETTE_SIZE);
        if (zs_gen_add_instance(s, mesh, place, rgb, err, "cube_%d_%d_%d", i, j, k) < 0)
          return err->code;
      }

  /* The camera: completed later from the bounds. */
  zs_camera_default(&s->camera);
  s->width = 1024;
  s->height = 768;

  /* Around the block, then into it along the gap x = 0 (n odd: x = 1)
   * between the middle layers, where the cubes hide each other, and out
   * through the far side. */
  double r = 2.0 * n + 4.0, g = (n % 2) ? 1.0 : 0.0;
  const zs_gen_key keys[] = {
      {{1.1 * r, 0.8 * r, 1.4 * r}, {0.0, 0.0, 0.0}},
      {{-1.3 * r, 0.5 * r, 1.2 * r}, {0.0, 0.0, 0.0}},
      {{-0.4 * r, 0.2 * r, 1.1 * r}, {g, g, 0.0}},
      {{g, g, 0.6 * r}, {g, g, 0.0}},
      {{g, g, 0.0}, {g, g, -r}},
      {{g, g, -0.6 * r}, {g, g, -2.0 * r}},
      {{0.8 * r, 0.9 * r, -1.2 * r}, {0.0, 0.0, 0.0}},
      {{1.1 * r, 0.8 * r, 1.4 * r}, {0.0, 0.0, 0.0}}};
  return zs_gen_path(s, keys, (int)(sizeof keys / sizeof keys[0]), zs_gen_int(a, "frames"),
                     err);
}

static const zs_gen_param cubes_params[] = {
    {"n", ZS_GEN_INT, 1, CUBES_MAX, 4}, {"frames", ZS_GEN_INT, 16, 100000, 200}};

const zs_gen_def zs_gen_cubes_def = {"cubes", cubes_params, 2, build_cubes, NULL};
