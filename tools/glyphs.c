/* The 3x5 label font (tools/glyphs.h). */
#include "tools/glyphs.h"

#include <string.h>

typedef struct glyph {
  char c;
  const char *rows; /* 5 rows of 3 cells, '1' painted */
} glyph;

static const glyph font[] = {
    {'0', "111101101101111"}, {'1', "010110010010111"}, {'2', "111001111100111"},
    {'3', "111001111001111"}, {'4', "101101111001001"}, {'5', "111100111001111"},
    {'6', "111100111101111"}, {'7', "111001001001001"}, {'8', "111101111101111"},
    {'9', "111101111001111"}, {'A', "010101111101101"}, {'D', "110101101101110"},
    {'E', "111100110100111"}, {'G', "111100101101111"}, {'H', "101101111101101"},
    {'I', "111010010010111"}, {'L', "100100100100111"}, {'N', "110101101101101"},
    {'O', "010101101101010"}, {'P', "110101110100100"}, {'R', "110101110101101"},
    {'S', "011100010001110"}, {'T', "111010010010010"}, {'W', "101101101111101"},
    {'X', "101101010101101"}, {'Z', "111001010100111"}, {'=', "000111000111000"},
    {'-', "000000111000000"},
};

static const char *rows_of(char c) {
  for (size_t i = 0; i < sizeof font / sizeof font[0]; i++)
    if (font[i].c == c) return font[i].rows;
  return NULL;
}

int zs_glyphs_draw(zs_image *im, int x, int y, int k, uint32_t rgb, const char *text) {
  for (; *text; text++, x += ZS_GLYPH_ADVANCE * k) {
    const char *rows = rows_of(*text);
    if (!rows) continue;
    for (int r = 0; r < ZS_GLYPH_H; r++)
      for (int c = 0; c < ZS_GLYPH_W; c++) {
        if (rows[r * ZS_GLYPH_W + c] != '1') continue;
        for (int py = y + r * k; py < y + (r + 1) * k; py++)
          for (int px = x + c * k; px < x + (c + 1) * k; px++)
            if (px >= 0 && py >= 0 && px < im->width && py < im->height)
              im->rgb[(size_t)py * (size_t)im->width + (size_t)px] = rgb;
      }
  }
  return x;
}
