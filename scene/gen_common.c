/* What the generators share in building a scene: colours, adding meshes
 * and instances, the ground, cameras and paths.  See gen_internal.h. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/matrix.h"
#include "scene/gen_internal.h"
#include "scene/teapot.h"

/* ---- colours ----------------------------------------------------------- */

/* Soft, distinct hues that stay apart under flat shading. */
static const uint32_t palette[ZS_GEN_PALETTE_SIZE] = {
    0xD1495Bu, /* raspberry */
    0xEDAE49u, /* saffron */
    0x00798Cu, /* teal */
    0x30638Eu, /* steel blue */
    0x66A182u, /* sage */
    0xE07A5Fu, /* terracotta */
    0x9C89B8u, /* lavender */
    0xF2CC8Fu, /* sand */
    0x3D405Bu, /* slate */
    0x81B29Au, /* mint */
    0xF0A6CAu, /* pink */
    0xB5838Du  /* dusty rose */
};

uint32_t zs_gen_palette(int i) { return palette[i]; }

/* ---- scenes ------------------------------------------------------------ */

int32_t zs_gen_add_mesh(zs_scene *s, zs_model *m, zs_error *err) {
  int32_t i = zs_scene_add_mesh(s, m);
  if (i < 0) {
    zs_model_free(m);
    ZS_GEN_NOMEM(err, "generated scene");
  }
  return i;
}

int32_t zs_gen_add_instance_v(zs_scene *s, int32_t mesh, const double model[16],
                              uint32_t rgb, zs_error *err, const char *fmt, va_list ap) {
  char name[96];
  vsnprintf(name, sizeof name, fmt, ap);
  int32_t i = zs_scene_add_instance(s, mesh, model, rgb, name);
  if (i < 0) ZS_GEN_NOMEM(err, name);
  return i;
}

int32_t zs_gen_add_instance(zs_scene *s, int32_t mesh, const double model[16],
                            uint32_t rgb, zs_error *err, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int32_t i = zs_gen_add_instance_v(s, mesh, model, rgb, err, fmt, ap);
  va_end(ap);
  return i;
}

void zs_gen_move_along_x(zs_scene *s, int32_t in, double speed) {
  zs_motion *mo = &s->inst[in].motion;
  mo->moving = 1;
  mo->axis[0] = 1.0;
  mo->axis[1] = mo->axis[2] = 0.0;
  mo->speed = speed;
}

void zs_gen_camera(zs_scene *s, const double eye[3], const double target[3],
                   double znear, double zfar) {
  zs_camera_default(&s->camera);
  memcpy(s->camera.eye, eye, sizeof s->camera.eye);
  memcpy(s->camera.target, target, sizeof s->camera.target);
  s->camera.znear = znear;
  s->camera.zfar = zfar;
  s->camera.has_eye = s->camera.has_target = 1;
  s->camera.has_near = s->camera.has_far = 1;
  s->width = 1024;
  s->height = 768;
}

static double dist3(const double a[3], const double b[3]) {
  double d2 = 0.0;
  for (int k = 0; k < 3; k++) d2 += (a[k] - b[k]) * (a[k] - b[k]);
  return sqrt(d2);
}

zs_status zs_gen_path(zs_scene *s, const zs_gen_key *keys, int nkeys, int frames,
                      zs_error *err) {
  if (nkeys < 2 || frames < nkeys)
    return zs_error_set(err, ZS_ERR_ARG, "path: %d frames for %d keys", frames, nkeys);
  for (int k = 0; k < nkeys; k++)
    for (int a = 0; a < 3; a++)
      if (!isfinite(keys[k].eye[a]) || !isfinite(keys[k].target[a]))
        return zs_error_set(err, ZS_ERR_ARG, "path: key %d is not finite", k);
  zs_keyframe *kf = calloc((size_t)nkeys, sizeof *kf);
  double *along = calloc((size_t)nkeys, sizeof *along);
  if (!kf || !along) {
    free(kf);
    free(along);
    return ZS_GEN_NOMEM(err, "path");
  }
  for (int k = 1; k < nkeys; k++)
    along[k] = along[k - 1] + dist3(keys[k].eye, keys[k - 1].eye) +
               0.25 * dist3(keys[k].target, keys[k - 1].target);
  double total = along[nkeys - 1] > 0.0 ? along[nkeys - 1] : 1.0;
  for (int k = 0; k < nkeys; k++) {
    kf[k].frame = (int32_t)floor(along[k] / total * (frames - 1) + 0.5);
    if (k > 0 && kf[k].frame <= kf[k - 1].frame) kf[k].frame = kf[k - 1].frame + 1;
  }
  /* From the end back: the last key at frames - 1, room for the others. */
  kf[nkeys - 1].frame = frames - 1;
  for (int k = nkeys - 2; k >= 0; k--)
    if (kf[k].frame >= kf[k + 1].frame) kf[k].frame = kf[k + 1].frame - 1;
  for (int k = 0; k < nkeys; k++) {
    memcpy(kf[k].eye, keys[k].eye, sizeof kf[k].eye);
    memcpy(kf[k].target, keys[k].target, sizeof kf[k].target);
    kf[k].up[0] = 0.0;
    kf[k].up[1] = 1.0;
    kf[k].up[2] = 0.0;
  }
  free(along);
  free(s->path.keys);
  s->path.keys = kf;
  s->path.nkeys = nkeys;
  s->path.frames = frames;
  return ZS_OK;
}

void zs_gen_bounds(zs_scene *s, const double lo[3], const double hi[3]) {
  memcpy(s->lo, lo, sizeof s->lo);
  memcpy(s->hi, hi, sizeof s->hi);
  s->has_bounds = 1;
}

int zs_gen_segments(double base, double detail, int min) {
  int n = (int)floor(base * detail + 0.5);
  return n < min ? min : n;
}

zs_status zs_gen_check_moving(const zs_gen_args *a, int moving, int max, const char *what,
                              zs_error *err) {
  if (moving <= max) return ZS_OK;
  return zs_error_set(err, ZS_ERR_ARG, "%s: moving: %d is more than %s (%d)", a->spec, moving, what,
                      max);
}

int32_t zs_gen_ground(zs_scene *s, const double lo[3], const double hi[3], const char *spec,
                      zs_error *err) {
  zs_model ground;
  int32_t obj = zs_gen_model(&ground, "ground", err);
  if (obj < 0) return -1;
  if (zs_gen_box(&ground, lo, hi, NULL, ZS_GEN_GROUND_RGB, obj)) {
    zs_model_free(&ground);
    ZS_GEN_NOMEM(err, spec);
    return -1;
  }
  int32_t mesh = zs_gen_add_mesh(s, &ground, err);
  if (mesh < 0) return -1;
  return zs_gen_add_instance(s, mesh, NULL, ZS_RGB_MESH, err, "ground");
}

int32_t zs_gen_teapot_mesh(zs_scene *s, int level, zs_error *err) {
  zs_model teapot;
  int32_t obj = zs_gen_model(&teapot, "teapot", err);
  if (obj < 0) return -1;
  if (zs_teapot_add(&teapot, level, NULL, ZS_GREY, obj, err)) {
    zs_model_free(&teapot);
    return -1;
  }
  return zs_gen_add_mesh(s, &teapot, err);
}
