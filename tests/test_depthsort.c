/* Depth sort with frame coherence: what each camera motion reuses, that a
 * scene without overlapping depth ranges is painted exactly, and that the
 * cyclic-overlap case is wrong by a counted number of pixels. */
#include <math.h>
#include <string.h>

#include "raster/raster.h"
#include "util/rng.h"
#include "tests/testutil.h"

static zs_error err;
enum { W = 96, H = 72 };

typedef struct frame_ids {
  uint32_t id[W * H];
} frame_ids;

static void keep_ids(void *user, const zs_row *row) {
  memcpy(((frame_ids *)user)->id + row->y * W, row->id, W * sizeof(uint32_t));
}

/* A device and camera: perspective, eye at `eye`, looking at the origin,
 * with an up vector rolled by roll degrees. */
static zs_device *device(zs_algo algo) {
  zs_device_config cfg = {W, H, algo, ZS_SHADE_ID, 0, 1, 0, 0, 0};
  zs_device *d = NULL;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
  return d;
}

static void frame(zs_device *d, const zs_mesh *m, const double eye[3], const double target[3],
                  double roll_deg, frame_ids *out) {
  double view[16], proj[16], up[3] = {sin(roll_deg * ZS_PI / 180), cos(roll_deg * ZS_PI / 180), 0};
  ck_assert(zs_mat_look_at(view, eye, target, up));
  zs_mat_perspective(proj, 50, (double)W / H, 0.5, 100);
  zs_device_clear(d);
  zs_device_set_camera(d, view, proj);
  ck_assert_int_eq(zs_device_draw(d, m, NULL, 0, ZS_RGB_MESH, &err), ZS_OK);
  static frame_ids scratch;
  ck_assert_int_eq(zs_device_finish(d, keep_ids, out ? out : &scratch, &err), ZS_OK);
}

/* Random triangles in a box around the origin. */
static void soup(mesh_buf *b, int n, uint64_t seed) {
  zs_rng rng;
  zs_rng_seed(&rng, seed);
  for (int i = 0; i < n; i++) {
    int32_t v[3];
    double cx = zs_rng_range(&rng, -4, 4), cy = zs_rng_range(&rng, -3, 3);
    double cz = zs_rng_range(&rng, -4, 4);
    for (int k = 0; k < 3; k++) {
      double x = cx + zs_rng_range(&rng, -0.6, 0.6), y = cy + zs_rng_range(&rng, -0.6, 0.6);
      double z = cz + zs_rng_range(&rng, -0.6, 0.6);
      v[k] = mb_vert(b, x, y, z);
    }
    mb_face(b, v, 3, 0xFFFFFF);
  }
}

static const double origin[3] = {0, 0, 0};

/* What a sort from scratch paints of m from that camera must be what the
 * coherent device painted. */
static void assert_paints_as_fresh(const zs_mesh *m, const double eye[3], double roll_deg,
                                   const frame_ids *painted) {
  static frame_ids exact;
  zs_device *fresh = device(ZS_ALGO_DEPTHSORT);
  frame(fresh, m, eye, origin, roll_deg, &exact);
  ck_assert_int_eq(memcmp(painted->id, exact.id, sizeof exact.id), 0);
  zs_device_destroy(fresh);
}

START_TEST(static_camera_does_no_comparisons) {
  mesh_buf b = {0};
  soup(&b, 500, 1);
  zs_device *d = device(ZS_ALGO_DEPTHSORT);
  double eye[3] = {1, 2, 12};
  frame(d, &b.m, eye, origin, 0, NULL);
  const zs_depthsort_stats *s = zs_device_depthsort_stats(d);
  ck_assert_int_eq(s->motion, ZS_MOTION_FIRST);
  ck_assert(s->full_sort);
  ck_assert_uint_gt(s->comparisons, 0);
  uint64_t faces = s->faces;
  frame(d, &b.m, eye, origin, 0, NULL);
  ck_assert_int_eq(s->motion, ZS_MOTION_STATIC);
  ck_assert_uint_eq(s->comparisons, 0);
  ck_assert_uint_eq(s->reused, faces);
  ck_assert_uint_eq(s->inserted, 0);
  zs_device_destroy(d);
  mb_free(&b);
}
END_TEST

START_TEST(roll_keeps_the_faces_beside_the_window) {
  /* Close up, the soup overfills the window, and a roll turns faces in
   * and out at its corners.  The painter orders every face that meets
   * the circle around the window, drawn or beside it: a roll keeps that
   * set, so no face is new and the order stands whole. */
  mesh_buf b = {0};
  soup(&b, 500, 2);
  zs_device *d = device(ZS_ALGO_DEPTHSORT);
  double eye[3] = {0, 0, 7};
  frame(d, &b.m, eye, origin, 0, NULL);
  uint64_t beside = 0;
  for (int k = 1; k <= 6; k++) {
    frame_ids painted;
    frame(d, &b.m, eye, origin, 15.0 * k, &painted);
    const zs_depthsort_stats *s = zs_device_depthsort_stats(d);
    beside += zs_device_stats(d)->polygons_offscreen;
    ck_assert_int_eq(s->motion, ZS_MOTION_ROLL);
    ck_assert_msg(s->comparisons == 0 && s->inserted == 0 && s->reused == s->faces,
                  "frame %d: faces %llu reused %llu inserted %llu cmp %llu", k,
                  (unsigned long long)s->faces, (unsigned long long)s->reused,
                  (unsigned long long)s->inserted, (unsigned long long)s->comparisons);
    assert_paints_as_fresh(&b.m, eye, 15.0 * k, &painted);
  }
  ck_assert_uint_gt(beside, 0); /* faces were beside the window, and kept */
  zs_device_destroy(d);
  mb_free(&b);
}
END_TEST

START_TEST(roll_keeps_specks_whatever_they_snap_to) {
  /* Triangles a few tenths of a pixel across, turned every way, with
   * back faces culled: as the view rolls, their corners snap to other
   * subpixels and set-up finds some of them drawn, turned away or without
   * area by turns.  The painter's set does not follow set-up there, so a
   * roll still keeps it whole. */
  mesh_buf b = {0};
  zs_rng rng;
  zs_rng_seed(&rng, 11);
  for (int i = 0; i < 3000; i++) {
    int32_t v[3];
    double cx = zs_rng_range(&rng, -8, 8), cy = zs_rng_range(&rng, -6, 6);
    double cz = zs_rng_range(&rng, -4, 4);
    for (int k = 0; k < 3; k++)
      v[k] = mb_vert(&b, cx + zs_rng_range(&rng, -0.06, 0.06),
                     cy + zs_rng_range(&rng, -0.06, 0.06), cz + zs_rng_range(&rng, -0.06, 0.06));
    mb_face(&b, v, 3, 0xFFFFFF);
  }
  zs_device_config cfg = {W, H, ZS_ALGO_DEPTHSORT, ZS_SHADE_ID, 1, 1, 0, 0, 0};
  zs_device *d = NULL;
  ck_assert_int_eq(zs_device_create(&cfg, &d, &err), ZS_OK);
  double eye[3] = {0, 0, 40};
  frame(d, &b.m, eye, origin, 0, NULL);
  uint64_t flips = 0, drawn0 = zs_device_stats(d)->polygons_rasterized;
  for (int k = 1; k <= 8; k++) {
    frame(d, &b.m, eye, origin, 7.0 * k, NULL);
    const zs_depthsort_stats *s = zs_device_depthsort_stats(d);
    ck_assert_int_eq(s->motion, ZS_MOTION_ROLL);
    ck_assert_msg(s->inserted == 0 && s->reused == s->faces, "roll %d: faces %llu reused %llu", k,
                  (unsigned long long)s->faces, (unsigned long long)s->reused);
    flips += zs_device_stats(d)->polygons_rasterized != drawn0;
  }
  ck_assert_uint_gt(flips, 0); /* set-up's verdicts did change */
  zs_device_destroy(d);
  mb_free(&b);
}
END_TEST

START_TEST(kept_frames_carry_the_depth_shift) {
  /* Moving along the view axis shifts every depth alike: frames that see
   * the same faces keep the order without touching it.  The frame after
   * them, with a face more, must still find every old face where the
   * shifts of all those frames put it. */
  mesh_buf b = {0};
  soup(&b, 400, 9);
  zs_device *d = device(ZS_ALGO_DEPTHSORT);
  double eye[3] = {0, 0, 30};
  frame(d, &b.m, eye, origin, 0, NULL);
  const zs_depthsort_stats *s = zs_device_depthsort_stats(d);
  uint64_t faces = s->faces;
  for (int k = 1; k <= 4; k++) {
    eye[2] = 30 - 0.5 * k;
    frame(d, &b.m, eye, origin, 0, NULL);
    ck_assert_int_eq(s->motion, ZS_MOTION_DOLLY);
    ck_assert_uint_eq(s->comparisons, 0);
    ck_assert_uint_eq(s->reused, faces);
  }
  int32_t v[3] = {mb_vert(&b, -1, -1, 0.1), mb_vert(&b, 1, -1, 0.1), mb_vert(&b, 0, 1, 0.1)};
  mb_face(&b, v, 3, 0xFFFFFF);
  eye[2] = 27.5;
  frame_ids painted;
  frame(d, &b.m, eye, origin, 0, &painted);
  ck_assert_int_eq(s->motion, ZS_MOTION_DOLLY);
  ck_assert_str_eq(zs_motion_class_name(s->motion), "dolly");
  ck_assert(!s->full_sort);
  ck_assert_uint_eq(s->reused, faces);
  ck_assert_uint_eq(s->inserted, 1);
  assert_paints_as_fresh(&b.m, eye, 0, &painted);
  zs_device_destroy(d);
  mb_free(&b);
}
END_TEST

START_TEST(a_face_around_the_whole_window_is_ordered) {
  /* A wall in front that holds the whole circle around the window (no
   * edge of it comes near) hides a square behind it. */
  mesh_buf b = {0};
  int32_t q[4] = {mb_vert(&b, -0.5, -0.5, -2), mb_vert(&b, 0.5, -0.5, -2),
                  mb_vert(&b, 0.5, 0.5, -2), mb_vert(&b, -0.5, 0.5, -2)};
  mb_face(&b, q, 4, 0xFFFFFF);
  int32_t w[4] = {mb_vert(&b, -50, -50, 1), mb_vert(&b, 50, -50, 1), mb_vert(&b, 50, 50, 1),
                  mb_vert(&b, -50, 50, 1)};
  mb_face(&b, w, 4, 0xFFFFFF);
  double eye[3] = {0, 0, 6};
  static frame_ids painted;
  zs_device *d = device(ZS_ALGO_DEPTHSORT);
  frame(d, &b.m, eye, origin, 0, &painted);
  ck_assert_uint_eq(zs_device_depthsort_stats(d)->faces, 2);
  for (int i = 0; i < W * H; i++) ck_assert_uint_eq(painted.id[i], 1);
  zs_device_destroy(d);
  mb_free(&b);
}
END_TEST

START_TEST(few_new_faces_gallop_into_the_kept_order) {
  /* 1,000 faces seen, then the same with 10 more among them (a static
   * camera: the order is kept).  Each new face finds its place by a
   * galloping search, about 2 log2(gap) comparisons; a plain merge would
   * compare against every kept face up to the last new one. */
  mesh_buf b = {0};
  soup(&b, 1000, 5);
  zs_device *d = device(ZS_ALGO_DEPTHSORT);
  double eye[3] = {0, 0, 30};
  frame(d, &b.m, eye, origin, 0, NULL);
  uint64_t faces = zs_device_depthsort_stats(d)->faces;
  zs_rng rng;
  zs_rng_seed(&rng, 6);
  for (int i = 0; i < 10; i++) {
    int32_t v[3];
    double cx = zs_rng_range(&rng, -3, 3), cz = -3.5 + 0.7 * i; /* spread over the depths */
    for (int k = 0; k < 3; k++)
      v[k] = mb_vert(&b, cx + (k == 1 ? 0.5 : 0), (k == 2 ? 0.5 : 0), cz);
    mb_face(&b, v, 3, 0xFFFFFF);
  }
  frame_ids painted;
  frame(d, &b.m, eye, origin, 0, &painted);
  const zs_depthsort_stats *s = zs_device_depthsort_stats(d);
  ck_assert_int_eq(s->motion, ZS_MOTION_STATIC);
  ck_assert_uint_eq(s->reused, faces);
  ck_assert_uint_eq(s->inserted, 10);
  ck_assert_msg(s->comparisons < 250, "comparisons %llu", (unsigned long long)s->comparisons);
  assert_paints_as_fresh(&b.m, eye, 0, &painted);
  zs_device_destroy(d);
  mb_free(&b);
}
END_TEST

START_TEST(roll_reuses_the_whole_order) {
  mesh_buf b = {0};
  soup(&b, 500, 2);
  zs_device *d = device(ZS_ALGO_DEPTHSORT);
  /* far enough that the soup stays inside the circle every roll keeps in
   * view: no face enters or leaves the frustum */
  double eye[3] = {0, 0, 30};
  frame(d, &b.m, eye, origin, 0, NULL);
  for (int k = 1; k <= 5; k++) {
    frame_ids painted;
    frame(d, &b.m, eye, origin, 2.0 * k, &painted);
    const zs_depthsort_stats *s = zs_device_depthsort_stats(d);
    ck_assert_int_eq(s->motion, ZS_MOTION_ROLL);
    ck_assert_msg(s->comparisons == 0, "frame %d: faces %llu reused %llu inserted %llu cmp %llu full %d", k,
                  (unsigned long long)s->faces, (unsigned long long)s->reused,
                  (unsigned long long)s->inserted, (unsigned long long)s->comparisons, s->full_sort);
    ck_assert_uint_eq(s->inserted, 0);
    ck_assert_uint_eq(s->reused, s->faces);
    /* the order kept is the order a fresh sort gives: same picture */
    assert_paints_as_fresh(&b.m, eye, 2.0 * k, &painted);
  }
  zs_device_destroy(d);
  mb_free(&b);
}
END_TEST

START_TEST(motions_reuse_as_the_paper_says) {
  mesh_buf b = {0};
  soup(&b, 800, 3);
  zs_device *d = device(ZS_ALGO_DEPTHSORT);
  double eye[3] = {0, 1, 12}, target[3] = {0, 0, 0};
  frame(d, &b.m, eye, target, 0, NULL);
  uint64_t full = zs_device_depthsort_stats(d)->comparisons;
  /* small horizontal translation: kept order, few new faces merged in */
  eye[0] += 0.05;
  target[0] += 0.05;
  frame(d, &b.m, eye, target, 0, NULL);
  const zs_depthsort_stats *s = zs_device_depthsort_stats(d);
  ck_assert_int_eq(s->motion, ZS_MOTION_TRANSLATE);
  ck_assert(!s->full_sort);
  ck_assert_uint_gt(s->reused, s->faces * 9 / 10);
  ck_assert_uint_lt(s->comparisons, full / 4);
  /* slow yaw: the nearly sorted old order re-sorted by insertion */
  double a = 1.0 * ZS_PI / 180;
  double t2[3] = {eye[0] + (target[0] - eye[0]) * cos(a) + (target[2] - eye[2]) * sin(a), target[1],
                  eye[2] - (target[0] - eye[0]) * sin(a) + (target[2] - eye[2]) * cos(a)};
  frame(d, &b.m, eye, t2, 0, NULL);
  ck_assert_int_eq(s->motion, ZS_MOTION_SLOW_ROTATE);
  ck_assert(!s->full_sort);
  ck_assert_uint_lt(s->comparisons, full);
  /* fast motion: a full sort */
  double far_eye[3] = {9, 4, 3};
  frame(d, &b.m, far_eye, target, 0, NULL);
  ck_assert_int_eq(s->motion, ZS_MOTION_FAST);
  ck_assert(s->full_sort);
  zs_device_destroy(d);
  mb_free(&b);
}
END_TEST

START_TEST(separate_depths_paint_exactly) {
  /* Squares facing the camera at distinct depths, overlapping on screen:
   * no two depth ranges overlap, so the painter is exact: byte-identical
   * ids to the z-buffer. */
  mesh_buf b = {0};
  zs_rng rng;
  zs_rng_seed(&rng, 4);
  for (int i = 0; i < 40; i++) {
    double x = zs_rng_range(&rng, -3, 2), y = zs_rng_range(&rng, -2, 1), s = zs_rng_range(&rng, 0.5, 2);
    double z = -0.2 * i;
    int32_t v[4] = {mb_vert(&b, x, y, z), mb_vert(&b, x + s, y, z), mb_vert(&b, x + s, y + s, z),
                    mb_vert(&b, x, y + s, z)};
    mb_face(&b, v, 4, 0xFFFFFF);
  }
  double eye[3] = {0.2, 0.1, 9};
  static frame_ids painted, exact;
  zs_device *d = device(ZS_ALGO_DEPTHSORT), *z = device(ZS_ALGO_ZBUFFER);
  frame(d, &b.m, eye, origin, 0, &painted);
  frame(z, &b.m, eye, origin, 0, &exact);
  int covered = 0;
  for (int i = 0; i < W * H; i++) covered += exact.id[i] != ZS_ID_NONE;
  ck_assert_int_gt(covered, 800);
  ck_assert_int_eq(memcmp(painted.id, exact.id, sizeof exact.id), 0);
  zs_device_destroy(d);
  zs_device_destroy(z);
  mb_free(&b);
}
END_TEST

START_TEST(cyclic_overlap_differs) {
  /* Three bars, each over the next and under the one before: no order
   * paints them right.  The z-buffer shows the cycle; the painter cannot. */
  mesh_buf b = {0};
  for (int k = 0; k < 3; k++) {
    double a = 2 * ZS_PI * k / 3, c = cos(a), s = sin(a);
    double p[4][3] = {{-2, -0.3, -0.5}, {2, -0.3, 0.5}, {2, 0.3, 0.5}, {-2, 0.3, -0.5}};
    int32_t v[4];
    for (int i = 0; i < 4; i++)
      v[i] = mb_vert(&b, c * p[i][0] - s * (p[i][1] + 0.8), s * p[i][0] + c * (p[i][1] + 0.8), p[i][2]);
    mb_face(&b, v, 4, 0xFFFFFF);
  }
  double eye[3] = {0.3, 0.2, 8};
  static frame_ids painted, exact;
  zs_device *d = device(ZS_ALGO_DEPTHSORT), *z = device(ZS_ALGO_ZBUFFER);
  frame(d, &b.m, eye, origin, 0, &painted);
  frame(z, &b.m, eye, origin, 0, &exact);
  int differ = 0, ids_seen[3] = {0, 0, 0};
  for (int i = 0; i < W * H; i++) {
    differ += painted.id[i] != exact.id[i];
    if (exact.id[i] < 3) ids_seen[exact.id[i]]++;
  }
  ck_assert_int_gt(ids_seen[0] * ids_seen[1] * ids_seen[2], 0);
  ck_assert_int_gt(differ, 10);
  ck_assert_int_lt(differ, W * H / 10);
  zs_device_destroy(d);
  zs_device_destroy(z);
  mb_free(&b);
}
END_TEST

START_TEST(moved_faces_are_sorted_in_again) {
  /* A static camera and one face that moves to the front: it leaves the
   * old queue and is merged in again, so the picture stays right. */
  mesh_buf b = {0};
  int32_t v[4] = {mb_vert(&b, -1, -1, -2), mb_vert(&b, 1, -1, -2), mb_vert(&b, 1, 1, -2),
                  mb_vert(&b, -1, 1, -2)};
  mb_face(&b, v, 4, 0xFFFFFF);
  int32_t u[4] = {mb_vert(&b, -0.5, -0.5, 0), mb_vert(&b, 0.5, -0.5, 0), mb_vert(&b, 0.5, 0.5, 0),
                  mb_vert(&b, -0.5, 0.5, 0)};
  mb_face(&b, u, 4, 0xFFFFFF);
  double eye[3] = {0, 0, 6};
  static frame_ids painted;
  zs_device *d = device(ZS_ALGO_DEPTHSORT);
  frame(d, &b.m, eye, origin, 0, &painted);
  ck_assert_uint_eq(painted.id[(H / 2) * W + W / 2], 1); /* the small square in front */
  for (int i = 4; i < 8; i++) b.m.pos[3 * i + 2] = -4;  /* now behind */
  frame(d, &b.m, eye, origin, 0, &painted);
  const zs_depthsort_stats *s = zs_device_depthsort_stats(d);
  ck_assert_int_eq(s->motion, ZS_MOTION_STATIC);
  ck_assert_uint_eq(s->reused, 1);
  ck_assert_uint_eq(s->inserted, 1);
  ck_assert_uint_eq(painted.id[(H / 2) * W + W / 2], 0);
  zs_device_destroy(d);
  mb_free(&b);
}
END_TEST

int main(void) {
  Suite *s = suite_create("depthsort");
  TCase *tc = tcase_create("coherence");
  tcase_add_test(tc, static_camera_does_no_comparisons);
  tcase_add_test(tc, roll_reuses_the_whole_order);
  tcase_add_test(tc, roll_keeps_the_faces_beside_the_window);
  tcase_add_test(tc, roll_keeps_specks_whatever_they_snap_to);
  tcase_add_test(tc, kept_frames_carry_the_depth_shift);
  tcase_add_test(tc, a_face_around_the_whole_window_is_ordered);
  tcase_add_test(tc, few_new_faces_gallop_into_the_kept_order);
  tcase_add_test(tc, motions_reuse_as_the_paper_says);
  tcase_add_test(tc, separate_depths_paint_exactly);
  tcase_add_test(tc, cyclic_overlap_differs);
  tcase_add_test(tc, moved_faces_are_sorted_in_again);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
