/* Cross-check against Mesa: the test scenes rendered by Mesa's llvmpipe
 * through OSMesa with the same matrices, one flat colour per face (the
 * face id, as --shade id encodes it) and a "less" depth test, faces drawn
 * in id order (so GL's first-drawn-wins at equal depth is zscan's lower-id
 * rule), compared pixel by pixel with zscan's face ids.
 *
 * What may differ, and why: llvmpipe snaps to 1/256 pixel as zscan does
 * and applies the same edge rule, but it interpolates depth in float from
 * its own plane set-up and keeps a 24-bit depth buffer (zscan: a 32-bit
 * fixed-point plane), so where two faces meet or nearly touch in depth the
 * nearer one can differ; and it fans polygons from their first vertex,
 * where zscan rasterizes convex polygons whole (the same pixels, a
 * slightly different depth plane for a polygon that is not quite planar).
 * The share of pixels that differ is printed for every scene (set
 * ZS_MESA_VERBOSE=1 to list them, each marked tie or coverage) and must
 * stay under 1 in 10,000 on closed meshes that do not touch (cubes,
 * spheres, the OBJ scenes).  Where objects touch or cut into each other
 * (buildings standing on the street, pipes through walls, teapots in
 * columns) a few pixels along the contact are decided by depth precision;
 * there the bound is 5 in 10,000.  tools/crosscheck.h tells those depth
 * ties (llvmpipe's face covers the pixel under zscan's rule too, within
 * four steps of a 24-bit buffer of zscan's nearest) from coverage
 * differences, which must stay under 1 in 10,000 on every scene. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"
#include "tests/testutil.h"
#include "lib/frame_camera.h"
#include "tools/crosscheck.h"
#include "tools/crosscheck_colours.h"
#include "tools/crosscheck_prims.h"
#include "lib/frame.h"
#include "lib/input.h"
#include "tools/mesa.h"

enum { W = 512, H = 384 };

typedef struct cross_case {
  const char *input;
  double max_per10k; /* pixels in 10,000 that may differ */
  int pixel_camera;  /* eye at the origin down -z, fovy 90: vertices on centres */
} cross_case;

static const cross_case cases[] = {
    {"tests/data/scenes/centres.obj", 0.0, 1}, /* the edge rule itself: no pixel may differ */
    {"builtin:cubes?n=6", 1.0, 0},         {"builtin:spheres?count=300", 1.0, 0},
    {"tests/data/scenes/sphere_ell.obj", 1.0, 0}, {"tests/data/scenes/interpenetrate.obj", 1.0, 0},
    {"tests/data/scenes/cyclic.obj", 1.0, 0},
    {"builtin:city", 5.0, 0},              {"builtin:plant?detail=0.25", 5.0, 0},
    {"builtin:default", 5.0, 0},           {"builtin:teapots?count=300", 5.0, 0},
};

START_TEST(faces_match_llvmpipe) {
  const cross_case *c = &cases[_i];
  zs_scene s;
  zs_error err;
  zs_error_clear(&err);
  char path[4096];
  snprintf(path, sizeof path, "%s",
           strncmp(c->input, "builtin:", 8) == 0 ? c->input : zs_test_src(c->input));
  ck_assert_msg(zs_input_load_scene(path, &s, &err) == ZS_OK, "%s", err.msg);
  zs_camera cam = s.camera;
  if (c->pixel_camera) {
    cam = (zs_camera){.target = {0, 0, -1}, .up = {0, 1, 0}, .fovy = 90.0, .znear = 0.5,
                      .zfar = 10, .has_eye = 1, .has_target = 1, .has_up = 1, .has_near = 1,
                      .has_far = 1};
  }
  double view[16], proj[16];
  ck_assert_int_eq(zs_frame_camera(&s, &cam, W, H, view, proj, &err), ZS_OK);
  static uint32_t ids[W * H];
  zs_mesa *mesa;
  ck_assert_msg(zs_mesa_create(W, H, &mesa, &err) == ZS_OK, "%s", err.msg);
  ck_assert_int_eq(zs_mesa_ids(mesa, &s, view, proj, ids, &err), ZS_OK);
  zs_mesa_destroy(mesa);
  zs_crosscheck x;
  ck_assert_msg(zs_crosscheck_faces(&s, view, proj, W, H, ids, getenv("ZS_MESA_VERBOSE") ? stdout : NULL,
                                    &x, &err) == ZS_OK, "%s", err.msg);
  double differ = 1e4 * (double)x.differ / (W * H), ties = 1e4 * (double)x.ties / (W * H);
  double coverage = differ - ties;
  printf("mesa %-40s %5d of %d pixels differ (%.2f in 10,000: %.2f depth ties, %.2f coverage; "
         "%d covered)\n", c->input, (int)x.differ, W * H, differ, ties, coverage, (int)x.covered);
  ck_assert_int_gt((int)x.covered, W * H / 50);
  if (c->max_per10k == 0) ck_assert_int_eq((int)x.differ, 0);
  ck_assert_msg(differ < c->max_per10k || c->max_per10k == 0,
                "%s: %.2f in 10,000 differ (bound %.0f)", c->input, differ, c->max_per10k);
  ck_assert_msg(coverage < 1.0, "%s: %.2f in 10,000 differ in coverage (bound 1)", c->input,
                coverage);
  zs_scene_free(&s);
}
END_TEST

/* ---- colours: zscan's unlit shading against llvmpipe's smooth shading ---- */

START_TEST(unlit_colours_match_llvmpipe) {
  /* the cases and their bounds: tools/crosscheck_colours.c; the figures
   * in docs/RESULTS.md from zscan bench colours */
  const zs_colour_case *c = &zs_colour_cases[_i];
  if (c->input[0] == '/' && !zs_test_exists(c->input)) {
    printf("mesa colours %s: not installed, skipped\n", c->input);
    return;
  }
  zs_error err;
  zs_error_clear(&err);
  char path[4096];
  snprintf(path, sizeof path, "%s",
           strncmp(c->input, "builtin:", 8) == 0 || c->input[0] == '/' ? c->input
                                                                       : zs_test_src(c->input));
  zs_colour_check x;
  const zs_status st = zs_crosscheck_colours(c, path, W, H, &x, &err);
  if (st == ZS_ERR_UNSUPPORTED && strstr(err.msg, "assimp")) { /* a glTF without assimp */
    printf("mesa colours %s: %s, skipped\n", c->input, err.msg);
    return;
  }
  ck_assert_msg(st == ZS_OK, "%s", err.msg);
  const double share = x.covered ? (double)x.close / (double)x.covered : 0.0;
  printf("mesa colours %-48s %-9s %7d covered, %.4f %% within %d a channel, %.4f %% exact, "
         "largest difference %d\n", c->input, zs_filter_name(c->filter), (int)x.covered,
         100.0 * share, c->max_diff,
         100.0 * (double)x.exact / (double)(x.covered ? x.covered : 1), x.worst);
  ck_assert_int_gt((int)x.covered, W * H / 100);
  ck_assert_msg(share >= c->min_share, "%s: %.4f %% of covered pixels within %d, bound %.2f %%",
                c->input, 100.0 * share, c->max_diff, 100.0 * c->min_share);
}
END_TEST

START_TEST(bench_draws_the_tilings_through_llvmpipe) {
  /* `bench raster --mesa` times the triangle tilings through llvmpipe too,
   * built as a scene of layers with the tiling's orthographic camera: both
   * show the same face at every pixel (the diagonals put thousands of
   * pixel centres on edges, so the edge rule is checked as well) */
  static char out[1 << 14], err[1 << 12];
  const char *args[] = {"bench", "raster", "--mesa", "--no-scenes", "--case", "triangles 10x10",
                        "--algo", "zbuffer", "--repeat", "1", "--size", "500x500", NULL};
  ck_assert_msg(zs_test_run_zscan(args, out, sizeof out, err, sizeof err) == 0, "%s", err);
  const char *row = strstr(out, "zscan (zbuffer, 1 thread) and llvmpipe");
  ck_assert_ptr_nonnull(row);
  row = strstr(row, "\ntriangles 10x10 ");
  ck_assert_ptr_nonnull(row);
  double zscan_ms, mesa_ms, ratio, mtri, differ, ties, coverage;
  ck_assert_int_eq(sscanf(row + 1, "triangles 10x10 %lf %lf %lf %lf %lf %lf %lf", &zscan_ms,
                          &mesa_ms, &ratio, &mtri, &differ, &ties, &coverage),
                   7);
  ck_assert(zscan_ms > 0 && mesa_ms > 0);
  ck_assert_msg(differ == 0 && ties == 0 && coverage == 0, "%.2f %.2f %.2f in 10,000", differ,
                ties, coverage);
}
END_TEST

/* ---- lines and points: GL's rules for aliased wide lines and points ---- */

static const double prim_widths[] = {1, 2, 3, 4, 5, 8}; /* bench_lines.c's */

START_TEST(lines_and_points_match_llvmpipe) {
  const double wd = prim_widths[_i];
  zs_error err;
  zs_error_clear(&err);
  zs_prim_check x;
  ck_assert_msg(zs_crosscheck_prims(W, H, 7 + (uint64_t)_i, 300, 300, wd, wd, &x, &err) == ZS_OK,
                "%s", err.msg);
  const double differ = 1e2 * (double)x.differ / (double)x.covered;
  const uint64_t rule = x.differ - x.at_ends - x.rounding;
  printf("mesa lines and points %g px: %d covered, %d differ (%.3f %%): %d at the ends, %d "
         "rounding, %d in the rule\n", wd, (int)x.covered, (int)x.differ, differ,
         (int)x.at_ends, (int)x.rounding, (int)rule);
  /* GL's rules away from the ends, to the last pixel; the figures in
   * docs/RESULTS.md from zscan bench lines */
  ck_assert_msg(rule == 0, "%d pixels differ in the rule", (int)rule);
  ck_assert_msg(differ < 0.1, "%.3f %% differ (bound 0.1 %%)", differ);
  ck_assert_int_gt((int)x.covered, 1000);
}
END_TEST

int main(void) {
  Suite *s = suite_create("mesa");
  TCase *tc = tcase_create("llvmpipe");
  tcase_set_timeout(tc, 600);
  tcase_add_loop_test(tc, faces_match_llvmpipe, 0, (int)(sizeof cases / sizeof cases[0]));
  tcase_add_loop_test(tc, unlit_colours_match_llvmpipe, 0,
                      zs_ncolour_cases);
  tcase_add_test(tc, bench_draws_the_tilings_through_llvmpipe);
  tcase_add_loop_test(tc, lines_and_points_match_llvmpipe, 0,
                      (int)(sizeof prim_widths / sizeof prim_widths[0]));
  suite_add_tcase(s, tc);
  setenv("CK_FORK", "no", 0);
  return zs_test_run(s);
}
