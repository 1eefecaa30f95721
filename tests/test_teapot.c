/* Checks of scene/teapot.c and the scenes built on it: the teapot's data,
 * counts, bounds, orientation and seams; the generated default scene and
 * cubes (scene/gen_default.c, gen_cubes.c); the box primitive. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "raster/raster.h"
#include "scene/gen_internal.h"
#include "scene/generate.h"
#include "scene/model.h"
#include "scene/scene.h"
#include "scene/teapot.h"
#include "tests/testutil.h"

/* ---- helpers ---- */

static void add_teapot(zs_model *m, int level, const double *xform) {
  zs_error err;
  zs_error_clear(&err);
  zs_model_init(m);
  int32_t obj = zs_model_object(m, "teapot");
  ck_assert_int_eq(obj, 0);
  zs_status st = zs_teapot_add(m, level, xform, 0x123456u, obj, &err);
  ck_assert_msg(st == ZS_OK, "zs_teapot_add: %s", err.msg);
}

/* Newell's normal of mesh face f (twice its vector area) and the average
 * of its corners. */
static void face_normal(const zs_mesh *me, int32_t f, double n[3],
                        double c[3]) {
  int32_t s = me->face_start[f], e = me->face_start[f + 1];
  for (int k = 0; k < 3; k++) n[k] = c[k] = 0.0;
  for (int32_t i = s; i < e; i++) {
    const double *a = me->pos + 3 * me->face_vert[i];
    const double *b = me->pos + 3 * me->face_vert[i + 1 < e ? i + 1 : s];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    for (int k = 0; k < 3; k++) c[k] += a[k];
  }
  for (int k = 0; k < 3; k++) c[k] /= (double)(e - s);
}

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The patch a teapot face came from: source faces go patch by patch. */
static int face_patch(const zs_model *m, int32_t f, int level) {
  return m->mesh.face_id[f] / (level * level);
}

/* ---- welding vertices by position, for the seam and edge checks ---- */

static const double *sort_pos;

static int cmp_by_pos(const void *pa, const void *pb) {
  const double *a = sort_pos + 3 * *(const int32_t *)pa;
  const double *b = sort_pos + 3 * *(const int32_t *)pb;
  for (int k = 0; k < 3; k++) {
    if (a[k] < b[k]) return -1;
    if (a[k] > b[k]) return 1;
  }
  return 0;
}

/* weld[v] = the smallest vertex index at exactly the position of v. */
static int32_t *weld_vertices(const zs_mesh *me) {
  int32_t n = me->nverts;
  int32_t *order = malloc(sizeof *order * (size_t)n);
  int32_t *weld = malloc(sizeof *weld * (size_t)n);
  ck_assert_ptr_nonnull(order);
  ck_assert_ptr_nonnull(weld);
  for (int32_t i = 0; i < n; i++) order[i] = i;
  sort_pos = me->pos;
  qsort(order, (size_t)n, sizeof *order, cmp_by_pos);
  for (int32_t i = 0; i < n;) {
    int32_t j = i, rep = order[i];
    while (j < n && cmp_by_pos(&order[i], &order[j]) == 0) {
      if (order[j] < rep) rep = order[j];
      j++;
    }
    for (int32_t k = i; k < j; k++) weld[order[k]] = rep;
    i = j;
  }
  free(order);
  return weld;
}

typedef struct edge {
  int32_t lo, hi; /* welded vertices, lo < hi */
  int forward;    /* 1 when the face runs lo -> hi */
} edge;

static int cmp_edge(const void *pa, const void *pb) {
  const edge *a = pa, *b = pb;
  if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
  if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
  return a->forward - b->forward;
}

typedef struct edge_stats {
  int boundary;     /* edges used by one face */
  int interior;     /* edges used by two faces in opposite directions */
  int inconsistent; /* two faces in the same direction */
  int nonmanifold;  /* more than two faces */
} edge_stats;

/* The edges of the welded mesh, zero-length ones left out. */
static edge_stats weld_edges(const zs_model *m) {
  const zs_mesh *me = &m->mesh;
  int32_t *weld = weld_vertices(me);
  int32_t total = me->face_start[me->nfaces];
  edge *edges = malloc(sizeof *edges * (size_t)(total > 0 ? total : 1));
  ck_assert_ptr_nonnull(edges);
  int32_t ne = 0;
  for (int32_t f = 0; f < me->nfaces; f++) {
    int32_t s = me->face_start[f], e = me->face_start[f + 1];
    for (int32_t i = s; i < e; i++) {
      int32_t a = weld[me->face_vert[i]];
      int32_t b = weld[me->face_vert[i + 1 < e ? i + 1 : s]];
      if (a == b) continue;
      edges[ne].lo = a < b ? a : b;
      edges[ne].hi = a < b ? b : a;
      edges[ne].forward = a < b;
      ne++;
    }
  }
  qsort(edges, (size_t)ne, sizeof *edges, cmp_edge);
  edge_stats st = {0, 0, 0, 0};
  for (int32_t i = 0; i < ne;) {
    int32_t j = i;
    while (j < ne && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi)
      j++;
    if (j - i == 1) st.boundary++;
    else if (j - i > 2) st.nonmanifold++;
    else if (edges[i].forward != edges[i + 1].forward) st.interior++;
    else st.inconsistent++;
    i = j;
  }
  free(edges);
  free(weld);
  return st;
}

/* ---- the data ---- */

/* The published table is symmetric: the rim, both body rings, both lid
 * parts and the bottom are four quarter turns of one patch about the axis,
 * the handle and the spout two mirror halves (y -> -y).  A typo in the
 * control points or the patches breaks one of these. */
START_TEST(test_data_symmetry) {
  /* Groups of four: first patch, direction of u seen from above (+1 counter-
   * clockwise: the next patch is a quarter turn +90 degrees about z). */
  static const int groups[][2] = {{0, -1}, {4, -1}, {8, -1},
                                  {20, -1}, {24, -1}, {28, +1}};
  for (size_t g = 0; g < sizeof groups / sizeof groups[0]; g++) {
    for (int q = 0; q < 4; q++) {
      int a[16], b[16];
      zs_teapot_patch(groups[g][0] + q, a);
      zs_teapot_patch(groups[g][0] + (q + 1) % 4, b);
      for (int k = 0; k < 16; k++) {
        double pa[3], pb[3];
        zs_teapot_control_point(a[k], pa);
        zs_teapot_control_point(b[k], pb);
        double turned[3] = {groups[g][1] < 0 ? pa[1] : -pa[1],
                            groups[g][1] < 0 ? -pa[0] : pa[0], pa[2]};
        for (int c = 0; c < 3; c++)
          ck_assert_msg(turned[c] == pb[c], "patch %d point %d axis %d",
                        groups[g][0] + q, k, c);
      }
    }
  }
  /* Mirror pairs: column s of one is column 3 - s of the other, y negated. */
  static const int pairs[][2] = {{12, 13}, {14, 15}, {16, 17}, {18, 19}};
  for (size_t i = 0; i < 4; i++) {
    int a[16], b[16];
    zs_teapot_patch(pairs[i][0], a);
    zs_teapot_patch(pairs[i][1], b);
    for (int r = 0; r < 4; r++)
      for (int s = 0; s < 4; s++) {
        double pa[3], pb[3];
        zs_teapot_control_point(a[4 * r + s], pa);
        zs_teapot_control_point(b[4 * r + 3 - s], pb);
        ck_assert(pa[0] == pb[0] && pa[1] == -pb[1] && pa[2] == pb[2]);
      }
  }
  /* Every point in range; exactly the four near the lid's pole unused. */
  int used[ZS_TEAPOT_CONTROL_POINTS] = {0};
  for (int p = 0; p < ZS_TEAPOT_PATCHES; p++) {
    int a[16];
    zs_teapot_patch(p, a);
    for (int k = 0; k < 16; k++) {
      ck_assert(a[k] >= 0 && a[k] < ZS_TEAPOT_CONTROL_POINTS);
      used[a[k]] = 1;
    }
  }
  int unused = 0;
  for (int c = 0; c < ZS_TEAPOT_CONTROL_POINTS; c++) {
    if (used[c]) continue;
    unused++;
    ck_assert(c == 204 || c == 205 || c == 215 || c == 222);
  }
  ck_assert_int_eq(unused, 4);
  /* A few landmarks of the published table (numbered from 1 there). */
  double p[3];
  zs_teapot_control_point(0, p); /* rim, inner edge */
  ck_assert(p[0] == 1.4 && p[1] == 0.0 && p[2] == 2.4);
  zs_teapot_control_point(188, p); /* spout lip */
  ck_assert(p[0] == 3.525 && p[1] == 0.0 && p[2] == 2.49375);
  zs_teapot_control_point(203, p); /* lid pole */
  ck_assert(p[0] == 0.0 && p[1] == 0.0 && p[2] == 3.15);
  zs_teapot_control_point(269, p); /* bottom pole */
  ck_assert(p[0] == 0.0 && p[1] == 0.0 && p[2] == 0.0);
}
END_TEST

/* ---- counts and attributes ---- */

static void check_counts(int level) {
  zs_model m;
  add_teapot(&m, level, NULL);
  int32_t side = level + 1;
  ck_assert_int_eq(m.mesh.nverts, 32 * side * side);
  ck_assert_int_eq(m.nsource_faces, 32 * level * level);
  /* zs_model may split a non-planar quad in two, nothing more. */
  ck_assert_int_ge(m.mesh.nfaces, m.nsource_faces);
  ck_assert_int_le(m.mesh.nfaces, 2 * m.nsource_faces);
  ck_assert_int_eq(m.nobjects, 1);
  for (int32_t f = 0; f < m.mesh.nfaces; f++) {
    ck_assert_int_eq(m.face_object[f], 0);
    ck_assert_uint_eq(m.mesh.face_rgb[f], 0x123456u);
  }
  zs_model_free(&m);
}

START_TEST(test_counts) {
  check_counts(1); /* 128 vertices, 32 faces */
  check_counts(6); /* 1568 vertices, 1152 faces */
  zs_model m;
  add_teapot(&m, 6, NULL);
  ck_assert_int_eq(m.mesh.nverts, 1568);
  ck_assert_int_eq(m.nsource_faces, 1152);
  zs_model_free(&m);
}
END_TEST

START_TEST(test_bad_level) {
  zs_model m;
  zs_model_init(&m);
  zs_error err;
  const int bad[] = {0, -1, ZS_TEAPOT_MAX_LEVEL + 1};
  for (int i = 0; i < 3; i++) {
    zs_error_clear(&err);
    ck_assert_int_eq(zs_teapot_add(&m, bad[i], NULL, 0, -1, &err),
                     ZS_ERR_ARG);
    ck_assert_int_eq(err.code, ZS_ERR_ARG);
    ck_assert(strstr(err.msg, "level") != NULL);
  }
  ck_assert_int_eq(m.mesh.nverts, 0);
  ck_assert_int_eq(m.nsource_faces, 0);
  zs_model_free(&m);
}
END_TEST

/* ---- bounds ---- */

/* The spout's tip: on the patches of the spout lip the x of the control
 * rows is (a, a, b, b) with b > a, so x is largest on the column u = 1,
 * whose control x are 3.3, 3.525, 3.45, 3.2; the grid samples it at
 * v = j / level. */
static double spout_tip_x(int level) {
  double best = 0.0;
  for (int j = 0; j <= level; j++) {
    double v = (double)j / level, s = 1.0 - v;
    double x = 3.3 * s * s * s + 3.0 * 3.525 * v * s * s +
               3.0 * 3.45 * v * v * s + 3.2 * v * v * v;
    if (x > best) best = x;
  }
  return best;
}

START_TEST(test_bounds) {
  for (int level = 1; level <= 8; level++) {
    zs_model m;
    add_teapot(&m, level, NULL);
    double lo[3], hi[3];
    ck_assert(zs_model_bounds(&m, lo, hi));
    /* Met exactly at every level, by control points on the surface: the
     * handle's outer corner (-3.0, 0, 1.8), the bottom's pole at 0, the lid
     * knob's pole at 3.15, the body's widest circle (radius 2, at data
     * points (0, +-2, 0.9)). */
    ck_assert(lo[0] == -3.0);
    ck_assert(lo[1] == 0.0);
    ck_assert(hi[1] == 3.15);
    ck_assert(lo[2] == -2.0);
    ck_assert(hi[2] == 2.0);
    ck_assert_double_eq_tol(hi[0], spout_tip_x(level), 1e-12);
    zs_model_free(&m);
  }
  /* Level 1 sees the lip's corners only (3.3); level 6 samples v = 1/3:
   * (3.3*8 + 3*3.525*4 + 3*3.45*2 + 3.2) / 27 = 92.6 / 27. */
  ck_assert_double_eq_tol(spout_tip_x(1), 3.3, 1e-15);
  ck_assert_double_eq_tol(spout_tip_x(6), 92.6 / 27.0, 1e-12);
  /* About 6.43 across, the standard size. */
  ck_assert(spout_tip_x(6) + 3.0 > 6.4 && spout_tip_x(6) + 3.0 < 6.44);
}
END_TEST

START_TEST(test_xform) {
  zs_model a, b;
  add_teapot(&a, 3, NULL);
  double t[16];
  zs_mat_translate(t, 10.0, -20.0, 0.5);
  add_teapot(&b, 3, t);
  ck_assert_int_eq(a.mesh.nverts, b.mesh.nverts);
  for (int32_t i = 0; i < a.mesh.nverts; i++) {
    ck_assert_double_eq_tol(b.mesh.pos[3 * i], a.mesh.pos[3 * i] + 10.0,
                            1e-12);
    ck_assert_double_eq_tol(b.mesh.pos[3 * i + 1],
                            a.mesh.pos[3 * i + 1] - 20.0, 1e-12);
    ck_assert_double_eq_tol(b.mesh.pos[3 * i + 2],
                            a.mesh.pos[3 * i + 2] + 0.5, 1e-12);
  }
  zs_model_free(&a);
  zs_model_free(&b);
}
END_TEST

/* ---- orientation and seams ---- */

/* Every face of the body (patches 4 .. 11) faces away from the axis. */
START_TEST(test_orientation_body) {
  const int level = 6;
  zs_model m;
  add_teapot(&m, level, NULL);
  int checked = 0;
  for (int32_t f = 0; f < m.mesh.nfaces; f++) {
    int p = face_patch(&m, f, level);
    if (p < 4 || p > 11) continue;
    double n[3], c[3];
    face_normal(&m.mesh, f, n, c);
    double radial[3] = {c[0], 0.0, c[2]};
    ck_assert_msg(dot3(n, radial) > 0.0, "body face %d faces inward",
                  (int)m.mesh.face_id[f]);
    checked++;
  }
  ck_assert_int_ge(checked, 8 * level * level);
  zs_model_free(&m);
}
END_TEST

/* Seams, orientation of the whole surface, and where it is open.  Welding
 * the vertices by exact position (patch boundaries are evaluated bit for bit
 * alike), every edge must be used by at most two faces, in opposite
 * directions: the orientation is consistent across patches.  One face per
 * part, checked outward, then orients each connected part: body with rim
 * and bottom, lid, handle, spout.  The edges used once are the six open
 * loops of teapot.h, 16 * level of them: rim's inner edge and lid's outer
 * edge (4 patches each), spout tip and base, handle ends (2 each).  From
 * level 2 on: at level 1 the tubes of handle and spout, sampled at their
 * seams only, collapse into flat ribbons in the plane z = 0 whose two
 * halves share every edge. */
START_TEST(test_orientation_closed) {
  for (int level = 2; level <= 8; level++) {
    zs_model m;
    add_teapot(&m, level, NULL);
    edge_stats st = weld_edges(&m);
    ck_assert_int_eq(st.inconsistent, 0);
    ck_assert_int_eq(st.nonmanifold, 0);
    ck_assert_int_eq(st.boundary, 16 * level);
    ck_assert_int_gt(st.interior, 0);

    /* Anchors: the first ring of the lid knob faces up, that of the bottom
     * down; each half of handle and spout (patches 12, 14, 16, 18 lie at
     * z >= 0, their mirrors at z <= 0) faces away from the y = 0 plane,
     * summed over the half (twice its area projected on that plane). */
    double half[20][3] = {{0}};
    for (int32_t f = 0; f < m.mesh.nfaces; f++) {
      int p = face_patch(&m, f, level);
      int ring = (m.mesh.face_id[f] % (level * level)) / level;
      double n[3], c[3];
      face_normal(&m.mesh, f, n, c);
      if (p >= 20 && p < 24 && ring == 0)
        ck_assert(n[1] > 0.0 || (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0));
      if (p >= 28 && ring == 0)
        ck_assert(n[1] < 0.0 || (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0));
      if (p >= 12 && p < 20)
        for (int k = 0; k < 3; k++) half[p][k] += n[k];
    }
    for (int p = 12; p < 20; p++) {
      double away = (p % 2 == 0) ? 1.0 : -1.0;
      ck_assert_msg(half[p][2] * away > 0.0, "level %d patch %d", level, p);
    }
    zs_model_free(&m);
  }
}
END_TEST

/* ---- the generated default scene and cubes ---- */

static void generate(const char *spec, zs_scene *s) {
  zs_error err;
  zs_error_clear(&err);
  zs_status st = zs_gen_scene(spec, s, &err);
  ck_assert_msg(st == ZS_OK, "%s: %s", spec, err.msg);
}

START_TEST(test_default_scene) {
  zs_scene s;
  generate("default", &s);
  /* Nine teapots and the ground, instances of one teapot mesh (level 6)
   * and one box. */
  ck_assert_int_eq(s.ninst, 10);
  ck_assert_int_eq(s.nmeshes, 2);
  for (int t = 0; t < 9; t++) {
    char name[32];
    snprintf(name, sizeof name, "teapot_%d", t);
    ck_assert_str_eq(s.inst[t].name, name);
    ck_assert_int_eq(s.inst[t].mesh, s.inst[0].mesh);
    ck_assert_uint_eq(s.inst[t].id_base, (uint32_t)(t * 1152));
  }
  const zs_instance *ground = &s.inst[9];
  ck_assert_str_eq(ground->name, "ground");
  ck_assert_uint_eq(ground->id_base, 9 * 1152);
  const zs_model *teapot = &s.meshes[s.inst[0].mesh], *slab = &s.meshes[ground->mesh];
  ck_assert_int_eq(teapot->mesh.nverts, 1568);
  ck_assert_int_eq(teapot->nsource_faces, 1152);
  ck_assert_int_eq(slab->mesh.nverts, 8);
  ck_assert_int_eq(slab->nsource_faces, 6);
  ck_assert_uint_eq(zs_scene_faces(&s), 9 * 1152 + 6);

  /* One colour per object, all different; the ground keeps its mesh's. */
  uint32_t colour[10];
  for (int t = 0; t < 9; t++) colour[t] = s.inst[t].rgb;
  ck_assert_uint_eq(ground->rgb, ZS_RGB_MESH);
  colour[9] = slab->mesh.face_rgb[0];
  ck_assert_uint_eq(colour[9], ZS_GEN_GROUND_RGB);
  for (int a = 0; a < 10; a++)
    for (int b = a + 1; b < 10; b++) ck_assert_uint_ne(colour[a], colour[b]);

  /* The field on the ground: teapot 3 r + c turned about +y and standing
   * at (8 (c - 1), 0, 8 (r - 1)). */
  for (int t = 0; t < 9; t++) {
    const double *m = s.inst[t].model;
    ck_assert(m[3] == 8.0 * (t % 3 - 1) && m[7] == 0.0 && m[11] == 8.0 * (t / 3 - 1));
    ck_assert(m[1] == 0.0 && m[4] == 0.0 && m[6] == 0.0 && m[9] == 0.0);
    ck_assert_double_eq_tol(m[5], 1.0, 1e-15);
  }
  ck_assert(s.lo[0] == -12.0 && s.hi[0] == 12.0);
  ck_assert(s.lo[2] == -12.0 && s.hi[2] == 12.0);
  ck_assert(s.lo[1] == -0.25);
  ck_assert_double_eq_tol(s.hi[1], 3.15, 1e-12);
  zs_scene_free(&s);
}
END_TEST

START_TEST(test_cubes) {
  const int n = 3;
  zs_scene s;
  generate("cubes?n=3", &s);
  ck_assert_int_eq(s.ninst, 27);
  ck_assert_int_eq(s.nmeshes, 1);
  ck_assert_uint_eq(zs_scene_faces(&s), 162);
  /* The unit cube: 8 vertices, 6 quads (planar convex quads stay whole),
   * closed and facing out. */
  const zs_model *cube = &s.meshes[0];
  ck_assert_int_eq(cube->mesh.nverts, 8);
  ck_assert_int_eq(cube->mesh.nfaces, 6);
  for (int32_t f = 0; f < cube->mesh.nfaces; f++) {
    double nrm[3], c[3];
    face_normal(&cube->mesh, f, nrm, c);
    ck_assert_msg(dot3(nrm, c) > 0.0, "cube face %d faces inward", (int)f);
    /* A unit square: Newell's normal has length twice the area. */
    ck_assert_double_eq_tol(sqrt(dot3(nrm, nrm)), 2.0, 1e-12);
    ck_assert_double_eq_tol(sqrt(dot3(c, c)), 0.5, 1e-12);
  }
  edge_stats st = weld_edges(cube);
  ck_assert_int_eq(st.boundary, 0);
  ck_assert_int_eq(st.inconsistent, 0);
  ck_assert_int_eq(st.nonmanifold, 0);
  ck_assert_int_eq(st.interior, 12);
  /* Cube (i, j, k): its name, its centre 2 apart from its neighbours',
   * its id range, a palette colour unlike the next cube's. */
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++)
      for (int k = 0; k < n; k++) {
        int o = (i * n + j) * n + k;
        const zs_instance *in = &s.inst[o];
        char name[64];
        snprintf(name, sizeof name, "cube_%d_%d_%d", i, j, k);
        ck_assert_str_eq(in->name, name);
        ck_assert(in->model[3] == 2.0 * i - (n - 1) && in->model[7] == 2.0 * j - (n - 1) &&
                  in->model[11] == 2.0 * k - (n - 1));
        ck_assert_uint_eq(in->id_base, (uint32_t)(6 * o));
        ck_assert_uint_eq(in->rgb, zs_gen_palette(o % ZS_GEN_PALETTE_SIZE));
      }
  for (int a = 0; a < 3; a++) {
    ck_assert(s.lo[a] == -2.5);
    ck_assert(s.hi[a] == 2.5);
  }
  zs_scene_free(&s);

  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_gen_scene("cubes?n=0", &s, &err), ZS_ERR_ARG);
  zs_error_clear(&err);
  ck_assert_int_eq(zs_gen_scene("cubes?n=65", &s, &err), ZS_ERR_ARG);
  ck_assert_int_eq(s.ninst, 0);
  zs_scene_free(&s);
}
END_TEST

START_TEST(test_box) {
  zs_model m;
  zs_model_init(&m);
  const double lo[3] = {-1.0, 2.0, 3.0}, hi[3] = {4.0, 5.0, 3.5};
  ck_assert_int_eq(zs_gen_box(&m, lo, hi, NULL, 0xABCDEFu, -1), ZS_OK);
  ck_assert_int_eq(m.mesh.nverts, 8);
  ck_assert_int_eq(m.nsource_faces, 6);
  ck_assert_int_eq(m.mesh.nfaces, 6);
  /* Faces in the order -x, +x, -y, +y, -z, +z. */
  for (int32_t f = 0; f < 6; f++) {
    double n[3], c[3];
    face_normal(&m.mesh, f, n, c);
    int axis = f / 2;
    double sign = (f % 2) ? 1.0 : -1.0;
    ck_assert(n[axis] * sign > 0.0);
    ck_assert(n[(axis + 1) % 3] == 0.0 && n[(axis + 2) % 3] == 0.0);
    ck_assert(c[axis] == ((f % 2) ? hi[axis] : lo[axis]));
    ck_assert_uint_eq(m.mesh.face_rgb[f], 0xABCDEFu);
    ck_assert_int_eq(m.face_object[f], -1);
  }
  for (int b = 0; b < 8; b++)
    for (int a = 0; a < 3; a++)
      ck_assert(m.mesh.pos[3 * b + a] == ((b >> a) & 1 ? hi[a] : lo[a]));
  const double bad[3] = {-1.0, 6.0, 3.0};
  ck_assert_int_eq(zs_gen_box(&m, bad, hi, NULL, 0, -1), ZS_ERR_ARG);
  const double nan_lo[3] = {NAN, 0.0, 0.0};
  ck_assert_int_eq(zs_gen_box(&m, nan_lo, hi, NULL, 0, -1), ZS_ERR_ARG);
  ck_assert_int_eq(m.mesh.nverts, 8);
  zs_model_free(&m);
}
END_TEST

static Suite *suite(void) {
  Suite *s = suite_create("teapot");
  TCase *tc = tcase_create("teapot");
  tcase_add_test(tc, test_data_symmetry);
  tcase_add_test(tc, test_counts);
  tcase_add_test(tc, test_bad_level);
  tcase_add_test(tc, test_bounds);
  tcase_add_test(tc, test_xform);
  tcase_add_test(tc, test_orientation_body);
  tcase_add_test(tc, test_orientation_closed);
  suite_add_tcase(s, tc);
  TCase *tb = tcase_create("generated");
  tcase_add_test(tb, test_default_scene);
  tcase_add_test(tb, test_cubes);
  tcase_add_test(tb, test_box);
  suite_add_tcase(s, tb);
  return s;
}

int main(void) { return zs_test_run(suite()); }
