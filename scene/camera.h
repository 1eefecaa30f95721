/* zscan scene — the camera: where it stands, where it looks, its lens.
 *
 * Conventions of gluLookAt / gluPerspective (raster/raster.h).  A camera
 * may be given in part; zs_camera_complete fills in what is missing from
 * the bounds of what is to be seen:
 *   - no eye: the default direction.  The eye looks at the centre of the
 *     bounds from the direction dir (when has_dir; else
 *     ZS_CAMERA_DEFAULT_DIR: front, right and above), far enough that the
 *     bounding sphere fits the narrower of the two fields of view with
 *     5 % to spare, that distance divided by fit (when fit > 0: 2 comes
 *     twice as close);
 *   - no target: the centre of the bounds;
 *   - no near / far: the bounding sphere seen from the eye, far = distance
 *     to its back + 1 %, near = distance to its front less 1 %, at least
 *     far / 10^4 (the eye may be inside).
 * An orthographic camera (ortho) maps the view-space rectangle extent
 * (left, right, bottom, top) onto the image, as glOrtho; for it fovy is
 * not used, and near may be 0 or negative (planes behind the eye).  The lecture's examples use one: with extent
 * (-0.5, W - 0.5, -0.5, H - 0.5) and the eye looking down -z, world (x, y)
 * lands on the centre of pixel column x, row H - 1 - y.
 */
#ifndef ZS_SCENE_CAMERA_H
#define ZS_SCENE_CAMERA_H

#include "zscan/error.h"

#define ZS_CAMERA_DEFAULT_DIR {0.55, 0.45, 1.0}
#define ZS_CAMERA_DEFAULT_FOVY 45.0

typedef struct zs_camera {
  double eye[3], target[3], up[3];
  double dir[3];        /* the automatic eye's direction from the target, when
                           has_dir (else ZS_CAMERA_DEFAULT_DIR) */
  double fit;           /* the automatic eye's distance over the default; 0: 1 */
  int has_dir;
  double fovy;          /* vertical field of view, degrees, in (0, 180) */
  int ortho;            /* orthographic (glOrtho) instead of perspective */
  double extent[4];     /* orthographic: left, right, bottom, top, in view units */
  double znear, zfar;   /* 0 < znear < zfar */
  int has_eye, has_target, has_up, has_near, has_far;
} zs_camera;

/* A camera with nothing given: up +y, fovy 45. */
void zs_camera_default(zs_camera *c);

/* Fills what c lacks from the bounds lo..hi (see above). */
void zs_camera_complete(zs_camera *c, const double lo[3], const double hi[3],
                        double aspect);

/* Checks the camera and makes its view and projection matrices; the
 * message names what is wrong (fovy outside (0, 180), near <= 0,
 * near >= far, eye == target, up zero or parallel to the view). */
zs_status zs_camera_matrices(const zs_camera *c, double aspect, double view[16],
                             double proj[16], zs_error *err);

#endif
