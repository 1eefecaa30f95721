/* zscan lib — images in memory, their hash and comparison, and PFM
 * files; see lib/image.h (PNG files: lib/png.c). */
#include "lib/image.h"

#include "lib/outfile.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "raster/raster.h"

int zs_image_size_ok(int width, int height) {
  return width >= 1 && width <= ZS_MAX_IMAGE_SIDE && height >= 1 &&
         height <= ZS_MAX_IMAGE_SIDE;
}

/* ---- Images in memory ---- */

zs_status zs_image_alloc(zs_image *im, int width, int height, zs_error *err) {
  im->width = 0;
  im->height = 0;
  im->rgb = NULL;
  if (!zs_image_size_ok(width, height))
    return zs_error_set(err, ZS_ERR_LIMIT,
                        "image size %dx%d: each side must be 1 .. %d", width,
                        height, ZS_MAX_IMAGE_SIDE);
  im->rgb = calloc((size_t)width * (size_t)height, sizeof *im->rgb);
  if (!im->rgb)
    return zs_error_set(err, ZS_ERR_NOMEM, "image %dx%d: out of memory",
                        width, height);
  im->width = width;
  im->height = height;
  return ZS_OK;
}

void zs_image_free(zs_image *im) {
  if (!im) return;
  free(im->rgb);
  im->rgb = NULL;
  im->width = 0;
  im->height = 0;
}

uint64_t zs_image_hash(const zs_image *im) {
  uint64_t h = 0xcbf29ce484222325ull; /* FNV-1a 64 offset basis */
  /* the size first, as two 32-bit little-endian numbers: a 64x48 and a
   * 48x64 frame of one colour must not share a hash */
  const uint32_t size[2] = {(uint32_t)im->width, (uint32_t)im->height};
  for (int k = 0; k < 8; k++) {
    h ^= (unsigned char)(size[k / 4] >> (8 * (k % 4)));
    h *= 0x100000001b3ull; /* FNV-1a 64 prime */
  }
  size_t n = (size_t)im->width * (size_t)im->height;
  for (size_t i = 0; i < n; i++) {
    uint32_t p = im->rgb[i];
    unsigned char bytes[3] = {(unsigned char)(p >> 16), (unsigned char)(p >> 8),
                              (unsigned char)p};
    for (int k = 0; k < 3; k++) {
      h ^= bytes[k];
      h *= 0x100000001b3ull;
    }
  }
  return h;
}

/* ---- Writing PFM ---- */

_Static_assert(sizeof(float) == 4, "PFM needs 32-bit floats");

/* A PFM of channels (1: "Pf", 3: "PF") floats a pixel. */
zs_status zs_pfm_write_in(zs_out_set *set, const char *path, int width, int height,
                          int channels, const float *values, zs_error *err) {
  if (!zs_image_size_ok(width, height))
    return zs_error_set(err, ZS_ERR_LIMIT,
                        "%s: image size %dx%d: each side must be 1 .. %d",
                        path, width, height, ZS_MAX_IMAGE_SIDE);
  const size_t row_floats = (size_t)channels * (size_t)width, row_bytes = 4 * row_floats;
  unsigned char *bytes = malloc(row_bytes);
  if (!bytes) return zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", path);
  zs_out f;
  zs_status st = zs_out_open(&f, path, err);
  if (st != ZS_OK) {
    free(bytes);
    return st;
  }
  int ok = fprintf(f.fp, "%s\n%d %d\n-1.0\n", channels == 3 ? "PF" : "Pf", width, height) > 0;
  /* The format stores the bottom row first. */
  for (int y = height - 1; y >= 0 && ok; y--) {
    const float *src = values + (size_t)y * row_floats;
    for (size_t x = 0; x < row_floats; x++) {
      uint32_t bits;
      memcpy(&bits, &src[x], sizeof bits);
      for (int k = 0; k < 4; k++) /* little-endian, whatever the host */
        bytes[4 * x + k] = (unsigned char)(bits >> (8 * k));
    }
    ok = fwrite(bytes, 1, row_bytes, f.fp) == row_bytes;
  }
  free(bytes);
  if (!ok) {
    st = zs_error_set(err, ZS_ERR_IO, "%s: cannot write: %s", path,
                      strerror(errno));
    zs_out_discard(&f);
    return st;
  }
  return zs_out_finish(&f, set, err);
}

zs_status zs_pfm_write(const char *path, int width, int height, const float *values,
                       zs_error *err) {
  return zs_pfm_write_in(NULL, path, width, height, 1, values, err);
}

zs_status zs_pfm_write_rgb(const char *path, int width, int height, const float *xyz,
                           zs_error *err) {
  return zs_pfm_write_in(NULL, path, width, height, 3, xyz, err);
}

/* ---- Comparing two images ---- */

#define RGB_MASK 0xFFFFFFu
#define DIFF_RED 0xFF0000u

/* The largest difference between corresponding channels of p and q. */
static int channel_diff(uint32_t p, uint32_t q) {
  int max = 0;
  for (int shift = 0; shift <= 16; shift += 8) {
    int d = abs((int)((p >> shift) & 0xFF) - (int)((q >> shift) & 0xFF));
    if (d > max) max = d;
  }
  return max;
}

/* Rec. 601 luma of 0xRRGGBB, 0 .. 255. */
static uint32_t luma(uint32_t p) {
  uint32_t r = (p >> 16) & 0xFF, g = (p >> 8) & 0xFF, b = p & 0xFF;
  return (77 * r + 150 * g + 29 * b + 128) >> 8;
}

static uint32_t grey(uint32_t v) { return v << 16 | v << 8 | v; }

/* The grey of p darkened to a quarter: R = G = B = luma / 4. */
static uint32_t dark_grey(uint32_t p) { return grey(luma(p) / 4); }

/* The heat map's colour of a pixel that changed by d (1 .. 255) in its
 * largest channel: from yellow (a step of rounding) to red (everything). */
static uint32_t heat(int d) {
  uint32_t g = (uint32_t)(224 - (224 * (d - 1)) / 254); /* 224 .. 0 */
  return 0xFF0000u | g << 8;
}

/* The grey of p faded towards white (160 .. 255): the picture under the
 * heat map, so that any colour of the map stands out. */
static uint32_t faded_grey(uint32_t p) { return grey(160 + luma(p) * 95 / 255); }

/* One comparison for both pictures: tolerance, the channel difference a
 * pixel may have and still count as equal; heat chooses the picture. */
static zs_status compare(const zs_image *a, const zs_image *b, int tolerance, int use_heat,
                         zs_image *diff_out, zs_diff_result *res, zs_error *err) {
  res->differing = 0;
  res->total = 0;
  res->max_channel_diff = 0;
  if (diff_out) {
    diff_out->width = 0;
    diff_out->height = 0;
    diff_out->rgb = NULL;
  }
  if (a->width != b->width || a->height != b->height)
    return zs_error_set(err, ZS_ERR_ARG, "images differ in size: %dx%d and %dx%d",
                        a->width, a->height, b->width, b->height);
  if (diff_out) {
    zs_status st = zs_image_alloc(diff_out, a->width, a->height, err);
    if (st != ZS_OK) return st;
  }
  size_t n = (size_t)a->width * (size_t)a->height;
  for (size_t i = 0; i < n; i++) {
    uint32_t pa = a->rgb[i] & RGB_MASK, pb = b->rgb[i] & RGB_MASK;
    int d = pa == pb ? 0 : channel_diff(pa, pb);
    if (d > res->max_channel_diff) res->max_channel_diff = d;
    if (d > tolerance) res->differing++;
    if (diff_out)
      diff_out->rgb[i] = use_heat ? (d > tolerance ? heat(d) : faded_grey(pa))
                                  : (d > 0 ? DIFF_RED : dark_grey(pa));
  }
  res->total = n;
  return ZS_OK;
}

zs_status zs_image_diff(const zs_image *a, const zs_image *b, zs_image *diff_out,
                        zs_diff_result *res, zs_error *err) {
  return compare(a, b, 0, 0, diff_out, res, err);
}

zs_status zs_image_compare(const zs_image *a, const zs_image *b, int max_channel_diff,
                           zs_image *heat_out, zs_diff_result *res, zs_error *err) {
  if (max_channel_diff < 0 || max_channel_diff > 255)
    return zs_error_set(err, ZS_ERR_ARG, "max_channel_diff %d: expected 0 to 255",
                        max_channel_diff);
  return compare(a, b, max_channel_diff, 1, heat_out, res, err);
}
