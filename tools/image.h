/* zscan tools — images in memory and image files (PNG, PFM).
 *
 * PIXELS
 *   A zs_image holds width * height pixels, row 0 at the top, each a
 *   uint32_t 0xRRGGBB (the top byte is ignored when writing and zero when
 *   reading).
 *
 * WRITING FILES
 *   Every file goes through the output primitive (tools/outfile.h): a
 *   regular file is written under a temporary name and renamed over PATH
 *   only once complete, a symbolic link is followed, a device, FIFO or
 *   socket is written directly, and "-" is standard output.  On any error
 *   PATH is left as it was.
 *
 *   PNGs are written deterministically: 8-bit RGB, not interlaced, zlib
 *   level 6, the fixed row filter "Up", and only the IHDR, IDAT and IEND
 *   chunks (no time, no gamma, no text).  With a given zlib, the same pixels
 *   give the same bytes.
 *
 * ERRORS
 *   Failures return a status and set err to "PATH: reason", e.g.
 *   "out/x.png: cannot create: No such file or directory".  libpng's errors
 *   are caught (setjmp/longjmp) and reported the same way; nothing here
 *   prints or exits.
 */
#ifndef ZS_TOOLS_IMAGE_H
#define ZS_TOOLS_IMAGE_H

#include <stdint.h>

#include "raster/error.h"

typedef struct zs_image {
  int width, height;
  uint32_t *rgb; /* 0xRRGGBB per pixel, row 0 at the top */
} zs_image;

/* Allocates a width x height image, all pixels 0 (black).  Each side must
 * be 1 .. ZS_MAX_IMAGE_SIDE.  On failure *im is left empty (all zero), so
 * zs_image_free is always safe. */
zs_status zs_image_alloc(zs_image *im, int width, int height, zs_error *err);

/* Frees the pixels and empties *im (im may be NULL). */
void zs_image_free(zs_image *im);

/* The image hash that golden tests and `--stats` print (image_hash):
 * 64-bit FNV-1a (offset basis 0xcbf29ce484222325, prime 0x100000001b3)
 * over the bytes
 *   width, height     each as a 32-bit little-endian number (8 bytes),
 *   R, G, B           of every pixel, row 0 first, left to right.
 * So a 2x1 image 0x666F6F, 0x626172 hashes the 14 bytes
 * 02 00 00 00 01 00 00 00 'f' 'o' 'o' 'b' 'a' 'r': 0xb950327571a622ff. */
uint64_t zs_image_hash(const zs_image *im);

/* Writes im as an 8-bit RGB PNG (through a zs_png_stream). */
zs_status zs_png_write(const char *path, const zs_image *im, zs_error *err);

/* Reads a PNG of any colour type (grey, grey+alpha, RGB, RGBA, palette),
 * any bit depth (1, 2, 4, 8, 16), interlaced or not, into *out (allocated
 * here; free it with zs_image_free).  16-bit samples are scaled to 8 bits
 * with rounding, grey becomes R = G = B, alpha and tRNS transparency are
 * dropped (no compositing), gamma is not applied.  On failure *out is left
 * empty. */
zs_status zs_png_read(const char *path, zs_image *out, zs_error *err);

/* A PNG written row by row, so a renderer need not hold the whole frame:
 *   zs_png_stream *s;
 *   zs_png_stream_open(&s, path, w, h, err);
 *   for each row y = 0 .. h-1, top to bottom: zs_png_stream_row(s, rgb, err);
 *   zs_png_stream_close(s, 1, err);
 * The file appears under path only when close commits after all h rows.
 * After an error the temporary is already removed; the stream must still
 * be closed, which then only frees it. */
typedef struct zs_png_stream zs_png_stream;

zs_status zs_png_stream_open(zs_png_stream **out, const char *path, int width,
                             int height, zs_error *err);

/* Appends the next row: width pixels 0xRRGGBB. */
zs_status zs_png_stream_row(zs_png_stream *s, const uint32_t *rgb,
                            zs_error *err);

/* commit = 1: finishes the file and renames it over path (an error if
 * rows are missing or an earlier call failed); commit = 0: discards it.
 * Frees s in every case (s may be NULL). */
zs_status zs_png_stream_close(zs_png_stream *s, int commit, zs_error *err);

/* Writes a single-channel PFM: the header "Pf\n<width> <height>\n-1.0\n"
 * (negative scale: little-endian) followed by width * height 32-bit floats,
 * rows stored bottom to top as the format wants.  values is row-major with
 * row 0 at the top, like a zs_image. */
zs_status zs_pfm_write(const char *path, int width, int height,
                       const float *values, zs_error *err);

#endif
