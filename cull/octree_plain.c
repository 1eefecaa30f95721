/* zscan cull — the plain octree's placement: descent from the root.
 *
 * A node's box is its cell.  Starting at the root, the descent looks at
 * the three planes that split the current cell into its children: a box
 * entirely on one side of each plane lies in one child cell, which becomes
 * the current cell; a box that crosses any of them stays.  So an object
 * ends in the smallest cell (down to max_depth) that contains its whole
 * box, and an object that straddles a plane, however small it is, stays in
 * the node above the plane: the root keeps every object that crosses the
 * middle of the scene.  Finding the cell costs one test per level, and an
 * update of the plain tree is always delete + this descent + insert
 * (octree.c, move_one), with the tight bounds re-computed on both paths.
 */
#include <math.h>

#include "cull/octree_internal.h"

int zs_oct_plain_target(const zs_octree *t, const double lo[3], const double hi[3],
                        int32_t *level, int32_t cell[3]) {
  int32_t L = 0;
  cell[0] = cell[1] = cell[2] = 0;
  double blo[3], bhi[3];
  zs_octree_cell_box(t, 0, cell, 1.0, blo, bhi);
  int tested = 1;
  if (zs_oct_inside(lo, hi, blo, bhi)) {
    while (L < t->params.max_depth) {
      /* the splitting planes of the current cell, the children's shared
       * faces: origin + (2 c + 1) s, as zs_octree_cell_box computes them */
      double s = ldexp(t->side, -(L + 1));
      int32_t child[3];
      int straddles = 0;
      for (int k = 0; k < 3; k++) {
        double mid = t->origin[k] + (double)(2 * cell[k] + 1) * s;
        if (hi[k] <= mid) child[k] = 2 * cell[k];
        else if (lo[k] >= mid) child[k] = 2 * cell[k] + 1;
        else straddles = 1;
      }
      tested++;
      if (straddles) break;
      zs_octree_cell_box(t, L + 1, child, 1.0, blo, bhi);
      if (!zs_oct_inside(lo, hi, blo, bhi)) break; /* not reached: same planes */
      L++;
      for (int k = 0; k < 3; k++) cell[k] = child[k];
    }
  }
  *level = L;
  return tested;
}
