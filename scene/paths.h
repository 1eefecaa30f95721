/* zscan scene — named camera paths: the four camera motions of the
 * frame-coherent depth-sort paper, and helpers for paths.
 *
 * A named path starts from a complete camera (eye, target, up; eye !=
 * target, up not along the view) and has one key per frame, so the camera
 * of frame f is key f exactly (zs_path_camera passes through its keys; up
 * is re-normalised).  With
 *   dist  = |target - eye|              the viewing distance,
 *   fwd   = (target - eye) / dist       the view direction,
 *   right = unit(fwd x up)              the image's right,
 *   u     = right x fwd                 the image's up (unit, orthogonal),
 * frame f (0 .. frames-1) of each path is:
 *
 *   "static"     eye and target of the base, up_f = u: no motion (the
 *                reference).
 *   "translate"  small horizontal translation along the view's x axis:
 *                eye_f = eye + s_f right, target_f = target + s_f right,
 *                s_f = 0.005 f dist (0.5 % of the viewing distance per
 *                frame), up_f = u.  The view direction never changes, so
 *                every eye-space depth stays the same (paper: 91.76 % of
 *                the faces keep their rank).
 *   "roll"       roll about the view axis: eye and target fixed,
 *                up_f = cos(a_f) u + sin(a_f) right, a_f = 2 f degrees
 *                (a right-handed turn about fwd): depths unchanged
 *                (paper: 100 % old faces).
 *   "yaw"        slow yaw: the eye fixed, the view direction turned about
 *                u by b_f = 0.5 f degrees, right-handed (to the left):
 *                target_f = eye + dist (cos(b_f) fwd - sin(b_f) right),
 *                up_f = u.  Depths change a little per frame (paper:
 *                81.83 % old).
 *   "fast"       fast horizontal translation: eye and target move together
 *                along right by 2.5 viewing distances every frame
 *                (ZS_PATH_FAST_STEP; over twice the width of the view at
 *                the target: a 45-degree lens at 4:3 sees 1.1 dist
 *                across), in a zigzag that keeps the eye within 5 dist of
 *                its start: s_f = 2.5 dist w(f) with w = 0, 1, 2, 1, 0,
 *                -1, -2, -1 repeating (period 8), up_f = u.  Most of the
 *                picture changes every frame (paper: 11.91 % old).
 * Angles go through zs_sincos_deg (util/exactmath.h): the same bytes
 * with every compiler and C library.
 */
#ifndef ZS_SCENE_PATHS_H
#define ZS_SCENE_PATHS_H

#include <stddef.h>
#include <stdint.h>

#include "zscan/error.h"
#include "scene/camera.h"
#include "scene/scene.h"

enum { ZS_PATH_MAX_FRAMES = 1000000 };

#define ZS_PATH_TRANSLATE_STEP 0.005 /* of the viewing distance, per frame */
#define ZS_PATH_ROLL_DEG 2.0         /* degrees per frame */
#define ZS_PATH_YAW_DEG 0.5          /* degrees per frame */
#define ZS_PATH_FAST_STEP 2.5         /* of the viewing distance, per frame */

/* The names zs_path_named knows, for messages: "static, translate, roll,
 * yaw, fast". */
extern const char zs_path_names[];

/* Makes the named path of frames frames (1 .. ZS_PATH_MAX_FRAMES) from the
 * complete camera base (see above) into *out (any previous content is not
 * freed).  Errors: an unknown name, frames out of range, a base camera
 * that is not complete ("eye and target are the same point", "up ...
 * parallel to the view direction"), out of memory. */
zs_status zs_path_named(const char *name, const zs_camera *base, int32_t frames, zs_path *out,
                        zs_error *err);

/* Frees the keys of a path and leaves it empty (no keys, 0 frames). */
void zs_path_free(zs_path *p);

/* The camera of the path at frame f, which may lie between whole frames
 * (the C1 curve of scene.h; held constant before the first key and after
 * the last).  p must have at least one key.  out->frame is floor(f). */
void zs_path_eval(const zs_path *p, double f, zs_keyframe *out);

/* Writes one line (with '\n') describing camera c at frame f:
 *   frame F eye X,Y,Z target X,Y,Z up X,Y,Z
 * each number with "%.6f" and -0.000000 written as 0.000000, so the text
 * depends only on the values.  Returns the length as snprintf does. */
int zs_path_format(char *buf, size_t cap, int32_t f, const zs_camera *c);

#endif
