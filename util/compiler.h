/* zscan util — what zscan asks of the compiler beyond C11, in one place:
 * gcc and clang spell it with attributes and builtins, and any other
 * compiler (MSVC) gets the plain C meaning.  The SIMD kernels' own
 * target attributes stand beside them (raster/cpu.h), compiled for gcc
 * and clang only. */
#ifndef ZS_UTIL_COMPILER_H
#define ZS_UTIL_COMPILER_H

#if defined(__GNUC__) || defined(__clang__)
/* A kernel's piece inlined into each caller, so that the caller's
 * constants fold its branches away. */
#define ZS_ALWAYS_INLINE __attribute__((always_inline)) static inline
/* A branch taken rarely (the painter's or an error's). */
#define ZS_UNLIKELY(x) __builtin_expect(!!(x), 0)
/* Memory read soon. */
#define ZS_PREFETCH(p) __builtin_prefetch(p)
/* A printf-like function: its arguments checked against the format. */
#define ZS_PRINTF_LIKE(f, a) __attribute__((format(printf, f, a)))
#elif defined(_MSC_VER)
#define ZS_ALWAYS_INLINE static __forceinline
#define ZS_UNLIKELY(x) (x)
#define ZS_PREFETCH(p) ((void)(p))
#define ZS_PRINTF_LIKE(f, a)
#else
#define ZS_ALWAYS_INLINE static inline
#define ZS_UNLIKELY(x) (x)
#define ZS_PREFETCH(p) ((void)(p))
#define ZS_PRINTF_LIKE(f, a)
#endif

#endif
