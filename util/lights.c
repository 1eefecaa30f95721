/* Lights checked, and the default ones (lights.h). */
#include "util/lights.h"

#include <math.h>
#include <string.h>

static int finite3(const double v[3]) {
  return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

zs_status zs_lights_check(const zs_light *lights, int n, zs_error *err) {
  if (n < 0 || n > ZS_MAX_LIGHTS)
    return zs_error_set(err, ZS_ERR_ARG, "lights: %d lights: 0 to %d may be set", n,
                        ZS_MAX_LIGHTS);
  for (int i = 0; i < n; i++) {
    const zs_light *l = &lights[i];
    if ((unsigned)l->kind > ZS_LIGHT_AMBIENT)
      return zs_error_set(err, ZS_ERR_ARG, "lights[%d].kind: unknown kind %d", i, (int)l->kind);
    if (!finite3(l->color) || l->color[0] < 0 || l->color[1] < 0 || l->color[2] < 0)
      return zs_error_set(err, ZS_ERR_ARG, "lights[%d].color: expected finite values >= 0", i);
    if ((l->kind == ZS_LIGHT_POINT || l->kind == ZS_LIGHT_SPOT) && !finite3(l->position))
      return zs_error_set(err, ZS_ERR_ARG, "lights[%d].position: not finite", i);
    if (l->kind == ZS_LIGHT_DIRECTIONAL || l->kind == ZS_LIGHT_SPOT) {
      const double *d = l->direction;
      if (!finite3(d) || (d[0] == 0.0 && d[1] == 0.0 && d[2] == 0.0))
        return zs_error_set(err, ZS_ERR_ARG, "lights[%d].direction: expected a finite, "
                            "non-zero vector", i);
    }
    if (l->kind == ZS_LIGHT_SPOT &&
        !(l->inner_deg > 0 && l->inner_deg <= l->outer_deg && l->outer_deg < 90))
      return zs_error_set(err, ZS_ERR_ARG, "lights[%d]: a spot's angles need 0 < inner_deg <= "
                          "outer_deg < 90, got %g and %g", i, l->inner_deg, l->outer_deg);
    if (l->shadow && l->kind != ZS_LIGHT_DIRECTIONAL && l->kind != ZS_LIGHT_SPOT)
      return zs_error_set(err, ZS_ERR_ARG, "lights[%d].shadow: only directional and spot "
                          "lights cast shadows", i);
  }
  return ZS_OK;
}

int zs_lights_default(zs_light out[ZS_MAX_LIGHTS]) {
  memset(out, 0, 2 * sizeof *out);
  out[0].kind = ZS_LIGHT_DIRECTIONAL;
  out[0].color[0] = out[0].color[1] = out[0].color[2] = 0.9;
  out[0].direction[2] = -1.0;
  out[0].eye_space = 1;
  out[1].kind = ZS_LIGHT_AMBIENT;
  out[1].color[0] = out[1].color[1] = out[1].color[2] = 0.1;
  return 2;
}


int zs_lights_key(zs_light out[2]) {
  memset(out, 0, 2 * sizeof *out);
  out[0].kind = ZS_LIGHT_DIRECTIONAL;
  out[0].color[0] = out[0].color[1] = out[0].color[2] = 0.8;
  out[0].direction[0] = 1.0;
  out[0].direction[1] = -2.0;
  out[0].direction[2] = -1.0;
  out[0].eye_space = 1;
  out[0].shadow = 1;
  out[1].kind = ZS_LIGHT_AMBIENT;
  out[1].color[0] = out[1].color[1] = out[1].color[2] = 0.2;
  return 2;
}
