/* zscan raster — what the CPU offers, asked once: the SIMD paths built
 * for x86-64 (and NEON's on aarch64) and the cpuid questions a device's
 * choices rest on (cpu.c).
 * The SIMD level itself, zs_simd, is the device's (raster.h). */
#ifndef ZS_RASTER_CPU_H
#define ZS_RASTER_CPU_H

/* x86-64 under gcc or clang: the SIMD paths (SSE2, AVX2, AVX-512) are
 * built, each taken at run time where the CPU has it (span_simd.c,
 * zs_span_simd_level).  ZS_AVX512_TARGET: what the device's AVX-512
 * level asks of the CPU (F, VL, BW, DQ), for every AVX-512 path (the
 * span fill, the polygon-order traversal, the vertex stage, the flat levels). */
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define ZS_HAVE_X86_PATHS 1
#define ZS_AVX512_TARGET __attribute__((target("avx512f,avx512vl,avx512bw,avx512dq")))
#define ZS_AVX512_INLINE ZS_AVX512_TARGET __attribute__((always_inline)) static inline
#endif

/* aarch64 under gcc or clang: the NEON span fill (span_simd.c), which
 * every aarch64 CPU has (Advanced SIMD is part of the architecture). */
#if defined(__aarch64__) && (defined(__GNUC__) || defined(__clang__))
#define ZS_HAVE_NEON_PATHS 1
#endif

/* Whether the CPU has PREFETCHW (cpuid): set-up asks for the batch's lines
 * with it when the device has threads. */
int zs_cpu_has_prefetchw(void);

#endif
