/* The raster core: coverage rule, watertightness, the lecture's z-buffer
 * examples, the two hidden-surface modes, order independence.  Geometry is
 * built directly as meshes; most tests use an orthographic camera whose
 * window coordinates are the world's x and y, so vertices on the 1/256 grid
 * are not moved by snapping and a slow reference can use them as they are. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "raster/pool.h"
#include "raster/device.h"
#include "util/rng.h"
#include "tests/testutil.h"

/* ---- helpers ---- */

typedef struct frame {
  int w, h;
  uint32_t *rgb, *depth, *id, *count;
} frame;

static void frame_sink(void *user, const zs_row *row) {
  frame *f = user;
  size_t off = (size_t)row->y * (size_t)f->w;
  memcpy(f->rgb + off, row->rgb, (size_t)f->w * 4);
  memcpy(f->depth + off, row->depth, (size_t)f->w * 4);
  memcpy(f->id + off, row->id, (size_t)f->w * 4);
  if (row->count) memcpy(f->count + off, row->count, (size_t)f->w * 4);
}

static frame frame_new(int w, int h) {
  frame f = {w, h, NULL, NULL, NULL, NULL};
  size_t n = (size_t)w * (size_t)h;
  f.rgb = calloc(n, 4);
  f.depth = calloc(n, 4);
  f.id = calloc(n, 4);
  f.count = calloc(n, 4);
  return f;
}

static void frame_free(frame *f) {
  free(f->rgb);
  free(f->depth);
  free(f->id);
  free(f->count);
}

/* Orthographic camera: window x = world x, window y = world y, eye depth
 * = -world z mapped from [znear, zfar]. */
static void ortho_camera(zs_device *d, int w, int h, double znear, double zfar) {
  double view[16], proj[16];
  zs_mat_identity(view);
  zs_mat_ortho(proj, 0, w, 0, h, znear, zfar);
  zs_device_set_camera(d, view, proj);
}

/* The span fill of the devices made here (simd_spans_equal_scalar sets it). */
static zs_span_fill spans_for_devices = ZS_SPANS_BEST;

static zs_device *device(int w, int h, zs_algo algo, zs_shade shade, int cull) {
  zs_device_config cfg = {w, h, algo, shade, cull, 1, 0, spans_for_devices, 0};
  zs_device *d = NULL;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
  ck_assert_int_eq(zs_device_simd(d), zs_span_simd_level(spans_for_devices == ZS_SPANS_BEST
                                                             ? ZS_SIMD_AVX512
                                                             : (zs_simd)(spans_for_devices - 1)));
  return d;
}

/* Renders mesh in the given mode into f (allocated by the caller). */
static zs_raster_stats render(const zs_mesh *m, int w, int h, zs_algo algo,
                              zs_shade shade, int cull, const double view[16],
                              const double proj[16], frame *f) {
  zs_device *d = device(w, h, algo, shade, cull);
  if (view) zs_device_set_camera(d, view, proj);
  else ortho_camera(d, w, h, -10, 10);
  zs_device_clear(d);
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_draw(d, m, NULL, 0, ZS_RGB_MESH, &err), ZS_OK);
  ck_assert_int_eq(zs_device_finish(d, frame_sink, f, &err), ZS_OK);
  zs_raster_stats s = *zs_device_stats(d);
  zs_device_destroy(d);
  return s;
}

/* ---- the example square ---- */

START_TEST(square_on_pixel_centres) {
  /* Corners (+-0.375, +-0.375, -1) seen from the origin down -z, fovy 90,
   * 8x8: the edges fall on pixel centres 2.5 and 5.5; left and bottom edges
   * are in, so columns 2..4 and rows 3..5 (row 0 at the top). */
  mesh_buf b = {0};
  int32_t v[4] = {mb_vert(&b, -0.375, -0.375, -1), mb_vert(&b, 0.375, -0.375, -1),
                  mb_vert(&b, 0.375, 0.375, -1), mb_vert(&b, -0.375, 0.375, -1)};
  mb_face(&b, v, 4, 0xFFFFFF);
  double view[16], proj[16];
  zs_mat_identity(view);
  zs_mat_perspective(proj, 90, 1, 0.1, 10);
  for (int algo = 0; algo < 2; algo++) {
    frame f = frame_new(8, 8);
    render(&b.m, 8, 8, (zs_algo)algo, ZS_SHADE_ID, 0, view, proj, &f);
    for (int y = 0; y < 8; y++)
      for (int x = 0; x < 8; x++) {
        int in = x >= 2 && x <= 4 && y >= 3 && y <= 5;
        ck_assert_msg((f.id[y * 8 + x] == 0) == in, "algo %d pixel %d,%d", algo, x, y);
      }
    frame_free(&f);
  }
  mb_free(&b);
}
END_TEST

/* ---- a slow reference: edge functions with the same tie rule ---- */

/* Is the centre of pixel (px, py) (image coordinates) inside the triangle
 * with image-subpixel vertices X, Y?  Edge functions, exact in integers;
 * on an edge, in when it is a left or a bottom edge of the written image. */
static int ref_inside(const int64_t X[3], const int64_t Y[3], int px, int py) {
  int64_t area2 = 0;
  for (int i = 0; i < 3; i++) area2 += X[i] * Y[(i + 1) % 3] - X[(i + 1) % 3] * Y[i];
  if (area2 == 0) return 0;
  int order[3] = {0, 1, 2};
  if (area2 < 0) { order[1] = 2; order[2] = 1; } /* make it clockwise on screen */
  int64_t cx = (int64_t)px * 256 + 128, cy = (int64_t)py * 256 + 128;
  for (int i = 0; i < 3; i++) {
    int a = order[i], b = order[(i + 1) % 3];
    int64_t dx = X[b] - X[a], dy = Y[b] - Y[a];
    int64_t e = dx * (cy - Y[a]) - dy * (cx - X[a]);
    if (e < 0) return 0;
    if (e == 0 && !(dy < 0 || (dy == 0 && dx < 0))) return 0;
  }
  return 1;
}

START_TEST(random_triangles_match_reference) {
  /* Seeded differential test: random triangles with vertices on the
   * subpixel grid, a third of them on pixel centres, against ref_inside.
   * On failure, the seed and triangle are printed to replay. */
  const int W = 40, H = 30;
  const uint64_t seed = 20261122;
  zs_rng rng;
  zs_rng_seed(&rng, seed);
  for (int t = 0; t < 400; t++) {
    int64_t X[3], Y[3];
    mesh_buf b = {0};
    int32_t v[3];
    for (int i = 0; i < 3; i++) {
      int64_t xs = (int64_t)zs_rng_below(&rng, (uint64_t)(W + 8) * 256) - 4 * 256;
      int64_t ys = (int64_t)zs_rng_below(&rng, (uint64_t)(H + 8) * 256) - 4 * 256;
      if (zs_rng_below(&rng, 3) == 0) { xs = (xs & ~255) + 128; ys = (ys & ~255) + 128; }
      if (t % 7 == 0 && i == 2) ys = Y[0]; /* horizontal edges */
      X[i] = xs;
      Y[i] = ys;
      /* image subpixel -> window units: x = X/256, y_win = H - Y/256 */
      v[i] = mb_vert(&b, xs / 256.0, H - ys / 256.0, -(double)i / 4.0);
    }
    mb_face(&b, v, 3, 0xFFFFFF);
    for (int algo = 0; algo < 2; algo++) {
      frame f = frame_new(W, H);
      render(&b.m, W, H, (zs_algo)algo, ZS_SHADE_OVERDRAW, 0, NULL, NULL, &f);
      for (int py = 0; py < H; py++)
        for (int px = 0; px < W; px++) {
          int want = ref_inside(X, Y, px, py);
          int got = (int)f.count[py * W + px];
          ck_assert_msg(got == want,
                        "seed %llu triangle %d algo %d pixel %d,%d: got %d want %d "
                        "(X %lld %lld %lld, Y %lld %lld %lld)",
                        (unsigned long long)seed, t, algo, px, py, got, want,
                        (long long)X[0], (long long)X[1], (long long)X[2],
                        (long long)Y[0], (long long)Y[1], (long long)Y[2]);
        }
      frame_free(&f);
    }
    mb_free(&b);
  }
}
END_TEST

/* ---- watertightness ---- */

START_TEST(fan_of_thin_triangles_covers_once) {
  /* 10,000 thin triangles around a centre on a pixel centre form a convex
   * 10,000-gon: inside it every pixel gets exactly one fragment, outside
   * none, and each row's covered pixels are one run. */
  const int W = 256, H = 256, N = 10000;
  mesh_buf b = {0};
  mb_fan(&b, 128.5, 128.5, 120.3, N);
  for (int algo = 0; algo < 2; algo++) {
    frame f = frame_new(W, H);
    zs_raster_stats s = render(&b.m, W, H, (zs_algo)algo, ZS_SHADE_OVERDRAW, 0, NULL, NULL, &f);
    uint64_t covered = 0;
    for (int y = 0; y < H; y++) {
      int runs = 0, prev = 0;
      for (int x = 0; x < W; x++) {
        uint32_t k = f.count[y * W + x];
        ck_assert_msg(k <= 1, "algo %d pixel %d,%d covered %u times", algo, x, y, k);
        if (k && !prev) runs++;
        prev = (int)k;
        covered += k;
      }
      ck_assert_msg(runs <= 1, "algo %d row %d has a crack (%d runs)", algo, y, runs);
    }
    /* A disc of radius 120.3 holds about pi r^2 = 45,465 pixel centres. */
    ck_assert_uint_gt(covered, 45000);
    ck_assert_uint_lt(covered, 46000);
    ck_assert_uint_eq(s.pixels_written, covered);
    frame_free(&f);
  }
  mb_free(&b);
}
END_TEST

/* A closed, convex mesh: a UV sphere.  With back faces culled, every pixel
 * of its silhouette is covered exactly once; without, exactly twice. */
START_TEST(closed_mesh_covers_once_front_twice_both) {
  mesh_buf b = {0};
  mb_sphere(&b, 0, 0, -6, 1.7, 48, 32, 0);
  double view[16], proj[16];
  zs_mat_look_at(view, (double[3]){0.3, 0.2, 0}, (double[3]){0, 0, -6}, (double[3]){0, 1, 0});
  zs_mat_perspective(proj, 40, 4.0 / 3.0, 0.5, 20);
  for (int algo = 0; algo < 2; algo++) {
    frame f1 = frame_new(160, 120), f2 = frame_new(160, 120), fid = frame_new(160, 120);
    render(&b.m, 160, 120, (zs_algo)algo, ZS_SHADE_OVERDRAW, 1, view, proj, &f1);
    render(&b.m, 160, 120, (zs_algo)algo, ZS_SHADE_OVERDRAW, 0, view, proj, &f2);
    render(&b.m, 160, 120, (zs_algo)algo, ZS_SHADE_ID, 0, view, proj, &fid);
    int covered = 0;
    for (int i = 0; i < 160 * 120; i++) {
      int in = fid.id[i] != ZS_ID_NONE;
      ck_assert_uint_eq(f1.count[i], in ? 1u : 0u);
      ck_assert_uint_eq(f2.count[i], in ? 2u : 0u);
      covered += in;
    }
    ck_assert_int_gt(covered, 3000);
    frame_free(&f1);
    frame_free(&f2);
    frame_free(&fid);
  }
  mb_free(&b);
}
END_TEST

/* ---- the lecture's z-buffer examples ---- */

/* The lecture's depth convention: z larger is nearer, background -5.  An
 * orthographic camera looking down -z from the origin with the far plane
 * at lecture z = -5 maps lecture z to window depth (10 - z) / 15. */
static int lecture_z(uint32_t d) {
  double z = 10.0 - 15.0 * (d / 4294967296.0);
  if (d == ZS_DEPTH_FAR) z = -5.0;
  return (int)lrint(z);
}

START_TEST(lecture_zbuffer_examples) {
  /* 8 x 6 buffers.  Example 1: a square at z = -1 over columns 2..5, rows
   * 1..4.  Example 2: then a sloped rectangle over columns 2..6, rows 2..3,
   * whose pixel depths are 2, 1, 0, -1, -2 (one step of -1 per pixel). */
  static const int after_square[6][8] = {
      {-5, -5, -5, -5, -5, -5, -5, -5}, {-5, -5, -1, -1, -1, -1, -5, -5},
      {-5, -5, -1, -1, -1, -1, -5, -5}, {-5, -5, -1, -1, -1, -1, -5, -5},
      {-5, -5, -1, -1, -1, -1, -5, -5}, {-5, -5, -5, -5, -5, -5, -5, -5}};
  static const int after_both[6][8] = {
      {-5, -5, -5, -5, -5, -5, -5, -5}, {-5, -5, -1, -1, -1, -1, -5, -5},
      {-5, -5, 2, 1, 0, -1, -2, -5},    {-5, -5, 2, 1, 0, -1, -2, -5},
      {-5, -5, -1, -1, -1, -1, -5, -5}, {-5, -5, -5, -5, -5, -5, -5, -5}};
  mesh_buf sq = {0}, both = {0};
  /* window y = 6 - image row; the square spans image rows 1..4 */
  int32_t s[4] = {mb_vert(&sq, 2, 1, -1), mb_vert(&sq, 6, 1, -1), mb_vert(&sq, 6, 5, -1),
                  mb_vert(&sq, 2, 5, -1)};
  mb_face(&sq, s, 4, 0xFF0000);
  int32_t s2[4] = {mb_vert(&both, 2, 1, -1), mb_vert(&both, 6, 1, -1),
                   mb_vert(&both, 6, 5, -1), mb_vert(&both, 2, 5, -1)};
  mb_face(&both, s2, 4, 0xFF0000);
  /* z = 4.5 - x: 2 at the centre of column 2, -2 at column 6 */
  int32_t t[4] = {mb_vert(&both, 2, 2, 2.5), mb_vert(&both, 7, 2, -2.5),
                  mb_vert(&both, 7, 4, -2.5), mb_vert(&both, 2, 4, 2.5)};
  mb_face(&both, t, 4, 0x00FF00);
  double view[16], proj[16];
  zs_mat_identity(view);
  zs_mat_ortho(proj, 0, 8, 0, 6, -10, 5);
  for (int algo = 0; algo < 2; algo++) {
    frame f = frame_new(8, 6);
    render(&sq.m, 8, 6, (zs_algo)algo, ZS_SHADE_ID, 0, view, proj, &f);
    for (int y = 0; y < 6; y++)
      for (int x = 0; x < 8; x++)
        ck_assert_int_eq(lecture_z(f.depth[y * 8 + x]), after_square[y][x]);
    render(&both.m, 8, 6, (zs_algo)algo, ZS_SHADE_ID, 0, view, proj, &f);
    for (int y = 0; y < 6; y++)
      for (int x = 0; x < 8; x++)
        ck_assert_msg(lecture_z(f.depth[y * 8 + x]) == after_both[y][x],
                      "algo %d pixel %d,%d: %d", algo, x, y, lecture_z(f.depth[y * 8 + x]));
    frame_free(&f);
  }
  mb_free(&sq);
  mb_free(&both);
}
END_TEST

/* n random triangles over a w x h window and margin pixels beyond it,
 * random colours; every third lies at depth -2 (so that coplanar faces
 * meet and the id rule decides), the others' vertices at random depths in
 * [zlo, -1].  One draw of the generator per statement (docs/ARCHITECTURE.md,
 * Determinism). */
static void random_triangles(mesh_buf *b, zs_rng *rng, int n, int w, int h, double margin,
                             double zlo) {
  for (int i = 0; i < n; i++) {
    int32_t v[3];
    for (int k = 0; k < 3; k++) {
      double x = zs_rng_range(rng, -margin, w + margin);
      double y = zs_rng_range(rng, -margin, h + margin);
      double z = (i % 3 == 0) ? -2.0 : zs_rng_range(rng, zlo, -1);
      v[k] = mb_vert(b, x, y, z);
    }
    mb_face(b, v, 3, (uint32_t)zs_rng_below(rng, 0x1000000));
  }
}

/* n small triangles and parallelograms, a soup, 0.5 to 20 pixels across:
 * half their corners on the half-pixel grid (edges through pixel
 * centres), some over the window's sides, a quarter at one depth (the id
 * decides), a quarter with corners on the near and far planes or
 * through them (depths at the clamp), the rest between. */
static void small_polygons(mesh_buf *b, zs_rng *rng, int n, int w, int h) {
  for (int i = 0; i < n; i++) {
    double px[4], py[4], pz[4];
    const double cx = zs_rng_range(rng, -12, w + 12), cy = zs_rng_range(rng, -12, h + 12);
    const double size = zs_rng_range(rng, 0.5, 20);
    for (int k = 0; k < 3; k++) {
      px[k] = cx + zs_rng_range(rng, -size, size);
      py[k] = cy + zs_rng_range(rng, -size, size);
      if (zs_rng_below(rng, 2)) { /* on the half-pixel grid */
        px[k] = (double)(int64_t)(2 * px[k]) / 2;
        py[k] = (double)(int64_t)(2 * py[k]) / 2;
      }
      const uint64_t on = zs_rng_below(rng, 3); /* through a plane, or corners on one */
      pz[k] = i % 4 == 0   ? -2.0
              : i % 4 == 1 ? (on == 0 ? 10.0 : on == 1 ? -10.0 : zs_rng_range(rng, -14, 14))
                           : zs_rng_range(rng, -9, -1);
    }
    const int quad = i % 3 == 0;
    if (quad) { /* the fourth corner: a parallelogram, flat */
      px[3] = px[0] + px[2] - px[1];
      py[3] = py[0] + py[2] - py[1];
      pz[3] = pz[0] + pz[2] - pz[1];
    }
    int32_t v[4];
    for (int k = 0; k < 3 + quad; k++) v[k] = mb_vert(b, px[k], py[k], pz[k]);
    mb_face(b, v, 3 + quad, (uint32_t)zs_rng_below(rng, 0x1000000));
  }
}

/* ---- order independence and the two modes ---- */

START_TEST(modes_agree_and_order_does_not_matter) {
  /* Random interpenetrating triangles, many coplanar (equal depth: the id
   * rule decides), drawn in file order and shuffled: all four images are
   * the same to the byte. */
  const int W = 96, H = 72;
  zs_rng rng;
  zs_rng_seed(&rng, 7);
  mesh_buf b = {0};
  random_triangles(&b, &rng, 300, W, H, 10, -5);
  /* the shuffled copy keeps each face's id */
  mesh_buf s = {0};
  int32_t *perm = malloc(300 * sizeof *perm), *ids = malloc(300 * sizeof *ids);
  for (int i = 0; i < 300; i++) perm[i] = i;
  zs_rng_shuffle(&rng, perm, 300, sizeof *perm);
  for (int i = 0; i < b.m.nverts; i++) mb_vert(&s, b.m.pos[3 * i], b.m.pos[3 * i + 1], b.m.pos[3 * i + 2]);
  for (int i = 0; i < 300; i++) {
    mb_face(&s, &b.m.face_vert[3 * perm[i]], 3, b.m.face_rgb[perm[i]]);
    ids[i] = perm[i];
  }
  s.m.face_id = ids;
  uint64_t hash[4];
  int k = 0;
  for (int shuffled = 0; shuffled < 2; shuffled++)
    for (int algo = 0; algo < 2; algo++) {
      frame f = frame_new(W, H);
      render(shuffled ? &s.m : &b.m, W, H, (zs_algo)algo, ZS_SHADE_FLAT, 0, NULL, NULL, &f);
      hash[k++] = zs_test_fnv1a(f.rgb, (size_t)W * H * 4) ^ zs_test_fnv1a(f.depth, (size_t)W * H * 4);
      frame_free(&f);
    }
  ck_assert_uint_eq(hash[0], hash[1]);
  ck_assert_uint_eq(hash[0], hash[2]);
  ck_assert_uint_eq(hash[0], hash[3]);
  free(perm);
  s.m.face_id = NULL;
  free(ids);
  mb_free(&s);
  mb_free(&b);
}
END_TEST

/* The z-buffer mode paints a soup of polygons, and an object's draw, a
 * polygon at a time, and walks a large mesh laid out in order row by row
 * (raster/paint.c); the scanline mode always walks.  For one draw both
 * take the batch's polygons in the same order, so every pixel sees the
 * same fragments in the same order: the same image, depths and ids, and
 * the same spans, pixels tested and pixels written, overwrites included. */
START_TEST(by_polygon_and_scanned_agree_to_the_counter) {
  const int W = 320, H = 240;
  zs_rng rng;
  zs_rng_seed(&rng, 23);
  mesh_buf soup = {0}, grid = {0}, few = {0};
  /* 8,000 small triangles anywhere, at random depths: overdrawn often */
  for (int i = 0; i < 8000; i++) {
    const double cx = zs_rng_range(&rng, -4, W + 4), cy = zs_rng_range(&rng, -4, H + 4);
    int32_t v[3];
    for (int k = 0; k < 3; k++) {
      const double x = cx + zs_rng_range(&rng, -6, 6), y = cy + zs_rng_range(&rng, -6, 6);
      const double z = i % 4 == 0 ? -2.0 : zs_rng_range(&rng, -9, -1);
      v[k] = mb_vert(&soup, x, y, z);
    }
    mb_face(&soup, v, 3, (uint32_t)zs_rng_below(&rng, 0x1000000));
  }
  /* two tilings of 5x5-pixel squares in one mesh, the far one first, the
   * near one tilted through it: 12,288 triangles in row order */
  for (int layer = 0; layer < 2; layer++)
    for (int j = 0; j < H / 5; j++)
      for (int i = 0; i < W / 5; i++) {
        const double z0 = layer ? -1.5 - 0.01 * i : -5.0, z1 = layer ? -1.5 - 0.01 * (i + 1) : -5.0;
        int32_t q[4] = {mb_vert(&grid, 5.0 * i, 5.0 * j, z0), mb_vert(&grid, 5.0 * i + 5, 5.0 * j, z1),
                        mb_vert(&grid, 5.0 * i + 5, 5.0 * j + 5, z1),
                        mb_vert(&grid, 5.0 * i, 5.0 * j + 5, z0)};
        const int32_t t0[3] = {q[0], q[1], q[2]}, t1[3] = {q[0], q[2], q[3]};
        mb_face(&grid, t0, 3, 0x406080);
        mb_face(&grid, t1, 3, 0x804020);
      }
  random_triangles(&few, &rng, 300, W, H, 10, -5);
  /* two layers of faces of 1 to 4 pixels in one mesh, in row order, over
   * a corner of the window and past its sides: quads and triangles, their
   * corners jittered (and some on the half-pixel grid, edges through
   * centres), the near layer tilted through the far one: a mesh over
   * less than a quarter of the window, which the z-buffer mode paints a
   * face at a time, clamping the spans of the faces across its sides. */
  mesh_buf tiny = {0};
  for (int layer = 0; layer < 2; layer++) {
    const double pitch = layer ? 2.5 : 3.25;
    for (int j = 0; j < 14; j++)
      for (int i = 0; i < 20; i++) {
        int32_t q[4];
        for (int c = 0; c < 4; c++) {
          const int ci = i + (c == 1 || c == 2), cj = j + (c >= 2);
          double x = -6.0 + pitch * ci + zs_rng_range(&rng, -0.6, 0.6);
          double y = -4.0 + pitch * cj + zs_rng_range(&rng, -0.6, 0.6);
          if (zs_rng_below(&rng, 3) == 0) { /* on the half-pixel grid */
            x = (double)(int64_t)(2 * x + 64) / 2 - 32;
            y = (double)(int64_t)(2 * y + 64) / 2 - 32;
          }
          const double z = layer ? -1.5 - 0.05 * ci - 0.03 * cj : -3.0;
          q[c] = mb_vert(&tiny, x, y, z);
        }
        if ((i + j) % 2) {
          mb_face(&tiny, q, 4, (uint32_t)zs_rng_below(&rng, 0x1000000));
        } else {
          const int32_t t0[3] = {q[0], q[1], q[2]}, t1[3] = {q[0], q[2], q[3]};
          mb_face(&tiny, t0, 3, (uint32_t)zs_rng_below(&rng, 0x1000000));
          mb_face(&tiny, t1, 3, (uint32_t)zs_rng_below(&rng, 0x1000000));
        }
      }
  }
  const mesh_buf *meshes[] = {&soup, &grid, &few, &tiny};
  for (int m = 0; m < 4; m++) {
    frame f[2] = {frame_new(W, H), frame_new(W, H)};
    zs_raster_stats st[2];
    for (int algo = 0; algo < 2; algo++)
      st[algo] = render(&meshes[m]->m, W, H, (zs_algo)algo, ZS_SHADE_FLAT, 0, NULL, NULL, &f[algo]);
    const size_t n = (size_t)W * H * 4;
    ck_assert_msg(memcmp(f[0].rgb, f[1].rgb, n) == 0 && memcmp(f[0].depth, f[1].depth, n) == 0 &&
                      memcmp(f[0].id, f[1].id, n) == 0,
                  "mesh %d: the modes' pictures differ", m);
    ck_assert_uint_eq(st[0].spans, st[1].spans);
    ck_assert_uint_eq(st[0].pixels_tested, st[1].pixels_tested);
    ck_assert_uint_eq(st[0].pixels_written, st[1].pixels_written);
    uint64_t covered = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) covered += f[0].id[i] != ZS_ID_NONE;
    if (m != 2) /* overwrites to count, whose number the order decides */
      ck_assert_uint_gt(st[0].pixels_written, covered);
    frame_free(&f[0]);
    frame_free(&f[1]);
  }
  mb_free(&soup);
  mb_free(&grid);
  mb_free(&few);
  mb_free(&tiny);
}
END_TEST

START_TEST(simd_spans_equal_scalar) {
  /* Large random triangles through each other, a third of them at one
   * depth (the id decides), and a sphere; then the triangles alone, a
   * soup, which the z-buffer mode paints (at AVX-512 every span in masked
   * steps, paint.c); then a soup of small polygons, which it paints at
   * AVX-512 by their edge functions: the SSE2, AVX2 and AVX-512 span
   * fills (where the CPU has them) and the scalar loop give the same
   * image, depth, ids and counters, in both modes. */
  const int W = 640, H = 480;
  zs_rng rng;
  zs_rng_seed(&rng, 11);
  mesh_buf meshes[3];
  memset(meshes, 0, sizeof meshes);
  random_triangles(&meshes[1], &rng, 400, W, H, 40, -9);
  zs_rng_seed(&rng, 11);
  random_triangles(&meshes[0], &rng, 400, W, H, 40, -9);
  mb_sphere(&meshes[0], W / 2.0, H / 2.0, -5.0, 150.0, 48, 24, 0);
  small_polygons(&meshes[2], &rng, 20000, W, H);
#if defined(__x86_64__)
  /* every x86-64 CPU has SSE2 */
  ck_assert_int_eq(zs_span_simd_level(ZS_SIMD_SSE2), ZS_SIMD_SSE2);
#endif
  ck_assert_int_eq(zs_span_simd_level(ZS_SIMD_SCALAR), ZS_SIMD_SCALAR);
  /* a device asked for a level the CPU lacks falls back to a lower one:
   * that level's comparison then checks nothing, and says so */
  for (int level = ZS_SIMD_SSE2; level <= ZS_SIMD_AVX512; level++)
    if ((int)zs_span_simd_level((zs_simd)level) != level)
      printf("simd_spans_equal_scalar: skipped %s: this CPU lacks it\n", zs_simd_name(level));
  for (int run = 0; run < 6; run++) { /* each mesh in each mode */
    const mesh_buf b = meshes[run / 2];
    const int algo = run % 2;
    frame f[4];
    zs_raster_stats st[4];
    for (int level = ZS_SIMD_SCALAR; level <= ZS_SIMD_AVX512; level++) {
      /* the device's own level: ZS_SPANS_SCALAR .. ZS_SPANS_AVX512 */
      spans_for_devices = (zs_span_fill)(ZS_SPANS_SCALAR + level);
      f[level] = frame_new(W, H);
      st[level] = render(&b.m, W, H, (zs_algo)algo, ZS_SHADE_FLAT, 0, NULL, NULL, &f[level]);
    }
    spans_for_devices = ZS_SPANS_BEST;
    size_t n = (size_t)W * H * 4;
    for (int level = ZS_SIMD_SSE2; level <= ZS_SIMD_AVX512; level++) {
      ck_assert_msg(memcmp(f[0].rgb, f[level].rgb, n) == 0, "%s: colours", zs_simd_name(level));
      ck_assert_msg(memcmp(f[0].depth, f[level].depth, n) == 0, "%s: depths", zs_simd_name(level));
      ck_assert_msg(memcmp(f[0].id, f[level].id, n) == 0, "%s: ids", zs_simd_name(level));
      ck_assert_uint_eq(st[0].pixels_written, st[level].pixels_written);
      ck_assert_uint_eq(st[0].pixels_tested, st[level].pixels_tested);
      frame_free(&f[level]);
    }
    ck_assert_uint_gt(st[0].pixels_written, (uint64_t)W * H); /* overdrawn */
    frame_free(&f[0]);
  }
  for (int i = 0; i < 3; i++) mb_free(&meshes[i]);
}
END_TEST

START_TEST(folded_face_painted_as_walked) {
  /* A pentagon whose every turn is the way of its area or straight, but
   * one straight back along a row (4 -> 0 after 3 -> 4): the fold hides a
   * reflex corner at 3, and the line of edge 3-2 cuts the pixel (7, 6)
   * that the walk's edges give the face.  Set-up draws such a face as a
   * fan; at every span fill level, in both modes, the same pixels and
   * counters. */
  const int S = 16;
  const double px[5] = {8, 7, 6.5, 7, 6.5}, py[5] = {6.5, 5, 7.5, 6.5, 6.5}; /* image, y down */
  mesh_buf b = {0};
  int32_t v[5];
  for (int k = 0; k < 5; k++) v[k] = mb_vert(&b, px[k], S - py[k], -2);
  mb_face(&b, v, 5, 0xFFFFFF);
  frame f[2][2];
  zs_raster_stats st[2][2];
  for (int algo = 0; algo < 2; algo++)
    for (int k = 0; k < 2; k++) {
      spans_for_devices = k ? ZS_SPANS_BEST : ZS_SPANS_SCALAR;
      f[algo][k] = frame_new(S, S);
      st[algo][k] = render(&b.m, S, S, (zs_algo)algo, ZS_SHADE_ID, 0, NULL, NULL, &f[algo][k]);
    }
  spans_for_devices = ZS_SPANS_BEST;
  for (int algo = 0; algo < 2; algo++)
    for (int k = 0; k < 2; k++) {
      ck_assert_msg(memcmp(f[0][0].id, f[algo][k].id, (size_t)S * S * 4) == 0,
                    "mode %d, level %d: ids", algo, k);
      ck_assert_uint_eq(st[0][0].pixels_tested, st[algo][k].pixels_tested);
      ck_assert_uint_eq(st[0][0].spans, st[algo][k].spans);
    }
  ck_assert_uint_eq(f[0][0].id[6 * S + 7], 0); /* the pixel the fold's edge cuts is the face's */
  for (int algo = 0; algo < 2; algo++)
    for (int k = 0; k < 2; k++) frame_free(&f[algo][k]);
  mb_free(&b);
}
END_TEST

START_TEST(flat_levels_simd_equal_scalar) {
  /* The flat levels eight at a time (AVX-512) against zs_flat_level, one
   * face at a time, on 2,003 normals (not a multiple of eight), random in
   * kind and at scales from 1e-300 to 1e300: squares that underflow to 0
   * or overflow to infinity, squares that are subnormal (whose rounding
   * takes the cosine past 1, where the clamp keeps the level 255), along
   * the light and against it, across it (cosine near 0), and cosines
   * whose level lies a hair from a rounding tie k + 1/2 (where an
   * operation taken in another order or rounded otherwise shows); then
   * zero and minus zero, infinite and NaN components.  The counts below
   * say that each kind is there. */
  if (zs_span_simd_level(ZS_SIMD_AVX512) != ZS_SIMD_AVX512) {
    printf("flat_levels_simd_equal_scalar: skipped: this CPU lacks AVX-512\n");
    return;
  }
  enum { N = 2003 };
  static double nx[N], ny[N], nz[N];
  static uint32_t q[2][N];
  const double l[3] = {0.2672612419124244, 0.5345224838248488, 0.8017837257372732};
  const double scale[] = {1e-300, 1e-170, 3e-162, 1e-150, 1e-8, 1.0, 3.5, 1e8, 1e150, 1e300};
  zs_rng rng;
  zs_rng_seed(&rng, 31);
  for (int k = 0; k < N; k++) {
    const double s = scale[k % 10];
    const int kind = (k / 10) % 6;
    double n[3];
    for (int c = 0; c < 3; c++) n[c] = zs_rng_range(&rng, -1.0, 1.0);
    if (kind == 1) { /* along the light or against it, a little off */
      const double sign = (k / 60) % 2 ? -1.0 : 1.0, off = 1.0 + n[0] * 1e-9;
      for (int c = 0; c < 3; c++) n[c] = sign * l[c] * off;
    }
    if (kind == 2) /* across it: n . L near 0 */
      n[2] = -(n[0] * l[0] + n[1] * l[1]) / l[2];
    if (kind >= 3) { /* a level a hair from a tie */
      const double c = ((double)(64 + k % 191) + 0.5) / 255.0, t = (c - 0.25) / 0.75;
      const double rl = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
      double p[3], pl = 0.0;
      for (int j = 0; j < 3; j++) p[j] = n[j] - rl * l[j], pl += p[j] * p[j];
      pl = sqrt(pl);
      for (int j = 0; j < 3; j++) n[j] = t * l[j] + sqrt(1.0 - t * t) * p[j] / pl;
    }
    nx[k] = s * n[0], ny[k] = s * n[1], nz[k] = s * n[2];
  }
  const double odd[][3] = {{0, 0, 0},       {-0.0, 0, -0.0},     {INFINITY, 1, 0},
                           {1, -INFINITY, 1}, {NAN, 1, 1},       {1, 1, NAN},
                           {INFINITY, INFINITY, INFINITY}, {1e-320, 0, 0}, {0, 0, 1e308}};
  for (size_t j = 0; j < sizeof odd / sizeof odd[0]; j++)
    nx[7 * j + 3] = odd[j][0], ny[7 * j + 3] = odd[j][1], nz[7 * j + 3] = odd[j][2];
  zs_flat_levels_for(ZS_SIMD_SCALAR)(nx, ny, nz, N, q[0]);
  zs_flat_levels_for(ZS_SIMD_AVX512)(nx, ny, nz, N, q[1]);
  int past_one = 0, across = 0, near_tie = 0, no_length = 0, nan_cosine = 0;
  for (int k = 0; k < N; k++) {
    ck_assert_msg(q[0][k] == zs_flat_level((const double[3]){nx[k], ny[k], nz[k]}), "face %d", k);
    ck_assert_msg(q[1][k] == q[0][k], "face %d: (%g, %g, %g): level %u, not %u", k, nx[k], ny[k],
                  nz[k], q[1][k], q[0][k]);
    /* the kinds, from zs_flat_level's own steps before its clamp */
    const double len = sqrt(nx[k] * nx[k] + ny[k] * ny[k] + nz[k] * nz[k]);
    const double cosine = fabs(nx[k] * l[0] + ny[k] * l[1] + nz[k] * l[2]) / len;
    const double level = 255.0 * (0.25 + 0.75 * cosine);
    no_length += len == 0.0 || isinf(len);
    nan_cosine += len > 0.0 && cosine != cosine;
    past_one += len > 0.0 && cosine > 1.0;
    across += len > 0.0 && !isinf(len) && q[0][k] == 64; /* 255 / 4 rounded: cosine 0 */
    near_tie += fabs(level - floor(level) - 0.5) < 1e-12;
  }
  ck_assert_int_gt(past_one, 20);
  ck_assert_int_gt(across, 100);
  ck_assert_int_gt(near_tie, 300);
  ck_assert_int_gt(no_length, 100);
  ck_assert_int_gt(nan_cosine, 1);
}
END_TEST

START_TEST(a_failed_draw_leaves_its_earlier_faces_as_drawn) {
  /* A draw whose second face uses a vertex out of range fails.  In
   * scanline and depth sort modes the face set up before it stays in the
   * frame's batch and is painted with the colour (its flat level) and the
   * depth it gets drawn alone: the face stage's deferred work is done on
   * the error path too.  zbuffer mode drops the draw. */
  enum { S = 48 };
  double pos[] = {4, 4, -1, 40, 6, -2, 38, 36, -3, 5, 30, -1.5};
  int32_t fs[] = {0, 4, 8}, fv[] = {0, 1, 2, 3, 0, 1, 2, 9};
  uint32_t frgb[] = {0xC08040, 0xFFFFFF};
  const zs_mesh bad = {.pos = pos, .nverts = 4, .face_start = fs, .face_vert = fv, .nfaces = 2, .face_rgb = frgb},
                good = {.pos = pos, .nverts = 4, .face_start = fs, .face_vert = fv, .nfaces = 1, .face_rgb = frgb};
  for (int algo = ZS_ALGO_ZBUFFER; algo <= ZS_ALGO_DEPTHSORT; algo++) {
    frame alone = frame_new(S, S), failed = frame_new(S, S);
    render(&good, S, S, (zs_algo)algo, ZS_SHADE_FLAT, 0, NULL, NULL, &alone);
    zs_device *d = device(S, S, (zs_algo)algo, ZS_SHADE_FLAT, 0);
    ortho_camera(d, S, S, -10, 10);
    zs_device_clear(d);
    zs_error err;
    zs_error_clear(&err);
    ck_assert_int_eq(zs_device_draw(d, &bad, NULL, 0, ZS_RGB_MESH, &err), ZS_ERR_ARG);
    ck_assert_ptr_nonnull(strstr(err.msg, "uses vertex 9"));
    ck_assert_int_eq(zs_device_finish(d, frame_sink, &failed, &err), ZS_OK);
    zs_device_destroy(d);
    int drawn = 0;
    for (int i = 0; i < S * S; i++)
      if (alone.id[i] != ZS_ID_NONE) {
        drawn++;
        ck_assert_uint_ne(alone.rgb[i], 0xC08040); /* shaded, not the bare colour */
      }
    ck_assert_int_gt(drawn, 500);
    if (algo == ZS_ALGO_ZBUFFER) {
      for (int i = 0; i < S * S; i++) ck_assert_uint_eq(failed.id[i], ZS_ID_NONE);
    } else {
      ck_assert_mem_eq(alone.rgb, failed.rgb, S * S * 4);
      ck_assert_mem_eq(alone.depth, failed.depth, S * S * 4);
      ck_assert_mem_eq(alone.id, failed.id, S * S * 4);
    }
    frame_free(&alone);
    frame_free(&failed);
  }
}
END_TEST

/* The vertex stage of vertices [FROM, n) of pos on a 256 x 256 device at
 * the span fill's scalar level (v[0]) and at AVX-512 (v[1]), under view
 * and proj. */
static void vertex_stage_both(double *pos, int n, const double view[16], const double proj[16],
                              zs_vert_scratch v[2], double *gx, double *gy) {
  enum { FROM = 5 };
  zs_mesh m = {.pos = pos, .nverts = n};
  for (int k = 0; k < 2; k++) {
    zs_device_config cfg = {256, 256, ZS_ALGO_ZBUFFER, ZS_SHADE_FLAT, 0, 1, 0,
                            k ? ZS_SPANS_AVX512 : ZS_SPANS_SCALAR, 0};
    zs_device *d = NULL;
    zs_error err;
    zs_error_clear(&err);
    ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
    ck_assert_int_eq(zs_device_simd(d), k ? ZS_SIMD_AVX512 : ZS_SIMD_SCALAR);
    zs_device_set_camera(d, view, proj);
    double model[16];
    zs_mat_identity(model);
    zs_draw_prep prep;
    zs_draw_prepare(&d->state_of[ZS_KERNEL_DRAW].prep, d->view, d->proj, model, &prep);
    ck_assert(prep.need_eye);
    ck_assert(zs_vert_scratch_reserve(&v[k], n));
    memset(v[k].snap, 0, (size_t)n * sizeof *v[k].snap);
    zs_draw_transform(&prep, &m, &v[k], FROM, n);
    *gx = d->gx;
    *gy = d->gy;
    zs_device_destroy(d);
  }
}

/* Every bit of clip space, outcode, eye space and (inside every plane)
 * the snapped position equal at both levels; the outcodes and the
 * vertices inside, for the caller. */
static int same_bits(const zs_vert_scratch v[2], int from, int n, int *inside) {
  int in = 0;
  for (int i = from; i < n; i++) {
    ck_assert_msg(memcmp(&v[0].clip[i], &v[1].clip[i], sizeof v[0].clip[i]) == 0, "clip %d", i);
    ck_assert_msg(memcmp(&v[0].eyepos[3 * i], &v[1].eyepos[3 * i], 3 * sizeof(double)) == 0,
                  "eye %d", i);
    ck_assert_uint_eq(v[0].outcode[i], v[1].outcode[i]);
    if (v[0].outcode[i]) continue;
    in++;
    ck_assert_msg(v[0].snap[i].x == v[1].snap[i].x && v[0].snap[i].y == v[1].snap[i].y,
                  "snap %d: (%d, %d) against (%d, %d)", i, v[0].snap[i].x, v[0].snap[i].y,
                  v[1].snap[i].x, v[1].snap[i].y);
    ck_assert_msg(memcmp(&v[0].snap[i].z, &v[1].snap[i].z, sizeof(double)) == 0, "z %d", i);
  }
  *inside = in;
  return n - from - in;
}

START_TEST(vertex_stage_simd_equals_scalar) {
  /* The vertex stage eight at a time (AVX-512) against the scalar loop,
   * bit for bit.  Under a perspective camera: 1,000 points in the view,
   * beyond each plane and the guard band, behind the eye, huge, NaN and
   * infinite.  Under a camera whose clip space is (x, y, z, -z), placed
   * by hand: on each plane exactly, at w = 0 (the origin is inside every
   * plane and snaps to NaN), w < 0, and at rounding ties of the subpixel
   * grid (x + 1 = (2k + 1) / 2^16 on a 256-pixel window: half a
   * subpixel), even and odd k.  Both ranges start and end off a multiple
   * of eight. */
  if (zs_span_simd_level(ZS_SIMD_AVX512) != ZS_SIMD_AVX512) {
    printf("vertex_stage_simd_equals_scalar: skipped: this CPU lacks AVX-512\n");
    return;
  }
  enum { N = 1003, FROM = 5 };
  zs_rng rng;
  zs_rng_seed(&rng, 23);
  double *pos = malloc(3 * N * sizeof *pos);
  ck_assert_ptr_nonnull(pos);
  for (int i = 0; i < N; i++) {
    const double r = i % 4 == 0 ? 0.6 : i % 4 == 1 ? 3.0 : i % 4 == 2 ? 40.0 : 1e6;
    for (int c = 0; c < 3; c++) pos[3 * i + c] = zs_rng_range(&rng, -r, r);
  }
  pos[3 * 17 + 2] = NAN;
  pos[3 * 40] = INFINITY;
  zs_vert_scratch v[2] = {{0}, {0}};
  double view[16], proj[16], gx, gy;
  zs_mat_look_at(view, (double[3]){0.3, 0.4, 3.0}, (double[3]){0, 0, 0}, (double[3]){0, 1, 0});
  zs_mat_perspective(proj, 50, 1.0, 0.5, 10);
  vertex_stage_both(pos, N, view, proj, v, &gx, &gy);
  int inside;
  const int outside = same_bits(v, FROM, N, &inside);
  ck_assert_int_gt(inside, 100);
  ck_assert_int_gt(outside, 100);
  ck_assert_uint_eq(v[0].outcode[17], ZS_CLIP_NEAR | ZS_CLIP_FAR | ZS_CLIP_LEFT | ZS_CLIP_RIGHT |
                                          ZS_CLIP_BOTTOM | ZS_CLIP_TOP); /* NaN: out of all */

  /* clip space (x, y, z, -z) */
  zs_mat_identity(view);
  zs_mat_identity(proj);
  proj[10] = 1.0, proj[14] = -1.0, proj[15] = 0.0;
  enum { M = 45 };
  double hand[3 * M];
  int n = 0;
#define PUT(X, Y, Z) (hand[3 * n] = (X), hand[3 * n + 1] = (Y), hand[3 * n + 2] = (Z), n++)
  for (int k = 0; k < FROM; k++) PUT(0.0, 0.0, -1.0); /* before the range */
  PUT(0.0, 0.0, 0.0);                                 /* w = 0: inside, NaN snap */
  PUT(0.0, 0.0, -0.0);
  PUT(1.0, 0.0, 0.0);                                 /* w = 0, beyond the right plane */
  PUT(0.5, 0.5, 1.0);                                 /* w = -1: behind the eye */
  PUT(0.0, 0.0, -1.0);                                /* z + w = 0: on the near plane */
  PUT(0.25, -0.25, -2.0);
  double g[2];
  vertex_stage_both(hand, n, view, proj, v, &g[0], &g[1]); /* the guard band, to place on it */
  for (int s = -1; s <= 1; s += 2) {                         /* on the left, right, top, bottom */
    PUT(s * g[0], 0.0, -1.0);
    PUT(0.0, s * g[1], -1.0);
    PUT(s * 2.0 * g[0], 0.0, -2.0);
  }
  for (int k = 0; k < 8; k++) { /* ties: half a subpixel, k even and odd */
    const double t = -1.0 + (2.0 * (100 * k + k % 2) + 1.0) / 65536.0;
    PUT(t, 0.0, -1.0);
    PUT(0.0, t, -1.0);
    PUT(t, t, -1.0);
  }
#undef PUT
  ck_assert_int_le(n, M);
  vertex_stage_both(hand, n, view, proj, v, &gx, &gy);
  const int out_hand = same_bits(v, FROM, n, &inside);
  ck_assert_int_gt(inside, 24);
  ck_assert_int_gt(out_hand, 1);
  ck_assert_uint_eq(v[0].outcode[FROM], 0u); /* the origin: inside, at w = 0 */
  ck_assert(isnan(v[1].snap[FROM].z));
  ck_assert_uint_eq(v[0].outcode[FROM + 4], 0u); /* on the near plane: inside */
  zs_vert_scratch_free(&v[0]);
  zs_vert_scratch_free(&v[1]);
  free(pos);
}
END_TEST

START_TEST(scanline_bands_start_each_frame_clean) {
  /* Scanline mode on threads walks bands into buffers it keeps from frame
   * to frame, cleared row by row as the walk reaches them: a second frame
   * on the same device, with fewer faces than the first, is the one
   * thread's second frame to the byte, in overdraw shading (its counts)
   * and flat (depth, ids, colours). */
  const int W = 160, H = 120;
  zs_rng rng;
  zs_rng_seed(&rng, 31);
  mesh_buf heavy = {0}, light = {0};
  random_triangles(&heavy, &rng, 300, W, H, 10, -9);
  random_triangles(&light, &rng, 12, W, H, 10, -9);
  for (int shade = 0; shade < 2; shade++) {
    const zs_shade sh = shade ? ZS_SHADE_OVERDRAW : ZS_SHADE_FLAT;
    frame f[2];
    zs_raster_stats st[2];
    for (int k = 0; k < 2; k++) {
      zs_device_config cfg = {W, H, ZS_ALGO_SCANLINE, sh, 0, k ? 3 : 1, 0, ZS_SPANS_BEST, 0};
      zs_device *d = NULL;
      zs_error err;
      zs_error_clear(&err);
      ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
      ortho_camera(d, W, H, -10, 10);
      for (int frame_no = 0; frame_no < 2; frame_no++) {
        zs_device_clear(d);
        f[k] = frame_new(W, H);
        ck_assert_int_eq(zs_device_draw(d, frame_no ? &light.m : &heavy.m, NULL, 0, ZS_RGB_MESH,
                                        &err),
                         ZS_OK);
        ck_assert_int_eq(zs_device_finish(d, frame_sink, &f[k], &err), ZS_OK);
        if (!frame_no) frame_free(&f[k]); /* the first frame only fills the bands */
      }
      st[k] = *zs_device_stats(d);
      zs_device_destroy(d);
    }
    const size_t n = (size_t)W * H * 4;
    ck_assert_msg(memcmp(f[0].rgb, f[1].rgb, n) == 0, "shade %d: colours", shade);
    ck_assert_msg(memcmp(f[0].depth, f[1].depth, n) == 0, "shade %d: depths", shade);
    ck_assert_msg(memcmp(f[0].id, f[1].id, n) == 0, "shade %d: ids", shade);
    ck_assert_uint_eq(st[0].pixels_written, st[1].pixels_written);
    ck_assert_uint_gt(st[0].pixels_written, 0);
    frame_free(&f[0]);
    frame_free(&f[1]);
  }
  mb_free(&heavy);
  mb_free(&light);
}
END_TEST

START_TEST(scanline_memory_grows_with_width_not_area) {
  /* The same sphere at four sizes: scanline mode's pixel buffers are rows
   * (width), zbuffer mode's the frame (area); the polygon tables do not
   * depend on the image's width at all. */
  mesh_buf b = {0};
  mb_sphere(&b, 0.5, 0.5, -3.0, 0.4, 64, 32, 0);
  const int sizes[4][2] = {{256, 192}, {1024, 192}, {256, 768}, {1024, 768}};
  zs_device_memory mem[2][4];
  for (int algo = 0; algo < 2; algo++)
    for (int k = 0; k < 4; k++) {
      int w = sizes[k][0], h = sizes[k][1];
      zs_device *d = device(w, h, (zs_algo)algo, ZS_SHADE_FLAT, 0);
      double view[16], proj[16];
      zs_mat_identity(view);
      zs_mat_ortho(proj, 0, 1, 0, 1, 0.5, 10);
      zs_device_set_camera(d, view, proj);
      zs_device_clear(d);
      zs_error err;
      zs_error_clear(&err);
      ck_assert_int_eq(zs_device_draw(d, &b.m, NULL, 0, ZS_RGB_MESH, &err), ZS_OK);
      ck_assert_int_eq(zs_device_finish(d, NULL, NULL, &err), ZS_OK);
      mem[algo][k] = zs_device_memory_of(d);
      zs_device_destroy(d);
    }
  const zs_device_memory *z = mem[ZS_ALGO_ZBUFFER], *s = mem[ZS_ALGO_SCANLINE];
  /* scanline: four rows of 4 bytes per pixel of width, and the shaded row */
  for (int k = 0; k < 4; k++) ck_assert_uint_eq(s[k].pixel_buffers, (size_t)sizes[k][0] * 5 * 4);
  ck_assert_uint_eq(s[0].pixel_buffers, s[2].pixel_buffers); /* 4x the height: the same */
  /* zbuffer: depth, id and colour for every pixel, the shaded row, the
   * blank row's four buffers and a flag a row (cleared or not) */
  for (int k = 0; k < 4; k++)
    ck_assert_uint_eq(z[k].pixel_buffers, (size_t)sizes[k][0] * sizes[k][1] * 12 +
                                              (size_t)sizes[k][0] * 4 * 5 + (size_t)sizes[k][1]);
  ck_assert_uint_eq(s[0].tables, s[1].tables); /* 4x the width: the same tables */
  mb_free(&b);
}
END_TEST

START_TEST(depth_stepping_equals_evaluation) {
  /* Steep and shallow planes: the depth the walk wrote at each pixel equals
   * the plane evaluated there in double, to within one unit of the 32-bit
   * depth (the plane is quantized once; stepping adds nothing).  The
   * second face runs from the near plane to the far one across the whole
   * window: its depths are clamped at both ends, and the walk may skip
   * neither the clamp of its spans nor the test of its depths (setup.c,
   * spans_inner). */
  const int W = 64, H = 64;
  /* x, y_win, distance along the view axis (ortho near -10 far 10) */
  const double faces[2][3][3] = {{{1, 1, 1}, {63, 5, 9}, {20, 62, 4}},
                                 {{0, 0, -10}, {64, 3, 10}, {10, 64, 0}}};
  for (int k = 0; k < 2; k++) {
    const double(*P)[3] = faces[k];
    mesh_buf b = {0};
    int32_t v[3];
    for (int i = 0; i < 3; i++) v[i] = mb_vert(&b, P[i][0], P[i][1], -P[i][2]);
    mb_face(&b, v, 3, 0xFFFFFF);
    frame f = frame_new(W, H);
    render(&b.m, W, H, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, NULL, NULL, &f);
    /* window depth = (distance + 10) / 20, on the plane through P */
    double ux = P[1][0] - P[0][0], uy = P[1][1] - P[0][1], uz = P[1][2] - P[0][2];
    double vx = P[2][0] - P[0][0], vy = P[2][1] - P[0][1], vz = P[2][2] - P[0][2];
    double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    int checked = 0;
    for (int y = 0; y < H; y++)
      for (int x = 0; x < W; x++) {
        if (f.id[y * W + x] == ZS_ID_NONE) continue;
        double cx = x + 0.5, cy = H - (y + 0.5);
        double dist = P[0][2] - (nx * (cx - P[0][0]) + ny * (cy - P[0][1])) / nz;
        double want = (dist + 10.0) / 20.0 * 4294967296.0;
        want = want < 0.0 ? 0.0 : want > 4294967295.0 ? 4294967295.0 : want;
        ck_assert_msg(fabs(f.depth[y * W + x] - want) <= 2.0, "face %d pixel %d,%d: %u vs %.1f",
                      k, x, y, f.depth[y * W + x], want);
        checked++;
      }
    ck_assert_int_gt(checked, 1500);
    frame_free(&f);
    mb_free(&b);
  }
}
END_TEST

/* Renders b in zbuffer mode with flat shading on `threads` threads under a
 * perspective camera; the device's buffers go to f, its counters are
 * returned; the draw's status to *st (and its message to msg). */
/* A device of the mode (zbuffer unless algo_of_next says otherwise) with
 * flat shading on `threads` threads, cleared, under a perspective camera
 * at eye looking at the origin. */
static zs_algo algo_of_next = ZS_ALGO_ZBUFFER;
static zs_device *perspective_device(const frame *f, int threads, double ex, double ey,
                                     double ez) {
  zs_device_config cfg = {f->w, f->h, algo_of_next, ZS_SHADE_FLAT, 0, threads, 0, 0, 0};
  zs_device *d = NULL;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
  double view[16], proj[16];
  zs_mat_look_at(view, (double[3]){ex, ey, ez}, (double[3]){0, 0, 0}, (double[3]){0, 1, 0});
  zs_mat_perspective(proj, 50, (double)f->w / f->h, 0.5, 10);
  zs_device_clear(d);
  zs_device_set_camera(d, view, proj);
  return d;
}

static zs_raster_stats render_threads(const zs_mesh *m, int threads, frame *f, zs_status *st,
                                      char *msg, size_t cap) {
  zs_device *d = perspective_device(f, threads, 0.3, 0.4, 3.0);
  zs_error err;
  zs_error_clear(&err);
  *st = zs_device_draw(d, m, NULL, 0, ZS_RGB_MESH, &err);
  snprintf(msg, cap, "%s", err.msg);
  if (*st == ZS_OK) ck_assert_int_eq(zs_device_finish(d, frame_sink, f, &err), ZS_OK);
  zs_raster_stats s = *zs_device_stats(d);
  zs_device_destroy(d);
  return s;
}

START_TEST(large_draws_set_up_on_threads_give_the_same_bytes) {
  /* A sphere of 24,000 faces (above the size at which a draw's set-up is
   * split over the threads), part of it outside the frustum: every buffer
   * and every counter equal for 1 to 4 threads.  Then a face with a vertex
   * out of range in the last part: the same error, the same counters. */
  mesh_buf b = {0};
  mb_sphere(&b, 0.4, 0, 0, 1.3, 200, 120, 0);
  ck_assert_int_gt(b.m.nfaces, 20000);
  frame one = frame_new(200, 150);
  zs_status st;
  char msg1[ZS_ERROR_MSG_MAX], msgn[ZS_ERROR_MSG_MAX];
  zs_raster_stats s1 = render_threads(&b.m, 1, &one, &st, msg1, sizeof msg1);
  ck_assert_int_eq(st, ZS_OK);
  ck_assert_uint_gt(s1.polygons_outside + s1.polygons_offscreen, 0);
  for (int threads = 2; threads <= 4; threads++) {
    frame many = frame_new(200, 150);
    zs_raster_stats sn = render_threads(&b.m, threads, &many, &st, msgn, sizeof msgn);
    ck_assert_int_eq(st, ZS_OK);
    ck_assert_mem_eq(&s1, &sn, sizeof s1);
    ck_assert_mem_eq(one.rgb, many.rgb, 200 * 150 * 4);
    ck_assert_mem_eq(one.depth, many.depth, 200 * 150 * 4);
    ck_assert_mem_eq(one.id, many.id, 200 * 150 * 4);
    frame_free(&many);
  }
  b.m.face_vert[b.m.face_start[b.m.nfaces - 3]] = b.m.nverts + 7;
  frame bad = frame_new(200, 150);
  s1 = render_threads(&b.m, 1, &bad, &st, msg1, sizeof msg1);
  ck_assert_int_eq(st, ZS_ERR_ARG);
  zs_raster_stats sn = render_threads(&b.m, 3, &bad, &st, msgn, sizeof msgn);
  ck_assert_int_eq(st, ZS_ERR_ARG);
  ck_assert_str_eq(msg1, msgn);
  ck_assert_ptr_nonnull(strstr(msg1, "uses vertex"));
  ck_assert_uint_eq(s1.polygons_in, sn.polygons_in);
  ck_assert_uint_eq(s1.polygons_rasterized, sn.polygons_rasterized);
  frame_free(&bad);
  frame_free(&one);
  mb_free(&b);
}
END_TEST

/* One frame of many small draws: spheres of 60 faces at seeded places,
 * every third one drawn twice at the same place in another colour (equal
 * depths: which draw writes depends on the order), with a query box in
 * the middle and, when bad >= 0, a face out of range in draw bad.  Deferred
 * when defer is set: the bad draw is queued like the others, and the
 * draws after it too until a flush reports it (the large draw 120 flushes
 * first), so the queue holds draws behind the one that fails.  The buffers go to f; the
 * counters, the clock and the query's samples are returned through the
 * pointers; the status of the first failing call is returned. */
enum { SMALL_DRAWS = 150 };

static zs_status small_draws_frame(const mesh_buf *m, int threads, int defer, int bad, frame *f,
                                   zs_raster_stats *stats, zs_clock_stats *clock,
                                   int64_t *frame_ps, uint64_t *samples, char *msg, size_t cap) {
  zs_device *d = perspective_device(f, threads, 0.0, 0.0, 4.0);
  zs_error err;
  zs_error_clear(&err);
  zs_device_defer_draws(d, defer);
  zs_status st = ZS_OK;
  *samples = 0;
  for (int i = 0; i < SMALL_DRAWS && st == ZS_OK; i++) {
    const zs_mesh *mesh = &m[i == bad ? SMALL_DRAWS : i / 3 * 3].m;
    uint32_t rgb = 0x204060u + (uint32_t)i * 0x010203u;
    st = zs_device_draw(d, mesh, NULL, (uint32_t)(i / 3 * 3) * 1000u, rgb, &err);
    if (st == ZS_OK && i == SMALL_DRAWS / 2 && algo_of_next == ZS_ALGO_ZBUFFER) {
      zs_query q;
      if ((st = zs_device_query_begin(d, &q, &err)) == ZS_OK &&
          (st = zs_device_query_box(d, (double[3]){-0.2, -0.2, -0.5}, (double[3]){0.2, 0.2, 0.5},
                                    &err)) == ZS_OK &&
          (st = zs_device_query_end(d, &err)) == ZS_OK)
        *samples = zs_device_query_result(d, q);
    }
  }
  if (st == ZS_OK) st = zs_device_flush(d, &err);
  snprintf(msg, cap, "%s", err.msg);
  ck_assert_int_eq(zs_device_finish(d, frame_sink, f, &err), ZS_OK);
  *stats = *zs_device_stats(d);
  *clock = *zs_device_clock(d);
  *frame_ps = zs_device_frame_ps(d);
  zs_device_destroy(d);
  return st;
}

/* The spheres of small_draws_frame: 150 draws, some of them large. */
static void small_draws_meshes(mesh_buf *m) {
  memset(m, 0, (SMALL_DRAWS + 1) * sizeof *m);
  zs_rng rng;
  zs_rng_seed(&rng, 7);
  for (int i = 0; i < SMALL_DRAWS; i += 3) {
    double x = zs_rng_below(&rng, 2001) / 1000.0 - 1.0, y = zs_rng_below(&rng, 1501) / 1000.0 - 0.75;
    double z = zs_rng_below(&rng, 1001) / 1000.0 - 0.5, r = 0.1 + zs_rng_below(&rng, 201) / 1000.0;
    mb_sphere(&m[i], x, y, z, r, 10, 6, 0);
  }
  /* draws 39-41 are queued too (66,560 faces), draws 120-122 drawn at
   * once (266,240 faces: the queue is flushed before each) */
  mb_free(&m[39]);
  mb_sphere(&m[39], 0.3, -0.2, 0.2, 0.25, 260, 256, 0);
  mb_free(&m[120]);
  mb_sphere(&m[120], -0.4, 0.3, -0.1, 0.3, 520, 512, 0);
  mb_sphere(&m[SMALL_DRAWS], 0, 0, 0, 0.3, 10, 6, 0);
  m[SMALL_DRAWS].m.face_vert[m[SMALL_DRAWS].m.face_start[20]] = m[SMALL_DRAWS].m.nverts;
  /* either side of the queue's limit, ZS_DEFER_MAX_FACES (raster.h) */
  ck_assert_int_lt(m[39].m.nfaces, 262144);
  ck_assert_int_ge(m[120].m.nfaces, 262144);
}

/* Every buffer, every counter, the modelled clock and a query's samples
 * (zbuffer mode) of the draws queued on 2 to 4 threads equal those of the
 * same draws made at once on one thread; with a bad face in draw 100, the
 * same error, and the 100 draws before it (not the 19 queued behind it). */
static void deferred_equals_at_once(zs_algo algo, const mesh_buf *m) {
  algo_of_next = algo;
  for (int bad = -1; bad <= 100; bad += 101) {
    frame one = frame_new(160, 120);
    zs_raster_stats s1, sn;
    zs_clock_stats c1, cn;
    int64_t f1, fn;
    uint64_t q1, qn;
    char msg1[ZS_ERROR_MSG_MAX], msgn[ZS_ERROR_MSG_MAX];
    zs_status st1 = small_draws_frame(m, 1, 0, bad, &one, &s1, &c1, &f1, &q1, msg1, sizeof msg1);
    ck_assert_int_eq(st1, bad < 0 ? ZS_OK : ZS_ERR_ARG);
    if (bad < 0 && algo == ZS_ALGO_ZBUFFER) ck_assert_uint_gt(q1, 0);
    for (int threads = 2; threads <= 4; threads++) {
      frame many = frame_new(160, 120);
      zs_status stn =
          small_draws_frame(m, threads, 1, bad, &many, &sn, &cn, &fn, &qn, msgn, sizeof msgn);
      ck_assert_int_eq(stn, st1);
      ck_assert_str_eq(msgn, msg1);
      ck_assert_mem_eq(&s1, &sn, sizeof s1);
      ck_assert_mem_eq(&c1, &cn, sizeof c1);
      ck_assert_int_eq(f1, fn);
      ck_assert_uint_eq(q1, qn);
      ck_assert_mem_eq(one.rgb, many.rgb, 160 * 120 * 4);
      ck_assert_mem_eq(one.depth, many.depth, 160 * 120 * 4);
      ck_assert_mem_eq(one.id, many.id, 160 * 120 * 4);
      frame_free(&many);
    }
    frame_free(&one);
  }
  algo_of_next = ZS_ALGO_ZBUFFER;
}

START_TEST(deferred_small_draws_land_as_drawn_at_once) {
  /* Queued draws, set up in chunks and walked in bands (zbuffer mode) or
   * set up in chunks and walked in bands at finish (scanline mode; depth
   * sort draws at once but walks in bands), against the same draws made
   * at once on one thread. */
  mesh_buf m[SMALL_DRAWS + 1];
  small_draws_meshes(m);
  deferred_equals_at_once(ZS_ALGO_ZBUFFER, m);
  deferred_equals_at_once(ZS_ALGO_SCANLINE, m);
  deferred_equals_at_once(ZS_ALGO_DEPTHSORT, m);

  /* the queue is real: before the flush nothing is written or counted */
  zs_device_config cfg = {160, 120, ZS_ALGO_ZBUFFER, ZS_SHADE_FLAT, 0, 2, 0, 0, 0};
  zs_device *d = NULL;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
  zs_device_clear(d);
  zs_device_defer_draws(d, 1);
  for (int i = 0; i < 30; i += 3)
    ck_assert_int_eq(zs_device_draw(d, &m[i].m, NULL, 0, ZS_RGB_MESH, &err), ZS_OK);
  ck_assert_uint_eq(zs_device_stats(d)->draws, 0);
  ck_assert_uint_eq(zs_device_stats(d)->polygons_in, 0);
  ck_assert_int_eq(zs_device_clock(d)->cpu_ps, 0);
  ck_assert_int_eq(zs_device_flush(d, &err), ZS_OK);
  ck_assert_uint_eq(zs_device_stats(d)->draws, 10);
  ck_assert_uint_eq(zs_device_stats(d)->polygons_in, 10 * (uint64_t)m[0].m.nfaces);
  ck_assert_uint_gt(zs_device_stats(d)->pixels_written, 0);
  /* a fill of the colour buffer (hidden-line paper) lands after the
   * queued draws, not under them */
  zs_device_clear(d);
  for (int i = 0; i < 30; i += 3)
    ck_assert_int_eq(zs_device_draw(d, &m[i].m, NULL, 0, ZS_RGB_MESH, &err), ZS_OK);
  ck_assert_int_eq(zs_device_fill_color(d, 0x123456, &err), ZS_OK);
  ck_assert_uint_gt(zs_device_stats(d)->pixels_written, 0);
  frame painted = frame_new(160, 120);
  ck_assert_int_eq(zs_device_finish(d, frame_sink, &painted, &err), ZS_OK);
  for (int i = 0; i < 160 * 120; i++) ck_assert_uint_eq(painted.rgb[i], 0x123456);
  frame_free(&painted);
  zs_device_destroy(d);

  /* The bands of a flush split the rows the last flush covered: a frame
   * that covers more than the one before still lands whole.  The first
   * frame draws one small sphere, the second every draw. */
  frame one = frame_new(160, 120), two = frame_new(160, 120);
  zs_device *d1 = perspective_device(&one, 1, 0.0, 0.0, 4.0);
  zs_device *d2 = perspective_device(&two, 2, 0.0, 0.0, 4.0);
  zs_device_defer_draws(d2, 1);
  double view[16], proj[16];
  zs_mat_look_at(view, (double[3]){0, 0, 4.0}, (double[3]){0, 0, 0}, (double[3]){0, 1, 0});
  zs_mat_perspective(proj, 50, 160.0 / 120, 0.5, 10);
  for (int pass = 0; pass < 2; pass++) {
    zs_device_clear(d2);
    zs_device_set_camera(d2, view, proj);
    for (int i = 0; i < (pass ? SMALL_DRAWS : 1); i += 3)
      ck_assert_int_eq(zs_device_draw(d2, &m[i].m, NULL, (uint32_t)i * 1000u, ZS_RGB_MESH, &err),
                       ZS_OK);
    ck_assert_int_eq(zs_device_finish(d2, frame_sink, &two, &err), ZS_OK);
  }
  for (int i = 0; i < SMALL_DRAWS; i += 3)
    ck_assert_int_eq(zs_device_draw(d1, &m[i].m, NULL, (uint32_t)i * 1000u, ZS_RGB_MESH, &err),
                     ZS_OK);
  ck_assert_int_eq(zs_device_finish(d1, frame_sink, &one, &err), ZS_OK);
  ck_assert_mem_eq(zs_device_stats(d1), zs_device_stats(d2), sizeof(zs_raster_stats));
  ck_assert_mem_eq(one.rgb, two.rgb, 160 * 120 * 4);
  ck_assert_mem_eq(one.depth, two.depth, 160 * 120 * 4);
  ck_assert_mem_eq(one.id, two.id, 160 * 120 * 4);
  frame_free(&one);
  frame_free(&two);
  zs_device_destroy(d1);
  zs_device_destroy(d2);
  for (int i = 0; i <= SMALL_DRAWS; i++) mb_free(&m[i]);
}
END_TEST

/* The pool's jobs: each task adds its index + 1 to its own slot. */
typedef struct pool_job {
  uint64_t slot[64];
} pool_job;

static void pool_task(void *ctx, int task) {
  /* a little work, so that the threads claim tasks at the same moments */
  volatile unsigned spin = 0;
  for (int i = 0; i < 64 * (task % 5); i++) spin = spin + 1u;
  ((pool_job *)ctx)->slot[task] += (uint64_t)task + 1;
}

START_TEST(pool_runs_every_task_once) {
  /* Many short jobs back to back, of 1 to 64 tasks, on 2 to 4 threads:
   * a task taken twice, or a late worker taking a task of the next job,
   * shows as a slot off its sum. */
  for (int threads = 2; threads <= 4; threads++) {
    zs_pool *p = zs_pool_create(threads);
    ck_assert_ptr_nonnull(p);
    pool_job j;
    memset(&j, 0, sizeof j);
    uint64_t runs[64] = {0};
    for (int round = 0; round < 3000; round++) {
      int ntasks = 1 + (round * 37) % 64;
      zs_pool_run(p, pool_task, &j, ntasks);
      for (int t = 0; t < ntasks; t++) runs[t]++;
    }
    for (int t = 0; t < 64; t++)
      ck_assert_msg(j.slot[t] == runs[t] * (uint64_t)(t + 1), "threads %d task %d: %llu of %llu",
                    threads, t, (unsigned long long)j.slot[t],
                    (unsigned long long)(runs[t] * (uint64_t)(t + 1)));
    zs_pool_destroy(p);
  }
  ck_assert_ptr_null(zs_pool_create(1));
}
END_TEST

START_TEST(degenerate_faces_draw_nothing) {
  mesh_buf b = {0};
  int32_t v[3] = {mb_vert(&b, 1, 1, 0), mb_vert(&b, 5, 5, 0), mb_vert(&b, 9, 9, 0)};
  mb_face(&b, v, 3, 0xFFFFFF); /* collinear */
  int32_t u[3] = {v[0], v[0], v[1]};
  mb_face(&b, u, 3, 0xFFFFFF); /* repeated vertex */
  for (int algo = 0; algo < 2; algo++) {
    frame f = frame_new(16, 16);
    zs_raster_stats s = render(&b.m, 16, 16, (zs_algo)algo, ZS_SHADE_OVERDRAW, 0, NULL, NULL, &f);
    ck_assert_uint_eq(s.pixels_written, 0);
    ck_assert_uint_eq(s.polygons_degenerate, 2);
    frame_free(&f);
  }
  mb_free(&b);
  /* A corner at the eye under a projection that puts it inside every
   * plane, clip space (x, y, z, -z): w = 0, no depth; the face is
   * degenerate, the other drawn (and nothing overflows: the sanitizer
   * build runs this). */
  mesh_buf e = {0};
  int32_t t[3] = {mb_vert(&e, 0, 0, 0), mb_vert(&e, 0.5, 0, -1), mb_vert(&e, 0, 0.5, -1)};
  mb_face(&e, t, 3, 0xFFFFFF);
  int32_t w[3] = {mb_vert(&e, -0.5, -0.5, -1), mb_vert(&e, 0, -0.5, -1), mb_vert(&e, -0.5, 0, -1)};
  mb_face(&e, w, 3, 0xFFFFFF);
  double view[16], proj[16];
  zs_mat_identity(view);
  zs_mat_identity(proj);
  proj[10] = 1.0, proj[14] = -1.0, proj[15] = 0.0;
  for (int algo = 0; algo < 2; algo++) {
    frame f = frame_new(16, 16);
    zs_raster_stats s = render(&e.m, 16, 16, (zs_algo)algo, ZS_SHADE_OVERDRAW, 0, view, proj, &f);
    ck_assert_uint_eq(s.polygons_degenerate, 1);
    ck_assert_uint_eq(s.polygons_rasterized, 1);
    ck_assert_uint_gt(s.pixels_written, 0);
    frame_free(&f);
  }
  mb_free(&e);
}
END_TEST

START_TEST(back_faces_culled_only_when_asked) {
  mesh_buf b = {0};
  /* counter-clockwise in window coordinates: front */
  int32_t f1[3] = {mb_vert(&b, 1, 1, 0), mb_vert(&b, 10, 1, 0), mb_vert(&b, 1, 10, 0)};
  mb_face(&b, f1, 3, 0xFFFFFF);
  int32_t f2[3] = {mb_vert(&b, 12, 1, 0), mb_vert(&b, 12, 10, 0), mb_vert(&b, 15, 1, 0)};
  mb_face(&b, f2, 3, 0xFFFFFF);
  frame f = frame_new(16, 16);
  zs_raster_stats s = render(&b.m, 16, 16, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 1, NULL, NULL, &f);
  ck_assert_uint_eq(s.polygons_culled_back, 1);
  ck_assert_uint_eq(s.polygons_rasterized, 1);
  s = render(&b.m, 16, 16, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, NULL, NULL, &f);
  ck_assert_uint_eq(s.polygons_culled_back, 0);
  ck_assert_uint_eq(s.polygons_rasterized, 2);
  frame_free(&f);
  mb_free(&b);
}
END_TEST

START_TEST(faces_off_the_window_are_dropped_at_set_up) {
  /* Clipping stops at the guard band, 2^15 pixels out: a face beyond the
   * window but inside the band reaches set-up, which drops it when its box
   * holds no pixel centre of the window.  The picture is that of the faces
   * that remain; the clock still charges every face set up. */
  mesh_buf all = {0}, kept = {0};
  static const double tris[6][6] = {
      {-6, 2, -1, 2, -3, 9},     /* left of the window */
      {17, 2, 20, 2, 18, 9},     /* right */
      {2, 17, 9, 17, 5, 20},     /* above */
      {2, -5, 9, -5, 5, -1},     /* below */
      {15.5, 2, 20, 2, 15.5, 9}, /* box starts on the centres of column 15: kept */
      {12, 12, 30, 12, 12, 30},  /* partly in the window: kept */
  };
  for (int t = 0; t < 6; t++) {
    int32_t v[3];
    for (int k = 0; k < 3; k++) v[k] = mb_vert(&all, tris[t][2 * k], tris[t][2 * k + 1], 0);
    mb_face(&all, v, 3, 0x102030u * (uint32_t)(t + 1));
    if (t < 4) continue;
    for (int k = 0; k < 3; k++) v[k] = mb_vert(&kept, tris[t][2 * k], tris[t][2 * k + 1], 0);
    mb_face(&kept, v, 3, 0x102030u * (uint32_t)(t + 1));
  }
  /* the kept faces keep their ids: number them as in `all` */
  int32_t ids[2] = {4, 5};
  kept.m.face_id = ids;
  for (int algo = 0; algo < 2; algo++) {
    frame fa = frame_new(16, 16), fk = frame_new(16, 16);
    zs_raster_stats sa = render(&all.m, 16, 16, (zs_algo)algo, ZS_SHADE_ID, 0, NULL, NULL, &fa);
    zs_raster_stats sk = render(&kept.m, 16, 16, (zs_algo)algo, ZS_SHADE_ID, 0, NULL, NULL, &fk);
    ck_assert_uint_eq(sa.polygons_offscreen, 4);
    ck_assert_uint_eq(sa.polygons_rasterized, 2);
    ck_assert_uint_eq(sa.polygons_outside, 0);
    ck_assert_uint_eq(zs_polygons_set_up(&sa), 6);
    ck_assert_uint_eq(sa.pixels_written, sk.pixels_written);
    ck_assert_uint_gt(sa.pixels_written, 0);
    ck_assert_mem_eq(fa.id, fk.id, 16 * 16 * 4);
    ck_assert_mem_eq(fa.depth, fk.depth, 16 * 16 * 4);
    /* the sliver's left edge runs through the centres of column 15, which
     * the coverage rule gives it: the face at the box's limit was
     * rasterized, not dropped */
    int in_col15 = 0;
    for (int y = 0; y < 16; y++) in_col15 += fa.id[16 * y + 15] == 4;
    ck_assert_int_gt(in_col15, 0);
    frame_free(&fa);
    frame_free(&fk);
  }
  kept.m.face_id = NULL;
  mb_free(&all);
  mb_free(&kept);
}
END_TEST

START_TEST(nothing_behind_the_eye) {
  /* A triangle straddling the eye plane: only the part in front of the
   * near plane is drawn; one wholly behind draws nothing. */
  mesh_buf b = {0};
  int32_t t[3] = {mb_vert(&b, -1, -1, -2), mb_vert(&b, 1, -1, -2), mb_vert(&b, 0, 1, 3)};
  mb_face(&b, t, 3, 0xFFFFFF);
  int32_t u[3] = {mb_vert(&b, -1, -1, 2), mb_vert(&b, 1, -1, 2), mb_vert(&b, 0, 1, 2)};
  mb_face(&b, u, 3, 0xFFFFFF);
  double view[16], proj[16];
  zs_mat_identity(view);
  zs_mat_perspective(proj, 60, 1, 0.5, 10);
  frame f = frame_new(32, 32);
  zs_raster_stats s = render(&b.m, 32, 32, ZS_ALGO_SCANLINE, ZS_SHADE_ID, 0, view, proj, &f);
  ck_assert_uint_eq(s.polygons_clipped, 1);
  ck_assert_uint_eq(s.polygons_outside, 1);
  ck_assert_uint_gt(s.pixels_written, 0);
  for (int i = 0; i < 32 * 32; i++) ck_assert(f.id[i] == ZS_ID_NONE || f.id[i] == 0);
  frame_free(&f);
  mb_free(&b);
}
END_TEST

static Suite *suite(void) {
  Suite *s = suite_create("raster");
  TCase *tc = tcase_create("core");
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, square_on_pixel_centres);
  tcase_add_test(tc, random_triangles_match_reference);
  tcase_add_test(tc, fan_of_thin_triangles_covers_once);
  tcase_add_test(tc, closed_mesh_covers_once_front_twice_both);
  tcase_add_test(tc, lecture_zbuffer_examples);
  tcase_add_test(tc, modes_agree_and_order_does_not_matter);
  tcase_add_test(tc, by_polygon_and_scanned_agree_to_the_counter);
  tcase_add_test(tc, simd_spans_equal_scalar);
  tcase_add_test(tc, folded_face_painted_as_walked);
  tcase_add_test(tc, vertex_stage_simd_equals_scalar);
  tcase_add_test(tc, flat_levels_simd_equal_scalar);
  tcase_add_test(tc, a_failed_draw_leaves_its_earlier_faces_as_drawn);
  tcase_add_test(tc, scanline_bands_start_each_frame_clean);
  tcase_add_test(tc, scanline_memory_grows_with_width_not_area);
  tcase_add_test(tc, depth_stepping_equals_evaluation);
  tcase_add_test(tc, degenerate_faces_draw_nothing);
  tcase_add_test(tc, large_draws_set_up_on_threads_give_the_same_bytes);
  tcase_add_test(tc, deferred_small_draws_land_as_drawn_at_once);
  tcase_add_test(tc, pool_runs_every_task_once);
  tcase_add_test(tc, faces_off_the_window_are_dropped_at_set_up);
  tcase_add_test(tc, back_faces_culled_only_when_asked);
  tcase_add_test(tc, nothing_behind_the_eye);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return zs_test_run(suite()); }
