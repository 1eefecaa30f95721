/* zscan cull — octrees over a scene's instances: Ulrich's loose octree and
 * a plain octree as its baseline, both kept up to date as objects move.
 *
 * One type, two kinds.  Both trees share the node layout, the object lists,
 * the tight bounds, the split policy and the node storage; they differ only
 * in where an object goes (its "target" node) and in how an update handles
 * a moved object:
 *
 *   LOOSE (Ulrich, Game Programming Gems 1, 4.11).  A node of level L
 *     covers a cube cell of side S_L = S_0 / 2^L; its box, the "loose box",
 *     is the cell enlarged k times about its centre (looseness k > 1,
 *     default 2: half a cell more on every side).  An object of radius r
 *     (half the largest side of its box) whose centre lies in a cell of
 *     half-size s_L = S_L / 2 fits that cell's loose box whenever
 *     r <= (k - 1) s_L.  So its level is the deepest L with that property,
 *       L = floor(log2((k - 1) s_0 / r)), clamped to 0 .. max_depth,
 *     and its cell at L is floor((centre - origin) / S_L) per axis: both in
 *     O(1), from its size and its centre, with no descent through the tree.
 *     (Should rounding put the box a hair outside that loose box, the object
 *     takes the parent cell instead: the stored tree never breaks the rule
 *     "every object lies inside its node's loose box".)
 *     An update compares the new target with the old one: the same cell
 *     costs no structural work at all, only the tight bounds.
 *
 *   PLAIN.  A node's box is its cell.  An object goes to the deepest cell
 *     that contains its whole box, found by descending from the root and
 *     testing the child cells level by level; an object that straddles a
 *     child's boundary stays in the parent.  An update is the textbook
 *     delete + re-insert by descent + re-bound, for every moved object.
 *
 * The root cell is the cube around the scene's bounds (scene->lo/hi):
 * centred on them, side their largest extent.  An object whose box does not
 * fit the root's box (it left the bounds) is kept at the root.
 *
 * NODES
 *   Nodes live in one array (t->node) and refer to each other by index;
 *   index 0 is the root, which always exists.  A node is named by its level
 *   and its cell (x, y, z at that level); child octant o = x + 2 y + 4 z of
 *   the low bits of the child's cell.  Nodes are created on demand (the
 *   tree is sparse) and deleted when their subtree becomes empty; a deleted
 *   slot has level -1 and is reused last-freed first.  A hash table maps
 *   (level, cell) to the node, so finding a target node is O(1) whatever
 *   the depth (a dense array per level would need 8^L entries at level L).
 *
 * SPLIT POLICY (parameter split = N >= 0)
 *   A node is a leaf or split.  A leaf above max_depth that holds more than
 *   N objects is split: every object it holds whose target is deeper moves
 *   into the child on its way (created if needed), and children that now
 *   hold more than N split in turn.  An object goes to its target node if
 *   that exists, else to the deepest existing node on the way to it: a
 *   split node gets the missing child created, a leaf keeps the object.  So
 *   an object deeper than a leaf waits there until the leaf splits.  A
 *   split node whose subtree falls to N/2 objects or fewer collapses: all
 *   the subtree's objects move up into it and its descendants are deleted
 *   (the gap between N and N/2 keeps a node from splitting and collapsing
 *   on every frame).  Non-root nodes with empty subtrees are deleted.  With
 *   N = 0 (the default) every object sits at its target node and the tree
 *   is exactly the union of the paths from the root to the objects' nodes.
 *   Insertion stays O(1)-ish: one hash probe per level tried (usually one),
 *   plus, only when the structure changes, work bounded by max_depth and N.
 *   A moved object is inserted at its new node before its old node is
 *   tidied (collapsed or deleted), so ancestors the two nodes share are
 *   never deleted and created again.
 *
 * TIGHT BOUNDS
 *   Every node keeps the box of its content (tlo, thi; empty flag): the
 *   union of its objects' boxes and its children's tight boxes, exact (the
 *   min and max of the objects' coordinates).  Culling tests these.  They
 *   are kept up to date incrementally: when box P leaves a node and box Q
 *   enters, the node grows by Q if P lay strictly inside its tight box, and
 *   is recomputed from its content only if P touched one of its faces; the
 *   parent then sees the node's old and new tight boxes as its P and Q, up
 *   the chain until nothing changes (at most max_depth + 1 nodes).
 *
 * DETERMINISM
 *   No randomness, no addresses, no clocks: the same build and the same
 *   moves give the same arrays, byte for byte (zs_octree_hash).
 *
 * Every object is an instance of the scene: object i is s->inst[i]; the
 * tree reads only the instances' boxes (lo, hi), the scene bounds and
 * ninst, and keeps its own copy of each box.
 */
#ifndef ZS_CULL_OCTREE_H
#define ZS_CULL_OCTREE_H

#include <stdint.h>

#include "zscan/error.h"
#include "scene/scene.h"

enum {
  ZS_OCTREE_ROOT = 0,        /* index of the root node */
  ZS_OCTREE_NONE = -1,       /* no node / no object */
  ZS_OCTREE_MAX_DEPTH = 16,  /* deepest max_depth accepted */
  ZS_OCTREE_DEFAULT_DEPTH = 4,
  ZS_OCTREE_DEFAULT_FLAT = 16  /* see zs_octree_params.flat */
};

#define ZS_OCTREE_DEFAULT_LOOSENESS 2.0
#define ZS_OCTREE_MAX_LOOSENESS 8.0

typedef enum zs_octree_kind { ZS_OCTREE_LOOSE = 0, ZS_OCTREE_PLAIN = 1 } zs_octree_kind;

typedef struct zs_octree_params {
  zs_octree_kind kind;
  int max_depth;    /* levels 0 .. max_depth, 0 .. ZS_OCTREE_MAX_DEPTH (default 4) */
  double looseness; /* k, 1 < k <= 8 (default 2); the plain tree stores 1 */
  int split;        /* N >= 0: see SPLIT POLICY (default 0) */
  int flat;         /* a scene of at most this many objects gets no hierarchy:
                     * the tree is built with depth 0, the root alone holding
                     * every object, and a culler traversing it tests the objects
                     * one by one (default 16; 0: always the hierarchy) */
} zs_octree_params;

/* A node; read it, never write it. */
typedef struct zs_octnode {
  int32_t parent;         /* -1 for the root */
  int32_t child[8];       /* by octant, ZS_OCTREE_NONE when absent */
  int32_t first;          /* first object held here (list through t->next) */
  int32_t nobj;           /* objects held here */
  int32_t count;          /* objects in the subtree (here and below) */
  int32_t level;          /* 0 at the root; -1: a free slot */
  int32_t cell[3];        /* cell coordinates at that level, 0 .. 2^level - 1 */
  int32_t split;          /* 1: split (children may exist), 0: leaf */
  int32_t empty;          /* 1: no content, tight box all zero */
  double lo[3], hi[3];    /* the node's box: loose box (loose), cell (plain) */
  double tlo[3], thi[3];  /* tight box of the content */
} zs_octnode;

/* Work done, added up over calls.  "Nodes touched" (zs_octree_work_nodes)
 * is visits + grows + rebounds + nodes created + nodes deleted. */
typedef struct zs_octree_work {
  int64_t moved;         /* objects re-placed because their box changed */
  int64_t same_cell;     /* of those: target unchanged, tight bounds only */
  int64_t same_node;     /* of those: target changed, node kept (split policy) */
  int64_t inserts;       /* objects linked into a node (placement) */
  int64_t deletes;       /* objects unlinked from a node (placement) */
  int64_t relinks;       /* objects moved by splits and collapses */
  int64_t visits;        /* placement: hash probes (loose), cells tested (plain) */
  int64_t nodes_created;
  int64_t nodes_deleted;
  int64_t splits, collapses;
  int64_t grows;         /* tight boxes widened by a union */
  int64_t rebounds;      /* tight boxes recomputed from their content */
  int64_t scanned;       /* boxes read by those recomputations */
} zs_octree_work;

typedef struct zs_octree {
  zs_octree_params params; /* as built: max_depth is 0 when flat */
  int32_t flat;          /* 1: nobjects <= params.flat, the root alone */
  double origin[3];      /* the root cell's low corner */
  double side;           /* the root cell's side S_0 */
  /* nodes */
  zs_octnode *node;      /* slots 0 .. nslots - 1; free slots have level -1 */
  int32_t nslots, cap_nodes;
  int32_t nnodes;        /* live nodes */
  int32_t free_head;     /* first free slot (chained through parent), -1 */
  /* objects: object i is instance i */
  int32_t nobjects;
  int32_t *home;         /* node holding the object */
  int32_t *next, *prev;  /* its node's list, ZS_OCTREE_NONE at the ends */
  int32_t *tlevel;       /* target level and cell */
  int32_t (*tcell)[3];
  double (*olo)[3], (*ohi)[3]; /* the boxes the tree knows */
  /* (level, cell) -> node, open addressing with linear probing */
  uint64_t *hkey;
  int32_t *hval;         /* -1: empty slot */
  uint32_t hmask;
  zs_octree_work work;   /* everything since the build (build included) */
} zs_octree;

/* Defaults: depth 4, looseness 2, split 0, flat 16. */
void zs_octree_params_default(zs_octree_params *p, zs_octree_kind kind);

/* Builds the tree over s's instances (inserted in index order).  p NULL:
 * the loose defaults.  ZS_ERR_ARG for parameters out of range, ZS_ERR_NOMEM.
 * All memory is taken here: updates never allocate and cannot fail. */
zs_status zs_octree_build(zs_octree *t, const zs_scene *s, const zs_octree_params *p,
                          zs_error *err);
void zs_octree_free(zs_octree *t);

/* Re-places every instance whose box differs from the one the tree holds
 * (call it after zs_scene_advance).  Adds the work to t->work and, when work
 * is not NULL, to *work.  ZS_ERR_ARG when s has a different number of
 * instances than the tree was built with. */
zs_status zs_octree_update(zs_octree *t, const zs_scene *s, zs_octree_work *work,
                           zs_error *err);

/* Re-places object i (0 <= i < nobjects) with the box lo .. hi (nothing to
 * do when the box is the one held). */
void zs_octree_move(zs_octree *t, int32_t i, const double lo[3], const double hi[3],
                    zs_octree_work *work);

/* ---- reading the tree (for culling) ----
 * Nodes: t->node[n] for live n (level >= 0); children t->node[n].child[o].
 * Objects held by node n:
 *   for (int32_t o = t->node[n].first; o != ZS_OCTREE_NONE; o = t->next[o])
 */

/* The node (level, cell), or ZS_OCTREE_NONE. */
int32_t zs_octree_find(const zs_octree *t, int level, const int32_t cell[3]);

/* The box of cell (level, cell) enlarged factor times about its centre
 * (factor 1: the cell itself). */
void zs_octree_cell_box(const zs_octree *t, int level, const int32_t cell[3], double factor,
                        double lo[3], double hi[3]);

/* Where object box lo .. hi belongs, by the tree's kind: its target level
 * and cell (the node it lives in when the split policy does not hold it
 * higher).  Returns the number of placement steps (hash probes are not
 * included; cells tested by the plain descent are). */
int zs_octree_target(const zs_octree *t, const double lo[3], const double hi[3], int32_t *level,
                     int32_t cell[3]);

typedef struct zs_octree_stats {
  int32_t nodes;                                /* live nodes */
  int32_t leaves;                               /* live nodes without children */
  int32_t depth;                                /* deepest live level */
  int32_t max_objects;                          /* most objects held by one node */
  int32_t outside;                              /* objects outside the root's box */
  int32_t nodes_per_level[ZS_OCTREE_MAX_DEPTH + 1];
  int32_t objects_per_level[ZS_OCTREE_MAX_DEPTH + 1]; /* by the level of their node */
} zs_octree_stats;

void zs_octree_stats_get(const zs_octree *t, zs_octree_stats *st);

/* Nodes touched by work w: visits + grows + rebounds + created + deleted. */
int64_t zs_octree_work_nodes(const zs_octree_work *w);

/* w += a */
void zs_octree_work_add(zs_octree_work *w, const zs_octree_work *a);

/* 64-bit FNV-1a over every node slot and every object's record, field by
 * field: equal hashes mean equal trees (layout included). */
uint64_t zs_octree_hash(const zs_octree *t);

/* Checks every invariant stated above (structure, counts, lists, hash
 * table, targets, boxes, exact tight bounds, split policy); ZS_ERR_ARG
 * with the first violation found. */
zs_status zs_octree_check(const zs_octree *t, zs_error *err);

#endif
