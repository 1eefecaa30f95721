/* zscan util — sRGB to linear light and back, by table (srgb.c): no pow,
 * so the same bytes on every C library. */
#ifndef ZS_UTIL_SRGB_H
#define ZS_UTIL_SRGB_H

#include <stdint.h>

/* The linear value of each 8-bit sRGB code, in units of 1/65535: IEC
 * 61966-2-1's curve, round(65535 * decode(c / 255)), made once by the
 * formula and written out (srgb.c). */
extern const uint16_t zs_srgb_to_linear16[256];

/* zs_linear16_to_srgb's first guess for q >> 4 (srgb.c). */
extern const uint8_t zs_srgb_of_linear_bucket[4096];

/* The 8-bit sRGB code nearest to a linear value q (0 .. 65535): the code c
 * whose table value is nearest to q, the higher of two equally near: c is
 * the code from which q reaches the midpoint between c - 1 and c.  The
 * bucket's guess is that code or one below it. */
static inline uint8_t zs_linear16_to_srgb(uint32_t q) {
  uint32_t c = zs_srgb_of_linear_bucket[q >> 4];
  if (c < 255 && 2 * q >= (uint32_t)zs_srgb_to_linear16[c] + zs_srgb_to_linear16[c + 1]) c++;
  return (uint8_t)c;
}

#endif
