/* Hidden-line output: edges of front faces over the paper, hidden edges
 * removed by the depth buffer, back faces' edges never drawn; and the
 * wireframe over the solid: the same edges, over the faces. */
#include <math.h>
#include <string.h>

#include "raster/raster.h"
#include "tests/testutil.h"

enum { W = 64, H = 64 };
static zs_error err;
static uint32_t image[W * H];

static void keep(void *user, const zs_row *row) {
  (void)user;
  memcpy(image + row->y * W, row->rgb, W * 4);
}

/* Draws m and its edges width pixels wide (ortho camera: window x, y =
 * world x, y; width 0: zs_device_draw_edges) into image and returns the
 * number of ink pixels. */
static int ink_wide(const zs_mesh *m, double width) {
  zs_device_config cfg = {W, H, ZS_ALGO_ZBUFFER, ZS_SHADE_FLAT, 0, 1, 0, 0, 0};
  zs_device *d = NULL;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
  double view[16], proj[16];
  zs_mat_identity(view);
  zs_mat_ortho(proj, 0, W, 0, H, 0, 100);
  zs_device_set_camera(d, view, proj);
  zs_device_clear(d);
  ck_assert_int_eq(zs_device_draw(d, m, NULL, 0, ZS_RGB_MESH, &err), ZS_OK);
  ck_assert_int_eq(zs_device_fill_color(d, 0xFFFFFF, &err), ZS_OK);
  if (width == 0.0)
    ck_assert_int_eq(zs_device_draw_edges(d, m, NULL, 0x000000, &err), ZS_OK);
  else
    ck_assert_int_eq(zs_device_draw_wide_edges(d, m, NULL, 0x000000, width, &err), ZS_OK);
  ck_assert_int_eq(zs_device_finish(d, keep, NULL, &err), ZS_OK);
  zs_device_destroy(d);
  int n = 0;
  for (int i = 0; i < W * H; i++) n += image[i] == 0x000000;
  return n;
}

static int ink(const zs_mesh *m) { return ink_wide(m, 0.0); }

static void square(mesh_buf *b, double x0, double y0, double s, double dist, int ccw) {
  int32_t v[4] = {mb_vert(b, x0, y0, -dist), mb_vert(b, x0 + s, y0, -dist),
                  mb_vert(b, x0 + s, y0 + s, -dist), mb_vert(b, x0, y0 + s, -dist)};
  if (!ccw) {
    int32_t t = v[1];
    v[1] = v[3];
    v[3] = t;
  }
  mb_face(b, v, 4, 0x808080);
}

START_TEST(hidden_edges_removed) {
  mesh_buf front = {0}, both = {0};
  square(&front, 10.3, 10.3, 40, 10, 1);
  square(&both, 10.3, 10.3, 40, 10, 1);
  square(&both, 20.3, 20.3, 20, 30, 1); /* wholly behind the first */
  int alone = ink(&front.m);
  ck_assert_int_gt(alone, 4 * 38);
  ck_assert_int_eq(ink(&both.m), alone);
  mb_free(&front);
  mb_free(&both);
}
END_TEST

START_TEST(back_faces_have_no_edges) {
  mesh_buf back = {0}, front = {0};
  square(&back, 10.3, 10.3, 40, 10, 0);
  square(&front, 10.3, 10.3, 40, 10, 1);
  ck_assert_int_eq(ink(&back.m), 0);
  ck_assert_int_gt(ink(&front.m), 0);
  mb_free(&back);
  mb_free(&front);
}
END_TEST

START_TEST(edge_in_front_is_drawn_over) {
  /* a small square in front of a large one: all four of its edges show,
   * and the large one's edges too (nothing hides them) */
  mesh_buf a = {0}, b = {0}, both = {0};
  square(&a, 5.3, 5.3, 50, 30, 1);
  square(&b, 20.3, 20.3, 10, 10, 1);
  square(&both, 5.3, 5.3, 50, 30, 1);
  square(&both, 20.3, 20.3, 10, 10, 1);
  ck_assert_int_eq(ink(&both.m), ink(&a.m) + ink(&b.m));
  mb_free(&a);
  mb_free(&b);
  mb_free(&both);
}
END_TEST

/* Whether image pixel (x, y) is ink by the rule for the square (10.3,
 * 10.3)-(50.3, 50.3) of square() drawn with edges w wide: its two
 * horizontal edges (image y 53.7 and 13.7) paint columns 10 .. 49, its
 * two vertical ones (x 10.3 and 50.3) rows 14 .. 53, each the w pixels
 * across centred on floor() of the exact edge, floor(e - (w - 1) / 2)
 * first. */
static int square_ink(int x, int y, int w) {
  const double across[2][2] = {{53.7, 13.7}, {10.3, 50.3}}; /* rows, columns */
  for (int e = 0; e < 2; e++) {
    const int y0 = (int)floor(across[0][e] - 0.5 * (w - 1));
    const int x0 = (int)floor(across[1][e] - 0.5 * (w - 1));
    if (x >= 10 && x <= 49 && y >= y0 && y < y0 + w) return 1;
    if (y >= 14 && y <= 53 && x >= x0 && x < x0 + w) return 1;
  }
  return 0;
}

/* An edge w pixels wide paints at each step the w pixels across it
 * centred on the one a width-1 edge paints (widths rounded as a line's);
 * width 1 is zs_device_draw_edges, byte for byte; a width out of range is
 * refused. */
START_TEST(wide_edges_paint_the_pixels_across) {
  mesh_buf b = {0};
  square(&b, 10.3, 10.3, 40, 10, 1);
  static uint32_t one[W * H];
  ink(&b.m);
  memcpy(one, image, sizeof one);
  ink_wide(&b.m, 1.0);
  ck_assert_mem_eq(image, one, sizeof one);
  static const double widths[] = {1.0, 2.0, 2.5, 3.0, 4.4};
  static const int rounded[] = {1, 2, 3, 3, 4};
  for (int k = 0; k < 5; k++) {
    ink_wide(&b.m, widths[k]);
    int wrong = 0;
    for (int y = 0; y < H; y++)
      for (int x = 0; x < W; x++)
        wrong += (image[y * W + x] == 0x000000) != square_ink(x, y, rounded[k]);
    ck_assert_msg(wrong == 0, "width %g: %d pixels against the rule", widths[k], wrong);
  }
  zs_device_config cfg = {W, H, ZS_ALGO_ZBUFFER, ZS_SHADE_FLAT, 0, 1, 0, 0, 0};
  zs_device *d = NULL;
  ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
  static const double bad[] = {0.0, -1.0, 64.5, NAN};
  static const char *const said[] = {"edges: width 0: expected above 0 and at most 64",
                                     "edges: width -1: expected above 0 and at most 64",
                                     "edges: width 64.5: expected above 0 and at most 64",
                                     "edges: width nan: expected above 0 and at most 64"};
  for (int k = 0; k < 4; k++) {
    zs_error_clear(&err);
    ck_assert_int_eq(zs_device_draw_wide_edges(d, &b.m, NULL, 0, bad[k], &err), ZS_ERR_ARG);
    ck_assert_str_eq(err.msg, said[k]);
  }
  zs_device_destroy(d);
  mb_free(&b);
}
END_TEST

/* Every pixel of the wireframe over the solid is the hidden-line image's
 * ink where that has ink, and the solid frame's everywhere else: the same
 * edges, offset the same way, none stitched through by its face. */
START_TEST(wireframe_is_the_hidden_lines_over_the_solid) {
  zs_scene *s = NULL;
  ck_assert_int_eq(zs_scene_load("builtin:cubes?n=3", NULL, &s, &err), ZS_OK);
  static const zs_shade shades[] = {ZS_SHADE_FLAT, ZS_SHADE_PHONG, ZS_SHADE_FLAT};
  static const double widths[] = {0.0, 0.0, 3.0}; /* both styles take the width */
  size_t thin_ink = 0;
  for (int k = 0; k < 3; k++) {
    zs_render_opts o = {0};
    o.width = 200, o.height = 150;
    o.line_width = widths[k];
    zs_image lines, solid, wire;
    o.hidden_line = 1;
    ck_assert_int_eq(zs_render(s, &o, &lines, NULL, NULL, &err), ZS_OK);
    o.hidden_line = 0, o.shade = shades[k];
    ck_assert_int_eq(zs_render(s, &o, &solid, NULL, NULL, &err), ZS_OK);
    o.wireframe = 1;
    ck_assert_int_eq(zs_render(s, &o, &wire, NULL, NULL, &err), ZS_OK);
    size_t ink = 0, bad = 0;
    for (size_t i = 0; i < 200 * 150; i++) {
      const int inked = lines.rgb[i] == 0x000000;
      ink += inked;
      bad += wire.rgb[i] != (inked ? 0x000000u : solid.rgb[i]);
    }
    ck_assert_uint_gt(ink, 1000);
    ck_assert_msg(bad == 0, "%s, width %g: %zu pixels are neither", zs_shade_name(shades[k]),
                  widths[k], bad);
    if (k == 0) thin_ink = ink;
    if (k == 2) ck_assert_uint_gt(ink, 2 * thin_ink); /* three pixels across, less overlaps */
    zs_image_free(&lines);
    zs_image_free(&solid);
    zs_image_free(&wire);
  }
  zs_render_opts both = {0};
  zs_image im;
  both.hidden_line = both.wireframe = 1;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_render(s, &both, &im, NULL, NULL, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "zs_render_opts: hidden_line and wireframe: one style");
  zs_scene_destroy(s);
}
END_TEST

int main(void) {
  Suite *s = suite_create("lines");
  TCase *tc = tcase_create("hidden-line");
  tcase_add_test(tc, hidden_edges_removed);
  tcase_add_test(tc, back_faces_have_no_edges);
  tcase_add_test(tc, edge_in_front_is_drawn_over);
  tcase_add_test(tc, wide_edges_paint_the_pixels_across);
  tcase_add_test(tc, wireframe_is_the_hidden_lines_over_the_solid);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
