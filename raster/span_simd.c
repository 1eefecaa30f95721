/* The draw kernel's span fill, eight pixels at a time with AVX2
 * (internal.h, "span_simd.c").
 *
 * It does what the scalar loop of scanline.c does for a span whose depth
 * stays strictly inside the range (depth = z >> shift, no clamps): the
 * same less-with-id test, the same writes, the same count.  Integers only,
 * so the results are the same bits; tests/test_raster.c renders with it on
 * and off and compares images and counters.  The test of a lane:
 *   d < zb  or  (d == zb and id < ir)      (unsigned)
 * AVX2 compares signed 32-bit lanes, so both sides are offset by 2^31.
 *
 * Chosen at run time: the CPU must have AVX2 (cpuid), and
 * zs_raster_set_simd(0) turns it off for everyone (tests, benchmarks). */
#include <stdint.h>

#include "raster/internal.h"

static int simd_allowed = 1;

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>

#define ZS_HAVE_AVX2_PATH 1

__attribute__((target("avx2"))) static int fill_avx2(uint32_t *zr, uint32_t *ir, uint32_t *cr,
                                                      int x0, int x1, int64_t z, int64_t dz,
                                                      int shift, uint32_t id, uint32_t rgb,
                                                      uint64_t *written) {
  const __m256i sign = _mm256_set1_epi32((int)0x80000000u);
  const __m256i idv = _mm256_set1_epi32((int)id), rgbv = _mm256_set1_epi32((int)rgb);
  const __m256i id_s = _mm256_xor_si256(idv, sign);
  const __m128i count = _mm_cvtsi32_si128(shift);
  /* the low 32 bits of four 64-bit lanes, into the low half */
  const __m256i low_dwords = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
  __m256i za = _mm256_setr_epi64x(z, z + dz, z + 2 * dz, z + 3 * dz);
  __m256i zb4 = _mm256_add_epi64(za, _mm256_set1_epi64x(4 * dz));
  const __m256i step = _mm256_set1_epi64x(8 * dz);
  uint64_t w = 0;
  int x = x0;
  for (; x + 8 <= x1; x += 8) {
    __m256i da = _mm256_permutevar8x32_epi32(_mm256_srl_epi64(za, count), low_dwords);
    __m256i db = _mm256_permutevar8x32_epi32(_mm256_srl_epi64(zb4, count), low_dwords);
    __m256i d = _mm256_permute2x128_si256(da, db, 0x20);
    __m256i zold = _mm256_loadu_si256((const __m256i *)(zr + x));
    __m256i iold = _mm256_loadu_si256((const __m256i *)(ir + x));
    __m256i less = _mm256_cmpgt_epi32(_mm256_xor_si256(zold, sign), _mm256_xor_si256(d, sign));
    __m256i tie = _mm256_and_si256(_mm256_cmpeq_epi32(d, zold),
                                   _mm256_cmpgt_epi32(_mm256_xor_si256(iold, sign), id_s));
    __m256i pass = _mm256_or_si256(less, tie);
    int bits = _mm256_movemask_ps(_mm256_castsi256_ps(pass));
    if (bits) {
      __m256i cold = _mm256_loadu_si256((const __m256i *)(cr + x));
      _mm256_storeu_si256((__m256i *)(zr + x), _mm256_blendv_epi8(zold, d, pass));
      _mm256_storeu_si256((__m256i *)(ir + x), _mm256_blendv_epi8(iold, idv, pass));
      _mm256_storeu_si256((__m256i *)(cr + x), _mm256_blendv_epi8(cold, rgbv, pass));
      w += (uint64_t)__builtin_popcount((unsigned)bits);
    }
    za = _mm256_add_epi64(za, step);
    zb4 = _mm256_add_epi64(zb4, step);
  }
  *written += w;
  return x;
}

static int cpu_has_avx2(void) { return __builtin_cpu_supports("avx2") != 0; }
#endif

int zs_raster_set_simd(int on) {
  simd_allowed = on != 0;
  return zs_span_simd_active();
}

int zs_span_simd_active(void) {
#ifdef ZS_HAVE_AVX2_PATH
  return simd_allowed && cpu_has_avx2();
#else
  return 0;
#endif
}

int zs_fill_span_simd(uint32_t *zr, uint32_t *ir, uint32_t *cr, int x0, int x1, int64_t z,
                      int64_t dz, int shift, uint32_t id, uint32_t rgb, uint64_t *written) {
#ifdef ZS_HAVE_AVX2_PATH
  return fill_avx2(zr, ir, cr, x0, x1, z, dz, shift, id, rgb, written);
#else
  (void)zr, (void)ir, (void)cr, (void)x1, (void)z, (void)dz, (void)shift, (void)id, (void)rgb,
      (void)written;
  return x0;
#endif
}
