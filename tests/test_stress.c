/* Numerical stress: inputs nobody tuned for.  Every test states exactly
 * what a user would see: pixels covered once and only once inside a closed
 * outline, nothing drawn from behind the eye, the nearer of two faces one
 * depth unit apart, the same bytes in both modes and in any order. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "raster/raster.h"
#include "util/rng.h"
#include "tests/testutil.h"

enum { W = 128, H = 96 };
static zs_error err;

typedef struct frame {
  uint32_t count[W * H], id[W * H], rgb[W * H];
} frame;

static void keep(void *user, const zs_row *row) {
  frame *f = user;
  if (row->count) memcpy(f->count + row->y * W, row->count, W * 4);
  memcpy(f->id + row->y * W, row->id, W * 4);
  memcpy(f->rgb + row->y * W, row->rgb, W * 4);
}

/* Renders m placed by model (NULL: identity) with the given camera. */
static zs_raster_stats draw(const zs_mesh *m, const double model[16], const double view[16],
                            const double proj[16], zs_algo algo, zs_shade shade, int cull,
                            frame *f) {
  zs_device_config cfg = {W, H, algo, shade, cull, 1, 0, 0, 0};
  zs_device *d = NULL;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
  zs_device_set_camera(d, view, proj);
  zs_device_clear(d);
  ck_assert_msg(zs_device_draw(d, m, model, 0, ZS_RGB_MESH, &err) == ZS_OK, "%s", err.msg);
  ck_assert_int_eq(zs_device_finish(d, keep, f, &err), ZS_OK);
  zs_raster_stats s = *zs_device_stats(d);
  zs_device_destroy(d);
  return s;
}

/* Every pixel counted at most once, and each row's covered pixels one run
 * (the outline is convex); returns the pixels covered. */
static int once_and_convex(const frame *f, const char *what) {
  int covered = 0;
  for (int y = 0; y < H; y++) {
    int runs = 0, prev = 0;
    for (int x = 0; x < W; x++) {
      uint32_t k = f->count[y * W + x];
      ck_assert_msg(k <= 1, "%s: pixel %d,%d covered %u times", what, x, y, k);
      if (k && !prev) runs++;
      prev = (int)k;
      covered += (int)k;
    }
    ck_assert_msg(runs <= 1, "%s: row %d has a crack", what, y);
  }
  return covered;
}

static void ortho(double view[16], double proj[16]) {
  zs_mat_identity(view);
  zs_mat_ortho(proj, 0, W, 0, H, -10, 10);
}

/* ---- watertightness ---- */

START_TEST(fan_of_100000_slivers) {
  mesh_buf b = {0};
  const int n = 100000;
  mb_fan(&b, 64.37, 47.81, 40.2, n);
  double view[16], proj[16];
  ortho(view, proj);
  static frame f;
  for (int algo = 0; algo < 2; algo++) {
    draw(&b.m, NULL, view, proj, (zs_algo)algo, ZS_SHADE_OVERDRAW, 0, &f);
    int covered = once_and_convex(&f, "fan");
    ck_assert_int_gt(covered, 5000); /* pi 40.2^2 = 5,077 centres */
    ck_assert_int_lt(covered, 5150);
  }
  mb_free(&b);
}
END_TEST

START_TEST(long_thin_triangles_across_the_screen) {
  /* A rectangle across the whole screen cut into 2,000 triangles, each
   * a hundredth of a pixel high: every pixel of it exactly once. */
  mesh_buf b = {0};
  const int n = 1000;
  for (int i = 0; i <= n; i++) {
    mb_vert(&b, -3.3, 20.25 + 50.0 * i / n, 0);
    mb_vert(&b, W + 3.7, 20.25 + 50.0 * i / n + 0.01, 0);
  }
  for (int i = 0; i < n; i++) {
    int32_t t[3] = {2 * i, 2 * i + 1, 2 * i + 3};
    int32_t u[3] = {2 * i, 2 * i + 3, 2 * i + 2};
    mb_face(&b, t, 3, 0xFFFFFF);
    mb_face(&b, u, 3, 0xFFFFFF);
  }
  double view[16], proj[16];
  ortho(view, proj);
  static frame f;
  draw(&b.m, NULL, view, proj, ZS_ALGO_SCANLINE, ZS_SHADE_OVERDRAW, 0, &f);
  ck_assert_int_eq(once_and_convex(&f, "strip"), W * 50);
  mb_free(&b);
}
END_TEST

START_TEST(vertices_on_pixel_centres) {
  /* A grid of quads whose corners are pixel centres: each pixel once. */
  mesh_buf b = {0};
  for (int y = 0; y <= 10; y++)
    for (int x = 0; x <= 10; x++) mb_vert(&b, 10.5 + 7 * x, 10.5 + 7 * y, 0);
  for (int y = 0; y < 10; y++)
    for (int x = 0; x < 10; x++) {
      int32_t q[4] = {y * 11 + x, y * 11 + x + 1, (y + 1) * 11 + x + 1, (y + 1) * 11 + x};
      mb_face(&b, q, 4, 0xFFFFFF);
    }
  double view[16], proj[16];
  ortho(view, proj);
  static frame f;
  for (int algo = 0; algo < 2; algo++) {
    draw(&b.m, NULL, view, proj, (zs_algo)algo, ZS_SHADE_OVERDRAW, 0, &f);
    /* centres 10.5 .. 80.5: left and bottom edges in: 70 x 70 pixels */
    ck_assert_int_eq(once_and_convex(&f, "grid"), 70 * 70);
  }
  mb_free(&b);
}
END_TEST

START_TEST(far_from_the_origin) {
  /* A closed sphere a million units out, the camera beside it: its outline
   * covered exactly once with back faces culled, twice without. */
  mesh_buf b = {0};
  mb_sphere(&b, 0, 0, 0, 1.0, 40, 24, 0);
  double model[16], view[16], proj[16];
  zs_mat_translate(model, 1e6, -1e6, 1e6);
  zs_mat_look_at(view, (double[3]){1e6 + 0.2, -1e6 + 0.3, 1e6 + 4.5}, (double[3]){1e6, -1e6, 1e6},
                 (double[3]){0, 1, 0});
  zs_mat_perspective(proj, 40, (double)W / H, 1, 10);
  static frame f, g;
  draw(&b.m, model, view, proj, ZS_ALGO_ZBUFFER, ZS_SHADE_OVERDRAW, 1, &f);
  draw(&b.m, model, view, proj, ZS_ALGO_ZBUFFER, ZS_SHADE_OVERDRAW, 0, &g);
  int covered = once_and_convex(&f, "far sphere");
  ck_assert_int_gt(covered, 1500);
  for (int i = 0; i < W * H; i++) ck_assert_uint_eq(g.count[i], 2 * f.count[i]);
  mb_free(&b);
}
END_TEST

START_TEST(rotated_in_small_steps) {
  mesh_buf b = {0};
  mb_sphere(&b, 0, 0, 0, 1.0, 32, 20, 0);
  double view[16], proj[16];
  zs_mat_look_at(view, (double[3]){0, 0, 4}, (double[3]){0, 0, 0}, (double[3]){0, 1, 0});
  zs_mat_perspective(proj, 50, (double)W / H, 1, 10);
  static frame f;
  for (int k = 0; k < 40; k++) {
    double model[16];
    zs_mat_rotate(model, 0.05 * k, 0.3, 1, 0.2);
    draw(&b.m, model, view, proj, ZS_ALGO_SCANLINE, ZS_SHADE_OVERDRAW, 1, &f);
    ck_assert_int_gt(once_and_convex(&f, "rotated sphere"), 1500);
  }
  mb_free(&b);
}
END_TEST

/* ---- clipping ---- */

START_TEST(camera_inside_a_closed_object) {
  /* From inside a closed convex mesh every view ray meets it once: with
   * its faces turned inward, every pixel is covered exactly once. */
  mesh_buf b = {0};
  mb_sphere(&b, 0, 0, 0, 5.0, 48, 32, 1);
  double view[16], proj[16];
  zs_mat_look_at(view, (double[3]){0.3, -0.2, 0.1}, (double[3]){1, 0.2, -3}, (double[3]){0, 1, 0});
  zs_mat_perspective(proj, 70, (double)W / H, 0.1, 20);
  static frame f;
  for (int algo = 0; algo < 2; algo++) {
    zs_raster_stats s = draw(&b.m, NULL, view, proj, (zs_algo)algo, ZS_SHADE_OVERDRAW, 1, &f);
    for (int i = 0; i < W * H; i++) ck_assert_uint_eq(f.count[i], 1);
    ck_assert_uint_gt(s.polygons_clipped, 0);
  }
  mb_free(&b);
}
END_TEST

START_TEST(grazing_the_near_plane) {
  /* A floor through the near plane seen at a grazing angle, a triangle
   * with a vertex exactly on the near plane and one behind the eye: what is
   * drawn lies in front of the near plane; the floor covers the bottom of
   * the image without a crack, the top not at all. */
  mesh_buf b = {0};
  int32_t q[4] = {mb_vert(&b, -50, -1, 50), mb_vert(&b, 50, -1, 50), mb_vert(&b, 50, -1, -50),
                  mb_vert(&b, -50, -1, -50)};
  mb_face(&b, q, 4, 0xFFFFFF);
  double view[16], proj[16];
  zs_mat_look_at(view, (double[3]){0, 0, 0}, (double[3]){0, -0.02, -1}, (double[3]){0, 1, 0});
  zs_mat_perspective(proj, 60, (double)W / H, 0.5, 200);
  static frame f;
  draw(&b.m, NULL, view, proj, ZS_ALGO_ZBUFFER, ZS_SHADE_OVERDRAW, 0, &f);
  for (int y = 0; y < H; y++) {
    int row = 0;
    for (int x = 0; x < W; x++) row += (int)f.count[y * W + x];
    ck_assert_msg(row == 0 || row == W, "row %d: %d of %d", y, row, W);
    if (y < H / 2) ck_assert_int_eq(row, 0);   /* above the horizon */
    if (y >= H - 5) ck_assert_int_eq(row, W);  /* under the eye */
  }
  mesh_buf t = {0};
  int32_t v[3] = {mb_vert(&t, -1, -1, -0.5), mb_vert(&t, 1, -1, -3), mb_vert(&t, 0, 1, 2)};
  mb_face(&t, v, 3, 0xFFFFFF);
  zs_raster_stats s = draw(&t.m, NULL, view, proj, ZS_ALGO_SCANLINE, ZS_SHADE_OVERDRAW, 0, &f);
  ck_assert_uint_eq(s.polygons_clipped, 1);
  ck_assert_int_le(once_and_convex(&f, "near triangle"), W * H);
  mb_free(&b);
  mb_free(&t);
}
END_TEST

START_TEST(beyond_the_far_plane) {
  mesh_buf b = {0};
  int32_t q[4] = {mb_vert(&b, -5, -5, -30), mb_vert(&b, 5, -5, -30), mb_vert(&b, 5, 5, -30),
                  mb_vert(&b, -5, 5, -30)};
  mb_face(&b, q, 4, 0xFFFFFF);
  double view[16], proj[16];
  zs_mat_identity(view);
  zs_mat_perspective(proj, 60, (double)W / H, 1, 20);
  static frame f;
  zs_raster_stats s = draw(&b.m, NULL, view, proj, ZS_ALGO_ZBUFFER, ZS_SHADE_OVERDRAW, 0, &f);
  ck_assert_uint_eq(s.polygons_outside, 1);
  ck_assert_uint_eq(s.pixels_written, 0);
  mb_free(&b);
}
END_TEST

START_TEST(huge_triangle) {
  /* Vertices at 1e30: the guard band clips it; it covers the screen once. */
  mesh_buf b = {0};
  int32_t v[3] = {mb_vert(&b, -1e30, -1e30, -5), mb_vert(&b, 1e30, -1e30, -5),
                  mb_vert(&b, 0, 1e30, -5)};
  mb_face(&b, v, 3, 0xFFFFFF);
  double view[16], proj[16];
  zs_mat_identity(view);
  zs_mat_perspective(proj, 60, (double)W / H, 1, 20);
  static frame f;
  for (int algo = 0; algo < 2; algo++) {
    draw(&b.m, NULL, view, proj, (zs_algo)algo, ZS_SHADE_OVERDRAW, 0, &f);
    for (int i = 0; i < W * H; i++) ck_assert_uint_eq(f.count[i], 1);
  }
  mb_free(&b);
}
END_TEST

/* ---- depth ---- */

/* Two squares facing the camera, the second one unit of the 32-bit depth
 * behind the first (orthographic: window depth is linear in z). */
START_TEST(one_depth_unit_apart) {
  double znear = 0, zfar = 4294967296.0 / 1024; /* one unit = 1/1024 world */
  mesh_buf b = {0};
  for (int k = 0; k < 2; k++) {
    double z = -(1000.0 + (k ? 1.0 / 1024 : 0.0));
    int32_t q[4] = {mb_vert(&b, 10, 10, z), mb_vert(&b, 100, 10, z), mb_vert(&b, 100, 80, z),
                    mb_vert(&b, 10, 80, z)};
    mb_face(&b, q, 4, 0xFFFFFF);
  }
  /* the far square gets the lower id: depth, not the id, must decide */
  int32_t ids[2] = {1, 0};
  b.m.face_id = ids;
  double view[16], proj[16];
  zs_mat_identity(view);
  zs_mat_ortho(proj, 0, W, 0, H, znear, zfar);
  static frame f;
  for (int algo = 0; algo < 2; algo++) {
    draw(&b.m, NULL, view, proj, (zs_algo)algo, ZS_SHADE_ID, 0, &f);
    int seen = 0;
    for (int i = 0; i < W * H; i++) {
      ck_assert(f.id[i] == ZS_ID_NONE || f.id[i] == 1);
      seen += f.id[i] == 1;
    }
    ck_assert_int_eq(seen, 90 * 70);
  }
  b.m.face_id = NULL;
  mb_free(&b);
}
END_TEST

START_TEST(depth_ranges) {
  /* near 1e-3 to far 1e6 and near 1 to far 1.001: of two parallel squares
   * the nearer wins wherever they overlap, in both modes */
  const double ranges[3][4] = {{1e-3, 1e6, 1.0, 1.01}, {1e-3, 1e6, 5e5, 6e5}, {1.0, 1.001, 1.0002, 1.0007}};
  for (int r = 0; r < 3; r++) {
    mesh_buf b = {0};
    for (int k = 0; k < 2; k++) {
      double d = ranges[r][2 + k], s = 0.3 * d;
      int32_t q[4] = {mb_vert(&b, -s - k * 0.1 * d, -s, -d), mb_vert(&b, s, -s, -d),
                      mb_vert(&b, s, s + k * 0.1 * d, -d), mb_vert(&b, -s, s, -d)};
      mb_face(&b, q, 4, 0xFFFFFF);
    }
    int32_t ids[2] = {1, 0}; /* the far square has the lower id */
    b.m.face_id = ids;
    double view[16], proj[16];
    zs_mat_identity(view);
    zs_mat_perspective(proj, 60, (double)W / H, ranges[r][0], ranges[r][1]);
    static frame f;
    for (int algo = 0; algo < 2; algo++) {
      draw(&b.m, NULL, view, proj, (zs_algo)algo, ZS_SHADE_ID, 0, &f);
      int near_px = 0;
      for (int y = H / 2 - 5; y < H / 2 + 5; y++)
        for (int x = W / 2 - 5; x < W / 2 + 5; x++) near_px += f.id[y * W + x] == 1;
      ck_assert_msg(near_px == 100, "range %d algo %d: nearer square at %d of 100", r, algo, near_px);
    }
    b.m.face_id = NULL;
    mb_free(&b);
  }
}
END_TEST

START_TEST(coplanar_faces_resolved_by_id) {
  /* Overlapping coplanar faces of a tilted plane: the lower id wins every
   * pixel they share, in both modes, whatever the order. */
  mesh_buf b = {0};
  int32_t a[3] = {mb_vert(&b, 5, 5, -1), mb_vert(&b, 100, 10, -3), mb_vert(&b, 20, 90, -2)};
  int32_t c[3] = {mb_vert(&b, 10, 8, 0), mb_vert(&b, 120, 60, 0), mb_vert(&b, 30, 80, 0)};
  /* put c's vertices on a's plane */
  double *p0 = &b.m.pos[0], *p1 = &b.m.pos[3], *p2 = &b.m.pos[6];
  double ux = p1[0] - p0[0], uy = p1[1] - p0[1], uz = p1[2] - p0[2];
  double vx = p2[0] - p0[0], vy = p2[1] - p0[1], vz = p2[2] - p0[2];
  double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
  for (int k = 3; k < 6; k++) {
    double *q = &b.m.pos[3 * k];
    q[2] = p0[2] - (nx * (q[0] - p0[0]) + ny * (q[1] - p0[1])) / nz;
  }
  mb_face(&b, c, 3, 0xFF0000); /* id 0 */
  mb_face(&b, a, 3, 0x00FF00); /* id 1 */
  double view[16], proj[16];
  ortho(view, proj);
  static frame f, g;
  draw(&b.m, NULL, view, proj, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, &f);
  draw(&b.m, NULL, view, proj, ZS_ALGO_SCANLINE, ZS_SHADE_ID, 0, &g);
  ck_assert_int_eq(memcmp(f.id, g.id, sizeof f.id), 0);
  int zero = 0;
  for (int i = 0; i < W * H; i++) zero += f.id[i] == 0;
  ck_assert_int_gt(zero, 1000);
  mb_free(&b);
}
END_TEST

START_TEST(random_scenes_every_mode_agrees) {
  /* Seeded random triangle soups and cameras: zbuffer and scanline agree
   * to the byte, and so does the soup drawn in a shuffled order. */
  const uint64_t seed = 4242;
  zs_rng rng;
  zs_rng_seed(&rng, seed);
  static frame a, c, d;
  for (int t = 0; t < 25; t++) {
    mesh_buf b = {0}, s = {0};
    int n = 50 + (int)zs_rng_below(&rng, 200);
    for (int i = 0; i < 3 * n; i++) {
      double x = zs_rng_range(&rng, -5, 5), y = zs_rng_range(&rng, -5, 5), z = zs_rng_range(&rng, -5, 5);
      mb_vert(&b, x, y, z);
      mb_vert(&s, x, y, z);
    }
    int32_t *perm = malloc((size_t)n * sizeof *perm), *ids = malloc((size_t)n * sizeof *ids);
    for (int i = 0; i < n; i++) perm[i] = i;
    zs_rng_shuffle(&rng, perm, (size_t)n, sizeof *perm);
    for (int i = 0; i < n; i++) {
      int32_t v[3] = {3 * i, 3 * i + 1, 3 * i + 2};
      mb_face(&b, v, 3, (uint32_t)zs_rng_below(&rng, 0x1000000));
    }
    for (int i = 0; i < n; i++) {
      mb_face(&s, &b.m.face_vert[3 * perm[i]], 3, b.m.face_rgb[perm[i]]);
      ids[i] = perm[i];
    }
    s.m.face_id = ids;
    double eye[3], view[16], proj[16];
    eye[0] = zs_rng_range(&rng, -12, 12);
    eye[1] = zs_rng_range(&rng, -12, 12);
    eye[2] = zs_rng_range(&rng, -12, 12);
    double fovy = zs_rng_range(&rng, 20, 120);
    if (!zs_mat_look_at(view, eye, (double[3]){0, 0, 0}, (double[3]){0, 1, 0})) continue;
    zs_mat_perspective(proj, fovy, (double)W / H, 0.1, 40);
    draw(&b.m, NULL, view, proj, ZS_ALGO_ZBUFFER, ZS_SHADE_FLAT, 0, &a);
    draw(&b.m, NULL, view, proj, ZS_ALGO_SCANLINE, ZS_SHADE_FLAT, 0, &c);
    draw(&s.m, NULL, view, proj, ZS_ALGO_ZBUFFER, ZS_SHADE_FLAT, 0, &d);
    ck_assert_msg(memcmp(a.rgb, c.rgb, sizeof a.rgb) == 0, "seed %llu scene %d: modes differ",
                  (unsigned long long)seed, t);
    ck_assert_msg(memcmp(a.rgb, d.rgb, sizeof a.rgb) == 0, "seed %llu scene %d: order matters",
                  (unsigned long long)seed, t);
    free(perm);
    s.m.face_id = NULL;
    free(ids);
    mb_free(&b);
    mb_free(&s);
  }
}
END_TEST

int main(void) {
  Suite *s = suite_create("stress");
  TCase *tc = tcase_create("numerics");
  tcase_set_timeout(tc, 900);
  tcase_add_test(tc, fan_of_100000_slivers);
  tcase_add_test(tc, long_thin_triangles_across_the_screen);
  tcase_add_test(tc, vertices_on_pixel_centres);
  tcase_add_test(tc, far_from_the_origin);
  tcase_add_test(tc, rotated_in_small_steps);
  tcase_add_test(tc, camera_inside_a_closed_object);
  tcase_add_test(tc, grazing_the_near_plane);
  tcase_add_test(tc, beyond_the_far_plane);
  tcase_add_test(tc, huge_triangle);
  tcase_add_test(tc, one_depth_unit_apart);
  tcase_add_test(tc, depth_ranges);
  tcase_add_test(tc, coplanar_faces_resolved_by_id);
  tcase_add_test(tc, random_scenes_every_mode_agrees);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
