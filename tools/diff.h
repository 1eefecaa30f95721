/* zscan tools — comparing two images: `zscan diff`.
 *
 *   zscan diff A.png B.png [-o diff.png] [--ids]
 *
 * prints to standard output
 *
 *   pixels_differing N of TOTAL
 *   max_channel_diff M
 *   faces_involved K: ID ID ...        (with --ids only)
 *
 * and exits 0 when the images are identical, 1 when they differ, 2 on an
 * error (one line "zscan diff: reason" on standard error).  Images of
 * different sizes are an error.
 *
 * M is the largest |a - b| over the R, G and B channels of all pixels.
 *
 * --ids reads the images as `--shade id` renderings, where a pixel is the
 * face id + 1 as a 24-bit number 0xRRGGBB and 0 is the background.  K is the
 * number of distinct values seen at the differing pixels, in either image;
 * they are listed in ascending order as face ids (value - 1), "background"
 * (value 0) first, at most 20 of them followed by "..." when there are
 * more.  With no differing pixel the line is "faces_involved 0:".
 *
 * -o writes a difference image (see zs_image_diff).
 */
#ifndef ZS_TOOLS_DIFF_H
#define ZS_TOOLS_DIFF_H

#include <stdint.h>

#include "raster/error.h"
#include "lib/image.h"

/* The `zscan diff` command: argv[0] is "diff".  Returns the exit status
 * (0 identical, 1 different, 2 error). */
int zs_cmd_diff(int argc, char **argv);

#endif
