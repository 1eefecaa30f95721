/* zscan scene — textures from image files (texture_file.c): PNG through
 * libpng, JPEG through libjpeg-turbo (its accurate integer IDCT, so its
 * SIMD and plain paths give the same texels), told apart by their
 * signatures, not their names. */
#ifndef ZS_SCENE_TEXTURE_FILE_H
#define ZS_SCENE_TEXTURE_FILE_H

#include <stddef.h>

#include "zscan/zscan.h"

/* Decodes the image file at path into a new texture (RGBA, sRGB colour,
 * alpha from the file or opaque).  Errors name the file: "PATH: cannot
 * open: REASON", "PATH: not a PNG or JPEG image", "PATH: corrupt PNG:
 * ...", "PATH: WxH texture: each side must be 1 to 8192". */
zs_status zs_texture_load(const char *path, zs_texture **out, zs_error *err);

/* The same from len bytes in memory (an image embedded in a glTF or
 * GLB); name is what the messages call it. */
zs_status zs_texture_decode(const void *data, size_t len, const char *name, zs_texture **out,
                            zs_error *err);

#endif
