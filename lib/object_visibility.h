/* zscan lib — per-object visibility (zs_query_objects of zscan/zscan.h)
 * with a camera and size already chosen, for zscan query's options. */
#ifndef ZS_LIB_OBJECT_VISIBILITY_H
#define ZS_LIB_OBJECT_VISIBILITY_H

#include "scene/camera.h"
#include "scene/scene.h"
#include "zscan/zscan.h"

/* The frame of s seen by cam (completed from the bounds) at width x
 * height, drawn in zbuffer mode with id shading, once a sample (samples:
 * 0 or 1 one a pixel, else 2, 4, 8 or 16 at the standard positions); then
 * per instance the samples it owns and its box's query samples, summed
 * over the samples, sorted by first face.  shade is the render's: the
 * instances it draws transparent hide nothing (zs_query_objects). */
zs_status zs_query_objects_at(const zs_scene *s, const zs_camera *cam, int width, int height,
                              int cull_back, int samples, zs_shade shade,
                              zs_object_visibility **out, int32_t *n, zs_error *err);

#endif
