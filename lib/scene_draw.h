/* zscan lib — a scene's instances drawn on a device: the one loop of
 * draws every frame, map and pass uses. */
#ifndef ZS_LIB_SCENE_DRAW_H
#define ZS_LIB_SCENE_DRAW_H

#include "raster/raster.h"
#include "scene/scene.h"

/* Draws every instance of scene (no clear, no finish). */
zs_status zs_frame_draw_scene(zs_device *dev, const zs_scene *scene, zs_error *err);
/* The same for the instances i with drawn[i] != 0 only. */
zs_status zs_frame_draw_some(zs_device *dev, const zs_scene *scene, const uint8_t *drawn,
                             zs_error *err);

/* The lines and points of every instance (zs_device_draw_lines,
 * _points), after its faces, line_width and point_size pixels (0: 1);
 * nothing to do (whatever the mode) when the scene has none. */
zs_status zs_frame_draw_prims(zs_device *dev, const zs_scene *scene, double line_width,
                              double point_size, zs_point_shape shape, zs_error *err);

/* Whether some instance of scene has lines or points. */
int zs_scene_has_prims(const zs_scene *scene);

/* A new frame of everything from (view, proj): clears dev, sets its
 * camera and draws every instance of scene; the caller finishes it. */
zs_status zs_frame_draw_all(zs_device *dev, const zs_scene *scene, const double view[16],
                            const double proj[16], zs_error *err);

#endif
