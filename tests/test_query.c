/* Occlusion queries and the modelled clock: exact sample counts on
 * constructed scenes, counts equal to what drawing writes, readiness in
 * modelled time, and identical clocks on every run. */
#include <string.h>

#include "raster/raster.h"
#include "util/rng.h"
#include "tests/testutil.h"

static zs_error err;

/* Orthographic device: window x, y = world x, y; eye distance = -z. */
static zs_device *ortho_device(int w, int h, zs_algo algo) {
  zs_device_config cfg = {w, h, algo, ZS_SHADE_ID, 0, 1, 0, 0, 0};
  zs_device *d = NULL;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
  double view[16], proj[16];
  zs_mat_identity(view);
  zs_mat_ortho(proj, 0, w, 0, h, 0, 100);
  zs_device_set_camera(d, view, proj);
  zs_device_clear(d);
  return d;
}

/* An axis-aligned square at distance dist in front of the eye. */
static void square(mesh_buf *b, double x0, double y0, double side, double dist) {
  int32_t v[4] = {mb_vert(b, x0, y0, -dist), mb_vert(b, x0 + side, y0, -dist),
                  mb_vert(b, x0 + side, y0 + side, -dist), mb_vert(b, x0, y0 + side, -dist)};
  mb_face(b, v, 4, 0xFFFFFF);
}

static void draw(zs_device *d, const mesh_buf *b, uint32_t id_base) {
  ck_assert_int_eq(zs_device_draw(d, &b->m, NULL, id_base, ZS_RGB_MESH, &err), ZS_OK);
}

START_TEST(square_behind_square_7500) {
  /* A 100 x 100 square behind a 50 x 50 square: 7,500 visible samples,
   * counted by drawing it inside a query and by querying its box. */
  zs_device *d = ortho_device(200, 200, ZS_ALGO_ZBUFFER);
  mesh_buf front = {0}, back = {0};
  square(&front, 60, 60, 50, 10);
  square(&back, 40, 40, 100, 20);
  draw(d, &front, 0);
  zs_query q;
  ck_assert_int_eq(zs_device_query_begin(d, &q, &err), ZS_OK);
  draw(d, &back, 1);
  ck_assert_int_eq(zs_device_query_end(d, &err), ZS_OK);
  ck_assert_uint_eq(zs_device_query_result(d, q), 7500);

  /* its box (a slab from the square back to distance 30) against the final
   * depth buffer: the square's own pixels pass less-or-equal */
  zs_query qb;
  ck_assert_int_eq(zs_device_query_begin(d, &qb, &err), ZS_OK);
  ck_assert_int_eq(zs_device_query_box(d, (double[3]){40, 40, -30}, (double[3]){140, 140, -20}, &err),
                   ZS_OK);
  ck_assert_int_eq(zs_device_query_end(d, &err), ZS_OK);
  ck_assert_uint_eq(zs_device_query_result(d, qb), 7500);
  /* query boxes wrote nothing: the id buffer still shows both squares */
  const uint32_t *ids = zs_device_id_buffer(d);
  uint64_t n0 = 0, n1 = 0;
  for (int i = 0; i < 200 * 200; i++) {
    n0 += ids[i] == 0;
    n1 += ids[i] == 1;
  }
  ck_assert_uint_eq(n0, 2500);
  ck_assert_uint_eq(n1, 7500);
  mb_free(&front);
  mb_free(&back);
  zs_device_destroy(d);
}
END_TEST

START_TEST(box_behind_wall_is_zero) {
  zs_device *d = ortho_device(64, 64, ZS_ALGO_ZBUFFER);
  mesh_buf wall = {0};
  square(&wall, -10, -10, 90, 5);
  draw(d, &wall, 0);
  zs_query q, in_front;
  zs_device_query_begin(d, &q, &err);
  zs_device_query_box(d, (double[3]){10, 10, -20}, (double[3]){30, 30, -10}, &err);
  zs_device_query_end(d, &err);
  ck_assert_uint_eq(zs_device_query_result(d, q), 0);
  /* the same box in front of the wall: its whole 20 x 20 outline */
  zs_device_query_begin(d, &in_front, &err);
  zs_device_query_box(d, (double[3]){10, 10, -4}, (double[3]){30, 30, -2}, &err);
  zs_device_query_end(d, &err);
  ck_assert_uint_eq(zs_device_query_result(d, in_front), 400);
  /* and from a ten-millionth of the range before the near plane, once
   * grown by the query's margin: pulled nearer by the query's bias, its
   * front depths fall below 0 and count as 0, in front of the wall, not
   * as a wrapped depth behind it */
  zs_query at_near;
  const double far_side[3] = {10, 10, -2}, near_side[3] = {30, 30, -1};
  const double m = zs_device_query_margin(d, far_side, near_side);
  ck_assert(m == 1.0 / 32); /* a pixel is a unit here: 1/32 pixel */
  zs_device_query_begin(d, &at_near, &err);
  zs_device_query_box(d, far_side, (double[3]){30, 30, -1e-7 - m}, &err);
  zs_device_query_end(d, &err);
  ck_assert_uint_eq(zs_device_query_result(d, at_near), 400);
  mb_free(&wall);
  zs_device_destroy(d);
}
END_TEST

/* A unit cube's faces, outward and counter-clockwise, around centre c with
 * half-size h, in perspective. */
static void cube(mesh_buf *b, const double c[3], double h) {
  static const int32_t f[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  int32_t v[8];
  for (int k = 0; k < 8; k++)
    v[k] = mb_vert(b, c[0] + ((k & 1) ? h : -h), c[1] + ((k & 2) ? h : -h), c[2] + ((k & 4) ? h : -h));
  for (int i = 0; i < 6; i++) {
    int32_t q[4] = {v[f[i][0]], v[f[i][1]], v[f[i][2]], v[f[i][3]]};
    mb_face(b, q, 4, 0xFFFFFF);
  }
}

START_TEST(counts_equal_pixels_written) {
  /* Seeded cubes in perspective, each drawn inside its own query: the
   * query's samples are the pixels that draw wrote; and after the frame, a
   * query of each cube's own box counts every pixel it owns, and more only
   * where another cube cuts through its faces closer than the box's bias
   * or closer to its outline than the box's margin (raster.h, queries):
   * 75 pixels of the 12,562 owned here. */
  const uint64_t seed = 99;
  zs_rng rng;
  zs_rng_seed(&rng, seed);
  zs_device_config cfg = {160, 120, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, 1, 0, 0, 0};
  zs_device *d = NULL;
  ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
  double view[16], proj[16];
  zs_mat_look_at(view, (double[3]){0.5, 1.5, 9}, (double[3]){0, 0, 0}, (double[3]){0, 1, 0});
  zs_mat_perspective(proj, 50, 4.0 / 3.0, 1, 30);
  zs_device_set_camera(d, view, proj);
  zs_device_clear(d);
  enum { N = 40 };
  mesh_buf cubes[N];
  double lo[N][3], hi[N][3];
  for (int i = 0; i < N; i++) {
    memset(&cubes[i], 0, sizeof cubes[i]);
    /* one draw per statement: C leaves the order of arguments and of
     * initializers unspecified, and gcc and clang differ */
    double c[3];
    c[0] = zs_rng_range(&rng, -4, 4);
    c[1] = zs_rng_range(&rng, -3, 3);
    c[2] = zs_rng_range(&rng, -4, 4);
    double h = zs_rng_range(&rng, 0.2, 0.9);
    cube(&cubes[i], c, h);
    for (int a = 0; a < 3; a++) {
      lo[i][a] = c[a] - h;
      hi[i][a] = c[a] + h;
    }
    uint64_t before = zs_device_stats(d)->pixels_written;
    zs_query q;
    zs_device_query_begin(d, &q, &err);
    ck_assert_int_eq(zs_device_draw(d, &cubes[i].m, NULL, (uint32_t)(6 * i), ZS_RGB_MESH, &err), ZS_OK);
    zs_device_query_end(d, &err);
    ck_assert_uint_eq(zs_device_query_result(d, q), zs_device_stats(d)->pixels_written - before);
  }
  const uint32_t *ids = zs_device_id_buffer(d);
  uint64_t owned_all = 0, extra = 0;
  for (int i = 0; i < N; i++) {
    uint64_t owned = 0;
    for (int p = 0; p < 160 * 120; p++) owned += ids[p] != ZS_ID_NONE && ids[p] / 6 == (uint32_t)i;
    zs_query q;
    zs_device_query_begin(d, &q, &err);
    zs_device_query_box(d, lo[i], hi[i], &err);
    zs_device_query_end(d, &err);
    uint64_t box = zs_device_query_result(d, q);
    ck_assert_msg(box >= owned, "seed %llu cube %d: box %llu, owns %llu", (unsigned long long)seed,
                  i, (unsigned long long)box, (unsigned long long)owned);
    owned_all += owned;
    extra += box - owned;
  }
  ck_assert_uint_eq(owned_all, 12562);
  ck_assert_uint_eq(extra, 75);
  for (int i = 0; i < N; i++) mb_free(&cubes[i]);
  zs_device_destroy(d);
}
END_TEST

START_TEST(ready_only_after_latency) {
  zs_device *d = ortho_device(64, 64, ZS_ALGO_ZBUFFER);
  zs_clock_params p;
  zs_clock_params_default(&p);
  p.query_latency_ns = 1000.0;
  ck_assert_int_eq(zs_device_set_clock(d, &p, &err), ZS_OK);
  zs_query q;
  zs_device_query_begin(d, &q, &err);
  zs_device_query_box(d, (double[3]){1, 1, -20}, (double[3]){9, 9, -10}, &err);
  ck_assert(!zs_device_query_ready(d, q)); /* still open */
  zs_device_query_end(d, &err);
  /* GPU end = CPU issue time + per_call + 2 faces' set-up... */
  const zs_clock_stats *c = zs_device_clock(d);
  int64_t gpu_end = c->gpu_ps;
  ck_assert(!zs_device_query_ready(d, q));
  /* CPU work up to just before the ready time: still not ready */
  int64_t ready = gpu_end + 1000000; /* 1000 ns latency in ps */
  int64_t nodes = (ready - c->cpu_ps) / 100000 - 1; /* 100 ns per node visit */
  zs_device_cpu_work(d, ZS_CPU_NODE, (uint64_t)nodes);
  ck_assert_int_lt(zs_device_clock(d)->cpu_ps, ready);
  ck_assert(!zs_device_query_ready(d, q));
  zs_device_cpu_work(d, ZS_CPU_NODE, 2);
  ck_assert_int_ge(zs_device_clock(d)->cpu_ps, ready);
  ck_assert(zs_device_query_ready(d, q));
  ck_assert_uint_eq(zs_device_query_result(d, q), 64);
  ck_assert_uint_eq(zs_device_clock(d)->query_waits, 0);
  ck_assert_int_eq(zs_device_clock(d)->stall_ps, 0);
  zs_device_destroy(d);
}
END_TEST

START_TEST(waiting_stalls_the_cpu) {
  zs_device *d = ortho_device(64, 64, ZS_ALGO_ZBUFFER);
  zs_query q;
  zs_device_query_begin(d, &q, &err);
  zs_device_query_box(d, (double[3]){1, 1, -20}, (double[3]){9, 9, -10}, &err);
  zs_device_query_end(d, &err);
  int64_t gpu_end = zs_device_clock(d)->gpu_ps, cpu = zs_device_clock(d)->cpu_ps;
  zs_device_query_result(d, q); /* asked at once: waits for GPU and latency */
  const zs_clock_stats *c = zs_device_clock(d);
  ck_assert_uint_eq(c->query_waits, 1);
  ck_assert_uint_eq(c->stalls, 1);
  ck_assert_int_eq(c->sync_ps, gpu_end - cpu);
  ck_assert_int_eq(c->stall_ps, 200000000); /* the default 200 us latency */
  ck_assert_int_eq(c->cpu_ps, gpu_end + 200000000);
  ck_assert_int_eq(zs_device_frame_ps(d), c->cpu_ps);
  zs_device_destroy(d);
}
END_TEST

START_TEST(latency_zero_never_stalls) {
  /* Many queries and draws, each result asked for at once: the CPU may
   * wait for queued GPU work (sync), but never for latency. */
  zs_device *d = ortho_device(128, 128, ZS_ALGO_ZBUFFER);
  zs_clock_params p;
  zs_clock_params_default(&p);
  p.query_latency_ns = 0;
  zs_device_set_clock(d, &p, &err);
  zs_rng rng;
  zs_rng_seed(&rng, 5);
  for (int i = 0; i < 200; i++) {
    mesh_buf b = {0};
    double x = zs_rng_range(&rng, -20, 120), y = zs_rng_range(&rng, -20, 120);
    double side = zs_rng_range(&rng, 5, 60), dist = zs_rng_range(&rng, 1, 90);
    square(&b, x, y, side, dist);
    zs_query q;
    zs_device_query_begin(d, &q, &err);
    draw(d, &b, (uint32_t)i);
    zs_device_query_end(d, &err);
    zs_device_query_result(d, q);
    mb_free(&b);
  }
  ck_assert_uint_eq(zs_device_clock(d)->stalls, 0);
  ck_assert_int_eq(zs_device_clock(d)->stall_ps, 0);
  ck_assert_uint_eq(zs_device_clock(d)->queries, 200);
  zs_device_destroy(d);
}
END_TEST

/* The clock of a fixed workload, as one hash of its counters. */
static uint64_t workload_clock_hash(void) {
  zs_device *d = ortho_device(96, 96, ZS_ALGO_ZBUFFER);
  zs_rng rng;
  zs_rng_seed(&rng, 11);
  for (int i = 0; i < 100; i++) {
    mesh_buf b = {0};
    double x = zs_rng_range(&rng, 0, 90), y = zs_rng_range(&rng, 0, 90);
    double side = zs_rng_range(&rng, 2, 30), dist = zs_rng_range(&rng, 1, 90);
    square(&b, x, y, side, dist);
    zs_query q;
    zs_device_query_begin(d, &q, &err);
    zs_device_query_box(d, (double[3]){10, 10, -50}, (double[3]){40, 40, -40}, &err);
    zs_device_query_end(d, &err);
    draw(d, &b, (uint32_t)i);
    zs_device_cpu_work(d, ZS_CPU_FRUSTUM_TEST, 3);
    if (i % 3 == 0) zs_device_query_result(d, q);
    mb_free(&b);
  }
  const zs_clock_stats c = *zs_device_clock(d);
  const zs_raster_stats s = *zs_device_stats(d);
  zs_device_destroy(d);
  const uint64_t v[] = {c.queries,
                        c.query_waits,
                        c.stalls,
                        c.query_pixels,
                        c.switches,
                        (uint64_t)c.sync_ps,
                        (uint64_t)c.stall_ps,
                        (uint64_t)c.gpu_ps,
                        (uint64_t)c.cpu_ps,
                        (uint64_t)c.draw_ps,
                        (uint64_t)c.query_ps,
                        (uint64_t)c.switch_ps,
                        s.draws,
                        s.vertices,
                        s.polygons_in,
                        s.polygons_outside,
                        s.polygons_clipped,
                        s.polygons_culled_back,
                        s.polygons_degenerate,
                        s.polygons_offscreen,
                        s.polygons_rasterized,
                        s.spans,
                        s.pixels_tested,
                        s.pixels_written};
  return zs_test_hash_values(v, sizeof v / sizeof v[0]);
}

START_TEST(clock_identical_every_run) {
  /* The value in tests/golden/clock.txt holds for every build CI makes (gcc -O2, clang -O0
   * with sanitizers): counters and modelled times never depend on the
   * compiler, the optimiser or the run. */
  uint64_t h = workload_clock_hash();
  ck_assert_uint_eq(h, workload_clock_hash());
  zs_golden_assert("clock.txt", "workload", h);
}
END_TEST

START_TEST(gpu_split_adds_up_to_the_frame) {
  /* A box queried and waited for at once, then a square drawn: the GPU
   * switches to querying, tests the box, idles through the latency (the
   * CPU issues the draw only once the answer is in), switches back and
   * draws; the four parts add up to the frame, to the picosecond. */
  zs_device *d = ortho_device(64, 64, ZS_ALGO_ZBUFFER);
  zs_query q;
  zs_device_query_begin(d, &q, &err);
  zs_device_query_box(d, (double[3]){1, 1, -20}, (double[3]){9, 9, -10}, &err);
  zs_device_query_end(d, &err);
  zs_device_query_result(d, q);
  mesh_buf b = {0};
  square(&b, 4, 4, 20, 30);
  draw(d, &b, 1);
  mb_free(&b);
  const zs_clock_stats *c = zs_device_clock(d);
  zs_gpu_split g = zs_clock_gpu_split(d);
  ck_assert_int_eq(g.draw_ps + g.query_ps + g.switch_ps + g.idle_ps, zs_device_frame_ps(d));
  ck_assert_int_eq(g.switch_ps, 2 * 1000000); /* to the query and back, 1 us each */
  ck_assert_uint_eq(c->switches, 2);
  ck_assert_int_gt(g.query_ps, 0);
  ck_assert_int_gt(g.draw_ps, 0);
  /* idle: at least the latency, during which the CPU had nothing to issue */
  ck_assert_int_ge(g.idle_ps, c->stall_ps);
  ck_assert_int_eq(c->stall_ps, 200000000);
  zs_device_destroy(d);
}
END_TEST

START_TEST(bad_use_is_refused) {
  zs_device *d = ortho_device(16, 16, ZS_ALGO_SCANLINE);
  zs_query q;
  ck_assert_int_eq(zs_device_query_begin(d, &q, &err), ZS_ERR_UNSUPPORTED);
  ck_assert_str_eq(err.msg, "occlusion queries need --algo zbuffer");
  zs_device_destroy(d);
  d = ortho_device(16, 16, ZS_ALGO_ZBUFFER);
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_query_end(d, &err), ZS_ERR_ARG);
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_query_box(d, (double[3]){0, 0, -2}, (double[3]){1, 1, -1}, &err), ZS_ERR_ARG);
  zs_error_clear(&err);
  zs_clock_params p;
  zs_clock_params_default(&p);
  p.per_pixel_ns = -1;
  ck_assert_int_eq(zs_device_set_clock(d, &p, &err), ZS_ERR_ARG);
  zs_device_destroy(d);
}
END_TEST

int main(void) {
  Suite *s = suite_create("query");
  TCase *tc = tcase_create("queries");
  tcase_add_test(tc, square_behind_square_7500);
  tcase_add_test(tc, box_behind_wall_is_zero);
  tcase_add_test(tc, counts_equal_pixels_written);
  tcase_add_test(tc, ready_only_after_latency);
  tcase_add_test(tc, waiting_stalls_the_cpu);
  tcase_add_test(tc, latency_zero_never_stalls);
  tcase_add_test(tc, clock_identical_every_run);
  tcase_add_test(tc, gpu_split_adds_up_to_the_frame);
  tcase_add_test(tc, bad_use_is_refused);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
