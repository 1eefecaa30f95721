/* zscan raster — the depth pyramid (hzb.c, raster.h "hzb.c"): built
 * from a depth buffer, boxes tested against it as conservatively as an
 * exact query.  Opaque; the device's commands (query.c) build and test it
 * and charge the clock. */
#ifndef ZS_RASTER_HZB_H
#define ZS_RASTER_HZB_H

#include <stddef.h>
#include <stdint.h>

typedef struct zs_hzb zs_hzb;

/* The camera and window a test sees its boxes through. */
typedef struct zs_hzb_view {
  double view[16], proj[16], mvp[16];
  double eye[3];
  int perspective;
  int width, height;
} zs_hzb_view;

zs_hzb *zs_hzb_create(void); /* NULL: out of memory */
void zs_hzb_destroy(zs_hzb *h);
/* The pyramid of depth (width x height); its texels in levels 1 and up
 * (*texels), 0 when out of memory. */
int zs_hzb_build(zs_hzb *h, const uint32_t *depth, int width, int height, int64_t *texels);
/* A clear: nothing built this frame. */
void zs_hzb_invalidate(zs_hzb *h);
int zs_hzb_built(const zs_hzb *h);
/* maybe_visible[i] of boxes [lo, hi][i] against the last pyramid built
 * of depth; the texels it read. */
uint64_t zs_hzb_test(const zs_hzb *h, const uint32_t *depth, const zs_hzb_view *v,
                     const double (*lo)[3], const double (*hi)[3], int n, uint8_t *maybe_visible);
size_t zs_hzb_bytes(const zs_hzb *h);
/* The levels built (0 before the first build), and level k >= 1's texels,
 * w x h of them, row by row (tests, the teaching trace). */
int zs_hzb_levels(const zs_hzb *h);
const uint32_t *zs_hzb_level(const zs_hzb *h, int k, int *w, int *h_out);

#endif
