/* Lighting (light.h): the lights moved into eye space once per camera,
 * and Blinn-Phong at a point in a fixed order of correctly rounded
 * operations. */
#include "raster/light.h"

#include <math.h>
#include <string.h>

#include "util/exactmath.h"
#include "util/lights.h"
#include "util/matrix.h"

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* v / |v| into out; 0 when v has no length (out then (0, 0, 0)); a v far
 * out of range is scaled first (zs_vec3_in_range). */
static int unit3(const double v_in[3], double out[3]) {
  double v[3];
  zs_vec3_in_range(v_in, v);
  const double len = sqrt(dot3(v, v));
  if (!(len > 0.0)) {
    out[0] = out[1] = out[2] = 0.0;
    return 0;
  }
  for (int k = 0; k < 3; k++) out[k] = v[k] / len;
  return 1;
}

/* The direction d (a vector: w = 0) in eye space. */
static void eye_dir(const double view[16], const double d[3], double out[3]) {
  for (int r = 0; r < 3; r++)
    out[r] = view[4 * r] * d[0] + view[4 * r + 1] * d[1] + view[4 * r + 2] * d[2];
}

void zs_light_set_make(const zs_light *lights, int n, const double view[16], int perspective,
                       const zs_shadow_map *maps, int nmaps, zs_light_set *out) {
  memset(out, 0, sizeof *out);
  out->perspective = perspective;
  for (int i = 0; i < n; i++) {
    const zs_light *l = &lights[i];
    if (l->kind == ZS_LIGHT_AMBIENT) {
      for (int k = 0; k < 3; k++) out->ambient[k] += l->color[k];
      continue;
    }
    zs_eye_light *e = &out->light[out->n++];
    e->kind = l->kind;
    e->shadow = -1;
    for (int j = 0; j < nmaps; j++)
      if (maps[j].light == i) e->shadow = j;
    memcpy(e->color, l->color, sizeof e->color);
    double dir[3], pos4[4];
    if (l->eye_space) {
      memcpy(dir, l->direction, sizeof dir);
      memcpy(e->pos, l->position, sizeof e->pos);
    } else {
      eye_dir(view, l->direction, dir);
      zs_mat_apply(view, l->position, pos4);
      memcpy(e->pos, pos4, sizeof e->pos);
    }
    double axis[3];
    unit3(dir, axis);
    memcpy(e->axis, axis, sizeof axis);
    for (int k = 0; k < 3; k++) e->to_light[k] = -axis[k];
    if (l->kind == ZS_LIGHT_SPOT) {
      double s;
      zs_sincos_deg(l->inner_deg, &s, &e->cos_inner);
      zs_sincos_deg(l->outer_deg, &s, &e->cos_outer);
    }
  }
}

/* x^k for an integer k >= 0, by squaring (k's bits from the lowest). */
static double power(double x, int k) {
  double r = 1.0;
  while (k > 0) {
    if (k & 1) r *= x;
    x *= x;
    k >>= 1;
  }
  return r;
}

void zs_light_at(const zs_light_set *ls, const zs_reflectance *r, const double p[3],
                 const double n_in[3], const double base[3], const double *lit, double d[3],
                 double s[3]) {
  double v[3], n[3];
  if (ls->perspective) {
    const double to_eye[3] = {-p[0], -p[1], -p[2]};
    if (!unit3(to_eye, v)) v[0] = v[1] = 0.0, v[2] = 1.0;
  } else {
    v[0] = v[1] = 0.0, v[2] = 1.0;
  }
  if (!unit3(n_in, n)) memcpy(n, v, sizeof n);
  if (r->double_sided && dot3(n, v) < 0.0)
    for (int k = 0; k < 3; k++) n[k] = -n[k];
  double diffuse[3] = {ls->ambient[0], ls->ambient[1], ls->ambient[2]};
  double spec[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < ls->n; i++) {
    const zs_eye_light *e = &ls->light[i];
    double l[3], radiance[3] = {e->color[0], e->color[1], e->color[2]};
    if (e->kind == ZS_LIGHT_DIRECTIONAL) {
      memcpy(l, e->to_light, sizeof l);
    } else {
      const double to[3] = {e->pos[0] - p[0], e->pos[1] - p[1], e->pos[2] - p[2]};
      const double d2 = dot3(to, to);
      if (!unit3(to, l)) continue;
      double f = 1.0 / d2;
      if (e->kind == ZS_LIGHT_SPOT) {
        const double c = -dot3(l, e->axis);
        double cone = (c - e->cos_outer) / (e->cos_inner - e->cos_outer);
        if (!(cone > 0.0)) continue;
        if (cone > 1.0) cone = 1.0;
        f = f * cone;
      }
      for (int k = 0; k < 3; k++) radiance[k] = radiance[k] * f;
    }
    if (lit) {
      if (!(lit[i] > 0.0)) continue;
      for (int k = 0; k < 3; k++) radiance[k] = radiance[k] * lit[i];
    }
    const double ndl = dot3(n, l);
    if (!(ndl > 0.0)) continue;
    for (int k = 0; k < 3; k++) diffuse[k] += radiance[k] * ndl;
    if (r->shininess > 0) {
      const double hv[3] = {l[0] + v[0], l[1] + v[1], l[2] + v[2]};
      double h[3];
      if (!unit3(hv, h)) continue;
      const double ndh = dot3(n, h);
      if (!(ndh > 0.0)) continue;
      const double pw = power(ndh, r->shininess);
      for (int k = 0; k < 3; k++) spec[k] += radiance[k] * pw;
    }
  }
  for (int k = 0; k < 3; k++) {
    d[k] = r->emissive[k] + base[k] * diffuse[k];
    s[k] = r->specular[k] * spec[k];
  }
}
