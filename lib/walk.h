/* zscan lib — the frame step of a walk (zscan/walk.h) in its two pieces:
 * the scene and camera moving on, and one method drawing the frame.
 * zs_walk_next is the two for one method; `zscan walk` moves the scene
 * once a frame and runs the second piece for each of its methods, so the
 * frames the command measures are the library's.  These are the
 * library's own: zs_walk_step_, apart from the public zs_walk_ names. */
#ifndef ZS_LIB_WALK_H
#define ZS_LIB_WALK_H

#include <stdint.h>

#include "cull/cull.h"
#include "cull/octree.h"
#include "scene/scene.h"
#include "zscan/walk.h"

/* The frames of a walk of s taking every step-th frame of its path: the
 * path's frames over step, rounded up, or 1 without a path. */
int32_t zs_walk_step_count(const zs_scene *s, int step);

/* Brings the walk to its frame k: from the second frame on (k > 0) the
 * scene advances step frames of its path and tree follows it; then the
 * camera of path frame k * step at width x height into view and proj. */
zs_status zs_walk_step_scene(zs_scene *s, zs_octree *tree, int32_t k, int step, int width,
                             int height, double view[16], double proj[16], zs_error *err);

/* One method's frame seen from (view, proj): its culler draws into dev,
 * whose frame then finishes (its rows to sink when sink is not NULL);
 * the culler's counters into cs. */
zs_status zs_walk_step_method(zs_culler *c, zs_device *dev, const zs_scene *s,
                              const zs_octree *tree, const double view[16],
                              const double proj[16], zs_cull_stats *cs, zs_row_sink sink,
                              void *user, zs_error *err);

#endif
