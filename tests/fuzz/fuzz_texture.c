/* libFuzzer target: the texture decoders (libpng, libjpeg-turbo) and the
 * mip chain on arbitrary bytes, told apart by their signatures as a
 * model's textures are.  Any input must give a texture of sides 1 to
 * ZS_MAX_TEXTURE_SIDE whose levels halve down to 1 x 1, or an error with
 * a one-line message and no texture; never a crash, a leak or undefined
 * behaviour.  A
 * texture decoded is then sampled: a quad drawn with it, unlit, at each
 * filter, reads its levels through the sampler.  (The seeds:
 * tests/data/textures, good and broken images.) */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "scene/texture_file.h"
#include "zscan/zscan.h"

enum { SIDE = 24 };

static void no_row(void *user, const zs_row *row) {
  (void)user;
  (void)row;
}

/* A quad over most of a small frame, receding, so that its pixels take
 * several levels; drawn with tex at filter f. */
static void draw_with(zs_texture *tex, zs_filter f) {
  static const double pos[12] = {-0.9, -0.9, -1.0, 0.9,  -0.9, -1.0,
                                 0.6,  0.9,  -6.0, -0.6, 0.9,  -6.0};
  static const float uv[8] = {-0.5f, 0.0f, 3.0f, 0.0f, 3.0f, 5.0f, -0.5f, 5.0f};
  int32_t start[2] = {0, 4}, vert[4] = {0, 1, 2, 3}, id[1] = {0};
  uint32_t rgb[1] = {0};
  zs_material mat = zs_material_default();
  mat.base_texture = tex;
  mat.filter = f;
  mat.wrap_s = ZS_WRAP_MIRROR;
  zs_mesh m = {.pos = (double *)pos,
               .nverts = 4,
               .face_start = start,
               .face_vert = vert,
               .nfaces = 1,
               .face_rgb = rgb,
               .face_id = id,
               .nattrs = 4,
               .uv = (float *)uv,
               .materials = &mat,
               .nmaterials = 1};
  zs_device_config cfg = {SIDE, SIDE, ZS_ALGO_ZBUFFER, ZS_SHADE_UNLIT, 0, 1, 0, 0, 0};
  zs_device *d = NULL;
  zs_error err;
  zs_error_clear(&err);
  if (zs_device_create(&cfg, &d, &err)) abort();
  static const double view[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  static const double proj[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1.2, -2.2, 0, 0, -1, 0};
  zs_device_set_camera(d, view, proj);
  if (zs_device_draw(d, &m, NULL, 0, ZS_RGB_MESH, &err) || zs_device_finish(d, no_row, NULL, &err))
    abort(); /* a texture decoded is always drawable */
  zs_device_destroy(d);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  zs_texture *tex = NULL;
  zs_error err;
  zs_error_clear(&err);
  if (zs_texture_decode(data, size, "fuzz", &tex, &err) != ZS_OK) {
    if (tex || strchr(err.msg, '\n') || err.msg[0] == '\0') abort();
    return 0;
  }
  int w = zs_texture_width(tex), h = zs_texture_height(tex);
  if (w < 1 || h < 1 || w > ZS_MAX_TEXTURE_SIDE || h > ZS_MAX_TEXTURE_SIDE) abort();
  const int levels = zs_texture_levels(tex);
  for (int k = 0; k < levels; k++) {
    int lw, lh;
    const uint8_t *t = zs_texture_level(tex, k, &lw, &lh);
    if (!t || lw != w || lh != h) abort();
    /* the level's first and last texels are there (ASan reads them) */
    volatile uint8_t sink = (uint8_t)(t[0] ^ t[4 * (size_t)lw * (size_t)lh - 1]);
    (void)sink;
    w = w > 1 ? w / 2 : 1;
    h = h > 1 ? h / 2 : 1;
  }
  if (w != 1 || h != 1) abort(); /* (the loop halved past the last level) */
  for (zs_filter f = ZS_FILTER_NEAREST; f <= ZS_FILTER_TRILINEAR; f++) draw_with(tex, f);
  zs_texture_destroy(tex);
  return 0;
}
