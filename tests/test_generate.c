/* Checks of the generated meshes and scenes (scene/generate.h): exact
 * counts per scene at the default, a small and the full size; determinism
 * (the same bytes twice, and a recorded hash of them, so any change of the
 * geometry is noticed); closed, outward-facing meshes; instances inside the
 * bounds; moving spheres staying inside the cube; the camera paths; the
 * parameter errors.  (How long the big scenes take to load: zscan bench
 * tradeoff.)
 *
 * When a generator changes on purpose, the recorded counts and hashes
 * change with it: run this suite, read the values it prints on failure,
 * and update the counts below, the hashes with ZS_GOLDEN_UPDATE=1
 * (tests/golden/scenes.txt), with the reason in the commit message. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/exactmath.h"
#include "raster/raster.h"
#include "scene/camera.h"
#include "scene/generate.h"
#include "scene/model.h"
#include "scene/scene.h"
#include "tests/testutil.h"

/* ---- helpers ---------------------------------------------------------- */

static void load(const char *spec, zs_scene *s) {
  zs_error err;
  zs_error_clear(&err);
  zs_status st = zs_gen_scene(spec, s, &err);
  ck_assert_msg(st == ZS_OK, "%s: %s", spec, err.msg);
}

/* A growable byte buffer, hashed at the end with zs_test_fnv1a. */
typedef struct bytes {
  unsigned char *p;
  size_t n, cap;
} bytes;

static void put(bytes *b, const void *data, size_t n) {
  if (n == 0) return;
  if (b->n + n > b->cap) {
    size_t cap = b->cap ? b->cap : 4096;
    while (cap < b->n + n) cap *= 2;
    b->p = realloc(b->p, cap);
    ck_assert_ptr_nonnull(b->p);
    b->cap = cap;
  }
  memcpy(b->p + b->n, data, n);
  b->n += n;
}

/* Every byte a generator decides: vertices, faces, colours, ids of every
 * mesh; mesh, matrix, colour, name and motion of every instance; the
 * camera, image size, bounds and path. */
static void scene_bytes(const zs_scene *s, bytes *b) {
  for (int32_t m = 0; m < s->nmeshes; m++) {
    const zs_mesh *me = &s->meshes[m].mesh;
    put(b, &me->nverts, sizeof me->nverts);
    put(b, me->pos, 3 * sizeof *me->pos * (size_t)me->nverts);
    put(b, &me->nfaces, sizeof me->nfaces);
    put(b, me->face_start, sizeof *me->face_start * (size_t)(me->nfaces + 1));
    put(b, me->face_vert, sizeof *me->face_vert * (size_t)me->face_start[me->nfaces]);
    put(b, me->face_rgb, sizeof *me->face_rgb * (size_t)me->nfaces);
    put(b, me->face_id, sizeof *me->face_id * (size_t)me->nfaces);
  }
  for (int32_t i = 0; i < s->ninst; i++) {
    const zs_instance *in = &s->inst[i];
    put(b, &in->mesh, sizeof in->mesh);
    put(b, in->model, sizeof in->model);
    put(b, &in->rgb, sizeof in->rgb);
    put(b, in->name, strlen(in->name) + 1);
    put(b, &in->id_base, sizeof in->id_base);
    put(b, &in->motion.moving, sizeof in->motion.moving);
    put(b, in->motion.axis, sizeof in->motion.axis);
    put(b, &in->motion.speed, sizeof in->motion.speed);
  }
  const zs_camera *c = &s->camera;
  put(b, c->eye, sizeof c->eye);
  put(b, c->target, sizeof c->target);
  put(b, &c->znear, sizeof c->znear);
  put(b, &c->zfar, sizeof c->zfar);
  put(b, &s->width, sizeof s->width);
  put(b, &s->height, sizeof s->height);
  put(b, s->lo, sizeof s->lo);
  put(b, s->hi, sizeof s->hi);
  put(b, &s->path.frames, sizeof s->path.frames);
  for (int32_t k = 0; k < s->path.nkeys; k++) {
    const zs_keyframe *kf = &s->path.keys[k];
    put(b, &kf->frame, sizeof kf->frame);
    put(b, kf->eye, sizeof kf->eye);
    put(b, kf->target, sizeof kf->target);
    put(b, kf->up, sizeof kf->up);
  }
}

static uint64_t scene_hash(const zs_scene *s) {
  bytes b = {0};
  scene_bytes(s, &b);
  uint64_t h = zs_test_fnv1a(b.p, b.n);
  free(b.p);
  return h;
}

/* ---- counts ------------------------------------------------------------ */

typedef struct count_case {
  const char *spec;
  int64_t objects, faces, triangles;
} count_case;

/* Objects / faces (source faces, the ids) / triangles, at the default
 * seed: for each scene its default, a small and the full size. */
static const count_case counts[] = {
    {"default", 10, 10374, 20748},
    {"default?level=2", 10, 9 * 128 + 6, 2316},
    {"cubes", 64, 384, 768},
    {"cubes?n=1", 1, 6, 12},
    {"cubes?n=16", 4096, 24576, 49152},
    {"teapots", 601, 307206, 614412},
    {"teapots?count=10&level=2", 11, 1286, 2572},
    {"teapots?count=6000", 6001, 3072006, 6144012},
    {"spheres", 5000, 2880000, 5520000},
    {"spheres?count=50", 50, 28800, 55200},
    {"city", 25, 11470, 23596},
    {"city?blocks=1", 7, 2660, 5480},
    {"city?blocks=8", 385, 184462, 379660},
    {"plant", 1223, 201738, 425668},
    {"plant?detail=0.05", 1223, 89734, 198776},
    {"plant?detail=1", 1223, 1998586, 4072508},
};
enum { NCOUNTS = sizeof counts / sizeof counts[0] };

START_TEST(scene_counts) {
  const count_case *c = &counts[_i];
  zs_scene s;
  load(c->spec, &s);
  zs_gen_counts n;
  zs_gen_count(&s, &n);
  ck_assert_msg(n.objects == c->objects && n.faces == c->faces && n.triangles == c->triangles,
                "%s: objects %lld, faces %lld, triangles %lld; expected %lld, %lld, %lld",
                c->spec, (long long)n.objects, (long long)n.faces, (long long)n.triangles,
                (long long)c->objects, (long long)c->faces, (long long)c->triangles);
  ck_assert_uint_eq(zs_scene_faces(&s), (uint64_t)n.faces);
  zs_scene_free(&s);
}
END_TEST

/* ---- determinism ------------------------------------------------------- */

/* The scenes whose bytes (scene_bytes) are pinned, by FNV-1a, in
 * tests/golden/scenes.txt: the same on every run and build (gcc, clang,
 * -O0, -O3), since every angle goes through zs_sincos_turns. */
static const char *const pinned_scenes[] = {
    "default",
    "cubes",
    "teapots",
    "teapots?count=200&level=3&moving=20&seed=7",
    "spheres",
    "spheres?count=500&moving=100&seed=3",
    "city",
    "city?blocks=3&moving=5&seed=9",
    "plant",
    "plant?detail=0.1&seed=5",
};
enum { NHASHES = sizeof pinned_scenes / sizeof pinned_scenes[0] };

/* The shell-safe form NAME,k=v,k=v is the URL form NAME?k=v&k=v, byte for
 * byte; the two may mix; a key given twice is an error either way. */
START_TEST(comma_form_is_the_query_form) {
  static const char *const pairs[][2] = {
      {"teapots,count=200,level=3,moving=20,seed=7", "teapots?count=200&level=3&moving=20&seed=7"},
      {"builtin:city,blocks=3,moving=5,seed=9", "city?blocks=3&moving=5&seed=9"},
      {"plant,detail=0.1&seed=5", "plant?detail=0.1&seed=5"},
  };
  for (int i = 0; i < 3; i++) {
    zs_scene a, b;
    load(pairs[i][0], &a);
    load(pairs[i][1], &b);
    bytes ba = {0}, bb = {0};
    scene_bytes(&a, &ba);
    scene_bytes(&b, &bb);
    ck_assert_msg(ba.n == bb.n && memcmp(ba.p, bb.p, ba.n) == 0, "%s", pairs[i][0]);
    free(ba.p);
    free(bb.p);
    zs_scene_free(&a);
    zs_scene_free(&b);
  }
  zs_scene s;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_gen_scene("cubes,n=2,n=3", &s, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "cubes,n=2,n=3: n given twice");
}
END_TEST

START_TEST(scene_same_bytes) {
  const char *spec = pinned_scenes[_i];
  zs_scene a, b;
  load(spec, &a);
  load(spec, &b);
  bytes ba = {0}, bb = {0};
  scene_bytes(&a, &ba);
  scene_bytes(&b, &bb);
  ck_assert_msg(ba.n == bb.n && memcmp(ba.p, bb.p, ba.n) == 0, "%s: two runs differ", spec);
  zs_golden_assert("scenes.txt", spec, zs_test_fnv1a(ba.p, ba.n));
  free(ba.p);
  free(bb.p);
  zs_scene_free(&a);
  zs_scene_free(&b);
}
END_TEST

START_TEST(seed_changes_the_scene) {
  static const char *pairs[][2] = {{"teapots?count=100", "teapots?count=100&seed=2"},
                                   {"spheres?count=100", "spheres?count=100&seed=2"},
                                   {"city", "city?seed=2"},
                                   {"plant?detail=0.05", "plant?detail=0.05&seed=2"}};
  for (int i = 0; i < 4; i++) {
    zs_scene a, b;
    load(pairs[i][0], &a);
    load(pairs[i][1], &b);
    ck_assert_msg(scene_hash(&a) != scene_hash(&b), "%s and %s are the same", pairs[i][0],
                  pairs[i][1]);
    zs_scene_free(&a);
    zs_scene_free(&b);
  }
  /* The default seed is ZS_GEN_DEFAULT_SEED. */
  zs_scene a, b;
  load("teapots?count=100", &a);
  load("teapots?count=100&seed=1", &b);
  ck_assert_uint_eq(scene_hash(&a), scene_hash(&b));
  zs_scene_free(&a);
  zs_scene_free(&b);
}
END_TEST

/* ---- closed, outward meshes -------------------------------------------- */

static int cmp_u64(const void *a, const void *b) {
  uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return (x > y) - (x < y);
}

/* Every directed edge of the mesh used by exactly one face and its reverse
 * by another: a closed surface, consistently wound.  Returns 0 and says
 * why in msg when not. */
static int closed(const zs_mesh *me, char *msg, size_t cap) {
  size_t n = (size_t)me->face_start[me->nfaces];
  uint64_t *e = malloc(n * sizeof *e);
  ck_assert_ptr_nonnull(e);
  size_t k = 0;
  for (int32_t f = 0; f < me->nfaces; f++) {
    int32_t s = me->face_start[f], t = me->face_start[f + 1];
    for (int32_t i = s; i < t; i++) {
      uint32_t a = (uint32_t)me->face_vert[i], b = (uint32_t)me->face_vert[i + 1 < t ? i + 1 : s];
      e[k++] = (uint64_t)a << 32 | b;
    }
  }
  qsort(e, k, sizeof *e, cmp_u64);
  int ok = 1;
  for (size_t i = 0; i < k && ok; i++) {
    if (i + 1 < k && e[i] == e[i + 1]) {
      snprintf(msg, cap, "edge %u -> %u used twice", (unsigned)(e[i] >> 32),
               (unsigned)(e[i] & 0xFFFFFFFFu));
      ok = 0;
    }
    uint64_t rev = (e[i] & 0xFFFFFFFFu) << 32 | e[i] >> 32;
    if (ok && !bsearch(&rev, e, k, sizeof *e, cmp_u64)) {
      snprintf(msg, cap, "edge %u -> %u has no reverse", (unsigned)(e[i] >> 32),
               (unsigned)(e[i] & 0xFFFFFFFFu));
      ok = 0;
    }
  }
  free(e);
  return ok;
}

/* Six times the signed volume enclosed (fans from each face's first
 * corner; positive when the faces wind counter-clockwise outside), and the
 * smallest face area (twice, from Newell's normal). */
static double volume6(const zs_mesh *me, double *min_area2) {
  double v = 0.0;
  *min_area2 = INFINITY;
  for (int32_t f = 0; f < me->nfaces; f++) {
    int32_t s = me->face_start[f], t = me->face_start[f + 1];
    const double *p0 = me->pos + 3 * me->face_vert[s];
    double nrm[3] = {0, 0, 0};
    for (int32_t i = s; i < t; i++) {
      const double *a = me->pos + 3 * me->face_vert[i];
      const double *b = me->pos + 3 * me->face_vert[i + 1 < t ? i + 1 : s];
      nrm[0] += (a[1] - b[1]) * (a[2] + b[2]);
      nrm[1] += (a[2] - b[2]) * (a[0] + b[0]);
      nrm[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    double area2 = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    if (area2 < *min_area2) *min_area2 = area2;
    for (int32_t i = s + 1; i + 1 < t; i++) {
      const double *p1 = me->pos + 3 * me->face_vert[i], *p2 = me->pos + 3 * me->face_vert[i + 1];
      v += p0[0] * (p1[1] * p2[2] - p1[2] * p2[1]) - p0[1] * (p1[0] * p2[2] - p1[2] * p2[0]) +
           p0[2] * (p1[0] * p2[1] - p1[1] * p2[0]);
    }
  }
  return v;
}

static void check_solid(const char *what, const zs_model *m) {
  char msg[128];
  ck_assert_msg(closed(&m->mesh, msg, sizeof msg), "%s: %s", what, msg);
  double min_area2, v = volume6(&m->mesh, &min_area2);
  ck_assert_msg(v > 0.0, "%s: signed volume %g, not > 0 (faces wind inwards)", what, v / 6.0);
  ck_assert_msg(min_area2 > 0.0, "%s: a face has no area", what);
}

START_TEST(meshes_closed_outward) {
  static const char *specs[] = {
      "sphere",        "sphere?slices=3&stacks=2",  "sphere?slices=100&stacks=7",
      "box",           "box?x=2&y=0.5&z=3",         "cube?size=4",
      "cylinder",      "cylinder?segments=3",       "cylinder?segments=100",
      "cone",          "cone?segments=200&radius=3", "torus",
      "torus?major=2&minor=1.5&segments=5&sides=70"};
  for (size_t i = 0; i < sizeof specs / sizeof specs[0]; i++) {
    zs_model m;
    zs_error err;
    zs_error_clear(&err);
    ck_assert_msg(zs_gen_mesh(specs[i], &m, &err) == ZS_OK, "%s: %s", specs[i], err.msg);
    check_solid(specs[i], &m);
    zs_model_free(&m);
  }
  /* A part of a torus (a pipe elbow) with its end caps, and an open
   * cylinder (not closed, as documented). */
  zs_model m;
  zs_model_init(&m);
  ck_assert_int_eq(zs_gen_torus(&m, 3.0, 1.0, 0.25, 6, 12, 1, NULL, ZS_GREY, -1), ZS_OK);
  check_solid("elbow", &m);
  zs_model_free(&m);
  ck_assert_int_eq(zs_gen_cylinder(&m, 1.0, 1.0, 8, 0, NULL, ZS_GREY, -1), ZS_OK);
  char msg[128];
  ck_assert(!closed(&m.mesh, msg, sizeof msg));
  zs_model_free(&m);
}
END_TEST

/* Every mesh of every generated scene is a closed, outward solid (a union
 * of them), except the teapot, which is open by its data. */
START_TEST(scene_meshes_closed_outward) {
  static const char *specs[] = {"default", "cubes", "teapots?count=20", "spheres?count=10",
                                "city", "plant?detail=0.05", "plant"};
  for (size_t i = 0; i < sizeof specs / sizeof specs[0]; i++) {
    zs_scene s;
    load(specs[i], &s);
    for (int32_t m = 0; m < s.nmeshes; m++) {
      const char *name = s.meshes[m].nobjects ? s.meshes[m].object_names[0] : "?";
      if (strcmp(name, "teapot") == 0) continue;
      char what[160];
      snprintf(what, sizeof what, "%s: mesh %d (%s)", specs[i], (int)m, name);
      check_solid(what, &s.meshes[m]);
    }
    zs_scene_free(&s);
  }
}
END_TEST

START_TEST(mesh_counts) {
  static const struct {
    const char *spec;
    int32_t verts, faces;
  } cases[] = {
      {"sphere", 2 + 23 * 24, 576},         {"sphere?slices=5&stacks=2", 2 + 5, 10},
      {"box", 8, 6},                         {"cube", 8, 6},
      {"cylinder", 32, 18},                  {"cylinder?caps=0", 32, 16},
      {"cylinder?segments=100", 202, 300},   {"cone", 17, 17},
      {"torus", 32 * 16, 32 * 16},           {"teapot", 1568, 1152},
      {"teapot?level=1", 128, 32},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    zs_model m;
    zs_error err;
    zs_error_clear(&err);
    ck_assert_msg(zs_gen_mesh(cases[i].spec, &m, &err) == ZS_OK, "%s", err.msg);
    ck_assert_msg(m.mesh.nverts == cases[i].verts && m.nsource_faces == cases[i].faces,
                  "%s: %d vertices, %d faces", cases[i].spec, (int)m.mesh.nverts,
                  (int)m.nsource_faces);
    ck_assert_int_eq(m.nobjects, 1);
    zs_model_free(&m);
  }
  /* Sizes: the unit sphere, a 2 x 0.5 x 3 box, the cylinder centred. */
  zs_model m;
  double lo[3], hi[3];
  zs_gen_mesh("box?x=2&y=0.5&z=3", &m, NULL);
  zs_model_bounds(&m, lo, hi);
  ck_assert(lo[0] == -1.0 && hi[0] == 1.0 && lo[1] == -0.25 && hi[1] == 0.25 && lo[2] == -1.5 &&
            hi[2] == 1.5);
  zs_model_free(&m);
  zs_gen_mesh("cylinder?radius=3&height=4", &m, NULL);
  zs_model_bounds(&m, lo, hi);
  ck_assert(lo[0] == -3.0 && hi[0] == 3.0 && lo[1] == -2.0 && hi[1] == 2.0);
  zs_model_free(&m);
  zs_gen_mesh("sphere", &m, NULL);
  zs_model_bounds(&m, lo, hi);
  ck_assert(lo[1] == -1.0 && hi[1] == 1.0 && hi[0] == 1.0);
  zs_model_free(&m);
}
END_TEST

/* ---- placement, bounds, motion ----------------------------------------- */

static double det3(const double m[16]) {
  return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
         m[2] * (m[4] * m[9] - m[5] * m[8]);
}

START_TEST(instances_inside_bounds) {
  static const char *specs[] = {"default", "cubes?n=5", "teapots", "spheres", "city",
                                "plant?detail=0.05"};
  for (size_t i = 0; i < sizeof specs / sizeof specs[0]; i++) {
    zs_scene s;
    load(specs[i], &s);
    ck_assert_int_gt(s.ninst, 0);
    for (int32_t k = 0; k < s.ninst; k++) {
      const zs_instance *in = &s.inst[k];
      for (int a = 0; a < 3; a++)
        ck_assert_msg(in->lo[a] >= s.lo[a] && in->hi[a] <= s.hi[a], "%s: %s outside the bounds",
                      specs[i], in->name);
      /* Proper placements keep the winding: a positive determinant. */
      ck_assert_msg(det3(in->model) > 0.0, "%s: %s is mirrored", specs[i], in->name);
      ck_assert_int_eq(in->model[12], 0.0);
      ck_assert_int_eq(in->model[15], 1.0);
    }
    ck_assert_int_eq(s.width, 1024);
    ck_assert_int_eq(s.height, 768);
    zs_scene_free(&s);
  }
  /* The spheres' bounds are the 1,000-unit cube. */
  zs_scene s;
  load("spheres?count=10", &s);
  ck_assert(s.has_bounds && s.lo[0] == 0.0 && s.hi[0] == 1000.0 && s.lo[2] == 0.0 &&
            s.hi[1] == 1000.0);
  zs_scene_free(&s);
}
END_TEST

START_TEST(spheres_move_inside_the_cube) {
  zs_scene s;
  load("spheres?count=300&moving=200", &s);
  double *start = malloc(sizeof(double) * 3 * (size_t)s.ninst);
  ck_assert_ptr_nonnull(start);
  for (int32_t i = 0; i < s.ninst; i++) {
    ck_assert_int_eq(s.inst[i].motion.moving, i < 200);
    for (int a = 0; a < 3; a++) start[3 * i + a] = s.inst[i].model[4 * a + 3];
  }
  /* 600 frames at up to 2.5 units a frame: most spheres bounce. */
  for (int f = 0; f < 600; f++) {
    zs_scene_advance(&s);
    for (int32_t i = 0; i < s.ninst; i++)
      for (int a = 0; a < 3; a++)
        ck_assert_msg(s.inst[i].lo[a] >= -1e-9 && s.inst[i].hi[a] <= 1000.0 + 1e-9,
                      "frame %d: %s leaves the cube", f, s.inst[i].name);
  }
  int moved = 0;
  for (int32_t i = 0; i < s.ninst; i++) {
    double d = 0.0;
    for (int a = 0; a < 3; a++) d += fabs(s.inst[i].model[4 * a + 3] - start[3 * i + a]);
    if (i < 200) moved += d > 0.0;
    else ck_assert_msg(d == 0.0, "%s moved", s.inst[i].name);
  }
  ck_assert_int_eq(moved, 200);
  free(start);
  zs_scene_free(&s);

  /* moving = N changes which spheres move and nothing else. */
  zs_scene a, b;
  load("spheres?count=100", &a);
  load("spheres?count=100&moving=0", &b);
  for (int32_t i = 0; i < a.ninst; i++) {
    ck_assert(memcmp(a.inst[i].model, b.inst[i].model, sizeof a.inst[i].model) == 0);
    ck_assert_int_eq(a.inst[i].motion.moving, 1);
    ck_assert_int_eq(b.inst[i].motion.moving, 0);
  }
  zs_scene_free(&a);
  zs_scene_free(&b);
}
END_TEST

START_TEST(paths) {
  static const struct {
    const char *spec;
    int32_t frames;
  } cases[] = {{"default", 200}, {"cubes", 200},         {"teapots", 300},
               {"spheres", 300}, {"city", 400},          {"plant?detail=0.05", 400},
               {"teapots?frames=1000", 1000}, {"city?frames=16", 16}, {"plant?detail=0.05&frames=32", 32},
               {"city?blocks=1", 400}, {"city?blocks=8", 400}, {"cubes?n=1", 200},
               {"cubes?n=7", 200},     {"teapots?count=1", 300}};
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    zs_scene s;
    load(cases[i].spec, &s);
    const zs_path *p = &s.path;
    ck_assert_int_eq(p->frames, cases[i].frames);
    ck_assert_int_ge(p->nkeys, 2);
    ck_assert_int_eq(p->keys[0].frame, 0);
    ck_assert_int_eq(p->keys[p->nkeys - 1].frame, p->frames - 1);
    for (int32_t k = 1; k < p->nkeys; k++) ck_assert_int_gt(p->keys[k].frame, p->keys[k - 1].frame);
    for (int32_t f = 0; f < p->frames; f++) {
      zs_camera c;
      zs_path_camera(&s, f, &c);
      double d = 0.0;
      for (int a = 0; a < 3; a++) {
        ck_assert(isfinite(c.eye[a]) && isfinite(c.target[a]));
        d += fabs(c.target[a] - c.eye[a]);
      }
      ck_assert_msg(d > 0.0, "%s: frame %d looks nowhere", cases[i].spec, (int)f);
      /* and has an image orientation: the plant's path looks straight
       * down at frame 258, where its up vector lay along the view */
      zs_camera full = c;
      zs_camera_complete(&full, s.lo, s.hi, 4.0 / 3.0);
      double view[16], proj[16];
      zs_error err;
      zs_error_clear(&err);
      ck_assert_msg(zs_camera_matrices(&full, 4.0 / 3.0, view, proj, &err) == ZS_OK,
                    "%s: frame %d: %s", cases[i].spec, (int)f, err.msg);
      /* The walks stay above the ground. */
      if (strncmp(cases[i].spec, "city", 4) == 0 || strncmp(cases[i].spec, "plant", 5) == 0)
        ck_assert_msg(c.eye[1] > 1.0, "%s: frame %d: eye at y = %g", cases[i].spec, (int)f,
                      c.eye[1]);
    }
    zs_scene_free(&s);
  }
}
END_TEST

/* ---- errors ------------------------------------------------------------ */

static void expect_scene_error(const char *spec, const char *msg) {
  zs_scene s;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_gen_scene(spec, &s, &err) != ZS_OK, "%s: accepted", spec);
  ck_assert_str_eq(err.msg, msg);
  ck_assert_int_eq(s.ninst, 0);
  ck_assert_int_eq(s.nmeshes, 0);
  zs_scene_free(&s);
}

static void expect_mesh_error(const char *spec, const char *msg) {
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_gen_mesh(spec, &m, &err) != ZS_OK, "%s: accepted", spec);
  ck_assert_str_eq(err.msg, msg);
  ck_assert_int_eq(m.mesh.nverts, 0);
  zs_model_free(&m);
}

START_TEST(parameter_errors) {
  expect_scene_error("teapots?count=x", "teapots?count=x: count: expected a whole number, got 'x'");
  expect_scene_error("teapots?count=7000", "teapots?count=7000: count: 7000 is outside 1 .. 6000");
  expect_scene_error("teapots?count=0", "teapots?count=0: count: 0 is outside 1 .. 6000");
  expect_scene_error("teapots?colour=red",
                     "teapots?colour=red: unknown parameter 'colour' (count, level, moving, "
                     "seed, frames)");
  expect_scene_error("x", "x: unknown generated scene 'x' (teapots, spheres, city, plant, "
                          "cubes, default)");
  expect_scene_error("builtin:teapot", "builtin:teapot: unknown generated scene 'teapot' "
                                       "(teapots, spheres, city, plant, cubes, default)");
  expect_scene_error("teapots?count=5.0", "teapots?count=5.0: count: expected a whole number, "
                                          "got '5.0'");
  expect_scene_error("teapots?count= 5", "teapots?count= 5: count: expected a whole number, "
                                         "got ' 5'");
  expect_scene_error("teapots?count=", "teapots?count=: count: expected a whole number, got ''");
  expect_scene_error("teapots?count=99999999999999999999",
                     "teapots?count=99999999999999999999: count: 99999999999999999999 is "
                     "outside 1 .. 6000");
  expect_scene_error("teapots?count=10&count=20", "teapots?count=10&count=20: count given twice");
  expect_scene_error("teapots?count", "teapots?count: expected key=value, got 'count'");
  expect_scene_error("teapots?", "teapots?: expected key=value, got ''");
  expect_scene_error("teapots?count=5&", "teapots?count=5&: expected key=value, got ''");
  expect_scene_error("teapots?=5", "teapots?=5: expected key=value, got '=5'");
  expect_scene_error("teapots?level=17", "teapots?level=17: level: 17 is outside 1 .. 16");
  expect_scene_error("teapots?count=10&moving=11",
                     "teapots?count=10&moving=11: moving: 11 is more than count (10)");
  expect_scene_error("spheres?count=100&moving=200",
                     "spheres?count=100&moving=200: moving: 200 is more than count (100)");
  expect_scene_error("spheres?count=5001", "spheres?count=5001: count: 5001 is outside 1 .. 5000");
  expect_scene_error("spheres?seed=-1", "spheres?seed=-1: seed: expected a whole number from 0 "
                                        "to 18446744073709551615, got '-1'");
  expect_scene_error("spheres?seed=18446744073709551616",
                     "spheres?seed=18446744073709551616: seed: expected a whole number from 0 "
                     "to 18446744073709551615, got '18446744073709551616'");
  expect_scene_error("plant?detail=2", "plant?detail=2: detail: 2 is outside 0.05 .. 1");
  expect_scene_error("plant?detail=0.01", "plant?detail=0.01: detail: 0.01 is outside 0.05 .. 1");
  expect_scene_error("plant?detail=nan", "plant?detail=nan: detail: expected a number, got 'nan'");
  expect_scene_error("plant?detail=0x1p-2",
                     "plant?detail=0x1p-2: detail: expected a number, got '0x1p-2'");
  expect_scene_error("plant?detail=.5e", "plant?detail=.5e: detail: expected a number, got '.5e'");
  expect_scene_error("plant?frames=31", "plant?frames=31: frames: 31 is outside 32 .. 100000");
  expect_scene_error("city?blocks=9", "city?blocks=9: blocks: 9 is outside 1 .. 8");
  expect_scene_error("city?moving=9", "city?moving=9: moving: 9 is more than the cars (8)");
  expect_scene_error("cubes?n=65", "cubes?n=65: n: 65 is outside 1 .. 64");
  expect_scene_error("default?seed=1",
                     "default?seed=1: unknown parameter 'seed' (level, frames)");

  char long_spec[ZS_GEN_SPEC_MAX + 2];
  memset(long_spec, 'a', sizeof long_spec - 1);
  long_spec[sizeof long_spec - 1] = '\0';
  zs_scene s;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_gen_scene(long_spec, &s, &err), ZS_ERR_ARG);
  ck_assert(strstr(err.msg, "...: longer than 1024 bytes") != NULL);

  /* Accepted forms: the builtin: prefix, reals written plainly, "+". */
  static const char *good[] = {"builtin:cubes?n=2", "plant?detail=.05&frames=40",
                               "plant?detail=5e-2", "plant?detail=+1e-1"};
  for (int i = 0; i < 4; i++) {
    zs_error_clear(&err);
    ck_assert_msg(zs_gen_scene(good[i], &s, &err) == ZS_OK, "%s: %s", good[i], err.msg);
    zs_scene_free(&s);
  }

  expect_mesh_error("sphere?slices=2", "sphere?slices=2: slices: 2 is outside 3 .. 1024");
  expect_mesh_error("pyramid", "pyramid: unknown generated mesh 'pyramid' (teapot, sphere, box, "
                               "cube, cylinder, cone, torus)");
  expect_mesh_error("torus?minor=2", "torus?minor=2: minor must be less than major");
  expect_mesh_error("box?x=0", "box?x=0: x: 0 is outside 1e-06 .. 1e+06");
  expect_mesh_error("cylinder?caps=2", "cylinder?caps=2: caps: 2 is outside 0 .. 1");

  /* A NULL err is allowed. */
  ck_assert_int_eq(zs_gen_scene("x", &s, NULL), ZS_ERR_ARG);
  ck_assert_int_eq(s.ninst, 0);
}
END_TEST

/* ---- trigonometry ------------------------------------------------------ */

START_TEST(sincos_turns_exact) {
  double s, c;
  static const double quarter[4][2] = {{0, 1}, {1, 0}, {0, -1}, {-1, 0}};
  for (int q = -8; q <= 8; q++) {
    zs_sincos_turns(0.25 * q, &s, &c);
    int k = ((q % 4) + 4) % 4;
    ck_assert(s == quarter[k][0] && c == quarter[k][1]);
    ck_assert(!signbit(s) || s != 0.0);
  }
  double worst = 0.0;
  for (int i = -2000; i <= 2000; i++) {
    double t = i / 997.0;
    zs_sincos_turns(t, &s, &c);
    double e = fmax(fabs(s - sin(2.0 * ZS_PI * t)), fabs(c - cos(2.0 * ZS_PI * t)));
    if (e > worst) worst = e;
  }
  ck_assert_msg(worst < 2e-15, "zs_sincos_turns is %g off", worst);
}
END_TEST

int main(void) {
  Suite *s = suite_create("generate");
  TCase *tc = tcase_create("counts");
  tcase_set_timeout(tc, 600);
  tcase_add_loop_test(tc, scene_counts, 0, NCOUNTS);
  tcase_add_test(tc, mesh_counts);
  suite_add_tcase(s, tc);

  tc = tcase_create("determinism");
  tcase_set_timeout(tc, 600);
  tcase_add_loop_test(tc, scene_same_bytes, 0, NHASHES);
  tcase_add_test(tc, comma_form_is_the_query_form);
  tcase_add_test(tc, seed_changes_the_scene);
  tcase_add_test(tc, sincos_turns_exact);
  suite_add_tcase(s, tc);

  tc = tcase_create("geometry");
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, meshes_closed_outward);
  tcase_add_test(tc, scene_meshes_closed_outward);
  tcase_add_test(tc, instances_inside_bounds);
  tcase_add_test(tc, spheres_move_inside_the_cube);
  tcase_add_test(tc, paths);
  suite_add_tcase(s, tc);

  tc = tcase_create("errors");
  tcase_add_test(tc, parameter_errors);
  suite_add_tcase(s, tc);

  return zs_test_run(s);
}
