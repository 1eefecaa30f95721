/* A frame's camera and size: what the user gave over the scene's own,
 * completed from the scene's bounds (lib/frame_camera.h). */
#include "lib/frame_camera.h"

#include <string.h>

#include "raster/raster.h"
#include "scene/paths.h"

void zs_frame_size(const zs_scene *scene, int width, int height, int *w, int *h) {
  *w = width ? width : scene->width ? scene->width : ZS_DEVICE_DEFAULT_WIDTH;
  *h = height ? height : scene->height ? scene->height : ZS_DEVICE_DEFAULT_HEIGHT;
}

void zs_frame_complete_camera(const zs_scene *scene, const zs_camera *cam, int width, int height,
                              zs_camera *used) {
  *used = *cam;
  zs_camera_complete(used, scene->lo, scene->hi, (double)width / height);
}

zs_status zs_frame_camera(const zs_scene *scene, const zs_camera *cam, int width,
                          int height, double view[16], double proj[16], zs_error *err) {
  zs_camera c;
  zs_frame_complete_camera(scene, cam, width, height, &c);
  return zs_camera_matrices(&c, (double)width / height, view, proj, err);
}

void zs_frame_view(const zs_scene *s, const zs_camera *u, int fovy_given, zs_camera *cam) {
  *cam = s->camera;
  if (u->has_eye) memcpy(cam->eye, u->eye, sizeof cam->eye), cam->has_eye = 1;
  if (u->has_target) memcpy(cam->target, u->target, sizeof cam->target), cam->has_target = 1;
  if (u->has_up) memcpy(cam->up, u->up, sizeof cam->up), cam->has_up = 1;
  if (u->has_dir) memcpy(cam->dir, u->dir, sizeof cam->dir), cam->has_dir = 1;
  if (u->fit > 0) cam->fit = u->fit;
  if (u->has_near) cam->znear = u->znear, cam->has_near = 1;
  if (u->has_far) cam->zfar = u->zfar, cam->has_far = 1;
  if (fovy_given) cam->fovy = u->fovy;
  if (u->ortho) {
    cam->ortho = 1;
    memcpy(cam->extent, u->extent, sizeof cam->extent);
  }
  /* an eye of the user's own with the scene's target would look somewhere
   * the user did not ask: the target then comes from the bounds */
  if (u->has_eye && !u->has_target) cam->has_target = 0;
  /* and the scene's near and far planes belong to the scene's eye */
  if (u->has_eye && !u->has_near) cam->has_near = 0;
  if (u->has_eye && !u->has_far) cam->has_far = 0;
}

zs_status zs_frame_path_camera(const zs_scene *s, int32_t f, int w, int h, double view[16],
                               double proj[16], zs_error *err) {
  zs_camera cam = s->camera;
  if (s->path.nkeys > 0) zs_path_camera(s, f % (s->path.frames > 0 ? s->path.frames : 1), &cam);
  return zs_frame_camera(s, &cam, w, h, view, proj, err);
}

zs_status zs_frame_named_path(zs_scene *s, const char *name, int32_t frames, int width, int height,
                              zs_error *err) {
  zs_camera base;
  zs_frame_complete_camera(s, &s->camera, width, height, &base);
  zs_path p;
  if (zs_path_named(name, &base, frames, &p, err)) return err->code;
  zs_path_free(&s->path);
  s->path = p;
  return ZS_OK;
}
