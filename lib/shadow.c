/* Shadows for a frame (lib/shadow.h) and the light's camera of a map
 * (zscan.h, zs_shadow_camera). */
#include "lib/shadow.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/scene_draw.h"
#include "util/lights.h"
#include "util/matrix.h"

int zs_shadow_camera(const zs_light *l, const double view[16], const double lo[3],
                     const double hi[3], double light_view[16], double light_proj[16]) {
  if (l->kind != ZS_LIGHT_DIRECTIONAL && l->kind != ZS_LIGHT_SPOT) return 0;
  double dir[3], pos[3];
  if (l->eye_space) {
    /* view = [R t]: a world direction is R^T d, a world point R^T (p - t) */
    const double q[3] = {l->position[0] - view[3], l->position[1] - view[7],
                         l->position[2] - view[11]};
    for (int k = 0; k < 3; k++) {
      dir[k] = view[k] * l->direction[0] + view[4 + k] * l->direction[1] +
               view[8 + k] * l->direction[2];
      pos[k] = view[k] * q[0] + view[4 + k] * q[1] + view[8 + k] * q[2];
    }
  } else {
    memcpy(dir, l->direction, sizeof dir);
    memcpy(pos, l->position, sizeof pos);
  }
  zs_vec3_in_range(dir, dir); /* (dir:1e200,...: its square would overflow) */
  const double dlen = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  if (!(dlen > 0.0)) return 0;
  for (int k = 0; k < 3; k++) dir[k] = dir[k] / dlen;
  double c[3], h[3];
  for (int k = 0; k < 3; k++) {
    c[k] = 0.5 * (lo[k] + hi[k]);
    h[k] = 0.5 * (hi[k] - lo[k]);
  }
  double r = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
  if (!(r > 0.0)) r = 1.0;
  /* up: y, unless the light runs (nearly) along it */
  const double up[3] = {fabs(dir[1]) < 0.9 ? 0.0 : 1.0, fabs(dir[1]) < 0.9 ? 1.0 : 0.0, 0.0};
  if (l->kind == ZS_LIGHT_DIRECTIONAL) {
    const double eye[3] = {c[0] - 2.0 * r * dir[0], c[1] - 2.0 * r * dir[1],
                           c[2] - 2.0 * r * dir[2]};
    if (!zs_mat_look_at(light_view, eye, c, up)) return 0;
    zs_mat_ortho(light_proj, -r, r, -r, r, r, 3.0 * r);
    return 1;
  }
  const double target[3] = {pos[0] + dir[0], pos[1] + dir[1], pos[2] + dir[2]};
  if (!zs_mat_look_at(light_view, pos, target, up)) return 0;
  const double to[3] = {c[0] - pos[0], c[1] - pos[1], c[2] - pos[2]};
  const double d = sqrt(to[0] * to[0] + to[1] * to[1] + to[2] * to[2]);
  double zfar = d + r, znear = d - r;
  if (znear < zfar / 1024.0) znear = zfar / 1024.0; /* the light within the bounds */
  zs_mat_perspective(light_proj, 2.0 * l->outer_deg, 1.0, znear, zfar);
  return 1;
}

void zs_shadow_set_free(zs_shadow_set *s) {
  if (!s) return;
  for (int j = 0; j < s->n; j++) free(s->depth[j]);
  memset(s, 0, sizeof *s);
}

/* The depth buffer of scene drawn through (lv, lp) at size x size: the
 * map's texels, both sides of every face (a back face casts too), with
 * the frame's span fill (every level gives the same depths). */
static zs_status draw_map(const zs_scene *scene, const double lv[16], const double lp[16],
                          int size, int threads, zs_span_fill spans, uint32_t **out,
                          zs_error *err) {
  const zs_device_config cfg = {size, size, ZS_ALGO_ZBUFFER, ZS_SHADE_FLAT, 0, threads, 0, spans, 0};
  zs_device *dev = NULL;
  *out = NULL;
  zs_status st = zs_device_create(&cfg, &dev, err);
  if (st == ZS_OK) st = zs_frame_draw_all(dev, scene, lv, lp, err);
  if (st == ZS_OK) {
    const size_t bytes = (size_t)size * (size_t)size * sizeof **out;
    if (!(*out = malloc(bytes))) st = zs_error_set(err, ZS_ERR_NOMEM, "shadow map: out of memory");
    else memcpy(*out, zs_device_depth_buffer(dev), bytes);
  }
  zs_device_destroy(dev);
  return st;
}

zs_status zs_frame_lights_and_shadows(zs_device *dev, const zs_scene *scene,
                                      const zs_light *lights, int n, const zs_shadow_opts *o,
                                      const double view[16], int threads, zs_shadow_set *out,
                                      zs_error *err) {
  zs_light chosen[ZS_MAX_LIGHTS];
  int nchosen = 0;
  if (n > 0 && !lights) return zs_error_set(err, ZS_ERR_ARG, "lights: NULL with n = %d", n);
  zs_status checked = zs_lights_check(lights, n, err);
  if (checked != ZS_OK) return checked;
  if (n > 0) memcpy(chosen, lights, (size_t)(nchosen = n) * sizeof *chosen);
  else if (scene->nlights > 0)
    memcpy(chosen, scene->lights, (size_t)(nchosen = scene->nlights) * sizeof *chosen);
  else if (o && o->all) nchosen = zs_lights_key(chosen);
  if (o && o->all)
    for (int i = 0; i < nchosen; i++)
      chosen[i].shadow = chosen[i].kind == ZS_LIGHT_DIRECTIONAL || chosen[i].kind == ZS_LIGHT_SPOT;
  if (nchosen > 0) {
    zs_status st = zs_device_set_lights(dev, chosen, nchosen, err);
    if (st != ZS_OK) return st;
  }
  if (!o) return ZS_OK;
  const zs_shade shade = zs_device_config_of(dev)->shade;
  if (shade != ZS_SHADE_AUTO && shade != ZS_SHADE_PHONG) {
    if (o->all)
      return zs_error_set(err, ZS_ERR_ARG, "shadows need the Phong shading (auto or phong), "
                          "not %s", zs_shade_name(shade));
    return ZS_OK; /* marked lights, a shading that shows none */
  }
  const int size = o->size ? o->size : ZS_SHADOW_DEFAULT_SIZE;
  memset(out, 0, sizeof *out);
  for (int i = 0; i < nchosen; i++) {
    if (!chosen[i].shadow) continue;
    if (out->n == ZS_MAX_SHADOW_MAPS) {
      zs_shadow_set_free(out);
      return zs_error_set(err, ZS_ERR_LIMIT, "shadows: more than %d lights cast them",
                          ZS_MAX_SHADOW_MAPS);
    }
    zs_shadow_map *m = &out->map[out->n];
    if (!zs_shadow_camera(&chosen[i], view, scene->lo, scene->hi, m->view, m->proj)) continue;
    zs_status st = draw_map(scene, m->view, m->proj, size, threads,
                            zs_device_config_of(dev)->spans, &out->depth[out->n], err);
    if (st != ZS_OK) {
      zs_shadow_set_free(out);
      return st;
    }
    m->light = i;
    m->width = m->height = size;
    m->depth = out->depth[out->n];
    m->bias_units = o->units;
    m->bias_slope = o->slope;
    out->n++;
  }
  zs_status st = zs_device_set_shadow_maps(dev, out->map, out->n, err);
  if (st != ZS_OK) zs_shadow_set_free(out);
  return st;
}
