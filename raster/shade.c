/* Shading: the flat colour of a face, and the colours of a finished row.
 *
 * Flat shading.  One directional light, fixed in eye space, coming from
 * the upper right behind the viewer: L = (1, 2, 3) / sqrt(14).  A face of
 * colour c and eye-space normal n gets the intensity
 *   I = 0.25 + 0.75 |n . L| / |n|        (two-sided: back faces lit too)
 * quantized once to q = round(255 I), and each channel becomes
 *   c' = (c q + 127) / 255               (integer division)
 * so the only floating point is the one rounding to q.  (zs_flat_level
 * and zs_flat_tint are inline in shade.h.)  The face stage (draw.c)
 * takes the levels of a run of faces at once, eight at a time with
 * AVX-512: a face's square root and division wait many cycles each, and
 * one face's at a time held up the faces of a small model (zscan bench
 * raster --case "triangles 4x4" and --case builtin:teapots measure it).
 * Each lane does zs_flat_level's operations in its order, and IEEE 754
 * rounds a lane's square root, division, add and multiply as it rounds
 * the scalar's (never fused: -ffp-contract=off); the
 * conversion to an integer is llrint's, in the default rounding mode; a
 * NaN cosine stays NaN past the clamp to 1 and converts as llrint's does
 * (llrint, not lrint: its 64 bits are the same where long is 32, on
 * Windows and i686, and so is a NaN's integer indefinite).
 *
 * Depth shading.  Grey from the linear eye distance, 255 at the near plane
 * and 0 at the far plane, background black.
 *
 * Overdraw.  Fragments per pixel as a heat map: 0 black, 1 blue, 2 green,
 * 3 yellow, 4 orange, 5-7 red, 8 or more white.
 */
#include <math.h>

#include "raster/shade.h"

#include "raster/cpu.h"

#ifdef ZS_HAVE_X86_PATHS
#include <immintrin.h>

/* zs_flat_level of faces [0, n - n % 8), eight a step; returns the first
 * face left. */
ZS_AVX512_TARGET static int flat_levels_avx512(const double *nx, const double *ny,
                                               const double *nz, int n, uint32_t *q) {
  const __m512d l0 = _mm512_set1_pd(0.2672612419124244), l1 = _mm512_set1_pd(0.5345224838248488),
                l2 = _mm512_set1_pd(0.8017837257372732), one = _mm512_set1_pd(1.0);
  int k = 0;
  for (; k + 8 <= n; k += 8) {
    const __m512d x = _mm512_loadu_pd(nx + k), y = _mm512_loadu_pd(ny + k),
                  z = _mm512_loadu_pd(nz + k);
    const __m512d len = _mm512_sqrt_pd(_mm512_add_pd(
        _mm512_add_pd(_mm512_mul_pd(x, x), _mm512_mul_pd(y, y)), _mm512_mul_pd(z, z)));
    const __m512d dot = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(x, l0), _mm512_mul_pd(y, l1)),
                                      _mm512_mul_pd(z, l2));
    /* len > 0 false for a NaN, as the scalar's; such lanes are 0 */
    const __mmask8 some = _mm512_cmp_pd_mask(len, _mm512_setzero_pd(), _CMP_GT_OQ);
    __m512d cosine = _mm512_maskz_div_pd(some, _mm512_abs_pd(dot), len);
    /* min(1, c) is c unless 1 < c, and c when c is NaN: the scalar's clamp */
    cosine = _mm512_min_pd(one, cosine);
    const __m512d level = _mm512_mul_pd(
        _mm512_set1_pd(255.0),
        _mm512_add_pd(_mm512_set1_pd(0.25), _mm512_mul_pd(_mm512_set1_pd(0.75), cosine)));
    /* llrint's conversion to 64 bits, then its low 32 as the (uint32_t) cast */
    _mm256_storeu_si256((__m256i *)(q + k), _mm512_cvtepi64_epi32(_mm512_cvtpd_epi64(level)));
  }
  return k;
}
#endif

/* zs_flat_level of faces [k, n). */
static void flat_levels_from(const double *nx, const double *ny, const double *nz, int k, int n,
                             uint32_t *q) {
  for (; k < n; k++) q[k] = zs_flat_level((const double[3]){nx[k], ny[k], nz[k]});
}

static void flat_levels_scalar(const double *nx, const double *ny, const double *nz, int n,
                               uint32_t *q) {
  flat_levels_from(nx, ny, nz, 0, n, q);
}

#ifdef ZS_HAVE_X86_PATHS
static void flat_levels_wide(const double *nx, const double *ny, const double *nz, int n,
                             uint32_t *q) {
  flat_levels_from(nx, ny, nz, flat_levels_avx512(nx, ny, nz, n, q), n, q);
}
#endif

zs_flat_levels_fn zs_flat_levels_for(zs_simd simd) {
#ifdef ZS_HAVE_X86_PATHS
  if (simd == ZS_SIMD_AVX512) return flat_levels_wide;
#endif
  (void)simd;
  return flat_levels_scalar;
}

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
  uint32_t g = (uint32_t)llrint(255.0 * (1.0 - t));
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
