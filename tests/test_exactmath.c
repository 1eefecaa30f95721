/* The one trigonometry, e^x and log x (util/exactmath.h): close to the C
 * library's, and the same bits everywhere, pinned for the matrices that
 * reach an image (perspective, rotation, the automatic camera, the walks'
 * paths).  The C library here is only the yardstick. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "util/exactmath.h"
#include "raster/raster.h"
#include "util/rng.h"
#include "scene/camera.h"
#include "scene/paths.h"
#include "tests/testutil.h"

/* Distance in units in the last place between two finite doubles of one
 * sign. */
static double ulps(double a, double b) {
  if (a == b) return 0;
  return fabs(a - b) / (nextafter(fabs(b), INFINITY) - fabs(b));
}

START_TEST(close_to_the_c_library) {
  zs_rng rng;
  zs_rng_seed(&rng, 7);
  double worst_sin = 0, worst_exp = 0, worst_log = 0, worst_atan = 0;
  for (int i = 0; i < 200000; i++) {
    double u = (double)zs_rng_below(&rng, 1u << 30) / (1u << 30); /* [0, 1) */
    double turns = 8.0 * u - 4.0, s, c;
    zs_sincos_turns(turns, &s, &c);
    double r = turns * 2.0 * ZS_PI;
    /* absolute error: the C library sees the angle rounded in radians,
     * which alone moves sin by up to |r| 2^-53 */
    worst_sin = fmax(worst_sin, fmax(fabs(s - sin(r)), fabs(c - cos(r))));
    double x = 1400.0 * u - 700.0;
    worst_exp = fmax(worst_exp, ulps(zs_exp(x), exp(x)));
    double y = ldexp(0.5 + u, (int)zs_rng_below(&rng, 2000) - 1000);
    worst_log = fmax(worst_log, ulps(zs_log(y), log(y)));
    double t = ldexp(u - 0.5, (int)zs_rng_below(&rng, 40) - 20);
    worst_atan = fmax(worst_atan, ulps(zs_atan_deg(t), atan(t) * (180.0 / ZS_PI)));
  }
  ck_assert_msg(worst_sin < 8 * ZS_PI * 0x1p-52, "sin/cos: off by %g", worst_sin);
  ck_assert_msg(worst_exp < 4, "exp: %g ulp", worst_exp);
  ck_assert_msg(worst_log < 4, "log: %g ulp", worst_log);
  ck_assert_msg(worst_atan < 8, "atan: %g ulp", worst_atan);
}
END_TEST

START_TEST(exact_where_it_must_be) {
  double s, c;
  for (int q = -8; q <= 8; q++) {
    zs_sincos_deg(90.0 * q, &s, &c);
    const double want_s[4] = {0, 1, 0, -1}, want_c[4] = {1, 0, -1, 0};
    int k = ((q % 4) + 4) % 4;
    ck_assert(s == want_s[k] && c == want_c[k]);
    ck_assert(!signbit(s) || s != 0.0); /* no -0.0 */
    ck_assert(!signbit(c) || c != 0.0);
  }
  ck_assert(zs_exp(0.0) == 1.0);
  ck_assert(zs_log(1.0) == 0.0);
  ck_assert(zs_exp(-1000.0) == 0.0);
  ck_assert(isinf(zs_exp(1000.0)));
  ck_assert(isinf(zs_log(0.0)) && zs_log(0.0) < 0);
  ck_assert(isnan(zs_log(-1.0)));
  ck_assert(isinf(zs_tan_deg(90.0)));
  ck_assert(zs_atan_deg(0.0) == 0.0);
  ck_assert(fabs(zs_atan_deg(1.0) - 45.0) < 1e-13 && fabs(zs_atan_deg(-1e300) + 90.0) < 1e-13);
  ck_assert(zs_log10(1000.0) > 2.999999999999 && zs_log10(1000.0) < 3.000000000001);
}
END_TEST

/* The doubles' bits, n <= 32. */
static uint64_t hash_doubles(const double *v, int n) {
  uint64_t u[32];
  memcpy(u, v, (size_t)n * sizeof *v);
  return zs_test_hash_values(u, (size_t)n);
}

/* The bits of the matrices an image is made from: these hashes
 * (tests/golden/matrices.txt) hold with
 * gcc and clang, -O0 to -O3, on glibc as on any other C library. */
START_TEST(matrices_pinned) {
  double m[16];
  zs_mat_perspective(m, 45, 4.0 / 3, 0.5, 100);
  zs_golden_assert("matrices.txt", "perspective", hash_doubles(m, 16));
  zs_mat_rotate(m, 30, 0, 1, 0);
  zs_golden_assert("matrices.txt", "rotate-30", hash_doubles(m, 16));
  zs_mat_rotate(m, 123.25, 1, 2, 3);
  zs_golden_assert("matrices.txt", "rotate-123.25", hash_doubles(m, 16));

  zs_camera c;
  zs_camera_default(&c);
  const double lo[3] = {-1, -2, -3}, hi[3] = {4, 5, 6};
  zs_camera_complete(&c, lo, hi, 4.0 / 3);
  double both[32];
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_camera_matrices(&c, 4.0 / 3, both, both + 16, &err), ZS_OK);
  zs_golden_assert("matrices.txt", "camera", hash_doubles(both, 32));

  static const char *const paths[2][2] = {{"roll", "path-roll"}, {"yaw", "path-yaw"}};
  for (int i = 0; i < 2; i++) {
    zs_path p;
    ck_assert_int_eq(zs_path_named(paths[i][0], &c, 30, &p, &err), ZS_OK);
    const zs_keyframe *k = &p.keys[29];
    const double v[9] = {k->eye[0],    k->eye[1],    k->eye[2],  k->target[0], k->target[1],
                         k->target[2], k->up[0],     k->up[1],   k->up[2]};
    zs_golden_assert("matrices.txt", paths[i][1], hash_doubles(v, 9));
    zs_path_free(&p);
  }
}
END_TEST

int main(void) {
  Suite *s = suite_create("exactmath");
  TCase *tc = tcase_create("exactmath");
  tcase_add_test(tc, close_to_the_c_library);
  tcase_add_test(tc, exact_where_it_must_be);
  tcase_add_test(tc, matrices_pinned);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
