/* Octrees (cull/octree.h): the loose tree's placement rule, the plain
 * tree's, exact tight bounds after any sequence of moves, the split
 * policy, identical trees for identical moves, the work counters, and
 * `zscan bench octree`.
 *
 * The random tests draw boxes from a seeded zs_rng and print the seed
 * with any failure.  They check the library's own zs_octree_check and, on
 * top of it, recompute what matters here independently of the library:
 * each object's level and cell, its node's box, and every tight box as
 * the union of the scene's boxes below the node. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cull/octree.h"
#include "util/rng.h"
#include "scene/generate.h"
#include "scene/scene.h"
#include "tests/testutil.h"
#include "tools/bench_octree.h"

static zs_error err;

/* ---- scenes of bare boxes ------------------------------------------------ */

/* A scene of n instances without meshes: only their boxes, which is all an
 * octree reads.  Bounds [0, 1000]^3. */
static void box_scene(zs_scene *s, int n) {
  zs_scene_init(s);
  s->inst = calloc((size_t)(n > 0 ? n : 1), sizeof *s->inst);
  ck_assert_ptr_nonnull(s->inst);
  s->ninst = s->cap_inst = n;
  for (int k = 0; k < 3; k++) {
    s->lo[k] = 0.0;
    s->hi[k] = 1000.0;
  }
  s->has_bounds = 1;
}

static void set_box(zs_scene *s, int i, double x, double y, double z, double r) {
  const double c[3] = {x, y, z};
  for (int k = 0; k < 3; k++) {
    s->inst[i].lo[k] = c[k] - r;
    s->inst[i].hi[k] = c[k] + r;
  }
}

/* A random box: mostly small (the spheres' radii), some large, a few
 * points and a few partly or wholly outside the bounds.  One draw per
 * statement (docs/ARCHITECTURE.md). */
static void random_box(zs_rng *rng, zs_scene *s, int i) {
  double kind = zs_rng_uniform(rng);
  double r;
  if (kind < 0.7) r = zs_rng_range(rng, 8.0, 16.0);
  else if (kind < 0.9) r = zs_rng_range(rng, 0.0, 300.0);
  else if (kind < 0.95) r = 0.0;
  else r = zs_rng_range(rng, 300.0, 700.0);
  double c[3];
  for (int k = 0; k < 3; k++) c[k] = zs_rng_range(rng, -20.0, 1020.0);
  set_box(s, i, c[0], c[1], c[2], r);
  /* a stretched box now and then */
  if (zs_rng_uniform(rng) < 0.1) s->inst[i].hi[1] += zs_rng_range(rng, 0.0, 100.0);
}

/* Moves box i by a random step of at most `step` per axis. */
static void nudge(zs_rng *rng, zs_scene *s, int i, double step) {
  for (int k = 0; k < 3; k++) {
    double d = zs_rng_range(rng, -step, step);
    s->inst[i].lo[k] += d;
    s->inst[i].hi[k] += d;
  }
}

/* One round of moves: a random subset nudged, a few teleported or
 * resized. */
static void random_round(zs_rng *rng, zs_scene *s) {
  for (int i = 0; i < s->ninst; i++) {
    double u = zs_rng_uniform(rng);
    if (u < 0.5) nudge(rng, s, i, 3.0);
    else if (u < 0.55) nudge(rng, s, i, 150.0);
    else if (u < 0.58) random_box(rng, s, i);
  }
}

/* ---- independent checks ------------------------------------------------- */

static int inside(const double lo[3], const double hi[3], const double blo[3],
                  const double bhi[3]) {
  for (int k = 0; k < 3; k++)
    if (!(lo[k] >= blo[k] && hi[k] <= bhi[k])) return 0;
  return 1;
}

/* The root cell of a tree over bounds [0, 1000]^3. */
static void cell_box(int level, const int32_t c[3], double factor, double lo[3], double hi[3]) {
  double s = 1000.0 / (double)(1 << level);
  for (int k = 0; k < 3; k++) {
    lo[k] = c[k] * s - 0.5 * (factor - 1.0) * s;
    hi[k] = (c[k] + 1) * s + 0.5 * (factor - 1.0) * s;
  }
}

/* Union of the scene's boxes of every object in node n's subtree. */
static void exact_union(const zs_octree *t, const zs_scene *s, int32_t n, int *empty,
                        double lo[3], double hi[3]) {
  const zs_octnode *nd = &t->node[n];
  for (int32_t i = nd->first; i != ZS_OCTREE_NONE; i = t->next[i]) {
    for (int k = 0; k < 3; k++) {
      if (*empty || s->inst[i].lo[k] < lo[k]) lo[k] = s->inst[i].lo[k];
      if (*empty || s->inst[i].hi[k] > hi[k]) hi[k] = s->inst[i].hi[k];
    }
    *empty = 0;
  }
  for (int o = 0; o < 8; o++)
    if (nd->child[o] != ZS_OCTREE_NONE) exact_union(t, s, nd->child[o], empty, lo, hi);
}

/* Every check of this file on tree t over scene s (bounds [0, 1000]^3). */
static void check_tree(const zs_octree *t, const zs_scene *s, unsigned long long seed) {
  zs_error_clear(&err);
  ck_assert_msg(zs_octree_check(t, &err) == ZS_OK, "seed %llu: %s", seed, err.msg);
  const int max = t->params.max_depth;
  const double k = t->params.looseness;
  const int loose = t->params.kind == ZS_OCTREE_LOOSE;
  double rootlo[3], rooths[3];
  cell_box(0, (int32_t[3]){0, 0, 0}, loose ? k : 1.0, rootlo, rooths);

  for (int32_t i = 0; i < t->nobjects; i++) {
    const double *lo = s->inst[i].lo, *hi = s->inst[i].hi;
    const zs_octnode *nd = &t->node[t->home[i]];
    /* the tree holds the scene's box */
    for (int a = 0; a < 3; a++)
      ck_assert_msg(t->olo[i][a] == lo[a] && t->ohi[i][a] == hi[a], "seed %llu: object %d stale",
                    seed, (int)i);
    /* inside its node's box, unless it left the root's */
    int in_root = inside(lo, hi, rootlo, rooths);
    ck_assert_msg(inside(lo, hi, nd->lo, nd->hi) || (!in_root && t->home[i] == ZS_OCTREE_ROOT),
                  "seed %llu: object %d outside its node's box", seed, (int)i);
    if (!in_root) {
      ck_assert_msg(t->home[i] == ZS_OCTREE_ROOT, "seed %llu: outsider %d below the root", seed,
                    (int)i);
      continue;
    }
    if (loose) {
      /* level: the deepest whose limit (k - 1) s_L takes the radius */
      double r = 0.0;
      for (int a = 0; a < 3; a++) r = fmax(r, 0.5 * (hi[a] - lo[a]));
      int ideal = 0;
      while (ideal < max && r <= (k - 1.0) * 500.0 / (double)(1 << (ideal + 1))) ideal++;
      int32_t cell[3];
      double clo[3], chi[3];
      for (int a = 0; a < 3; a++) {
        double x = floor((0.5 * (lo[a] + hi[a])) / (1000.0 / (double)(1 << ideal)));
        cell[a] = x < 0 ? 0 : x >= (1 << ideal) ? (1 << ideal) - 1 : (int32_t)x;
      }
      cell_box(ideal, cell, k, clo, chi);
      if (inside(lo, hi, clo, chi)) { /* always, but for rounding at the very edge */
        ck_assert_msg(t->tlevel[i] == ideal, "seed %llu: object %d at level %d, not %d", seed,
                      (int)i, (int)t->tlevel[i], ideal);
        for (int a = 0; a < 3; a++)
          ck_assert_msg(t->tcell[i][a] == cell[a], "seed %llu: object %d in the wrong cell", seed,
                        (int)i);
      } else {
        ck_assert_int_lt(t->tlevel[i], ideal);
      }
    } else {
      /* plain: the deepest cell containing the box: fits its node's cell
       * and, at its target, no child cell */
      if (t->tlevel[i] < max) {
        for (int o = 0; o < 8; o++) {
          int32_t c[3];
          double clo[3], chi[3];
          for (int a = 0; a < 3; a++) c[a] = 2 * t->tcell[i][a] + (o >> a & 1);
          cell_box(t->tlevel[i] + 1, c, 1.0, clo, chi);
          ck_assert_msg(!inside(lo, hi, clo, chi), "seed %llu: object %d fits a child", seed,
                        (int)i);
        }
      }
    }
    /* with split 0 every object sits at its target */
    if (t->params.split == 0) ck_assert_int_eq(nd->level, t->tlevel[i]);
    else ck_assert_int_le(nd->level, t->tlevel[i]);
  }

  /* tight boxes: the exact union of the content */
  for (int32_t n = 0; n < t->nslots; n++) {
    const zs_octnode *nd = &t->node[n];
    if (nd->level < 0) continue;
    int empty = 1;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    exact_union(t, s, n, &empty, lo, hi);
    ck_assert_msg(nd->empty == empty, "seed %llu: node %d empty flag", seed, (int)n);
    for (int a = 0; a < 3; a++)
      ck_assert_msg(empty || (nd->tlo[a] == lo[a] && nd->thi[a] == hi[a]),
                    "seed %llu: node %d's tight box is not the union of its content", seed,
                    (int)n);
  }
}

/* The default parameters, but a hierarchy however few the objects: the
 * placement tests below use a handful of boxes. */
static void hierarchy_params(zs_octree_params *p, zs_octree_kind kind) {
  zs_octree_params_default(p, kind);
  p->flat = 0;
}

/* ---- tests ----------------------------------------------------------------- */

START_TEST(loose_level_and_cell) {
  /* Root [0, 1000]^3: s_0 = 500, cells of level L are 1000 / 2^L. */
  zs_scene s;
  box_scene(&s, 6);
  set_box(&s, 0, 100, 100, 100, 10);      /* 500/10 = 50: level 5, clamped to 4 */
  set_box(&s, 1, 100, 300, 900, 100);     /* 500/100 = 5: level 2 */
  set_box(&s, 2, 500, 500, 500, 300);     /* 500/300: level 0 */
  set_box(&s, 3, 600, 600, 600, 125);     /* r = s_2 exactly: level 2 */
  set_box(&s, 4, 600, 600, 600, 125.001); /* just over: level 1 */
  set_box(&s, 5, 999, 1, 999, 20);        /* a corner cell: 500/20 = 25: level 4 */
  zs_octree_params p;
  hierarchy_params(&p, ZS_OCTREE_LOOSE);
  zs_octree t;
  ck_assert_int_eq(zs_octree_build(&t, &s, &p, &err), ZS_OK);
  check_tree(&t, &s, 0);
  static const int want_level[6] = {4, 2, 0, 2, 1, 4};
  static const int32_t want_cell[6][3] = {{1, 1, 1}, {0, 1, 3}, {0, 0, 0},
                                          {2, 2, 2}, {1, 1, 1}, {15, 0, 15}};
  for (int i = 0; i < 6; i++) {
    const zs_octnode *nd = &t.node[t.home[i]];
    ck_assert_int_eq(nd->level, want_level[i]);
    for (int k = 0; k < 3; k++) ck_assert_int_eq(nd->cell[k], want_cell[i][k]);
    ck_assert(inside(s.inst[i].lo, s.inst[i].hi, nd->lo, nd->hi));
  }
  /* the loose box is the cell grown by half a cell on every side */
  const zs_octnode *n0 = &t.node[t.home[0]];
  ck_assert(n0->lo[0] == 62.5 - 31.25 && n0->hi[0] == 125.0 + 31.25);
  /* sparse: the root and the paths to the five nodes, shared prefixes once */
  zs_octree_stats st;
  zs_octree_stats_get(&t, &st);
  ck_assert_int_eq(st.depth, 4);
  ck_assert_int_eq(st.objects_per_level[0], 1);
  ck_assert_int_eq(st.objects_per_level[1], 1);
  ck_assert_int_eq(st.objects_per_level[2], 2);
  ck_assert_int_eq(st.objects_per_level[4], 2);
  ck_assert_int_eq(zs_octree_find(&t, 4, (int32_t[3]){1, 1, 1}), t.home[0]);
  ck_assert_int_eq(zs_octree_find(&t, 4, (int32_t[3]){1, 1, 2}), ZS_OCTREE_NONE);
  zs_octree_free(&t);

  /* the plain tree keeps the small object crossing the middle at the root */
  hierarchy_params(&p, ZS_OCTREE_PLAIN);
  set_box(&s, 0, 500, 100, 100, 1);
  ck_assert_int_eq(zs_octree_build(&t, &s, &p, &err), ZS_OK);
  check_tree(&t, &s, 0);
  ck_assert_int_eq(t.home[0], ZS_OCTREE_ROOT);
  ck_assert_int_eq(t.home[5], ZS_OCTREE_ROOT); /* x 979 .. 1019 leaves the root cell */
  zs_octree_free(&t);
  zs_scene_free(&s);
}
END_TEST

/* Random rounds of moves on trees of every kind and several parameters. */
static void random_moves(zs_octree_kind kind, int depth, double k, int split,
                         unsigned long long seed, int n, int rounds) {
  zs_rng rng;
  zs_rng_seed(&rng, seed);
  zs_scene s;
  box_scene(&s, n);
  for (int i = 0; i < n; i++) random_box(&rng, &s, i);
  zs_octree_params p;
  hierarchy_params(&p, kind);
  p.max_depth = depth;
  p.looseness = k;
  p.split = split;
  zs_octree t;
  ck_assert_int_eq(zs_octree_build(&t, &s, &p, &err), ZS_OK);
  check_tree(&t, &s, seed);
  for (int r = 0; r < rounds; r++) {
    random_round(&rng, &s);
    ck_assert_int_eq(zs_octree_update(&t, &s, NULL, &err), ZS_OK);
    check_tree(&t, &s, seed);
  }
  zs_octree_free(&t);
  zs_scene_free(&s);
}

START_TEST(loose_random_moves) {
  for (unsigned long long seed = 1; seed <= 6; seed++) {
    random_moves(ZS_OCTREE_LOOSE, 4, 2.0, 0, seed, 300, 25);
    random_moves(ZS_OCTREE_LOOSE, 4, 2.0, 3, seed, 300, 25);
  }
  random_moves(ZS_OCTREE_LOOSE, 0, 2.0, 0, 11, 100, 10);
  random_moves(ZS_OCTREE_LOOSE, 7, 2.0, 0, 12, 300, 15);
  random_moves(ZS_OCTREE_LOOSE, 5, 1.5, 8, 13, 300, 15);
  random_moves(ZS_OCTREE_LOOSE, 4, 3.0, 1, 14, 300, 15);
}
END_TEST

START_TEST(plain_random_moves) {
  for (unsigned long long seed = 21; seed <= 26; seed++) {
    random_moves(ZS_OCTREE_PLAIN, 4, 2.0, 0, seed, 300, 25);
    random_moves(ZS_OCTREE_PLAIN, 4, 2.0, 5, seed, 300, 25);
  }
  random_moves(ZS_OCTREE_PLAIN, 6, 2.0, 2, 27, 300, 15);
}
END_TEST

START_TEST(tight_bounds_shrink) {
  /* Two objects in one level-4 cell [62.5, 125)^3; the second leaves. */
  zs_scene s;
  box_scene(&s, 2);
  set_box(&s, 0, 100, 100, 100, 10);
  set_box(&s, 1, 110, 110, 110, 12);
  for (int kind = 0; kind < 2; kind++) {
    set_box(&s, 1, 110, 110, 110, 12);
    zs_octree_params p;
    hierarchy_params(&p, (zs_octree_kind)kind);
    zs_octree t;
    ck_assert_int_eq(zs_octree_build(&t, &s, &p, &err), ZS_OK);
    int32_t n = t.home[0];
    ck_assert_int_eq(t.home[1], n);
    ck_assert(t.node[n].tlo[0] == 90.0 && t.node[n].thi[0] == 122.0);
    ck_assert(t.node[ZS_OCTREE_ROOT].thi[2] == 122.0);
    /* within the cell, inwards: the node shrinks to what is left */
    set_box(&s, 1, 100, 100, 100, 2);
    ck_assert_int_eq(zs_octree_update(&t, &s, NULL, &err), ZS_OK);
    ck_assert(t.node[n].tlo[0] == 90.0 && t.node[n].thi[0] == 110.0);
    ck_assert(t.node[ZS_OCTREE_ROOT].thi[2] == 110.0);
    /* far away: the node holds object 0 alone, exactly its box */
    set_box(&s, 1, 900, 900, 900, 12);
    ck_assert_int_eq(zs_octree_update(&t, &s, NULL, &err), ZS_OK);
    ck_assert_int_ne(t.home[1], n);
    for (int k = 0; k < 3; k++) {
      ck_assert(t.node[n].tlo[k] == 90.0 && t.node[n].thi[k] == 110.0);
      ck_assert(t.node[ZS_OCTREE_ROOT].tlo[k] == 90.0 && t.node[ZS_OCTREE_ROOT].thi[k] == 912.0);
    }
    check_tree(&t, &s, 0);
    /* object 0 leaves too: its old node is gone, the root shrinks again */
    set_box(&s, 0, 880, 880, 880, 10);
    ck_assert_int_eq(zs_octree_update(&t, &s, NULL, &err), ZS_OK);
    check_tree(&t, &s, 0);
    ck_assert(t.node[ZS_OCTREE_ROOT].tlo[0] == 870.0);
    zs_octree_free(&t);
    set_box(&s, 0, 100, 100, 100, 10);
  }
  zs_scene_free(&s);
}
END_TEST

START_TEST(same_moves_same_tree) {
  for (int kind = 0; kind < 2; kind++) {
    uint64_t hashes[2][12];
    for (int run = 0; run < 2; run++) {
      zs_rng rng;
      zs_rng_seed(&rng, 77);
      zs_scene s;
      box_scene(&s, 400);
      for (int i = 0; i < 400; i++) random_box(&rng, &s, i);
      zs_octree_params p;
      hierarchy_params(&p, (zs_octree_kind)kind);
      p.split = 2;
      zs_octree t;
      ck_assert_int_eq(zs_octree_build(&t, &s, &p, &err), ZS_OK);
      hashes[run][0] = zs_octree_hash(&t);
      for (int r = 1; r < 12; r++) {
        random_round(&rng, &s);
        ck_assert_int_eq(zs_octree_update(&t, &s, NULL, &err), ZS_OK);
        hashes[run][r] = zs_octree_hash(&t);
      }
      zs_octree_free(&t);
      zs_scene_free(&s);
    }
    for (int r = 0; r < 12; r++) {
      ck_assert_uint_eq(hashes[0][r], hashes[1][r]);
      if (r > 0) ck_assert_uint_ne(hashes[0][r], hashes[0][r - 1]); /* the tree did change */
    }
    /* and on every compiler and optimisation level (CI: gcc -O2, -O3,
     * clang -O0 with sanitizers) */
    zs_golden_assert("octree.txt", kind ? "plain-after-11-rounds" : "loose-after-11-rounds",
                     hashes[0][11]);
  }
}
END_TEST

START_TEST(same_cell_move_is_free) {
  zs_scene s;
  box_scene(&s, 3);
  set_box(&s, 0, 100, 100, 100, 10);
  set_box(&s, 1, 700, 300, 200, 10);
  set_box(&s, 2, 300, 800, 600, 50);
  zs_octree lt, pt;
  zs_octree_params lp, p;
  hierarchy_params(&lp, ZS_OCTREE_LOOSE);
  hierarchy_params(&p, ZS_OCTREE_PLAIN);
  ck_assert_int_eq(zs_octree_build(&lt, &s, &lp, &err), ZS_OK);
  ck_assert_int_eq(zs_octree_build(&pt, &s, &p, &err), ZS_OK);
  uint64_t before = zs_octree_hash(&lt);

  /* 100 -> 101.5: the same level-4 cell [62.5, 125) */
  set_box(&s, 0, 101.5, 100, 100, 10);
  zs_octree_work lw, pw;
  memset(&lw, 0, sizeof lw);
  memset(&pw, 0, sizeof pw);
  ck_assert_int_eq(zs_octree_update(&lt, &s, &lw, &err), ZS_OK);
  ck_assert_int_eq(zs_octree_update(&pt, &s, &pw, &err), ZS_OK);
  ck_assert_int_eq(lw.moved, 1);
  ck_assert_int_eq(lw.same_cell, 1);
  ck_assert_int_eq(lw.inserts + lw.deletes + lw.relinks, 0);
  ck_assert_int_eq(lw.nodes_created + lw.nodes_deleted + lw.splits + lw.collapses, 0);
  ck_assert_int_eq(lw.visits, 1); /* the O(1) placement, no probe of the table */
  check_tree(&lt, &s, 0);
  ck_assert_uint_ne(zs_octree_hash(&lt), before); /* the tight boxes moved */
  /* the plain tree deletes and re-inserts by descent, always */
  ck_assert_int_eq(pw.moved, 1);
  ck_assert_int_eq(pw.same_cell, 0);
  ck_assert_int_eq(pw.deletes, 1);
  ck_assert_int_eq(pw.inserts, 1);
  ck_assert_int_ge(pw.visits, 5); /* the descent: root + 4 levels */
  check_tree(&pt, &s, 0);

  /* the next cell: delete + insert in the loose tree too */
  set_box(&s, 0, 130, 100, 100, 10);
  memset(&lw, 0, sizeof lw);
  ck_assert_int_eq(zs_octree_update(&lt, &s, &lw, &err), ZS_OK);
  ck_assert_int_eq(lw.same_cell, 0);
  ck_assert_int_eq(lw.inserts, 1);
  ck_assert_int_eq(lw.deletes, 1);
  /* new: level-4 cell (2,1,1) and its parent (1,0,0); emptied and
   * deleted: (1,1,1) and its parent (0,0,0); level 2 and up are shared */
  ck_assert_int_eq(lw.nodes_created, 2);
  ck_assert_int_eq(lw.nodes_deleted, 2);
  check_tree(&lt, &s, 0);
  /* one object by hand: zs_octree_move, the same as an update */
  set_box(&s, 2, 320, 790, 610, 50);
  memset(&lw, 0, sizeof lw);
  zs_octree_move(&lt, 2, s.inst[2].lo, s.inst[2].hi, &lw);
  ck_assert_int_eq(lw.moved, 1);
  ck_assert_int_eq(lw.same_cell, 1); /* level 3, cell (2, 6, 4) still */
  check_tree(&lt, &s, 0);
  /* unchanged boxes: no work at all */
  memset(&lw, 0, sizeof lw);
  ck_assert_int_eq(zs_octree_update(&lt, &s, &lw, &err), ZS_OK);
  ck_assert_int_eq(zs_octree_work_nodes(&lw) + lw.moved, 0);
  zs_octree_free(&lt);
  zs_octree_free(&pt);
  zs_scene_free(&s);
}
END_TEST

START_TEST(flat_for_a_handful) {
  /* Up to ZS_OCTREE_DEFAULT_FLAT objects the default tree is the root
   * alone, whatever their sizes and places, and stays so as they move; one
   * more and the levels are back. */
  for (int n = ZS_OCTREE_DEFAULT_FLAT; n <= ZS_OCTREE_DEFAULT_FLAT + 1; n++) {
    for (int kind = 0; kind < 2; kind++) {
      zs_rng rng;
      zs_rng_seed(&rng, 40 + (unsigned long long)n);
      zs_scene s;
      box_scene(&s, n);
      for (int i = 0; i < n; i++) set_box(&s, i, 60.0 + 55.0 * i, 100, 900 - 50.0 * i, 4);
      zs_octree_params p;
      zs_octree_params_default(&p, (zs_octree_kind)kind);
      zs_octree t;
      ck_assert_int_eq(zs_octree_build(&t, &s, &p, &err), ZS_OK);
      check_tree(&t, &s, 0);
      const int flat = n <= ZS_OCTREE_DEFAULT_FLAT;
      ck_assert_int_eq(t.flat, flat);
      zs_octree_stats st;
      zs_octree_stats_get(&t, &st);
      if (flat) {
        ck_assert_int_eq(st.nodes, 1);
        ck_assert_int_eq(t.node[ZS_OCTREE_ROOT].nobj, n);
        ck_assert_int_eq(t.params.max_depth, 0);
      } else {
        ck_assert_int_eq(st.depth, 4); /* boxes of radius 4: the deepest level */
        ck_assert_int_gt(st.nodes, n);
      }
      for (int r = 0; r < 5; r++) {
        random_round(&rng, &s);
        ck_assert_int_eq(zs_octree_update(&t, &s, NULL, &err), ZS_OK);
        check_tree(&t, &s, 0);
        zs_octree_stats_get(&t, &st);
        if (flat) ck_assert_int_eq(st.nodes, 1);
      }
      zs_octree_free(&t);
      zs_scene_free(&s);
    }
  }
}
END_TEST

START_TEST(split_policy) {
  /* split = 4: five small objects in the root's octant 0, each in its own
   * level-2 cell. */
  zs_scene s;
  box_scene(&s, 5);
  static const double xyz[5][3] = {
      {60, 60, 60}, {310, 60, 60}, {60, 310, 60}, {60, 60, 310}, {310, 310, 310}};
  for (int i = 0; i < 5; i++) set_box(&s, i, xyz[i][0], xyz[i][1], xyz[i][2], 1);
  zs_octree_params p;
  hierarchy_params(&p, ZS_OCTREE_LOOSE);
  p.split = 4;
  zs_octree t;
  ck_assert_int_eq(zs_octree_build(&t, &s, &p, &err), ZS_OK);
  check_tree(&t, &s, 0);
  /* the root split at the fifth object, its child 0 at once too: five
   * level-2 leaves holding one object each */
  zs_octree_stats st;
  zs_octree_stats_get(&t, &st);
  ck_assert_int_eq(st.nodes, 7);
  ck_assert_int_eq(st.objects_per_level[2], 5);
  ck_assert_int_eq(t.work.splits, 2);

  /* three objects leave octant 0: at 2 (= 4 / 2) its subtree collapses */
  set_box(&s, 0, 900, 900, 900, 1);
  ck_assert_int_eq(zs_octree_update(&t, &s, NULL, &err), ZS_OK);
  check_tree(&t, &s, 0);
  set_box(&s, 1, 900, 600, 900, 1);
  ck_assert_int_eq(zs_octree_update(&t, &s, NULL, &err), ZS_OK);
  check_tree(&t, &s, 0);
  ck_assert_int_eq(t.work.collapses, 0);
  set_box(&s, 2, 600, 900, 900, 1);
  ck_assert_int_eq(zs_octree_update(&t, &s, NULL, &err), ZS_OK);
  check_tree(&t, &s, 0);
  ck_assert_int_eq(t.work.collapses, 1);
  int32_t c0 = zs_octree_find(&t, 1, (int32_t[3]){0, 0, 0});
  ck_assert_int_ge(c0, 0);
  ck_assert_int_eq(t.node[c0].nobj, 2);
  ck_assert_int_eq(t.node[c0].split, 0);
  ck_assert_int_eq(t.home[3], c0);
  ck_assert_int_eq(t.home[4], c0);
  zs_octree_free(&t);
  zs_scene_free(&s);
}
END_TEST

START_TEST(spheres_scene_frames) {
  zs_scene s;
  ck_assert_msg(zs_gen_scene("spheres?count=600&moving=300&slices=8&stacks=6&seed=3", &s, &err) ==
                    ZS_OK,
                "%s", err.msg);
  zs_octree lt, pt;
  zs_octree_params p;
  hierarchy_params(&p, ZS_OCTREE_PLAIN);
  ck_assert_int_eq(zs_octree_build(&lt, &s, NULL, &err), ZS_OK);
  ck_assert_int_eq(zs_octree_build(&pt, &s, &p, &err), ZS_OK);
  check_tree(&lt, &s, 3);
  check_tree(&pt, &s, 3);
  zs_octree_work lw, pw;
  memset(&lw, 0, sizeof lw);
  memset(&pw, 0, sizeof pw);
  for (int f = 0; f < 40; f++) {
    zs_scene_advance(&s);
    ck_assert_int_eq(zs_octree_update(&lt, &s, &lw, &err), ZS_OK);
    ck_assert_int_eq(zs_octree_update(&pt, &s, &pw, &err), ZS_OK);
    if (f % 8 == 0) {
      check_tree(&lt, &s, 3);
      check_tree(&pt, &s, 3);
    }
  }
  check_tree(&lt, &s, 3);
  check_tree(&pt, &s, 3);
  ck_assert_int_eq(lw.moved, 40 * 300);
  ck_assert_int_eq(pw.moved, 40 * 300);
  /* most moves keep their cell; the plain tree re-inserts every one */
  ck_assert_int_gt(lw.same_cell, lw.moved * 9 / 10);
  ck_assert_int_eq(pw.inserts, pw.moved);
  ck_assert_int_lt(zs_octree_work_nodes(&lw), zs_octree_work_nodes(&pw));
  /* the spheres (radius 8 .. 16) all sit at level 4 of the loose tree */
  zs_octree_stats st;
  zs_octree_stats_get(&lt, &st);
  ck_assert_int_eq(st.objects_per_level[4], 600);
  zs_octree_stats_get(&pt, &st);
  ck_assert_int_gt(st.objects_per_level[0], 0); /* stuck on the middle planes */
  zs_octree_free(&lt);
  zs_octree_free(&pt);
  zs_scene_free(&s);
}
END_TEST

START_TEST(bad_parameters) {
  zs_scene s;
  box_scene(&s, 1);
  zs_octree t;
  zs_octree_params p;
  hierarchy_params(&p, ZS_OCTREE_LOOSE);
  p.looseness = 1.0;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_octree_build(&t, &s, &p, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "octree: looseness 1 is outside (1, 8]");
  p.looseness = 2.0;
  p.max_depth = 17;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_octree_build(&t, &s, &p, &err), ZS_ERR_ARG);
  p.max_depth = 4;
  p.flat = -1;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_octree_build(&t, &s, &p, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "octree: flat -1 is negative");
  p.flat = 0;
  ck_assert_int_eq(zs_octree_build(&t, &s, &p, &err), ZS_OK);
  zs_scene s2;
  box_scene(&s2, 2);
  zs_error_clear(&err);
  ck_assert_int_eq(zs_octree_update(&t, &s2, NULL, &err), ZS_ERR_ARG);
  zs_octree_free(&t);
  zs_scene_free(&s);
  zs_scene_free(&s2);
}
END_TEST

/* ---- zscan bench octree ------------------------------------------------------ */

static int have_gnuplot(void) {
  const char *path = getenv("PATH");
  if (!path) return 0;
  char buf[4096];
  for (const char *p = path; *p;) {
    const char *e = strchr(p, ':');
    size_t n = e ? (size_t)(e - p) : strlen(p);
    snprintf(buf, sizeof buf, "%.*s/gnuplot", (int)n, p);
    if (access(buf, X_OK) == 0) return 1;
    p += n + (e ? 1 : 0);
  }
  return 0;
}

START_TEST(bench_command) {
  char csv[4096], png[4096];
  snprintf(csv, sizeof csv, "%s", zs_test_bin("bench_octree_test.csv"));
  snprintf(png, sizeof png, "%s", zs_test_bin("bench_octree_test.png"));
  remove(csv);
  remove(png);
  int plot = have_gnuplot();
  char *argv[] = {"octree", "--count", "200", "--frames", "3", "--csv", csv,
                  plot ? "--plot" : NULL, png, NULL};
  int argc = plot ? 9 : 7;
  ck_assert_int_eq(zs_cmd_bench_octree(argc, argv), 0);
  FILE *f = fopen(csv, "r");
  ck_assert_ptr_nonnull(f);
  char line[1024];
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  ck_assert_msg(strncmp(line, "moving,loose_ms,plain_ms,", 25) == 0, "header: %s", line);
  int rows = 0, first = -1;
  while (fgets(line, sizeof line, f)) {
    if (rows == 0) first = atoi(line);
    rows++;
  }
  fclose(f);
  ck_assert_int_eq(rows, 10);
  ck_assert_int_eq(first, 20);
  if (plot) {
    f = fopen(png, "rb");
    ck_assert_ptr_nonnull(f);
    unsigned char sig[8];
    ck_assert_int_eq(fread(sig, 1, 8, f), 8);
    fclose(f);
    ck_assert(memcmp(sig, "\x89PNG\r\n\x1a\n", 8) == 0);
  }

  char *bad1[] = {"octree", "--frames", "0", NULL};
  ck_assert_int_ne(zs_cmd_bench_octree(3, bad1), 0);
  char *bad2[] = {"octree", "--looseness", "1", NULL};
  ck_assert_int_ne(zs_cmd_bench_octree(3, bad2), 0);
  char *bad3[] = {"octree", "--colour", NULL};
  ck_assert_int_ne(zs_cmd_bench_octree(2, bad3), 0);
}
END_TEST

int main(void) {
  Suite *s = suite_create("octree");
  TCase *tc = tcase_create("octree");
  tcase_set_timeout(tc, 300);
  tcase_add_test(tc, loose_level_and_cell);
  tcase_add_test(tc, loose_random_moves);
  tcase_add_test(tc, plain_random_moves);
  tcase_add_test(tc, tight_bounds_shrink);
  tcase_add_test(tc, same_moves_same_tree);
  tcase_add_test(tc, same_cell_move_is_free);
  tcase_add_test(tc, flat_for_a_handful);
  tcase_add_test(tc, split_policy);
  tcase_add_test(tc, spheres_scene_frames);
  tcase_add_test(tc, bad_parameters);
  tcase_add_test(tc, bench_command);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
