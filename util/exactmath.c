/* Trigonometry, e^x and log x from + - * / (util/exactmath.h).
 *
 * Each function reduces its argument to a small interval exactly (or with
 * a two-part constant), then sums a truncated series by Horner's rule; the
 * first omitted term is below 2^-60 of the result. */
#include "util/exactmath.h"

#include <float.h>
#include <math.h> /* floor, frexp, ldexp: exact; the constants HUGE_VAL, NAN */

/* Every output is a function of correctly rounded double operations: a
 * target that keeps doubles in more precision (the x87's FLT_EVAL_METHOD
 * 2, or one that cannot say) would round them otherwise.  32-bit x86
 * builds with -msse2 -mfpmath=sse (CMakeLists.txt).  FLT_EVAL_METHOD 1
 * (s390x: floats evaluated as doubles) rounds every double as 0 does;
 * zscan computes in double and keeps floats as storage, a float quotient
 * assigned to a float before use (it then rounds once, as in float). */
#if !defined(FLT_EVAL_METHOD) || (FLT_EVAL_METHOD != 0 && FLT_EVAL_METHOD != 1)
#error "zscan needs FLT_EVAL_METHOD 0 or 1 (each double operation rounded to double): on 32-bit x86 build with -msse2 -mfpmath=sse"
#endif

#define PI 3.14159265358979323846
/* ln 2 in two parts: LN2_HI has its low 32 bits zero, so k * LN2_HI is
 * exact for |k| < 2^20. */
#define LN2_HI 6.93147180369123816490e-01
#define LN2_LO 1.90821492927058770002e-10
#define LN10 2.30258509299404568402

/* Taylor series of sin and cos on |x| <= pi/4, where the first omitted
 * terms (x^19/19!, x^18/18!) are below 2^-60. */
static double sin_poly(double x) {
  double x2 = x * x;
  double t = 1.0 / 355687428096000.0;                  /* 1/17! */
  t = 1.0 / 1307674368000.0 - x2 * t;                  /* 1/15! */
  t = 1.0 / 6227020800.0 - x2 * t;                     /* 1/13! */
  t = 1.0 / 39916800.0 - x2 * t;                       /* 1/11! */
  t = 1.0 / 362880.0 - x2 * t;                         /* 1/9!  */
  t = 1.0 / 5040.0 - x2 * t;                           /* 1/7!  */
  t = 1.0 / 120.0 - x2 * t;                            /* 1/5!  */
  t = 1.0 / 6.0 - x2 * t;                              /* 1/3!  */
  return x - x * x2 * t;
}

static double cos_poly(double x) {
  double x2 = x * x;
  double t = 1.0 / 6402373705728000.0;                 /* 1/18! */
  t = 1.0 / 20922789888000.0 - x2 * t;                 /* 1/16! */
  t = 1.0 / 87178291200.0 - x2 * t;                    /* 1/14! */
  t = 1.0 / 479001600.0 - x2 * t;                      /* 1/12! */
  t = 1.0 / 3628800.0 - x2 * t;                        /* 1/10! */
  t = 1.0 / 40320.0 - x2 * t;                          /* 1/8!  */
  t = 1.0 / 720.0 - x2 * t;                            /* 1/6!  */
  t = 1.0 / 24.0 - x2 * t;                             /* 1/4!  */
  t = 0.5 - x2 * t;                                    /* 1/2!  */
  return 1.0 - x2 * t;
}

void zs_sincos_turns(double turns, double *s, double *c) {
  /* Reduce to the nearest quarter turn q and a remainder r in
   * [-1/8, 1/8] turn; then sin(q/4 + r) by the quadrant's symmetry. */
  double t = turns - floor(turns);       /* [0, 1) */
  double q = floor(4.0 * t + 0.5);       /* 0 .. 4 */
  double r = (t - 0.25 * q) * (2.0 * PI);
  double sr = sin_poly(r), cr = cos_poly(r);
  switch ((int)q & 3) {
    case 0: *s = sr;  *c = cr;  break;
    case 1: *s = cr;  *c = -sr; break;
    case 2: *s = -sr; *c = -cr; break;
    default: *s = -cr; *c = sr; break;
  }
  /* -0.0 would make the bytes of a matrix depend on the path taken. */
  if (*s == 0.0) *s = 0.0;
  if (*c == 0.0) *c = 0.0;
}

void zs_sincos_deg(double deg, double *s, double *c) { zs_sincos_turns(deg / 360.0, s, c); }

double zs_tan_deg(double deg) {
  double s, c;
  zs_sincos_deg(deg, &s, &c);
  return c == 0.0 ? (s > 0 ? HUGE_VAL : -HUGE_VAL) : s / c;
}

double zs_atan_deg(double x) {
  if (x != x) return x;
  int neg = x < 0;
  if (neg) x = -x;
  int inverted = x > 1.0; /* atan x = pi/2 - atan(1/x) */
  if (inverted) x = 1.0 / x;
  /* twice atan x = 2 atan(x / (1 + sqrt(1 + x^2))): |x| <= tan(pi/16) < 0.2,
   * where the series to x^23/23 leaves below 2^-60 */
  for (int k = 0; k < 2; k++) x = x / (1.0 + sqrt(1.0 + x * x));
  double x2 = x * x, t = 1.0 / 23.0;
  for (int k = 21; k >= 1; k -= 2) t = 1.0 / k - x2 * t;
  double a = 4.0 * x * t; /* radians */
  if (inverted) a = 0.5 * PI - a;
  a *= 180.0 / PI;
  return neg ? -a : a;
}

double zs_exp(double x) {
  if (x != x) return x;
  if (x > 709.78) return HUGE_VAL;
  if (x < -745.2) return 0.0;
  /* x = k ln 2 + r, |r| <= ln2 / 2; e^x = 2^k e^r.  The series of e^r to
   * r^17/17! leaves below 2^-60 for |r| <= 0.35. */
  double k = floor(x * (1.0 / LN2_HI) + 0.5);
  double r = (x - k * LN2_HI) - k * LN2_LO;
  double t = 1.0 / 355687428096000.0;                  /* 1/17! */
  static const double inv_fact[17] = {
      1.0 / 20922789888000.0, 1.0 / 1307674368000.0, 1.0 / 87178291200.0,
      1.0 / 6227020800.0,     1.0 / 479001600.0,     1.0 / 39916800.0,
      1.0 / 3628800.0,        1.0 / 362880.0,        1.0 / 40320.0,
      1.0 / 5040.0,           1.0 / 720.0,           1.0 / 120.0,
      1.0 / 24.0,             1.0 / 6.0,             0.5,
      1.0,                    1.0}; /* 1/16! .. 1/0! */
  for (int i = 0; i < 17; i++) t = inv_fact[i] + r * t;
  return ldexp(t, (int)k);
}

double zs_log(double x) {
  if (x != x || x < 0.0) return NAN;
  if (x == 0.0) return -HUGE_VAL;
  if (x == HUGE_VAL) return x;
  /* x = m 2^e with m in [sqrt(1/2), sqrt(2)); log m = 2 atanh(u),
   * u = (m - 1) / (m + 1), |u| <= 0.1716: the series to u^23 / 23 leaves
   * below 2^-60. */
  int e;
  double m = frexp(x, &e); /* [0.5, 1) */
  if (m < 0.70710678118654752440) {
    m *= 2.0;
    e--;
  }
  double u = (m - 1.0) / (m + 1.0), u2 = u * u;
  double t = 1.0 / 23.0;
  for (int k = 21; k >= 1; k -= 2) t = 1.0 / k + u2 * t;
  double log_m = 2.0 * u * t;
  return (e * LN2_LO + log_m) + e * LN2_HI;
}

double zs_log10(double x) { return zs_log(x) * (1.0 / LN10); }

double zs_exp10(double x) { return zs_exp(x * LN10); }
