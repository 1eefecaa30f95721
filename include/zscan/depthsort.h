/* zscan — the depth-sort mode's frame coherence and its counters.  An
 * extra to zscan.h. */
#ifndef ZSCAN_DEPTHSORT_H
#define ZSCAN_DEPTHSORT_H

#include <stdint.h>

#include "zscan/zscan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- depthsort.c: the painter's algorithm with frame coherence ----
 *
 * In ZS_ALGO_DEPTHSORT the faces of a frame are ordered back to front by
 * the key: the eye-space distance along the view axis of the centroid of
 * the face's vertices (ties: the higher id first, so the lower id is
 * painted last and wins, as in the z-buffer).  They are then painted in
 * that order, without a depth test: the walk gives each polygon the
 * constant depth n - 1 - rank, and its "less" test then keeps the face
 * painted last.  The depth buffer therefore holds ranks in this mode.
 *
 * Frame coherence (the depth-sort paper): each face keeps its place from
 * the previous frame.  The camera's motion between frames is classified
 * from the two view matrices:
 *   static, translation in the view plane, translation along the view
 *     axis (a dolly), roll about the view axis: depths are unchanged or
 *     shift all by the same amount, so the old order is kept as it is;
 *     only new faces are sorted and merged in (a few among many gallop
 *     to their places: O(log gap) comparisons each);
 *   slow rotation (about an axis off the view axis, under 2 degrees): the
 *     old order is nearly right: re-sorted by insertion sort with a
 *     galloping search (O(log d) comparisons for a face d places out),
 *     then the new faces merged in;
 *   fast rotation, or more than half the faces new: a full sort.
 * A kept face whose depth did not change as the camera's motion says (an
 * object that moved) is taken out and sorted in as new. */
typedef enum zs_motion_class {
  ZS_MOTION_FIRST,        /* no previous frame */
  ZS_MOTION_STATIC,
  ZS_MOTION_TRANSLATE,    /* translation in the view plane */
  ZS_MOTION_ROLL,         /* roll about the view axis (and translation) */
  ZS_MOTION_SLOW_ROTATE,  /* slow pitch / yaw */
  ZS_MOTION_FAST,         /* anything else: a full sort */
  ZS_MOTION_DOLLY         /* translation with a part along the view axis */
} zs_motion_class;

typedef struct zs_depthsort_stats {
  zs_motion_class motion;
  uint64_t faces;         /* faces ordered this frame */
  uint64_t reused;        /* kept their place from the last frame */
  uint64_t inserted;      /* new (or moved) faces sorted in */
  uint64_t comparisons;   /* key comparisons of the sort */
  int full_sort;          /* whether the whole list was sorted */
} zs_depthsort_stats;

const zs_depthsort_stats *zs_device_depthsort_stats(const zs_device *dev);
/* Wall time of the last frame's ordering, in ms (a measurement). */
double zs_device_depthsort_ms(const zs_device *dev);
/* Forget the previous frame's order: the next frame sorts from scratch. */
void zs_device_depthsort_reset(zs_device *dev);
const char *zs_motion_class_name(zs_motion_class m);

#ifdef __cplusplus
}
#endif

#endif
