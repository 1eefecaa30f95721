/* The draw kernel's span fill, sixteen pixels at a time with AVX-512,
 * eight with AVX2 or four with SSE2 (span.h).
 *
 * It does what the scalar loop of scanline.c does for a span whose depth
 * stays strictly inside the range (depth = z >> shift, no clamps): the
 * same less-with-id test, the same writes, the same count.  Integers only,
 * so the results are the same bits; tests/test_raster.c renders at every
 * level and compares images and counters with the scalar loop's.  The
 * test of a lane:
 *   d < zb  or  (d == zb and id < ir)      (unsigned)
 * SSE2 and AVX2 compare signed 32-bit lanes, so both sides are offset by
 * 2^31; AVX-512 compares unsigned lanes into a mask.
 *
 * Each traversal is compiled once per SIMD level and calls its level's
 * fill directly (traversal.h); the level is chosen once per device, when
 * it is created: AVX-512 when the CPU has it (cpuid), else AVX2, else
 * SSE2, which every x86-64 CPU has, capped by the device's config (tests,
 * benchmarks).  On aarch64 NEON, which every aarch64 CPU has, fills four
 * at a time, its compares unsigned like AVX-512's; tools/cross-check.sh
 * shows its images and counters equal the x86-64 build's under qemu.
 * Elsewhere the scalar loop fills every span. */
#include <stdint.h>

#include "raster/span_simd.h"

#ifdef ZS_HAVE_NEON_PATHS
#include <arm_neon.h>

int zs_fill_span_neon(uint32_t *zr, uint32_t *ir, uint32_t *cr, int x0, int x1, int64_t z,
                      int64_t dz, int shift, uint32_t id, uint32_t rgb, uint64_t *written) {
  const uint32x4_t idv = vdupq_n_u32(id), rgbv = vdupq_n_u32(rgb);
  const int64x2_t right = vdupq_n_s64(-(int64_t)shift); /* a negative left shift */
  const int64_t start[4] = {z, z + dz, z + 2 * dz, z + 3 * dz};
  uint64x2_t za = vreinterpretq_u64_s64(vld1q_s64(start));
  uint64x2_t zb2 = vreinterpretq_u64_s64(vld1q_s64(start + 2));
  const uint64x2_t step = vreinterpretq_u64_s64(vdupq_n_s64(4 * dz));
  uint64_t w = 0;
  int x = x0;
  for (; x + 4 <= x1; x += 4) {
    /* the low 32 bits of each 64-bit lane, four in a row */
    const uint32x4_t d = vcombine_u32(vmovn_u64(vshlq_u64(za, right)), vmovn_u64(vshlq_u64(zb2, right)));
    const uint32x4_t zold = vld1q_u32(zr + x), iold = vld1q_u32(ir + x);
    const uint32x4_t pass = vorrq_u32(vcltq_u32(d, zold),
                                      vandq_u32(vceqq_u32(d, zold), vcltq_u32(idv, iold)));
    const uint32_t n = vaddvq_u32(vshrq_n_u32(pass, 31)); /* lanes passed */
    if (n == 4) { /* all four pass: no old values to keep */
      vst1q_u32(zr + x, d);
      vst1q_u32(ir + x, idv);
      vst1q_u32(cr + x, rgbv);
    } else if (n) {
      vst1q_u32(zr + x, vbslq_u32(pass, d, zold));
      vst1q_u32(ir + x, vbslq_u32(pass, idv, iold));
      vst1q_u32(cr + x, vbslq_u32(pass, rgbv, vld1q_u32(cr + x)));
    }
    w += n;
    za = vaddq_u64(za, step);
    zb2 = vaddq_u64(zb2, step);
  }
  *written += w;
  return x;
}
#endif

#ifdef ZS_HAVE_X86_PATHS
#include <immintrin.h>

/* SSE2 has no blend: keep old where the mask is clear, take new where set. */
static inline __m128i select_sse2(__m128i mask, __m128i old, __m128i new_) {
  return _mm_or_si128(_mm_and_si128(mask, new_), _mm_andnot_si128(mask, old));
}

int zs_fill_span_sse2(uint32_t *zr, uint32_t *ir, uint32_t *cr, int x0, int x1, int64_t z,
                     int64_t dz, int shift, uint32_t id, uint32_t rgb, uint64_t *written) {
  const __m128i sign = _mm_set1_epi32((int)0x80000000u);
  const __m128i idv = _mm_set1_epi32((int)id), rgbv = _mm_set1_epi32((int)rgb);
  const __m128i id_s = _mm_xor_si128(idv, sign);
  const __m128i count = _mm_cvtsi32_si128(shift);
  __m128i za = _mm_set_epi64x(z + dz, z), zb2 = _mm_set_epi64x(z + 3 * dz, z + 2 * dz);
  const __m128i step = _mm_set1_epi64x(4 * dz);
  uint64_t w = 0;
  int x = x0;
  for (; x + 4 <= x1; x += 4) {
    /* the low 32 bits of each 64-bit lane, four in a row */
    __m128i da = _mm_shuffle_epi32(_mm_srl_epi64(za, count), _MM_SHUFFLE(2, 0, 2, 0));
    __m128i db = _mm_shuffle_epi32(_mm_srl_epi64(zb2, count), _MM_SHUFFLE(2, 0, 2, 0));
    __m128i d = _mm_unpacklo_epi64(da, db);
    __m128i zold = _mm_loadu_si128((const __m128i *)(zr + x));
    __m128i iold = _mm_loadu_si128((const __m128i *)(ir + x));
    __m128i less = _mm_cmpgt_epi32(_mm_xor_si128(zold, sign), _mm_xor_si128(d, sign));
    __m128i tie = _mm_and_si128(_mm_cmpeq_epi32(d, zold),
                                _mm_cmpgt_epi32(_mm_xor_si128(iold, sign), id_s));
    __m128i pass = _mm_or_si128(less, tie);
    int bits = _mm_movemask_ps(_mm_castsi128_ps(pass));
    if (bits == 0xF) { /* all four pass: no old values to keep */
      _mm_storeu_si128((__m128i *)(zr + x), d);
      _mm_storeu_si128((__m128i *)(ir + x), idv);
      _mm_storeu_si128((__m128i *)(cr + x), rgbv);
      w += 4;
    } else if (bits) {
      static const uint8_t passed[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};
      __m128i cold = _mm_loadu_si128((const __m128i *)(cr + x));
      _mm_storeu_si128((__m128i *)(zr + x), select_sse2(pass, zold, d));
      _mm_storeu_si128((__m128i *)(ir + x), select_sse2(pass, iold, idv));
      _mm_storeu_si128((__m128i *)(cr + x), select_sse2(pass, cold, rgbv));
      w += passed[bits];
    }
    za = _mm_add_epi64(za, step);
    zb2 = _mm_add_epi64(zb2, step);
  }
  *written += w;
  return x;
}

__attribute__((target("avx2"))) int zs_fill_span_avx2(uint32_t *zr, uint32_t *ir, uint32_t *cr,
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
    if (bits == 0xFF) { /* all eight pass: no old values to keep */
      _mm256_storeu_si256((__m256i *)(zr + x), d);
      _mm256_storeu_si256((__m256i *)(ir + x), idv);
      _mm256_storeu_si256((__m256i *)(cr + x), rgbv);
      w += 8;
    } else if (bits) {
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

#endif
