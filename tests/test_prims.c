/* Lines and points with a width (zs_device_draw_lines, _points): GL's
 * rules pixel for pixel on lines and points placed by hand, the depth test
 * against faces in either order, the loaders, and every refusal. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lib/input.h"
#include "scene/load_obj.h"
#include "lib/scene_draw.h"
#include "raster/raster.h"
#include "tests/testutil.h"

enum { W = 16, H = 16 };

/* A device of W x H whose camera maps world (x, y) to window pixels (y
 * up) and world z in [-1, -100] to depth. */
static zs_device *pixel_device(zs_algo algo) {
  zs_device_config cfg = {.width = W, .height = H, .algo = algo, .shade = ZS_SHADE_ID, .threads = 1};
  zs_device *d = NULL;
  zs_error err;
  ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
  double view[16], proj[16];
  zs_mat_identity(view);
  zs_mat_ortho(proj, 0, W, 0, H, 0, 100);
  zs_device_clear(d);
  zs_device_set_camera(d, view, proj);
  return d;
}

static void keep_ids(void *user, const zs_row *row) {
  uint32_t *ids = user;
  memcpy(ids + (size_t)row->y * W, row->id, W * sizeof *ids);
}

static void finish_ids(zs_device *d, uint32_t ids[W * H]) {
  zs_error err;
  ck_assert_int_eq(zs_device_finish(d, keep_ids, ids, &err), ZS_OK);
}

/* The image as rows of '.' (nothing) and '#' (id), for messages. */
static void expect(const uint32_t ids[W * H], const char *const want[H], uint32_t id) {
  char got[H * (W + 1) + 1], exp[H * (W + 1) + 1];
  for (int y = 0; y < H; y++) {
    for (int x = 0; x < W; x++) {
      got[y * (W + 1) + x] = ids[y * W + x] == id ? '#' : ids[y * W + x] == ZS_ID_NONE ? '.' : '?';
      exp[y * (W + 1) + x] = want[y][x];
    }
    got[y * (W + 1) + W] = exp[y * (W + 1) + W] = '\n';
  }
  got[H * (W + 1)] = exp[H * (W + 1)] = '\0';
  ck_assert_msg(strcmp(got, exp) == 0, "got\n%s\nwant\n%s", got, exp);
}

/* A line from (2.3, 8.4) to (12.6, 8.4), 3 wide: image y 7.6, rows whose
 * centres lie in (6.1, 9.1]; the start is before its column's centre, so
 * column 2 is drawn; the end lies inside its pixel's diamond, so column
 * 12 is not. */
START_TEST(wide_line_follows_gl) {
  zs_device *d = pixel_device(ZS_ALGO_ZBUFFER);
  double pos[] = {2.3, 8.4, -5, 12.6, 8.4, -5};
  int32_t lv[] = {0, 1};
  zs_mesh m = {.pos = pos, .nverts = 2, .line_vert = lv, .nlines = 1, .prim_id = 7};
  double model[16];
  zs_mat_identity(model);
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_draw_lines(d, &m, model, 100, ZS_RGB_MESH, 3.0, &err), ZS_OK);
  uint32_t ids[W * H];
  finish_ids(d, ids);
  static const char *const want[H] = {
      "................", "................", "................", "................",
      "................", "................", "..##########....", "..##########....",
      "..##########....", "................", "................", "................",
      "................", "................", "................", "................"};
  expect(ids, want, 107);
  zs_device_destroy(d);
}
END_TEST

/* A steep line is y-major: the width runs across x, left side included;
 * 2.6 is GL's 3 (halves and above round up). */
START_TEST(y_major_line_takes_its_width_across_x) {
  zs_device *d = pixel_device(ZS_ALGO_ZBUFFER);
  double pos[] = {6.0, 2.2, -5, 6.0, 13.7, -5};
  int32_t lv[] = {0, 1};
  zs_mesh m = {.pos = pos, .nverts = 2, .line_vert = lv, .nlines = 1};
  double model[16];
  zs_mat_identity(model);
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_draw_lines(d, &m, model, 0, ZS_RGB_MESH, 2.6, &err), ZS_OK);
  uint32_t ids[W * H];
  finish_ids(d, ids);
  /* x 6: centres in [4.5, 7.5): columns 4, 5, 6.  Window y 2.2 to 13.7
   * runs up the image from y 13.8 to 2.3: the start's row 13 is drawn
   * (13.8 lies before its centre 13.5), and so is the end's row 2 (2.3
   * lies past its centre 2.5, and outside its diamond: x 6.0 is half a
   * pixel from every centre) */
  static const char *const want[H] = {
      "................", "................", "....###.........", "....###.........",
      "....###.........", "....###.........", "....###.........", "....###.........",
      "....###.........", "....###.........", "....###.........", "....###.........",
      "....###.........", "....###.........", "................", "................"};
  expect(ids, want, 0);
  zs_device_destroy(d);
}
END_TEST

/* Squares: an odd size centred on the pixel the point is in, an even one
 * on the nearest corner; a disc of 5 keeps the 21 centres within 2.5. */
START_TEST(points_are_squares_or_discs) {
  double pos[] = {3.2, 12.9, -5, 9.5, 9.5, -5, 8.5, 3.5, -5};
  int32_t pv[] = {0, 1, 2};
  zs_mesh m = {.pos = pos, .nverts = 3, .point_vert = pv, .npoints = 2};
  double model[16];
  zs_mat_identity(model);
  zs_error err;
  zs_error_clear(&err);
  zs_device *d = pixel_device(ZS_ALGO_ZBUFFER);
  ck_assert_int_eq(zs_device_draw_points(d, &m, model, 0, ZS_RGB_MESH, 3, ZS_POINT_SQUARE, &err),
                   ZS_OK);
  uint32_t ids[W * H];
  finish_ids(d, ids);
  /* (3.2, 12.9): pixel (3, 12) window, image row 3, the 3 x 3 about it;
   * (9.5, 9.5) exactly on a centre: image (9.5, 6.5), x in (8, 11], y
   * in [5, 8): columns 8..10, rows 5..7 */
  static const char *const squares[H] = {
      "................", "................", "..###...........", "..###...........",
      "..###...........", "........###.....", "........###.....", "........###.....",
      "................", "................", "................", "................",
      "................", "................", "................", "................"};
  for (int i = 0; i < W * H; i++)
    if (ids[i] == 1) ids[i] = 0; /* one id for the picture */
  expect(ids, squares, 0);
  zs_device_destroy(d);

  d = pixel_device(ZS_ALGO_ZBUFFER);
  m.point_vert = &pv[2];
  m.npoints = 1;
  ck_assert_int_eq(zs_device_draw_points(d, &m, model, 0, ZS_RGB_MESH, 5, ZS_POINT_DISC, &err),
                   ZS_OK);
  finish_ids(d, ids);
  static const char *const disc[H] = {
      "................", "................", "................", "................",
      "................", "................", "................", "................",
      "................", "................", ".......###......", "......#####.....",
      "......#####.....", "......#####.....", ".......###......", "................"};
  expect(ids, disc, 0);
  zs_device_destroy(d);
}
END_TEST

/* A square face at depth -10 and a line through it, half in front and
 * half behind: the same pixels whichever is drawn first, the line hidden
 * where it is behind. */
START_TEST(lines_and_faces_share_the_depth_test) {
  double pos[] = {4, 4, -10, 12, 4, -10, 12, 12, -10, 4, 12, -10, 1.5, 8.5, -5, 14.5, 8.5, -15};
  int32_t start[] = {0, 4}, fv[] = {0, 1, 2, 3}, lv[] = {4, 5};
  zs_mesh face = {.pos = pos, .nverts = 6, .face_start = start, .face_vert = fv, .nfaces = 1};
  zs_mesh line = {.pos = pos, .nverts = 6, .line_vert = lv, .nlines = 1, .prim_id = 1};
  double model[16];
  zs_mat_identity(model);
  zs_error err;
  zs_error_clear(&err);
  uint32_t a[W * H], b[W * H];
  zs_device *d = pixel_device(ZS_ALGO_ZBUFFER);
  ck_assert_int_eq(zs_device_draw(d, &face, model, 0, ZS_RGB_MESH, &err), ZS_OK);
  ck_assert_int_eq(zs_device_draw_lines(d, &line, model, 0, ZS_RGB_MESH, 1, &err), ZS_OK);
  finish_ids(d, a);
  zs_device_destroy(d);
  d = pixel_device(ZS_ALGO_ZBUFFER);
  ck_assert_int_eq(zs_device_draw_lines(d, &line, model, 0, ZS_RGB_MESH, 1, &err), ZS_OK);
  ck_assert_int_eq(zs_device_draw(d, &face, model, 0, ZS_RGB_MESH, &err), ZS_OK);
  finish_ids(d, b);
  zs_device_destroy(d);
  ck_assert_mem_eq(a, b, sizeof a);
  /* row 7 (image): the line from x 1 to 14; in front of the face on its
   * left half, behind it on its right */
  ck_assert_uint_eq(a[7 * W + 2], 1);
  ck_assert_uint_eq(a[7 * W + 5], 1);
  ck_assert_uint_eq(a[7 * W + 10], 0);
  ck_assert_uint_eq(a[7 * W + 13], 1);
  ck_assert_uint_eq(a[7 * W + 15], ZS_ID_NONE);
}
END_TEST

/* A line whose start lies inside its pixel's diamond, past the column's
 * centre, at the near plane: that column's depth is the line's extended
 * back to the centre, kept at 0, never wrapped round to far. */
START_TEST(extended_depth_stays_in_range) {
  zs_device *d = pixel_device(ZS_ALGO_ZBUFFER);
  double pos[] = {2.6, 8.5, 0, 12.3, 8.5, -50};
  int32_t lv[] = {0, 1};
  zs_mesh m = {.pos = pos, .nverts = 2, .line_vert = lv, .nlines = 1};
  double model[16];
  zs_mat_identity(model);
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_draw_lines(d, &m, model, 0, ZS_RGB_MESH, 1, &err), ZS_OK);
  const uint32_t *depth = zs_device_depth_buffer(d);
  ck_assert_uint_eq(depth[7 * W + 2], 0);
  ck_assert_uint_lt(depth[7 * W + 3], depth[7 * W + 4]);
  zs_device_destroy(d);
}
END_TEST

/* Two lines crossing at one depth: the lower id wins the crossing in
 * either order of drawing. */
START_TEST(crossing_lines_tie_by_id) {
  double pos[] = {1.5, 8.5, -5, 14.5, 8.5, -5, 8.5, 1.5, -5, 8.5, 14.5, -5};
  int32_t la[] = {0, 1}, lb[] = {2, 3};
  zs_mesh a = {.pos = pos, .nverts = 4, .line_vert = la, .nlines = 1};
  zs_mesh b = {.pos = pos, .nverts = 4, .line_vert = lb, .nlines = 1};
  double model[16];
  zs_mat_identity(model);
  zs_error err;
  zs_error_clear(&err);
  uint32_t one[W * H], two[W * H];
  zs_device *d = pixel_device(ZS_ALGO_ZBUFFER);
  ck_assert_int_eq(zs_device_draw_lines(d, &a, model, 3, ZS_RGB_MESH, 2, &err), ZS_OK);
  ck_assert_int_eq(zs_device_draw_lines(d, &b, model, 9, ZS_RGB_MESH, 2, &err), ZS_OK);
  finish_ids(d, one);
  zs_device_destroy(d);
  d = pixel_device(ZS_ALGO_ZBUFFER);
  ck_assert_int_eq(zs_device_draw_lines(d, &b, model, 9, ZS_RGB_MESH, 2, &err), ZS_OK);
  ck_assert_int_eq(zs_device_draw_lines(d, &a, model, 3, ZS_RGB_MESH, 2, &err), ZS_OK);
  finish_ids(d, two);
  zs_device_destroy(d);
  ck_assert_mem_eq(one, two, sizeof one);
  ck_assert_uint_eq(one[7 * W + 8], 3);
}
END_TEST

START_TEST(bad_widths_sizes_and_modes_refused) {
  double pos[] = {1, 1, -5, 9, 9, -5};
  int32_t lv[] = {0, 1}, bad[] = {0, 2};
  zs_mesh m = {.pos = pos, .nverts = 2, .line_vert = lv, .nlines = 1, .point_vert = lv, .npoints = 2};
  double model[16];
  zs_mat_identity(model);
  zs_error err;
  zs_error_clear(&err);
  zs_device *d = pixel_device(ZS_ALGO_ZBUFFER);
  const double widths[] = {0.0, -1.0, 64.5, NAN, INFINITY};
  for (size_t i = 0; i < sizeof widths / sizeof widths[0]; i++) {
    zs_error_clear(&err);
    ck_assert_int_eq(zs_device_draw_lines(d, &m, model, 0, ZS_RGB_MESH, widths[i], &err), ZS_ERR_ARG);
    ck_assert_msg(strstr(err.msg, "lines: width ") && strstr(err.msg, "at most 64"), "%s", err.msg);
    zs_error_clear(&err);
    ck_assert_int_eq(zs_device_draw_points(d, &m, model, 0, ZS_RGB_MESH, widths[i],
                                           ZS_POINT_SQUARE, &err), ZS_ERR_ARG);
    ck_assert_msg(strstr(err.msg, "points: size "), "%s", err.msg);
  }
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_draw_points(d, &m, model, 0, ZS_RGB_MESH, 2, (zs_point_shape)7, &err),
                   ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "points: shape 7: expected ZS_POINT_SQUARE or _DISC");
  m.line_vert = bad;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_draw_lines(d, &m, model, 0, ZS_RGB_MESH, 1, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "lines: line 0 uses vertex 2 of 2");
  zs_device_destroy(d);
  d = pixel_device(ZS_ALGO_DEPTHSORT);
  m.line_vert = lv;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_draw_lines(d, &m, model, 0, ZS_RGB_MESH, 1, &err), ZS_ERR_UNSUPPORTED);
  ck_assert_str_eq(err.msg, "lines need the zbuffer or scanline mode");
  zs_device_destroy(d);
}
END_TEST

/* OBJ's l and p, a PLY point cloud: loaded as lines and points, numbered
 * after the faces, in their material's or vertex's colour. */
START_TEST(models_bring_their_lines_and_points) {
  zs_scene s;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_input_load_scene(zs_test_src("tests/data/scenes/wire_cube.obj"), &s, &err) == ZS_OK,
                "%s", err.msg);
  int32_t lines = 0, points = 0;
  for (int32_t i = 0; i < s.ninst; i++) {
    const zs_mesh *m = &s.meshes[s.inst[i].mesh].mesh;
    lines += m->nlines;
    points += m->npoints;
    if (m->nlines) {
      ck_assert_int_eq(m->prim_id, 6); /* after the cube's six faces */
      ck_assert_uint_eq(m->line_rgb[0], 0xF2BF33u); /* Kd 0.95 0.75 0.2 */
    }
  }
  ck_assert_int_eq(lines, 48);
  ck_assert_int_eq(points, 8);
  ck_assert(zs_scene_has_prims(&s));
  zs_scene_free(&s);
#ifdef ZS_HAVE_ASSIMP
  zs_error_clear(&err);
  ck_assert_msg(zs_input_load_scene(zs_test_src("tests/data/models/cloud.ply"), &s, &err) == ZS_OK,
                "%s", err.msg);
  const zs_mesh *m = &s.meshes[s.inst[0].mesh].mesh;
  ck_assert_int_eq(m->npoints, 600);
  ck_assert_int_eq(m->nfaces, 0);
  zs_scene_free(&s);
#endif
}
END_TEST

START_TEST(bad_obj_lines_refused) {
  static const struct {
    const char *text, *why;
  } cases[] = {
      {"v 0 0 0\nv 1 0 0\nl 1\n", "obj:3: line with 1 vertices (at least 2 needed)"},
      {"v 0 0 0\nv 1 0 0\nl 1 3\n", "obj:3: vertex index 3 out of range"},
      {"v 0 0 0\np\n", "obj:2: point statement without a vertex"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    zs_model m;
    zs_error err;
    zs_error_clear(&err);
    ck_assert_int_eq(zs_obj_parse(cases[i].text, strlen(cases[i].text), "obj", NULL, &m, &err),
                     ZS_ERR_PARSE);
    ck_assert_msg(strstr(err.msg, cases[i].why), "%s (want %s)", err.msg, cases[i].why);
  }
}
END_TEST

/* The command: the widths from the options, and the modes that cannot
 * draw lines refused with the input named, no image written. */
START_TEST(render_command_draws_and_refuses) {
  static char out[1 << 14], err[1 << 12];
  char png[4096];
  snprintf(png, sizeof png, "%s/prims-wire.png", ZS_BINARY_DIR);
  const char *in = zs_test_src("tests/data/scenes/wire_cube.obj");
  unlink(png);
  const char *bad[] = {"render", in, "--algo", "depthsort", "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(bad, out, sizeof out, err, sizeof err), 1);
  char want[4200];
  snprintf(want, sizeof want, "zscan render: %s: lines and points need --algo zbuffer or scanline\n", in);
  ck_assert_str_eq(err, want);
  ck_assert(!zs_test_exists(png));
  const char *thin[] = {"render", in, "--size", "64x48", "-o", png, "--stats", NULL};
  const char *wide[] = {"render", in, "--size", "64x48", "-o", png, "--stats", "--line-width",
                        "4", "--point-size", "6", NULL};
  ck_assert_int_eq(zs_test_run_zscan(thin, out, sizeof out, err, sizeof err), 0);
  const char *h = strstr(out, "\"image_hash\"");
  ck_assert_ptr_nonnull(h);
  char first[64];
  snprintf(first, sizeof first, "%.31s", h); /* "image_hash":"<16 hex digits>" */
  ck_assert_int_eq(zs_test_run_zscan(wide, out, sizeof out, err, sizeof err), 0);
  ck_assert_ptr_null(strstr(out, first)); /* wider lines, another image */
  /* the default width and size (1) hold on every path of the command:
   * a layer written beside the image, and a culled walk's frame */
  char zsl[4096];
  snprintf(zsl, sizeof zsl, "%s/prims-wire.zsl", ZS_BINARY_DIR);
  const char *layer[] = {"render", in, "--size", "64x48", "-o", png, "--stats", "--layer", zsl, NULL};
  const char *culled[] = {"render", in, "--size", "64x48", "-o", png, "--stats", "--cull", "chc", NULL};
  const char *const *paths[] = {layer, culled};
  for (int k = 0; k < 2; k++) {
    ck_assert_msg(zs_test_run_zscan(paths[k], out, sizeof out, err, sizeof err) == 0, "%s", err);
    ck_assert_msg(strstr(out, first) != NULL, "%s: another image than the plain render's",
                  paths[k][7]);
  }
  unlink(zsl);
  unlink(png);
}
END_TEST

/* Scanline mode draws a model's lines and points into its rows at
 * finish (raster/prim_rows.h): the image, its depth and the pixels
 * written are zbuffer mode's, on one thread and on three (bands of rows),
 * at each width and size, over faces, and anti-aliased. */
START_TEST(scanline_mode_draws_them_as_zbuffer_mode) {
  zs_error err;
  zs_error_clear(&err);
  zs_scene *scene;
  ck_assert_int_eq(zs_scene_load(zs_test_src("tests/data/scenes/wire_cube.obj"), NULL, &scene,
                                 &err), ZS_OK);
  static const double widths[] = {1, 3, 8};
  for (int w = 0; w < 3; w++)
    for (int samples = 1; samples <= 4; samples += 3) {
      zs_image im[3];
      zs_raster_stats st[3];
      for (int k = 0; k < 3; k++) {
        zs_render_opts o = {0};
        o.width = 96;
        o.height = 72;
        o.algo = k ? ZS_ALGO_SCANLINE : ZS_ALGO_ZBUFFER;
        o.threads = k == 2 ? 3 : 1;
        o.line_width = widths[w];
        o.point_size = widths[w] + 1;
        o.samples = samples;
        ck_assert_msg(zs_render(scene, &o, &im[k], NULL, &st[k], &err) == ZS_OK, "%s", err.msg);
      }
      for (int k = 1; k < 3; k++) {
        ck_assert_mem_eq(im[k].rgb, im[0].rgb, 96 * 72 * sizeof *im[0].rgb);
        ck_assert_uint_eq(st[k].pixels_written, st[0].pixels_written);
      }
      for (int k = 0; k < 3; k++) zs_image_free(&im[k]);
    }
  zs_scene_destroy(scene);
}
END_TEST

int main(void) {
  Suite *s = suite_create("prims");
  TCase *tc = tcase_create("prims");
  tcase_add_test(tc, wide_line_follows_gl);
  tcase_add_test(tc, y_major_line_takes_its_width_across_x);
  tcase_add_test(tc, points_are_squares_or_discs);
  tcase_add_test(tc, lines_and_faces_share_the_depth_test);
  tcase_add_test(tc, crossing_lines_tie_by_id);
  tcase_add_test(tc, extended_depth_stays_in_range);
  tcase_add_test(tc, bad_widths_sizes_and_modes_refused);
  tcase_add_test(tc, models_bring_their_lines_and_points);
  tcase_add_test(tc, bad_obj_lines_refused);
  tcase_add_test(tc, render_command_draws_and_refuses);
  tcase_add_test(tc, scanline_mode_draws_them_as_zbuffer_mode);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
