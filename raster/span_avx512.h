/* zscan raster — the draw kernel's span fill with AVX-512 (span_simd.c's
 * header comment: the same test and writes as the scalar loop), in a
 * header: span_simd.c calls it for the scan's long spans, and the
 * polygon-order traversal's AVX-512 copy (polyorder.c) for every span of a soup, where clang
 * inlines it and gcc calls it.  Forcing it inline under gcc (that copy
 * built for AVX-512 throughout) gained nothing measurable (zscan bench
 * raster --case "random 4x4 back to front", the two builds in turn). */
#ifndef ZS_RASTER_SPAN_AVX512_H
#define ZS_RASTER_SPAN_AVX512_H

#include <stdint.h>

#include "raster/cpu.h"

#ifdef ZS_HAVE_X86_PATHS
#include <immintrin.h>
#define ZS_HAVE_AVX512_SPANS 1

/* The depths of sixteen pixels from their planes' values, eight in za and
 * eight in zb, each already between 0 and the far plane: shifted down,
 * the low 32 bits. */
ZS_AVX512_INLINE __m512i zs_avx512_depths(__m512i za, __m512i zb, __m128i shift) {
  const __m256i da = _mm512_cvtepi64_epi32(_mm512_srl_epi64(za, shift));
  const __m256i db = _mm512_cvtepi64_epi32(_mm512_srl_epi64(zb, shift));
  return _mm512_inserti64x4(_mm512_castsi256_si512(da), db, 1);
}

/* The pixels of mask m among sixteen from zr, ir, cr tested at depths d
 * and written where they pass, as the scalar loop does (nearer, or as
 * near with a smaller id); masked lanes neither load nor store.  The ids
 * are read only where a depth ties, which is rare: a load less on the
 * way to the stores (zscan bench raster --algo zbuffer --case "random
 * 10x10 back to front" measures it).  Returns the pixels written. */
ZS_AVX512_INLINE __mmask16 zs_avx512_test_write(uint32_t *zr, uint32_t *ir, uint32_t *cr,
                                                __mmask16 m, __m512i d, __m512i idv,
                                                __m512i rgbv) {
  const __m512i zold = _mm512_maskz_loadu_epi32(m, zr);
  const __mmask16 tie = _mm512_mask_cmpeq_epu32_mask(m, d, zold);
  __mmask16 pass = _mm512_mask_cmplt_epu32_mask(m, d, zold);
  if (__builtin_expect(tie != 0, 0)) {
    const __m512i iold = _mm512_maskz_loadu_epi32(tie, ir);
    pass |= _mm512_mask_cmplt_epu32_mask(tie, idv, iold);
  }
  _mm512_mask_storeu_epi32(zr, pass, d);
  _mm512_mask_storeu_epi32(ir, pass, idv);
  _mm512_mask_storeu_epi32(cr, pass, rgbv);
  return pass;
}

/* Sixteen pixels a step, the last step masked: a span of any length in
 * whole steps, with no scalar tail and no branch on its pixels' tests
 * (masked lanes neither load nor store, nor fault). */
ZS_AVX512_TARGET static inline int zs_fill_span_avx512(uint32_t *zr, uint32_t *ir, uint32_t *cr,
                                                       int x0, int x1, int64_t z, int64_t dz,
                                                       int shift, uint32_t id, uint32_t rgb,
                                                       uint64_t *written) {
  const __m512i idv = _mm512_set1_epi32((int)id), rgbv = _mm512_set1_epi32((int)rgb);
  const __m128i count = _mm_cvtsi32_si128(shift);
  const __m512i dzv = _mm512_set1_epi64(dz);
  __m512i za = _mm512_add_epi64(_mm512_set1_epi64(z),
                                _mm512_mullo_epi64(dzv, _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7)));
  const __m512i step8 = _mm512_slli_epi64(dzv, 3);
  __m512i zb = _mm512_add_epi64(za, step8);
  const __m512i step16 = _mm512_slli_epi64(dzv, 4);
  uint64_t w = 0;
  for (int x = x0; x < x1; x += 16) {
    const int n = x1 - x < 16 ? x1 - x : 16;
    const __mmask16 m = (__mmask16)((1u << n) - 1u);
    const __m512i d = zs_avx512_depths(za, zb, count);
    const __mmask16 pass = zs_avx512_test_write(zr + x, ir + x, cr + x, m, d, idv, rgbv);
    w += (uint64_t)__builtin_popcount((unsigned)pass);
    za = _mm512_add_epi64(za, step16);
    zb = _mm512_add_epi64(zb, step16);
  }
  *written += w;
  return x1;
}
#endif

#endif
