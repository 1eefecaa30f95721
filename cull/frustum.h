/* zscan cull — the view frustum: planes, box tests with plane masking,
 * and the conservative view box of the conservative-visibility paper. */
#ifndef ZS_CULL_FRUSTUM_H
#define ZS_CULL_FRUSTUM_H

#include <stdint.h>

/* Six planes a x + b y + c z + d >= 0 inside, in world coordinates, from
 * the rows of proj x view (Gribb and Hartmann): left, right, bottom, top,
 * near, far. */
typedef struct zs_frustum {
  double plane[6][4];
} zs_frustum;

enum { ZS_FRUSTUM_ALL_PLANES = 0x3F };

typedef enum zs_frustum_result {
  ZS_FRUSTUM_OUTSIDE,   /* wholly outside one plane */
  ZS_FRUSTUM_INTERSECT, /* crosses a plane (or cannot be told apart) */
  ZS_FRUSTUM_INSIDE     /* inside every plane */
} zs_frustum_result;

void zs_frustum_from_matrices(zs_frustum *f, const double view[16], const double proj[16]);

/* Tests the box lo..hi against the planes set in *mask (bit i: plane i).
 * For each plane the box corner farthest along the plane's normal (the
 * "p-vertex") decides outside; the nearest (the "n-vertex") decides
 * inside.  Planes the box is wholly inside are cleared from *mask: a
 * child, inside its parent's box, need not test them again (plane
 * masking).  *tests counts plane tests done. */
zs_frustum_result zs_frustum_test_box(const zs_frustum *f, const double lo[3], const double hi[3],
                                      unsigned *mask, uint64_t *tests);

/* The conservative view box (PCVR paper): in view space, the box from the
 * near plane to the far plane that contains the frustum,
 *   |x| <= far tan(fovx / 2), |y| <= far tan(fovy / 2), -far <= z <= -near.
 * A point is kept when it lies inside: six comparisons after one
 * transformation of the point. */
typedef struct zs_view_box {
  double view[16];
  double hx, hy, znear, zfar;
} zs_view_box;

void zs_view_box_make(zs_view_box *b, const double view[16], const double proj[16]);
int zs_view_box_contains(const zs_view_box *b, const double p[3]);

#endif
