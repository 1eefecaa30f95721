/* zscan cull — where an object goes in the octree (octree.h): the boxes of
 * the cells, and the target cell of a box, for the loose tree (from its
 * radius and centre) and for the plain tree (by descent from the root).
 * octree.c places objects by these; they read only the tree's geometry.
 */
#include <math.h>

#include "cull/box.h"
#include "cull/octree.h"

void zs_octree_cell_box(const zs_octree *t, int level, const int32_t cell[3], double factor,
                        double lo[3], double hi[3]) {
  double s = ldexp(t->side, -level);
  double margin = 0.5 * (factor - 1.0) * s;
  for (int k = 0; k < 3; k++) {
    lo[k] = t->origin[k] + (double)cell[k] * s - margin;
    hi[k] = t->origin[k] + (double)(cell[k] + 1) * s + margin;
  }
}

/* The loose tree's target: level from the radius, cell from the centre. */
static int loose_target(const zs_octree *t, const double lo[3], const double hi[3],
                        int32_t *level, int32_t cell[3]) {
  const int max = t->params.max_depth;
  double r = 0.0;
  for (int k = 0; k < 3; k++)
    if (0.5 * (hi[k] - lo[k]) > r) r = 0.5 * (hi[k] - lo[k]);
  /* fit(L) = (k - 1) s_L: the largest radius that level L takes */
  const double fit0 = (t->params.looseness - 1.0) * 0.5 * t->side;
  int L;
  double ratio = fit0 / r;
  if (!(r > 0.0) || !(ratio < 131072.0)) {
    L = max; /* a point, or smaller than any level's limit */
  } else {
    int e;
    frexp(ratio, &e); /* ratio in [2^(e-1), 2^e): floor(log2(ratio)) = e - 1 */
    L = e - 1;
  }
  if (L < 0) L = 0;
  if (L > max) L = max;
  /* settle rounding of the ratio with the exact test r <= fit(L) */
  if (L > 0 && !(r <= ldexp(fit0, -L))) L--;
  else if (L < max && r <= ldexp(fit0, -(L + 1))) L++;

  int steps = 1;
  for (;; L--) {
    double s = ldexp(t->side, -L);
    int32_t n = (int32_t)1 << L;
    for (int k = 0; k < 3; k++) {
      double x = floor((0.5 * (lo[k] + hi[k]) - t->origin[k]) / s);
      cell[k] = !(x >= 0.0) ? 0 : x >= (double)n ? n - 1 : (int32_t)x;
    }
    double blo[3], bhi[3];
    zs_octree_cell_box(t, L, cell, t->params.looseness, blo, bhi);
    if (L == 0 || zs_box_inside(lo, hi, blo, bhi)) break;
    steps++; /* rounding (or a box outside the bounds): one level up */
  }
  *level = L;
  return steps;
}

/* The plain tree's target: descent from the root.  A node's box is its
 * cell.  Starting at the root, the descent looks at the three planes that
 * split the current cell into its children: a box entirely on one side of
 * each plane lies in one child cell, which becomes the current cell; a box
 * that crosses any of them stays.  So an object ends in the smallest cell
 * (down to max_depth) that contains its whole box, and an object that
 * straddles a plane, however small it is, stays in the node above the
 * plane: the root keeps every object that crosses the middle of the
 * scene.  Finding the cell costs one test per level, and an update of the
 * plain tree is always delete + this descent + insert (octree.c), with the
 * tight bounds re-computed on both paths. */
static int plain_target(const zs_octree *t, const double lo[3], const double hi[3],
                        int32_t *level, int32_t cell[3]) {
  int32_t L = 0;
  cell[0] = cell[1] = cell[2] = 0;
  double blo[3], bhi[3];
  zs_octree_cell_box(t, 0, cell, 1.0, blo, bhi);
  int tested = 1;
  if (zs_box_inside(lo, hi, blo, bhi)) {
    while (L < t->params.max_depth) {
      /* the splitting planes of the current cell, the children's shared
       * faces: origin + (2 c + 1) s, as zs_octree_cell_box computes them */
      double s = ldexp(t->side, -(L + 1));
      int32_t child[3] = {0, 0, 0}; /* (each set below unless it straddles) */
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
      if (!zs_box_inside(lo, hi, blo, bhi)) break; /* not reached: same planes */
      L++;
      for (int k = 0; k < 3; k++) cell[k] = child[k];
    }
  }
  *level = L;
  return tested;
}

int zs_octree_target(const zs_octree *t, const double lo[3], const double hi[3], int32_t *level,
                     int32_t cell[3]) {
  if (t->params.kind == ZS_OCTREE_PLAIN) return plain_target(t, lo, hi, level, cell);
  return loose_target(t, lo, hi, level, cell);
}
