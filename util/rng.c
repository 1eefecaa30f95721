#include "util/rng.h"

#include <string.h>

static uint64_t splitmix64(uint64_t *x) {
  uint64_t z = (*x += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

void zs_rng_seed(zs_rng *rng, uint64_t seed) {
  for (int i = 0; i < 4; i++) rng->s[i] = splitmix64(&seed);
}

uint64_t zs_rng_next(zs_rng *rng) {
  uint64_t *s = rng->s;
  uint64_t result = rotl(s[1] * 5, 7) * 9;
  uint64_t t = s[1] << 17;
  s[2] ^= s[0];
  s[3] ^= s[1];
  s[1] ^= s[2];
  s[0] ^= s[3];
  s[2] ^= t;
  s[3] = rotl(s[3], 45);
  return result;
}

double zs_rng_uniform(zs_rng *rng) {
  return (double)(zs_rng_next(rng) >> 11) * (1.0 / 9007199254740992.0);
}

double zs_rng_range(zs_rng *rng, double lo, double hi) {
  return lo + (hi - lo) * zs_rng_uniform(rng);
}

uint64_t zs_rng_below(zs_rng *rng, uint64_t n) {
  /* Rejection sampling: draw until the value falls below the largest
   * multiple of n, so every residue is equally likely. */
  uint64_t limit = UINT64_MAX - UINT64_MAX % n;
  uint64_t x;
  do x = zs_rng_next(rng); while (x >= limit);
  return x % n;
}

void zs_rng_shuffle(zs_rng *rng, void *base, size_t n, size_t size) {
  unsigned char *p = base, tmp[64];
  for (size_t i = n; i > 1; i--) {
    size_t j = (size_t)zs_rng_below(rng, i);
    unsigned char *a = p + (i - 1) * size, *b = p + j * size;
    for (size_t k = 0; k < size; k += sizeof tmp) {
      size_t c = size - k < sizeof tmp ? size - k : sizeof tmp;
      memcpy(tmp, a + k, c);
      memcpy(a + k, b + k, c);
      memcpy(b + k, tmp, c);
    }
  }
}
