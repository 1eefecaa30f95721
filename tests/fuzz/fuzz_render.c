/* libFuzzer target: a fuzzed OBJ scene rendered in both hidden-surface
 * modes, which must agree to the byte (64 x 48, default camera). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "tests/fuzz/fuzz_obj_scene.h"
#include "lib/frame.h"

static uint64_t render(const zs_scene *s, zs_algo algo) {
  zs_camera cam;
  zs_camera_default(&cam);
  zs_frame_opts o = {.width = 64, .height = 48, .algo = algo, .shade = ZS_SHADE_ID, .threads = 1};
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
  if (render(&s, ZS_ALGO_ZBUFFER) != render(&s, ZS_ALGO_SCANLINE)) abort();
  zs_scene_free(&s);
  return 0;
}
