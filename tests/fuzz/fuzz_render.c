/* libFuzzer target: a fuzzed OBJ scene rendered in both hidden-surface
 * modes, which must agree to the byte (64 x 48, default camera).  Lines
 * and points are drawn by the z-buffer mode alone (the scanline mode
 * refuses them), so a scene with them is held to another promise: the
 * same bytes on one thread and on two. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "tests/fuzz/fuzz_obj_scene.h"
#include "lib/frame.h"
#include "lib/scene_draw.h"

static uint64_t render(const zs_scene *s, zs_algo algo, int threads) {
  zs_camera cam;
  zs_camera_default(&cam);
  zs_frame_opts o = {.width = 64, .height = 48, .algo = algo, .shade = ZS_SHADE_ID, .threads = threads};
  zs_image im;
  zs_error err;
  zs_error_clear(&err);
  if (zs_frame_render(s, &cam, &o, &im, NULL, NULL, &err) != ZS_OK) return 0;
  uint64_t h = zs_image_hash(&im);
  zs_image_free(&im);
  return h;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  zs_scene s;
  if (!fuzz_obj_scene(data, size, &s)) return 0;
  const uint64_t one = render(&s, ZS_ALGO_ZBUFFER, 1);
  if (zs_scene_has_prims(&s) ? one != render(&s, ZS_ALGO_ZBUFFER, 2)
                             : one != render(&s, ZS_ALGO_SCANLINE, 1))
    abort();
  zs_scene_free(&s);
  return 0;
}
