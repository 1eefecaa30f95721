/* zscan tools — zscan's faces against another renderer's, pixel by pixel,
 * with coverage told apart from depth ties (the cross-check with Mesa's
 * llvmpipe in `tests/test_mesa.c` and `zscan bench raster --mesa`).
 *
 * The other renderer hands over, per pixel, the face it shows (face id + 1,
 * 0 for the background, as `--shade id` encodes it).  zscan renders the
 * same scene and camera with its own ids and depths.  A pixel whose face
 * differs is one of two things:
 *
 *   a depth tie: the other renderer's face covers the pixel under zscan's
 *     rule too, and zscan's depth for it there lies within
 *     ZS_CROSSCHECK_TIE_DEPTH of the depth of the face zscan shows.  Both
 *     faces are there; which is in front is decided below the other
 *     renderer's depth resolution (llvmpipe: a 24-bit buffer filled from
 *     float interpolation, one step = 256 units of 2^-32), as happens where
 *     objects touch or surfaces coincide;
 *   a coverage difference: everything else: one side shows the background,
 *     or the other renderer's face does not cover the pixel under zscan's
 *     rule, or lies behind zscan's by more than the tolerance (so zscan's
 *     face does not cover the pixel over there).
 *
 * To find the depth of the other renderer's face, each such face is drawn
 * alone into a second device (one clear and one draw per distinct face). */
#ifndef ZS_TOOLS_CROSSCHECK_H
#define ZS_TOOLS_CROSSCHECK_H

#include <stdint.h>
#include <stdio.h>

#include "zscan/error.h"
#include "scene/scene.h"

/* Four steps of a 24-bit depth buffer, in zscan's depth units (2^-32 of
 * the window depth range): the rounding of llvmpipe's float plane and its
 * 24-bit quantization, with room to spare. */
#define ZS_CROSSCHECK_TIE_DEPTH 1024u

typedef struct zs_crosscheck {
  uint64_t pixels;   /* width * height */
  uint64_t covered;  /* pixels zscan covers */
  uint64_t differ;   /* pixels whose face differs */
  uint64_t ties;     /* of those, depth ties; differ - ties differ in coverage */
} zs_crosscheck;

/* Renders s with view and proj at w x h in zbuffer mode on one thread and
 * compares its faces with other (w * h face ids + 1, row 0 at the top).
 * When list is not NULL, each differing pixel gets a line there:
 *   "  pixel X,Y: zscan face A, other face B, tie (depth +D)" or
 *   "  pixel X,Y: zscan face A, other face B, coverage"
 * (faces as ids, "none" for the background). */
zs_status zs_crosscheck_faces(const zs_scene *s, const double view[16], const double proj[16],
                              int w, int h, const uint32_t *other, FILE *list,
                              zs_crosscheck *out, zs_error *err);

#endif
