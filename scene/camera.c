#include "scene/camera.h"

#include <math.h>

#include "util/exactmath.h"
#include "util/matrix.h"

void zs_camera_default(zs_camera *c) {
  *c = (zs_camera){.up = {0, 1, 0}, .fovy = ZS_CAMERA_DEFAULT_FOVY};
}

void zs_camera_complete(zs_camera *c, const double lo[3], const double hi[3],
                        double aspect) {
  double centre[3], r2 = 0.0;
  for (int i = 0; i < 3; i++) {
    centre[i] = 0.5 * (lo[i] + hi[i]);
    double h = 0.5 * (hi[i] - lo[i]);
    r2 += h * h;
  }
  double radius = sqrt(r2);
  if (!(radius > 0.0)) radius = 1.0;
  if (!c->has_target) {
    for (int i = 0; i < 3; i++) c->target[i] = centre[i];
    c->has_target = 1;
  }
  if (!c->has_eye) {
    const double fallback[3] = ZS_CAMERA_DEFAULT_DIR;
    const double *dir = c->has_dir ? c->dir : fallback;
    double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    /* The narrower half angle, by its tangent (tan is monotonic), and
     * its sine from the tangent: sin = t / sqrt(1 + t^2). */
    double t = zs_tan_deg(0.5 * c->fovy) * (aspect < 1.0 ? aspect : 1.0);
    double dist = 1.05 * radius * sqrt(1.0 + t * t) / t;
    if (c->fit > 0) dist /= c->fit;
    for (int i = 0; i < 3; i++) c->eye[i] = c->target[i] + dir[i] / len * dist;
    c->has_eye = 1;
  }
  double d2 = 0.0;
  for (int i = 0; i < 3; i++) d2 += (c->eye[i] - centre[i]) * (c->eye[i] - centre[i]);
  double d = sqrt(d2);
  if (!c->has_far) {
    c->zfar = 1.01 * (d + radius);
    c->has_far = 1;
  }
  if (!c->has_near) {
    double n = 0.99 * (d - radius);
    double floor_n = c->zfar * 1e-4;
    /* orthographic: the eye may stand among the objects, near may be < 0 */
    c->znear = c->ortho ? d - 1.01 * radius : n > floor_n ? n : floor_n;
    c->has_near = 1;
  }
}

zs_status zs_camera_matrices(const zs_camera *c, double aspect, double view[16],
                             double proj[16], zs_error *err) {
  if (c->ortho && !(c->extent[0] < c->extent[1] && c->extent[2] < c->extent[3]))
    return zs_error_set(err, ZS_ERR_ARG, "ortho %g,%g,%g,%g: need left < right and bottom < top",
                        c->extent[0], c->extent[1], c->extent[2], c->extent[3]);
  if (!c->ortho && !(c->fovy > 0.0 && c->fovy < 180.0))
    return zs_error_set(err, ZS_ERR_ARG, "fovy %g: must be between 0 and 180 degrees", c->fovy);
  /* glOrtho takes any near < far; a perspective camera needs near > 0 */
  if (!c->ortho && !(c->znear > 0.0))
    return zs_error_set(err, ZS_ERR_ARG, "near %g: must be greater than 0", c->znear);
  if (!(c->znear < c->zfar))
    return zs_error_set(err, ZS_ERR_ARG, "near %g, far %g: near must be less than far",
                        c->znear, c->zfar);
  if (c->eye[0] == c->target[0] && c->eye[1] == c->target[1] && c->eye[2] == c->target[2])
    return zs_error_set(err, ZS_ERR_ARG, "eye and target are the same point");
  if (!zs_mat_look_at(view, c->eye, c->target, c->up))
    return zs_error_set(err, ZS_ERR_ARG, "up %g,%g,%g: zero or parallel to the view direction",
                        c->up[0], c->up[1], c->up[2]);
  if (c->ortho)
    zs_mat_ortho(proj, c->extent[0], c->extent[1], c->extent[2], c->extent[3], c->znear, c->zfar);
  else
    zs_mat_perspective(proj, c->fovy, aspect, c->znear, c->zfar);
  return ZS_OK;
}
