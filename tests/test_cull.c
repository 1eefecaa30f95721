/* Culling: every exact method gives, in every frame of a walk (moving
 * objects included) and from random cameras (orthographic, wide, with the
 * eye inside objects), the image of drawing everything; the approximate
 * vfc-box reports how far it is off; the images stay exact whatever the
 * query latency; and the counters are the same on every run. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cull/cull.h"
#include "cull/frustum.h"
#include "cull/octree.h"
#include "cull/parts.h"
#include "util/rng.h"
#include "scene/generate.h"
#include "scene/load_obj.h"
#include "scene/scene.h"
#include "scene/load_scenefile.h"
#include "tests/testutil.h"

enum { W = 160, H = 120 };
static zs_error err;
static zs_query_bounds walk_bounds = ZS_BOUNDS_PARTS; /* what walk's cullers query */

typedef struct walk_result {
  uint64_t diff[ZS_CULL_METHODS];     /* pixels differing from none, summed */
  uint64_t queries[ZS_CULL_METHODS];
  uint64_t objects[ZS_CULL_METHODS];
  int64_t modelled_ps[ZS_CULL_METHODS];
  int frames; /* walked */
} walk_result;

/* The cost model's parameters of each method of the next walk (NULL: the
 * defaults). */
static const zs_cost_params *const *walk_costs;

/* The image size of the walks (W x H unless a test says otherwise). */
static int walk_w = W, walk_h = H;

/* The camera of frame f of the next walk (NULL: the scene's path's). */
static void (*walk_camera)(int f, const zs_scene *s, zs_camera *cam);
/* When set, walk hands it the stats of method k in frame f. */
static void (*walk_stats)(int f, int k, const zs_cull_stats *st);

/* Runs methods[0..n-1] (methods[0] must be none) in lockstep over frames
 * frames of spec's walk (every step-th frame of its path; frames 0: the
 * whole path), with the query latency given in ns (negative: the
 * default). */

static void walk(const char *spec, int frames, int step, const zs_cull_method *methods, int n,
                 double latency_ns, walk_result *out) {
  memset(out, 0, sizeof *out);
  zs_scene s;
  zs_error_clear(&err);
  ck_assert_msg(zs_gen_scene(spec, &s, &err) == ZS_OK, "%s: %s", spec, err.msg);
  zs_octree t;
  ck_assert_msg(zs_octree_build(&t, &s, NULL, &err) == ZS_OK, "%s", err.msg);
  zs_device *dev[ZS_CULL_METHODS];
  zs_culler *cul[ZS_CULL_METHODS];
  zs_clock_params clock;
  zs_clock_params_default(&clock);
  if (latency_ns >= 0) clock.query_latency_ns = latency_ns;
  for (int k = 0; k < n; k++) {
    zs_device_config cfg = {walk_w, walk_h, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, 1, 0, 0, 0};
    ck_assert_int_eq(zs_device_create(&cfg, &dev[k], &err), ZS_OK);
    ck_assert_int_eq(zs_device_set_clock(dev[k], &clock, &err), ZS_OK);
    ck_assert_int_eq(zs_culler_create(methods[k], walk_costs ? walk_costs[k] : NULL, &cul[k], &err),
                     ZS_OK);
    ck_assert_int_eq(zs_culler_set_bounds(cul[k], walk_bounds, &err), ZS_OK);
  }
  uint32_t *ref = malloc((size_t)walk_w * walk_h * sizeof *ref);
  int path_frames = s.path.frames > 0 ? s.path.frames : 1;
  if (frames == 0) frames = (path_frames + step - 1) / step;
  out->frames = frames;
  for (int f = 0; f < frames; f++) {
    for (int k = 0; k < step && f > 0; k++) {
      zs_scene_advance(&s);
      ck_assert_int_eq(zs_octree_update(&t, &s, NULL, &err), ZS_OK);
    }
    zs_camera cam = s.camera;
    if (walk_camera) walk_camera(f, &s, &cam);
    else if (s.path.nkeys > 0) zs_path_camera(&s, (f * step) % path_frames, &cam);
    zs_camera_complete(&cam, s.lo, s.hi, (double)walk_w / walk_h);
    double view[16], proj[16];
    ck_assert_int_eq(zs_camera_matrices(&cam, (double)walk_w / walk_h, view, proj, &err), ZS_OK);
    for (int k = 0; k < n; k++) {
      zs_cull_stats st;
      ck_assert_msg(zs_culler_frame(cul[k], dev[k], &s, &t, view, proj, &st, &err) == ZS_OK, "%s",
                    err.msg);
      ck_assert_int_eq(zs_device_finish(dev[k], NULL, NULL, &err), ZS_OK);
      const uint32_t *ids = zs_device_id_buffer(dev[k]);
      if (k == 0) memcpy(ref, ids, (size_t)walk_w * walk_h * sizeof *ref);
      for (int i = 0; i < walk_w * walk_h; i++) out->diff[k] += ids[i] != ref[i];
      if (walk_stats) walk_stats(f, k, &st);
      out->queries[k] += st.queries;
      out->objects[k] += st.objects_drawn;
      out->modelled_ps[k] += zs_device_frame_ps(dev[k]);
    }
  }
  free(ref);
  for (int k = 0; k < n; k++) {
    zs_culler_destroy(cul[k]);
    zs_device_destroy(dev[k]);
  }
  zs_octree_free(&t);
  zs_scene_free(&s);
}

static const zs_cull_method exact[] = {ZS_CULL_NONE,  ZS_CULL_VFC,           ZS_CULL_HSW,
                                       ZS_CULL_CHC,   ZS_CULL_CHC_PROB,      ZS_CULL_IDEAL,
                                       ZS_CULL_AUTO,  ZS_CULL_CHCPP,         ZS_CULL_CHCPP_NOBATCH,
                                       ZS_CULL_CHCPP_NODEFER, ZS_CULL_CHCPP_NOMULTI, ZS_CULL_CHCPP_PROB,
                                       ZS_CULL_NOHC,  ZS_CULL_IDEAL_BOX,     ZS_CULL_HZB};
enum { NEXACT = sizeof exact / sizeof exact[0] };

/* The generated scenes, small, with their own walks and moving objects. */
static const char *const scenes[] = {
    "teapots?count=120&moving=30", "spheres?count=400&moving=200", "city?moving=4",
    "plant?detail=0.05",           "cubes?n=6",                    "default",
};

START_TEST(exact_methods_match_none_on_every_walk) {
  walk_result r;
  walk(scenes[_i], 12, 9, exact, NEXACT, -1, &r);
  uint64_t drawn_all = r.objects[0];
  ck_assert_uint_gt(drawn_all, 0);
  for (int k = 1; k < NEXACT; k++)
    ck_assert_msg(r.diff[k] == 0, "%s: %s differs from none in %llu pixels", scenes[_i],
                  zs_cull_method_name(exact[k]), (unsigned long long)r.diff[k]);
  /* and they cull: ideal never draws more than none */
  ck_assert_uint_le(r.objects[5], drawn_all);
}
END_TEST

/* The same on every frame: each scene's whole path, frame by frame, its
 * objects moving; the test above takes every 9th frame of the first 108,
 * where each frame's objects have moved further.  Unoptimised under the
 * sanitizers a frame costs many times as much, so there it takes every
 * 8th frame of the whole path (the sanitizers look for memory errors,
 * which the same code meets in either). */
#ifdef ZS_SANITIZED
enum { EVERY_FRAME_STEP = 8 };
#else
enum { EVERY_FRAME_STEP = 1 };
#endif
START_TEST(exact_on_every_frame_of_every_walk) {
  walk_result r;
  walk(scenes[_i], 0, EVERY_FRAME_STEP, exact, NEXACT, -1, &r);
  ck_assert_int_ge(r.frames * EVERY_FRAME_STEP, 200); /* the paths: 200 to 400 frames */
  for (int k = 1; k < NEXACT; k++)
    ck_assert_msg(r.diff[k] == 0, "%s, %d frames: %s differs from none in %llu pixels", scenes[_i],
                  r.frames, zs_cull_method_name(exact[k]), (unsigned long long)r.diff[k]);
  ck_assert_uint_lt(r.objects[5], r.objects[0]); /* ideal culls */
  ck_assert_uint_gt(r.queries[2], 0);           /* hsw asks */
  /* and it is the floor of modelled time: it draws the fewest objects,
   * front to back, as the methods that traverse do */
  for (int k = 0; k < NEXACT; k++)
    ck_assert_msg(r.modelled_ps[5] <= r.modelled_ps[k], "%s: ideal %lld ps, %s %lld ps", scenes[_i],
                  (long long)r.modelled_ps[5], zs_cull_method_name(exact[k]),
                  (long long)r.modelled_ps[k]);
}
END_TEST

/* A camera anywhere: the eye in or around the scene's box (inside
 * objects too), looking anywhere in it; the field of view from 5 to 175
 * degrees, or orthographic one frame in four; the near plane from 1e-8
 * to 0.05 of the scene's size.  Each frame jumps, so nothing a culler
 * remembers of the last frame holds.  Seeded: the same cameras every run. */
static zs_rng camera_rng;
static void random_camera(int f, const zs_scene *s, zs_camera *cam) {
  (void)f;
  zs_camera_default(cam);
  double size = 0.0;
  for (int k = 0; k < 3; k++) size = fmax(size, s->hi[k] - s->lo[k]);
  for (int k = 0; k < 3; k++) {
    double pad = 0.3 * (s->hi[k] - s->lo[k]);
    cam->eye[k] = zs_rng_range(&camera_rng, s->lo[k] - pad, s->hi[k] + pad);
    cam->target[k] = zs_rng_range(&camera_rng, s->lo[k], s->hi[k]);
  }
  cam->fovy = zs_rng_range(&camera_rng, 5.0, 175.0);
  if (zs_rng_below(&camera_rng, 4) == 0) {
    double e = zs_rng_range(&camera_rng, 0.01, 1.0) * size;
    cam->ortho = 1;
    cam->extent[0] = -e;
    cam->extent[1] = e;
    cam->extent[2] = -0.75 * e;
    cam->extent[3] = 0.75 * e;
  }
  cam->znear = size * pow(10.0, zs_rng_range(&camera_rng, -8.0, -1.3));
  cam->zfar = 4.0 * size;
  cam->has_eye = cam->has_target = cam->has_near = cam->has_far = 1;
}

START_TEST(exact_from_random_cameras) {
  walk_result r;
  zs_rng_seed(&camera_rng, 0xCA3 + (uint64_t)_i);
  walk_camera = random_camera;
  walk(scenes[_i], 16, 1, exact, NEXACT, -1, &r);
  walk_camera = NULL;
  for (int k = 1; k < NEXACT; k++)
    ck_assert_msg(r.diff[k] == 0, "%s, random cameras: %s differs from none in %llu pixels",
                  scenes[_i], zs_cull_method_name(exact[k]), (unsigned long long)r.diff[k]);
  /* the cameras see the scene, and the methods cull and ask */
  ck_assert_uint_gt(r.objects[5], 0);       /* ideal */
  ck_assert_uint_lt(r.objects[5], r.objects[0]);
  ck_assert_uint_gt(r.queries[2], 0);       /* hsw */
}
END_TEST

START_TEST(exact_at_every_latency) {
  /* latency from 0 to 3 frames' worth of none's modelled time */
  const zs_cull_method m[] = {ZS_CULL_NONE, ZS_CULL_HSW, ZS_CULL_CHC, ZS_CULL_CHC_PROB, ZS_CULL_AUTO,
                              ZS_CULL_CHCPP, ZS_CULL_CHCPP_PROB, ZS_CULL_NOHC};
  enum { NM = sizeof m / sizeof m[0] };
  walk_result base;
  walk("plant?detail=0.05", 1, 1, m, 1, -1, &base);
  double frame_ns = (double)base.modelled_ps[0] / 1000.0;
  const double fractions[] = {0.0, 0.01, 0.1, 0.5, 1.0, 2.0, 3.0};
  for (size_t i = 0; i < sizeof fractions / sizeof fractions[0]; i++) {
    walk_result r;
    walk("plant?detail=0.05", 6, 11, m, NM, fractions[i] * frame_ns, &r);
    for (int k = 1; k < NM; k++)
      ck_assert_msg(r.diff[k] == 0, "latency %.2f frames: %s differs in %llu pixels", fractions[i],
                    zs_cull_method_name(m[k]), (unsigned long long)r.diff[k]);
  }
}
END_TEST

START_TEST(vfc_box_reports_its_error) {
  /* The conservative box drops objects whose centre lies outside though
   * part of them is seen: on the city street walk it differs, and says so. */
  const zs_cull_method m[] = {ZS_CULL_NONE, ZS_CULL_VFC_BOX, ZS_CULL_VFC};
  walk_result r;
  walk("city", 10, 7, m, 3, -1, &r);
  ck_assert_uint_eq(r.diff[2], 0);
  ck_assert_uint_gt(r.diff[1], 0);
  ck_assert_uint_lt(r.objects[1], r.objects[0]);
}
END_TEST

START_TEST(query_ordering_on_the_plant) {
  /* fewer queries for chc-prob than chc, and for chc than hsw */
  const zs_cull_method m[] = {ZS_CULL_NONE, ZS_CULL_HSW, ZS_CULL_CHC, ZS_CULL_CHC_PROB};
  walk_result r;
  walk("plant?detail=0.25", 8, 5, m, 4, -1, &r);
  ck_assert_uint_lt(r.queries[3], r.queries[2]);
  ck_assert_uint_lt(r.queries[2], r.queries[1]);
  /* hsw waits for every answer: the slowest of them */
  ck_assert_int_gt(r.modelled_ps[1], r.modelled_ps[2]);
}
END_TEST

START_TEST(method_list_names_every_method) {
  /* the list that usage lines and errors print is the names, in order */
  char list[512] = "";
  for (int m = 0; m < ZS_CULL_METHODS; m++) {
    if (m) strcat(list, " ");
    strcat(list, zs_cull_method_name((zs_cull_method)m));
  }
  ck_assert_str_eq(list, ZS_CULL_METHOD_LIST);
  for (int m = 0; m < ZS_CULL_METHODS; m++)
    ck_assert_int_eq(zs_cull_method_parse(zs_cull_method_name((zs_cull_method)m)), m);
  ck_assert_int_eq(zs_cull_method_parse("chcpp-magic"), -1);
}
END_TEST

/* Every exact method, in lockstep, over the cameras cams[0 .. n-1] of
 * scene s at w x h: pixels differing from none, objects drawn, queries. */
static void walk_cameras(const zs_scene *s, const zs_camera *cams, int n, int w, int h,
                         walk_result *out) {
  memset(out, 0, sizeof *out);
  zs_octree t;
  ck_assert_int_eq(zs_octree_build(&t, s, NULL, &err), ZS_OK);
  uint32_t *ref = malloc((size_t)w * h * sizeof *ref);
  for (int k = 0; k < NEXACT; k++) {
    zs_device_config cfg = {w, h, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, 1, 0, 0, 0};
    zs_device *dev;
    zs_culler *c;
    ck_assert_int_eq(zs_device_create(&cfg, &dev, &err), ZS_OK);
    ck_assert_int_eq(zs_culler_create(exact[k], NULL, &c, &err), ZS_OK);
    for (int f = 0; f < n; f++) {
      zs_camera cam = cams[f];
      zs_camera_complete(&cam, s->lo, s->hi, (double)w / h);
      double view[16], proj[16];
      ck_assert_int_eq(zs_camera_matrices(&cam, (double)w / h, view, proj, &err), ZS_OK);
      zs_cull_stats st;
      ck_assert_msg(zs_culler_frame(c, dev, s, &t, view, proj, &st, &err) == ZS_OK, "%s: %s",
                    zs_cull_method_name(exact[k]), err.msg);
      ck_assert_int_eq(zs_device_finish(dev, NULL, NULL, &err), ZS_OK);
      const uint32_t *ids = zs_device_id_buffer(dev);
      if (k == 0) memcpy(ref, ids, (size_t)w * h * sizeof *ref);
      for (int i = 0; i < w * h; i++) out->diff[exact[k]] += ids[i] != ref[i];
      out->objects[exact[k]] += st.objects_drawn;
      out->queries[exact[k]] += st.queries;
    }
    zs_culler_destroy(c);
    zs_device_destroy(dev);
  }
  free(ref);
  zs_octree_free(&t);
}

START_TEST(empty_scene_every_method) {
  /* no objects (an empty OBJ file): every method draws and asks nothing
   * (the sanitizer build caught ideal clearing a buffer never allocated) */
  zs_scene s;
  zs_scene_init(&s);
  ck_assert_int_eq(zs_scene_finish(&s, &err), ZS_OK);
  zs_camera cam[2];
  zs_camera_default(&cam[0]);
  cam[1] = cam[0];
  walk_result r;
  walk_cameras(&s, cam, 2, W, H, &r);
  for (int k = 0; k < NEXACT; k++) {
    ck_assert_uint_eq(r.objects[exact[k]], 0);
    ck_assert_uint_eq(r.queries[exact[k]], 0);
  }
  zs_scene_free(&s);
}
END_TEST

/* The OBJ file rel seen at 64 x 48 from one camera (eye, target, fovy,
 * near, far): every exact method's image is none's. */
static void obj_from_camera(const char *rel, const double eye[3], const double target[3],
                            double fovy, double znear, double zfar) {
  zs_model m;
  ck_assert_msg(zs_obj_load(zs_test_src(rel), &m, &err) == ZS_OK, "%s", err.msg);
  zs_scene s;
  zs_scene_init(&s);
  ck_assert_int_eq(zs_scene_from_model(&s, &m, &err), ZS_OK);
  ck_assert_int_eq(zs_scene_finish(&s, &err), ZS_OK);
  zs_camera cam;
  zs_camera_default(&cam);
  memcpy(cam.eye, eye, sizeof cam.eye);
  memcpy(cam.target, target, sizeof cam.target);
  cam.fovy = fovy;
  cam.znear = znear;
  cam.zfar = zfar;
  cam.has_eye = cam.has_target = cam.has_near = cam.has_far = 1;
  walk_result r;
  walk_cameras(&s, &cam, 1, 64, 48, &r);
  ck_assert_uint_gt(r.objects[ZS_CULL_NONE], 0);
  for (int k = 1; k < NEXACT; k++)
    ck_assert_msg(r.diff[exact[k]] == 0, "%s: %s differs from none in %llu pixels", rel,
                  zs_cull_method_name(exact[k]), (unsigned long long)r.diff[exact[k]]);
  zs_scene_free(&s);
}

START_TEST(shared_quad_through_a_wide_lens) {
  /* tests/data/cull/shared_quad.obj: three objects hold the same quad;
   * where their depths tie the first one's face id wins, and a query of
   * its box must see that, also where a wide lens makes the quad's depth
   * change fast across a pixel (the camera fuzz_cull found; raster.h,
   * queries: the bias by slope) */
  obj_from_camera("tests/data/cull/shared_quad.obj",
                  (double[3]){6.187987893455424, 9.8415673984363039, -4.5124365023717097},
                  (double[3]){4.860630388594311, 1.5448126739204691, -6.945933849229462},
                  152.54908844727493, 0.001376857406511696, 13.76857406511696);
}
END_TEST

START_TEST(flat_triangle_in_a_box_without_area) {
  /* tests/data/cull/flat_triangle.obj: a triangle flat in the world, its
   * box a segment, snapped into a sliver that holds a pixel (the camera
   * fuzz_cull found; raster.h, queries: the margin) */
  obj_from_camera("tests/data/cull/flat_triangle.obj",
                  (double[3]){2.3115178930805085, 0.74829846958275903, 0.56322110204035214},
                  (double[3]){0.63054699189940377, -0.47418007969387244, 0.88699014340236515},
                  86.885893345846213, 0.1498466053764714, 4.7602896796201373);
}
END_TEST

/* chc-prob on the small plant's walk twice, as [1] with the cost model's
 * parameters p and as [2] with the defaults, both drawing none's pixels. */
static void walk_chc_prob_against_defaults(const zs_cost_params *p, walk_result *r) {
  const zs_cull_method m[] = {ZS_CULL_NONE, ZS_CULL_CHC_PROB, ZS_CULL_CHC_PROB};
  const zs_cost_params *const costs[] = {NULL, p, NULL};
  walk_costs = costs;
  walk("plant?detail=0.25", 12, 8, m, 3, -1, r);
  walk_costs = NULL;
  ck_assert_uint_eq(r->diff[1], 0);
  ck_assert_uint_eq(r->diff[2], 0);
}

START_TEST(cost_model_learns_w1_w2_when_asked) {
  /* With learn, chc-prob predicts P(V) with w1 and w2 learnt from what its
   * queries find instead of the given ones: other decisions, the same
   * pixels.  (On this small plant the learnt weights ask fewer queries.) */
  zs_cost_params learnt;
  zs_cost_params_default(&learnt);
  learnt.learn = 10;
  walk_result r;
  walk_chc_prob_against_defaults(&learnt, &r);
  ck_assert_msg(r.queries[1] < r.queries[2], "learnt %llu queries, given %llu",
                (unsigned long long)r.queries[1], (unsigned long long)r.queries[2]);
}
END_TEST

START_TEST(chc_prob_measures_what_it_draws) {
  /* chc-prob takes an object's P_{t-1}(V) from what its draw wrote: an
   * object drawn unasked that wrote nothing is asked about in the next
   * frame, not drawn again on a prediction.  With measure=0 it predicts
   * from the prediction it drew on: the same pixels, more objects drawn
   * and a longer modelled frame. */
  zs_cost_params predicted;
  zs_cost_params_default(&predicted);
  predicted.measure = 0;
  walk_result r;
  walk_chc_prob_against_defaults(&predicted, &r);
  ck_assert_msg(r.objects[2] < r.objects[1], "measured %llu objects drawn, predicted %llu",
                (unsigned long long)r.objects[2], (unsigned long long)r.objects[1]);
  ck_assert_int_lt(r.modelled_ps[2], r.modelled_ps[1]);
}
END_TEST

START_TEST(ideal_box_bounds_every_box_query_method) {
  /* A method skips an object only when its box found no sample against a
   * depth buffer that only gets nearer, so it draws every object whose box
   * has a sample against the final one: ideal-box's set.  And that set
   * holds the ideal's. */
  const zs_cull_method m[] = {ZS_CULL_NONE, ZS_CULL_IDEAL,    ZS_CULL_IDEAL_BOX, ZS_CULL_HSW,
                              ZS_CULL_CHC,  ZS_CULL_CHC_PROB, ZS_CULL_CHCPP,     ZS_CULL_NOHC};
  enum { NM = sizeof m / sizeof m[0] };
  walk_result r;
  walk("teapots?count=300&moving=40", 10, 7, m, NM, -1, &r);
  ck_assert_uint_lt(r.objects[1], r.objects[2]); /* boxes are looser than pixels */
  for (int k = 3; k < NM; k++)
    ck_assert_msg(r.objects[2] <= r.objects[k], "ideal-box draws %llu objects, %s %llu",
                  (unsigned long long)r.objects[2], zs_cull_method_name(m[k]),
                  (unsigned long long)r.objects[k]);
  ck_assert_int_le(r.modelled_ps[1], r.modelled_ps[2]);
}
END_TEST

/* hzb_phase_one_in_passes: the largest set phase 1 drew, and the objects
 * it left out that last frame's set held */
static uint64_t hzb_most_phase1, hzb_left_out;
static void check_hzb(int f, int k, const zs_cull_stats *st) {
  (void)f;
  if (k != 1) return;
  if (st->hzb_phase1 > hzb_most_phase1) hzb_most_phase1 = st->hzb_phase1;
  hzb_left_out += st->hzb_stale;
}

START_TEST(hzb_phase_one_in_passes) {
  /* A set of thousands of objects is drawn in passes (cull/two_phase_hzb.c), each
   * after the first tested against the pyramid of those before: every
   * frame still the image of none, at an image size where thousands of
   * small teapots stay in the set. */
  const zs_cull_method m[] = {ZS_CULL_NONE, ZS_CULL_HZB};
  walk_result r;
  hzb_most_phase1 = hzb_left_out = 0;
  walk_stats = check_hzb;
  walk_w = 640, walk_h = 480;
  walk("teapots?count=2500&moving=500", 16, 1, m, 2, -1, &r);
  walk_w = W, walk_h = H;
  walk_stats = NULL;
  ck_assert_msg(hzb_most_phase1 >= 1024, "phase 1 drew at most %llu objects: one pass",
                (unsigned long long)hzb_most_phase1);
  ck_assert_msg(r.diff[1] == 0, "hzb differs from none in %llu pixels",
                (unsigned long long)r.diff[1]);
  ck_assert_uint_lt(r.objects[1], r.objects[0]);
}
END_TEST

/* ideal_box_churn_adds_up: the frames' checks, and what they saw */
static uint64_t churn_last_set, churn_entered, churn_left, churn_outside;
static int churn_ranked_above_known;

static void check_churn(int f, int k, const zs_cull_stats *st) {
  (void)k;
  zs_clock_params clock;
  zs_clock_params_default(&clock);
  const int64_t call = llround(clock.per_call_ns * 1000.0);
  if (f == 0) {
    ck_assert(st->set_entered == 0 && st->set_left == 0 && st->churn_known_ps == 0 &&
              st->churn_ranked_ps == 0);
  } else {
    ck_assert_int_eq((int64_t)st->objects_drawn - (int64_t)churn_last_set,
                     (int64_t)st->set_entered - (int64_t)st->set_left);
    ck_assert_uint_le(st->set_entered_outside, st->set_entered);
    ck_assert_uint_le(st->set_left_outside, st->set_left);
    const int64_t in_entered = (int64_t)(st->set_entered - st->set_entered_outside);
    ck_assert_int_eq(st->churn_known_ps,
                     (in_entered + (int64_t)(st->set_left - st->set_left_outside)) * call);
    ck_assert_int_le(st->churn_known_ps, st->churn_ranked_ps);
    ck_assert_int_le(st->churn_ranked_ps, (in_entered + (int64_t)churn_last_set) * call);
    churn_ranked_above_known += st->churn_ranked_ps > st->churn_known_ps;
    churn_entered += st->set_entered;
    churn_left += st->set_left;
    churn_outside += st->set_entered_outside + st->set_left_outside;
  }
  churn_last_set = st->objects_drawn;
}

START_TEST(ideal_box_churn_adds_up) {
  /* ideal-box's set against the last frame (cull/churn.h): what entered
   * and what left make up the change in its size; the floor knowing the
   * changes is one call a change inside the frustum; the ranked floor is
   * never below it, nor above asking about the whole last set; the first
   * frame has nothing to compare with. */
  const zs_cull_method m[] = {ZS_CULL_IDEAL_BOX};
  walk_result r;
  churn_last_set = churn_entered = churn_left = churn_outside = 0;
  churn_ranked_above_known = 0;
  walk_stats = check_churn;
  walk("teapots?count=300&moving=40", 12, 7, m, 1, -1, &r);
  walk_stats = NULL;
  /* the walk has churn to measure, inside the frustum and across it */
  ck_assert_uint_gt(churn_entered, 0);
  ck_assert_uint_gt(churn_left, 0);
  ck_assert_uint_gt(churn_outside, 0);
  ck_assert_int_gt(churn_ranked_above_known, 0);
}
END_TEST

/* Checks the parts of every instance of scene spec: every face lies in
 * one part's box, every part's box in the object's, and an object has at
 * most one part per ZS_FACES_PER_PART faces.  Returns how many objects
 * are split, and in *most the most parts an object has. */
static int check_parts(const char *spec, int *most) {
  zs_scene s;
  ck_assert_msg(zs_gen_scene(spec, &s, &err) == ZS_OK, "%s", err.msg);
  zs_parts *p = zs_parts_create();
  ck_assert_ptr_nonnull(p);
  int split = 0;
  *most = 0;
  for (int32_t i = 0; i < s.ninst; i++) {
    const double(*lo)[3], (*hi)[3];
    int n;
    ck_assert(zs_parts_of(p, &s, i, &lo, &hi, &n));
    const zs_mesh *m = &s.meshes[s.inst[i].mesh].mesh;
    split += n > 1;
    if (n > *most) *most = n;
    ck_assert_int_le(n, ZS_PARTS_MAX);
    ck_assert(n == 1 || n <= m->nfaces / ZS_FACES_PER_PART);
    for (int k = 0; k < n; k++)
      for (int a = 0; a < 3; a++) {
        ck_assert(lo[k][a] >= s.inst[i].lo[a] && hi[k][a] <= s.inst[i].hi[a]);
        ck_assert(lo[k][a] <= hi[k][a]);
      }
    const double *t = s.inst[i].model;
    for (int32_t f = 0; f < m->nfaces; f++) {
      int held = 0;
      for (int k = 0; k < n && !held; k++) {
        held = 1;
        for (int32_t j = m->face_start[f]; j < m->face_start[f + 1] && held; j++) {
          const double *v = m->pos + 3 * m->face_vert[j];
          for (int r = 0; r < 3; r++) {
            double w = t[4 * r] * v[0] + t[4 * r + 1] * v[1] + t[4 * r + 2] * v[2] + t[4 * r + 3];
            held &= w >= lo[k][r] && w <= hi[k][r];
          }
        }
      }
      ck_assert_msg(held, "%s: instance %d face %d lies in no part", spec, i, f);
    }
  }
  zs_parts_destroy(p);
  zs_scene_free(&s);
  return split;
}

START_TEST(parts_hold_every_face_inside_the_box) {
  /* The teapots split into parts (the ground, flat, does not); so do the
   * plant's long pipes and vessels, its largest meshes into more than the
   * 8 parts an object had until the count followed the faces. */
  int most;
  ck_assert_int_eq(check_parts("teapots?count=5", &most), 5);
  ck_assert_int_gt(check_parts("plant?detail=0.25", &most), 0);
  ck_assert_int_gt(most, 8);
}
END_TEST

START_TEST(parts_are_exact_and_tighter_than_boxes) {
  /* the same walk asked about boxes and about parts: both exact; with
   * parts, the oracle of box queries and nohc draw fewer objects */
  const zs_cull_method m[] = {ZS_CULL_NONE, ZS_CULL_IDEAL_BOX, ZS_CULL_CHC, ZS_CULL_NOHC,
                              ZS_CULL_CHCPP};
  enum { NM = sizeof m / sizeof m[0] };
  walk_result box, parts;
  walk_bounds = ZS_BOUNDS_BOX;
  walk("teapots?count=300&moving=40", 10, 7, m, NM, -1, &box);
  walk_bounds = ZS_BOUNDS_PARTS;
  walk("teapots?count=300&moving=40", 10, 7, m, NM, -1, &parts);
  for (int k = 1; k < NM; k++) {
    ck_assert_uint_eq(box.diff[k], 0);
    ck_assert_uint_eq(parts.diff[k], 0);
  }
  ck_assert_uint_lt(parts.objects[1], box.objects[1]);
  ck_assert_uint_lt(parts.objects[3], box.objects[3]);
}
END_TEST

START_TEST(counters_identical_every_run) {
  walk_result a, b;
  walk("teapots?count=60&moving=20", 6, 13, exact, NEXACT, -1, &a);
  walk("teapots?count=60&moving=20", 6, 13, exact, NEXACT, -1, &b);
  ck_assert_int_eq(memcmp(&a, &b, sizeof a), 0);
}
END_TEST

START_TEST(auto_costs_nothing_without_occlusion) {
  /* A single open layer of objects: nothing is hidden, so auto must not be
   * slower than vfc in modelled time (it runs vfc, and queries nothing). */
  zs_scene s;
  zs_error_clear(&err);
  char path[4096];
  snprintf(path, sizeof path, "%s", zs_test_src("scene/examples/open_layer.json"));
  ck_assert_msg(zs_scenefile_load(path, &s, &err) == ZS_OK, "%s", err.msg);
  zs_octree t;
  ck_assert_int_eq(zs_octree_build(&t, &s, NULL, &err), ZS_OK);
  const zs_cull_method m[4] = {ZS_CULL_VFC, ZS_CULL_AUTO, ZS_CULL_CHC, ZS_CULL_NOHC};
  int64_t total[4] = {0, 0, 0, 0};
  uint64_t queries[4] = {0, 0, 0, 0};
  for (int k = 0; k < 4; k++) {
    zs_device_config cfg = {W, H, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, 1, 0, 0, 0};
    zs_device *d;
    zs_culler *c;
    ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
    ck_assert_int_eq(zs_culler_create(m[k], NULL, &c, &err), ZS_OK);
    for (int f = 0; f < s.path.frames; f++) {
      zs_camera cam = s.camera;
      zs_path_camera(&s, f, &cam);
      zs_camera_complete(&cam, s.lo, s.hi, (double)W / H);
      double view[16], proj[16];
      ck_assert_int_eq(zs_camera_matrices(&cam, (double)W / H, view, proj, &err), ZS_OK);
      zs_cull_stats st;
      ck_assert_int_eq(zs_culler_frame(c, d, &s, &t, view, proj, &st, &err), ZS_OK);
      ck_assert_int_eq(zs_device_finish(d, NULL, NULL, &err), ZS_OK);
      total[k] += zs_device_frame_ps(d);
      queries[k] += st.queries;
    }
    zs_culler_destroy(c);
    zs_device_destroy(d);
  }
  ck_assert_int_le(total[1], total[0]);
  ck_assert_uint_eq(queries[1], 0);
  ck_assert_uint_gt(queries[2], 0); /* chc does pay for queries here */
  ck_assert_int_gt(total[2], total[0]);
  /* nohc: its coverage finds nothing to hide here, and it is within 5 % of vfc */
  ck_assert_msg(total[3] * 100 <= total[0] * 105, "nohc %lld ps, vfc %lld ps", (long long)total[3],
                (long long)total[0]);
  zs_octree_free(&t);
  zs_scene_free(&s);
}
END_TEST

START_TEST(frustum_planes_and_masking) {
  double view[16], proj[16];
  zs_mat_look_at(view, (double[3]){0, 0, 0}, (double[3]){0, 0, -1}, (double[3]){0, 1, 0});
  zs_mat_perspective(proj, 90, 1, 1, 100);
  zs_frustum f;
  zs_frustum_from_matrices(&f, view, proj);
  uint64_t tests = 0;
  unsigned mask = ZS_FRUSTUM_ALL_PLANES;
  ck_assert_int_eq(zs_frustum_test_box(&f, (double[3]){-1, -1, -11}, (double[3]){1, 1, -9}, &mask, &tests),
                   ZS_FRUSTUM_INSIDE);
  ck_assert_uint_eq(mask, 0); /* children need test nothing */
  mask = ZS_FRUSTUM_ALL_PLANES;
  ck_assert_int_eq(zs_frustum_test_box(&f, (double[3]){-1, -1, 1}, (double[3]){1, 1, 2}, &mask, &tests),
                   ZS_FRUSTUM_OUTSIDE); /* behind the eye */
  mask = ZS_FRUSTUM_ALL_PLANES;
  ck_assert_int_eq(zs_frustum_test_box(&f, (double[3]){5, -1, -6}, (double[3]){7, 1, -4}, &mask, &tests),
                   ZS_FRUSTUM_INTERSECT); /* across the right plane */
  ck_assert_uint_ne(mask, 0);
  zs_view_box vb;
  zs_view_box_make(&vb, view, proj);
  ck_assert(zs_view_box_contains(&vb, (double[3]){0, 0, -50}));
  ck_assert(zs_view_box_contains(&vb, (double[3]){90, 0, -50})); /* in the box, not the frustum */
  ck_assert(!zs_view_box_contains(&vb, (double[3]){0, 0, -101}));
}
END_TEST

int main(void) {
  Suite *s = suite_create("cull");
  TCase *tc = tcase_create("walks");
  tcase_set_timeout(tc, 900);
  tcase_add_loop_test(tc, exact_methods_match_none_on_every_walk, 0,
                      (int)(sizeof scenes / sizeof scenes[0]));
  tcase_add_loop_test(tc, exact_from_random_cameras, 0, (int)(sizeof scenes / sizeof scenes[0]));
  tcase_add_test(tc, exact_at_every_latency);
  tcase_add_test(tc, vfc_box_reports_its_error);
  tcase_add_test(tc, query_ordering_on_the_plant);
  tcase_add_test(tc, counters_identical_every_run);
  tcase_add_test(tc, ideal_box_bounds_every_box_query_method);
  tcase_add_test(tc, ideal_box_churn_adds_up);
  tcase_add_test(tc, hzb_phase_one_in_passes);
  tcase_add_test(tc, parts_hold_every_face_inside_the_box);
  tcase_add_test(tc, parts_are_exact_and_tighter_than_boxes);
  tcase_add_test(tc, cost_model_learns_w1_w2_when_asked);
  tcase_add_test(tc, chc_prob_measures_what_it_draws);
  tcase_add_test(tc, method_list_names_every_method);
  tcase_add_test(tc, empty_scene_every_method);
  tcase_add_test(tc, shared_quad_through_a_wide_lens);
  tcase_add_test(tc, flat_triangle_in_a_box_without_area);
  tcase_add_test(tc, frustum_planes_and_masking);
  tcase_add_test(tc, auto_costs_nothing_without_occlusion);
  suite_add_tcase(s, tc);
  /* a case of its own, so that ctest runs it beside the others
   * (CMakeLists.txt: test_cull_every_frame) */
  TCase *every = tcase_create("every frame");
  tcase_set_timeout(every, 900);
  tcase_add_loop_test(every, exact_on_every_frame_of_every_walk, 0,
                      (int)(sizeof scenes / sizeof scenes[0]));
  suite_add_tcase(s, every);
  return zs_test_run(s);
}
