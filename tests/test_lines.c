/* Hidden-line output: edges of front faces over the paper, hidden edges
 * removed by the depth buffer, back faces' edges never drawn; and the
 * wireframe over the solid: the same edges, over the faces. */
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

/* Draws m and its edges (ortho camera: window x, y = world x, y) and
 * returns the number of ink pixels. */
static int ink(const zs_mesh *m) {
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
  ck_assert_int_eq(zs_device_draw_edges(d, m, NULL, 0x000000, &err), ZS_OK);
  ck_assert_int_eq(zs_device_finish(d, keep, NULL, &err), ZS_OK);
  zs_device_destroy(d);
  int n = 0;
  for (int i = 0; i < W * H; i++) n += image[i] == 0x000000;
  return n;
}

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

/* Every pixel of the wireframe over the solid is the hidden-line image's
 * ink where that has ink, and the solid frame's everywhere else: the same
 * edges, offset the same way, none stitched through by its face. */
START_TEST(wireframe_is_the_hidden_lines_over_the_solid) {
  zs_scene *s = NULL;
  ck_assert_int_eq(zs_scene_load("builtin:cubes?n=3", NULL, &s, &err), ZS_OK);
  static const zs_shade shades[] = {ZS_SHADE_FLAT, ZS_SHADE_PHONG};
  for (int k = 0; k < 2; k++) {
    zs_render_opts o = {0};
    o.width = 200, o.height = 150;
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
    ck_assert_msg(bad == 0, "%s: %zu pixels are neither", zs_shade_name(shades[k]), bad);
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
  tcase_add_test(tc, wireframe_is_the_hidden_lines_over_the_solid);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
