/* zscan lib — the camera and size of a frame: what the user gave put
 * over the scene's own, then completed from the scene's bounds, as
 * `zscan render`, the library's zs_render and the walks all do. */
#ifndef ZS_LIB_FRAME_CAMERA_H
#define ZS_LIB_FRAME_CAMERA_H

#include <stdint.h>

#include "scene/camera.h"
#include "scene/scene.h"

/* The image size of a frame of scene: width and height where given (not
 * 0), else the scene's own, else the device's default. */
void zs_frame_size(const zs_scene *scene, int width, int height, int *w, int *h);

/* The camera a frame is drawn with: cam completed from the scene's bounds
 * (eye, target, near and far where cam lacks them) at aspect w/h. */
void zs_frame_complete_camera(const zs_scene *scene, const zs_camera *cam, int width, int height,
                              zs_camera *used);

/* The camera's matrices for the scene at aspect w/h: cam completed from
 * the scene's bounds, then checked. */
zs_status zs_frame_camera(const zs_scene *scene, const zs_camera *cam, int width,
                          int height, double view[16], double proj[16], zs_error *err);

/* The camera a frame of scene s uses: the scene's own, with what the user
 * gave (u: its has_ flags; fovy when fovy_given) put over it.  An eye of
 * the user's own drops the scene's target, near and far (they belong to
 * the scene's eye); the rest is completed from the bounds later. */
void zs_frame_view(const zs_scene *s, const zs_camera *u, int fovy_given, zs_camera *cam);

/* The camera of frame f of the scene's walk: the path's (frame f modulo
 * the path's length) or, without a path, the scene's camera; completed
 * from the scene's bounds at aspect w/h. */
zs_status zs_frame_path_camera(const zs_scene *s, int32_t f, int w, int h, double view[16],
                               double proj[16], zs_error *err);

/* Replaces s's camera path by the named one (zs_path_named: static,
 * translate, roll, yaw, fast) of frames frames, from s's camera completed
 * at aspect width/height. */
zs_status zs_frame_named_path(zs_scene *s, const char *name, int32_t frames, int width, int height,
                              zs_error *err);

#endif
