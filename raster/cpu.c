/* What the CPU offers (cpu.h), asked once per device at create: the
 * widest SIMD level it has up to a cap, and PREFETCHW. */
#include "raster/cpu.h"

#include "raster/raster.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <cpuid.h>
#endif

#ifdef ZS_HAVE_X86_PATHS
static int cpu_has_avx2(void) { return __builtin_cpu_supports("avx2") != 0; }

static int cpu_has_avx512(void) {
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
         __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
}
#endif

zs_simd zs_span_simd_level(zs_simd most) {
#ifdef ZS_HAVE_X86_PATHS
  if (most >= ZS_SIMD_AVX512 && cpu_has_avx512()) return ZS_SIMD_AVX512;
  if (most >= ZS_SIMD_AVX2 && cpu_has_avx2()) return ZS_SIMD_AVX2;
  if (most >= ZS_SIMD_SSE2) return ZS_SIMD_SSE2;
#endif
#ifdef ZS_HAVE_NEON_PATHS
  if (most != ZS_SIMD_SCALAR) return ZS_SIMD_NEON;
#endif
  (void)most;
  return ZS_SIMD_SCALAR;
}

const char *zs_simd_name(zs_simd level) {
  return level == ZS_SIMD_NEON     ? "neon"
         : level == ZS_SIMD_AVX512 ? "avx512"
         : level == ZS_SIMD_AVX2 ? "avx2"
         : level == ZS_SIMD_SSE2 ? "sse2"
                                 : "scalar";
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
int zs_cpu_has_prefetchw(void) {
  unsigned a, b, c, d;
  return __get_cpuid(0x80000001u, &a, &b, &c, &d) && (c & (1u << 8)) != 0;
}
#else
int zs_cpu_has_prefetchw(void) { return 0; }
#endif
