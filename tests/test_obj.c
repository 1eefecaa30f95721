/* Tests of scene/model.c (polygon splitting, numbering) and scene/load_obj.c
 * (the OBJ reader and its error messages). */
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
    {"nul.obj", NULL, 3, ZS_ERR_PARSE},
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
