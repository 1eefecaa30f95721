/* zscan — walking a scene's camera path with a culling method: the frames
 * `zscan walk` measures, one method at a time.  An extra to zscan.h.
 *
 *   zs_walk *w;
 *   zs_walk_opts o = {0};
 *   o.method = "chc";
 *   zs_walk_create(scene, &o, &w, &err);
 *   for (int32_t f = 0; f < zs_walk_frames(w); f++) {
 *     zs_walk_frame fr;
 *     zs_walk_next(w, &fr, &err);       // fr.modelled_ms, fr.queries, ...
 *   }
 *   zs_walk_destroy(w);
 *
 * The methods (docs/CULLING.md): none vfc vfc-box hsw chc chc-prob ideal
 * auto chcpp chcpp-nobatch chcpp-nodefer chcpp-nomulti chcpp-prob nohc
 * ideal-box.  Every exact method draws, each frame, exactly the image of
 * drawing everything; the modelled times come from the device's clock
 * (zscan/clock.h: set it on zs_walk_device before the first frame). */
#ifndef ZSCAN_WALK_H
#define ZSCAN_WALK_H

#include <stdint.h>

#include "zscan/zscan.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct zs_walk zs_walk;

typedef struct zs_walk_opts {
  const char *method;   /* NULL: "none" */
  int width, height;    /* 0: the scene's size, else 1024 x 768 */
  int step;             /* path frames from one walk frame to the next; 0: 1 */
} zs_walk_opts;

/* One frame of the walk, as a row of `zscan walk --csv`. */
typedef struct zs_walk_frame {
  int32_t frame;          /* the frame of the scene's path */
  double modelled_ms;     /* the device clock's frame time */
  double stall_ms;        /* of it, the CPU waiting for query latency */
  uint64_t queries, queries_hidden;
  uint64_t objects_drawn, faces_drawn;
  uint64_t nodes_visited;
} zs_walk_frame;

/* A walk of scene (which it moves: objects that move in the scene file
 * move frame by frame; the scene must outlive the walk) with a method.
 * Builds the loose octree of zscan walk's defaults. */
zs_status zs_walk_create(zs_scene *scene, const zs_walk_opts *opts, zs_walk **out,
                         zs_error *err);
void zs_walk_destroy(zs_walk *w);

/* The walk's frames: the path's frames over step, or 1 without a path. */
int32_t zs_walk_frames(const zs_walk *w);

/* Renders the next frame (id shading, zbuffer mode) with the method and
 * reports it; the first call renders frame 0. */
zs_status zs_walk_next(zs_walk *w, zs_walk_frame *out, zs_error *err);

/* The walk's device: its id buffer holds the last frame, its clock the
 * constants the frames are charged with. */
zs_device *zs_walk_device(zs_walk *w);

#ifdef __cplusplus
}
#endif

#endif
