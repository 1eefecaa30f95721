/* Sample positions and the projection of a sample (lib/samples.h). */
#include "lib/samples.h"

#include <string.h>

/* D3D11's standard multisample patterns (Vulkan's standardSampleLocations
 * are the same), in 1/16 pixel from the centre, y down. */
static const int8_t one[] = {0, 0};
static const int8_t two[] = {4, 4, -4, -4};
static const int8_t four[] = {-2, -6, 6, -2, -6, 2, 2, 6};
static const int8_t eight[] = {1, -3, -1, 3, 5, 1, -3, -5, -5, 5, -7, -1, 3, 7, 7, -7};
static const int8_t sixteen[] = {1,  1,  -1, -3, -3, 2,  4,  -1, -5, -2, 2,  5,  5,  3,  3,  -5,
                                 -2, 6,  0,  -7, -4, -6, -6, 4,  -8, 0,  7,  -4, 6,  7,  -7, -8};

int zs_samples_valid(int n) { return n == 1 || n == 2 || n == 4 || n == 8 || n == 16; }

const int8_t *zs_sample_positions(int n) {
  return n == 2 ? two : n == 4 ? four : n == 8 ? eight : n == 16 ? sixteen : one;
}

void zs_sample_projection(const double proj[16], int width, int height, int dx, int dy,
                          double out[16]) {
  const double tx = -2.0 * dx / (16.0 * width), ty = 2.0 * dy / (16.0 * height);
  memcpy(out, proj, 16 * sizeof *out);
  for (int c = 0; c < 4; c++) {
    out[c] = proj[c] + tx * proj[12 + c];
    out[4 + c] = proj[4 + c] + ty * proj[12 + c];
  }
}
