/* zscan cull — how ideal-box's set changes from frame to frame, and the
 * least that change costs a method that learns visibility from the last
 * frame.
 *
 * A method that does not know the answer carries its knowledge over from
 * the last frame.  An object that entered ideal-box's set, from behind
 * other objects, it must find with a query that comes back visible (or
 * draw on a guess); an object that left it, it must ask about before
 * drawing or draw for nothing.  Against the device's clock:
 *   query  >= per_call                     (its call, nothing else)
 *   draw_i >= per_call + per_polygon P_i + per_pixel T_i
 * (P_i the polygons object i sets up at this camera, T_i the pixels it
 * tests: both independent of the order of drawing; only its writes are
 * left out).  Two floors over ideal-box, per frame, for a method that
 * finds each change with a query (an object drawn on a guess that proves
 * wrong costs a draw, more than a query):
 *   known:  (entered + left, both inside the frustum) x query: it asks
 *           exactly where the set changed, and nowhere else;
 *   ranked: the methods' own way to guess where to ask (chc-prob,
 *           chcpp-prob and nohc keep the pixels an object wrote): the last
 *           frame's set still in the frustum ranked by the pixels each
 *           owned, fewest first; the first k asked about, the others drawn
 *           unasked, with the k of least cost in each frame (chosen
 *           knowing the answer); the entered as in known.
 * Objects that came from or went outside the frustum are left out: a
 * frustum test, not a query, deals with them. */
#ifndef ZS_CULL_CHURN_H
#define ZS_CULL_CHURN_H

#include <stdint.h>

#include "cull/cull.h"

typedef struct zs_churn {
  /* per instance, [0] this frame and [1] the last */
  uint8_t *visible[2], *inside[2];
  uint32_t *pixels[2];     /* pixels it owns of the full image */
  int64_t *draw_ps;        /* this frame: the floor of its draw, above */
  uint64_t *rank;          /* scratch: (pixels << 32) | instance */
  int32_t n, cap;
  int have_last;           /* [1] holds a frame of the same n instances */
} zs_churn;

/* Room for n instances in [0] and draw_ps (zeroed pixels); 0 when out of
 * memory.  A different n than the last frame's forgets the last frame. */
int cull_churn_begin(zs_churn *ch, int32_t n);

/* Compares this frame, filled in by the caller, with the last one into
 * st's set_* and churn_* fields (all 0 in the first frame), with query_ps
 * the floor of a query; this frame then becomes the last. */
void cull_churn_compare(zs_churn *ch, int64_t query_ps, zs_cull_stats *st);

void cull_churn_free(zs_churn *ch);

#endif
