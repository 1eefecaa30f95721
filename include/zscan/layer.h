/* zscan — rgbα+z layers: a frame's colour, coverage, depth and face ids
 * kept losslessly, and layers merged by depth.  An extra to zscan.h.
 *
 * A z-buffer frame is a function of its fragments: each pixel shows the
 * fragment of least (depth, id), its colour a function of that face and
 * pixel.  So the frame of a scene drawn in parts, each part into a layer
 * with the same camera, is the per-pixel least (depth, id) of the layers:
 * zs_layer_composite gives, byte for byte, the frame of the whole scene
 * (the building block of sort-last parallel rendering,
 * docs/ARCHITECTURE.md).  A transparent surface is kept blended over its
 * layer's own opaque surface, so that holds where each transparent
 * surface is in the layer of everything behind it.
 *
 * The file, version 1: a text header of six lines,
 *
 *   ZSLAYER 1
 *   WIDTH HEIGHT
 *   view V0 V1 ... V15
 *   proj P0 P1 ... P15
 *   background RRGGBB
 *   shade NAME
 *
 * WIDTH and HEIGHT in decimal digits, RRGGBB six hexadecimal digits (the
 * device's background option, flat shading's: under other shadings the
 * background pixels may be other colours), NAME as zs_shade_name gives it;
 * the matrices' doubles (in the order zs_device_set_camera takes them)
 * as the 16 hexadecimal digits of their IEEE bits, so that
 * they read back exactly on every machine; then WIDTH * HEIGHT pixels of
 * 12 bytes, row 0 (the top) first, left to right: R, G, B, alpha (255
 * where a face is, 0 at the background), the depth (32 bits, little
 * endian, in 2^-32 of the window's depth range, ZS_DEPTH_FAR at the
 * background) and the face id (32 bits, little endian, ZS_ID_NONE at the
 * background). */
#ifndef ZSCAN_LAYER_H
#define ZSCAN_LAYER_H

#include <stdint.h>

#include "zscan/zscan.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct zs_layer {
  int width, height;
  double view[16], proj[16]; /* the camera the frame was drawn with */
  uint32_t background;       /* 0xRRGGBB: the device's background option */
  zs_shade shade;            /* the shading the colours were drawn with */
  uint32_t *rgb;             /* width * height 0xRRGGBB, row 0 at the top */
  uint8_t *alpha;            /* 255 where a face is, 0 at the background */
  uint32_t *depth;           /* as the device's depth buffer */
  uint32_t *id;              /* as the device's id buffer */
} zs_layer;

/* An empty layer of width x height (every pixel uncovered: the background
 * colour, ZS_DEPTH_FAR, ZS_ID_NONE) for the camera, background and
 * shading given.  On failure *l is left empty. */
zs_status zs_layer_alloc(zs_layer *l, int width, int height, const double view[16],
                         const double proj[16], uint32_t background, zs_shade shade,
                         zs_error *err);
/* Frees the pixels and empties *l (l may be NULL). */
void zs_layer_free(zs_layer *l);

/* A zs_row_sink that copies each row into the zs_layer user (of the
 * device's size): zs_device_finish(dev, zs_layer_row_sink, &layer, err). */
void zs_layer_row_sink(void *user, const zs_row *row);

/* The layer's colours as an image (allocated here). */
zs_status zs_layer_image(const zs_layer *l, zs_image *out, zs_error *err);

/* Writes l to path (replaced whole or not at all; "-" is standard
 * output). */
zs_status zs_layer_write(const char *path, const zs_layer *l, zs_error *err);
/* Reads a layer file; a file that is not one, is cut short, or holds a
 * pixel that is neither a face (alpha 255 and a face id) nor the
 * background (alpha 0, ZS_ID_NONE, ZS_DEPTH_FAR) is refused with its name
 * and what is wrong (ZS_ERR_PARSE, the pixel's x and y), a size out of
 * range with ZS_ERR_LIMIT. */
zs_status zs_layer_read(const char *path, zs_layer *out, zs_error *err);

/* The layers in[0 .. n) merged into out (allocated here): at each pixel
 * the one of least (depth, id), the first of equals.  They must have one
 * size, one camera, one background and one shading, else ZS_ERR_ARG naming
 * the first that differs from in[0] by its index.  (Lights and texture
 * filters are not recorded: layers drawn with others merge, but not into
 * any one frame.) */
zs_status zs_layer_composite(const zs_layer *const *in, int n, zs_layer *out, zs_error *err);

#ifdef __cplusplus
}
#endif

#endif
