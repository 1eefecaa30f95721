/* Anti-aliasing: the standard sample positions, seen through the pixels
 * they cover.  A square's right edge 3/16 pixel right of a column's
 * centres, and a second's on the centres themselves, drawn white on black
 * (unlit): each pixel on the edge is the mean of its covered samples,
 * (255 k + n / 2) / n for k of n samples left of the edge, and a sample on
 * the edge is the right edge's, not covered (the top-left rule).  (The
 * same bytes in every mode, thread count, SIMD level and draw order:
 * test_golden's anti-aliased cases.) */
#include <stdio.h>
#include <string.h>

#include "lib/samples.h"
#include "tests/testutil.h"

static char out[1 << 14], err[1 << 14];

static uint32_t mean(int k, int n) { return (uint32_t)((255 * k + n / 2) / n); }

/* Of the n positions, those whose x is below dx (1/16 pixel). */
static int left_of(int n, int dx) {
  const int8_t *p = zs_sample_positions(n);
  int k = 0;
  for (int i = 0; i < n; i++) k += p[2 * i] < dx;
  return k;
}

START_TEST(edge_pixels_are_the_mean_of_their_samples) {
  static const int counts[] = {1, 2, 4, 8, 16};
  /* D3D's 4x pattern, and the counts by hand for 3/16: 1, 1, 3, 5, 11 */
  static const int8_t four[] = {-2, -6, 6, -2, -6, 2, 2, 6};
  ck_assert_mem_eq(zs_sample_positions(4), four, sizeof four);
  static const int by_hand[] = {1, 1, 3, 5, 11};
  char png[4096];
  snprintf(png, sizeof png, "%s/samples-edge.png", ZS_BINARY_DIR);
  for (int c = 0; c < 5; c++) {
    const int n = counts[c];
    ck_assert(zs_samples_valid(n));
    ck_assert_int_eq(left_of(n, 3), by_hand[c]);
    char ns[8];
    snprintf(ns, sizeof ns, "%d", n);
    const char *args[] = {"render", zs_test_src("tests/data/scenes/half_plane.obj"), "--ortho",
                          "-1,1,-0.75,0.75", "--eye", "0,0,5", "--target", "0,0,0", "--size",
                          "160x120", "--shade", "unlit", "--background", "000000", "--samples",
                          ns, "-o", png, "-q", NULL};
    ck_assert_msg(zs_test_run_zscan(args, out, sizeof out, err, sizeof err) == 0, "%s", err);
    zs_image im;
    zs_error e;
    zs_error_clear(&e);
    ck_assert_msg(zs_png_read(png, &im, &e) == ZS_OK, "%s", e.msg);
    const uint32_t *top = im.rgb + 30 * 160, *bottom = im.rgb + 90 * 160;
    ck_assert_uint_eq(top[79], 0xFFFFFF);
    ck_assert_uint_eq(top[81], 0);
    const uint32_t a = mean(left_of(n, 3), n), b = mean(left_of(n, 0), n);
    ck_assert_msg(top[80] == (a << 16 | a << 8 | a), "%d samples: %06x, want %02x", n, top[80], a);
    ck_assert_msg(bottom[80] == (b << 16 | b << 8 | b), "%d samples: %06x, want %02x", n,
                  bottom[80], b);
    ck_assert_uint_eq(bottom[79], 0xFFFFFF);
    zs_image_free(&im);
  }
  ck_assert(!zs_samples_valid(3) && !zs_samples_valid(0) && !zs_samples_valid(32));
}
END_TEST

int main(void) {
  Suite *s = suite_create("samples");
  TCase *tc = tcase_create("positions");
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, edge_pixels_are_the_mean_of_their_samples);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
