/* zscan lib — shadows for a frame: the lights that cast them, their maps
 * drawn by the same device code from each light's camera, and handed to
 * the frame's device (zscan.h, zs_shadow_map). */
#ifndef ZS_LIB_SHADOW_H
#define ZS_LIB_SHADOW_H

#include "scene/scene.h"
#include "zscan/zscan.h"

enum { ZS_SHADOW_DEFAULT_SIZE = 1024, ZS_SHADOW_MIN_SIZE = 16, ZS_SHADOW_MAX_SIZE = 8192 };

typedef struct zs_shadow_opts {
  int all;              /* every directional and spot light casts shadows,
                         * and a scene with no lights gets the key light;
                         * 0: only the lights marked shadow */
  int size;             /* each map's side; 0: ZS_SHADOW_DEFAULT_SIZE */
  double units, slope;  /* the bias (zs_shadow_map) */
} zs_shadow_opts;

/* The maps of a frame, their depths owned. */
typedef struct zs_shadow_set {
  zs_shadow_map map[ZS_MAX_SHADOW_MAPS];
  uint32_t *depth[ZS_MAX_SHADOW_MAPS];
  int n;
} zs_shadow_set;

/* Sets the frame's lights on dev: lights[0 .. n) when n > 0, else the
 * scene's, else (o->all) the key light, else the device's headlight.
 * Then, unless o is NULL, each light that casts shadows gets its map:
 * scene drawn from the light's camera over the scene's bounds
 * (zs_shadow_camera; view places eye-space lights) in zbuffer mode on
 * threads threads, into out, and set on dev.  Where only marked lights
 * cast and dev's shading shows no shadows (not auto or Phong), none are
 * drawn; o->all there is an error. */
zs_status zs_frame_lights_and_shadows(zs_device *dev, const zs_scene *scene,
                                      const zs_light *lights, int n, const zs_shadow_opts *o,
                                      const double view[16], int threads, zs_shadow_set *out,
                                      zs_error *err);

void zs_shadow_set_free(zs_shadow_set *s);

#endif
