/* zscan lib — hidden lines as an SVG picture, for slides and print.
 *
 * The picture is the PNG's, as vectors: a rectangle of paper the size of
 * the image, then one path of the visible runs of the edges (raster.h,
 * zs_line_run), each "M x0 y0 L x1 y1" in pixels with three decimals, in
 * the order they were drawn.  One pixel of the PNG is one unit of the SVG
 * (width, height and viewBox), the stroke line_width units wide (the
 * edges' width in the PNG, as zs_gl_rounded_size gives it).  The same runs
 * give the same bytes; the file goes through the output primitive
 * (lib/outfile.h). */
#ifndef ZS_LIB_SVG_H
#define ZS_LIB_SVG_H

#include <stdint.h>

#include "lib/outfile.h"
#include "zscan/error.h"
#include "raster/raster.h"

/* The file finished into set (NULL: committed at once; lib/outfile.h). */
zs_status zs_svg_write_lines(zs_out_set *set, const char *path, int width, int height, const zs_line_run *runs,
                             int32_t n, int line_width, uint32_t paper, uint32_t ink,
                             zs_error *err);

#endif
