/* zscan tools — a 3x5 pixel font for labels in pictures: digits, the
 * capitals A D E G H I L N O P R S T W X Z, '=', '-' and space (others
 * draw as space).  Each glyph is 3 columns by 5 rows of cells k x k
 * pixels, 4k apart. */
#ifndef ZS_TOOLS_GLYPHS_H
#define ZS_TOOLS_GLYPHS_H

#include <stdint.h>

#include "zscan/zscan.h"

enum { ZS_GLYPH_W = 3, ZS_GLYPH_H = 5, ZS_GLYPH_ADVANCE = 4 };

/* Draws text with its top left at (x, y), clipped to im; returns the x
 * after it. */
int zs_glyphs_draw(zs_image *im, int x, int y, int k, uint32_t rgb, const char *text);

#endif
