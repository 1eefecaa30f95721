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

void zs_shade_row(zs_shade shade, int width, const uint32_t *depth,
                  const uint32_t *id, const uint32_t *count,
                  uint32_t background, double znear, double zfar,
                  int perspective, uint32_t *out) {
  (void)background;
  switch (shade) {
    case ZS_SHADE_ID:
      for (int x = 0; x < width; x++)
        out[x] = id[x] == ZS_ID_NONE ? 0 : (id[x] + 1) & 0xFFFFFF;
      break;
    case ZS_SHADE_DEPTH:
      for (int x = 0; x < width; x++) {
        if (id[x] == ZS_ID_NONE) {
          out[x] = 0;
          continue;
        }
        double d = depth[x] / 4294967296.0; /* window depth in [0, 1) */
        double t = d;                       /* 0 near .. 1 far, linear */
        if (perspective) {
          double ndc = 2.0 * d - 1.0;
          double dist = 2.0 * zfar * znear / ((zfar + znear) - ndc * (zfar - znear));
          t = (dist - znear) / (zfar - znear);
        }
        if (t < 0.0) t = 0.0;
        if (t > 1.0) t = 1.0;
        uint32_t g = (uint32_t)lrint(255.0 * (1.0 - t));
        out[x] = g << 16 | g << 8 | g;
      }
      break;
    case ZS_SHADE_OVERDRAW:
      for (int x = 0; x < width; x++) out[x] = heat[count[x] < 8 ? count[x] : 8];
      break;
    case ZS_SHADE_FLAT:
      break; /* the colour buffer already holds the image */
  }
}
