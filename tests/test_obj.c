/* Tests of scene/model.c (polygon splitting, numbering), scene/normals.c
 * (normals where a model has none) and scene/load_obj.c (the OBJ reader:
 * attributes, materials, textures, and its error messages). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/exactmath.h"
#include "util/rng.h"
#include "scene/model.h"
#include "scene/load_obj.h"
#include "tests/testutil.h"

/* ---- helpers ---------------------------------------------------------- */

/* Parses text (no material libraries) and asserts success. */
static void parse_ok(const char *text, zs_model *m) {
  zs_error err;
  zs_error_clear(&err);
  zs_status st = zs_obj_parse(text, strlen(text), "mem.obj", NULL, m, &err);
  ck_assert_msg(st == ZS_OK, "parse failed: %s", err.msg);
}

/* Parses text that must fail; returns the status and leaves the message. */
static zs_status parse_bad(const char *text, size_t len, zs_error *err) {
  zs_model m;
  zs_error_clear(err);
  zs_status st = zs_obj_parse(text, len, "mem.obj", NULL, &m, err);
  /* On failure the model is left empty. */
  ck_assert_int_eq(m.mesh.nverts, 0);
  ck_assert_int_eq(m.mesh.nfaces, 0);
  ck_assert_ptr_null(m.mesh.pos);
  ck_assert_ptr_null(m.mesh.face_vert);
  ck_assert_ptr_null(m.object_names);
  return st;
}

static int face_size(const zs_model *m, int32_t f) {
  return m->mesh.face_start[f + 1] - m->mesh.face_start[f];
}

static int32_t face_vert(const zs_model *m, int32_t f, int i) {
  return m->mesh.face_vert[m->mesh.face_start[f] + i];
}

static const double *vertex(const zs_model *m, int32_t v) {
  return m->mesh.pos + 3 * v;
}

/* Vector area (half the cross product) of triangle face f. */
static void triangle_area(const zs_model *m, int32_t f, double out[3]) {
  ck_assert_int_eq(face_size(m, f), 3);
  const double *a = vertex(m, face_vert(m, f, 0));
  const double *b = vertex(m, face_vert(m, f, 1));
  const double *c = vertex(m, face_vert(m, f, 2));
  double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  out[0] = 0.5 * (u[1] * v[2] - u[2] * v[1]);
  out[1] = 0.5 * (u[2] * v[0] - u[0] * v[2]);
  out[2] = 0.5 * (u[0] * v[1] - u[1] * v[0]);
}

/* Whether (x, y) is strictly inside triangle face f, projected to xy. */
static int inside_xy(const zs_model *m, int32_t f, double x, double y) {
  double s[3];
  for (int i = 0; i < 3; i++) {
    const double *a = vertex(m, face_vert(m, f, i));
    const double *b = vertex(m, face_vert(m, f, (i + 1) % 3));
    s[i] = (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
  }
  return (s[0] > 0 && s[1] > 0 && s[2] > 0) ||
         (s[0] < 0 && s[1] < 0 && s[2] < 0);
}

static void write_file(const char *path, const char *data, size_t len) {
  FILE *f = fopen(path, "wb");
  ck_assert_ptr_nonnull(f);
  ck_assert_uint_eq(fwrite(data, 1, len, f), len);
  ck_assert_int_eq(fclose(f), 0);
}

/* ---- the model -------------------------------------------------------- */

START_TEST(model_basics) {
  zs_model m;
  zs_model_init(&m);
  double lo[3], hi[3];
  ck_assert_int_eq(zs_model_bounds(&m, lo, hi), 0);
  ck_assert_int_eq(zs_model_add_vertex(&m, 1, -2, 3), 0);
  ck_assert_int_eq(zs_model_add_vertex(&m, -1, 5, 0), 1);
  ck_assert_int_eq(zs_model_add_vertex(&m, 0, 0, 7), 2);
  ck_assert_int_eq(zs_model_bounds(&m, lo, hi), 1);
  ck_assert(lo[0] == -1 && lo[1] == -2 && lo[2] == 0);
  ck_assert(hi[0] == 1 && hi[1] == 5 && hi[2] == 7);

  ck_assert_int_eq(zs_model_object(&m, "a"), 0);
  ck_assert_int_eq(zs_model_object(&m, "b"), 1);
  ck_assert_int_eq(zs_model_object(&m, "a"), 0);
  ck_assert_int_eq(m.nobjects, 2);
  ck_assert_str_eq(m.object_names[1], "b");

  int32_t tri[3] = {0, 1, 2}, bad[3] = {0, 1, 3};
  ck_assert_int_eq(zs_model_add_polygon(&m, bad, 3, 0, -1), ZS_ERR_ARG);
  ck_assert_int_eq(zs_model_add_polygon(&m, tri, 2, 0, -1), ZS_ERR_ARG);
  ck_assert_int_eq(zs_model_add_polygon(&m, tri, 3, 0, 2), ZS_ERR_ARG);
  ck_assert_int_eq(m.nsource_faces, 0);
  ck_assert_int_eq(zs_model_add_polygon(&m, tri, 3, 0x123456, 1), ZS_OK);
  ck_assert_int_eq(m.mesh.nfaces, 1);
  ck_assert_int_eq(m.nsource_faces, 1);
  ck_assert_int_eq(m.mesh.face_start[0], 0);
  ck_assert_int_eq(m.mesh.face_start[1], 3);
  ck_assert_uint_eq(m.mesh.face_rgb[0], 0x123456);
  ck_assert_int_eq(m.mesh.face_id[0], 0);
  ck_assert_int_eq(m.face_object[0], 1);
  zs_model_free(&m);
  ck_assert_int_eq(m.mesh.nverts, 0);
  ck_assert_ptr_null(m.mesh.pos);
}
END_TEST

/* Many vertices and faces: the arrays grow and stay consistent. */
START_TEST(model_growth) {
  zs_model m;
  zs_model_init(&m);
  for (int i = 0; i < 10000; i++) {
    ck_assert_int_eq(zs_model_add_vertex(&m, i, i % 7, 0), i);
    if (i >= 2) {
      int32_t tri[3] = {i - 2, i - 1, i};
      ck_assert_int_eq(zs_model_add_polygon(&m, tri, 3, 0, -1), ZS_OK);
    }
  }
  ck_assert_int_eq(m.mesh.nfaces, m.nsource_faces);
  for (int32_t f = 0; f < m.mesh.nfaces; f++) {
    ck_assert_int_eq(m.mesh.face_id[f], f);
    ck_assert_int_eq(face_vert(&m, f, 0), f);
  }
  ck_assert(vertex(&m, 9999)[0] == 9999.0);
  zs_model_free(&m);
}
END_TEST

/* Random star-shaped polygons (simple by construction: vertices at
 * increasing angles around the origin, at random radii), in the plane
 * z = 0 and tilted: n - 2 triangles, each wound like the polygon, whose
 * areas add up to the polygon's. */
START_TEST(model_random_polygons) {
  zs_rng rng;
  zs_rng_seed(&rng, 12345);
  const double pi = acos(-1.0);
  for (int trial = 0; trial < 500; trial++) {
    int n = 3 + (int)zs_rng_below(&rng, ZS_MAX_POLY_VERTS - 2);
    int tilted = trial % 2;
    zs_model m;
    zs_model_init(&m);
    int32_t idx[ZS_MAX_POLY_VERTS];
    double area = 0, px = 0, py = 0, x0 = 0, y0 = 0;
    for (int i = 0; i < n; i++) {
      double a = 2 * pi * (i + zs_rng_range(&rng, 0.05, 0.95)) / n;
      double r = zs_rng_range(&rng, 0.2, 1.0);
      double x = r * cos(a), y = r * sin(a);
      if (i > 0) {
        area += 0.5 * (px * y - py * x);
      } else {
        x0 = x;
        y0 = y;
      }
      px = x;
      py = y;
      /* tilted: rotate about the x axis, so z = 0.6 y, y = 0.8 y */
      idx[i] = zs_model_add_vertex(&m, x, tilted ? 0.8 * y : y,
                                   tilted ? 0.6 * y : 0.0);
    }
    area += 0.5 * (px * y0 - py * x0);
    ck_assert_int_eq(zs_model_add_polygon(&m, idx, n, 0, -1), ZS_OK);
    ck_assert_int_eq(m.nsource_faces, 1);
    if (m.mesh.nfaces == 1) {
      ck_assert_int_eq(face_size(&m, 0), n); /* convex, stored whole */
    } else {
      ck_assert_int_eq(m.mesh.nfaces, n - 2);
      double total = 0;
      for (int32_t f = 0; f < m.mesh.nfaces; f++) {
        ck_assert_int_eq(m.mesh.face_id[f], 0);
        double a[3];
        triangle_area(&m, f, a);
        /* the normal of the plane is (0, -0.6, 0.8) when tilted */
        double along = tilted ? -0.6 * a[1] + 0.8 * a[2] : a[2];
        ck_assert(along > 0);
        total += along;
      }
      ck_assert_double_eq_tol(total, area, 1e-12);
    }
    zs_model_free(&m);
  }
}
END_TEST

/* ---- reading OBJ ------------------------------------------------------ */

START_TEST(obj_counts) {
  zs_model m;
  parse_ok("# a unit square and a triangle\n"
           "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
           "v 2 0 0 2\n" /* w = 2: (1, 0, 0) */
           "vt 0 0\nvn 0 0 1\ns off\nl 1 2\np 1\nfoo bar baz\n\n"
           "f 1 2 3 4\n"
           "f 1 2 5 # a comment\n",
           &m);
  ck_assert_int_eq(m.mesh.nverts, 5);
  ck_assert_int_eq(m.mesh.nfaces, 2);
  ck_assert_int_eq(m.nsource_faces, 2);
  ck_assert_int_eq(m.nobjects, 0);
  ck_assert_int_eq(face_size(&m, 0), 4); /* convex planar: stored whole */
  ck_assert_int_eq(face_size(&m, 1), 3);
  for (int i = 0; i < 4; i++) ck_assert_int_eq(face_vert(&m, 0, i), i);
  ck_assert_int_eq(m.mesh.face_id[0], 0);
  ck_assert_int_eq(m.mesh.face_id[1], 1);
  ck_assert_int_eq(m.face_object[0], -1);
  ck_assert_uint_eq(m.mesh.face_rgb[0], ZS_GREY);
  ck_assert(vertex(&m, 2)[0] == 1.0 && vertex(&m, 2)[1] == 1.0);
  ck_assert(vertex(&m, 4)[0] == 1.0 && vertex(&m, 4)[1] == 0.0);
  zs_model_free(&m);
}
END_TEST

/* The four forms of a face vertex name the same vertices. */
START_TEST(obj_face_formats) {
  zs_model m;
  parse_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
           "f 1 2 3\nf 1/1 2/2 3/3\nf 1//1 2//1 3//1\nf 1/1/1 2/2/1 3/3/1\n"
           "f +1/-1/-1 2/2/1 3/3/1\n",
           &m);
  ck_assert_int_eq(m.mesh.nfaces, 5);
  for (int32_t f = 0; f < 5; f++) {
    ck_assert_int_eq(face_size(&m, f), 3);
    for (int i = 0; i < 3; i++) ck_assert_int_eq(face_vert(&m, f, i), i);
    ck_assert_int_eq(m.mesh.face_id[f], f);
  }
  zs_model_free(&m);
}
END_TEST

/* Negative indices count back from the last vertex defined so far. */
START_TEST(obj_negative_indices) {
  zs_model m;
  parse_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\n"
           "f -3 -2 -1\n"
           "v 5 5 5\nv 6 5 5\nv 5 6 5\n"
           "f -3 -2 -1\n"
           "f -6 2 -1\n",
           &m);
  ck_assert_int_eq(m.mesh.nfaces, 3);
  int32_t want[3][3] = {{0, 1, 2}, {3, 4, 5}, {0, 1, 5}};
  for (int f = 0; f < 3; f++)
    for (int i = 0; i < 3; i++) ck_assert_int_eq(face_vert(&m, f, i), want[f][i]);
  zs_model_free(&m);
}
END_TEST

START_TEST(obj_objects) {
  zs_model m;
  parse_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\n"
           "f 1 2 3\n"         /* 0: no object */
           "g wheel\nf 1 2 3\n" /* 1: wheel */
           "o body\nf 1 2 3\n"  /* 2: body */
           "g wheel\nf 1 2 3\n" /* 3: wheel again, the same object */
           "g door left\nf 1 2 3\n" /* 4: door (first name) */
           "g\nf 1 2 3\n"       /* 5: no object */
           "o body\nf 1 2 3\n", /* 6: body */
           &m);
  ck_assert_int_eq(m.nobjects, 3);
  ck_assert_str_eq(m.object_names[0], "wheel");
  ck_assert_str_eq(m.object_names[1], "body");
  ck_assert_str_eq(m.object_names[2], "door");
  int32_t want[7] = {-1, 0, 1, 0, 2, -1, 1};
  ck_assert_int_eq(m.mesh.nfaces, 7);
  for (int f = 0; f < 7; f++) ck_assert_int_eq(m.face_object[f], want[f]);
  zs_model_free(&m);
}
END_TEST

START_TEST(obj_materials) {
  char path[4096];
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/obj/colors.obj"));
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  zs_status st = zs_obj_load(path, &m, &err);
  ck_assert_msg(st == ZS_OK, "%s", err.msg);
  /* none, red, clamped (1.5 -0.2 0.5), single (0.2), no Kd, unknown,
   * late (from a library read after its usemtl), red */
  uint32_t want[8] = {ZS_GREY, 0xFF0000, 0xFF0080, 0x333333,
                      ZS_GREY, ZS_GREY,  0x00FF00, 0xFF0000};
  ck_assert_int_eq(m.mesh.nfaces, 8);
  for (int f = 0; f < 8; f++) ck_assert_uint_eq(m.mesh.face_rgb[f], want[f]);
  zs_model_free(&m);

  /* Without a directory no library is read: everything is grey. */
  static const char text[] = "mtllib colors.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                             "usemtl red\nf 1 2 3\n";
  st = zs_obj_parse(text, sizeof text - 1, "mem.obj", NULL, &m, &err);
  ck_assert_int_eq(st, ZS_OK);
  ck_assert_uint_eq(m.mesh.face_rgb[0], ZS_GREY);
  zs_model_free(&m);
}
END_TEST

/* An L-shaped hexagon (area 3) is cut into 4 triangles of face 0 that
 * cover it exactly once; the next face is still number 1. */
START_TEST(obj_concave) {
  zs_model m;
  parse_ok("v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n"
           "f 1 2 3 4 5 6\nf 1 2 3\n",
           &m);
  ck_assert_int_eq(m.nsource_faces, 2);
  ck_assert_int_eq(m.mesh.nfaces, 5);
  double total = 0;
  for (int32_t f = 0; f < 4; f++) {
    ck_assert_int_eq(m.mesh.face_id[f], 0);
    double a[3];
    triangle_area(&m, f, a);
    ck_assert(a[2] > 0); /* the polygon's winding */
    total += a[2];
  }
  ck_assert_int_eq(m.mesh.face_id[4], 1);
  ck_assert_double_eq_tol(total, 3.0, 1e-12);
  /* Sample points off every edge and diagonal: covered once inside the L,
   * never outside. */
  for (int i = 0; i < 25; i++) {
    for (int j = 0; j < 25; j++) {
      double x = -0.213 + 0.1 * i, y = -0.187 + 0.1 * j;
      int in = x > 0 && y > 0 && x < 2 && y < 2 && (x < 1 || y < 1);
      int covered = 0;
      for (int32_t f = 0; f < 4; f++) covered += inside_xy(&m, f, x, y);
      ck_assert_int_eq(covered, in);
    }
  }
  zs_model_free(&m);
}
END_TEST

/* The same L in the plane x = 0, wound clockwise seen from +x: the pieces
 * keep the polygon's orientation (normal along -x). */
START_TEST(obj_concave_tilted) {
  zs_model m;
  parse_ok("v 0 0 0\nv 0 0 2\nv 0 1 2\nv 0 1 1\nv 0 2 1\nv 0 2 0\n"
           "f 1 2 3 4 5 6\n",
           &m);
  ck_assert_int_eq(m.mesh.nfaces, 4);
  double total = 0;
  for (int32_t f = 0; f < 4; f++) {
    double a[3];
    triangle_area(&m, f, a);
    ck_assert(a[0] < 0 && a[1] == 0 && a[2] == 0);
    total -= a[0];
  }
  ck_assert_double_eq_tol(total, 3.0, 1e-12);
  zs_model_free(&m);
}
END_TEST

START_TEST(obj_nonplanar) {
  zs_model m;
  parse_ok("v 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0 1 0\n"
           "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
           "f 1 2 3 4\n"  /* non-planar, convex in projection: a fan */
           "f 5 6 7 8\n", /* planar: whole */
           &m);
  ck_assert_int_eq(m.nsource_faces, 2);
  ck_assert_int_eq(m.mesh.nfaces, 3);
  int32_t want[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (int f = 0; f < 2; f++) {
    ck_assert_int_eq(m.mesh.face_id[f], 0);
    for (int i = 0; i < 3; i++) ck_assert_int_eq(face_vert(&m, f, i), want[f][i]);
  }
  ck_assert_int_eq(m.mesh.face_id[2], 1);
  ck_assert_int_eq(face_size(&m, 2), 4);
  zs_model_free(&m);
}
END_TEST

/* A pentagram turns left at every vertex but is not convex. */
START_TEST(obj_pentagram) {
  char text[512];
  int n = 0;
  for (int i = 0; i < 5; i++) {
    double a = 2 * acos(-1.0) * (2 * i) / 5; /* every second point of a pentagon */
    n += snprintf(text + n, sizeof text - n, "v %.17g %.17g 0\n", cos(a), sin(a));
  }
  snprintf(text + n, sizeof text - n, "f 1 2 3 4 5\n");
  zs_model m;
  parse_ok(text, &m);
  ck_assert_int_eq(m.nsource_faces, 1);
  ck_assert_int_eq(m.mesh.nfaces, 3);
  for (int32_t f = 0; f < 3; f++) {
    ck_assert_int_eq(face_size(&m, f), 3);
    ck_assert_int_eq(m.mesh.face_id[f], 0);
  }
  zs_model_free(&m);
}
END_TEST

/* Repeated vertices are dropped; a face left with fewer than 3 is kept as
 * given (zero area) so the faces after it keep their numbers. */
START_TEST(obj_degenerate) {
  zs_model m;
  parse_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\n"
           "f 1 1 2\n"        /* 0: two distinct vertices */
           "f 1 2 2 3 3 1\n"  /* 1: the triangle 1 2 3 */
           "f 2 2 2\n"        /* 2: one vertex */
           "f 1 2 3\n",       /* 3 */
           &m);
  ck_assert_int_eq(m.nsource_faces, 4);
  ck_assert_int_eq(m.mesh.nfaces, 4);
  for (int32_t f = 0; f < 4; f++) {
    ck_assert_int_eq(m.mesh.face_id[f], f);
    ck_assert_int_eq(face_size(&m, f), 3);
  }
  int32_t want[4][3] = {{0, 0, 1}, {0, 1, 2}, {1, 1, 1}, {0, 1, 2}};
  for (int f = 0; f < 4; f++)
    for (int i = 0; i < 3; i++) ck_assert_int_eq(face_vert(&m, f, i), want[f][i]);
  zs_model_free(&m);
}
END_TEST

/* \r\n endings, a last line without a newline, a line of exactly the
 * maximum length, and text that is not NUL-terminated. */
START_TEST(obj_lines) {
  zs_model m;
  parse_ok("v 0 0 0\r\nv 1 0 0\r\n\r\nv 0 1 0\r\nf 1 2 3", &m);
  ck_assert_int_eq(m.mesh.nverts, 3);
  ck_assert_int_eq(m.mesh.nfaces, 1);
  zs_model_free(&m);

  size_t len = ZS_OBJ_LINE_MAX + 2;
  char *text = malloc(len);
  ck_assert_ptr_nonnull(text);
  memset(text, ' ', len);
  text[0] = '#';
  text[len - 2] = '\r';
  text[len - 1] = '\n';
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_obj_parse(text, len, "max.obj", NULL, &m, &err), ZS_OK);
  zs_model_free(&m);
  free(text);

  /* An exact-size heap copy, so reading past len would be caught by ASan;
   * the text stops right after "3". */
  static const char src[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3";
  char *exact = malloc(sizeof src - 1);
  ck_assert_ptr_nonnull(exact);
  memcpy(exact, src, sizeof src - 1);
  ck_assert_int_eq(zs_obj_parse(exact, sizeof src - 1, "x.obj", NULL, &m, &err),
                   ZS_OK);
  ck_assert_int_eq(m.mesh.nfaces, 1);
  zs_model_free(&m);
  free(exact);

  /* Cut the same text in the middle of "3": "f 1 2 " has two vertices. */
  ck_assert_int_ne(parse_bad(src, sizeof src - 2, &err), ZS_OK);
  ck_assert_str_eq(err.msg, "mem.obj:4: face with 2 vertices (at least 3 needed)");

  /* An empty text is an empty model. */
  ck_assert_int_eq(zs_obj_parse("", 0, "empty.obj", NULL, &m, &err), ZS_OK);
  ck_assert_int_eq(m.mesh.nverts, 0);
  ck_assert_int_eq(m.mesh.nfaces, 0);
  zs_model_free(&m);
}
END_TEST

/* ---- errors ----------------------------------------------------------- */

/* Each bad file, the file the message names (the OBJ unless said), and
 * the line it names. */
static const struct bad_case {
  const char *file;
  const char *blamed; /* NULL: file itself */
  long line;
  zs_status code;
} bad_cases[] = {
    {"bad_number.obj", NULL, 3, ZS_ERR_PARSE},
    {"nan.obj", NULL, 2, ZS_ERR_PARSE},
    {"inf.obj", NULL, 4, ZS_ERR_PARSE},
    {"overflow.obj", NULL, 2, ZS_ERR_PARSE},
    {"index_zero.obj", NULL, 5, ZS_ERR_PARSE},
    {"index_range.obj", NULL, 4, ZS_ERR_PARSE},
    {"neg_index_range.obj", NULL, 4, ZS_ERR_PARSE},
    {"huge_index.obj", NULL, 4, ZS_ERR_PARSE},
    {"forward_ref.obj", NULL, 3, ZS_ERR_PARSE},
    {"two_verts.obj", NULL, 5, ZS_ERR_PARSE},
    {"empty_face.obj", NULL, 5, ZS_ERR_PARSE},
    {"truncated.obj", NULL, 4, ZS_ERR_PARSE},
    {"slashes.obj", NULL, 4, ZS_ERR_PARSE},
    {"garbage.obj", NULL, 2, ZS_ERR_PARSE},
    {"missing_coord.obj", NULL, 2, ZS_ERR_PARSE},
    {"too_many_coords.obj", NULL, 1, ZS_ERR_PARSE},
    {"w_zero.obj", NULL, 2, ZS_ERR_PARSE},
    {"nul_byte.obj", NULL, 3, ZS_ERR_PARSE}, /* (not nul.obj: Windows' null device) */
    {"crlf.obj", NULL, 4, ZS_ERR_PARSE},
    {"no_newline.obj", NULL, 4, ZS_ERR_PARSE},
    {"usemtl_empty.obj", NULL, 2, ZS_ERR_PARSE},
    {"bad_kd.obj", "bad_kd.mtl", 4, ZS_ERR_PARSE},
};

START_TEST(obj_bad_files) {
  const struct bad_case *c = &bad_cases[_i];
  char rel[256], path[4096], dir[4096], prefix[4400];
  snprintf(dir, sizeof dir, "%s", zs_test_src("tests/data/bad_obj"));
  snprintf(rel, sizeof rel, "tests/data/bad_obj/%s", c->file);
  snprintf(path, sizeof path, "%s", zs_test_src(rel));
  snprintf(prefix, sizeof prefix, "%s/%s:%ld: ", dir,
           c->blamed ? c->blamed : c->file, c->line);
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  zs_status st = zs_obj_load(path, &m, &err);
  ck_assert_msg(st == c->code, "%s: status %d, message '%s'", c->file, st,
                err.msg);
  ck_assert_int_eq(err.code, c->code);
  ck_assert_msg(strncmp(err.msg, prefix, strlen(prefix)) == 0,
                "%s: message '%s' does not start with '%s'", c->file, err.msg,
                prefix);
  ck_assert_int_gt(strlen(err.msg), strlen(prefix)); /* a reason follows */
  ck_assert_int_eq(m.mesh.nverts, 0);
  ck_assert_int_eq(m.mesh.nfaces, 0);
  ck_assert_ptr_null(m.mesh.pos);
}
END_TEST

/* Unknown statements of other programs stay ignored (s, vp, an
 * exporter's own word), as every OBJ reader does. */
START_TEST(obj_unknown_statements_ignored) {
  static const char text[] = "# exported\nmtllib\tnone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                             "vp 0.5\ns 1\nmyexporter_tag 7\nf 1 2 3\n";
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_obj_parse(text, sizeof text - 1, "mem.obj", NULL, &m, &err) == ZS_OK, "%s",
                err.msg);
  ck_assert_int_eq(m.nsource_faces, 1);
  zs_model_free(&m);
}
END_TEST

/* A regular n-gon of radius r in the plane z = 0, or a star whose odd
 * corners sit at 0.9 r (concave); with fan, the same outline as n
 * triangles around the centre. */
static void write_ngon(const char *path, int n, int star, int fan) {
  FILE *f = fopen(path, "w");
  ck_assert_ptr_nonnull(f);
  for (int i = 0; i < n; i++) {
    double s, c;
    zs_sincos_turns((double)i / n, &s, &c);
    double r = star && i % 2 ? 0.9 : 1.0;
    fprintf(f, "v %.17g %.17g 0\n", r * c, r * s);
  }
  if (fan) {
    fprintf(f, "v 0 0 0\n");
    for (int i = 0; i < n; i++) fprintf(f, "f %d %d %d\n", n + 1, i + 1, (i + 1) % n + 1);
  } else {
    fputs("f", f);
    for (int i = 0; i < n; i++) fprintf(f, " %d", i + 1);
    fputs("\n", f);
  }
  ck_assert_int_eq(fclose(f), 0);
}

/* render --stats of path: the image hash, and the face count. */
static void render_hash(const char *path, const char *algo, char hash[17], long *faces) {
  const char *args[] = {"render", path, "--algo", algo, "--eye", "0,0,3", "--target", "0,0,0",
                        "--size", "320x240", "--stats", "-o", zs_test_bin("ngon.png"), NULL};
  static char out[1 << 14], err[1 << 12];
  ck_assert_msg(zs_test_run_zscan(args, out, sizeof out, err, sizeof err) == 0, "%s", err);
  const char *h = strstr(out, "\"image_hash\":\""), *fc = strstr(out, "\"faces\":");
  ck_assert_ptr_nonnull(h);
  ck_assert_ptr_nonnull(fc);
  memcpy(hash, h + 14, 16);
  hash[16] = '\0';
  *faces = strtol(fc + 8, NULL, 10);
}

/* A face of 10,000 corners, convex (a disc) and concave (a star): the
 * pixels of the same outline drawn as 10,000 triangles, in both modes. */
START_TEST(obj_faces_of_any_size) {
  enum { N = 10000 };
  static const char *const algos[2] = {"zbuffer", "scanline"};
  for (int star = 0; star < 2; star++) {
    char one[4096], fan[4096];
    snprintf(one, sizeof one, "%s", zs_test_bin(star ? "star-10000.obj" : "disc-10000.obj"));
    snprintf(fan, sizeof fan, "%s", zs_test_bin(star ? "star-fan.obj" : "disc-fan.obj"));
    write_ngon(one, N, star, 0);
    write_ngon(fan, N, star, 1);
    zs_model m;
    zs_error err;
    zs_error_clear(&err);
    ck_assert_msg(zs_obj_load(one, &m, &err) == ZS_OK, "%s", err.msg);
    ck_assert_int_eq(m.nsource_faces, 1);
    for (int32_t f = 0; f < m.mesh.nfaces; f++) {
      ck_assert_int_le(m.mesh.face_start[f + 1] - m.mesh.face_start[f], ZS_MAX_POLY_VERTS);
      ck_assert_int_eq(m.mesh.face_id[f], 0);
    }
    zs_model_free(&m);
    for (int a = 0; a < 2; a++) {
      char h1[17], h2[17];
      long f1, f2;
      render_hash(one, algos[a], h1, &f1);
      render_hash(fan, algos[a], h2, &f2);
      ck_assert_int_eq(f1, 1);
      ck_assert_int_eq(f2, N);
      ck_assert_msg(strcmp(h1, h2) == 0, "%s %s: one face %s, fan %s", star ? "star" : "disc",
                    algos[a], h1, h2);
    }
  }
}
END_TEST

/* Some messages in full. */
START_TEST(obj_messages) {
  static const struct {
    const char *text, *msg;
  } cases[] = {
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
       "mem.obj:4: vertex index 4 out of range (3 vertices so far)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n",
       "mem.obj:4: vertex index -4 out of range (3 vertices so far)"},
      {"v 0 0 0\nf 0 1 1\n", "mem.obj:2: vertex index 0 (indices start at 1)"},
      {"v 1.0abc 0 0\n", "mem.obj:1: expected a number, got '1.0abc'"},
      {"v 0x10 0 0\n", "mem.obj:1: expected a number, got '0x10'"},
      {"v 0 0 NaN\n", "mem.obj:1: not a finite number: 'NaN'"},
      {"v 1 2\n", "mem.obj:1: expected x y z [w] (or x y z r g b), got 2 numbers"},
      {"v 0 0 0\nf 1/ 1 1\n", "mem.obj:2: truncated face vertex '1/'"},
      {"v 0 0 0\nf 1//x 1 1\n", "mem.obj:2: bad face vertex '1//x'"},
      {"\n\nmtllib\n", "mem.obj:3: expected a file name"},
      /* not an OBJ: a control byte, a line that starts with no word, or
       * mostly unknown words (another text) */
      {"v 0 0 0\n\x01\x02zz\n", "mem.obj:2: not an OBJ statement"},
      {"v 0 0 0\nv 1 0 0\x1b[0m\n", "mem.obj:2: not an OBJ statement"},
      {"{\"cases\": []}\n", "mem.obj:1: not an OBJ statement"},
      {"# notes\nhello world\nthis is a readme\nv 0 0 0\n", "mem.obj:2: not an OBJ statement"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    zs_error err;
    ck_assert_int_eq(parse_bad(cases[i].text, strlen(cases[i].text), &err),
                     ZS_ERR_PARSE);
    ck_assert_str_eq(err.msg, cases[i].msg);
  }
}
END_TEST

/* A line longer than ZS_OBJ_LINE_MAX is refused, also without a newline;
 * generated here rather than kept in the source tree. */
START_TEST(obj_overlong_line) {
  size_t len = ZS_OBJ_LINE_MAX + 20;
  char *text = malloc(len);
  ck_assert_ptr_nonnull(text);
  memcpy(text, "v 0 0 0\n#", 9);
  memset(text + 9, 'x', len - 10);
  text[len - 1] = '\n';
  char path[4096], prefix[4200];
  snprintf(path, sizeof path, "%s", zs_test_bin("test_obj_overlong.obj"));
  write_file(path, text, len);
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_obj_load(path, &m, &err), ZS_ERR_LIMIT);
  snprintf(prefix, sizeof prefix, "%s:2: line longer than", path);
  ck_assert_msg(strncmp(err.msg, prefix, strlen(prefix)) == 0, "%s", err.msg);
  remove(path);

  /* The same without the final newline, in memory. */
  ck_assert_int_eq(parse_bad(text, len - 1, &err), ZS_ERR_LIMIT);
  ck_assert_str_eq(err.msg, "mem.obj:2: line longer than 65536 bytes");
  free(text);
}
END_TEST

START_TEST(obj_cannot_open) {
  char path[4096], prefix[4200];
  snprintf(path, sizeof path, "%s",
           zs_test_src("tests/data/obj/no_such_file.obj"));
  snprintf(prefix, sizeof prefix, "%s: cannot open: ", path);
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_obj_load(path, &m, &err), ZS_ERR_IO);
  ck_assert_msg(strncmp(err.msg, prefix, strlen(prefix)) == 0, "%s", err.msg);
  ck_assert_int_eq(m.mesh.nverts, 0);
}
END_TEST

/* ---- attributes and materials ----------------------------------------- */

/* The attribute vertex of corner i of face f. */
static int32_t attr_at(const zs_model *m, int32_t f, int i) {
  return m->mesh.corner_attr[m->mesh.face_start[f] + i];
}

static void assert_normal(const zs_model *m, int32_t a, float x, float y, float z) {
  ck_assert_int_ge(a, 0);
  ck_assert_int_lt(a, m->mesh.nattrs);
  const float *n = m->mesh.normal + 3 * a;
  ck_assert_msg(n[0] == x && n[1] == y && n[2] == z,
                "attr %d: normal (%.9g %.9g %.9g), want (%g %g %g)", a, n[0], n[1], n[2], x, y, z);
}

static void assert_no_attributes(const zs_model *m) {
  ck_assert_int_eq(m->mesh.nattrs, 0);
  ck_assert_ptr_null(m->mesh.corner_attr);
  ck_assert_ptr_null(m->mesh.normal);
  ck_assert_ptr_null(m->mesh.color);
  ck_assert_ptr_null(m->mesh.uv);
}

/* Files without vt, vn or vertex colours make no attribute arrays (with
 * materials: materials only), so they draw exactly as before; vt and vn
 * lines that no face names make none either. */
START_TEST(obj_no_attribute_arrays) {
  zs_model m;
  parse_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1 2 3\n", &m);
  assert_no_attributes(&m);
  ck_assert_ptr_null(m.mesh.face_material);
  ck_assert_int_eq(m.mesh.nmaterials, 0);
  ck_assert_int_eq(m.ntextures, 0);
  zs_model_free(&m);

  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_obj_load(zs_test_src("tests/data/obj/colors.obj"), &m, &err) == ZS_OK, "%s",
                err.msg);
  assert_no_attributes(&m);
  /* red, clamped, single, nokd, nosuch, late; then the grey of the face
   * before any usemtl */
  ck_assert_int_eq(m.mesh.nmaterials, 7);
  int32_t want[8] = {6, 0, 1, 2, 3, 4, 5, 0};
  for (int f = 0; f < 8; f++) ck_assert_int_eq(m.mesh.face_material[f], want[f]);
  const zs_material *red = &m.mesh.materials[0], *nokd = &m.mesh.materials[3];
  ck_assert(red->base[0] == 255 && red->base[1] == 0 && red->base[2] == 0 && red->base[3] == 255);
  ck_assert(red->specular[0] == 128 && red->specular[1] == 128 && red->specular[2] == 128);
  ck_assert(nokd->base[0] == 0xB4 && nokd->shininess == 10);
  ck_assert_int_eq(m.mesh.materials[6].base[0], 0xB4);
  for (int i = 0; i < 7; i++) ck_assert_int_eq(m.mesh.materials[i].double_sided, 1);
  zs_model_free(&m);

  /* Faces after every usemtl: no extra material. */
  parse_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 1 2 3\nusemtl a\nf 1 2 3\n",
           &m);
  assert_no_attributes(&m);
  ck_assert_int_eq(m.mesh.nmaterials, 2);
  int32_t want2[3] = {0, 1, 0};
  for (int f = 0; f < 3; f++) ck_assert_int_eq(m.mesh.face_material[f], want2[f]);
  zs_model_free(&m);

  /* A usemtl after the last face: that face gets a grey material of its
   * own, not material 0. */
  parse_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nusemtl a\n", &m);
  ck_assert_int_eq(m.mesh.nmaterials, 2);
  ck_assert_int_eq(m.mesh.face_material[0], 1);
  zs_model_free(&m);
}
END_TEST

/* tests/data/obj/attributes.obj: an attribute vertex per distinct (vt,
 * vn, coloured vertex), in the order of first use; colours clamped to
 * 0 .. 1 and rounded; a vertex without colour is white; vt's w ignored,
 * its missing v 0; the normals as written (any length). */
START_TEST(obj_attributes) {
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_obj_load(zs_test_src("tests/data/obj/attributes.obj"), &m, &err) == ZS_OK,
                "%s", err.msg);
  ck_assert_int_eq(m.mesh.nfaces, 3);
  ck_assert_int_eq(m.mesh.nattrs, 8);
  ck_assert_ptr_nonnull(m.mesh.corner_attr);
  ck_assert_ptr_nonnull(m.mesh.normal);
  ck_assert_ptr_nonnull(m.mesh.color);
  ck_assert_ptr_nonnull(m.mesh.uv);
  ck_assert_ptr_null(m.mesh.face_material);
  static const int32_t corners[3][3] = {{0, 1, 2}, {0, 3, 4}, {5, 6, 7}};
  static const int32_t verts[3][3] = {{0, 1, 2}, {0, 2, 3}, {0, 1, 2}};
  for (int f = 0; f < 3; f++)
    for (int i = 0; i < 3; i++) {
      ck_assert_int_eq(attr_at(&m, f, i), corners[f][i]);
      ck_assert_int_eq(face_vert(&m, f, i), verts[f][i]);
    }
  static const float normal[8][3] = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 2},
                                     {0, 0, 2}, {0, 0, 2}, {0, 0, 1}, {0, 0, 2}};
  static const uint8_t color[8][4] = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255},
                                      {0, 0, 255, 255}, {255, 255, 255, 255}, {255, 0, 0, 255},
                                      {0, 255, 0, 255}, {0, 0, 255, 255}};
  static const float uv[8][2] = {{0, 0}, {1, 0}, {1, 1}, {1, 1}, {0.25f, 0}, {0.25f, 0},
                                 {1, 1}, {1, 0}};
  for (int a = 0; a < 8; a++) {
    assert_normal(&m, a, normal[a][0], normal[a][1], normal[a][2]);
    ck_assert_msg(memcmp(m.mesh.color + 4 * a, color[a], 4) == 0, "attr %d: colour", a);
    ck_assert_msg(m.mesh.uv[2 * a] == uv[a][0] && m.mesh.uv[2 * a + 1] == uv[a][1],
                  "attr %d: uv %g %g", a, m.mesh.uv[2 * a], m.mesh.uv[2 * a + 1]);
  }
  zs_model_free(&m);
}
END_TEST

/* The texels of tests/data/obj/textured/checker.png (made by a few lines
 * of Python with zlib and struct). */
static void checker_texel(int x, int y, uint8_t out[4]) {
  out[0] = (uint8_t)(80 * x);
  out[1] = (uint8_t)(80 * y);
  out[2] = (uint8_t)(255 - 30 * (x + y));
  out[3] = (uint8_t)(255 - 10 * x);
}

static void assert_material(const zs_material *mat, const uint8_t base[4], const uint8_t spec[3],
                            const uint8_t emis[3], int shininess, zs_wrap wrap,
                            const zs_texture *tex) {
  ck_assert_msg(memcmp(mat->base, base, 4) == 0, "base %d %d %d %d", mat->base[0], mat->base[1],
                mat->base[2], mat->base[3]);
  ck_assert_msg(memcmp(mat->specular, spec, 3) == 0, "specular %d %d %d", mat->specular[0],
                mat->specular[1], mat->specular[2]);
  ck_assert_msg(memcmp(mat->emissive, emis, 3) == 0, "emissive %d %d %d", mat->emissive[0],
                mat->emissive[1], mat->emissive[2]);
  ck_assert_int_eq(mat->shininess, shininess);
  ck_assert_int_eq(mat->double_sided, 1);
  ck_assert_int_eq(mat->wrap_s, wrap);
  ck_assert_int_eq(mat->wrap_t, wrap);
  ck_assert_int_eq(mat->filter, ZS_FILTER_DEFAULT);
  ck_assert_ptr_eq(mat->base_texture, tex);
}

/* tests/data/obj/textured.obj: every MTL statement read, one texture for
 * two materials (relative to the library's folder), texture coordinates
 * without normals: normals computed (the square is flat: all (0, 0, 1)),
 * the corners without vt given vertices of their own. */
START_TEST(obj_textured) {
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_obj_load(zs_test_src("tests/data/obj/textured.obj"), &m, &err) == ZS_OK, "%s",
                err.msg);
  ck_assert_int_eq(m.mesh.nfaces, 5);
  ck_assert_int_eq(m.ntextures, 1);
  const zs_texture *tex = m.textures[0];
  ck_assert_int_eq(zs_texture_width(tex), 4);
  ck_assert_int_eq(zs_texture_height(tex), 4);
  int w, h;
  const uint8_t *texels = zs_texture_level(tex, 0, &w, &h);
  for (int y = 0; y < 4; y++)
    for (int x = 0; x < 4; x++) {
      uint8_t want[4];
      checker_texel(x, y, want);
      ck_assert_msg(memcmp(texels + 4 * (4 * y + x), want, 4) == 0, "texel %d %d", x, y);
    }

  /* wood, glass, plain, nosuch, and the grey of the face before usemtl */
  ck_assert_int_eq(m.mesh.nmaterials, 5);
  int32_t fm[5] = {4, 0, 1, 2, 3};
  uint32_t rgb[5] = {ZS_GREY, 0xCC9966, 0xFFFFFF, 0x336699, ZS_GREY};
  for (int f = 0; f < 5; f++) {
    ck_assert_int_eq(m.mesh.face_material[f], fm[f]);
    ck_assert_uint_eq(m.mesh.face_rgb[f], rgb[f]);
  }
  static const uint8_t none[3] = {0, 0, 0}, half[3] = {128, 128, 128}, blue[3] = {0, 0, 51};
  static const uint8_t wood[4] = {204, 153, 102, 128}, glass[4] = {255, 255, 255, 191},
                       plain[4] = {51, 102, 153, 255}, grey[4] = {0xB4, 0xB4, 0xB4, 255};
  const zs_material *mat = m.mesh.materials;
  assert_material(&mat[0], wood, half, blue, 97, ZS_WRAP_CLAMP, tex); /* d wins over Tr */
  assert_material(&mat[1], glass, none, none, ZS_MAX_SHININESS, ZS_WRAP_REPEAT, tex);
  assert_material(&mat[2], plain, none, none, 0, ZS_WRAP_REPEAT, NULL);
  assert_material(&mat[3], grey, none, none, 0, ZS_WRAP_REPEAT, NULL);
  assert_material(&mat[4], grey, none, none, 0, ZS_WRAP_REPEAT, NULL);

  /* vt 1 .. 4 are vertices 0 .. 3, given the normal; the corners of
   * faces 0, 3 and 4 (no vt) share one new vertex per position */
  static const int32_t attrs[5][4] = {{4, 5, 6}, {0, 1, 2, 3}, {0, 1, 2}, {4, 6, 7}, {4, 5, 6}};
  ck_assert_int_eq(m.mesh.nattrs, 8);
  for (int f = 0; f < 5; f++)
    for (int i = 0; i < face_size(&m, f); i++) ck_assert_int_eq(attr_at(&m, f, i), attrs[f][i]);
  static const float uv[8][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}, {0, 0}, {0, 0}, {0, 0}};
  for (int a = 0; a < 8; a++) {
    assert_normal(&m, a, 0, 0, 1);
    ck_assert(m.mesh.uv[2 * a] == uv[a][0] && m.mesh.uv[2 * a + 1] == uv[a][1]);
  }
  ck_assert_ptr_null(m.mesh.color);
  zs_model_free(&m);
}
END_TEST

/* A texture that cannot be opened is an error at its map_Kd line, naming
 * the file as the library writes it; with ZS_OBJ_SKIP_MISSING_TEXTURES
 * the material is left untextured, and the model's notes hold that
 * message and ": drawn without it". */
START_TEST(obj_missing_texture) {
  char path[4096], want[4400];
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/obj/missing_texture.obj"));
  snprintf(want, sizeof want,
           "%s: map_Kd nothing here.png: cannot open: No such file or directory",
           zs_test_src("tests/data/obj/missing_texture.mtl:4"));
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_obj_load(path, &m, &err), ZS_ERR_IO);
  ck_assert_str_eq(err.msg, want);
  ck_assert_ptr_null(m.mesh.pos);
  ck_assert_ptr_null(m.materials);
  ck_assert_ptr_null(m.notes.text);

  zs_error_clear(&err);
  ck_assert_msg(zs_obj_load_flags(path, ZS_OBJ_SKIP_MISSING_TEXTURES, &m, &err) == ZS_OK, "%s",
                err.msg);
  strcat(want, ": drawn without it\n");
  ck_assert_str_eq(m.notes.text, want);
  ck_assert_int_eq(m.notes.len, (int)strlen(want));
  ck_assert_int_eq(m.mesh.nmaterials, 1);
  ck_assert_ptr_null(m.mesh.materials[0].base_texture);
  ck_assert_int_eq(m.ntextures, 0);
  ck_assert_uint_eq(m.mesh.face_rgb[0], 0xFF0000);
  assert_no_attributes(&m);
  zs_model_free(&m);
}
END_TEST

/* Writes NAME.obj and NAME.mtl (mtl NULL: none) in the build tree and
 * loads the OBJ with flags; returns the status, err the message. */
static zs_status load_pair(const char *name, const char *obj, const char *mtl, int flags,
                           zs_model *m, zs_error *err) {
  char path[4096], file[256];
  snprintf(file, sizeof file, "%s.mtl", name);
  if (mtl) {
    snprintf(path, sizeof path, "%s", zs_test_bin(file));
    write_file(path, mtl, strlen(mtl));
  }
  snprintf(file, sizeof file, "%s.obj", name);
  snprintf(path, sizeof path, "%s", zs_test_bin(file));
  write_file(path, obj, strlen(obj));
  zs_error_clear(err);
  return zs_obj_load_flags(path, flags, m, err);
}

/* The errors of libraries and textures in full (the path of the build
 * tree cut off). */
START_TEST(obj_mtl_messages) {
  static const char obj[] = "mtllib mtlerr.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
  static const struct {
    const char *mtl, *msg;
    zs_status code;
  } cases[] = {
      {"newmtl a\nKs 1 2\n", "mtlerr.mtl:2: Ks takes 1 or 3 numbers", ZS_ERR_PARSE},
      {"newmtl a\nKe 1 0 0 1\n", "mtlerr.mtl:2: Ke takes 1 or 3 numbers", ZS_ERR_PARSE},
      {"newmtl a\nNs 1 2\n", "mtlerr.mtl:2: Ns takes 1 number", ZS_ERR_PARSE},
      {"newmtl a\nNs nan\n", "mtlerr.mtl:2: not a finite number: 'nan'", ZS_ERR_PARSE},
      {"d 0.5\nnewmtl a\n", "mtlerr.mtl:1: d before newmtl", ZS_ERR_PARSE},
      {"newmtl a\nd -halo\n", "mtlerr.mtl:2: expected a number", ZS_ERR_PARSE},
      {"newmtl a\nTr x\n", "mtlerr.mtl:2: expected a number, got 'x'", ZS_ERR_PARSE},
      {"newmtl a\nmap_Kd\n", "mtlerr.mtl:2: map_Kd: expected a file name", ZS_ERR_PARSE},
      {"newmtl a\nmap_Kd -s 1 2\n", "mtlerr.mtl:2: map_Kd: expected a file name", ZS_ERR_PARSE},
      {"newmtl a\nmap_Kd -foo 1 a.png\n", "mtlerr.mtl:2: map_Kd: unknown option '-foo'",
       ZS_ERR_PARSE},
      {"newmtl a\nmap_Kd -clamp maybe a.png\n",
       "mtlerr.mtl:2: map_Kd: -clamp takes on or off, got 'maybe'", ZS_ERR_PARSE},
      {"newmtl a\nmap_Kd -s\n", "mtlerr.mtl:2: map_Kd: option -s needs a value", ZS_ERR_PARSE},
      {"newmtl a\n\nmap_Kd mtlerr.obj\n",
       "mtlerr.mtl:3: map_Kd mtlerr.obj: not a PNG or JPEG image", ZS_ERR_PARSE},
      {"newmtl a\nmap_Kd -o 1 -clamp off nope.png\n",
       "mtlerr.mtl:2: map_Kd nope.png: cannot open: No such file or directory", ZS_ERR_IO},
  };
  char dir[4096];
  snprintf(dir, sizeof dir, "%s", zs_test_bin(""));
  size_t dlen = strlen(dir);
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    zs_model m;
    zs_error err;
    ck_assert_int_eq(load_pair("mtlerr", obj, cases[i].mtl, 0, &m, &err), cases[i].code);
    ck_assert_msg(strncmp(err.msg, dir, dlen) == 0, "%s", err.msg);
    ck_assert_str_eq(err.msg + dlen + (dir[dlen - 1] != '/'), cases[i].msg);
    ck_assert_ptr_null(m.mesh.pos);
  }
  /* A texture that is there but corrupt is an error with the flag too. */
  zs_model m;
  zs_error err;
  ck_assert_int_eq(load_pair("mtlerr", obj, "newmtl a\nmap_Kd mtlerr.obj\n",
                             ZS_OBJ_SKIP_MISSING_TEXTURES, &m, &err),
                   ZS_ERR_PARSE);
  /* A missing file is noted once, at the first material that names it,
   * with the control bytes of its name blanked: one line. */
  static const char two[] = "mtllib mtlerr.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n"
                            "usemtl b\nf 3 2 1\n";
  ck_assert_msg(load_pair("mtlerr", two,
                          "newmtl a\nmap_Kd no\x01pe.png\nnewmtl b\nmap_Kd no\x01pe.png\n",
                          ZS_OBJ_SKIP_MISSING_TEXTURES, &m, &err) == ZS_OK, "%s", err.msg);
  ck_assert_msg(strncmp(m.notes.text, dir, dlen) == 0, "%s", m.notes.text);
#ifdef _WIN32
  const char *why = "Invalid argument"; /* (Windows refuses a control byte in a name) */
#else
  const char *why = "No such file or directory";
#endif
  char want[256];
  snprintf(want, sizeof want, "mtlerr.mtl:2: map_Kd no pe.png: cannot open: %s: drawn without it\n",
           why);
  ck_assert_str_eq(m.notes.text + dlen + (dir[dlen - 1] != '/'), want);
  ck_assert_int_eq(m.mesh.nmaterials, 2);
  ck_assert_ptr_null(m.mesh.materials[0].base_texture);
  ck_assert_ptr_null(m.mesh.materials[1].base_texture);
  zs_model_free(&m);
  /* A texture used by no face is not read. */
  ck_assert_int_eq(load_pair("mtlerr", obj, "newmtl a\nnewmtl b\nmap_Kd nope.png\n", 0, &m, &err),
                   ZS_OK);
  ck_assert_int_eq(m.ntextures, 0);
  assert_no_attributes(&m);
  zs_model_free(&m);
}
END_TEST

/* A textured face without vt or vn still gets normals (and so attribute
 * vertices), and a path with Windows' backslashes finds its file. */
START_TEST(obj_texture_without_vt) {
  char png[4096], mtl[4400];
  snprintf(png, sizeof png, "%s", zs_test_src("tests/data/obj/textured/checker.png"));
  snprintf(mtl, sizeof mtl, "newmtl a\nmap_Kd %s\n", png);
  for (char *c = strstr(mtl, "textured/checker"); c; c = NULL) c[8] = '\\';
  zs_model m;
  zs_error err;
  ck_assert_msg(load_pair("texnovt", "mtllib texnovt.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\n"
                          "f 1 2 3\n", mtl, 0, &m, &err) == ZS_OK, "%s", err.msg);
  ck_assert_int_eq(m.ntextures, 1);
  ck_assert_ptr_eq(m.mesh.materials[0].base_texture, m.textures[0]);
  ck_assert_int_eq(m.mesh.nattrs, 3);
  for (int i = 0; i < 3; i++) {
    ck_assert_int_eq(attr_at(&m, 0, i), i);
    assert_normal(&m, i, 0, 0, 1);
  }
  ck_assert_ptr_null(m.mesh.uv);
  zs_model_free(&m);
}
END_TEST

/* Messages of vn, vt, vertex colours and face indices in full. */
START_TEST(obj_attribute_messages) {
  static const struct {
    const char *text, *msg;
  } cases[] = {
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\nf 1//1 2//2 3//5\n",
       "mem.obj:7: normal index 5 out of range (3 normals so far)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//-2 2//1 3//1\n",
       "mem.obj:5: normal index -2 out of range (1 normals so far)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n",
       "mem.obj:4: normal index 1 out of range (0 normals so far)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//0 2//1 3//1\n",
       "mem.obj:5: normal index 0 (indices start at 1)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nf 1/1 2/2 3/3\n",
       "mem.obj:6: texture coordinate index 3 out of range (2 texture coordinates so far)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/-1 2/-2 3/1\n",
       "mem.obj:5: texture coordinate index -2 out of range (1 texture coordinates so far)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/0/1 2/1/1 3/1/1\n",
       "mem.obj:6: texture coordinate index 0 (indices start at 1)"},
      /* the vertex is checked first */
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 4/9/9 2 3\n",
       "mem.obj:4: vertex index 4 out of range (3 vertices so far)"},
      {"vn 0 nan 1\n", "mem.obj:1: not a finite number: 'nan'"},
      {"vt inf 0\n", "mem.obj:1: not a finite number: 'inf'"},
      {"v 0 0 0\nv 1 0 0 0.5 NaN 0\n", "mem.obj:2: not a finite number: 'NaN'"},
      {"vn 0 1\n", "mem.obj:1: expected x y z, got 2 numbers"},
      {"vn 0 1 0 1\n", "mem.obj:1: expected x y z, got more than 3 numbers"},
      {"vt\n", "mem.obj:1: expected u [v [w]], got 0 numbers"},
      {"vt 0 0 0 0\n", "mem.obj:1: expected u [v [w]], got more than 3 numbers"},
      {"vt 1e300 0\n", "mem.obj:1: texture coordinate out of range: '1e300'"},
      {"vn 0 0 x\n", "mem.obj:1: expected a number, got 'x'"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    zs_error err;
    ck_assert_int_eq(parse_bad(cases[i].text, strlen(cases[i].text), &err), ZS_ERR_PARSE);
    ck_assert_str_eq(err.msg, cases[i].msg);
  }
}
END_TEST

/* vn beyond the range of a float keeps its direction; a zero vn is none
 * and gets a computed normal, as do the corners without vn. */
START_TEST(obj_partial_normals) {
  zs_model m;
  parse_ok("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 1e300 0 1e300\nvn 0 0 0\n"
           "f 1//1 2//1 3//2\nf 1 3 4\n",
           &m);
  ck_assert_int_eq(m.mesh.nfaces, 2);
  const float *n0 = m.mesh.normal + 3 * attr_at(&m, 0, 0);
  ck_assert(n0[0] > 0 && n0[0] == n0[2] && n0[1] == 0 && isfinite(n0[0]));
  ck_assert_int_eq(attr_at(&m, 0, 0), attr_at(&m, 0, 1));
  /* vn 2 (zero): computed in place, the plane's (0, 0, 1) */
  assert_normal(&m, attr_at(&m, 0, 2), 0, 0, 1);
  ck_assert_int_eq(attr_at(&m, 0, 2), 1);
  for (int i = 0; i < 3; i++) assert_normal(&m, attr_at(&m, 1, i), 0, 0, 1);
  /* face 1's corners get new vertices, even at position 2 where vertex
   * 1 took the same normal: corners of different sources never share */
  ck_assert_int_eq(m.mesh.nattrs, 5);
  zs_model_free(&m);
}
END_TEST

/* A cube with a colour per vertex (as MeshLab writes it): three normals
 * per corner position, so 24 attribute vertices, each keeping the colour
 * of its position. */
START_TEST(obj_coloured_cube) {
  static const char text[] =
      "v 0 0 0 0 0 0\nv 1 0 0 1 0 0\nv 0 1 0 0 1 0\nv 1 1 0 1 1 0\n"
      "v 0 0 1 0 0 1\nv 1 0 1 1 0 1\nv 0 1 1 0 1 1\nv 1 1 1 1 1 1\n"
      "f 1 5 7 3\nf 2 4 8 6\nf 1 2 6 5\nf 3 7 8 4\nf 1 3 4 2\nf 5 6 8 7\n";
  zs_model m;
  parse_ok(text, &m);
  ck_assert_int_eq(m.mesh.nfaces, 6);
  ck_assert_int_eq(m.mesh.nattrs, 24);
  static const float axis[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0},
                                   {0, 1, 0},  {0, 0, -1}, {0, 0, 1}};
  int used[24] = {0};
  for (int f = 0; f < 6; f++) {
    for (int i = 0; i < 4; i++) {
      int32_t a = attr_at(&m, f, i), v = face_vert(&m, f, i);
      assert_normal(&m, a, axis[f][0], axis[f][1], axis[f][2]);
      const uint8_t *c = m.mesh.color + 4 * a;
      ck_assert(c[0] == 255 * (v & 1) && c[1] == 255 * (v >> 1 & 1) && c[2] == 255 * (v >> 2) &&
                c[3] == 255);
      used[a]++;
    }
  }
  for (int a = 0; a < 24; a++) ck_assert_int_eq(used[a], 1);
  ck_assert_ptr_null(m.mesh.uv);
  zs_model_free(&m);
}
END_TEST

/* ---- normals ---------------------------------------------------------- */

/* The unit cube as 6 quads, counter-clockwise seen from outside. */
static void add_cube(zs_model *m) {
  for (int b = 0; b < 8; b++) zs_model_add_vertex(m, b & 1, b >> 1 & 1, b >> 2);
  static const int32_t quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                      {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (int f = 0; f < 6; f++) ck_assert_int_eq(zs_model_add_polygon(m, quads[f], 4, 0, -1), ZS_OK);
}

/* A cube keeps its edges: 3 normals at each of its 8 corners, exactly
 * its faces' axes; a second call has nothing to do. */
START_TEST(normals_cube) {
  zs_model m;
  zs_model_init(&m);
  add_cube(&m);
  ck_assert_int_eq(zs_model_compute_normals(&m, 60.0), 1);
  ck_assert_int_eq(m.mesh.nattrs, 24);
  static const float axis[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0},
                                   {0, 1, 0},  {0, 0, -1}, {0, 0, 1}};
  for (int f = 0; f < 6; f++)
    for (int i = 0; i < 4; i++)
      assert_normal(&m, attr_at(&m, f, i), axis[f][0], axis[f][1], axis[f][2]);
  /* numbered position by position: vertex 0's three first */
  ck_assert_int_eq(attr_at(&m, 0, 0), 0);
  ck_assert_int_eq(attr_at(&m, 2, 0), 1);
  ck_assert_int_eq(attr_at(&m, 4, 0), 2);
  ck_assert_ptr_null(m.mesh.color);
  ck_assert_ptr_null(m.mesh.uv);
  float before[72];
  memcpy(before, m.mesh.normal, sizeof before);
  ck_assert_int_eq(zs_model_compute_normals(&m, 60.0), 1);
  ck_assert_int_eq(m.mesh.nattrs, 24);
  ck_assert(memcmp(before, m.mesh.normal, sizeof before) == 0);
  zs_model_free(&m);

  /* Past 90 degrees the cube is smooth: one normal per corner, along
   * its diagonal. */
  zs_model_init(&m);
  add_cube(&m);
  ck_assert_int_eq(zs_model_compute_normals(&m, 90.5), 1);
  ck_assert_int_eq(m.mesh.nattrs, 8);
  const float *n = m.mesh.normal + 3 * attr_at(&m, 1, 3); /* vertex 5: +x, -y, +z */
  ck_assert(n[0] > 0.577f && n[0] < 0.5774f && n[1] == -n[0] && n[2] == n[0]);
  zs_model_free(&m);
}
END_TEST

/* A UV sphere of stacks x slices, triangles at the poles, quads between
 * (non-planar ones split by the model), centred at c with radius r. */
static void add_sphere(zs_model *m, int slices, int stacks, double r, const double c[3]) {
  int32_t top = zs_model_add_vertex(m, c[0], c[1] + r, c[2]);
  for (int i = 1; i < stacks; i++) {
    double sp, cp;
    zs_sincos_deg(180.0 * i / stacks, &sp, &cp);
    for (int j = 0; j < slices; j++) {
      double st, ct;
      zs_sincos_deg(360.0 * j / slices, &st, &ct);
      zs_model_add_vertex(m, c[0] + r * sp * ct, c[1] + r * cp, c[2] - r * sp * st);
    }
  }
  int32_t bottom = zs_model_add_vertex(m, c[0], c[1] - r, c[2]);
#define RING(i, j) (top + 1 + ((i) - 1) * slices + ((j) % slices))
  for (int j = 0; j < slices; j++) {
    int32_t t[3] = {top, RING(1, j), RING(1, j + 1)};
    ck_assert_int_eq(zs_model_add_polygon(m, t, 3, 0, -1), ZS_OK);
    int32_t b[3] = {bottom, RING(stacks - 1, j + 1), RING(stacks - 1, j)};
    ck_assert_int_eq(zs_model_add_polygon(m, b, 3, 0, -1), ZS_OK);
  }
  for (int i = 1; i + 1 < stacks; i++)
    for (int j = 0; j < slices; j++) {
      int32_t q[4] = {RING(i, j), RING(i + 1, j), RING(i + 1, j + 1), RING(i, j + 1)};
      ck_assert_int_eq(zs_model_add_polygon(m, q, 4, 0, -1), ZS_OK);
    }
#undef RING
}

/* A smooth sphere shares: one attribute vertex per position, of unit
 * length, close to the radius there. */
START_TEST(normals_sphere) {
  static const int sizes[3][3] = {{16, 8, 995}, {48, 24, 999}, {7, 5, 985}};
  for (int s = 0; s < 3; s++) {
    zs_model m;
    zs_model_init(&m);
    const double c[3] = {1e3, -2.0, 0.5};
    add_sphere(&m, sizes[s][0], sizes[s][1], 2.0, c);
    ck_assert_int_eq(zs_model_compute_normals(&m, 60.0), 1);
    ck_assert_int_eq(m.mesh.nattrs, m.mesh.nverts);
    int32_t *attr_of = malloc((size_t)m.mesh.nverts * sizeof *attr_of);
    for (int32_t v = 0; v < m.mesh.nverts; v++) attr_of[v] = -1;
    double worst = 1.0;
    for (int32_t k = 0; k < m.mesh.face_start[m.mesh.nfaces]; k++) {
      int32_t v = m.mesh.face_vert[k], a = m.mesh.corner_attr[k];
      ck_assert(attr_of[v] == -1 || attr_of[v] == a);
      attr_of[v] = a;
      const float *n = m.mesh.normal + 3 * a;
      const double *p = vertex(&m, v);
      double d = (n[0] * (p[0] - c[0]) + n[1] * (p[1] - c[1]) + n[2] * (p[2] - c[2])) / 2.0;
      if (d < worst) worst = d;
      ck_assert(fabs(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0) < 1e-6);
    }
    free(attr_of);
    /* area weighting tilts a coarse sphere's normals towards its larger
     * faces: 6 degrees at 7 x 5, 2 at 48 x 24 */
    ck_assert_msg(worst > sizes[s][2] / 1000.0, "%d x %d: cos %.9f from the radius", sizes[s][0],
                  sizes[s][1], worst);
    zs_model_free(&m);
  }
}
END_TEST

/* The Newell normal of mesh face f. */
static void newell(const zs_model *m, int32_t f, double n[3]) {
  n[0] = n[1] = n[2] = 0.0;
  int c = face_size(m, f);
  for (int i = 0; i < c; i++)
    zs_newell_add(n, vertex(m, face_vert(m, f, i)), vertex(m, face_vert(m, f, (i + 1) % c)));
}

static double dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* What the header says, the slow way: the normal of corner i of face f,
 * the sum over every face at its position that passes the crease test
 * (its own always), taken in face order, then normalised as the model
 * stores it (scaled to a largest component in [0.5, 1), divided by its
 * length, rounded to float). */
static void reference_normal(const zs_model *m, int32_t f, int i, double cos_crease, float out[3]) {
  int32_t v = face_vert(m, f, i);
  double nf[3], sum[3] = {0, 0, 0};
  newell(m, f, nf);
  for (int32_t g = 0; g < m->mesh.nfaces; g++) {
    int at = 0;
    for (int j = 0; j < face_size(m, g); j++) at |= face_vert(m, g, j) == v;
    double ng[3];
    newell(m, g, ng);
    if (!at || (ng[0] == 0 && ng[1] == 0 && ng[2] == 0)) continue;
    if (g != f && !(dot(nf, ng) >= cos_crease * sqrt(dot(nf, nf)) * sqrt(dot(ng, ng)))) continue;
    for (int k = 0; k < 3; k++) sum[k] += ng[k];
  }
  if (sum[0] == 0 && sum[1] == 0 && sum[2] == 0) memcpy(sum, nf, sizeof sum);
  double big = fmax(fabs(sum[0]), fmax(fabs(sum[1]), fabs(sum[2])));
  int e;
  frexp(big, &e);
  for (int k = 0; k < 3; k++) sum[k] = ldexp(sum[k], -e);
  double len = sqrt(dot(sum, sum));
  for (int k = 0; k < 3; k++) out[k] = (float)(sum[k] / len);
}

/* A bumpy grid of n x n quads (non-planar ones split), heights up to
 * bump, and a few zero-area faces. */
static void add_bumpy_grid(zs_model *m, zs_rng *rng, int n, double bump) {
  for (int y = 0; y <= n; y++)
    for (int x = 0; x <= n; x++) zs_model_add_vertex(m, x, y, zs_rng_range(rng, 0.0, bump));
  for (int y = 0; y < n; y++)
    for (int x = 0; x < n; x++) {
      int32_t a = y * (n + 1) + x, q[4] = {a, a + 1, a + n + 2, a + n + 1};
      ck_assert_int_eq(zs_model_add_polygon(m, q, 4, 0, -1), ZS_OK);
      if (zs_rng_below(rng, 10) == 0) {
        int32_t flat[3] = {a, a + 1, a}; /* zero area */
        ck_assert_int_eq(zs_model_add_polygon(m, flat, 3, 0, -1), ZS_OK);
      }
    }
}

/* Bit for bit what the header says, on random bumpy grids and spheres
 * at creases from none to all (both the exact crease test and the
 * shortcut for smooth positions); corners that end alike share. */
START_TEST(normals_reference) {
  static const double creases[] = {0.0, 0.05, 1.0, 20.0, 45.0, 60.0, 89.9, 120.0, 179.0, 179.5,
                                   180.0, 270.0, 1e9, -5.0};
  zs_rng rng;
  zs_rng_seed(&rng, 20261201);
  for (int trial = 0; trial < 60; trial++) {
    double crease = creases[trial % (sizeof creases / sizeof creases[0])];
    zs_model m;
    zs_model_init(&m);
    if (trial % 3 == 2) {
      const double c[3] = {zs_rng_range(&rng, -5, 5), 0.25, 3.0};
      add_sphere(&m, 5 + (int)zs_rng_below(&rng, 20), 3 + (int)zs_rng_below(&rng, 10), 1.5, c);
    } else {
      add_bumpy_grid(&m, &rng, 3 + (int)zs_rng_below(&rng, 10), trial % 3 ? 0.05 : 1.5);
    }
    ck_assert_int_eq(zs_model_compute_normals(&m, crease), 1);
    double s, cos_crease;
    zs_sincos_deg(crease < 0 ? 0 : crease > 180 ? 180 : crease, &s, &cos_crease);
    for (int32_t f = 0; f < m.mesh.nfaces; f++) {
      double nf[3];
      newell(&m, f, nf);
      for (int i = 0; i < face_size(&m, f); i++) {
        int32_t a = attr_at(&m, f, i);
        if (nf[0] == 0 && nf[1] == 0 && nf[2] == 0) {
          ck_assert_int_eq(a, -1); /* zero area: left alone */
          continue;
        }
        float want[3];
        reference_normal(&m, f, i, cos_crease, want);
        ck_assert_msg(a >= 0 && memcmp(m.mesh.normal + 3 * a, want, sizeof want) == 0,
                      "trial %d, crease %g, face %d corner %d: (%.9g %.9g %.9g), want (%.9g %.9g "
                      "%.9g)", trial, crease, f, i, m.mesh.normal[3 * a], m.mesh.normal[3 * a + 1],
                      m.mesh.normal[3 * a + 2], want[0], want[1], want[2]);
      }
    }
    /* corners of one position with the same normal share a vertex, and
     * a vertex serves one position */
    int32_t total = m.mesh.face_start[m.mesh.nfaces];
    int32_t *pos_of = malloc((size_t)m.mesh.nattrs * sizeof *pos_of);
    for (int32_t a = 0; a < m.mesh.nattrs; a++) pos_of[a] = -1;
    for (int32_t k = 0; k < total; k++) {
      int32_t a = m.mesh.corner_attr[k];
      if (a < 0) continue;
      ck_assert(pos_of[a] == -1 || pos_of[a] == m.mesh.face_vert[k]);
      pos_of[a] = m.mesh.face_vert[k];
      for (int32_t j = 0; j < k; j++) {
        int32_t b = m.mesh.corner_attr[j];
        if (b >= 0 && m.mesh.face_vert[j] == m.mesh.face_vert[k] &&
            memcmp(m.mesh.normal + 3 * a, m.mesh.normal + 3 * b, 3 * sizeof(float)) == 0)
          ck_assert_int_eq(a, b);
      }
    }
    for (int32_t a = 0; a < m.mesh.nattrs; a++) ck_assert_int_ge(pos_of[a], 0); /* none unused */
    free(pos_of);
    zs_model_free(&m);
  }
}
END_TEST

/* Existing attributes: a normal given is kept; a vertex without one that
 * corners of several positions share is given the first position's
 * normal and cloned for the others (colour and uv kept); attributes by
 * position (corner_attr NULL, nattrs == nverts) are read as such. */
START_TEST(normals_existing_attributes) {
  zs_model m;
  zs_model_init(&m);
  add_cube(&m);
  /* by position: vertex b's colour (b, 0, 0) */
  for (int b = 0; b < 8; b++) {
    uint8_t rgba[4] = {(uint8_t)b, 0, 0, 255};
    ck_assert_int_eq(zs_model_add_attr(&m, NULL, rgba, NULL), b);
  }
  ck_assert_ptr_null(m.mesh.corner_attr);
  ck_assert_int_eq(zs_model_compute_normals(&m, 60.0), 1);
  ck_assert_int_eq(m.mesh.nattrs, 24);
  for (int32_t f = 0; f < 6; f++)
    for (int i = 0; i < 4; i++) {
      int32_t a = attr_at(&m, f, i);
      ck_assert_int_eq(m.mesh.color[4 * a], face_vert(&m, f, i));
    }
  /* the first corner of each position keeps its own vertex */
  ck_assert_int_eq(attr_at(&m, 0, 0), 0);
  ck_assert_int_eq(attr_at(&m, 1, 0), 1);
  zs_model_free(&m);

  /* Two triangles folded along their diagonal 0-3 (by 37 degrees): one
   * has a uv vertex without normal at each corner, the other a normal
   * given but at one corner. */
  zs_model_init(&m);
  for (int i = 0; i < 4; i++) zs_model_add_vertex(&m, i & 1, i >> 1, i == 3 ? 0.5 : 0.0);
  const float uv[2] = {0.5f, 0.25f}, given[3] = {0, 1, 0};
  ck_assert_int_eq(zs_model_add_attr(&m, NULL, NULL, uv), 0);
  ck_assert_int_eq(zs_model_add_attr(&m, given, NULL, NULL), 1);
  int32_t t0[3] = {0, 1, 3}, a0[3] = {0, 0, 0}, t1[3] = {0, 3, 2}, a1[3] = {1, 1, -1};
  ck_assert_int_eq(zs_model_add_face(&m, t0, a0, 3, 0, -1, -1), ZS_OK);
  ck_assert_int_eq(zs_model_add_face(&m, t1, a1, 3, 0, -1, -1), ZS_OK);
  ck_assert_int_eq(zs_model_compute_normals(&m, 60.0), 1);
  /* vertex 0 at position 0 (both faces), again at 3 (the same sum, the
   * same bits); a clone at 1 (t0 alone); a new one at 2 (t1 alone) */
  static const int32_t want[2][3] = {{0, 2, 0}, {1, 1, 3}};
  for (int f = 0; f < 2; f++)
    for (int i = 0; i < 3; i++) ck_assert_int_eq(attr_at(&m, f, i), want[f][i]);
  ck_assert_int_eq(m.mesh.nattrs, 4);
  double s, c60;
  zs_sincos_deg(60.0, &s, &c60);
  float n[3];
  reference_normal(&m, 0, 0, c60, n);
  assert_normal(&m, 0, n[0], n[1], n[2]);
  reference_normal(&m, 0, 1, c60, n);
  assert_normal(&m, 2, n[0], n[1], n[2]);
  reference_normal(&m, 1, 2, c60, n);
  assert_normal(&m, 3, n[0], n[1], n[2]);
  assert_normal(&m, 1, 0, 1, 0);
  ck_assert(m.mesh.uv[4] == 0.5f && m.mesh.uv[5] == 0.25f); /* the clone's */
  ck_assert(m.mesh.uv[6] == 0 && m.mesh.uv[7] == 0);
  zs_model_free(&m);
}
END_TEST

/* A flat fan of many triangles about one position costs additions, not
 * their square: 200,000 triangles, one normal at the centre. */
START_TEST(normals_large_fan) {
  enum { N = 200000 };
  zs_model m;
  zs_model_init(&m);
  zs_model_add_vertex(&m, 0, 0, 0);
  for (int i = 0; i < N; i++) {
    double s, c;
    zs_sincos_turns((double)i / N, &s, &c);
    zs_model_add_vertex(&m, c, s, 0.0);
  }
  for (int i = 0; i < N; i++) {
    int32_t t[3] = {0, 1 + i, 1 + (i + 1) % N};
    ck_assert_int_eq(zs_model_add_polygon(&m, t, 3, 0, -1), ZS_OK);
  }
  ck_assert_int_eq(zs_model_compute_normals(&m, 60.0), 1);
  ck_assert_int_eq(m.mesh.nattrs, N + 1);
  for (int32_t f = 0; f < N; f += 997) assert_normal(&m, attr_at(&m, f, 0), 0, 0, 1);
  zs_model_free(&m);
}
END_TEST

static Suite *obj_suite(void) {
  Suite *s = suite_create("obj");
  TCase *model = tcase_create("model");
  tcase_add_test(model, model_basics);
  tcase_add_test(model, model_growth);
  tcase_add_test(model, model_random_polygons);
  suite_add_tcase(s, model);

  TCase *read = tcase_create("read");
  tcase_add_test(read, obj_counts);
  tcase_add_test(read, obj_face_formats);
  tcase_add_test(read, obj_negative_indices);
  tcase_add_test(read, obj_objects);
  tcase_add_test(read, obj_materials);
  tcase_add_test(read, obj_concave);
  tcase_add_test(read, obj_concave_tilted);
  tcase_add_test(read, obj_nonplanar);
  tcase_add_test(read, obj_pentagram);
  tcase_add_test(read, obj_degenerate);
  tcase_add_test(read, obj_lines);
  tcase_add_test(read, obj_unknown_statements_ignored);
  tcase_add_test(read, obj_faces_of_any_size);
  suite_add_tcase(s, read);

  TCase *attrs = tcase_create("attributes");
  tcase_add_test(attrs, obj_no_attribute_arrays);
  tcase_add_test(attrs, obj_attributes);
  tcase_add_test(attrs, obj_textured);
  tcase_add_test(attrs, obj_missing_texture);
  tcase_add_test(attrs, obj_mtl_messages);
  tcase_add_test(attrs, obj_texture_without_vt);
  tcase_add_test(attrs, obj_attribute_messages);
  tcase_add_test(attrs, obj_partial_normals);
  tcase_add_test(attrs, obj_coloured_cube);
  suite_add_tcase(s, attrs);

  TCase *normals = tcase_create("normals");
  tcase_add_test(normals, normals_cube);
  tcase_add_test(normals, normals_sphere);
  tcase_add_test(normals, normals_reference);
  tcase_add_test(normals, normals_existing_attributes);
  tcase_add_test(normals, normals_large_fan);
  suite_add_tcase(s, normals);

  TCase *bad = tcase_create("errors");
  tcase_add_loop_test(bad, obj_bad_files, 0,
                      (int)(sizeof bad_cases / sizeof bad_cases[0]));
  tcase_add_test(bad, obj_messages);
  tcase_add_test(bad, obj_overlong_line);
  tcase_add_test(bad, obj_cannot_open);
  suite_add_tcase(s, bad);
  return s;
}

int main(void) { return zs_test_run(obj_suite()); }
