/* zscan raster — the draw kernel's span fills at each SIMD level
 * (span_simd.c for SSE2, AVX2 and NEON, span_avx512.h for AVX-512), and the
 * shortest span each takes; the level is a constant in every traversal's
 * copy (traversal.h), so the choice below folds away. */
#ifndef ZS_RASTER_SPAN_SIMD_H
#define ZS_RASTER_SPAN_SIMD_H

#include <limits.h>
#include <stdint.h>

#include "raster/raster.h"
#include "raster/span_avx512.h"
#include "raster/tuning.h"

/* The shortest span a SIMD level fills (tuning.h); shorter ones stay
 * with the scalar loop, inlined. */
static inline int zs_simd_min_span(zs_simd simd) {
  return simd == ZS_SIMD_AVX512 ? ZS_AVX512_MIN_SPAN
         : simd != ZS_SIMD_SCALAR ? ZS_SIMD_MIN_SPAN
                                  : INT_MAX;
}

/* span_simd.c: the draw kernel's span fill for a span whose depths
 * z .. z + (x1 - x0 - 1) dz all lie strictly inside the depth range: the
 * scalar loop's test and writes, four (SSE2, NEON) or eight (AVX2) pixels at a
 * time, as far as whole steps go; adds the pixels written to *written and
 * returns the column where the scalar loop takes over. */
int zs_fill_span_sse2(uint32_t *zr, uint32_t *ir, uint32_t *cr, int x0, int x1, int64_t z,
                      int64_t dz, int shift, uint32_t id, uint32_t rgb, uint64_t *written);
int zs_fill_span_avx2(uint32_t *zr, uint32_t *ir, uint32_t *cr, int x0, int x1, int64_t z,
                      int64_t dz, int shift, uint32_t id, uint32_t rgb, uint64_t *written);
/* The same four pixels at a time with NEON, on aarch64. */
int zs_fill_span_neon(uint32_t *zr, uint32_t *ir, uint32_t *cr, int x0, int x1, int64_t z,
                      int64_t dz, int shift, uint32_t id, uint32_t rgb, uint64_t *written);

/* The level's fill, simd a constant in every traversal's copy, so the
 * choice folds away (AVX-512's inline where it can, span_avx512.h); the
 * scalar level takes no column. */
static inline int zs_fill_span_wide(const zs_simd simd, uint32_t *zr, uint32_t *ir, uint32_t *cr,
                                    int x0, int x1, int64_t z, int64_t dz, int shift, uint32_t id,
                                    uint32_t rgb, uint64_t *written) {
#ifdef ZS_HAVE_AVX512_SPANS
  if (simd == ZS_SIMD_AVX512)
    return zs_fill_span_avx512(zr, ir, cr, x0, x1, z, dz, shift, id, rgb, written);
  if (simd == ZS_SIMD_AVX2)
    return zs_fill_span_avx2(zr, ir, cr, x0, x1, z, dz, shift, id, rgb, written);
  if (simd == ZS_SIMD_SSE2)
    return zs_fill_span_sse2(zr, ir, cr, x0, x1, z, dz, shift, id, rgb, written);
#endif
#ifdef ZS_HAVE_NEON_PATHS
  if (simd == ZS_SIMD_NEON)
    return zs_fill_span_neon(zr, ir, cr, x0, x1, z, dz, shift, id, rgb, written);
#endif
  (void)simd, (void)zr, (void)ir, (void)cr, (void)x1, (void)z, (void)dz, (void)shift, (void)id,
      (void)rgb, (void)written;
  return x0;
}

#endif
