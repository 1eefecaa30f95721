/* zscan — the one seeded pseudo-random generator of the code base.
 *
 * xoshiro256** (Blackman and Vigna), seeded through splitmix64.  Everything
 * random in zscan (generated scenes, test scenes, random intervals of the
 * culling methods) draws from a zs_rng seeded explicitly, so the same seed
 * gives the same bytes on every run, build and machine.  No rand(), no time.
 */
#ifndef ZS_RNG_H
#define ZS_RNG_H

#include <stddef.h>
#include <stdint.h>

typedef struct zs_rng {
  uint64_t s[4];
} zs_rng;

void zs_rng_seed(zs_rng *rng, uint64_t seed);
uint64_t zs_rng_next(zs_rng *rng);
/* Uniform in [0, 1) with 53 random bits. */
double zs_rng_uniform(zs_rng *rng);
/* Uniform in [lo, hi). */
double zs_rng_range(zs_rng *rng, double lo, double hi);
/* Uniform integer in [0, n), n > 0, without modulo bias. */
uint64_t zs_rng_below(zs_rng *rng, uint64_t n);
/* Shuffles the n elements of size bytes at base (Fisher-Yates, drawing
 * from the last element down): every order equally likely. */
void zs_rng_shuffle(zs_rng *rng, void *base, size_t n, size_t size);

#endif
