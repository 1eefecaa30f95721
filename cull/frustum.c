#include "cull/frustum.h"

#include <math.h>

#include "raster/raster.h"

void zs_frustum_from_matrices(zs_frustum *f, const double view[16], const double proj[16]) {
  double m[16];
  zs_mat_mul(m, proj, view);
  /* clip = M p; inside when -w <= x, y, z <= w: planes are row 3 +- row i */
  for (int i = 0; i < 3; i++)
    for (int s = 0; s < 2; s++) {
      double *p = f->plane[2 * i + s];
      for (int k = 0; k < 4; k++) p[k] = m[12 + k] + (s ? -m[4 * i + k] : m[4 * i + k]);
      double len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      if (len > 0)
        for (int k = 0; k < 4; k++) p[k] /= len;
    }
}

zs_frustum_result zs_frustum_test_box(const zs_frustum *f, const double lo[3], const double hi[3],
                                      unsigned *mask, uint64_t *tests) {
  zs_frustum_result r = ZS_FRUSTUM_INSIDE;
  for (int i = 0; i < 6; i++) {
    if (!(*mask & (1u << i))) continue;
    const double *p = f->plane[i];
    ++*tests;
    /* p-vertex: the corner farthest in the direction of the normal */
    double px = p[0] >= 0 ? hi[0] : lo[0], py = p[1] >= 0 ? hi[1] : lo[1];
    double pz = p[2] >= 0 ? hi[2] : lo[2];
    if (p[0] * px + p[1] * py + p[2] * pz + p[3] < 0) return ZS_FRUSTUM_OUTSIDE;
    double nx = p[0] >= 0 ? lo[0] : hi[0], ny = p[1] >= 0 ? lo[1] : hi[1];
    double nz = p[2] >= 0 ? lo[2] : hi[2];
    if (p[0] * nx + p[1] * ny + p[2] * nz + p[3] >= 0) *mask &= ~(1u << i); /* wholly inside */
    else r = ZS_FRUSTUM_INTERSECT;
  }
  return r;
}

void zs_view_box_make(zs_view_box *b, const double view[16], const double proj[16]) {
  for (int i = 0; i < 16; i++) b->view[i] = view[i];
  /* perspective: proj[0] = cot(fovx/2), proj[5] = cot(fovy/2);
   * near and far from the depth row */
  double a = proj[10], c = proj[11];
  if (proj[14] != 0.0) {
    b->znear = c / (a - 1.0);
    b->zfar = c / (a + 1.0);
    b->hx = b->zfar / proj[0];
    b->hy = b->zfar / proj[5];
  } else { /* orthographic: the box is the view volume itself */
    b->znear = (c + 1.0) / a;
    b->zfar = (c - 1.0) / a;
    b->hx = 1.0 / proj[0] + fabs(proj[3] / proj[0]);
    b->hy = 1.0 / proj[5] + fabs(proj[7] / proj[5]);
  }
}

int zs_view_box_contains(const zs_view_box *b, const double p[3]) {
  double v[4];
  zs_mat_apply(b->view, p, v);
  return v[0] >= -b->hx && v[0] <= b->hx && v[1] >= -b->hy && v[1] <= b->hy &&
         v[2] <= -b->znear && v[2] >= -b->zfar;
}
