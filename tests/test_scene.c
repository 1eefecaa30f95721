/* Scenes: the container (ids, bounds, a scene from one model), moving
 * instances and their bounces, camera paths (keyframed and the four named
 * motions of the depth-sort paper), scene files (the examples, each
 * rendered, and a corpus of broken files with the exact place each error
 * names), and models through assimp (good ones counted independently,
 * broken ones refused cleanly or loaded sane). */
#include <cjson/cJSON.h>
#include <dirent.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "lib/input.h"
#include "raster/raster.h"
#include "util/rng.h"
#include "scene/load_assimp.h"
#include "scene/generate.h"
#include "scene/camera.h"
#include "scene/load_obj.h"
#include "scene/paths.h"
#include "scene/scene.h"
#include "scene/load_scenefile.h"
#include "tests/testutil.h"
#include "util/os.h"

#define ASSIMP_MODELS "/usr/share/assimp/models"

/* ---- helpers ----------------------------------------------------------- */

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double len3(const double a[3]) { return sqrt(dot3(a, a)); }

static double dist3(const double a[3], const double b[3]) {
  double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return len3(d);
}

static void sub3(const double a[3], const double b[3], double out[3]) {
  for (int i = 0; i < 3; i++) out[i] = a[i] - b[i];
}

static void cross3(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

/* The angle between two vectors, in degrees. */
static double angle_deg(const double a[3], const double b[3]) {
  double c[3];
  cross3(a, b, c);
  return atan2(len3(c), dot3(a, b)) * 180.0 / ZS_PI;
}

static char *slurp_src(const char *rel, size_t *len);

static void load_scene(const char *rel, zs_scene *s) {
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_scenefile_load(zs_test_src(rel), s, &err) == ZS_OK, "%s", err.msg);
}

static void parse_scene(const char *text, zs_scene *s) {
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_scenefile_parse(text, strlen(text), "t.json", zs_test_src("scene/examples"), s,
                                   &err) == ZS_OK,
                "%s", err.msg);
}

/* 64-bit FNV-1a, continued from h. */
static uint64_t fnv_more(uint64_t h, const void *data, size_t n) {
  const unsigned char *p = data;
  for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

/* A hash of everything of a scene that motion changes or a loader makes. */
static uint64_t scene_hash(const zs_scene *s) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (int32_t m = 0; m < s->nmeshes; m++) {
    const zs_mesh *mesh = &s->meshes[m].mesh;
    h = fnv_more(h, mesh->pos, 3 * sizeof(double) * (size_t)mesh->nverts);
    h = fnv_more(h, mesh->face_vert, sizeof(int32_t) * (size_t)mesh->face_start[mesh->nfaces]);
    h = fnv_more(h, mesh->face_rgb, sizeof(uint32_t) * (size_t)mesh->nfaces);
  }
  for (int32_t i = 0; i < s->ninst; i++) {
    const zs_instance *in = &s->inst[i];
    h = fnv_more(h, in->model, sizeof in->model);
    h = fnv_more(h, in->lo, sizeof in->lo);
    h = fnv_more(h, in->hi, sizeof in->hi);
    h = fnv_more(h, &in->motion.speed, sizeof in->motion.speed);
    h = fnv_more(h, &in->id_base, sizeof in->id_base);
    h = fnv_more(h, &in->rgb, sizeof in->rgb);
  }
  for (int32_t k = 0; k < s->path.nkeys; k++) { /* field by field: no padding */
    const zs_keyframe *key = &s->path.keys[k];
    h = fnv_more(h, &key->frame, sizeof key->frame);
    h = fnv_more(h, key->eye, sizeof key->eye);
    h = fnv_more(h, key->target, sizeof key->target);
    h = fnv_more(h, key->up, sizeof key->up);
  }
  return h;
}

/* ---- rendering a scene (what `zscan render SCENE.json` will do) --------- */

typedef struct frame_acc {
  uint64_t hash;
  int64_t covered; /* pixels with a face */
} frame_acc;

static void acc_row(void *user, const zs_row *row) {
  frame_acc *a = user;
  a->hash = fnv_more(a->hash, row->rgb, sizeof(uint32_t) * (size_t)row->width);
  a->hash = fnv_more(a->hash, row->id, sizeof(uint32_t) * (size_t)row->width);
  for (int x = 0; x < row->width; x++) a->covered += row->id[x] != ZS_ID_NONE;
}

/* Draws frame f of s (the path's camera, completed from the bounds) and
 * returns the hash of its colours and ids; *covered counts face pixels. */
static uint64_t render_scene(const zs_scene *s, int32_t f, zs_algo algo, zs_shade shade,
                             int64_t *covered) {
  int w = s->width > 0 ? s->width : 160, h = s->height > 0 ? s->height : 120;
  double aspect = (double)w / h, view[16], proj[16];
  zs_camera cam;
  zs_path_camera(s, f, &cam);
  zs_camera_complete(&cam, s->lo, s->hi, aspect);
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_camera_matrices(&cam, aspect, view, proj, &err) == ZS_OK, "%s", err.msg);
  zs_device_config cfg = {
      .width = w, .height = h, .algo = algo, .shade = shade, .threads = 1, .background = 0x1E2228};
  zs_device *dev;
  ck_assert_msg(zs_device_create(&cfg, &dev, &err) == ZS_OK, "%s", err.msg);
  zs_device_set_camera(dev, view, proj);
  zs_device_clear(dev);
  for (int32_t i = 0; i < s->ninst; i++) {
    const zs_instance *in = &s->inst[i];
    ck_assert_msg(zs_device_draw(dev, &s->meshes[in->mesh].mesh, in->model, in->id_base, in->rgb,
                                 &err) == ZS_OK,
                  "%s", err.msg);
  }
  frame_acc acc = {0xcbf29ce484222325ull, 0};
  ck_assert_msg(zs_device_finish(dev, acc_row, &acc, &err) == ZS_OK, "%s", err.msg);
  zs_device_destroy(dev);
  if (covered) *covered = acc.covered;
  return acc.hash;
}

/* ---- the container ----------------------------------------------------- */

/* Two triangles (a unit square in z = 0), two source faces. */
static void square_model(zs_model *m) {
  zs_model_init(m);
  zs_model_add_vertex(m, 0, 0, 0);
  zs_model_add_vertex(m, 1, 0, 0);
  zs_model_add_vertex(m, 1, 1, 0);
  zs_model_add_vertex(m, 0, 1, 0);
  int32_t a[3] = {0, 1, 2}, b[3] = {0, 2, 3};
  ck_assert_int_eq(zs_model_add_polygon(m, a, 3, 0x112233, -1), ZS_OK);
  ck_assert_int_eq(zs_model_add_polygon(m, b, 3, 0x112233, -1), ZS_OK);
}

START_TEST(container_ids_and_bounds) {
  zs_scene s;
  zs_scene_init(&s);
  zs_model box, sq;
  zs_model_init(&box);
  const double lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
  ck_assert_int_eq(zs_gen_box(&box, lo, hi, NULL, 0xFF0000, -1), ZS_OK);
  square_model(&sq);
  ck_assert_int_eq(zs_scene_add_mesh(&s, &box), 0);
  ck_assert_int_eq(zs_scene_add_mesh(&s, &sq), 1);
  ck_assert_int_eq(box.mesh.nverts, 0); /* moved into the scene */
  ck_assert_ptr_null(box.mesh.pos);

  double t[16], sc[16];
  zs_mat_translate(t, 10, 0, 0);
  zs_mat_scale(sc, 2, 3, 4);
  char name[] = "first";
  ck_assert_int_eq(zs_scene_add_instance(&s, 0, NULL, ZS_RGB_MESH, name), 0);
  ck_assert_int_eq(zs_scene_add_instance(&s, 1, t, 0x00FF00, "square"), 1);
  ck_assert_int_eq(zs_scene_add_instance(&s, 0, sc, ZS_RGB_MESH, NULL), 2);
  name[0] = 'X';
  ck_assert_str_eq(s.inst[0].name, "first"); /* copied */
  ck_assert_str_eq(s.inst[2].name, "");

  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_scene_finish(&s, &err), ZS_OK);
  ck_assert_uint_eq(s.inst[0].id_base, 0);
  ck_assert_uint_eq(s.inst[1].id_base, 6);
  ck_assert_uint_eq(s.inst[2].id_base, 8);
  ck_assert_uint_eq(zs_scene_faces(&s), 14);

  /* world boxes: exact boxes of the transformed vertices */
  const double e1lo[3] = {10, 0, 0}, e1hi[3] = {11, 1, 0};
  const double e2lo[3] = {-2, -3, -4}, e2hi[3] = {2, 3, 4};
  for (int k = 0; k < 3; k++) {
    ck_assert_double_eq(s.inst[0].lo[k], -1);
    ck_assert_double_eq(s.inst[0].hi[k], 1);
    ck_assert_double_eq(s.inst[1].lo[k], e1lo[k]);
    ck_assert_double_eq(s.inst[1].hi[k], e1hi[k]);
    ck_assert_double_eq(s.inst[2].lo[k], e2lo[k]);
    ck_assert_double_eq(s.inst[2].hi[k], e2hi[k]);
  }
  /* the scene's bounds: their union */
  const double ulo[3] = {-2, -3, -4}, uhi[3] = {11, 3, 4};
  for (int k = 0; k < 3; k++) {
    ck_assert_double_eq(s.lo[k], ulo[k]);
    ck_assert_double_eq(s.hi[k], uhi[k]);
  }
  /* finishing again changes nothing */
  uint64_t h = scene_hash(&s);
  ck_assert_int_eq(zs_scene_finish(&s, &err), ZS_OK);
  ck_assert_uint_eq(scene_hash(&s), h);

  /* given bounds are kept */
  s.has_bounds = 1;
  for (int k = 0; k < 3; k++) s.lo[k] = -100, s.hi[k] = 100;
  ck_assert_int_eq(zs_scene_finish(&s, &err), ZS_OK);
  ck_assert_double_eq(s.lo[1], -100);
  ck_assert_double_eq(s.hi[2], 100);

  /* an instance of a mesh that does not exist */
  ck_assert_int_eq(zs_scene_add_instance(&s, 7, NULL, ZS_RGB_MESH, "ghost"), 3);
  ck_assert_int_eq(zs_scene_finish(&s, &err), ZS_ERR_ARG);
  ck_assert_msg(strstr(err.msg, "ghost") != NULL, "%s", err.msg);
  zs_scene_free(&s);
  ck_assert_int_eq(s.ninst, 0);
  ck_assert_ptr_null(s.inst);
  zs_scene_free(&s); /* twice is harmless */
}
END_TEST

/* zs_scene_from_model: one instance per object, ids the file's face
 * numbers, each face with its own vertices. */
static void check_from_model(const char *rel) {
  zs_model src, m;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_obj_load(zs_test_src(rel), &src, &err) == ZS_OK, "%s", err.msg);
  ck_assert_msg(zs_obj_load(zs_test_src(rel), &m, &err) == ZS_OK, "%s", err.msg);
  zs_scene s;
  zs_scene_init(&s);
  ck_assert_msg(zs_scene_from_model(&s, &m, &err) == ZS_OK, "%s", err.msg);
  ck_assert_int_eq(m.mesh.nverts, 0); /* consumed */
  ck_assert_int_eq(zs_scene_finish(&s, &err), ZS_OK);
  ck_assert_uint_eq(zs_scene_faces(&s), (uint64_t)src.nsource_faces);

  int32_t *seen = calloc((size_t)src.nsource_faces, sizeof *seen);
  int32_t mesh_faces = 0;
  for (int32_t i = 0; i < s.ninst; i++) {
    const zs_instance *in = &s.inst[i];
    ck_assert_uint_eq(in->id_base, 0);
    ck_assert_uint_eq(in->rgb, ZS_RGB_MESH);
    const zs_model *part = &s.meshes[in->mesh];
    mesh_faces += part->mesh.nfaces;
    for (int32_t f = 0; f < part->mesh.nfaces; f++) {
      int32_t id = part->mesh.face_id[f];
      ck_assert_int_ge(id, 0);
      ck_assert_int_lt(id, src.nsource_faces);
      seen[id] = 1;
      /* the source's face with this id: same object and same corners */
      int32_t g = 0;
      while (g < src.mesh.nfaces && src.mesh.face_id[g] != id) g++;
      while (g < src.mesh.nfaces && src.mesh.face_id[g] == id &&
             src.mesh.face_start[g + 1] - src.mesh.face_start[g] !=
                 part->mesh.face_start[f + 1] - part->mesh.face_start[f])
        g++;
      ck_assert_int_lt(g, src.mesh.nfaces);
      int32_t o = src.face_object[g];
      ck_assert_str_eq(in->name, o >= 0 ? src.object_names[o] : "(none)");
      ck_assert_uint_eq(part->mesh.face_rgb[f], src.mesh.face_rgb[g]);
    }
    /* a part holds only the vertices its faces use */
    for (int32_t v = 0; v < part->mesh.nverts; v++) {
      int used = 0;
      for (int32_t k = 0; k < part->mesh.face_start[part->mesh.nfaces] && !used; k++)
        used = part->mesh.face_vert[k] == v;
      ck_assert_msg(used, "%s: vertex %d of %s unused", rel, (int)v, in->name);
    }
  }
  for (int32_t id = 0; id < src.nsource_faces; id++) ck_assert_int_eq(seen[id], 1);
  ck_assert_int_eq(mesh_faces, src.mesh.nfaces);
  free(seen);
  zs_scene_free(&s);
  zs_model_free(&src);
}

START_TEST(container_from_model) {
  check_from_model("tests/data/scenes/cyclic.obj");
  check_from_model("tests/data/scenes/sphere_ell.obj");
  check_from_model("tests/data/scenes/interpenetrate.obj");

  /* cyclic.obj: three bars, one face each, ids 0, 1, 2 */
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_obj_load(zs_test_src("tests/data/scenes/cyclic.obj"), &m, &err), ZS_OK);
  zs_scene s;
  zs_scene_init(&s);
  ck_assert_int_eq(zs_scene_from_model(&s, &m, &err), ZS_OK);
  ck_assert_int_eq(zs_scene_finish(&s, &err), ZS_OK);
  ck_assert_int_eq(s.ninst, 3);
  for (int i = 0; i < 3; i++) {
    char name[16];
    snprintf(name, sizeof name, "bar_%d", i);
    ck_assert_str_eq(s.inst[i].name, name);
    ck_assert_int_eq(s.meshes[s.inst[i].mesh].mesh.nverts, 4);
    ck_assert_int_eq(s.meshes[s.inst[i].mesh].mesh.face_id[0], i);
  }
  /* an instance added later takes ids after the file's */
  zs_model box;
  zs_model_init(&box);
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  ck_assert_int_eq(zs_gen_box(&box, lo, hi, NULL, 0, -1), ZS_OK);
  int32_t bm = zs_scene_add_mesh(&s, &box);
  ck_assert_int_eq(zs_scene_add_instance(&s, bm, NULL, ZS_RGB_MESH, "box"), 3);
  ck_assert_int_eq(zs_scene_finish(&s, &err), ZS_OK);
  ck_assert_uint_eq(s.inst[3].id_base, 3);
  ck_assert_uint_eq(s.inst[2].id_base, 0);
  zs_scene_free(&s);

  /* faces of no object, before and after an object */
  zs_model_init(&m);
  for (int v = 0; v < 6; v++) zs_model_add_vertex(&m, v, v * v, 1);
  int32_t obj = zs_model_object(&m, "thing");
  int32_t a[3] = {0, 1, 2}, b[3] = {3, 4, 5}, c[3] = {0, 2, 4};
  zs_model_add_polygon(&m, a, 3, 1, -1);
  zs_model_add_polygon(&m, b, 3, 2, obj);
  zs_model_add_polygon(&m, c, 3, 3, -1);
  zs_scene_init(&s);
  ck_assert_int_eq(zs_scene_from_model(&s, &m, &err), ZS_OK);
  ck_assert_int_eq(s.ninst, 2);
  ck_assert_str_eq(s.inst[0].name, "thing");
  ck_assert_str_eq(s.inst[1].name, "(none)");
  const zs_model *none = &s.meshes[s.inst[1].mesh];
  ck_assert_int_eq(none->nsource_faces, 2);
  ck_assert_int_eq(none->mesh.face_id[0], 0);
  ck_assert_int_eq(none->mesh.face_id[1], 2);
  ck_assert_int_eq(none->mesh.nverts, 4); /* 0, 1, 2 and 4 */
  zs_scene_free(&s);
}
END_TEST

/* ---- motion ------------------------------------------------------------ */

/* A unit cube (side 1, centred on the origin) placed by model, moving along
 * axis at speed, in bounds x in [-2, 2], y and z in [-10, 10]. */
static void moving_cube(zs_scene *s, const double model[16], double ax, double ay, double az,
                        double speed) {
  zs_scene_init(s);
  zs_model box;
  zs_model_init(&box);
  const double lo[3] = {-0.5, -0.5, -0.5}, hi[3] = {0.5, 0.5, 0.5};
  ck_assert_int_eq(zs_gen_box(&box, lo, hi, NULL, 0x808080, -1), ZS_OK);
  ck_assert_int_eq(zs_scene_add_mesh(s, &box), 0);
  ck_assert_int_eq(zs_scene_add_instance(s, 0, model, ZS_RGB_MESH, "cube"), 0);
  s->inst[0].motion = (zs_motion){1, {ax, ay, az}, speed};
  s->has_bounds = 1;
  const double blo[3] = {-2, -10, -10}, bhi[3] = {2, 10, 10};
  memcpy(s->lo, blo, sizeof blo);
  memcpy(s->hi, bhi, sizeof bhi);
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_scene_finish(s, &err), ZS_OK);
}

START_TEST(motion_bounce_exact) {
  /* Steps of 1/4 are exact: the cube's right side reaches x = 2 after 6
   * frames, turns back, reaches x = -2 with its left side 12 frames later,
   * and is back home after 24 frames, to the bit. */
  zs_scene s;
  moving_cube(&s, NULL, 1, 0, 0, 0.25);
  double start[16];
  memcpy(start, s.inst[0].model, sizeof start);
  for (int k = 1; k <= 48; k++) {
    zs_scene_advance(&s);
    int q = k % 24;
    double steps = q <= 6 ? q : q <= 18 ? 12 - q : q - 24;
    ck_assert_msg(s.inst[0].model[3] == 0.25 * steps, "frame %d: x %.17g, expected %.17g", k,
                  s.inst[0].model[3], 0.25 * steps);
    ck_assert_double_eq(s.inst[0].lo[0], s.inst[0].model[3] - 0.5);
    ck_assert_double_eq(s.inst[0].hi[0], s.inst[0].model[3] + 0.5);
    ck_assert(s.inst[0].hi[0] <= 2.0 && s.inst[0].lo[0] >= -2.0);
    if (q == 6) ck_assert_double_eq(s.inst[0].hi[0], 2.0); /* touches the wall */
    if (q == 18) ck_assert_double_eq(s.inst[0].lo[0], -2.0);
    if (q == 0) {
      ck_assert(memcmp(s.inst[0].model, start, sizeof start) == 0);
      ck_assert_double_eq(s.inst[0].motion.speed, 0.25);
    }
  }
  zs_scene_free(&s);
}
END_TEST

START_TEST(motion_bounce_inexact) {
  /* Steps of 0.4 do not divide the room: the cube goes to the wall and back
   * within a frame, never leaves the bounds, and turns at each wall. */
  zs_scene s, again;
  moving_cube(&s, NULL, 1, 0, 0, 0.4);
  moving_cube(&again, NULL, 1, 0, 0, 0.4);
  double prev = s.inst[0].model[3];
  int turns = 0;
  double max_x = 0, min_x = 0;
  for (int k = 1; k <= 1000; k++) {
    double before_speed = s.inst[0].motion.speed;
    zs_scene_advance(&s);
    zs_scene_advance(&again);
    double x = s.inst[0].model[3];
    ck_assert(s.inst[0].hi[0] <= 2.0 + 1e-12 && s.inst[0].lo[0] >= -2.0 - 1e-12);
    ck_assert(fabs(fabs(x - prev) - 0.4) < 1e-12 || s.inst[0].motion.speed != before_speed);
    if (s.inst[0].motion.speed != before_speed) {
      turns++;
      /* the distance travelled, to the wall and back, is one step */
      double wall = before_speed > 0 ? 1.5 : -1.5;
      ck_assert(fabs(fabs(wall - prev) + fabs(wall - x) - 0.4) < 1e-9);
    }
    if (x > max_x) max_x = x;
    if (x < min_x) min_x = x;
    prev = x;
    /* the y and z rows are untouched */
    ck_assert_double_eq(s.inst[0].model[7], 0.0);
    ck_assert_double_eq(s.inst[0].model[11], 0.0);
  }
  ck_assert_int_ge(turns, 2 * (int)(1000 * 0.4 / 6.0) - 1);
  ck_assert(max_x > 1.5 - 0.4 && min_x < -1.5 + 0.4);
  ck_assert_uint_eq(scene_hash(&s), scene_hash(&again)); /* the same bytes */
  zs_scene_free(&s);
  zs_scene_free(&again);
}
END_TEST

START_TEST(motion_local_axis) {
  /* Local +x turned 90 degrees about +y is world -z; speed is in world
   * units, whatever the scale. */
  double rot[16], sc[16], m[16];
  zs_mat_rotate(rot, 90, 0, 1, 0);
  zs_mat_scale(sc, 3, 1, 1);
  zs_mat_mul(m, rot, sc);
  zs_scene s;
  moving_cube(&s, m, 1, 0, 0, 0.5);
  zs_scene_advance(&s);
  ck_assert_double_eq(s.inst[0].model[3], 0.0);
  ck_assert_double_eq(s.inst[0].model[7], 0.0);
  ck_assert_double_eq(s.inst[0].model[11], -0.5);
  zs_scene_free(&s);

  /* a static instance does not move */
  moving_cube(&s, NULL, 1, 0, 0, 0.5);
  s.inst[0].motion.moving = 0;
  uint64_t h = scene_hash(&s);
  for (int k = 0; k < 10; k++) zs_scene_advance(&s);
  ck_assert_uint_eq(scene_hash(&s), h);
  zs_scene_free(&s);
}
END_TEST

START_TEST(motion_scene_file_deterministic) {
  /* The same scene file advanced the same number of frames gives the same
   * bytes; every ball stays inside the bounds. */
  zs_scene a, b;
  load_scene("scene/examples/moving.json", &a);
  load_scene("scene/examples/moving.json", &b);
  ck_assert_uint_eq(scene_hash(&a), scene_hash(&b));
  uint64_t start = scene_hash(&a);
  for (int k = 0; k < 500; k++) {
    zs_scene_advance(&a);
    zs_scene_advance(&b);
    for (int32_t i = 0; i < a.ninst; i++)
      for (int c = 0; c < 3; c++) {
        ck_assert(a.inst[i].lo[c] >= a.lo[c] - 1e-9);
        ck_assert(a.inst[i].hi[c] <= a.hi[c] + 1e-9);
      }
  }
  ck_assert_uint_ne(scene_hash(&a), start);
  ck_assert_uint_eq(scene_hash(&a), scene_hash(&b));
  zs_scene_free(&a);
  zs_scene_free(&b);
}
END_TEST

/* ---- keyframed paths ---------------------------------------------------- */

static const zs_keyframe test_keys[] = {
    {0, {0, 0, 10}, {0, 0, 0}, {0, 1, 0}},
    {10, {10, 0, 0}, {0, 1, 0}, {0, 1, 0}},
    {40, {0, 5, -10}, {1, 0, 0}, {0, 1, 0.2}},
    {50, {-10, 0, 0}, {0, 0, 0}, {0, 1, 0}},
};
enum { NTEST_KEYS = sizeof test_keys / sizeof test_keys[0] };

static void keyed_scene(zs_scene *s) {
  zs_scene_init(s);
  s->path.keys = malloc(sizeof test_keys);
  memcpy(s->path.keys, test_keys, sizeof test_keys);
  s->path.nkeys = NTEST_KEYS;
  s->path.frames = 60;
  s->camera.fovy = 30;
}

START_TEST(path_through_keys) {
  zs_scene s;
  keyed_scene(&s);
  for (int k = 0; k < NTEST_KEYS; k++) {
    zs_camera c;
    zs_path_camera(&s, test_keys[k].frame, &c);
    ck_assert(c.has_eye && c.has_target && c.has_up);
    ck_assert_double_eq(c.fovy, 30); /* the rest from the scene's camera */
    ck_assert_double_le(dist3(c.eye, test_keys[k].eye), 1e-12);
    ck_assert_double_le(dist3(c.target, test_keys[k].target), 1e-12);
  }
  /* held before the first key and after the last */
  zs_camera c;
  zs_path_camera(&s, 59, &c);
  ck_assert_double_le(dist3(c.eye, test_keys[3].eye), 1e-12);
  zs_path_camera(&s, -5, &c);
  ck_assert_double_le(dist3(c.eye, test_keys[0].eye), 1e-12);
  /* up: unit, orthogonal to the view, on the side of the keys' up */
  for (int f = 0; f < 60; f++) {
    zs_path_camera(&s, f, &c);
    double d[3];
    sub3(c.target, c.eye, d);
    ck_assert_double_le(fabs(len3(c.up) - 1.0), 1e-12);
    ck_assert_double_le(fabs(dot3(c.up, d)) / len3(d), 1e-12);
    ck_assert_double_gt(c.up[1], 0.5);
  }
  /* no keys: the scene's camera as it is */
  zs_path_free(&s.path);
  s.camera.eye[0] = 42;
  zs_path_camera(&s, 3, &c);
  ck_assert_double_eq(c.eye[0], 42);
  ck_assert_int_eq(c.has_eye, 0);
  zs_scene_free(&s);
}
END_TEST

START_TEST(path_is_c1) {
  /* At each inner key the velocity from the left equals the velocity from
   * the right (finite differences), and equals the Catmull-Rom tangent,
   * although the chords' slopes on the two sides differ a lot (a
   * piecewise-linear path would jump). */
  zs_scene s;
  keyed_scene(&s);
  const double h = 1e-4;
  for (int k = 1; k + 1 < NTEST_KEYS; k++) {
    const zs_keyframe *a = &test_keys[k - 1], *b = &test_keys[k], *c = &test_keys[k + 1];
    double f = b->frame;
    zs_keyframe lo, mid, hi;
    zs_path_eval(&s.path, f - h, &lo);
    zs_path_eval(&s.path, f, &mid);
    zs_path_eval(&s.path, f + h, &hi);
    for (int which = 0; which < 2; which++) {
      const double *pl = which ? lo.target : lo.eye, *pm = which ? mid.target : mid.eye;
      const double *ph = which ? hi.target : hi.eye;
      const double *va = which ? a->target : a->eye, *vb = which ? b->target : b->eye;
      const double *vc = which ? c->target : c->eye;
      double jump = 0.0;
      for (int i = 0; i < 3; i++) {
        double left = (pm[i] - pl[i]) / h, right = (ph[i] - pm[i]) / h;
        double tangent = (vc[i] - va[i]) / (c->frame - a->frame);
        ck_assert_msg(fabs(left - right) < 1e-3, "key %d: velocity %g from the left, %g right", k,
                      left, right);
        ck_assert_msg(fabs(left - tangent) < 1e-3, "key %d: velocity %g, tangent %g", k, left,
                      tangent);
        double chord_l = (vb[i] - va[i]) / (b->frame - a->frame);
        double chord_r = (vc[i] - vb[i]) / (c->frame - b->frame);
        if (fabs(chord_l - chord_r) > jump) jump = fabs(chord_l - chord_r);
      }
      ck_assert_double_gt(jump, 0.1);
    }
  }
  /* and between keys, no frame-to-frame step is far from its neighbours */
  for (int f = 1; f + 1 < 50; f++) {
    zs_keyframe p0, p1, p2;
    zs_path_eval(&s.path, f - 1, &p0);
    zs_path_eval(&s.path, f, &p1);
    zs_path_eval(&s.path, f + 1, &p2);
    for (int i = 0; i < 3; i++)
      ck_assert_double_lt(fabs(p2.eye[i] - 2 * p1.eye[i] + p0.eye[i]), 0.5);
  }
  zs_scene_free(&s);
}
END_TEST

/* ---- named paths -------------------------------------------------------- */

static const zs_camera base_camera = {.eye = {3, 4, 10},
                                      .target = {1, 0, -2},
                                      .up = {0, 1, 0},
                                      .fovy = 45,
                                      .znear = 0.1,
                                      .zfar = 100,
                                      .has_eye = 1,
                                      .has_target = 1,
                                      .has_up = 1,
                                      .has_near = 1,
                                      .has_far = 1};

static void named(const char *name, int32_t frames, zs_path *p) {
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_path_named(name, &base_camera, frames, p, &err) == ZS_OK, "%s", err.msg);
  ck_assert_int_eq(p->nkeys, frames);
  ck_assert_int_eq(p->frames, frames);
  for (int32_t f = 0; f < frames; f++) ck_assert_int_eq(p->keys[f].frame, f);
}

static double base_dist(void) { return dist3(base_camera.eye, base_camera.target); }

START_TEST(named_roll) {
  zs_path p;
  named("roll", 200, &p);
  double fwd[3];
  sub3(base_camera.target, base_camera.eye, fwd);
  for (int f = 0; f < 200; f++) {
    const zs_keyframe *k = &p.keys[f];
    ck_assert(memcmp(k->eye, base_camera.eye, sizeof k->eye) == 0);
    ck_assert(memcmp(k->target, base_camera.target, sizeof k->target) == 0);
    ck_assert_double_le(fabs(len3(k->up) - 1), 1e-12);
    ck_assert_double_le(fabs(dot3(k->up, fwd)), 1e-12);
    if (f == 0) continue;
    const double *prev = p.keys[f - 1].up;
    ck_assert_msg(fabs(angle_deg(prev, k->up) - 2.0) < 1e-9, "frame %d: %.12f degrees", f,
                  angle_deg(prev, k->up));
    double c[3];
    cross3(prev, k->up, c);
    ck_assert_double_gt(dot3(c, fwd), 0); /* right-handed about the view */
  }
  /* frame 45 is a quarter turn: up is then the base's right */
  double right[3];
  cross3(fwd, base_camera.up, right);
  ck_assert_double_lt(angle_deg(p.keys[45].up, right), 1e-9);
  zs_path_free(&p);
  ck_assert_ptr_null(p.keys);
  ck_assert_int_eq(p.nkeys, 0);
}
END_TEST

START_TEST(named_translate) {
  zs_path p;
  named("translate", 100, &p);
  double d0[3], up0[3];
  sub3(p.keys[0].target, p.keys[0].eye, d0);
  memcpy(up0, p.keys[0].up, sizeof up0);
  for (int f = 1; f < 100; f++) {
    const zs_keyframe *k = &p.keys[f];
    double d[3], step[3];
    sub3(k->target, k->eye, d);
    ck_assert_double_le(dist3(d, d0), 1e-12 * len3(d0)); /* the view direction is kept */
    sub3(k->eye, p.keys[f - 1].eye, step);
    ck_assert_double_le(fabs(len3(step) - 0.005 * base_dist()), 1e-12);
    ck_assert_double_le(fabs(dot3(step, d0)), 1e-12);  /* sideways */
    ck_assert_double_le(fabs(dot3(step, up0)), 1e-12); /* horizontal in the view */
    ck_assert(memcmp(k->up, up0, sizeof up0) == 0);
  }
  zs_path_free(&p);
}
END_TEST

START_TEST(named_yaw) {
  zs_path p;
  named("yaw", 100, &p);
  const double *up = p.keys[0].up;
  for (int f = 1; f < 100; f++) {
    const zs_keyframe *k = &p.keys[f];
    ck_assert(memcmp(k->eye, base_camera.eye, sizeof k->eye) == 0);
    double d[3], d_prev[3];
    sub3(k->target, k->eye, d);
    sub3(p.keys[f - 1].target, p.keys[f - 1].eye, d_prev);
    ck_assert_double_le(fabs(len3(d) - base_dist()), 1e-9);
    ck_assert_msg(fabs(angle_deg(d_prev, d) - 0.5) < 1e-9, "frame %d: %.12f", f,
                  angle_deg(d_prev, d));
    double c[3];
    cross3(d_prev, d, c);
    ck_assert_double_lt(angle_deg(c, up), 1e-6); /* about up, to the left */
    ck_assert(memcmp(k->up, up, 3 * sizeof *up) == 0);
  }
  zs_path_free(&p);
}
END_TEST

START_TEST(named_fast) {
  zs_path p;
  named("fast", 64, &p);
  double d0[3];
  sub3(p.keys[0].target, p.keys[0].eye, d0);
  for (int f = 1; f < 64; f++) {
    const zs_keyframe *k = &p.keys[f];
    ck_assert_double_le(fabs(dist3(k->eye, p.keys[f - 1].eye) - ZS_PATH_FAST_STEP * base_dist()),
                        1e-12 * base_dist());
    ck_assert_double_le(dist3(k->eye, base_camera.eye), 2 * ZS_PATH_FAST_STEP * base_dist() + 1e-12);
    double d[3];
    sub3(k->target, k->eye, d);
    ck_assert_double_le(dist3(d, d0), 1e-12 * len3(d0));
  }
  ck_assert_double_le(dist3(p.keys[8].eye, base_camera.eye), 1e-12); /* period 8 */
  zs_path_free(&p);

  named("static", 5, &p);
  for (int f = 0; f < 5; f++) {
    ck_assert(memcmp(p.keys[f].eye, base_camera.eye, sizeof base_camera.eye) == 0);
    ck_assert(memcmp(p.keys[f].target, base_camera.target, sizeof base_camera.target) == 0);
  }
  zs_path_free(&p);
}
END_TEST

START_TEST(named_errors) {
  zs_path p;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_path_named("spin", &base_camera, 10, &p, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "unknown named path 'spin' (static, translate, roll, yaw, fast)");
  ck_assert_ptr_null(p.keys);
  zs_error_clear(&err);
  ck_assert_int_eq(zs_path_named("roll", &base_camera, 0, &p, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "frames 0: must be 1 to 1000000");
  zs_camera c = base_camera;
  memcpy(c.target, c.eye, sizeof c.eye);
  zs_error_clear(&err);
  ck_assert_int_eq(zs_path_named("roll", &c, 10, &p, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "eye and target are the same point");
  c = base_camera;
  c.eye[0] = c.target[0];
  c.eye[2] = c.target[2]; /* looking straight down, up +y */
  zs_error_clear(&err);
  ck_assert_int_eq(zs_path_named("yaw", &c, 10, &p, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "up 0,1,0: zero or parallel to the view direction");
}
END_TEST

START_TEST(path_format_line) {
  zs_camera c = base_camera;
  c.eye[1] = -1e-9; /* prints as zero, without a sign */
  c.up[2] = -0.25;
  char buf[512];
  int n = zs_path_format(buf, sizeof buf, 7, &c);
  ck_assert_str_eq(buf,
                   "frame 7 eye 3.000000,0.000000,10.000000 target 1.000000,0.000000,-2.000000 "
                   "up 0.000000,1.000000,-0.250000\n");
  ck_assert_int_eq(n, (int)strlen(buf));
}
END_TEST

/* ---- scene files: the examples ------------------------------------------ */

static int compare_names(const void *a, const void *b) { return strcmp(a, b); }

/* The .json files of a directory below the source tree, sorted. */
static int list_json(const char *rel, char names[][256], int cap) {
  DIR *d = opendir(zs_test_src(rel));
  ck_assert_ptr_nonnull(d);
  int n = 0;
  struct dirent *e;
  while ((e = readdir(d))) {
    size_t len = strlen(e->d_name);
    if (len < 6 || strcmp(e->d_name + len - 5, ".json") != 0 || len >= 256) continue;
    ck_assert_int_lt(n, cap);
    snprintf(names[n++], 256, "%s", e->d_name);
  }
  closedir(d);
  qsort(names, (size_t)n, 256, compare_names);
  return n;
}

START_TEST(examples_load_and_render) {
  char names[32][256];
  int n = list_json("scene/examples", names, 32);
  ck_assert_int_ge(n, 4);
  for (int i = 0; i < n; i++) {
    char rel[512];
    snprintf(rel, sizeof rel, "scene/examples/%.255s", names[i]);
    zs_scene s, again;
    load_scene(rel, &s);
    load_scene(rel, &again);
    ck_assert_msg(scene_hash(&s) == scene_hash(&again), "%s: two loads differ", rel);
    ck_assert_int_gt(s.ninst, 0);
    ck_assert_msg(s.width > 0 && s.height > 0, "%s: no size", rel);
    int32_t last = s.path.frames > 0 ? s.path.frames - 1 : 0;
    for (int which = 0; which < 2; which++) {
      int32_t f = which ? last : 0;
      if (which) {
        /* moving instances move with the frames */
        for (int32_t k = 0; k < f; k++) zs_scene_advance(&s);
        for (int32_t k = 0; k < f; k++) zs_scene_advance(&again);
      }
      int64_t covered;
      uint64_t hz = render_scene(&s, f, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, &covered);
      uint64_t hs = render_scene(&again, f, ZS_ALGO_SCANLINE, ZS_SHADE_ID, NULL);
      ck_assert_msg(hz == hs, "%s frame %d: zbuffer and scanline differ", rel, (int)f);
      ck_assert_msg(covered > (int64_t)s.width * s.height / 10,
                    "%s frame %d: only %lld pixels covered", rel, (int)f, (long long)covered);
      uint64_t flat = render_scene(&s, f, ZS_ALGO_ZBUFFER, ZS_SHADE_FLAT, NULL);
      ck_assert_uint_eq(flat, render_scene(&again, f, ZS_ALGO_ZBUFFER, ZS_SHADE_FLAT, NULL));
    }
    zs_scene_free(&s);
    zs_scene_free(&again);
  }
}
END_TEST

START_TEST(example_in_header_is_a_file) {
  /* load_scenefile.h's example is scene/examples/table.json, line for line */
  size_t hlen, flen;
  char *h = slurp_src("scene/load_scenefile.h", &hlen);
  char *f = slurp_src("scene/examples/table.json", &flen);
  char *body = malloc(hlen + 1), *at = strstr(h, "EXAMPLE (scene/examples/table.json)\n");
  ck_assert_ptr_nonnull(at);
  size_t n = 0;
  for (char *line = strchr(at, '\n') + 1; strncmp(line, " *   ", 5) == 0;
       line = strchr(line, '\n') + 1) {
    size_t k = (size_t)(strchr(line, '\n') + 1 - (line + 5));
    memcpy(body + n, line + 5, k);
    n += k;
  }
  ck_assert_uint_eq(n, flen);
  ck_assert(memcmp(body, f, n) == 0);
  free(body);
  free(h);
  free(f);
}
END_TEST

START_TEST(examples_content) {
  zs_scene s;
  load_scene("scene/examples/room.json", &s);
  ck_assert_int_eq(s.nmeshes, 3);
  ck_assert_int_eq(s.ninst, 13);
  ck_assert_str_eq(s.inst[8].name, "teapot");
  ck_assert_uint_eq(s.inst[8].rgb, 0xCC4D33); /* [0.8, 0.3, 0.2] */
  ck_assert_uint_eq(s.inst[0].rgb, 0x9C968C);
  ck_assert_int_eq(s.meshes[2].nsource_faces, 16 * 12); /* sphere slices x stacks */
  ck_assert_int_eq(s.path.nkeys, 0);
  ck_assert(s.camera.has_eye && s.camera.has_target && !s.camera.has_near);
  ck_assert_double_eq(s.camera.fovy, 50);
  zs_scene_free(&s);

  load_scene("scene/examples/objects.json", &s);
  ck_assert_int_eq(s.meshes[0].nsource_faces, 8);  /* gem.obj */
  ck_assert_int_eq(s.meshes[1].nsource_faces, 10); /* arch.obj: 2 octagons, 8 sides */
  ck_assert_str_eq(s.inst[0].name, "ground_0");    /* a default name */
  ck_assert_uint_eq(s.inst[1].rgb, ZS_RGB_MESH);
  ck_assert_uint_eq(s.meshes[1].mesh.face_rgb[0], 0xB8A894); /* arch.mtl: 0.72 0.66 0.58 */
  ck_assert_int_eq(s.path.nkeys, 90);
  /* a roll: the eye stays where the camera says */
  for (int f = 0; f < 90; f++)
    ck_assert(memcmp(s.path.keys[f].eye, s.camera.eye, sizeof s.camera.eye) == 0);
  zs_scene_free(&s);

  load_scene("scene/examples/moving.json", &s);
  int moving = 0;
  for (int32_t i = 0; i < s.ninst; i++) moving += s.inst[i].motion.moving;
  ck_assert_int_eq(moving, 3);
  ck_assert(s.has_bounds);
  ck_assert_int_eq(s.path.nkeys, 4);
  ck_assert_int_eq(s.path.frames, 120);
  ck_assert_double_eq(s.path.keys[0].up[1], 1); /* the camera's default up */
  zs_scene_free(&s);

  zs_scene a;
  load_scene("scene/examples/field.json", &s);
  load_scene("scene/examples/field.json", &a);
  ck_assert_int_eq(s.ninst, 101); /* 100 teapots and the ground */
  ck_assert_int_eq(s.path.frames, 60);
  ck_assert_uint_eq(scene_hash(&s), scene_hash(&a)); /* the same seed, the same bytes */
  /* yaw: the eye stays */
  for (int f = 1; f < 60; f++)
    ck_assert(memcmp(s.path.keys[f].eye, s.path.keys[0].eye, sizeof s.path.keys[0].eye) == 0);
  zs_scene_free(&s);
  zs_scene_free(&a);
}
END_TEST

/* ---- scene files: the format --------------------------------------------- */

#define BOX_MESH "\"meshes\": [{\"name\": \"box\", \"generator\": \"box\"}]"

START_TEST(format_transform) {
  zs_scene s;
  parse_scene("{" BOX_MESH ", \"instances\": [{\"mesh\": \"box\", \"transform\": "
              "{\"translate\": [1, 2, 3], \"rotate\": [90, 0, 0, 1], \"scale\": [2, 3, 4]}}]}",
              &s);
  /* T * Rz(90) * S: x -> 2y, y -> -3x, z -> 4z, then + (1, 2, 3) */
  const double expect[16] = {0, -3, 0, 1, 2, 0, 0, 2, 0, 0, 4, 3, 0, 0, 0, 1};
  for (int k = 0; k < 16; k++) ck_assert_double_eq(s.inst[0].model[k], expect[k]);
  ck_assert_str_eq(s.inst[0].name, "box_0");
  zs_scene_free(&s);

  /* a list of rotations, the first applied first: x -> y (about z), then
   * y -> z (about x) */
  parse_scene("{" BOX_MESH ", \"instances\": [{\"mesh\": \"box\", \"transform\": "
              "{\"rotate\": [[90, 0, 0, 1], [90, 1, 0, 0]], \"scale\": 2}}]}",
              &s);
  ck_assert_double_eq(s.inst[0].model[0], 0);
  ck_assert_double_eq(s.inst[0].model[4], 0);
  ck_assert_double_eq(s.inst[0].model[8], 2);
  zs_scene_free(&s);

  parse_scene("{" BOX_MESH ", \"instances\": [{\"mesh\": \"box\", \"name\": \"m\", \"matrix\": "
              "[1, 0, 0, 5, 0, 2, 0, 6, 0, 0, -1, 7, 0, 0, 0, 1], \"color\": \"#FF8000\"}, "
              "{\"mesh\": \"box\", \"color\": [1, 0.5, 0], "
              "\"motion\": {\"axis\": [0, 0, 2], \"speed\": -0.5}}]}",
              &s);
  ck_assert_double_eq(s.inst[0].model[3], 5);
  ck_assert_double_eq(s.inst[0].model[5], 2);
  ck_assert_double_eq(s.inst[0].model[10], -1);
  ck_assert_uint_eq(s.inst[0].rgb, 0xFF8000);
  ck_assert_uint_eq(s.inst[1].rgb, 0xFF8000);
  ck_assert_str_eq(s.inst[1].name, "box_1");
  ck_assert_int_eq(s.inst[0].motion.moving, 0);
  ck_assert_int_eq(s.inst[1].motion.moving, 1);
  ck_assert_double_eq(s.inst[1].motion.axis[2], 2);
  ck_assert_double_eq(s.inst[1].motion.speed, -0.5);
  zs_scene_free(&s);
}
END_TEST

START_TEST(format_camera_path_generators) {
  zs_scene s;
  parse_scene("{\"meshes\": [{\"name\": \"b\", \"generator\": \"sphere\", \"slices\": 8, "
              "\"stacks\": 6}, {\"name\": \"t\", \"generator\": \"torus\", \"major\": 1.5, "
              "\"minor\": 0.25}, {\"name\": \"g\", \"file\": \"gem.obj\"}], "
              "\"instances\": [{\"mesh\": \"b\"}, {\"mesh\": \"t\"}, {\"mesh\": \"g\"}], "
              "\"camera\": {\"eye\": [0, 1, 9], \"target\": [0, 0, 0], \"up\": [0, 0, -1], "
              "\"fovy\": 60, \"near\": 0.5, \"far\": 50, \"size\": [640, 360]}, "
              "\"path\": {\"frames\": 20, \"keys\": [{\"frame\": 5, \"eye\": [0, 1, 9], "
              "\"target\": [0, 0, 0]}]}, \"bounds\": {\"min\": [-9, -9, -9], \"max\": [9, 9, 9]}}",
              &s);
  ck_assert_int_eq(s.meshes[0].nsource_faces, 48);
  ck_assert_int_gt(s.meshes[1].nsource_faces, 0);
  ck_assert_int_eq(s.meshes[2].nsource_faces, 8); /* relative to dir */
  ck_assert(s.camera.has_eye && s.camera.has_target && s.camera.has_up);
  ck_assert(s.camera.has_near && s.camera.has_far);
  ck_assert_double_eq(s.camera.fovy, 60);
  ck_assert_double_eq(s.camera.znear, 0.5);
  ck_assert_double_eq(s.camera.zfar, 50);
  ck_assert_int_eq(s.width, 640);
  ck_assert_int_eq(s.height, 360);
  ck_assert_int_eq(s.path.nkeys, 1);
  ck_assert_int_eq(s.path.frames, 20);
  ck_assert_double_eq(s.path.keys[0].up[2], -1); /* the camera's up */
  ck_assert(s.has_bounds);
  ck_assert_double_eq(s.lo[0], -9);
  ck_assert_uint_eq(s.inst[1].id_base, 48);
  zs_scene_free(&s);

  /* a generated scene whose camera and path the file replaces */
  parse_scene(
      "{\"generator\": \"cubes?n=2\", \"camera\": {\"eye\": [5, 6, 7], \"size\": [100, 50]},"
      " \"path\": {\"frames\": 3, \"named\": \"translate\"}}",
      &s);
  ck_assert_int_eq(s.ninst, 8);
  ck_assert_double_eq(s.camera.eye[1], 6);
  ck_assert_int_eq(s.width, 100);
  ck_assert_int_eq(s.path.nkeys, 3);
  ck_assert_double_eq(s.path.keys[0].eye[2], 7);
  zs_scene_free(&s);
}
END_TEST

/* ---- scene files: the broken corpus ---------------------------------------- */

typedef struct bad_scene {
  const char *file;   /* in tests/data/bad_scene */
  const char *expect; /* what follows the file's path; '@' stands for its directory */
} bad_scene;

static const bad_scene bad_scenes[] = {
    {"bad_color.json", ": instances[0].color: expected \"#rrggbb\", got \"#12345g\""},
    {"bounds_inverted.json", ": bounds.max: below min on the y axis"},
    {"broken_model.json", ": meshes[0].file: @/huge_count.off: "},
    {"broken_obj.json", ": meshes[0].file: @/broken.obj:4: vertex index 3 out of range"},
    {"color_range.json", ": instances[0].color[0]: 1.2 is outside 0 .. 1"},
    {"control_key.json", ": instances[0].col our: unknown key"},
    {"deep.json", ":1:1016: invalid JSON"},
    {"description_type.json", ": description: expected string"},
    {"duplicate_instance.json", ": instances[1].name: duplicate instance name 'a'"},
    {"duplicate_key.json", ": instances[0].mesh: duplicate key"},
    {"duplicate_mesh.json", ": meshes[1].name: duplicate mesh name 'box'"},
    {"empty.json", ":1:1: invalid JSON"},
    {"empty_instances.json", ": instances: expected at least one instance"},
    {"eye_target.json", ": camera.target: the same point as the eye"},
    {"fovy.json", ": camera.fovy: 180: must be between 0 and 180 degrees"},
    {"generator_bool.json", ": meshes[0].smooth: expected number or string"},
    {"generator_keys.json", ": meshes[0]: more than 64 keys"},
    {"generator_long.json", ": meshes[0].generator: generator spec too long"},
    {"generator_param.json", ": meshes[0].generator: sphere?slices=many: "},
    {"generator_unknown.json", ": meshes[0].generator: dodecahedron: "},
    {"instances_object.json", ": instances: expected array"},
    {"key_missing_eye.json", ": path.keys[0]: missing \"eye\""},
    {"key_range.json", ": path.keys[1].frame: 50 is outside 0 .. 9"},
    {"keys_order.json", ": path.keys[2].frame: 10 is not after the previous key's frame 20"},
    {"light_color_negative.json", ": lights[0].color: expected finite values >= 0"},
    {"light_direction_zero.json", ": lights[0].direction: expected a finite, non-zero vector"},
    {"light_key.json", ": lights[0].colour: unknown key"},
    {"light_point_shadow.json", ": lights[0].shadow: only directional and spot lights cast shadows"},
    {"light_spot_angles.json",
     ": lights[0].inner: a spot's angles need 0 < inner_deg <= outer_deg < 90, got 40 and 30"},
    {"light_type.json",
     ": lights[0].type: expected one of directional, point, spot, ambient, got \"laser\""},
    {"lights_many.json", ": lights: 17 lights: at most 16"},
    {"material_alpha.json", ": meshes[0].material.alpha: 1.5 is outside 0 .. 1"},
    {"material_texture_missing.json",
     ": meshes[0].material.texture: @/nothing.png: cannot open: No such file or directory"},
    {"material_wrap.json",
     ": meshes[0].material.wrap: expected one of repeat, clamp, mirror, got \"tile\""},
    {"matrix_length.json", ": instances[0].matrix: expected 16 numbers, got 15"},
    {"matrix_projective.json", ": instances[0].matrix: the last row must be 0 0 0 1"},
    {"matrix_singular.json", ": instances[0].matrix: singular matrix"},
    {"mesh_both.json", ": meshes[0].generator: cannot be combined with \"file\""},
    {"mesh_no_faces.json", ": meshes[0].file: @/nofaces.obj: no faces"},
    {"missing_file.json",
     ": meshes[0].file: @/nothere.obj: cannot open: No such file or directory"},
    {"motion_axis.json", ": instances[0].motion.axis: must not be zero"},
    {"named_unknown.json", ": path.named: unknown named path 'spin'"},
    {"nan.json", ": camera.eye[1]: not a finite number"},
    {"near_far.json", ": camera.far: 1: must be greater than near (10)"},
    {"no_instances.json", ": missing \"instances\" (or a \"generator\")"},
    {"nul.json", ":1:32: NUL byte"},
    {"path_frames.json", ": path.frames: 0 is outside 1 .. 1000000"},
    {"rotate_axis.json", ": instances[0].transform.rotate: rotation axis must not be zero"},
    {"rotate_list.json", ": instances[0].transform.rotate[1]: expected 4 numbers, got 3"},
    {"scene_generator_mixed.json",
     ": generator: cannot be combined with \"meshes\" or \"instances\""},
    {"scene_generator_unknown.json", ": generator: galaxy?stars=9: "},
    {"size_fraction.json", ": camera.size[0]: expected a whole number, got 320.5"},
    {"size_zero.json", ": camera.size[0]: 0 is outside 1 .. 16384"},
    {"speed_missing.json", ": instances[0].motion: missing \"speed\""},
    {"string_for_array.json", ": camera.eye: expected array of 3 numbers"},
    {"syntax.json", ":3:33: invalid JSON"},
    {"top_array.json", ": expected object"},
    {"top_unknown.json", ": camara: unknown key"},
    {"trailing.json", ":5:1: invalid JSON"},
    {"transform_and_matrix.json", ": instances[0].matrix: cannot be combined with \"transform\""},
    {"unknown_key.json", ": instances[0].colour: unknown key"},
    {"unknown_mesh.json", ": instances[1].mesh: unknown mesh 'teapot'"},
    {"up_parallel.json", ": camera.up: parallel to the view direction"},
    {"wrong_type_nested.json",
     ": instances[1].transform.scale: expected number or array of 3 numbers"},
    {"zero_scale.json", ": instances[0].transform.scale: scale must not be zero"},
};
enum { NBAD_SCENES = sizeof bad_scenes / sizeof bad_scenes[0] };

/* The one-line message err, of a failed load of path, begins with path
 * followed by expect ('@' in expect: the directory of path). */
static void check_message(const char *path, const char *expect, const zs_error *err) {
  char want[4096], dir[2048];
  snprintf(dir, sizeof dir, "%s", path);
  char *slash = strrchr(dir, '/');
  if (slash) *slash = '\0';
  size_t n = (size_t)snprintf(want, sizeof want, "%s", path);
  for (const char *e = expect; *e && n + 1 < sizeof want; e++) {
    if (*e == '@') n += (size_t)snprintf(want + n, sizeof want - n, "%s", dir);
    else want[n++] = *e;
  }
  want[n] = '\0';
  ck_assert_msg(err->code != ZS_OK, "%s: no error code", path);
  ck_assert_msg(strncmp(err->msg, want, strlen(want)) == 0, "message\n  '%s'\nexpected\n  '%s...'",
                err->msg, want);
  ck_assert_msg(strchr(err->msg, '\n') == NULL && strchr(err->msg, '\r') == NULL,
                "not one line: '%s'", err->msg);
}

START_TEST(bad_scene_file) {
  const bad_scene *b = &bad_scenes[_i];
  char rel[512];
  snprintf(rel, sizeof rel, "tests/data/bad_scene/%s", b->file);
  char path[4096];
  snprintf(path, sizeof path, "%s", zs_test_src(rel));
  zs_scene s;
  zs_error err;
  zs_error_clear(&err);
  zs_status st = zs_scenefile_load(path, &s, &err);
  ck_assert_msg(st != ZS_OK, "%s loaded", b->file);
  ck_assert_int_eq(st, err.code);
  check_message(path, b->expect, &err);
  /* the scene is left empty */
  ck_assert_int_eq(s.ninst, 0);
  ck_assert_int_eq(s.nmeshes, 0);
  ck_assert_ptr_null(s.path.keys);
}
END_TEST

START_TEST(bad_scene_corpus_complete) {
  /* every file of the corpus has an expectation, and there are enough */
  char names[128][256];
  int n = list_json("tests/data/bad_scene", names, 128);
  ck_assert_int_ge(n, 20);
  ck_assert_int_eq(n, NBAD_SCENES);
  for (int i = 0; i < n; i++) ck_assert_str_eq(names[i], bad_scenes[i].file);
}
END_TEST

/* Reads a file below the source tree into a malloc'd buffer. */
static char *slurp_src(const char *rel, size_t *len) {
  return (char *)zs_test_slurp(zs_test_src(rel), len);
}

START_TEST(mutated_examples) {
  /* Each example, damaged at seeded random places (a byte replaced by a
   * character that matters to JSON, a range cut out, the end cut off):
   * it loads, or fails with one line naming the file; never a crash (the
   * sanitizer builds run this too).  Digits are never written, so no
   * mutation asks a generator for a huge mesh. */
  static const char marks[] = "{}[],:\" x-.e\\";
  char names[32][256];
  int n = list_json("scene/examples", names, 32), loaded = 0, refused = 0;
  zs_rng rng;
  zs_rng_seed(&rng, 2024);
  for (int i = 0; i < n; i++) {
    char rel[512];
    snprintf(rel, sizeof rel, "scene/examples/%.255s", names[i]);
    size_t len;
    char *text = slurp_src(rel, &len);
    char *copy = malloc(len + 1);
    for (int trial = 0; trial < 150; trial++) {
      memcpy(copy, text, len);
      size_t m = len, at = (size_t)zs_rng_below(&rng, len);
      switch (trial % 3) {
      case 0:
        copy[at] = marks[zs_rng_below(&rng, sizeof marks - 1)];
        break;
      case 1: {
        size_t cut = 1 + (size_t)zs_rng_below(&rng, 40);
        if (at + cut > len) cut = len - at;
        memmove(copy + at, copy + at + cut, len - at - cut);
        m = len - cut;
        break;
      }
      default:
        m = at;
        break;
      }
      zs_scene s;
      zs_error err;
      zs_error_clear(&err);
      if (zs_scenefile_parse(copy, m, "mutant.json", zs_test_src("scene/examples"), &s, &err) ==
          ZS_OK) {
        loaded++;
        zs_scene_free(&s);
      } else {
        refused++;
        ck_assert_msg(strncmp(err.msg, "mutant.json", 11) == 0, "%s", err.msg);
        ck_assert_msg(strchr(err.msg, '\n') == NULL, "not one line: %s", err.msg);
        ck_assert_int_eq(s.ninst, 0);
      }
    }
    free(copy);
    free(text);
  }
  ck_assert_int_gt(refused, 100);
  ck_assert_int_gt(loaded, 0);
}
END_TEST

/* Makes a sparse file of size bytes at path. */
static void sparse_file(const char *path, off_t size) {
  int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ck_assert_int_ge(fd, 0);
  ck_assert_int_eq(ftruncate(fd, size), 0);
  close(fd);
}

START_TEST(bad_scene_sizes_and_io) {
  char dir[4096], big[4200], json[4200], text[512];
  snprintf(dir, sizeof dir, "%s", zs_test_bin("scene-test-big"));
  zs_os_mkdir(dir);
  const off_t over = (off_t)ZS_SCENEFILE_MAX_BYTES + 1;
  zs_scene s;
  zs_error err;

  /* a scene file over the limit is refused before it is read */
  snprintf(json, sizeof json, "%s/huge.json", dir);
  sparse_file(json, over);
  zs_error_clear(&err);
  ck_assert_int_eq(zs_scenefile_load(json, &s, &err), ZS_ERR_LIMIT);
  check_message(json, ": larger than 256 MiB", &err);
  unlink(json);

  /* so is a mesh file over the limit */
  snprintf(big, sizeof big, "%s/huge.obj", dir);
  sparse_file(big, over);
  snprintf(json, sizeof json, "%s/scene.json", dir);
  snprintf(text, sizeof text,
           "{\"meshes\": [{\"name\": \"h\", \"file\": \"huge.obj\"}], \"instances\": [{\"mesh\": "
           "\"h\"}]}");
  FILE *f = fopen(json, "w");
  ck_assert_ptr_nonnull(f);
  fputs(text, f);
  fclose(f);
  zs_error_clear(&err);
  ck_assert_int_eq(zs_scenefile_load(json, &s, &err), ZS_ERR_LIMIT);
  check_message(json, ": meshes[0].file: @/huge.obj: larger than 256 MiB", &err);
  unlink(big);
  unlink(json);
  rmdir(dir);

  /* a scene file that does not exist, a directory */
  zs_error_clear(&err);
  ck_assert_int_eq(zs_scenefile_load("no/such/scene.json", &s, &err), ZS_ERR_IO);
  ck_assert_str_eq(err.msg, "no/such/scene.json: cannot open: No such file or directory");
  zs_error_clear(&err);
  ck_assert_int_eq(zs_scenefile_load(zs_test_src("scene/examples"), &s, &err), ZS_ERR_IO);
  ck_assert(strstr(err.msg, ": not a regular file") != NULL);

  /* text that is not NUL-terminated: only len bytes count */
  const char *t = "{" BOX_MESH ", \"instances\": [{\"mesh\": \"box\"}]} garbage";
  zs_error_clear(&err);
  ck_assert_int_eq(zs_scenefile_parse(t, strlen(t) - 8, "mem", NULL, &s, &err), ZS_OK);
  zs_scene_free(&s);
  zs_error_clear(&err);
  ck_assert_int_eq(zs_scenefile_parse(t, strlen(t), "mem", NULL, &s, &err), ZS_ERR_PARSE);
  ck_assert_str_eq(err.msg, "mem:1:83: invalid JSON"); /* at the g of garbage */
}
END_TEST

/* Writes text to the file at path. */
static void write_text(const char *path, const char *text) {
  FILE *f = fopen(path, "wb");
  ck_assert_msg(f != NULL, "%s", path);
  fputs(text, f);
  ck_assert_int_eq(fclose(f), 0);
}

/* An OBJ's material that cannot be had is drawn grey with a note: a
 * library that is not there (by its mtllib line), a usemtl name that no
 * library read defines. */
START_TEST(obj_missing_materials_noted) {
  char dir[4096], path[4200], want[9000];
  snprintf(dir, sizeof dir, "%s", zs_test_bin("scene-test-nomtl"));
  zs_os_mkdir(dir);
  snprintf(path, sizeof path, "%s/m.mtl", dir);
  write_text(path, "newmtl red\nKd 1 0 0\n");
  snprintf(path, sizeof path, "%s/m.obj", dir);
  write_text(path, "mtllib m.mtl\nmtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\n"
                   "f 1 2 3\nusemtl rde\nf 1 3 2\n");
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_obj_load(path, &m, &err) == ZS_OK, "%s", err.msg);
  snprintf(want, sizeof want,
           "%s:2: mtllib gone.mtl: no such file: its materials drawn grey\n"
           "%s: usemtl rde: no library defines it: drawn grey\n",
           path, path);
  ck_assert_ptr_nonnull(m.notes.text);
  ck_assert_str_eq(m.notes.text, want);
  ck_assert_uint_eq(m.mesh.face_rgb[0], 0xFF0000u);
  zs_model_free(&m);
}
END_TEST

/* A texture that cannot be opened, of a mesh file or of a mesh's own
 * material, is an error; with ZS_SCENEFILE_SKIP_MISSING_TEXTURES (and
 * zs_input_load's ZS_INPUT_SKIP_MISSING_TEXTURES) the material is drawn
 * without it and the scene's notes hold each error with ": drawn without
 * it", in the order of the meshes.  A corrupt image stays an error. */
START_TEST(scenefile_missing_textures_noted) {
  char dir[4096], path[4200], json[4200], want[20480];
  snprintf(dir, sizeof dir, "%s", zs_test_bin("scene-test-notex"));
  zs_os_mkdir(dir);
  snprintf(path, sizeof path, "%s/m.obj", dir);
  write_text(path, "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
  snprintf(path, sizeof path, "%s/m.mtl", dir);
  write_text(path, "newmtl a\nKd 1 0 0\nmap_Kd gone.png\n");
  snprintf(json, sizeof json, "%s/scene.json", dir);
  write_text(json, "{\"meshes\": [{\"name\": \"m\", \"file\": \"m.obj\"},\n"
                   "  {\"name\": \"b\", \"generator\": \"box\",\n"
                   "   \"material\": {\"color\": \"#00ff00\", \"texture\": \"wood.png\"}}],\n"
                   " \"instances\": [{\"mesh\": \"m\"}, {\"mesh\": \"b\"}]}\n");
  const char *why = "cannot open: No such file or directory";
  zs_scene s;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_scenefile_load(json, &s, &err), ZS_ERR_IO);
  snprintf(want, sizeof want, "%s: meshes[0].file: %s/m.mtl:3: map_Kd gone.png: %s", json, dir,
           why);
  ck_assert_str_eq(err.msg, want);
  ck_assert_ptr_null(s.notes.text);

  zs_error_clear(&err);
  ck_assert_msg(zs_scenefile_load_flags(json, ZS_SCENEFILE_SKIP_MISSING_TEXTURES, &s, &err) ==
                    ZS_OK, "%s", err.msg);
  snprintf(want, sizeof want,
           "%s: meshes[0].file: %s/m.mtl:3: map_Kd gone.png: %s: drawn without it\n"
           "%s: meshes[1].material.texture: %s/wood.png: %s: drawn without it\n",
           json, dir, why, json, dir, why);
  ck_assert_str_eq(s.notes.text, want);
  ck_assert_int_eq(s.nmeshes, 2);
  for (int32_t i = 0; i < s.nmeshes; i++) {
    ck_assert_int_eq(s.meshes[i].mesh.nmaterials, 1);
    ck_assert_ptr_null(s.meshes[i].mesh.materials[0].base_texture);
    ck_assert_ptr_null(s.meshes[i].notes.text); /* moved into the scene's */
  }
  ck_assert_uint_eq(s.meshes[0].mesh.face_rgb[0], 0xFF0000);
  ck_assert_uint_eq(s.meshes[1].mesh.materials[0].base[1], 0xFF);
  zs_scene_free(&s);
  ck_assert_ptr_null(s.notes.text);

  /* the same through the inputs of the command and the library */
  zs_error_clear(&err);
  ck_assert_int_eq(zs_input_load(json, 0, &s, &err), ZS_ERR_IO);
  zs_error_clear(&err);
  ck_assert_msg(zs_input_load(json, ZS_INPUT_SKIP_MISSING_TEXTURES, &s, &err) == ZS_OK, "%s",
                err.msg);
  ck_assert_str_eq(s.notes.text, want);
  zs_scene_free(&s);
  snprintf(path, sizeof path, "%s/m.obj", dir);
  zs_error_clear(&err);
  ck_assert_msg(zs_input_load(path, ZS_INPUT_SKIP_MISSING_TEXTURES, &s, &err) == ZS_OK, "%s",
                err.msg);
  snprintf(want, sizeof want, "%s/m.mtl:3: map_Kd gone.png: %s: drawn without it\n", dir, why);
  ck_assert_str_eq(s.notes.text, want);
  zs_scene_free(&s);

  /* the material's own texture alone: the error the note repeats */
  write_text(json, "{\"meshes\": [{\"name\": \"b\", \"generator\": \"box\",\n"
                   "   \"material\": {\"texture\": \"wood.png\"}}],\n"
                   " \"instances\": [{\"mesh\": \"b\"}]}\n");
  zs_error_clear(&err);
  ck_assert_int_eq(zs_scenefile_load(json, &s, &err), ZS_ERR_IO);
  snprintf(want, sizeof want, "%s: meshes[0].material.texture: %s/wood.png: %s", json, dir, why);
  ck_assert_str_eq(err.msg, want);

  /* a texture that is there but no image stays an error */
  snprintf(path, sizeof path, "%s/wood.png", dir);
  write_text(path, "not an image\n");
  zs_error_clear(&err);
  ck_assert_int_eq(zs_scenefile_load_flags(json, ZS_SCENEFILE_SKIP_MISSING_TEXTURES, &s, &err),
                   ZS_ERR_PARSE);
  snprintf(want, sizeof want, "%s: meshes[0].material.texture: %s/wood.png: not a PNG or JPEG image",
           json, dir);
  ck_assert_str_eq(err.msg, want);
  ck_assert_ptr_null(s.notes.text);
  static const char *const files[] = {"wood.png", "scene.json", "m.obj", "m.mtl"};
  for (int i = 0; i < 4; i++) {
    snprintf(path, sizeof path, "%s/%s", dir, files[i]);
    unlink(path);
  }
  rmdir(dir);
}
END_TEST

/* ---- models through assimp ----------------------------------------------------- */

/* Finite coordinates, indices in range, ids and objects consistent. */
static void check_sane_model(const char *path, const zs_model *m) {
  const zs_mesh *mesh = &m->mesh;
  for (int32_t i = 0; i < 3 * mesh->nverts; i++)
    ck_assert_msg(isfinite(mesh->pos[i]), "%s: coordinate %d not finite", path, (int)i);
  ck_assert_msg(mesh->nfaces >= m->nsource_faces, "%s", path);
  for (int32_t f = 0; f < mesh->nfaces; f++) {
    int32_t n = mesh->face_start[f + 1] - mesh->face_start[f];
    ck_assert_msg(n >= 3 && n <= ZS_MAX_POLY_VERTS, "%s: face %d has %d corners", path, (int)f,
                  (int)n);
    for (int32_t k = mesh->face_start[f]; k < mesh->face_start[f + 1]; k++)
      ck_assert_msg(mesh->face_vert[k] >= 0 && mesh->face_vert[k] < mesh->nverts, "%s", path);
    ck_assert_msg(mesh->face_id[f] >= 0 && mesh->face_id[f] < m->nsource_faces, "%s", path);
    ck_assert_msg(m->face_object[f] >= -1 && m->face_object[f] < m->nobjects, "%s", path);
  }
}

/* Loads path: refused with a one-line message naming it, or loaded sane.
 * Returns whether it loaded. */
static int load_or_refuse(const char *path) {
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  zs_status st = zs_assimp_load(path, &m, &err);
  if (st != ZS_OK) {
    ck_assert_int_eq(st, err.code);
    check_message(path, ":", &err); /* "PATH: reason" or "PATH:LINE: reason" */
    const char after = err.msg[strlen(path) + 1];
    ck_assert_msg(after == ' ' || (after >= '0' && after <= '9'), "%s: %s", path, err.msg);
    ck_assert_msg(strlen(err.msg) > strlen(path) + 2, "%s: no reason", path);
    ck_assert_int_eq(m.mesh.nverts, 0);
    ck_assert_ptr_null(m.mesh.pos);
    return 0;
  }
  check_sane_model(path, &m);
  zs_model_free(&m);
  return 1;
}

static int have_assimp_models(void) {
  struct stat st;
  if (!zs_assimp_available()) {
    fprintf(stderr, "test_scene: built without assimp; assimp model tests skipped\n");
    return 0;
  }
  if (stat(ASSIMP_MODELS, &st) != 0 || !S_ISDIR(st.st_mode)) {
    fprintf(stderr, "test_scene: %s absent (Debian assimp-testmodels); skipped\n", ASSIMP_MODELS);
    return 0;
  }
  return 1;
}

/* Every file of a directory of the assimp models whose name ends in ext
 * ("" for all), through load_or_refuse; returns how many there were. */
static int try_directory(const char *rel, const char *ext) {
  char dir[1024];
  snprintf(dir, sizeof dir, "%s/%s", ASSIMP_MODELS, rel);
  DIR *d = opendir(dir);
  if (!d) return 0;
  int n = 0;
  struct dirent *e;
  while ((e = readdir(d))) {
    size_t len = strlen(e->d_name), k = strlen(ext);
    if (e->d_name[0] == '.' || len < k || strcmp(e->d_name + len - k, ext) != 0) continue;
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    load_or_refuse(path);
    n++;
  }
  closedir(d);
  return n;
}

static const char *const assimp_broken[] = {
    "OFF/invalid.off",
    "PLY/issue623.ply",
    "PLY/points.ply",
    "PLY/pond.0.ply",
    "STL/triangle_with_empty_solid.stl",
    "glTF2/BoxBadNormals-glTF-Binary/BoxBadNormals.glb",
    "glTF2/IncorrectVertexArrays/Cube.gltf",
    "glTF2/IndexOutOfRange/AllIndicesOutOfRange.gltf",
    "glTF2/IndexOutOfRange/IndexOutOfRange.gltf",
    "glTF2/MissingBin/BoxTextured.gltf",
    "glTF2/RecursiveNodes/RecursiveNodes.gltf",
    "glTF2/SchemaFailures/sceneWrongType.gltf",
    "glTF2/TestNoRootNode/NoScene.gltf",
    "glTF2/TestNoRootNode/SceneWithoutNodes.gltf",
    "glTF2/issue_3269/texcoord_crash.gltf",
    "glTF/IncorrectVertexArrays/Cube_v1.gltf",
};

START_TEST(assimp_broken_models) {
  if (!have_assimp_models()) return;
  int n = try_directory("invalid", "");
  ck_assert_int_ge(n, 10);
  ck_assert_int_ge(try_directory("glTF2/wrongTypes", ".gltf"), 6);
  for (size_t i = 0; i < sizeof assimp_broken / sizeof assimp_broken[0]; i++) {
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", ASSIMP_MODELS, assimp_broken[i]);
    load_or_refuse(path);
  }
  /* the ones that must be refused, and why */
  static const struct {
    const char *file, *reason;
  } refused[] = {
      {"invalid/OutOfMemory.off", ": OFF header declares 353535235358 vertices"},
      {"OFF/invalid.off", ":6: '0': expected a face's corner count, 1 to 9"},
      {"glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb",
       ": mesh 0 vertex 0: not a finite number"},
      {"glTF2/wrongTypes/badArray.gltf", ": "},
      {"glTF2/TestNoRootNode/SceneWithoutNodes.gltf", ": no meshes"},
      {"invalid/empty.ply", ": "},
  };
  for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++) {
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", ASSIMP_MODELS, refused[i].file);
    zs_model m;
    zs_error err;
    zs_error_clear(&err);
    ck_assert_msg(zs_assimp_load(path, &m, &err) != ZS_OK, "%s loaded", path);
    check_message(path, refused[i].reason, &err);
  }
}
END_TEST

static const struct {
  const char *file, *reason;
} own_broken[] = {
    {"bad_header_line.ply", ":3: not a line of a PLY header"},
    {"deep_nodes.gltf", ": node tree deeper than 256"},
    {"empty.stl", ": "},
    {"empty_face.ply", ":18: vertex 3: fewer values than its 7 properties take"},
    {"empty_face_binary.ply", ": mesh 0 face 1: no vertices"}, /* (assimp would abort) */
    {"face_index_negative.off", ":7: face corner '-1': expected a vertex index below 4"},
    {"face_index_past_end.off", ":8: face corner '7': expected a vertex index below 4, the "
                                "header's vertex count"},
    {"face_of_ten.off", ":13: a face of 10 corners: assimp's OFF reader takes 1 to 9"},
    {"face_short.off", ":7: a face of 4 corners lists 3"},
    {"face_short.ply", ":14: face 0: fewer values than its 1 properties take"},
    {"cut_short.ply", ": cut short: 11 of the 14 element lines the header declares (face 3 of 6)"},
    {"garbage.ply", ": "},
    {"huge_accessor.gltf", ": "},
    {"huge_binary.ply", ": PLY header declares elements of at least 600000001 bytes"},
    {"huge_count.off", ": OFF header declares 3 vertices and 2000000000 faces"},
    {"huge_vertices.off", ": OFF header declares 4000000000 vertices and 1 faces"},
    {"huge_vertices.ply", ": PLY header declares elements of at least 3000000001 bytes"},
    {"inf.stl", ": mesh 0 vertex 1: not a finite number"},
    {"inf_colour.ply", ":15: 'inf': not a finite number"},
    {"nan.off", ":3: 'nan': not a finite number"},
    /* a NaN vertex that assimp's joining of identical vertices merged away */
    {"nan_joined.gltf", ": mesh 0 vertex 2: not a finite number"},
    {"nan_joined.stl", ": mesh 0 vertex 2: not a finite number"},
    {"nan_joined_binary.ply", ": mesh 0 vertex 2: not a finite number"},
    {"nan_position.ply", ":11: 'nan': not a finite number"},
    {"nan_position.stl", ":5: 'nan': not a finite number"}, /* (its name nanite is no number) */
    {"nan_normal.ply", ":13: 'nan': not a finite number"},
    {"not_a_model.off", ": "},
    {"no_end_header.ply", ": PLY header without an end_header line"},
    {"nul_in_header.ply", ": PLY header holds a NUL byte"},
    {"overflow_transform.gltf", ": mesh 0 vertex 0: not a finite number"},
    {"truncated.stl", ": "},
};

START_TEST(assimp_own_broken_models) {
  if (!zs_assimp_available()) {
    /* without assimp every file is refused the same way */
    char path[4096];
    snprintf(path, sizeof path, "%s", zs_test_src("tests/data/models/tetra.ply"));
    zs_model m;
    zs_error err;
    zs_error_clear(&err);
    ck_assert_int_eq(zs_assimp_load(path, &m, &err), ZS_ERR_UNSUPPORTED);
    check_message(path, ": this build reads only .obj (built without assimp)", &err);
    return;
  }
  char rel[512], path[4096];
  snprintf(rel, sizeof rel, "tests/data/bad_models/%s", own_broken[_i].file);
  snprintf(path, sizeof path, "%s", zs_test_src(rel));
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_assimp_load(path, &m, &err) != ZS_OK, "%s loaded", path);
  check_message(path, own_broken[_i].reason, &err);
  ck_assert_int_eq(m.mesh.nverts, 0);
}
END_TEST

/* ---- good models, counted independently ----------------------------------- */

/* Triangles of an ASCII OFF or PLY file: after the header, nv vertex lines,
 * then nf face lines "k i1 .. ik", each k - 2 triangles. */
static long text_triangles(const char *path, int ply) {
  FILE *f = fopen(path, "r");
  ck_assert_ptr_nonnull(f);
  char line[4096];
  long nv = -1, nf = -1;
  while (fgets(line, sizeof line, f)) {
    if (ply) {
      sscanf(line, "element vertex %ld", &nv);
      sscanf(line, "element face %ld", &nf);
      if (strncmp(line, "end_header", 10) == 0) break;
    } else if (line[0] != '#' && sscanf(line, "%ld %ld", &nv, &nf) == 2) {
      break;
    }
  }
  ck_assert(nv > 0 && nf > 0);
  long tris = 0;
  for (long v = 0; v < nv;) v += fgets(line, sizeof line, f) && line[0] != '#' && line[0] != '\n';
  for (long k = 0; k < nf;) {
    ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
    long corners;
    if (sscanf(line, "%ld", &corners) != 1) continue;
    tris += corners - 2;
    k++;
  }
  fclose(f);
  return tris;
}

/* Triangles of an STL file: facets of an ASCII one, the count of a binary
 * one. */
static long stl_triangles(const char *path) {
  FILE *f = fopen(path, "rb");
  ck_assert_ptr_nonnull(f);
  char head[6] = {0};
  long n = 0;
  if (fread(head, 1, 5, f) == 5 && strncmp(head, "solid", 5) == 0) {
    char line[1024];
    while (fgets(line, sizeof line, f)) n += strstr(line, "facet normal") != NULL;
  } else {
    unsigned char c[4];
    ck_assert_int_eq(fseek(f, 80, SEEK_SET), 0);
    ck_assert_int_eq(fread(c, 1, 4, f), 4);
    n = (long)c[0] | (long)c[1] << 8 | (long)c[2] << 16 | (long)c[3] << 24;
  }
  fclose(f);
  return n;
}

/* Triangles of a glTF 2 file: the index count of each mesh primitive (mode
 * 4) over the nodes that place meshes, divided by 3. */
static long gltf_triangles(const char *path) {
  FILE *f = fopen(path, "rb");
  ck_assert_ptr_nonnull(f);
  static char text[1 << 20];
  size_t len = fread(text, 1, sizeof text - 1, f);
  fclose(f);
  text[len] = '\0';
  cJSON *doc = cJSON_Parse(text);
  ck_assert_ptr_nonnull(doc);
  const cJSON *meshes = cJSON_GetObjectItem(doc, "meshes");
  const cJSON *acc = cJSON_GetObjectItem(doc, "accessors");
  const cJSON *nodes = cJSON_GetObjectItem(doc, "nodes");
  long tris = 0;
  const cJSON *node;
  cJSON_ArrayForEach(node, nodes) {
    const cJSON *mi = cJSON_GetObjectItem(node, "mesh");
    if (!mi) continue;
    const cJSON *prim;
    cJSON_ArrayForEach(
        prim, cJSON_GetObjectItem(cJSON_GetArrayItem(meshes, mi->valueint), "primitives")) {
      const cJSON *mode = cJSON_GetObjectItem(prim, "mode");
      ck_assert(!mode || mode->valueint == 4);
      const cJSON *ix = cJSON_GetObjectItem(prim, "indices");
      ck_assert_ptr_nonnull(ix);
      tris += cJSON_GetObjectItem(cJSON_GetArrayItem(acc, ix->valueint), "count")->valueint / 3;
    }
  }
  cJSON_Delete(doc);
  return tris;
}

static void expect_faces(const char *path, long faces) {
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_assimp_load(path, &m, &err) == ZS_OK, "%s", err.msg);
  check_sane_model(path, &m);
  ck_assert_msg(m.nsource_faces == faces, "%s: %d faces, expected %ld", path, (int)m.nsource_faces,
                faces);
  zs_model_free(&m);
}

START_TEST(assimp_good_models) {
  if (!zs_assimp_available()) return;
  char path[4096];
  /* our own: two nodes placing one quad, a material colour */
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/models/two_nodes.gltf"));
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_assimp_load(path, &m, &err) == ZS_OK, "%s", err.msg);
  ck_assert_int_eq(m.nsource_faces, 4);
  ck_assert_int_eq(m.nobjects, 2);
  ck_assert_str_eq(m.object_names[0], "left");
  ck_assert_str_eq(m.object_names[1], "right");
  for (int32_t f = 0; f < m.mesh.nfaces; f++) {
    ck_assert_uint_eq(m.mesh.face_rgb[f], 0x336699); /* 0.2 0.4 0.6 */
    ck_assert_int_eq(m.mesh.face_id[f], f);
    ck_assert_int_eq(m.face_object[f], f / 2);
  }
  double lo[3], hi[3];
  ck_assert(zs_model_bounds(&m, lo, hi));
  ck_assert_double_eq(lo[0], -2); /* left: + (-2, 0, 0) */
  ck_assert_double_eq(hi[0], 5);  /* right: * 2 + (3, 0, 0) */
  ck_assert_double_eq(hi[1], 2);
  zs_model_free(&m);
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/models/tetra.ply"));
  expect_faces(path, text_triangles(path, 1));
  expect_faces(path, 4);

  if (!have_assimp_models()) return;
  static const char *const ply[] = {"PLY/cube.ply", "PLY/Wuson.ply"};
  for (int i = 0; i < 2; i++) {
    snprintf(path, sizeof path, "%s/%s", ASSIMP_MODELS, ply[i]);
    expect_faces(path, text_triangles(path, 1));
  }
  static const char *const off[] = {"OFF/Cube.off", "OFF/Wuson.off"};
  for (int i = 0; i < 2; i++) {
    snprintf(path, sizeof path, "%s/%s", ASSIMP_MODELS, off[i]);
    expect_faces(path, text_triangles(path, 0));
  }
  static const char *const stl[] = {"STL/triangle_with_two_solids.stl", "STL/Spider_ascii.stl",
                                    "STL/Spider_binary.stl", "STL/Wuson.stl"};
  for (int i = 0; i < 4; i++) {
    snprintf(path, sizeof path, "%s/%s", ASSIMP_MODELS, stl[i]);
    expect_faces(path, stl_triangles(path));
  }
  snprintf(path, sizeof path, "%s/glTF2/BoxTextured-glTF/BoxTextured.gltf", ASSIMP_MODELS);
  expect_faces(path, gltf_triangles(path));
  expect_faces(path, 12);
}
END_TEST

/* ---- textures that cannot be opened, through assimp ---------------------- */

/* The painted triangle with its image a file beside it that is not there:
 * an error; with ZS_ASSIMP_SKIP_MISSING_TEXTURES a note, the material
 * untextured, the rest as read; in a scene file the note follows the
 * mesh's path.  A corrupt image stays an error. */
START_TEST(assimp_missing_texture_noted) {
#ifndef ZS_HAVE_ASSIMP
  fprintf(stderr, "test_scene: built without assimp; assimp_missing_texture_noted skipped\n");
  return;
#else
  char dir[4096], gltf[4200], json[4200], png[4200], want[16384];
  snprintf(dir, sizeof dir, "%s", zs_test_bin("scene-test-gltf-notex"));
  zs_os_mkdir(dir);
  snprintf(gltf, sizeof gltf, "%s/tri.gltf", dir);
  snprintf(json, sizeof json, "%s/scene.json", dir);
  snprintf(png, sizeof png, "%s/gone.png", dir);
  unlink(png);
  size_t n;
  char *text = slurp_src("tests/data/models/painted_triangle.gltf", &n);
  const char *uri = "\"uri\": \"data:image/png;base64,";
  char *at = strstr(text, uri);
  ck_assert_ptr_nonnull(at);
  char *end = strchr(at + strlen(uri), '"');
  ck_assert_ptr_nonnull(end);
  *at = '\0';
  FILE *f = fopen(gltf, "wb");
  ck_assert_ptr_nonnull(f);
  fprintf(f, "%s\"uri\": \"gone.png%s", text, end);
  ck_assert_int_eq(fclose(f), 0);
  free(text);

  const char *why = "cannot open: No such file or directory";
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_assimp_load(gltf, &m, &err), ZS_ERR_IO);
  snprintf(want, sizeof want, "%s: texture %s: %s", gltf, png, why);
  ck_assert_str_eq(err.msg, want);
  ck_assert_ptr_null(m.notes.text);

  zs_error_clear(&err);
  ck_assert_msg(zs_assimp_load_flags(gltf, ZS_ASSIMP_SKIP_MISSING_TEXTURES, &m, &err) == ZS_OK,
                "%s", err.msg);
  snprintf(want, sizeof want, "%s: texture %s: %s: drawn without it\n", gltf, png, why);
  ck_assert_str_eq(m.notes.text, want);
  ck_assert_int_eq(m.mesh.nmaterials, 1);
  ck_assert_ptr_null(m.mesh.materials[0].base_texture);
  ck_assert_int_eq(m.ntextures, 0);
  ck_assert_int_eq(m.mesh.materials[0].base[1], 128); /* baseColorFactor's 0.5 */
  ck_assert_int_eq(m.mesh.nattrs, 3);                 /* the colours and uvs kept */
  zs_model_free(&m);

  /* as a scene file's mesh, and through the command's inputs */
  write_text(json, "{\"meshes\": [{\"name\": \"t\", \"file\": \"tri.gltf\"}],"
                   " \"instances\": [{\"mesh\": \"t\"}]}\n");
  zs_scene s;
  zs_error_clear(&err);
  ck_assert_msg(zs_scenefile_load_flags(json, ZS_SCENEFILE_SKIP_MISSING_TEXTURES, &s, &err) ==
                    ZS_OK, "%s", err.msg);
  char prefixed[24576];
  snprintf(prefixed, sizeof prefixed, "%s: meshes[0].file: %s", json, want);
  ck_assert_str_eq(s.notes.text, prefixed);
  zs_scene_free(&s);
  zs_error_clear(&err);
  ck_assert_msg(zs_input_load(gltf, ZS_INPUT_SKIP_MISSING_TEXTURES, &s, &err) == ZS_OK, "%s",
                err.msg);
  ck_assert_str_eq(s.notes.text, want);
  zs_scene_free(&s);

  /* an image that is there but corrupt */
  write_text(png, "not an image\n");
  zs_error_clear(&err);
  ck_assert_int_eq(zs_assimp_load_flags(gltf, ZS_ASSIMP_SKIP_MISSING_TEXTURES, &m, &err),
                   ZS_ERR_PARSE);
  snprintf(want, sizeof want, "%s: texture %s: not a PNG or JPEG image", gltf, png);
  ck_assert_str_eq(err.msg, want);
  unlink(png);
  unlink(gltf);
  unlink(json);
  rmdir(dir);
#endif
}
END_TEST

/* ---- the suite ------------------------------------------------------------- */

static Suite *scene_suite(void) {
  Suite *s = suite_create("scene");
  TCase *tc = tcase_create("container");
  tcase_add_test(tc, container_ids_and_bounds);
  tcase_add_test(tc, container_from_model);
  suite_add_tcase(s, tc);

  tc = tcase_create("motion");
  tcase_add_test(tc, motion_bounce_exact);
  tcase_add_test(tc, motion_bounce_inexact);
  tcase_add_test(tc, motion_local_axis);
  tcase_add_test(tc, motion_scene_file_deterministic);
  suite_add_tcase(s, tc);

  tc = tcase_create("paths");
  tcase_add_test(tc, path_through_keys);
  tcase_add_test(tc, path_is_c1);
  tcase_add_test(tc, named_roll);
  tcase_add_test(tc, named_translate);
  tcase_add_test(tc, named_yaw);
  tcase_add_test(tc, named_fast);
  tcase_add_test(tc, named_errors);
  tcase_add_test(tc, path_format_line);
  suite_add_tcase(s, tc);

  tc = tcase_create("scenefile");
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, examples_load_and_render);
  tcase_add_test(tc, examples_content);
  tcase_add_test(tc, example_in_header_is_a_file);
  tcase_add_test(tc, format_transform);
  tcase_add_test(tc, format_camera_path_generators);
  tcase_add_loop_test(tc, bad_scene_file, 0, NBAD_SCENES);
  tcase_add_test(tc, bad_scene_corpus_complete);
  tcase_add_test(tc, bad_scene_sizes_and_io);
  tcase_add_test(tc, mutated_examples);
  tcase_add_test(tc, scenefile_missing_textures_noted);
  tcase_add_test(tc, obj_missing_materials_noted);
  suite_add_tcase(s, tc);

  tc = tcase_create("assimp");
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, assimp_broken_models);
  tcase_add_loop_test(tc, assimp_own_broken_models, 0,
                      (int)(sizeof own_broken / sizeof own_broken[0]));
  tcase_add_test(tc, assimp_good_models);
  tcase_add_test(tc, assimp_missing_texture_noted);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return zs_test_run(scene_suite()); }
