/* Shadow maps: a shadow falls where the geometry puts it, takes away only
 * the light that casts it, has no acne on a lit plane at the default bias,
 * and the refusals of bad maps and options.  (The same bytes in every
 * mode, thread count, SIMD level and draw order: test_golden's shadow
 * cases.) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/frame_camera.h"
#include "lib/shadow.h"
#include "tests/testutil.h"

static zs_error err;

static zs_scene *load(const char *rel) {
  zs_scene *s = NULL;
  zs_error_clear(&err);
  ck_assert_msg(zs_scene_load(zs_test_src(rel), NULL, &s, &err) == ZS_OK, "%s", err.msg);
  return s;
}

static zs_image render(const zs_scene *s, const zs_render_opts *o) {
  zs_image im = {0, 0, NULL};
  zs_error_clear(&err);
  ck_assert_msg(zs_render(s, o, &im, NULL, NULL, &err) == ZS_OK, "%s", err.msg);
  return im;
}

/* The pixel world point p falls in, for scene s's own camera. */
static size_t pixel_of(const zs_scene *s, int w, int h, const double p[3]) {
  double view[16], proj[16], vp[16], c[4];
  zs_error_clear(&err);
  ck_assert_int_eq(zs_frame_camera(s, &s->camera, w, h, view, proj, &err), ZS_OK);
  zs_mat_mul(vp, proj, view);
  zs_mat_apply(vp, p, c);
  const int x = (int)((c[0] / c[3] + 1.0) * 0.5 * w), y = (int)((1.0 - c[1] / c[3]) * 0.5 * h);
  ck_assert(x >= 0 && x < w && y >= 0 && y < h);
  return (size_t)y * (size_t)w + (size_t)x;
}

static int channel(uint32_t rgb, int k) { return (int)(rgb >> (16 - 8 * k) & 0xFF); }

/* A tile 3 units above a floor under a light straight down: its shadow is
 * the square below it, as dark as the ambient light alone; a lit pixel is
 * as the frame without shadows has it; no pixel darker than ambient alone
 * or brighter than unshadowed; a penumbra of the 3 x 3 filter at the edge. */
START_TEST(shadow_falls_below_the_tile) {
  zs_scene *s = load("tests/data/scenes/shadow_probe.json");
  zs_light unshadowed[2], ambient = s->lights[1];
  memcpy(unshadowed, s->lights, sizeof unshadowed);
  unshadowed[0].shadow = 0;
  zs_render_opts o = {0};
  const zs_image lit = render(s, &o);
  o.lights = unshadowed, o.nlights = 2;
  const zs_image bright = render(s, &o);
  o.lights = &ambient, o.nlights = 1;
  const zs_image dark = render(s, &o);
  const int w = lit.width, h = lit.height;
  size_t umbra = 0, penumbra = 0;
  for (size_t i = 0; i < (size_t)w * (size_t)h; i++) {
    const uint32_t a = lit.rgb[i], b = bright.rgb[i], c = dark.rgb[i];
    for (int k = 0; k < 3; k++)
      ck_assert_msg(channel(a, k) >= channel(c, k) && channel(a, k) <= channel(b, k),
                    "pixel %zu: %06x not between ambient %06x and unshadowed %06x", i, a, c, b);
    umbra += a == c && a != b;
    penumbra += a != b && a != c;
  }
  /* the floor at the tile's centre and at its corner's shadow, inside and
   * out; the tile's own top, lit */
  const double centre[3] = {0, 0, 0}, inside[3] = {0.8, 0, 0.8}, outside[3] = {1.3, 0, 1.3},
               far[3] = {3.5, 0, 3.5}, top[3] = {0, 3.1, 0};
  ck_assert_uint_eq(lit.rgb[pixel_of(s, w, h, centre)], dark.rgb[pixel_of(s, w, h, centre)]);
  ck_assert_uint_eq(lit.rgb[pixel_of(s, w, h, inside)], dark.rgb[pixel_of(s, w, h, inside)]);
  ck_assert_uint_eq(lit.rgb[pixel_of(s, w, h, outside)], bright.rgb[pixel_of(s, w, h, outside)]);
  ck_assert_uint_eq(lit.rgb[pixel_of(s, w, h, far)], bright.rgb[pixel_of(s, w, h, far)]);
  ck_assert_uint_eq(lit.rgb[pixel_of(s, w, h, top)], bright.rgb[pixel_of(s, w, h, top)]);
  ck_assert_uint_ne(lit.rgb[pixel_of(s, w, h, centre)], bright.rgb[pixel_of(s, w, h, centre)]);
  ck_assert_uint_gt(umbra, 300);
  ck_assert_uint_gt(penumbra, 0);
  ck_assert_uint_lt(penumbra, umbra / 4);
  /* a coarser map widens the filter's penumbra: 3 texels of 64 */
  o.lights = NULL, o.nlights = 0, o.shadow_size = 64;
  const zs_image coarse = render(s, &o);
  size_t coarse_penumbra = 0;
  for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
    coarse_penumbra += coarse.rgb[i] != bright.rgb[i] && coarse.rgb[i] != dark.rgb[i];
  ck_assert_msg(coarse_penumbra > 5 * penumbra, "penumbra: %zu pixels at 64 texels, %zu at 1024",
                coarse_penumbra, penumbra);
  o.shadow_size = 0;

  /* under a slanting light, without a bias the lit floor shadows itself
   * (acne): many more pixels change than the tile's shadow */
  unshadowed[0].direction[0] = 0.6, unshadowed[0].direction[2] = 0.4;
  zs_light slant[2] = {unshadowed[0], unshadowed[1]};
  slant[0].shadow = 1;
  o.lights = unshadowed, o.nlights = 2;
  const zs_image slant_bright = render(s, &o);
  o.lights = slant;
  const zs_image slant_lit = render(s, &o);
  o.has_shadow_bias = 1;
  const zs_image acne = render(s, &o);
  size_t slant_changed = 0, acne_changed = 0;
  for (size_t i = 0; i < (size_t)w * (size_t)h; i++) {
    slant_changed += slant_lit.rgb[i] != slant_bright.rgb[i];
    acne_changed += acne.rgb[i] != slant_bright.rgb[i];
  }
  printf("shadow: umbra %zu, penumbra %zu (%zu at 64 texels); slanting: %zu changed, %zu without a bias\n",
         umbra, penumbra, coarse_penumbra, slant_changed, acne_changed);
  ck_assert_uint_gt(slant_changed, 300);
  ck_assert_msg(acne_changed > 2 * slant_changed, "%zu pixels with no bias, %zu with the default",
                acne_changed, slant_changed);
  zs_image_free((zs_image *)&coarse);
  zs_image_free((zs_image *)&slant_bright);
  zs_image_free((zs_image *)&slant_lit);
  zs_image_free((zs_image *)&lit);
  zs_image_free((zs_image *)&bright);
  zs_image_free((zs_image *)&dark);
  zs_image_free((zs_image *)&acne);
  zs_scene_destroy(s);
}
END_TEST

/* A spot light low over a floor that reaches behind it: the floor's
 * corners lie behind the light's eye (w <= 0 in its clip space), and its
 * bias still holds its slope, so the lit floor is as without shadows. */
START_TEST(plane_behind_a_spot_does_not_shadow_itself) {
  zs_scene *s = load("tests/data/scenes/spot_over_floor.json");
  zs_light unmarked[2];
  memcpy(unmarked, s->lights, sizeof unmarked);
  ck_assert(unmarked[0].shadow);
  unmarked[0].shadow = 0;
  zs_render_opts o = {0};
  const zs_image shadowed = render(s, &o);
  o.lights = unmarked, o.nlights = 2;
  const zs_image plain = render(s, &o);
  zs_diff_result d;
  ck_assert_int_eq(zs_image_diff(&shadowed, &plain, NULL, &d, &err), ZS_OK);
  ck_assert_msg(d.differing == 0, "%llu pixels of the floor shadow it", (unsigned long long)d.differing);
  zs_image_free((zs_image *)&shadowed);
  zs_image_free((zs_image *)&plain);
  zs_scene_destroy(s);
}
END_TEST

/* --shadows on a scene without lights: the key light, casting; the same
 * bytes as that light given by hand and marked. */
START_TEST(key_light_of_a_scene_without_lights) {
  zs_scene *s = NULL;
  ck_assert_int_eq(zs_scene_load("builtin:default", NULL, &s, &err), ZS_OK);
  zs_render_opts o = {0};
  o.width = 160, o.height = 120, o.shadows = 1;
  const zs_image a = render(s, &o);
  zs_light key[2];
  ck_assert_int_eq(zs_lights_key(key), 2);
  ck_assert(key[0].shadow && key[0].eye_space && key[1].kind == ZS_LIGHT_AMBIENT);
  o.shadows = 0, o.lights = key, o.nlights = 2;
  const zs_image b = render(s, &o);
  ck_assert_uint_eq(zs_image_hash(&a), zs_image_hash(&b));
  key[0].shadow = 0;
  const zs_image c = render(s, &o);
  zs_diff_result d;
  ck_assert_int_eq(zs_image_diff(&a, &c, NULL, &d, &err), ZS_OK);
  ck_assert_uint_gt(d.differing, 200); /* the teapots' shadows on the floor */
  zs_image_free((zs_image *)&a);
  zs_image_free((zs_image *)&b);
  zs_image_free((zs_image *)&c);
  zs_scene_destroy(s);
}
END_TEST

/* A directional light's map holds the bounds whole; a spot's camera sits
 * at the light; a point light has none. */
START_TEST(shadow_cameras_hold_the_bounds) {
  const double lo[3] = {-3, -1, -2}, hi[3] = {5, 2, 4};
  zs_light l[3];
  memset(l, 0, sizeof l);
  l[0].kind = ZS_LIGHT_DIRECTIONAL;
  l[0].direction[0] = 1, l[0].direction[1] = -2, l[0].direction[2] = -0.5;
  l[1].kind = ZS_LIGHT_SPOT;
  l[1].position[1] = 9, l[1].direction[1] = -1, l[1].inner_deg = 20, l[1].outer_deg = 40;
  l[2].kind = ZS_LIGHT_POINT;
  double id[16], v[16], p[16], vp[16];
  zs_mat_identity(id);
  ck_assert(zs_shadow_camera(&l[0], id, lo, hi, v, p));
  zs_mat_mul(vp, p, v);
  for (int k = 0; k < 8; k++) {
    const double c[3] = {k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]};
    double q[4];
    zs_mat_apply(vp, c, q);
    for (int j = 0; j < 3; j++) ck_assert(q[j] >= -q[3] && q[j] <= q[3]);
  }
  ck_assert(zs_shadow_camera(&l[1], id, lo, hi, v, p));
  double eye[3];
  zs_mat_eye_of_view(v, eye);
  ck_assert(fabs(eye[1] - 9) < 1e-12 && fabs(eye[0]) < 1e-12 && fabs(eye[2]) < 1e-12);
  ck_assert(!zs_shadow_camera(&l[2], id, lo, hi, v, p));
}
END_TEST

/* Maps a device cannot use are refused with the field at fault. */
START_TEST(bad_shadow_maps_refused) {
  static uint32_t texels[16];
  zs_device *flat = NULL, *phong = NULL;
  zs_device_config cfg = {64, 48, ZS_ALGO_ZBUFFER, ZS_SHADE_FLAT, 0, 1, 0, 0, 0};
  ck_assert_int_eq(zs_device_create(&cfg, &flat, &err), ZS_OK);
  cfg.shade = ZS_SHADE_PHONG;
  ck_assert_int_eq(zs_device_create(&cfg, &phong, &err), ZS_OK);
  zs_light lights[3];
  memset(lights, 0, sizeof lights);
  lights[0].kind = ZS_LIGHT_DIRECTIONAL, lights[0].direction[1] = -1;
  lights[1].kind = ZS_LIGHT_AMBIENT;
  lights[2].kind = ZS_LIGHT_SPOT, lights[2].direction[1] = -1, lights[2].inner_deg = 10,
  lights[2].outer_deg = 20;
  ck_assert_int_eq(zs_device_set_lights(phong, lights, 3, &err), ZS_OK);
  ck_assert_int_eq(zs_device_set_lights(flat, lights, 3, &err), ZS_OK);
  zs_shadow_map m[2];
  memset(m, 0, sizeof m);
  m[0].width = m[0].height = 4, m[0].depth = texels;
  zs_mat_identity(m[0].view);
  zs_mat_identity(m[0].proj);
  m[1] = m[0];
  m[1].light = 2;
  ck_assert_int_eq(zs_device_set_shadow_maps(phong, m, 2, &err), ZS_OK);
  static const struct {
    int field;
    const char *message;
  } bad[] = {{0, "shadow maps need the Phong shading (auto or phong), not flat"},
             {1, "maps[1].light: 1 is not a directional or spot light of those set"},
             {2, "maps[1].light: light 0 has maps[0] already"},
             {3, "maps[1]: 0 x 4 texels: 1 to 16384 a side"},
             {4, "maps[1].depth: NULL"},
             {5, "maps[1].bias_units: -1: 0 to 2^32"},
             {6, "maps[1].bias_slope: nan: 0 to 1e6"},
             {7, "maps[1].proj: not finite"},
             {8, "shadow maps: 5 maps: 0 to 4 may be set"}};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    zs_shadow_map b[2] = {m[0], m[1]};
    int n = 2;
    zs_device *d = phong;
    switch (bad[i].field) {
      case 0: d = flat; break;
      case 1: b[1].light = 1; break;
      case 2: b[1].light = 0; break;
      case 3: b[1].width = 0; break;
      case 4: b[1].depth = NULL; break;
      case 5: b[1].bias_units = -1; break;
      case 6: b[1].bias_slope = NAN; break;
      case 7: b[1].proj[5] = INFINITY; break;
      default: n = 5; break;
    }
    zs_error_clear(&err);
    ck_assert_int_eq(zs_device_set_shadow_maps(d, b, n, &err), ZS_ERR_ARG);
    ck_assert_str_eq(err.msg, bad[i].message);
  }
  /* maps hold for a frame: not set between its draws */
  {
    double pos[9] = {0, 0, -2, 1, 0, -2, 0, 1, -2}, v[16], p[16];
    int32_t start[2] = {0, 3}, fv[3] = {0, 1, 2};
    zs_mesh tri = {.pos = pos, .nverts = 3, .face_start = start, .face_vert = fv, .nfaces = 1};
    zs_mat_identity(v);
    zs_mat_perspective(p, 60, 4.0 / 3, 0.5, 10);
    zs_device_set_camera(phong, v, p);
    zs_device_clear(phong);
    ck_assert_int_eq(zs_device_draw(phong, &tri, NULL, 0, 0xFFFFFF, &err), ZS_OK);
    zs_error_clear(&err);
    ck_assert_int_eq(zs_device_set_shadow_maps(phong, m, 2, &err), ZS_ERR_ARG);
    ck_assert_str_eq(err.msg, "shadow maps: set before a frame's first draw (after "
                              "zs_device_clear), not between its draws");
    ck_assert_int_eq(zs_device_finish(phong, NULL, NULL, &err), ZS_OK);
    zs_device_clear(phong);
  }
  /* a point light marked to cast is refused with the lights */
  lights[1].kind = ZS_LIGHT_POINT, lights[1].shadow = 1;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_set_lights(phong, lights, 3, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "lights[1].shadow: only directional and spot lights cast shadows");
  zs_device_destroy(flat);
  zs_device_destroy(phong);

  /* the render options' */
  zs_scene *s = NULL;
  ck_assert_int_eq(zs_scene_load("builtin:default", NULL, &s, &err), ZS_OK);
  zs_render_opts o = {0};
  zs_image im;
  o.shadow_size = 8;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_render(s, &o, &im, NULL, NULL, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "zs_render_opts.shadow_size: 8: 16 to 8192 (0: 1024)");
  o.shadow_size = 0, o.shadows = 1, o.shade = ZS_SHADE_GOURAUD;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_render(s, &o, &im, NULL, NULL, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "shadows need the Phong shading (auto or phong), not gouraud");
  o.shade = ZS_SHADE_AUTO, o.has_shadow_bias = 1, o.shadow_bias[1] = -2;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_render(s, &o, &im, NULL, NULL, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "zs_render_opts.shadow_bias: 0, -2: units 0 to 2^32, slope 0 to 1e6");
  zs_scene_destroy(s);
}
END_TEST

int main(void) {
  Suite *s = suite_create("shadow");
  TCase *tc = tcase_create("maps");
  tcase_set_timeout(tc, 300);
  tcase_add_test(tc, shadow_falls_below_the_tile);
  tcase_add_test(tc, plane_behind_a_spot_does_not_shadow_itself);
  tcase_add_test(tc, key_light_of_a_scene_without_lights);
  tcase_add_test(tc, shadow_cameras_hold_the_bounds);
  tcase_add_test(tc, bad_shadow_maps_refused);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
