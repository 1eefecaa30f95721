/* libFuzzer target: a fuzzed OBJ scene (its objects and groups become the
 * scene's objects) walked by every exact culling method over four cameras
 * drawn from the input, at 64 x 48; each method's image must be, to the
 * byte, that of drawing everything.  Extreme geometry is the point: specks,
 * flat and huge boxes, objects far off, the eye inside one. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cull/cull.h"
#include "cull/octree.h"
#include "util/rng.h"
#include "tests/fuzz/fuzz_obj_scene.h"

enum { W = 64, H = 48, FRAMES = 4 };

static const zs_cull_method methods[] = {
    ZS_CULL_NONE,  ZS_CULL_VFC,           ZS_CULL_HSW,           ZS_CULL_CHC,
    ZS_CULL_CHC_PROB, ZS_CULL_IDEAL,      ZS_CULL_AUTO,          ZS_CULL_CHCPP,
    ZS_CULL_CHCPP_PROB, ZS_CULL_NOHC,     ZS_CULL_IDEAL_BOX};
enum { NM = sizeof methods / sizeof methods[0] };

/* Camera f: the default view first, then eyes in or around the bounds
 * looking into them, from a PRNG seeded with the input's hash. */
static int camera(const zs_scene *s, zs_rng *rng, int f, double view[16], double proj[16]) {
  zs_camera cam;
  zs_camera_default(&cam);
  if (f > 0) {
    for (int k = 0; k < 3; k++) {
      double pad = 0.3 * (s->hi[k] - s->lo[k]);
      cam.eye[k] = zs_rng_range(rng, s->lo[k] - pad, s->hi[k] + pad);
      cam.target[k] = zs_rng_range(rng, s->lo[k], s->hi[k]);
    }
    cam.fovy = zs_rng_range(rng, 5.0, 175.0);
    cam.has_eye = cam.has_target = 1;
  }
  zs_camera_complete(&cam, s->lo, s->hi, (double)W / H);
  zs_error err;
  zs_error_clear(&err);
  return zs_camera_matrices(&cam, (double)W / H, view, proj, &err) == ZS_OK;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  zs_scene s;
  if (!fuzz_obj_scene(data, size, &s)) return 0;
  zs_error err;
  zs_error_clear(&err);
  zs_octree t;
  int have_tree = 0;
  zs_device *dev[NM] = {0};
  zs_culler *cul[NM] = {0};
  uint32_t *ref = malloc((size_t)W * H * sizeof *ref);
  if (!ref || zs_octree_build(&t, &s, NULL, &err) != ZS_OK) goto done;
  have_tree = 1;
  for (int k = 0; k < NM; k++) {
    zs_device_config cfg = {W, H, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, 1, 0, 0, 0};
    if (zs_device_create(&cfg, &dev[k], &err) != ZS_OK ||
        zs_culler_create(methods[k], NULL, &cul[k], &err) != ZS_OK)
      goto done;
  }
  uint64_t seed = 1469598103934665603u; /* FNV-1a of the input */
  for (size_t i = 0; i < size; i++) seed = (seed ^ data[i]) * 1099511628211u;
  zs_rng rng;
  zs_rng_seed(&rng, seed);
  for (int f = 0; f < FRAMES; f++) {
    double view[16], proj[16];
    if (!camera(&s, &rng, f, view, proj)) continue;
    for (int k = 0; k < NM; k++) {
      zs_cull_stats st;
      /* a method that fails (out of memory) must fail for none too */
      if (zs_culler_frame(cul[k], dev[k], &s, &t, view, proj, &st, &err) != ZS_OK ||
          zs_device_finish(dev[k], NULL, NULL, &err) != ZS_OK) {
        if (k > 0) abort();
        goto done;
      }
      const uint32_t *ids = zs_device_id_buffer(dev[k]);
      if (k == 0) memcpy(ref, ids, (size_t)W * H * sizeof *ref);
      else if (memcmp(ref, ids, (size_t)W * H * sizeof *ref) != 0) {
        int n = 0;
        for (int p = 0; p < W * H; p++) n += ids[p] != ref[p];
        fprintf(stderr, "camera %d: %s differs from none in %d pixels\n", f,
                zs_cull_method_name(methods[k]), n);
        abort();
      }
    }
  }
done:
  for (int k = 0; k < NM; k++) {
    zs_culler_destroy(cul[k]);
    zs_device_destroy(dev[k]);
  }
  if (have_tree) zs_octree_free(&t);
  zs_scene_free(&s);
  free(ref);
  return 0;
}
