/* zscan cull — what octree.c (the shared core and the loose tree) and
 * octree_plain.c (the plain tree) share; not part of the public API. */
#ifndef ZS_CULL_OCTREE_INTERNAL_H
#define ZS_CULL_OCTREE_INTERNAL_H

#include "cull/octree.h"

/* Whether box lo .. hi lies inside blo .. bhi (closed). */
int zs_oct_inside(const double lo[3], const double hi[3], const double blo[3],
                  const double bhi[3]);

/* The plain tree's target: the deepest cell (<= max_depth) containing the
 * whole box, by descent from the root; level 0 when the box leaves the
 * root cell.  Returns the number of cells tested. */
int zs_oct_plain_target(const zs_octree *t, const double lo[3], const double hi[3],
                        int32_t *level, int32_t cell[3]);

/* Unlinks object i from its node: counts and tight bounds (its held box
 * olo/ohi[i] leaves).  Returns the node it left, which the caller then
 * passes to zs_oct_tidy. */
int32_t zs_oct_remove(zs_octree *t, int32_t i, zs_octree_work *w);

/* After an object left node n: the highest split node on n's chain whose
 * subtree holds split/2 objects or fewer collapses, and empty non-root
 * nodes are deleted upwards. */
void zs_oct_tidy(zs_octree *t, int32_t n, zs_octree_work *w);

/* Links object i (not in the tree; box and target already stored) into
 * the node its target and the split policy give, growing tight bounds and
 * splitting the node if it now holds too many. */
void zs_oct_place(zs_octree *t, int32_t i, zs_octree_work *w);

/* Stores box lo .. hi and target (level, cell) as object i's. */
void zs_oct_store(zs_octree *t, int32_t i, const double lo[3], const double hi[3],
                  int32_t level, const int32_t cell[3]);

#endif
