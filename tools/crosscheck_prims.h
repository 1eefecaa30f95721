/* zscan tools — zscan's lines and points against llvmpipe's, pixel by
 * pixel (`tests/test_mesa.c` bounds the shares, `zscan bench lines`
 * prints them for docs/RESULTS.md).
 *
 * The scene: nlines lines and npoints points scattered over a w x h window
 * by a seeded zs_rng, their ends anywhere within the pixels (not on the
 * 1/256 grid's centres), each at a depth of its own under an orthographic
 * camera that maps window pixels to world units, so that no two meet at
 * the same depth.  Both renderers draw their ids (id + 1) with a "less"
 * depth test: zscan with zs_device_draw_lines and _points, llvmpipe with
 * GL_LINES and GL_POINTS at the same width and size.  A pixel differs when
 * the ids differ; it is at an end when it lies within w / 2 + 1 pixels
 * (each axis) of an end of the line either side shows there, or of the
 * point (GL lets an implementation approximate its diamond-exit rule
 * there, and llvmpipe does); of the rest, it is rounding when the exact
 * line's edge passes within ZS_CROSSCHECK_EDGE of the pixel's centre, so
 * that which side it falls is decided by snapping, in float or double.
 * What is neither is a difference in the rule itself. */
#ifndef ZS_TOOLS_CROSSCHECK_PRIMS_H
#define ZS_TOOLS_CROSSCHECK_PRIMS_H

#include <stdint.h>

#include "zscan/error.h"
#include "zscan/zscan.h"

typedef struct zs_prim_check {
  uint64_t covered;   /* pixels zscan covers */
  uint64_t differ;    /* pixels whose ids differ */
  uint64_t at_ends;   /* of those, at a line's end or a point */
  uint64_t rounding;  /* of the rest, where a line's edge passes within
                       * ZS_CROSSCHECK_EDGE of the pixel's centre */
} zs_prim_check;

/* 1/64 pixel: four steps of the 1/256 grid both snap to, from positions
 * llvmpipe computes in float and zscan in double. */
#define ZS_CROSSCHECK_EDGE (1.0 / 64.0)

/* Draws nlines lines of width and npoints squares of size (seed, w x h)
 * both ways and compares them. */
zs_status zs_crosscheck_prims(int w, int h, uint64_t seed, int nlines, int npoints, double width,
                              double size, zs_prim_check *out, zs_error *err);

#endif
