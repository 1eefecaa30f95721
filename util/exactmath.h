/* zscan — the one trigonometry, exponential and logarithm of the code base.
 *
 * glibc, musl and macOS round sin, cos, tan, exp and log differently, so a
 * camera or a cost that used them could change its bytes with the C
 * library.  These are built from + - * / and floor, frexp and ldexp only
 * (all exact in IEEE arithmetic, and compiled with -ffp-contract=off), so
 * every value that reaches an output is the same on every machine.  They
 * are accurate to a few ulp; what they promise is sameness, not the last
 * bit of the true value. */
#ifndef ZS_EXACTMATH_H
#define ZS_EXACTMATH_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The greatest common divisor of |a| and |b| (0 when both are 0): the
 * exact fractions of the teaching trace. */
static inline int64_t zs_gcd64(int64_t a, int64_t b) {
  if (a < 0) a = -a;
  if (b < 0) b = -b;
  while (b) {
    const int64_t t = a % b;
    a = b;
    b = t;
  }
  return a;
}

/* e with v = m 2^e, |m| in [0.5, 1), as frexp gives it: read off the
 * bits of a normal v (every one a set-up meets), frexp's for the rest. */
static inline int zs_binary_exponent(double v) {
  uint64_t bits;
  memcpy(&bits, &v, sizeof bits);
  const int biased = (int)((bits >> 52) & 0x7FF);
  if (biased != 0 && biased != 0x7FF) return biased - 1022;
  int e;
  frexp(v, &e);
  return e;
}

/* 2^e, exactly: made from its bits where it is normal, by ldexp beyond. */
static inline double zs_pow2(int e) {
  if (e < -1022 || e > 1023) return ldexp(1.0, e);
  const uint64_t bits = (uint64_t)(e + 1023) << 52;
  double v;
  memcpy(&v, &bits, sizeof v);
  return v;
}

/* sin and cos of an angle in turns (1 turn = 360 degrees).  Exact at
 * multiples of a quarter turn (no -0.0); within 2 ulp elsewhere. */
void zs_sincos_turns(double turns, double *s, double *c);

/* The same for an angle in degrees. */
void zs_sincos_deg(double deg, double *s, double *c);

/* tan of an angle in degrees (an odd multiple of 90 gives +-inf). */
double zs_tan_deg(double deg);

/* atan x in degrees (-90 .. 90).  Within a few ulp. */
double zs_atan_deg(double x);

/* e^x: +0 below about -745, +inf above about 709.8, NaN for NaN.
 * Within 2 ulp. */
double zs_exp(double x);

/* The natural logarithm: -inf at 0, NaN below 0, +inf at +inf.  Within
 * 2 ulp. */
double zs_log(double x);

/* log10 and 10^x, from zs_log and zs_exp. */
double zs_log10(double x);
double zs_exp10(double x);

#ifdef __cplusplus
}
#endif

#endif
