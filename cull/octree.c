/* zscan cull — the octree (octree.h): nodes, object lists, hash table,
 * tight bounds, split policy, build and update.  Where an object goes (its
 * target cell, loose or plain) is octree_target.c's.
 */
#include "cull/octree.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cull/box.h"

/* ---- tight boxes -------------------------------------------------------- */

/* Whether p (a part of the content of old) reaches one of old's faces, so
 * that old without p may be smaller.  (Always, for an empty old.) */
static int box_touches(const zs_box *p, const zs_box *old) {
  for (int k = 0; k < 3; k++)
    if (p->lo[k] <= old->lo[k] || p->hi[k] >= old->hi[k]) return 1;
  return 0;
}

static zs_box tight_of(const zs_octnode *n) {
  return n->empty ? zs_box_empty() : zs_box_of(n->tlo, n->thi);
}

/* A node stores an empty tight box as all zero, with its empty flag. */
static void set_tight(zs_octnode *n, const zs_box *b) {
  n->empty = zs_box_is_empty(b);
  for (int k = 0; k < 3; k++) {
    n->tlo[k] = n->empty ? 0.0 : b->lo[k];
    n->thi[k] = n->empty ? 0.0 : b->hi[k];
  }
}

/* ---- parameters, cells ------------------------------------------------- */

void zs_octree_params_default(zs_octree_params *p, zs_octree_kind kind) {
  p->kind = kind;
  p->max_depth = ZS_OCTREE_DEFAULT_DEPTH;
  p->looseness = ZS_OCTREE_DEFAULT_LOOSENESS;
  p->split = 0;
  p->flat = ZS_OCTREE_DEFAULT_FLAT;
}

/* The factor by which the tree enlarges its cells into node boxes. */
static double box_factor(const zs_octree *t) {
  return t->params.kind == ZS_OCTREE_LOOSE ? t->params.looseness : 1.0;
}

/* ---- the hash table: (level, cell) -> node ------------------------------
 * Linear probing; deletion shifts the following entries back, so the table
 * never holds tombstones and its contents depend only on the live keys and
 * the order they came in. */

static uint64_t node_key(int level, const int32_t cell[3]) {
  return (uint64_t)level << 48 | (uint64_t)cell[0] << 32 | (uint64_t)cell[1] << 16 |
         (uint64_t)cell[2];
}

static uint32_t key_slot(const zs_octree *t, uint64_t key) {
  uint64_t h = key * 0x9E3779B97F4A7C15ull;
  return (uint32_t)(h >> 32) & t->hmask;
}

static int32_t hash_find(const zs_octree *t, uint64_t key) {
  for (uint32_t i = key_slot(t, key);; i = (i + 1) & t->hmask) {
    if (t->hval[i] < 0) return ZS_OCTREE_NONE;
    if (t->hkey[i] == key) return t->hval[i];
  }
}

static void hash_put(zs_octree *t, uint64_t key, int32_t node) {
  uint32_t i = key_slot(t, key);
  while (t->hval[i] >= 0) i = (i + 1) & t->hmask;
  t->hkey[i] = key;
  t->hval[i] = node;
}

static void hash_del(zs_octree *t, uint64_t key) {
  uint32_t i = key_slot(t, key);
  while (t->hkey[i] != key || t->hval[i] < 0) i = (i + 1) & t->hmask;
  /* Shift back every following entry of the run whose home slot does not
   * lie cyclically in (i, j]. */
  for (uint32_t j = i;;) {
    j = (j + 1) & t->hmask;
    if (t->hval[j] < 0) break;
    uint32_t h = key_slot(t, t->hkey[j]);
    int stays = i <= j ? (i < h && h <= j) : (i < h || h <= j);
    if (stays) continue;
    t->hkey[i] = t->hkey[j];
    t->hval[i] = t->hval[j];
    i = j;
  }
  t->hkey[i] = 0;
  t->hval[i] = -1;
}

int32_t zs_octree_find(const zs_octree *t, int level, const int32_t cell[3]) {
  if (level < 0 || level > t->params.max_depth) return ZS_OCTREE_NONE;
  for (int k = 0; k < 3; k++)
    if (cell[k] < 0 || cell[k] >= (1 << level)) return ZS_OCTREE_NONE;
  return hash_find(t, node_key(level, cell));
}

/* ---- nodes ------------------------------------------------------------- */

/* The octant of the child of a node at `level` on the way to target cell
 * tcell at tlevel > level. */
static int octant_toward(int level, int32_t tlevel, const int32_t tcell[3]) {
  int shift = tlevel - level - 1;
  return (tcell[0] >> shift & 1) | (tcell[1] >> shift & 1) << 1 | (tcell[2] >> shift & 1) << 2;
}

static int32_t node_new(zs_octree *t, int32_t parent, int octant, zs_octree_work *w) {
  int32_t n;
  if (t->free_head >= 0) {
    n = t->free_head;
    t->free_head = t->node[n].parent;
  } else {
    n = t->nslots++; /* capacity is enough by construction (zs_octree_build) */
  }
  zs_octnode *nd = &t->node[n];
  memset(nd, 0, sizeof *nd);
  nd->parent = parent;
  for (int o = 0; o < 8; o++) nd->child[o] = ZS_OCTREE_NONE;
  nd->first = ZS_OCTREE_NONE;
  nd->empty = 1;
  if (parent < 0) {
    nd->level = 0;
  } else {
    const zs_octnode *p = &t->node[parent];
    nd->level = p->level + 1;
    for (int k = 0; k < 3; k++) nd->cell[k] = 2 * p->cell[k] + (octant >> k & 1);
    t->node[parent].child[octant] = n;
  }
  zs_octree_cell_box(t, nd->level, nd->cell, box_factor(t), nd->lo, nd->hi);
  hash_put(t, node_key(nd->level, nd->cell), n);
  t->nnodes++;
  w->nodes_created++;
  return n;
}

/* Frees node n's slot (its objects and children already gone). */
static void node_free(zs_octree *t, int32_t n, zs_octree_work *w) {
  zs_octnode *nd = &t->node[n];
  hash_del(t, node_key(nd->level, nd->cell));
  if (nd->parent >= 0) {
    zs_octnode *p = &t->node[nd->parent];
    for (int o = 0; o < 8; o++)
      if (p->child[o] == n) p->child[o] = ZS_OCTREE_NONE;
  }
  memset(nd, 0, sizeof *nd);
  nd->level = -1;
  nd->parent = t->free_head;
  t->free_head = n;
  t->nnodes--;
  w->nodes_deleted++;
}

/* ---- object lists ------------------------------------------------------ */

static void link_obj(zs_octree *t, int32_t n, int32_t i) {
  zs_octnode *nd = &t->node[n];
  t->prev[i] = ZS_OCTREE_NONE;
  t->next[i] = nd->first;
  if (nd->first >= 0) t->prev[nd->first] = i;
  nd->first = i;
  nd->nobj++;
  t->home[i] = n;
}

static void unlink_obj(zs_octree *t, int32_t i) {
  zs_octnode *nd = &t->node[t->home[i]];
  if (t->prev[i] >= 0) t->next[t->prev[i]] = t->next[i];
  else nd->first = t->next[i];
  if (t->next[i] >= 0) t->prev[t->next[i]] = t->prev[i];
  t->next[i] = t->prev[i] = ZS_OCTREE_NONE;
  nd->nobj--;
  t->home[i] = ZS_OCTREE_NONE;
}

static void add_count(zs_octree *t, int32_t n, int32_t delta) {
  for (; n >= 0; n = t->node[n].parent) t->node[n].count += delta;
}

/* Stores box lo .. hi and target (level, cell) as object i's. */
static void store_object(zs_octree *t, int32_t i, const double lo[3], const double hi[3],
                  int32_t level, const int32_t cell[3]) {
  for (int k = 0; k < 3; k++) {
    t->olo[i][k] = lo[k];
    t->ohi[i][k] = hi[k];
    t->tcell[i][k] = cell[k];
  }
  t->tlevel[i] = level;
}

/* ---- tight bounds ------------------------------------------------------ */

/* Node n's tight box from its content: its objects and its children. */
static void recompute(zs_octree *t, int32_t n, zs_octree_work *w) {
  zs_octnode *nd = &t->node[n];
  zs_box b = zs_box_empty();
  for (int32_t i = nd->first; i >= 0; i = t->next[i]) {
    zs_box_add(&b, t->olo[i], t->ohi[i]);
    w->scanned++;
  }
  for (int o = 0; o < 8; o++) {
    int32_t c = nd->child[o];
    if (c < 0) continue;
    w->scanned++;
    if (!t->node[c].empty) zs_box_add(&b, t->node[c].tlo, t->node[c].thi);
  }
  set_tight(nd, &b);
  w->rebounds++;
}

/* Box p left node n's content and box q entered it (either may be empty);
 * brings the tight boxes of n and its ancestors up to date. */
static void refresh(zs_octree *t, int32_t n, zs_box p, zs_box q, zs_octree_work *w) {
  while (n >= 0) {
    zs_octnode *nd = &t->node[n];
    zs_box old = tight_of(nd);
    if (!zs_box_is_empty(&p) && box_touches(&p, &old)) {
      recompute(t, n, w);
    } else if (!zs_box_is_empty(&q)) {
      zs_box b = old;
      zs_box_add(&b, q.lo, q.hi);
      set_tight(nd, &b);
      w->grows++;
    } else {
      return;
    }
    zs_box now = tight_of(nd);
    if (zs_box_eq(&old, &now)) return;
    p = old;
    q = now;
    n = nd->parent;
  }
}

/* ---- split policy ------------------------------------------------------ */

static void maybe_split(zs_octree *t, int32_t n, zs_octree_work *w);

/* Splits leaf n: its objects with deeper targets move one level down. */
static void split_node(zs_octree *t, int32_t n, zs_octree_work *w) {
  t->node[n].split = 1;
  w->splits++;
  int level = t->node[n].level;
  int32_t next;
  for (int32_t i = t->node[n].first; i >= 0; i = next) {
    next = t->next[i];
    if (t->tlevel[i] <= level) continue;
    int o = octant_toward(level, t->tlevel[i], t->tcell[i]);
    int32_t c = t->node[n].child[o];
    if (c < 0) c = node_new(t, n, o, w);
    unlink_obj(t, i);
    link_obj(t, c, i);
    t->node[c].count++;
    zs_box b = tight_of(&t->node[c]);
    zs_box_add(&b, t->olo[i], t->ohi[i]);
    set_tight(&t->node[c], &b);
    w->grows++;
    w->relinks++;
  }
  /* n's content is the same, so its tight box is too. */
  for (int o = 0; o < 8; o++)
    if (t->node[n].child[o] >= 0) maybe_split(t, t->node[n].child[o], w);
}

static void maybe_split(zs_octree *t, int32_t n, zs_octree_work *w) {
  const zs_octnode *nd = &t->node[n];
  if (!nd->split && nd->level < t->params.max_depth && nd->nobj > t->params.split)
    split_node(t, n, w);
}

/* Moves every object below node `into`'s descendant n up into `into` and
 * frees n and its descendants. */
static void gather(zs_octree *t, int32_t n, int32_t into, zs_octree_work *w) {
  while (t->node[n].first >= 0) {
    int32_t i = t->node[n].first;
    unlink_obj(t, i);
    link_obj(t, into, i);
    w->relinks++;
  }
  for (int o = 0; o < 8; o++)
    if (t->node[n].child[o] >= 0) gather(t, t->node[n].child[o], into, w);
  node_free(t, n, w);
}

/* Split node a becomes a leaf holding its whole subtree's objects (same
 * content: counts and tight box stay). */
static void collapse(zs_octree *t, int32_t a, zs_octree_work *w) {
  for (int o = 0; o < 8; o++)
    if (t->node[a].child[o] >= 0) gather(t, t->node[a].child[o], a, w);
  t->node[a].split = 0;
  w->collapses++;
}

/* After an object left node n: the highest split node on n's chain whose
 * subtree fell to split/2 objects or fewer collapses, then empty non-root
 * nodes are deleted upwards. */
static void tidy(zs_octree *t, int32_t n, zs_octree_work *w) {
  int32_t a = ZS_OCTREE_NONE;
  for (int32_t m = n; m >= 0; m = t->node[m].parent)
    if (t->node[m].split && t->node[m].count <= t->params.split / 2) a = m;
  if (a >= 0) {
    collapse(t, a, w);
    n = a;
  }
  while (n != ZS_OCTREE_ROOT && t->node[n].count == 0 && t->node[n].nobj == 0) {
    int32_t p = t->node[n].parent;
    int leaf = 1;
    for (int o = 0; o < 8; o++)
      if (t->node[n].child[o] >= 0) leaf = 0;
    if (!leaf) collapse(t, n, w); /* empty children only */
    node_free(t, n, w);
    n = p;
  }
}

/* ---- placing objects --------------------------------------------------- */

/* The deepest existing node on the way from the root to (level, cell). */
static int32_t deepest_on_path(const zs_octree *t, int32_t level, const int32_t cell[3],
                               zs_octree_work *w) {
  for (int32_t l = level; l > 0; l--) {
    int32_t c[3];
    for (int k = 0; k < 3; k++) c[k] = cell[k] >> (level - l);
    w->visits++;
    int32_t n = hash_find(t, node_key(l, c));
    if (n >= 0) return n;
  }
  return ZS_OCTREE_ROOT;
}

/* Links object i (not in the tree; box and target already stored) into
 * the node its target and the split policy give, growing tight bounds and
 * splitting the node if it now holds too many. */
static void place_object(zs_octree *t, int32_t i, zs_octree_work *w) {
  int32_t n = deepest_on_path(t, t->tlevel[i], t->tcell[i], w);
  if (t->node[n].level < t->tlevel[i] && t->node[n].split)
    n = node_new(t, n, octant_toward(t->node[n].level, t->tlevel[i], t->tcell[i]), w);
  link_obj(t, n, i);
  add_count(t, n, 1);
  w->inserts++;
  refresh(t, n, zs_box_empty(), zs_box_of(t->olo[i], t->ohi[i]), w);
  maybe_split(t, n, w);
}

/* Unlinks object i from its node: counts and tight bounds (its held box
 * olo/ohi[i] leaves).  Returns the node it left, for tidy. */
static int32_t remove_object(zs_octree *t, int32_t i, zs_octree_work *w) {
  int32_t n = t->home[i];
  unlink_obj(t, i);
  add_count(t, n, -1);
  w->deletes++;
  refresh(t, n, zs_box_of(t->olo[i], t->ohi[i]), zs_box_empty(), w);
  return n;
}

/* ---- build, update ----------------------------------------------------- */

void zs_octree_free(zs_octree *t) {
  free(t->node);
  free(t->home);
  free(t->next);
  free(t->prev);
  free(t->tlevel);
  free(t->tcell);
  free(t->olo);
  free(t->ohi);
  free(t->hkey);
  free(t->hval);
  memset(t, 0, sizeof *t);
}

zs_status zs_octree_build(zs_octree *t, const zs_scene *s, const zs_octree_params *p,
                          zs_error *err) {
  memset(t, 0, sizeof *t);
  zs_octree_params def;
  if (!p) {
    zs_octree_params_default(&def, ZS_OCTREE_LOOSE);
    p = &def;
  }
  if (p->kind != ZS_OCTREE_LOOSE && p->kind != ZS_OCTREE_PLAIN)
    return zs_error_set(err, ZS_ERR_ARG, "octree: unknown kind %d", (int)p->kind);
  if (p->max_depth < 0 || p->max_depth > ZS_OCTREE_MAX_DEPTH)
    return zs_error_set(err, ZS_ERR_ARG, "octree: depth %d is outside 0 .. %d", p->max_depth,
                        ZS_OCTREE_MAX_DEPTH);
  if (p->kind == ZS_OCTREE_LOOSE &&
      !(p->looseness > 1.0 && p->looseness <= ZS_OCTREE_MAX_LOOSENESS))
    return zs_error_set(err, ZS_ERR_ARG, "octree: looseness %g is outside (1, %g]", p->looseness,
                        ZS_OCTREE_MAX_LOOSENESS);
  if (p->split < 0)
    return zs_error_set(err, ZS_ERR_ARG, "octree: split %d is negative", p->split);
  if (p->flat < 0)
    return zs_error_set(err, ZS_ERR_ARG, "octree: flat %d is negative", p->flat);
  t->params = *p;
  if (t->params.kind == ZS_OCTREE_PLAIN) t->params.looseness = 1.0;
  /* A handful of objects: levels would cost more node visits and box tests
   * than they save, so the root alone lists them (the number of instances
   * never changes after the build, so neither does this choice). */
  if (s->ninst <= p->flat) {
    t->flat = 1;
    t->params.max_depth = 0;
  }
  p = &t->params;

  /* the root cell: the cube around the scene's bounds */
  double side = 0.0;
  for (int k = 0; k < 3; k++)
    if (s->hi[k] - s->lo[k] > side) side = s->hi[k] - s->lo[k];
  if (!(side > 0.0) || !isfinite(side)) side = 1.0;
  t->side = side;
  for (int k = 0; k < 3; k++) {
    double mid = 0.5 * (s->lo[k] + s->hi[k]);
    t->origin[k] = isfinite(mid) ? mid - 0.5 * side : -0.5 * side;
  }

  /* Every non-root node has an object below it, except, during one move,
   * the path the moved object just left (emptied nodes are deleted after
   * the insertion): at most 1 + (n + 1) depth nodes, and never more than
   * the full tree's. */
  int64_t n = s->ninst < 0 ? 0 : s->ninst;
  int64_t cap = 1 + (n + 1) * p->max_depth, full = 0;
  for (int l = 0; l <= p->max_depth && full < cap; l++) full += (int64_t)1 << (3 * l);
  if (full < cap) cap = full;
  if (cap > (int64_t)1 << 28)
    return zs_error_set(err, ZS_ERR_LIMIT, "octree: %lld nodes would be too many",
                        (long long)cap);
  uint32_t hcap = 16;
  while (hcap < 2 * (uint64_t)cap) hcap *= 2;

  t->cap_nodes = (int32_t)cap;
  t->node = calloc((size_t)cap, sizeof *t->node);
  size_t no = n > 0 ? (size_t)n : 1;
  t->home = malloc(no * sizeof *t->home);
  t->next = malloc(no * sizeof *t->next);
  t->prev = malloc(no * sizeof *t->prev);
  t->tlevel = malloc(no * sizeof *t->tlevel);
  t->tcell = malloc(no * sizeof *t->tcell);
  t->olo = malloc(no * sizeof *t->olo);
  t->ohi = malloc(no * sizeof *t->ohi);
  t->hkey = calloc(hcap, sizeof *t->hkey);
  t->hval = malloc(hcap * sizeof *t->hval);
  if (!t->node || !t->home || !t->next || !t->prev || !t->tlevel || !t->tcell || !t->olo ||
      !t->ohi || !t->hkey || !t->hval) {
    zs_octree_free(t);
    return zs_error_set(err, ZS_ERR_NOMEM, "octree: out of memory");
  }
  for (uint32_t h = 0; h < hcap; h++) t->hval[h] = -1;
  t->hmask = hcap - 1;
  t->free_head = ZS_OCTREE_NONE;
  t->nobjects = (int32_t)n;

  zs_octree_work *w = &t->work;
  node_new(t, -1, 0, w); /* the root, index 0 */
  for (int32_t i = 0; i < t->nobjects; i++) {
    int32_t level, cell[3];
    w->visits += zs_octree_target(t, s->inst[i].lo, s->inst[i].hi, &level, cell);
    store_object(t, i, s->inst[i].lo, s->inst[i].hi, level, cell);
    t->next[i] = t->prev[i] = t->home[i] = ZS_OCTREE_NONE;
    place_object(t, i, w);
  }
  return ZS_OK;
}

static int same_box(const zs_octree *t, int32_t i, const double lo[3], const double hi[3]) {
  for (int k = 0; k < 3; k++)
    if (t->olo[i][k] != lo[k] || t->ohi[i][k] != hi[k]) return 0;
  return 1;
}

/* One moved object, the work into w. */
static void move_one(zs_octree *t, int32_t i, const double lo[3], const double hi[3],
                     zs_octree_work *w) {
  w->moved++;
  zs_box old = zs_box_of(t->olo[i], t->ohi[i]);
  int32_t level, cell[3];
  w->visits += zs_octree_target(t, lo, hi, &level, cell);
  if (t->params.kind == ZS_OCTREE_LOOSE) {
    int same = level == t->tlevel[i];
    for (int k = 0; k < 3; k++) same = same && cell[k] == t->tcell[i][k];
    int32_t n = t->home[i];
    if (!same) {
      /* another cell: does the split policy keep it in the same node? */
      int32_t d = deepest_on_path(t, level, cell, w);
      if (d == n && !(t->node[d].level < level && t->node[d].split)) {
        w->same_node++;
        same = 1;
      }
    } else {
      w->same_cell++;
    }
    if (same) {
      store_object(t, i, lo, hi, level, cell);
      refresh(t, n, old, zs_box_of(lo, hi), w);
      return;
    }
  }
  /* delete, re-insert, re-bound; the old node is tidied (collapsed or
   * deleted when the split policy says so) only after the insertion, so
   * ancestors shared by the old and the new node are never deleted and
   * created again */
  int32_t from = remove_object(t, i, w);
  store_object(t, i, lo, hi, level, cell);
  place_object(t, i, w);
  tidy(t, from, w);
}

void zs_octree_move(zs_octree *t, int32_t i, const double lo[3], const double hi[3],
                    zs_octree_work *work) {
  if (i < 0 || i >= t->nobjects || same_box(t, i, lo, hi)) return;
  zs_octree_work w;
  memset(&w, 0, sizeof w);
  move_one(t, i, lo, hi, &w);
  zs_octree_work_add(&t->work, &w);
  if (work) zs_octree_work_add(work, &w);
}

zs_status zs_octree_update(zs_octree *t, const zs_scene *s, zs_octree_work *work,
                           zs_error *err) {
  if (s->ninst != t->nobjects)
    return zs_error_set(err, ZS_ERR_ARG, "octree: the scene has %d instances, the tree %d",
                        (int)s->ninst, (int)t->nobjects);
  zs_octree_work w;
  memset(&w, 0, sizeof w);
  for (int32_t i = 0; i < t->nobjects; i++)
    if (!same_box(t, i, s->inst[i].lo, s->inst[i].hi))
      move_one(t, i, s->inst[i].lo, s->inst[i].hi, &w);
  zs_octree_work_add(&t->work, &w);
  if (work) zs_octree_work_add(work, &w);
  return ZS_OK;
}

/* ---- reading ----------------------------------------------------------- */

int64_t zs_octree_work_nodes(const zs_octree_work *w) {
  return w->visits + w->grows + w->rebounds + w->nodes_created + w->nodes_deleted;
}

void zs_octree_work_add(zs_octree_work *w, const zs_octree_work *a) {
  w->moved += a->moved;
  w->same_cell += a->same_cell;
  w->same_node += a->same_node;
  w->inserts += a->inserts;
  w->deletes += a->deletes;
  w->relinks += a->relinks;
  w->visits += a->visits;
  w->nodes_created += a->nodes_created;
  w->nodes_deleted += a->nodes_deleted;
  w->splits += a->splits;
  w->collapses += a->collapses;
  w->grows += a->grows;
  w->rebounds += a->rebounds;
  w->scanned += a->scanned;
}

void zs_octree_stats_get(const zs_octree *t, zs_octree_stats *st) {
  memset(st, 0, sizeof *st);
  for (int32_t n = 0; n < t->nslots; n++) {
    const zs_octnode *nd = &t->node[n];
    if (nd->level < 0) continue;
    st->nodes++;
    st->nodes_per_level[nd->level]++;
    st->objects_per_level[nd->level] += nd->nobj;
    if (nd->level > st->depth) st->depth = nd->level;
    if (nd->nobj > st->max_objects) st->max_objects = nd->nobj;
    int leaf = 1;
    for (int o = 0; o < 8; o++)
      if (nd->child[o] >= 0) leaf = 0;
    st->leaves += leaf;
  }
  const zs_octnode *root = &t->node[ZS_OCTREE_ROOT];
  for (int32_t i = 0; i < t->nobjects; i++)
    if (!zs_box_inside(t->olo[i], t->ohi[i], root->lo, root->hi)) st->outside++;
}

static uint64_t fnv(uint64_t h, const void *data, size_t n) {
  const unsigned char *p = data;
  for (size_t i = 0; i < n; i++) {
    h ^= p[i];
    h *= 0x100000001b3ull;
  }
  return h;
}

uint64_t zs_octree_hash(const zs_octree *t) {
  uint64_t h = 0xcbf29ce484222325ull;
  h = fnv(h, &t->nslots, sizeof t->nslots);
  h = fnv(h, &t->nnodes, sizeof t->nnodes);
  h = fnv(h, &t->free_head, sizeof t->free_head);
  for (int32_t n = 0; n < t->nslots; n++) {
    const zs_octnode *nd = &t->node[n];
    h = fnv(h, &nd->parent, sizeof nd->parent);
    h = fnv(h, nd->child, sizeof nd->child);
    h = fnv(h, &nd->first, sizeof nd->first);
    h = fnv(h, &nd->nobj, sizeof nd->nobj);
    h = fnv(h, &nd->count, sizeof nd->count);
    h = fnv(h, &nd->level, sizeof nd->level);
    h = fnv(h, nd->cell, sizeof nd->cell);
    h = fnv(h, &nd->split, sizeof nd->split);
    h = fnv(h, &nd->empty, sizeof nd->empty);
    h = fnv(h, nd->lo, sizeof nd->lo);
    h = fnv(h, nd->hi, sizeof nd->hi);
    h = fnv(h, nd->tlo, sizeof nd->tlo);
    h = fnv(h, nd->thi, sizeof nd->thi);
  }
  for (int32_t i = 0; i < t->nobjects; i++) {
    h = fnv(h, &t->home[i], sizeof t->home[i]);
    h = fnv(h, &t->next[i], sizeof t->next[i]);
    h = fnv(h, &t->prev[i], sizeof t->prev[i]);
    h = fnv(h, &t->tlevel[i], sizeof t->tlevel[i]);
    h = fnv(h, t->tcell[i], sizeof t->tcell[i]);
    h = fnv(h, t->olo[i], sizeof t->olo[i]);
    h = fnv(h, t->ohi[i], sizeof t->ohi[i]);
  }
  return h;
}

/* ---- the invariants ---------------------------------------------------- */

#define CHECK(cond, ...)                                   \
  do {                                                     \
    if (!(cond)) return zs_error_set(err, ZS_ERR_ARG, __VA_ARGS__); \
  } while (0)

zs_status zs_octree_check(const zs_octree *t, zs_error *err) {
  const int N = t->params.split, max = t->params.max_depth;
  CHECK(t->nslots >= 1 && t->nslots <= t->cap_nodes, "octree: %d slots", (int)t->nslots);
  CHECK(t->node[0].level == 0 && t->node[0].parent == -1, "octree: node 0 is not the root");
  CHECK(!t->flat || (t->params.max_depth == 0 && t->nobjects <= t->params.flat),
        "octree: flat with depth %d and %d objects", t->params.max_depth, (int)t->nobjects);

  /* the free list */
  int32_t nfree = 0;
  for (int32_t f = t->free_head; f >= 0; f = t->node[f].parent) {
    CHECK(f < t->nslots && t->node[f].level == -1 && nfree < t->nslots,
          "octree: free list broken at %d", (int)f);
    nfree++;
  }

  int32_t live = 0;
  for (int32_t n = 0; n < t->nslots; n++) {
    const zs_octnode *nd = &t->node[n];
    if (nd->level < 0) continue;
    live++;
    CHECK(nd->level <= max, "octree: node %d at level %d", (int)n, (int)nd->level);
    /* links */
    if (n != ZS_OCTREE_ROOT) {
      const zs_octnode *p = &t->node[nd->parent];
      CHECK(nd->parent >= 0 && nd->parent < t->nslots && p->level == nd->level - 1,
            "octree: node %d has a bad parent", (int)n);
      int o = (nd->cell[0] & 1) | (nd->cell[1] & 1) << 1 | (nd->cell[2] & 1) << 2;
      CHECK(p->child[o] == n, "octree: node %d is not its parent's child %d", (int)n, o);
      for (int k = 0; k < 3; k++)
        CHECK(nd->cell[k] >> 1 == p->cell[k], "octree: node %d lies outside its parent", (int)n);
      CHECK(p->split, "octree: node %d hangs below a leaf", (int)n);
      CHECK(nd->count >= 1, "octree: node %d is empty", (int)n);
    }
    CHECK(zs_octree_find(t, nd->level, nd->cell) == n, "octree: node %d is not in the table",
          (int)n);
    double lo[3], hi[3];
    zs_octree_cell_box(t, nd->level, nd->cell, box_factor(t), lo, hi);
    for (int k = 0; k < 3; k++)
      CHECK(lo[k] == nd->lo[k] && hi[k] == nd->hi[k], "octree: node %d has a wrong box", (int)n);
    /* objects, counts, tight box */
    int32_t count = 0, prev = ZS_OCTREE_NONE;
    zs_box b = zs_box_empty();
    for (int32_t i = nd->first; i >= 0; i = t->next[i]) {
      CHECK(i < t->nobjects && count < t->nobjects, "octree: node %d: bad list", (int)n);
      CHECK(t->home[i] == n && t->prev[i] == prev, "octree: object %d: bad list links", (int)i);
      prev = i;
      count++;
      zs_box_add(&b, t->olo[i], t->ohi[i]);
      CHECK(t->tlevel[i] >= nd->level, "octree: object %d above its target", (int)i);
      for (int k = 0; k < 3; k++)
        CHECK(t->tcell[i][k] >> (t->tlevel[i] - nd->level) == nd->cell[k],
              "octree: object %d is off its target's path", (int)i);
      if (t->tlevel[i] > nd->level)
        CHECK(!nd->split, "octree: object %d waits in split node %d", (int)i, (int)n);
      /* only the root keeps objects that leave its box */
      CHECK(n == ZS_OCTREE_ROOT || zs_box_inside(t->olo[i], t->ohi[i], nd->lo, nd->hi),
            "octree: object %d is outside node %d's box", (int)i, (int)n);
    }
    CHECK(count == nd->nobj, "octree: node %d holds %d objects, says %d", (int)n, (int)count,
          (int)nd->nobj);
    for (int o = 0; o < 8; o++) {
      int32_t c = nd->child[o];
      if (c < 0) continue;
      CHECK(c < t->nslots && t->node[c].level == nd->level + 1 && t->node[c].parent == n,
            "octree: node %d: bad child %d", (int)n, o);
      count += t->node[c].count;
      if (!t->node[c].empty) zs_box_add(&b, t->node[c].tlo, t->node[c].thi);
    }
    CHECK(count == nd->count, "octree: node %d counts %d, has %d", (int)n, (int)nd->count,
          (int)count);
    zs_box tb = tight_of(nd);
    CHECK(zs_box_eq(&b, &tb) && nd->empty == (count == 0),
          "octree: node %d's tight box is not the union of its content", (int)n);
    if (nd->empty)
      for (int k = 0; k < 3; k++)
        CHECK(nd->tlo[k] == 0.0 && nd->thi[k] == 0.0, "octree: node %d: empty box not zero",
              (int)n);
    /* split policy */
    if (!nd->split && nd->level < max)
      CHECK(nd->nobj <= N, "octree: leaf %d holds %d > %d objects", (int)n, (int)nd->nobj, N);
    if (nd->split) CHECK(nd->count > N / 2, "octree: split node %d holds only %d", (int)n,
                         (int)nd->count);
    if (nd->level == max) CHECK(!nd->split, "octree: node %d below the depth limit", (int)n);
  }
  CHECK(live == t->nnodes && live + nfree == t->nslots, "octree: %d live nodes, %d free, %d slots",
        (int)live, (int)nfree, (int)t->nslots);
  CHECK(t->node[0].count == t->nobjects, "octree: the root counts %d of %d objects",
        (int)t->node[0].count, (int)t->nobjects);

  /* the hash table holds exactly the live nodes */
  int32_t entries = 0;
  for (uint32_t h = 0; h <= t->hmask; h++) {
    if (t->hval[h] < 0) continue;
    entries++;
    CHECK(hash_find(t, t->hkey[h]) == t->hval[h], "octree: table slot %u unreachable", h);
  }
  CHECK(entries == live, "octree: the table holds %d nodes of %d", (int)entries, (int)live);

  /* every object: placed, its target is what its box gives */
  for (int32_t i = 0; i < t->nobjects; i++) {
    CHECK(t->home[i] >= 0 && t->home[i] < t->nslots && t->node[t->home[i]].level >= 0,
          "octree: object %d has no node", (int)i);
    int32_t level, cell[3];
    zs_octree_target(t, t->olo[i], t->ohi[i], &level, cell);
    CHECK(level == t->tlevel[i] && cell[0] == t->tcell[i][0] && cell[1] == t->tcell[i][1] &&
              cell[2] == t->tcell[i][2],
          "octree: object %d has a stale target", (int)i);
  }
  return ZS_OK;
}
