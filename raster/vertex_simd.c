/* The vertex stage eight vertices at a time with AVX-512 (draw.h,
 * zs_vertex_stage_for): what draw.c's loop does for each vertex, to clip
 * space, the outcode, the snapped window position, and eye space.
 *
 * The same bits.  Every lane does the scalar loop's operations in its
 * order, and IEEE 754 rounds each add, multiply and divide of a lane as
 * it rounds the scalar's: the matrix rows as ((m0 x + m1 y) + m2 z) + m3,
 * never fused into a multiply-add (AVX-512 has one; -ffp-contract=off,
 * which the build gives every file, forbids the fusing), the plane
 * distances as in zs_clip_plane_dist (a NaN is outside), the window
 * position as in zs_window_xy, rounded to the nearest subpixel, ties to
 * even, by the same conversion lrint makes in the default rounding mode,
 * and the depth clamped with the same two compares (a NaN kept).
 * tests/test_raster.c compares this stage with the scalar one on vertices
 * in and out of every plane, on them, behind the eye, at w = 0, at NaN
 * and at rounding ties, and every golden image is drawn through it.
 *
 * Chosen with the span fill, once per device: on a CPU with AVX-512 (F,
 * VL, BW, DQ, as span_simd.c asks), unless the device's config caps it
 * lower.  The vertices past the last whole eight go through the scalar
 * loop. */
#include <stdint.h>

#include "raster/cpu.h"
#include "raster/draw.h"

#ifdef ZS_HAVE_X86_PATHS
#include <immintrin.h>

/* One row of m applied to the eight points (x, y, z, 1). */
ZS_AVX512_INLINE __m512d
row_of(const double *m, __m512d x, __m512d y, __m512d z) {
  const __m512d s = _mm512_add_pd(_mm512_mul_pd(_mm512_set1_pd(m[0]), x),
                                  _mm512_mul_pd(_mm512_set1_pd(m[1]), y));
  return _mm512_add_pd(_mm512_add_pd(s, _mm512_mul_pd(_mm512_set1_pd(m[2]), z)),
                       _mm512_set1_pd(m[3]));
}

/* A lane's outcode bit where the distance is not >= 0 (NaN included). */
ZS_AVX512_INLINE __m512i
mark_out(__m512i code, __m512d dist, unsigned bit) {
  const __mmask8 in = _mm512_cmp_pd_mask(dist, _mm512_setzero_pd(), _CMP_GE_OQ);
  return _mm512_mask_or_epi64(code, (__mmask8)~in, code, _mm512_set1_epi64(bit));
}

ZS_AVX512_TARGET static int32_t
vertex_stage_avx512(const zs_draw_prep *pr, const zs_mesh *mesh, zs_vert_scratch *v,
                    int32_t i0, int32_t i1) {
  const double gx = pr->gx, gy = pr->gy;
  /* the x, y and z of eight points from their 24 doubles, and back */
  const __m512i x_ab = _mm512_setr_epi64(0, 3, 6, 9, 12, 15, 0, 0);
  const __m512i x_c = _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 10, 13);
  const __m512i y_ab = _mm512_setr_epi64(1, 4, 7, 10, 13, 0, 0, 0);
  const __m512i y_c = _mm512_setr_epi64(0, 1, 2, 3, 4, 8, 11, 14);
  const __m512i z_ab = _mm512_setr_epi64(2, 5, 8, 11, 14, 0, 0, 0);
  const __m512i z_c = _mm512_setr_epi64(0, 1, 2, 3, 4, 9, 12, 15);
  const __m512i a_xy = _mm512_setr_epi64(0, 8, 0, 1, 9, 0, 2, 10);
  const __m512i a_z = _mm512_setr_epi64(0, 1, 8, 3, 4, 9, 6, 7);
  const __m512i b_xy = _mm512_setr_epi64(0, 3, 11, 0, 4, 12, 0, 5);
  const __m512i b_z = _mm512_setr_epi64(10, 1, 2, 11, 4, 5, 12, 7);
  const __m512i c_xy = _mm512_setr_epi64(13, 0, 6, 14, 0, 7, 15, 0);
  const __m512i c_z = _mm512_setr_epi64(0, 13, 2, 3, 14, 5, 6, 15);
  const __m512d one = _mm512_set1_pd(1.0), half = _mm512_set1_pd(0.5);
  const __m512d sub = _mm512_set1_pd((double)ZS_SUBPIXEL_ONE);
  const __m512d half_w = _mm512_set1_pd(0.5 * pr->sp.width);
  const __m512d half_h = _mm512_set1_pd(0.5 * pr->sp.height);
  const __m512d gxv = _mm512_set1_pd(gx), gyv = _mm512_set1_pd(gy);
  const __m512i h_sub = _mm512_set1_epi64((int64_t)pr->sp.height * ZS_SUBPIXEL_ONE);
  int32_t i = i0;
  for (; i + 8 <= i1; i += 8) {
    const double *p = &mesh->pos[3 * (int64_t)i];
    const __m512d a = _mm512_loadu_pd(p), b = _mm512_loadu_pd(p + 8),
                  c = _mm512_loadu_pd(p + 16);
    const __m512d x = _mm512_permutex2var_pd(_mm512_permutex2var_pd(a, x_ab, b), x_c, c);
    const __m512d y = _mm512_permutex2var_pd(_mm512_permutex2var_pd(a, y_ab, b), y_c, c);
    const __m512d z = _mm512_permutex2var_pd(_mm512_permutex2var_pd(a, z_ab, b), z_c, c);

    const __m512d cx = row_of(pr->mvp, x, y, z), cy = row_of(pr->mvp + 4, x, y, z);
    const __m512d cz = row_of(pr->mvp + 8, x, y, z), cw = row_of(pr->mvp + 12, x, y, z);
    /* clip space, (x, y, z, w) a vertex: a 4 x 8 transpose */
    const __m512d t0 = _mm512_unpacklo_pd(cx, cy), t1 = _mm512_unpackhi_pd(cx, cy);
    const __m512d t2 = _mm512_unpacklo_pd(cz, cw), t3 = _mm512_unpackhi_pd(cz, cw);
    const __m512d s0 = _mm512_shuffle_f64x2(t0, t2, 0x44), s1 = _mm512_shuffle_f64x2(t1, t3, 0x44);
    const __m512d s2 = _mm512_shuffle_f64x2(t0, t2, 0xEE), s3 = _mm512_shuffle_f64x2(t1, t3, 0xEE);
    double *clip = &v->clip[i].x;
    _mm512_storeu_pd(clip, _mm512_shuffle_f64x2(s0, s1, 0x88));
    _mm512_storeu_pd(clip + 8, _mm512_shuffle_f64x2(s0, s1, 0xDD));
    _mm512_storeu_pd(clip + 16, _mm512_shuffle_f64x2(s2, s3, 0x88));
    _mm512_storeu_pd(clip + 24, _mm512_shuffle_f64x2(s2, s3, 0xDD));

    __m512i code = _mm512_setzero_si512();
    code = mark_out(code, _mm512_add_pd(cz, cw), ZS_CLIP_NEAR);
    code = mark_out(code, _mm512_sub_pd(cw, cz), ZS_CLIP_FAR);
    code = mark_out(code, _mm512_add_pd(_mm512_mul_pd(gxv, cw), cx), ZS_CLIP_LEFT);
    code = mark_out(code, _mm512_sub_pd(_mm512_mul_pd(gxv, cw), cx), ZS_CLIP_RIGHT);
    code = mark_out(code, _mm512_add_pd(_mm512_mul_pd(gyv, cw), cy), ZS_CLIP_BOTTOM);
    code = mark_out(code, _mm512_sub_pd(_mm512_mul_pd(gyv, cw), cy), ZS_CLIP_TOP);
    _mm256_storeu_si256((__m256i *)&v->outcode[i], _mm512_cvtepi64_epi32(code));

    /* snapped, for the vertices inside every plane only */
    const __mmask8 inside = _mm512_cmpeq_epi64_mask(code, _mm512_setzero_si512());
    if (inside) {
      const __m512d xw = _mm512_mul_pd(_mm512_add_pd(_mm512_div_pd(cx, cw), one), half_w);
      const __m512d yw = _mm512_mul_pd(_mm512_add_pd(_mm512_div_pd(cy, cw), one), half_h);
      __m512d zw = _mm512_mul_pd(_mm512_add_pd(_mm512_div_pd(cz, cw), one), half);
      zw = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(zw, _mm512_setzero_pd(), _CMP_LT_OQ), zw,
                                _mm512_setzero_pd());
      zw = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(zw, one, _CMP_GT_OQ), zw, one);
      const __m512i sx = _mm512_cvtpd_epi64(_mm512_mul_pd(xw, sub));
      const __m512i sy = _mm512_sub_epi64(h_sub, _mm512_cvtpd_epi64(_mm512_mul_pd(yw, sub)));
      int32_t X[8], Y[8];
      double Z[8];
      _mm256_storeu_si256((__m256i *)X, _mm512_cvtepi64_epi32(sx));
      _mm256_storeu_si256((__m256i *)Y, _mm512_cvtepi64_epi32(sy));
      _mm512_storeu_pd(Z, zw);
      for (int k = 0; k < 8; k++)
        if (inside >> k & 1) v->snap[i + k] = (zs_snap_vert){X[k], Y[k], Z[k]};
    }

    if (pr->need_eye) { /* eye space, (x, y, z) a vertex */
      const __m512d ex = row_of(pr->mv, x, y, z), ey = row_of(pr->mv + 4, x, y, z);
      const __m512d ez = row_of(pr->mv + 8, x, y, z);
      double *eye = &v->eyepos[3 * (int64_t)i];
      _mm512_storeu_pd(eye, _mm512_permutex2var_pd(_mm512_permutex2var_pd(ex, a_xy, ey), a_z, ez));
      _mm512_storeu_pd(eye + 8,
                       _mm512_permutex2var_pd(_mm512_permutex2var_pd(ex, b_xy, ey), b_z, ez));
      _mm512_storeu_pd(eye + 16,
                       _mm512_permutex2var_pd(_mm512_permutex2var_pd(ex, c_xy, ey), c_z, ez));
    }
  }
  return i;
}
#endif

/* Below AVX-512 draw.c's loop takes every vertex. */
static int32_t vertex_stage_none(const zs_draw_prep *pr, const zs_mesh *mesh, zs_vert_scratch *v,
                                 int32_t i0, int32_t i1) {
  (void)pr, (void)mesh, (void)v, (void)i1;
  return i0;
}

zs_vertex_stage_fn zs_vertex_stage_for(zs_simd simd) {
#ifdef ZS_HAVE_X86_PATHS
  if (simd == ZS_SIMD_AVX512) return vertex_stage_avx512;
#endif
  (void)simd;
  return vertex_stage_none;
}
