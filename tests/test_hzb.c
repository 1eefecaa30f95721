/* The hierarchical depth buffer: the pyramid holds the farthest depth of
 * what each texel covers, its costs follow from its counts, and a box is
 * never called hidden when its exact query counts a sample (random boxes,
 * scenes and cameras, near planes and boxes round the eye included). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "raster/device.h"
#include "util/rng.h"
#include "tests/testutil.h"

static zs_error err;

static zs_device *device(int w, int h) {
  zs_device_config cfg = {w, h, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, 1, 0, 0, 0};
  zs_device *d = NULL;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
  return d;
}

/* A random perspective camera looking at the origin from 4 to 40 units,
 * near plane 0.05 to 2 (so that boxes straddle it). */
static void random_camera(zs_device *d, zs_rng *r, int w, int h) {
  double eye[3], target[3] = {zs_rng_range(r, -1, 1), zs_rng_range(r, -1, 1),
                              zs_rng_range(r, -1, 1)};
  double dist = zs_rng_range(r, 4, 40);
  double dir[3] = {zs_rng_range(r, -1, 1), zs_rng_range(r, -1, 1), zs_rng_range(r, -1, 1)};
  if (zs_rng_below(r, 3) == 0) { /* along an axis: walls of one depth, flush with boxes */
    const int a = 2 * (int)zs_rng_below(r, 2); /* x or z, so that up = y is not along it */
    dir[0] = dir[1] = dir[2] = 0.0;
    dir[a] = zs_rng_below(r, 2) ? 1.0 : -1.0;
  }
  double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]) + 1e-9;
  for (int k = 0; k < 3; k++) eye[k] = target[k] + dir[k] / len * dist;
  const double up[3] = {0, 1, 0};
  double view[16], proj[16];
  ck_assert(zs_mat_look_at(view, eye, target, up));
  zs_mat_perspective(proj, zs_rng_range(r, 20, 90), (double)w / h, zs_rng_range(r, 0.05, 2.0),
                     zs_rng_range(r, 30, 120));
  zs_device_set_camera(d, view, proj);
}

/* Random quads: walls, slivers and specks, some crossing the near plane;
 * every third one axis-aligned, so that boxes lie flush with it. */
static void random_scene(mesh_buf *b, zs_rng *r, int n) {
  for (int i = 0; i < n; i++) {
    if (i % 3 == 0) {
      const int a = (int)zs_rng_below(r, 3), u = (a + 1) % 3, v = (a + 2) % 3;
      double lo[3], hi[3];
      for (int k = 0; k < 3; k++) {
        lo[k] = zs_rng_range(r, -8, 8);
        hi[k] = lo[k] + exp(zs_rng_range(r, log(0.05), log(6.0)));
      }
      hi[a] = lo[a];
      double p[4][3];
      for (int c = 0; c < 4; c++) {
        p[c][a] = lo[a];
        p[c][u] = (c == 1 || c == 2) ? hi[u] : lo[u];
        p[c][v] = (c >= 2) ? hi[v] : lo[v];
      }
      int32_t q[4];
      for (int c = 0; c < 4; c++) q[c] = mb_vert(b, p[c][0], p[c][1], p[c][2]);
      mb_face(b, q, 4, 0xFFFFFF);
      continue;
    }
    double c[3] = {zs_rng_range(r, -8, 8), zs_rng_range(r, -8, 8), zs_rng_range(r, -8, 8)};
    double s = exp(zs_rng_range(r, log(0.05), log(6.0)));
    double u[3] = {zs_rng_range(r, -1, 1) * s, zs_rng_range(r, -1, 1) * s, zs_rng_range(r, -1, 1) * s};
    double v[3] = {zs_rng_range(r, -1, 1) * s, zs_rng_range(r, -1, 1) * s, zs_rng_range(r, -1, 1) * s};
    int32_t q[4] = {mb_vert(b, c[0] - u[0] - v[0], c[1] - u[1] - v[1], c[2] - u[2] - v[2]),
                    mb_vert(b, c[0] + u[0] - v[0], c[1] + u[1] - v[1], c[2] + u[2] - v[2]),
                    mb_vert(b, c[0] + u[0] + v[0], c[1] + u[1] + v[1], c[2] + u[2] + v[2]),
                    mb_vert(b, c[0] - u[0] + v[0], c[1] - u[1] + v[1], c[2] - u[2] + v[2])};
    mb_face(b, q, 4, 0xFFFFFF);
  }
}

/* A random box: from specks to slabs larger than the scene, thin in one
 * axis a third of the time (faces seen edge-on). */
static void random_box(zs_rng *r, double lo[3], double hi[3]) {
  int thin = (int)zs_rng_below(r, 9);
  for (int k = 0; k < 3; k++) {
    double c = zs_rng_range(r, -12, 12);
    double s = exp(zs_rng_range(r, log(0.001), log(8.0)));
    if (k == thin) s = exp(zs_rng_range(r, log(1e-6), log(0.01)));
    lo[k] = c - s;
    hi[k] = c + s;
  }
}

static uint64_t exact_samples(zs_device *d, const double lo[3], const double hi[3]) {
  zs_query q;
  ck_assert_int_eq(zs_device_query_begin(d, &q, &err), ZS_OK);
  ck_assert_int_eq(zs_device_query_box(d, lo, hi, &err), ZS_OK);
  ck_assert_int_eq(zs_device_query_end(d, &err), ZS_OK);
  return zs_device_query_result(d, q);
}

START_TEST(never_hides_what_a_query_sees) {
  /* 60 scenes and cameras, 200 boxes each */
  uint64_t boxes = 0, seen = 0, unseen = 0, culled = 0;
  for (int scene = 0; scene < 60; scene++) {
    zs_rng r;
    zs_rng_seed(&r, 1000 + (uint64_t)scene);
    const int w = 64 + (int)zs_rng_below(&r, 200), h = 48 + (int)zs_rng_below(&r, 150);
    zs_device *d = device(w, h);
    random_camera(d, &r, w, h);
    zs_device_clear(d);
    mesh_buf b = {0};
    random_scene(&b, &r, 10 + (int)zs_rng_below(&r, 300));
    ck_assert_int_eq(zs_device_draw(d, &b.m, NULL, 0, ZS_RGB_MESH, &err), ZS_OK);
    ck_assert_int_eq(zs_device_hzb_build(d, &err), ZS_OK);
    for (int i = 0; i < 200; i++) {
      double lo[3], hi[3];
      random_box(&r, lo, hi);
      if (i % 4 == 1) { /* a quad's own box, or just behind or before it */
        const mesh_buf *m = &b;
        const int32_t f = (int32_t)zs_rng_below(&r, (uint64_t)m->m.nfaces);
        for (int k = 0; k < 3; k++) {
          lo[k] = INFINITY;
          hi[k] = -INFINITY;
        }
        for (int c = m->m.face_start[f]; c < m->m.face_start[f + 1]; c++)
          for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], m->m.pos[3 * m->m.face_vert[c] + k]);
            hi[k] = fmax(hi[k], m->m.pos[3 * m->m.face_vert[c] + k]);
          }
        const int k = (int)zs_rng_below(&r, 3);
        const double shift = zs_rng_below(&r, 2) ? 0.0 : zs_rng_range(&r, -1e-4, 1e-4);
        lo[k] += shift;
        hi[k] += shift;
      }
      if (i % 4 == 2) { /* a box behind an axis-aligned wall, its face in the wall's plane */
        const mesh_buf *m = &b;
        const int32_t f = 3 * (int32_t)zs_rng_below(&r, (uint64_t)(m->m.nfaces + 2) / 3);
        const double *p0 = &m->m.pos[3 * m->m.face_vert[m->m.face_start[f]]];
        const double *p2 = &m->m.pos[3 * m->m.face_vert[m->m.face_start[f] + 2]];
        int a = 0;
        for (int k = 0; k < 3; k++)
          if (p0[k] == p2[k]) a = k;
        for (int k = 0; k < 3; k++) {
          const double t0 = zs_rng_range(&r, 0.3, 0.7), t1 = zs_rng_range(&r, 0.3, 0.7);
          lo[k] = p0[k] + fmin(t0, t1) * (p2[k] - p0[k]);
          hi[k] = p0[k] + fmax(t0, t1) * (p2[k] - p0[k]);
        }
        const double depth = exp(zs_rng_range(&r, log(1e-4), log(4.0)));
        if (d->eye[a] < p0[a]) {
          lo[a] = p0[a];
          hi[a] = p0[a] + depth;
        } else {
          hi[a] = p0[a];
          lo[a] = p0[a] - depth;
        }
      }
      if (i % 20 == 0) { /* round the eye: d->eye inside, or the near plane through it */
        for (int k = 0; k < 3; k++) {
          lo[k] = d->eye[k] - zs_rng_range(&r, 0.0, 1.0);
          hi[k] = d->eye[k] + zs_rng_range(&r, -0.5, 1.0);
          if (hi[k] <= lo[k]) hi[k] = lo[k] + 0.01;
        }
      }
      uint8_t maybe = 9;
      ck_assert_int_eq(zs_device_hzb_test(d, (const double(*)[3])lo, (const double(*)[3])hi, 1,
                                          &maybe, &err),
                       ZS_OK);
      uint64_t samples = exact_samples(d, lo, hi);
      ck_assert_msg(maybe == 1 || samples == 0,
                    "scene %d box %d (%.9g %.9g %.9g .. %.9g %.9g %.9g): hidden, but its query "
                    "counts %llu samples",
                    scene, i, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], (unsigned long long)samples);
      boxes++;
      seen += samples > 0;
      unseen += samples == 0;
      culled += maybe == 0;
    }
    mb_free(&b);
    zs_device_destroy(d);
  }
  ck_assert_uint_eq(boxes, 12000);
  /* and it does cull: four in five of the boxes whose query counts
   * nothing (the rest lie flush behind a face, within its bias, or
   * round the eye) */
  printf("hzb: %llu boxes, %llu seen by their query, %llu not; the pyramid hides %llu\n",
         (unsigned long long)boxes, (unsigned long long)seen, (unsigned long long)unseen,
         (unsigned long long)culled);
  ck_assert_uint_gt(seen, 1000);
  ck_assert_uint_gt(5 * culled, 4 * unseen);
}
END_TEST

START_TEST(levels_hold_the_farthest) {
  /* odd sizes: the last column and row of a level cover one texel below */
  const int w = 101, h = 37;
  zs_device *d = device(w, h);
  double view[16], proj[16];
  zs_mat_identity(view);
  zs_mat_ortho(proj, 0, w, 0, h, 0, 100);
  zs_device_set_camera(d, view, proj);
  zs_device_clear(d);
  zs_rng r;
  zs_rng_seed(&r, 7);
  mesh_buf b = {0};
  for (int i = 0; i < 80; i++) {
    double x = zs_rng_range(&r, -5, w), y = zs_rng_range(&r, -5, h), s = zs_rng_range(&r, 1, 30);
    int32_t q[4] = {mb_vert(&b, x, y, -zs_rng_range(&r, 1, 99)),
                    mb_vert(&b, x + s, y, -zs_rng_range(&r, 1, 99)),
                    mb_vert(&b, x + s, y + s, -zs_rng_range(&r, 1, 99)),
                    mb_vert(&b, x, y + s, -zs_rng_range(&r, 1, 99))};
    mb_face(&b, q, 4, 0xFFFFFF);
  }
  ck_assert_int_eq(zs_device_draw(d, &b.m, NULL, 0, ZS_RGB_MESH, &err), ZS_OK);
  const zs_clock_stats before = *zs_device_clock(d);
  ck_assert_int_eq(zs_device_hzb_build(d, &err), ZS_OK);
  /* the device's pyramid is the one built from its depth buffer */
  const uint32_t *depth = zs_device_depth_buffer(d);
  zs_hzb *hz = zs_hzb_create();
  int64_t texels = 0;
  ck_assert(hz && zs_hzb_build(hz, depth, w, h, &texels));
  /* 51x19, 26x10, 13x5, 7x3, 4x2, 2x1, 1x1 */
  ck_assert_int_eq(zs_hzb_levels(hz), 8);
  ck_assert_int_eq(texels, 51 * 19 + 26 * 10 + 13 * 5 + 7 * 3 + 4 * 2 + 2 * 1 + 1);
  for (int k = 1; k < zs_hzb_levels(hz); k++) {
    int lw, lh;
    const uint32_t *lv = zs_hzb_level(hz, k, &lw, &lh);
    for (int ty = 0; ty < lh; ty++)
      for (int tx = 0; tx < lw; tx++) {
        uint32_t far = 0;
        for (int y = ty << k; y < ((ty + 1) << k) && y < h; y++)
          for (int x = tx << k; x < ((tx + 1) << k) && x < w; x++)
            if (depth[y * w + x] > far) far = depth[y * w + x];
        ck_assert_uint_eq(lv[ty * lw + tx], far);
      }
  }
  zs_hzb_destroy(hz);
  /* its cost: the pass and the texels written, on the GPU; one call on the CPU */
  const zs_clock_stats *after = zs_device_clock(d);
  const zs_clock_params *p = zs_device_clock_params(d);
  ck_assert_uint_eq(after->hzb_texels - before.hzb_texels, (uint64_t)texels);
  ck_assert_int_eq(after->draw_ps - before.draw_ps,
                   llround(p->hzb_pass_ns * 1000) + llround(p->hzb_per_texel_ns * 1000) * texels);
  ck_assert_int_eq(after->cpu_ps - before.cpu_ps, llround(p->cpu_per_call_ns * 1000));
  mb_free(&b);
  zs_device_destroy(d);
}
END_TEST

/* A box just behind a wall that covers its picture and a quarter pixel
 * more: the pyramid's texels over the box's rectangle hold the far
 * background round its outline, so only a descent to the pixels proves
 * it hidden; the test does, reads more than the first level's texels to
 * do so, and the clock charges every texel read. */
START_TEST(descends_to_the_pixels) {
  const int side = 256;
  zs_device *d = device(side, side);
  double view[16], proj[16];
  zs_mat_identity(view);
  zs_mat_perspective(proj, 60.0, 1.0, 1.0, 100.0);
  zs_device_set_camera(d, view, proj);
  zs_device_clear(d);
  const double lo[3] = {-1.3, -0.4, -14.0}, hi[3] = {0.9, 1.1, -12.0};
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (int k = 0; k < 8; k++) { /* the box's picture, window pixels */
    const double p[3] = {k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]};
    double o[4];
    zs_mat_apply(proj, p, o);
    x0 = fmin(x0, (o[0] / o[3] + 1.0) * 0.5 * side), x1 = fmax(x1, (o[0] / o[3] + 1.0) * 0.5 * side);
    y0 = fmin(y0, (o[1] / o[3] + 1.0) * 0.5 * side), y1 = fmax(y1, (o[1] / o[3] + 1.0) * 0.5 * side);
  }
  const double f = proj[5], z = -10.0; /* the wall, over those pixels and a quarter more */
  const double u0 = ((x0 - 0.25) * 2.0 / side - 1.0) * -z / f, u1 = ((x1 + 0.25) * 2.0 / side - 1.0) * -z / f;
  const double v0 = ((y0 - 0.25) * 2.0 / side - 1.0) * -z / f, v1 = ((y1 + 0.25) * 2.0 / side - 1.0) * -z / f;
  mesh_buf b = {0};
  int32_t q[4] = {mb_vert(&b, u0, v0, z), mb_vert(&b, u1, v0, z), mb_vert(&b, u1, v1, z),
                  mb_vert(&b, u0, v1, z)};
  mb_face(&b, q, 4, 0xFFFFFF);
  ck_assert_int_eq(zs_device_draw(d, &b.m, NULL, 0, ZS_RGB_MESH, &err), ZS_OK);
  ck_assert_uint_eq(exact_samples(d, lo, hi), 0);
  ck_assert_int_eq(zs_device_hzb_build(d, &err), ZS_OK);
  const zs_clock_stats before = *zs_device_clock(d);
  uint8_t maybe = 9;
  ck_assert_int_eq(zs_device_hzb_test(d, (const double(*)[3])lo, (const double(*)[3])hi, 1, &maybe,
                                      &err),
                   ZS_OK);
  ck_assert_int_eq(maybe, 0);
  const zs_clock_stats *after = zs_device_clock(d);
  const uint64_t reads = after->hzb_reads - before.hzb_reads;
  ck_assert_uint_gt(reads, 3 * 3 * 2); /* the first level's, twice over, and more */
  const zs_clock_params *p = zs_device_clock_params(d);
  ck_assert_uint_eq(after->hzb_boxes - before.hzb_boxes, 1);
  ck_assert_int_eq(after->draw_ps - before.draw_ps,
                   llround(p->hzb_pass_ns * 1000) + llround(p->hzb_per_box_ns * 1000) +
                       llround(p->hzb_per_read_ns * 1000) * (int64_t)reads);
  /* and where the wall leaves a pixel of the box's picture open, the box shows */
  const double lo2[3] = {lo[0], lo[1], lo[2]}, hi2[3] = {hi[0] + 0.3, hi[1], hi[2]};
  ck_assert_uint_gt(exact_samples(d, lo2, hi2), 0);
  ck_assert_int_eq(zs_device_hzb_test(d, (const double(*)[3])lo2, (const double(*)[3])hi2, 1,
                                      &maybe, &err),
                   ZS_OK);
  ck_assert_int_eq(maybe, 1);
  mb_free(&b);
  zs_device_destroy(d);
}
END_TEST

START_TEST(test_needs_a_pyramid_of_this_frame) {
  zs_device *d = device(32, 32);
  double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  uint8_t maybe;
  ck_assert_int_eq(zs_device_hzb_test(d, (const double(*)[3])lo, (const double(*)[3])hi, 1,
                                      &maybe, &err),
                   ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "hzb_test: no depth pyramid built this frame");
  ck_assert_int_eq(zs_device_hzb_build(d, &err), ZS_OK);
  zs_device_clear(d); /* a new frame: the old pyramid is gone */
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_hzb_test(d, (const double(*)[3])lo, (const double(*)[3])hi, 1,
                                      &maybe, &err),
                   ZS_ERR_ARG);
  zs_device_destroy(d);
  zs_device_config cfg = {32, 32, ZS_ALGO_SCANLINE, ZS_SHADE_ID, 0, 1, 0, 0, 0};
  ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_hzb_build(d, &err), ZS_ERR_UNSUPPORTED);
  ck_assert_str_eq(err.msg, "the depth pyramid needs the z-buffer mode");
  zs_device_destroy(d);
}
END_TEST

int main(void) {
  Suite *s = suite_create("hzb");
  TCase *tc = tcase_create("hzb");
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, never_hides_what_a_query_sees);
  tcase_add_test(tc, levels_hold_the_farthest);
  tcase_add_test(tc, descends_to_the_pixels);
  tcase_add_test(tc, test_needs_a_pyramid_of_this_frame);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
