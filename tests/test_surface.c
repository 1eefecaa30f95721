/* Surface shading: vertex colours, normals, textures and lights, the same
 * bytes in every mode, traversal, SIMD level and thread count; probes of
 * the interpolation, the texture sampler and the lighting formula
 * (docs/ALGORITHMS.md) at pixels whose values are known. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "raster/raster.h"
#include "util/exactmath.h"
#include "tests/testutil.h"

enum { W = 160, H = 120 };
static zs_error err;
static uint32_t image[W * H];

static float normals[3 * W * H]; /* the rows' normals, when asked for */
static int normals_asked, rows_with_normals;

static void keep(void *user, const zs_row *row) {
  (void)user;
  memcpy(image + (size_t)row->y * W, row->rgb, W * sizeof *image);
  if (row->normal) {
    memcpy(normals + 3 * (size_t)row->y * W, row->normal, 3 * W * sizeof *normals);
    rows_with_normals++;
  }
}

/* ---- a model with every attribute ---- */

typedef struct model {
  double pos[3 * 600];
  float nrm[3 * 600], uv[2 * 600];
  uint8_t col[4 * 600];
  int32_t start[700], vert[4 * 700], nv, nf;
  int32_t face_material[700];
  zs_material mat[2];
  zs_texture *tex;
} model;

static int32_t vertex(model *m, double x, double y, double z, const double n[3], double u,
                      double v, uint32_t rgb) {
  const int32_t k = m->nv++;
  m->pos[3 * k] = x, m->pos[3 * k + 1] = y, m->pos[3 * k + 2] = z;
  for (int i = 0; i < 3; i++) m->nrm[3 * k + i] = (float)n[i];
  m->uv[2 * k] = (float)u, m->uv[2 * k + 1] = (float)v;
  m->col[4 * k] = (uint8_t)(rgb >> 16), m->col[4 * k + 1] = (uint8_t)(rgb >> 8);
  m->col[4 * k + 2] = (uint8_t)rgb, m->col[4 * k + 3] = 255;
  return k;
}

static void face(model *m, const int32_t *v, int n, int32_t material) {
  const int32_t s = m->nf ? m->start[m->nf] : 0;
  m->start[m->nf] = s;
  memcpy(&m->vert[s], v, (size_t)n * sizeof *v);
  m->face_material[m->nf] = material;
  m->start[++m->nf] = s + n;
}

/* A checker of 4 x 4 texel squares, 32 x 32 texels: red and white. */
static zs_texture *checker(void) {
  static uint8_t t[32 * 32 * 4];
  for (int y = 0; y < 32; y++)
    for (int x = 0; x < 32; x++) {
      uint8_t *p = &t[4 * (y * 32 + x)];
      const int white = ((x / 4) ^ (y / 4)) & 1;
      p[0] = 255, p[1] = p[2] = white ? 255 : 0, p[3] = 255;
    }
  zs_texture *tex = NULL;
  ck_assert_int_eq(zs_texture_create(32, 32, t, &tex, &err), ZS_OK);
  return tex;
}

/* A UV sphere (smooth normals, colours by place, material 0, textured)
 * and a floor of quads under it (flat normal, material 1, untextured),
 * one quad crossing the near plane of the camera below. */
static void build(model *m) {
  memset(m, 0, sizeof *m);
  m->tex = checker();
  m->mat[0] = zs_material_default();
  m->mat[0].base_texture = m->tex;
  m->mat[0].specular[0] = m->mat[0].specular[1] = m->mat[0].specular[2] = 200;
  m->mat[0].shininess = 24;
  m->mat[1] = zs_material_default();
  m->mat[1].base[0] = 90, m->mat[1].base[1] = 160, m->mat[1].base[2] = 90;
  m->mat[1].double_sided = 0;
  enum { NU = 24, NV = 12 };
  const int32_t first = m->nv;
  for (int j = 0; j <= NV; j++)
    for (int i = 0; i <= NU; i++) {
      double s, c, s2, c2;
      zs_sincos_deg(180.0 * j / NV, &s, &c);
      zs_sincos_deg(360.0 * i / NU, &s2, &c2);
      const double n[3] = {s * c2, c, s * s2};
      vertex(m, n[0], n[1] + 1.0, n[2], n, 2.0 * i / NU, 1.0 * j / NV,
             (uint32_t)(255 * i / NU) << 16 | (uint32_t)(255 * j / NV) << 8 | 0x80);
    }
  for (int j = 0; j < NV; j++)
    for (int i = 0; i < NU; i++) {
      const int32_t a = first + j * (NU + 1) + i;
      const int32_t q[4] = {a, a + NU + 1, a + NU + 2, a + 1};
      face(m, q, 4, 0);
    }
  const double up[3] = {0, 1, 0};
  for (int z = -3; z < 3; z++)
    for (int x = -3; x < 3; x++) {
      const int32_t q[4] = {vertex(m, x, 0, z, up, 0, 0, 0xFFFFFF),
                            vertex(m, x, 0, z + 1, up, 0, 1, 0xFFFFFF),
                            vertex(m, x + 1, 0, z + 1, up, 1, 1, 0xFFFFFF),
                            vertex(m, x + 1, 0, z, up, 1, 0, 0xFFFFFF)};
      face(m, q, 4, 1);
    }
}

static zs_mesh mesh_of(model *m) {
  zs_mesh me = {.pos = m->pos, .nverts = m->nv, .face_start = m->start, .face_vert = m->vert,
                .nfaces = m->nf, .nattrs = m->nv, .normal = m->nrm, .color = m->col,
                .uv = m->uv, .face_material = m->face_material, .materials = m->mat,
                .nmaterials = 2};
  return me;
}

/* The frame's hash: mesh drawn as `parts` draws of consecutive faces, in
 * order or backwards, from a camera whose near plane cuts the floor. */
static uint64_t render(const zs_mesh *mesh, zs_algo algo, zs_shade shade, int threads,
                       zs_span_fill spans, int parts, int backwards, zs_filter filter) {
  zs_device_config cfg = {W, H, algo, shade, 0, threads, 0x203040, spans, (int)filter};
  zs_device *d = NULL;
  ck_assert_msg(zs_device_create(&cfg, &d, &err) == ZS_OK, "%s", err.msg);
  ck_assert_int_eq(zs_device_set_normals(d, normals_asked, &err), ZS_OK);
  rows_with_normals = 0;
  double view[16], proj[16];
  const double eye[3] = {0.6, 1.6, 3.2}, target[3] = {0, 0.8, 0}, up[3] = {0, 1, 0};
  zs_mat_look_at(view, eye, target, up);
  zs_mat_perspective(proj, 50, (double)W / H, 0.5, 20);
  zs_device_set_camera(d, view, proj);
  const zs_light lights[3] = {
      {ZS_LIGHT_DIRECTIONAL, {0.8, 0.8, 0.7}, {0, 0, 0}, {-0.5, -1, -0.3}, 0, 0, 0, 0},
      {ZS_LIGHT_SPOT, {6, 5, 5}, {1.5, 2.5, 1.5}, {-1.5, -2.5, -1.5}, 15, 30, 0, 0},
      {ZS_LIGHT_AMBIENT, {0.08, 0.08, 0.1}, {0, 0, 0}, {0, 0, 0}, 0, 0, 0, 0}};
  ck_assert_int_eq(zs_device_set_lights(d, lights, 3, &err), ZS_OK);
  zs_device_clear(d);
  for (int p = 0; p < parts; p++) {
    const int k = backwards ? parts - 1 - p : p;
    zs_mesh part = *mesh;
    const int32_t f0 = (int32_t)((int64_t)mesh->nfaces * k / parts),
                  f1 = (int32_t)((int64_t)mesh->nfaces * (k + 1) / parts);
    part.face_start = mesh->face_start + f0;
    part.face_material = mesh->face_material + f0;
    part.nfaces = f1 - f0;
    int32_t ids[700];
    for (int32_t f = 0; f < part.nfaces; f++) ids[f] = f0 + f;
    part.face_id = ids;
    ck_assert_msg(zs_device_draw(d, &part, NULL, 0, ZS_RGB_MESH, &err) == ZS_OK, "%s", err.msg);
  }
  ck_assert_msg(zs_device_finish(d, keep, NULL, &err) == ZS_OK, "%s", err.msg);
  zs_device_destroy(d);
  return zs_test_fnv1a(image, sizeof image);
}

static const zs_shade shades[] = {ZS_SHADE_UNLIT, ZS_SHADE_GOURAUD, ZS_SHADE_PHONG,
                                  ZS_SHADE_NORMAL, ZS_SHADE_AUTO};
static const char *const shade_keys[] = {"surface-unlit", "surface-gouraud", "surface-phong",
                                         "surface-normal", "surface-auto"};

/* Every shading: one picture whatever the mode, threads, SIMD level and
 * order of the draws; and that picture pinned (tests/golden/hashes.txt),
 * so builds with other compilers and flags compare with this one. */
START_TEST(same_bytes_in_every_mode) {
  model *m = malloc(sizeof *m);
  build(m);
  const zs_mesh mesh = mesh_of(m);
  const zs_span_fill fills[] = {ZS_SPANS_SCALAR, ZS_SPANS_SSE2, ZS_SPANS_AVX2, ZS_SPANS_BEST};
  for (int s = 0; s < 5; s++) {
    const uint64_t want = render(&mesh, ZS_ALGO_ZBUFFER, shades[s], 1, ZS_SPANS_SCALAR, 1, 0, 0);
    for (int algo = ZS_ALGO_ZBUFFER; algo <= ZS_ALGO_SCANLINE; algo++)
      for (int t = 1; t <= 4; t *= 2)
        for (int f = 0; f < 4; f++)
          ck_assert_msg(render(&mesh, (zs_algo)algo, shades[s], t, fills[f], 3, t == 2, 0) == want,
                        "%s: %s, %d threads, fill %d differs", shade_keys[s],
                        zs_algo_name((zs_algo)algo), t, (int)fills[f]);
    zs_golden_assert("hashes.txt", shade_keys[s], want);
  }
  zs_texture_destroy(m->tex);
  free(m);
}
END_TEST

/* Depth sort paints the same pixels where its order is right: a picture
 * of faces that do not overlap on the screen (the floor seen from above). */
START_TEST(depthsort_agrees_where_it_applies) {
  model *m = malloc(sizeof *m);
  build(m);
  zs_mesh floor = mesh_of(m);
  floor.face_start += 24 * 12;
  floor.face_material += 24 * 12;
  floor.nfaces = 36;
  for (int s = 0; s < 4; s++)
    ck_assert_uint_eq(render(&floor, ZS_ALGO_DEPTHSORT, shades[s], 1, ZS_SPANS_BEST, 1, 0, 0),
                      render(&floor, ZS_ALGO_ZBUFFER, shades[s], 1, ZS_SPANS_BEST, 1, 0, 0));
  zs_texture_destroy(m->tex);
  free(m);
}
END_TEST

/* ---- probes, with a parallel camera: world x, y are window x, y ---- */

static void draw_flat_on(zs_device *d, const zs_mesh *mesh) {
  double view[16], proj[16];
  zs_mat_identity(view);
  zs_mat_ortho(proj, 0, W, 0, H, 0, 100);
  zs_device_set_camera(d, view, proj);
  zs_device_clear(d);
  ck_assert_msg(zs_device_draw(d, mesh, NULL, 0, ZS_RGB_MESH, &err) == ZS_OK, "%s", err.msg);
  ck_assert_msg(zs_device_finish(d, keep, NULL, &err) == ZS_OK, "%s", err.msg);
}

static uint32_t at(int x, int y_up) { return image[(size_t)(H - 1 - y_up) * W + (size_t)x]; }

/* A quad of four corner colours, unlit: shaded as the fan (0, 1, 2),
 * (0, 2, 3); at the pixel whose centre is a triangle's centroid its
 * colour is the mean of that triangle's corners, exactly (to rounding). */
START_TEST(quads_are_fans_from_the_first_corner) {
  const double pos[] = {0, 0, -1, 120, 0, -1, 120, 120, -1, 0, 120, -1};
  const uint8_t col[] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
  int32_t start[] = {0, 4}, vert[] = {0, 1, 2, 3};
  zs_mesh q = {.pos = (double *)pos, .nverts = 4, .face_start = start,
               .face_vert = vert, .nfaces = 1, .nattrs = 4, .color = (uint8_t *)col};
  zs_device_config cfg = {W, H, ZS_ALGO_ZBUFFER, ZS_SHADE_UNLIT, 0, 1, 0, 0, 0};
  zs_device *d = NULL;
  ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
  draw_flat_on(d, &q);
  zs_device_destroy(d);
  /* centroids (80 - 0.5, 40 - 0.5) and (40 - 0.5, 80 - 0.5): pixel 79, 39
   * and 39, 79 lie half a pixel off, within 1 of the mean */
  const uint32_t a = at(79, 39), b = at(39, 79);
  const int ra = (int)(a >> 16), ga = (int)(a >> 8 & 255), ba = (int)(a & 255);
  const int rb = (int)(b >> 16), gb = (int)(b >> 8 & 255), bb = (int)(b & 255);
  ck_assert_msg(abs(ra - 85) <= 2 && abs(ga - 85) <= 2 && abs(ba - 85) <= 2,
                "first triangle's centre %06x", a);
  ck_assert_msg(abs(rb - 170) <= 2 && abs(gb - 85) <= 2 && abs(bb - 170) <= 2,
                "second triangle's centre %06x", b);
}
END_TEST

/* A 4 x 4 texture over 64 x 64 pixels, nearest and unlit: each 16 x 16
 * block of pixels is one texel, exactly; row 0 of the texture at the top. */
START_TEST(nearest_texels_exact) {
  uint8_t t[4 * 4 * 4];
  for (int i = 0; i < 16; i++) t[4 * i] = (uint8_t)(16 * i), t[4 * i + 1] = (uint8_t)(255 - 16 * i),
                               t[4 * i + 2] = (uint8_t)(i * 7), t[4 * i + 3] = 255;
  zs_texture *tex = NULL;
  ck_assert_int_eq(zs_texture_create(4, 4, t, &tex, &err), ZS_OK);
  zs_material mat = zs_material_default();
  mat.base[0] = mat.base[1] = mat.base[2] = 255;
  mat.base_texture = tex;
  mat.filter = ZS_FILTER_NEAREST;
  const double pos[] = {0, 0, -1, 64, 0, -1, 64, 64, -1, 0, 64, -1};
  const float uv[] = {0, 0, 1, 0, 1, 1, 0, 1};
  int32_t start[] = {0, 4}, vert[] = {0, 1, 2, 3};
  zs_mesh q = {.pos = (double *)pos, .nverts = 4, .face_start = start, .face_vert = vert,
               .nfaces = 1, .nattrs = 4, .uv = (float *)uv, .materials = &mat, .nmaterials = 1};
  zs_device_config cfg = {W, H, ZS_ALGO_SCANLINE, ZS_SHADE_UNLIT, 0, 1, 0, 0, 0};
  zs_device *d = NULL;
  ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
  draw_flat_on(d, &q);
  zs_device_destroy(d);
  for (int y = 0; y < 64; y++)
    for (int x = 0; x < 64; x++) {
      const int i = (3 - y / 16) * 4 + x / 16; /* texture row 0 at the top */
      const uint32_t want = (uint32_t)t[4 * i] << 16 | (uint32_t)t[4 * i + 1] << 8 | t[4 * i + 2];
      ck_assert_msg(at(x, y) == want, "pixel %d,%d: %06x, want texel %d %06x", x, y, at(x, y), i,
                    want);
    }
  zs_texture_destroy(tex);
}
END_TEST

/* The 32-texel checker over 2 x 2 pixels, 16 texels a pixel: level 4 of
 * its mip chain, where (as in levels 3 and 5) every texel is the mean of
 * as many red squares as white ones, pink (255, 128, 128); trilinear and
 * bilinear sample those levels, nearest level 0 (red or white). */
START_TEST(minified_texture_takes_its_level) {
  zs_texture *tex = checker();
  zs_material mat = zs_material_default();
  mat.base[0] = mat.base[1] = mat.base[2] = 255;
  mat.base_texture = tex;
  const double pos[] = {0, 0, -1, 2, 0, -1, 2, 2, -1, 0, 2, -1};
  const float uv[] = {0, 0, 1, 0, 1, 1, 0, 1};
  int32_t start[] = {0, 4}, vert[] = {0, 1, 2, 3};
  zs_mesh q = {.pos = (double *)pos, .nverts = 4, .face_start = start, .face_vert = vert,
               .nfaces = 1, .nattrs = 4, .uv = (float *)uv, .materials = &mat, .nmaterials = 1};
  const zs_filter filters[] = {ZS_FILTER_TRILINEAR, ZS_FILTER_BILINEAR, ZS_FILTER_NEAREST};
  for (int f = 0; f < 3; f++) {
    zs_device_config cfg = {W, H, ZS_ALGO_ZBUFFER, ZS_SHADE_UNLIT, 0, 1, 0, 0, (int)filters[f]};
    zs_device *d = NULL;
    ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
    draw_flat_on(d, &q);
    zs_device_destroy(d);
    int pink = 0;
    for (int y = 0; y < 2; y++)
      for (int x = 0; x < 2; x++) pink += at(x, y) == 0xFF8080;
    ck_assert_int_eq(pink, filters[f] == ZS_FILTER_NEAREST ? 0 : 4);
  }
  zs_texture_destroy(tex);
}
END_TEST

/* sRGB's curve by the formula, for the probe's expectation only. */
static double encode(double v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}
static double decode(double c) {
  return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

/* A square facing the eye, one directional light at 60 degrees and an
 * ambient light: at every pixel base (n.l r + a) + specular r (n.h)^s,
 * in linear light, then sRGB: within 1 of the formula's code in each
 * channel, for Phong and Gouraud alike. */
START_TEST(lighting_follows_its_formula) {
  const double pos[] = {0, 0, -1, 100, 0, -1, 100, 100, -1, 0, 100, -1};
  const float nrm[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  int32_t start[] = {0, 4}, vert[] = {0, 1, 2, 3};
  zs_material mat = zs_material_default();
  mat.base[0] = 200, mat.base[1] = 120, mat.base[2] = 40;
  mat.specular[0] = mat.specular[1] = mat.specular[2] = 100;
  mat.shininess = 8;
  zs_mesh q = {.pos = (double *)pos, .nverts = 4, .face_start = start, .face_vert = vert,
               .nfaces = 1, .nattrs = 4, .normal = (float *)nrm, .materials = &mat,
               .nmaterials = 1};
  double s60, c60;
  zs_sincos_deg(60.0, &s60, &c60);
  const zs_light lights[2] = {
      {ZS_LIGHT_DIRECTIONAL, {0.9, 0.8, 0.7}, {0, 0, 0}, {0, -s60, -c60}, 0, 0, 1, 0},
      {ZS_LIGHT_AMBIENT, {0.05, 0.05, 0.05}, {0, 0, 0}, {0, 0, 0}, 0, 0, 0, 0}};
  /* l = (0, s60, c60), v = (0, 0, 1) (parallel projection), n = (0, 0, 1) */
  const double ndl = c60, hl = sqrt(s60 * s60 + (c60 + 1) * (c60 + 1)), ndh = (c60 + 1) / hl;
  const zs_shade sh[2] = {ZS_SHADE_PHONG, ZS_SHADE_GOURAUD};
  for (int k = 0; k < 2; k++) {
    zs_device_config cfg = {W, H, ZS_ALGO_ZBUFFER, sh[k], 0, 1, 0, 0, 0};
    zs_device *d = NULL;
    ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
    ck_assert_int_eq(zs_device_set_lights(d, lights, 2, &err), ZS_OK);
    draw_flat_on(d, &q);
    zs_device_destroy(d);
    for (int c = 0; c < 3; c++) {
      const double base = decode(mat.base[c] / 255.0), spec = decode(100 / 255.0);
      const double r = lights[0].color[c];
      const double lin = base * (r * ndl + 0.05) + spec * r * pow(ndh, 8);
      const int want = (int)lround(255 * encode(lin));
      for (int y = 10; y < 100; y += 30)
        for (int x = 10; x < 100; x += 30) {
          const int got = (int)(at(x, y) >> (16 - 8 * c) & 255);
          ck_assert_msg(abs(got - want) <= 1, "%s channel %d at %d,%d: %d, formula %d",
                        zs_shade_name(sh[k]), c, x, y, got, want);
        }
    }
  }
}
END_TEST

/* A flat draw next to attribute draws keeps its colours; a frame of flat
 * draws alone under auto is the flat picture, byte for byte. */
START_TEST(flat_draws_keep_their_colours) {
  const double pos[] = {10, 10, -1, 50, 10, -1, 50, 50, -1, 10, 50, -1};
  int32_t start[] = {0, 4}, vert[] = {0, 1, 2, 3};
  uint32_t rgb[] = {0x336699};
  zs_mesh q = {.pos = (double *)pos, .nverts = 4, .face_start = start, .face_vert = vert,
               .nfaces = 1, .face_rgb = rgb};
  uint64_t h[2];
  for (int k = 0; k < 2; k++) {
    zs_device_config cfg = {W, H, ZS_ALGO_ZBUFFER, k ? ZS_SHADE_AUTO : ZS_SHADE_FLAT, 0, 1, 0, 0,
                            0};
    zs_device *d = NULL;
    ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
    draw_flat_on(d, &q);
    zs_device_destroy(d);
    h[k] = zs_test_fnv1a(image, sizeof image);
  }
  ck_assert_uint_eq(h[0], h[1]);
}
END_TEST

START_TEST(bad_lights_refused) {
  zs_device *d = NULL;
  ck_assert_int_eq(zs_device_create(NULL, &d, &err), ZS_OK);
  zs_light l = {ZS_LIGHT_SPOT, {1, 1, 1}, {0, 0, 0}, {0, 0, -1}, 40, 30, 0, 0};
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_set_lights(d, &l, 1, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "lights[0]: a spot's angles need 0 < inner_deg <= outer_deg < 90, "
                            "got 40 and 30");
  l.kind = ZS_LIGHT_DIRECTIONAL;
  l.direction[2] = 0;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_set_lights(d, &l, 1, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "lights[0].direction: expected a finite, non-zero vector");
  l.direction[2] = -1;
  l.color[1] = NAN;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_set_lights(d, &l, 1, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "lights[0].color: expected finite values >= 0");
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_set_lights(d, &l, ZS_MAX_LIGHTS + 1, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "lights: 17 lights: 0 to 16 may be set");
  zs_device_destroy(d);
}
END_TEST

/* Normals handed out with the rows: unit where a face is, the normal
 * shading's colours of them, 0 at the background; the same floats in every
 * mode and thread count, and under another shading of the same faces. */
START_TEST(normals_go_out_with_the_rows) {
  model *m = malloc(sizeof *m);
  build(m);
  const zs_mesh mesh = mesh_of(m);
  normals_asked = 1;
  render(&mesh, ZS_ALGO_ZBUFFER, ZS_SHADE_NORMAL, 1, ZS_SPANS_BEST, 1, 0, 0);
  ck_assert_int_eq(rows_with_normals, H);
  const uint64_t want = zs_test_fnv1a(normals, sizeof normals);
  int faces = 0, bad = -1;
  for (size_t i = 0; i < (size_t)W * H && bad < 0; i++) {
    const float *n = &normals[3 * i];
    const double len2 = (double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2];
    if (image[i] == 0x203040) { /* the background */
      if (len2 != 0) bad = (int)i;
      continue;
    }
    faces++;
    if (!(fabs(len2 - 1.0) < 1e-6)) bad = (int)i;
    for (int k = 0; k < 3; k++) { /* the colour is the normal, to its rounding */
      const double v = n[k] * 127.5 + 128.0;
      if (!(fabs(v - (double)(image[i] >> (16 - 8 * k) & 255)) < 1.0 + 1e-4)) bad = (int)i;
    }
  }
  ck_assert_msg(bad < 0, "pixel %d: normal %f %f %f, colour %06X", bad,
                bad < 0 ? 0 : normals[3 * bad], bad < 0 ? 0 : normals[3 * bad + 1],
                bad < 0 ? 0 : normals[3 * bad + 2], bad < 0 ? 0 : image[bad]);
  ck_assert_int_gt(faces, W * H / 4);
  for (int algo = ZS_ALGO_ZBUFFER; algo <= ZS_ALGO_SCANLINE; algo++)
    for (int t = 1; t <= 4; t *= 2) {
      render(&mesh, (zs_algo)algo, ZS_SHADE_NORMAL, t, ZS_SPANS_BEST, 3, t == 2, 0);
      ck_assert_uint_eq(zs_test_fnv1a(normals, sizeof normals), want);
      render(&mesh, (zs_algo)algo, ZS_SHADE_UNLIT, t, ZS_SPANS_BEST, 3, t == 4, 0);
      ck_assert_uint_eq(zs_test_fnv1a(normals, sizeof normals), want);
    }
  normals_asked = 0;
  /* a shading that reads no attributes has none to give */
  zs_device_config cfg = {W, H, ZS_ALGO_ZBUFFER, ZS_SHADE_FLAT, 0, 1, 0, 0, 0};
  zs_device *d = NULL;
  ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_set_normals(d, 1, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "normals need a shading that reads attributes (auto, unlit, "
                            "gouraud, phong or normal), not flat");
  zs_device_destroy(d);
  zs_texture_destroy(m->tex);
  free(m);
}
END_TEST

/* Textures: sizes out of range refused; the mip chain's levels. */
START_TEST(texture_limits_and_levels) {
  uint8_t px[4 * 6] = {0};
  zs_texture *t = NULL;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_texture_create(0, 4, px, &t, &err), ZS_ERR_LIMIT);
  ck_assert_str_eq(err.msg, "texture: 0x4: each side must be 1 to 8192");
  zs_error_clear(&err);
  ck_assert_int_eq(zs_texture_create(8193, 1, px, &t, &err), ZS_ERR_LIMIT);
  ck_assert_int_eq(zs_texture_create(3, 2, px, &t, &err), ZS_OK);
  ck_assert_int_eq(zs_texture_levels(t), 2); /* 3x2, 1x1 */
  int w, h;
  ck_assert_ptr_nonnull(zs_texture_level(t, 1, &w, &h));
  ck_assert_int_eq(w, 1);
  ck_assert_int_eq(h, 1);
  ck_assert_ptr_null(zs_texture_level(t, 2, &w, &h));
  zs_texture_destroy(t);
}
END_TEST

int main(void) {
  Suite *s = suite_create("surface");
  TCase *tc = tcase_create("surface");
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, same_bytes_in_every_mode);
  tcase_add_test(tc, depthsort_agrees_where_it_applies);
  tcase_add_test(tc, quads_are_fans_from_the_first_corner);
  tcase_add_test(tc, nearest_texels_exact);
  tcase_add_test(tc, minified_texture_takes_its_level);
  tcase_add_test(tc, lighting_follows_its_formula);
  tcase_add_test(tc, flat_draws_keep_their_colours);
  tcase_add_test(tc, bad_lights_refused);
  tcase_add_test(tc, texture_limits_and_levels);
  tcase_add_test(tc, normals_go_out_with_the_rows);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
