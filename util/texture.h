/* zscan util — a texture's storage (texture.c): its levels, the base one
 * and the mip chain below it, in one allocation.  The raster samples it
 * (raster/texture.h); the scene's loaders make it from decoded images. */
#ifndef ZS_UTIL_TEXTURE_H
#define ZS_UTIL_TEXTURE_H

#include <stdint.h>

#include "zscan/zscan.h"

enum { ZS_TEXTURE_MAX_LEVELS = 14 }; /* 8192 = 2^13: levels 0 .. 13 */

typedef struct zs_texlevel {
  int32_t width, height;
  const uint8_t *rgba; /* width * height texels, row 0 at the top */
} zs_texlevel;

struct zs_texture {
  int32_t levels;
  zs_texlevel level[ZS_TEXTURE_MAX_LEVELS];
  uint8_t *texels; /* every level, base first */
  int opaque;      /* every texel's alpha is 255 */
};

#endif
