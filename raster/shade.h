/* zscan raster — shading (shade.c): a face's flat level from its normal
 * against the fixed light, and the colours of a finished row in the
 * depth, id and overdraw shadings.  Chosen once: the flat levels' copy by
 * the SIMD level, a row shader by the shading and the projection. */
#ifndef ZS_RASTER_SHADE_H
#define ZS_RASTER_SHADE_H

#include <math.h>
#include <stdint.h>

#include "raster/raster.h"

/* The shadings whose colours come from the surfaces drawn (flat, and
 * those that read attributes), as against those made from the buffers
 * (id, depth, overdraw). */
static inline int zs_shade_is_surface(zs_shade s) {
  return s == ZS_SHADE_AUTO || s == ZS_SHADE_FLAT || s >= ZS_SHADE_UNLIT;
}
/* The shadings that read a mesh's attributes (auto: when it has any). */
static inline int zs_shade_reads_attrs(zs_shade s) {
  return s == ZS_SHADE_AUTO || s >= ZS_SHADE_UNLIT;
}

/* The flat level of a face, q = round(255 I) (shade.c), from its
 * eye-space normal n (need not be unit) against the fixed light. */
static inline uint32_t zs_flat_level(const double n[3]) {
  const double l[3] = {0.2672612419124244, 0.5345224838248488,
                       0.8017837257372732}; /* (1,2,3)/sqrt(14) */
  double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  double cosine = len > 0.0 ? fabs(n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / len : 0.0;
  /* past 1 where the squares are subnormal (|n| near 1e-162) and round
   * coarsely: up to 1.015, a level of 258 without the clamp */
  if (cosine > 1.0) cosine = 1.0;
  return (uint32_t)llrint(255.0 * (0.25 + 0.75 * cosine));
}

/* rgb at level q: each channel times q / 255, rounded. */
static inline uint32_t zs_flat_tint(uint32_t rgb, uint32_t q) {
  uint32_t r = (rgb >> 16) & 0xFF, g = (rgb >> 8) & 0xFF, b = rgb & 0xFF;
  r = (r * q + 127) / 255;
  g = (g * q + 127) / 255;
  b = (b * q + 127) / 255;
  return r << 16 | g << 8 | b;
}

/* The levels q[0 .. n) of n faces whose normals are (nx, ny, nz)[k]:
 * eight at a time with AVX-512 where simd is, the same bits as
 * zs_flat_level (shade.c). */

/* The levels q[0 .. n) of n faces whose normals are (nx, ny, nz)[k], the
 * same bits as zs_flat_level at every level (eight at a time with
 * AVX-512); zs_flat_levels_for gives the copy for a SIMD level. */
typedef void (*zs_flat_levels_fn)(const double *nx, const double *ny, const double *nz, int n,
                                  uint32_t *q);
zs_flat_levels_fn zs_flat_levels_for(zs_simd simd);

/* The colours of one finished row (out) for a shading mode other than
 * flat; chosen with the projection, when the camera is set (device.c). */
typedef void (*zs_row_shader)(int width, const uint32_t *depth, const uint32_t *id,
                              const uint32_t *count, double znear, double zfar, uint32_t *out);
zs_row_shader zs_row_shader_for(zs_shade shade, int perspective);

#endif
