/* zscan util — sRGB to linear light and back, by table (srgb.c): no pow,
 * so the same bytes on every C library. */
#ifndef ZS_UTIL_SRGB_H
#define ZS_UTIL_SRGB_H

#include <stdint.h>

/* The linear value of each 8-bit sRGB code, in units of 1/65535: IEC
 * 61966-2-1's curve, round(65535 * decode(c / 255)), made once by the
 * formula and written out (srgb.c). */
extern const uint16_t zs_srgb_to_linear16[256];

/* The 8-bit sRGB code nearest to a linear value q (0 .. 65535): the code c
 * whose table value is nearest to q, the higher of two equally near. */
static inline uint8_t zs_linear16_to_srgb(uint32_t q) {
  int lo = 0, hi = 255; /* the answer lies in [lo, hi] */
  while (lo < hi) {
    const int mid = (lo + hi + 1) / 2;
    /* code mid or above when q reaches the midpoint between mid - 1 and mid */
    if (2 * q >= (uint32_t)zs_srgb_to_linear16[mid - 1] + zs_srgb_to_linear16[mid]) lo = mid;
    else hi = mid - 1;
  }
  return (uint8_t)lo;
}

#endif
