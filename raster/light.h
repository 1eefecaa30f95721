/* zscan raster — lighting (light.c): a device's lights in eye space, and
 * Blinn-Phong at a point, in double with +, -, *, / and sqrt only, in the
 * order written here, so that each result is rounded the same way on
 * every IEEE machine (no FMA: the build passes -ffp-contract=off).
 *
 * THE FORMULA (docs/ALGORITHMS.md, "Lighting"), all colours linear:
 *   c = emissive + base * (sum of ambient lights + sum_l r_l max(0, n.l))
 *       + specular * sum_l r_l [n.l > 0] max(0, n.h)^shininess
 * n the unit normal, turned to the eye on a double-sided surface; l the
 * unit direction to the light, h = (l + v) / |l + v|, v the unit direction
 * to the eye ((0, 0, 1) under a parallel projection); r_l the light's
 * colour, over d^2 for point and spot lights, times a spot's cone factor
 * (cos a - cos outer) / (cos inner - cos outer) clamped to [0, 1].  The
 * power is taken by squaring. */
#ifndef ZS_RASTER_LIGHT_H
#define ZS_RASTER_LIGHT_H

#include "zscan/zscan.h"

/* One light in eye space, ready to evaluate. */
typedef struct zs_eye_light {
  zs_light_kind kind;
  double color[3];
  double pos[3];       /* point, spot */
  double to_light[3];  /* directional: unit, towards the light */
  double axis[3];      /* spot: unit, the way it shines */
  double cos_inner, cos_outer;
  int shadow;          /* its shadow map's index, -1: none */
} zs_eye_light;

typedef struct zs_light_set {
  zs_eye_light light[ZS_MAX_LIGHTS];
  int n;
  double ambient[3];   /* the ambient lights' sum */
  int perspective;     /* the view vector is towards the eye point (else +z) */
} zs_light_set;

/* The lights in the eye space of view; a light marked eye_space is taken
 * as it is.  maps[0 .. nmaps) are the shadow maps, by the index of the
 * light each belongs to. */
void zs_light_set_make(const zs_light *lights, int n, const double view[16], int perspective,
                       const zs_shadow_map *maps, int nmaps, zs_light_set *out);

/* What a surface reflects, linear, 0 .. 1 a channel (specular may be 0). */
typedef struct zs_reflectance {
  double emissive[3], specular[3];
  int shininess;
  int double_sided;
} zs_reflectance;

/* At eye point p with normal n (need not be unit): the light reflected by
 * a surface of linear base colour base, split in diffuse (d: emissive +
 * base times the ambient and diffuse light) and specular (s) parts, as
 * OpenGL's separate specular colour keeps them, so that a texture can
 * modulate d alone.  A normal of zero length is the direction to the eye.
 * lit, when not NULL, weights light i's r_l (a shadow's fraction, 0 .. 1);
 * NULL: every light whole. */
void zs_light_at(const zs_light_set *ls, const zs_reflectance *r, const double p[3],
                 const double n[3], const double base[3], const double *lit, double d[3],
                 double s[3]);

#endif
