/* zscan tools — zscan's unlit colours against llvmpipe's smooth shading
 * and texturing, pixel by pixel (the colour half of the cross-check with
 * Mesa: `tests/test_mesa.c` bounds the shares, `zscan bench colours`
 * prints them for docs/RESULTS.md).
 *
 * Each case renders one input both ways at the same size and camera:
 * zscan in zbuffer mode with ZS_SHADE_UNLIT, llvmpipe with zs_mesa_unlit
 * (vertex colours interpolated, GL_MODULATE textures over zscan's own mip
 * chain, the filter given).  Over the pixels zscan covers, the largest
 * difference of a channel is taken at each; the shares within the case's
 * bound and exact, and the largest, are the figures. */
#ifndef ZS_TOOLS_CROSSCHECK_COLOURS_H
#define ZS_TOOLS_CROSSCHECK_COLOURS_H

#include <stdint.h>

#include "zscan/error.h"
#include "zscan/zscan.h"

typedef struct zs_colour_case {
  const char *input;  /* builtin:, absolute, or relative to the source tree */
  int paint;          /* give every attribute vertex a colour of its own */
  zs_filter filter;
  double min_share;   /* of covered pixels within max_diff a channel */
  int max_diff;
} zs_colour_case;

/* The cases, from the bounds the issue of exact shading set: vertex
 * colours within 2 on 99.9 %; GL_NEAREST the same texel on 99.5 %;
 * bilinear and trilinear within 8 on 95 %. */
extern const zs_colour_case zs_colour_cases[];
extern const int zs_ncolour_cases;

typedef struct zs_colour_check {
  uint64_t covered; /* pixels zscan covers */
  uint64_t close;   /* of them, within the case's max_diff a channel */
  uint64_t exact;   /* of them, the same colour */
  int worst;        /* the largest difference of a channel */
} zs_colour_check;

/* Runs case c on input path (c->input resolved by the caller) at w x h.
 * ZS_ERR_UNSUPPORTED when zscan has no OSMesa or the input needs assimp. */
zs_status zs_crosscheck_colours(const zs_colour_case *c, const char *path, int w, int h,
                                zs_colour_check *out, zs_error *err);

#endif
