/* Shading: the flat colour of a face, and the colours of a finished row.
 *
 * Flat shading.  One directional light, fixed in eye space, coming from
 * the upper right behind the viewer: L = (1, 2, 3) / sqrt(14).  A face of
 * colour c and eye-space normal n gets the intensity
 *   I = 0.25 + 0.75 |n . L| / |n|        (two-sided: back faces lit too)
 * quantized once to q = round(255 I), and each channel becomes
 *   c' = (c q + 127) / 255               (integer division)
 * so the only floating point is the one rounding to q.  (zs_shade_flat is
 * inline in internal.h: set-up calls it once per face.)
 *
 * Depth shading.  Grey from the linear eye distance, 255 at the near plane
 * and 0 at the far plane, background black.
 *
 * Overdraw.  Fragments per pixel as a heat map: 0 black, 1 blue, 2 green,
 * 3 yellow, 4 orange, 5-7 red, 8 or more white.
 */
#include <math.h>

#include "raster/internal.h"

static const uint32_t heat[9] = {0x000000, 0x2050E0, 0x20C040, 0xF0E020,
                                 0xF09020, 0xE02020, 0xE02020, 0xE02020,
                                 0xFFFFFF};

static void shade_ids(int width, const uint32_t *depth, const uint32_t *id,
                      const uint32_t *count, double znear, double zfar, uint32_t *out) {
  (void)depth, (void)count, (void)znear, (void)zfar;
  for (int x = 0; x < width; x++) out[x] = id[x] == ZS_ID_NONE ? 0 : (id[x] + 1) & 0xFFFFFF;
}

/* grey from t, 0 near .. 1 far (clamped) */
static inline uint32_t grey_of(double t) {
  if (t < 0.0) t = 0.0;
  if (t > 1.0) t = 1.0;
  uint32_t g = (uint32_t)lrint(255.0 * (1.0 - t));
  return g << 16 | g << 8 | g;
}

/* a parallel projection: the window depth is linear in the distance */
static void shade_depths_parallel(int width, const uint32_t *depth, const uint32_t *id,
                                  const uint32_t *count, double znear, double zfar,
                                  uint32_t *out) {
  (void)count, (void)znear, (void)zfar;
  for (int x = 0; x < width; x++)
    out[x] = id[x] == ZS_ID_NONE ? 0 : grey_of(depth[x] / 4294967296.0);
}

/* a perspective: the eye distance from the window depth d in [0, 1) */
static void shade_depths_perspective(int width, const uint32_t *depth, const uint32_t *id,
                                     const uint32_t *count, double znear, double zfar,
                                     uint32_t *out) {
  (void)count;
  for (int x = 0; x < width; x++) {
    if (id[x] == ZS_ID_NONE) {
      out[x] = 0;
      continue;
    }
    double ndc = 2.0 * (depth[x] / 4294967296.0) - 1.0;
    double dist = 2.0 * zfar * znear / ((zfar + znear) - ndc * (zfar - znear));
    out[x] = grey_of((dist - znear) / (zfar - znear));
  }
}

static void shade_overdraw(int width, const uint32_t *depth, const uint32_t *id,
                           const uint32_t *count, double znear, double zfar, uint32_t *out) {
  (void)depth, (void)id, (void)znear, (void)zfar;
  for (int x = 0; x < width; x++) out[x] = heat[count[x] < 8 ? count[x] : 8];
}

zs_row_shader zs_row_shader_for(zs_shade shade, int perspective) {
  switch (shade) {
    case ZS_SHADE_ID: return shade_ids;
    case ZS_SHADE_DEPTH: return perspective ? shade_depths_perspective : shade_depths_parallel;
    case ZS_SHADE_OVERDRAW: return shade_overdraw;
    default: return NULL; /* flat: the colour buffer already holds the image */
  }
}
