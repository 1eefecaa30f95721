/* zscan lib — the sample positions of an anti-aliased frame, and the
 * projection that moves a pixel's centre onto one of them. */
#ifndef ZS_LIB_SAMPLES_H
#define ZS_LIB_SAMPLES_H

#include <stdint.h>

/* Whether n samples a pixel is a count zscan draws: 1, 2, 4, 8 or 16. */
int zs_samples_valid(int n);

/* The n standard positions (D3D's and Vulkan's standard sample locations,
 * which lie on the 1/16-pixel grid), x then y a sample, in 1/16 pixel
 * from the pixel's centre, y down the image; n valid. */
const int8_t *zs_sample_positions(int n);

/* proj moved so that, in a width x height window, the centre of every
 * pixel falls where sample (dx, dy) (1/16 pixel) of the original lies:
 * the clip-space translation by (-2 dx / 16 width, 2 dy / 16 height)
 * times w, applied to proj's rows. */
void zs_sample_projection(const double proj[16], int width, int height, int dx, int dy,
                          double out[16]);

#endif
