/* Generated scenes: the default teapot field, a block of cubes, boxes.  See
 * builtin.h for the layouts and the counts. */
#include "scene/builtin.h"

#include <stdio.h>

#include "raster/raster.h"
#include "raster/rng.h"
#include "scene/teapot.h"

/* Soft, distinct hues that stay apart under flat shading. */
static const uint32_t palette[ZS_BUILTIN_PALETTE_SIZE] = {
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

/* The default scene gives every teapot its own palette entry. */
_Static_assert(ZS_BUILTIN_TEAPOTS_SIDE * ZS_BUILTIN_TEAPOTS_SIDE <=
                   ZS_BUILTIN_PALETTE_SIZE,
               "more teapots than colours");

uint32_t zs_builtin_palette(int i) { return palette[i]; }

zs_status zs_builtin_hexahedron(zs_model *m, const double c[8][3], uint32_t rgb, int32_t obj) {
  int32_t first = m->mesh.nverts;
  for (int b = 0; b < 8; b++)
    if (zs_model_add_vertex(m, c[b][0], c[b][1], c[b][2]) < 0) return ZS_ERR_NOMEM;
  /* Corner b: bit 0 the +x side, bit 1 +y, bit 2 +z.  Each quad runs
   * counter-clockwise seen from outside, e.g. -x: 0 -> 4 is +z, 4 -> 6 is
   * +y, and z x y = -x. */
  static const int quads[6][4] = {
      {0, 4, 6, 2}, /* -x */
      {1, 3, 7, 5}, /* +x */
      {0, 1, 5, 4}, /* -y */
      {2, 6, 7, 3}, /* +y */
      {0, 2, 3, 1}, /* -z */
      {4, 5, 7, 6}  /* +z */
  };
  for (int f = 0; f < 6; f++) {
    int32_t idx[4];
    for (int k = 0; k < 4; k++) idx[k] = first + quads[f][k];
    zs_status st = zs_model_add_polygon(m, idx, 4, rgb, obj);
    if (st != ZS_OK) return st;
  }
  return ZS_OK;
}

zs_status zs_builtin_box(zs_model *m, const double lo[3], const double hi[3],
                         uint32_t rgb, int32_t obj) {
  for (int a = 0; a < 3; a++)
    if (!(lo[a] <= hi[a])) return ZS_ERR_ARG;
  double c[8][3];
  for (int b = 0; b < 8; b++) {
    c[b][0] = (b & 1) ? hi[0] : lo[0];
    c[b][1] = (b & 2) ? hi[1] : lo[1];
    c[b][2] = (b & 4) ? hi[2] : lo[2];
  }
  return zs_builtin_hexahedron(m, c, rgb, obj);
}

zs_status zs_builtin_cubes(zs_model *m, int n, zs_error *err) {
  if (n < 1 || n > ZS_BUILTIN_CUBES_MAX)
    return zs_error_set(err, ZS_ERR_ARG, "cubes: n = %d is not in 1 .. %d",
                        n, (int)ZS_BUILTIN_CUBES_MAX);
  for (int i = 0; i < n; i++) {
    for (int j = 0; j < n; j++) {
      for (int k = 0; k < n; k++) {
        char name[64];
        snprintf(name, sizeof name, "cube_%d_%d_%d", i, j, k);
        int32_t obj = zs_model_object(m, name);
        if (obj < 0)
          return zs_error_set(err, ZS_ERR_NOMEM, "cubes: out of memory");
        /* Centres 2 apart, the block centred on the origin. */
        double c[3] = {2.0 * i - (n - 1), 2.0 * j - (n - 1),
                       2.0 * k - (n - 1)};
        double lo[3], hi[3];
        for (int a = 0; a < 3; a++) {
          lo[a] = c[a] - 0.5;
          hi[a] = c[a] + 0.5;
        }
        int number = (i * n + j) * n + k;
        zs_status st = zs_builtin_box(
            m, lo, hi, palette[number % ZS_BUILTIN_PALETTE_SIZE], obj);
        if (st != ZS_OK)
          return zs_error_set(err, st, "cubes: cannot add cube %s", name);
      }
    }
  }
  return ZS_OK;
}

void zs_builtin_teapot_field_layout(
    double place[ZS_BUILTIN_TEAPOTS_SIDE * ZS_BUILTIN_TEAPOTS_SIDE][16],
    uint32_t rgb[ZS_BUILTIN_TEAPOTS_SIDE * ZS_BUILTIN_TEAPOTS_SIDE]) {
  const int side = ZS_BUILTIN_TEAPOTS_SIDE;
  const int count = side * side;
  const double spacing = 8.0;

  zs_rng rng;
  zs_rng_seed(&rng, ZS_BUILTIN_SEED);

  /* A Fisher-Yates shuffle of the palette: teapot t takes entry t, so no two
   * teapots share a colour. */
  uint32_t colours[ZS_BUILTIN_PALETTE_SIZE];
  for (int i = 0; i < ZS_BUILTIN_PALETTE_SIZE; i++) colours[i] = palette[i];
  zs_rng_shuffle(&rng, colours, ZS_BUILTIN_PALETTE_SIZE, sizeof colours[0]);

  for (int t = 0; t < count; t++) {
    int row = t / side, col = t % side;
    /* Whole degrees: a short, exact record of the angle. */
    double yaw = (double)zs_rng_below(&rng, 360);
    double rot[16], move[16];
    zs_mat_rotate(rot, yaw, 0.0, 1.0, 0.0);
    zs_mat_translate(move, spacing * (col - (side - 1) / 2.0), 0.0,
                     spacing * (row - (side - 1) / 2.0));
    zs_mat_mul(place[t], move, rot); /* turn first, then move */
    rgb[t] = colours[t];
  }
}

void zs_builtin_ground(double lo[3], double hi[3]) {
  static const double ground_lo[3] = {-12.0, -0.25, -12.0};
  static const double ground_hi[3] = {12.0, 0.0, 12.0};
  for (int a = 0; a < 3; a++) {
    lo[a] = ground_lo[a];
    hi[a] = ground_hi[a];
  }
}

zs_status zs_builtin_teapot_field(zs_model *m, int level, zs_error *err) {
  const int count = ZS_BUILTIN_TEAPOTS_SIDE * ZS_BUILTIN_TEAPOTS_SIDE;
  double place[ZS_BUILTIN_TEAPOTS_SIDE * ZS_BUILTIN_TEAPOTS_SIDE][16];
  uint32_t colours[ZS_BUILTIN_TEAPOTS_SIDE * ZS_BUILTIN_TEAPOTS_SIDE];
  zs_builtin_teapot_field_layout(place, colours);

  for (int t = 0; t < count; t++) {
    char name[32];
    snprintf(name, sizeof name, "teapot_%d", t);
    int32_t obj = zs_model_object(m, name);
    if (obj < 0)
      return zs_error_set(err, ZS_ERR_NOMEM, "default scene: out of memory");
    zs_status st = zs_teapot_add(m, level, place[t], colours[t], obj, err);
    if (st != ZS_OK) return st;
  }

  int32_t ground = zs_model_object(m, "ground");
  if (ground < 0)
    return zs_error_set(err, ZS_ERR_NOMEM, "default scene: out of memory");
  double lo[3], hi[3];
  zs_builtin_ground(lo, hi);
  zs_status st = zs_builtin_box(m, lo, hi, ZS_BUILTIN_GROUND_RGB, ground);
  if (st != ZS_OK)
    return zs_error_set(err, st, "default scene: cannot add the ground");
  return ZS_OK;
}

zs_status zs_builtin_default(zs_model *m, zs_error *err) {
  return zs_builtin_teapot_field(m, ZS_BUILTIN_TEAPOT_LEVEL, err);
}
