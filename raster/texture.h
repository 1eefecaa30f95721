/* zscan raster — texture sampling, in integers (inlined into the surface
 * shading's loops, surface.c).
 *
 * COORDINATES
 *   A texture coordinate reaches the sampler as (s, t) in units of 2^-16
 *   of the texture's side, t down the image (t = 1 - v for OpenGL's v up):
 *   texel column i of a level W texels wide covers s in [i, i + 1) / W.
 *   Nearest takes texel floor(s W); bilinear the four texels around
 *   s W - 1/2, weighted by the fraction in 1/256 texel, (256 - f) and f
 *   each way, the sum rounded to nearest; trilinear blends the bilinear
 *   samples of two levels by the level of detail's fraction, also in
 *   1/256.  Texels are filtered as stored (sRGB codes), as a texture
 *   without an sRGB format is in OpenGL.
 *
 * LEVEL OF DETAIL
 *   lod = log2(rho), rho the larger of the lengths (in level-0 texels) of
 *   the mapping's derivatives along x and along y at the pixel, from the
 *   exact planes of the triangle (surface.c), in 1/256 of a level: the
 *   exponent of rho^2 from frexp, its mantissa's logarithm from a table
 *   of 256 entries.
 *   Nearest samples level 0 only; bilinear the level nearest to lod;
 *   trilinear the levels floor(lod) and floor(lod) + 1.  lod <= 0 is
 *   magnification: level 0, by the filter (nearest or bilinear). */
#ifndef ZS_RASTER_TEXTURE_H
#define ZS_RASTER_TEXTURE_H

#include <stdint.h>

#include "util/texture.h"

/* A texture as a surface samples it: its levels, wraps and filter. */
typedef struct zs_sampler {
  const zs_texture *tex;
  zs_wrap wrap_s, wrap_t;
  zs_filter filter; /* never ZS_FILTER_DEFAULT here */
} zs_sampler;

/* i wrapped into [0, n).  An index already inside is every wrap's own,
 * and most are: they skip the division. */
static inline int32_t zs_wrap_index(int64_t i, int32_t n, zs_wrap w) {
  if ((uint64_t)i < (uint64_t)n) return (int32_t)i;
  if (w == ZS_WRAP_CLAMP) return i < 0 ? 0 : i >= n ? n - 1 : (int32_t)i;
  if (w == ZS_WRAP_MIRROR) {
    int64_t m = i % (2 * (int64_t)n);
    if (m < 0) m += 2 * (int64_t)n;
    return (int32_t)(m < n ? m : 2 * (int64_t)n - 1 - m);
  }
  int64_t m = i % n;
  return (int32_t)(m < 0 ? m + n : m);
}

static inline const uint8_t *zs_texel(const zs_texlevel *l, int32_t x, int32_t y) {
  return l->rgba + 4 * ((size_t)y * (size_t)l->width + (size_t)x);
}

/* The nearest texel of level l to (s, t). */
static inline void zs_sample_nearest(const zs_sampler *sm, const zs_texlevel *l, int64_t s,
                                     int64_t t, uint8_t out[4]) {
  const int64_t fx = s * l->width, fy = t * l->height; /* 2^-16 texel */
  const uint8_t *p = zs_texel(l, zs_wrap_index(fx >> 16, l->width, sm->wrap_s),
                              zs_wrap_index(fy >> 16, l->height, sm->wrap_t));
  for (int c = 0; c < 4; c++) out[c] = p[c];
}

/* The bilinear sample of level l at (s, t), each channel times 256 (the
 * rounding left to the caller, which may blend two levels first). */
static inline void zs_sample_bilinear256(const zs_sampler *sm, const zs_texlevel *l, int64_t s,
                                         int64_t t, uint32_t out[4]) {
  const int64_t fx = s * l->width - 32768, fy = t * l->height - 32768;
  const uint32_t wx = (uint32_t)((fx >> 8) & 255), wy = (uint32_t)((fy >> 8) & 255);
  const int32_t x0 = zs_wrap_index(fx >> 16, l->width, sm->wrap_s),
                x1 = zs_wrap_index((fx >> 16) + 1, l->width, sm->wrap_s),
                y0 = zs_wrap_index(fy >> 16, l->height, sm->wrap_t),
                y1 = zs_wrap_index((fy >> 16) + 1, l->height, sm->wrap_t);
  const uint8_t *a = zs_texel(l, x0, y0), *b = zs_texel(l, x1, y0), *c = zs_texel(l, x0, y1),
                *d = zs_texel(l, x1, y1);
  for (int k = 0; k < 4; k++) {
    const uint32_t top = a[k] * (256 - wx) + b[k] * wx, bottom = c[k] * (256 - wx) + d[k] * wx;
    out[k] = (top * (256 - wy) + bottom * wy + 128) >> 8; /* 256 x the texel value */
  }
}

/* The texel of sm at (s, t) with level of detail lod256 (1/256 level;
 * <= 0: magnified). */
static inline void zs_sample(const zs_sampler *sm, int64_t s, int64_t t, int32_t lod256,
                             uint8_t out[4]) {
  const zs_texture *tx = sm->tex;
  if (sm->filter == ZS_FILTER_NEAREST) {
    zs_sample_nearest(sm, &tx->level[0], s, t, out);
    return;
  }
  const int32_t top = (tx->levels - 1) * 256;
  if (lod256 < 0) lod256 = 0;
  if (lod256 > top) lod256 = top;
  uint32_t a[4];
  if (sm->filter == ZS_FILTER_BILINEAR) {
    zs_sample_bilinear256(sm, &tx->level[(lod256 + 128) >> 8], s, t, a);
    for (int k = 0; k < 4; k++) out[k] = (uint8_t)((a[k] + 128) >> 8);
    return;
  }
  const int32_t lv = lod256 >> 8, f = lod256 & 255;
  zs_sample_bilinear256(sm, &tx->level[lv], s, t, a);
  if (f == 0) {
    for (int k = 0; k < 4; k++) out[k] = (uint8_t)((a[k] + 128) >> 8);
    return;
  }
  uint32_t b[4];
  zs_sample_bilinear256(sm, &tx->level[lv + 1], s, t, b);
  for (int k = 0; k < 4; k++)
    out[k] = (uint8_t)((a[k] * (uint32_t)(256 - f) + b[k] * (uint32_t)f + 32768) >> 16);
}

#endif
