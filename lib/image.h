/* zscan lib — images in memory and image files (PNG, PFM).  The public
 * part (zs_image, hash, diff, PNG, PFM) is declared in zscan/zscan.h; here
 * is what it does in full, and the row-by-row PNG writer.
 *
 * PIXELS
 *   A zs_image holds width * height pixels, row 0 at the top, each a
 *   uint32_t 0xRRGGBB (the top byte is ignored when writing and zero when
 *   reading).
 *
 * WRITING FILES
 *   Every file goes through the output primitive (lib/outfile.h): a
 *   regular file is written under a temporary name and renamed over PATH
 *   only once complete, a symbolic link is followed, a device, FIFO or
 *   socket is written directly, and "-" is standard output.  On any error
 *   PATH is left as it was.
 *
 *   PNGs are written deterministically: 8-bit RGB, not interlaced, zlib
 *   level 6, the fixed row filter "Up", and only the IHDR, IDAT and IEND
 *   chunks (no time, no gamma), with one exception: a `--shade id`
 *   rendering also carries the text chunk "zscan shade" = "id", so that
 *   `zscan diff --ids` can refuse an ordinary picture, whose colours are
 *   not face ids.  With a given zlib, the same pixels give the same bytes.
 *
 * ERRORS
 *   Failures return a status and set err to "PATH: reason", e.g.
 *   "out/x.png: cannot create: No such file or directory".  libpng's errors
 *   are caught (setjmp/longjmp) and reported the same way; nothing here
 *   prints or exits.
 */
#ifndef ZS_LIB_IMAGE_H
#define ZS_LIB_IMAGE_H

#include <stdint.h>

#include "lib/outfile.h"
#include "zscan/error.h"
#include "zscan/zscan.h"

/* Whether width x height is a size an image may have: each side 1 ..
 * ZS_MAX_IMAGE_SIDE. */
int zs_image_size_ok(int width, int height);

/* The text chunk (keyword, text) that marks a PNG whose pixels are face
 * id + 1, background 0. */
#define ZS_PNG_SHADE_KEY "zscan shade"
#define ZS_PNG_SHADE_IDS "id"

/* zs_png_write, marking the file as face ids when shade is ZS_SHADE_ID. */
zs_status zs_png_write_shaded(const char *path, const zs_image *im, zs_shade shade,
                              zs_error *err);

/* zs_png_write_shaded and zs_pfm_write (channels 1) or zs_pfm_write_rgb
 * (3), each file finished into set (lib/outfile.h: replaced with the
 * set's others, or not at all); set NULL: committed at once. */
zs_status zs_png_write_in(zs_out_set *set, const char *path, const zs_image *im, zs_shade shade,
                          zs_error *err);
zs_status zs_pfm_write_in(zs_out_set *set, const char *path, int width, int height,
                          int channels, const float *values, zs_error *err);

/* zs_png_read, also telling (ids, may be NULL) whether the file carries
 * the face-id mark: 1 or 0. */
zs_status zs_png_read_marked(const char *path, zs_image *out, int *ids,
                             zs_error *err);

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

#endif
