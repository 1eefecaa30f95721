/* Textures (zscan.h): the texels copied and the mip chain built below
 * them in integers, so that every level is the same bytes everywhere. */
#include "util/texture.h"

#include <stdlib.h>
#include <string.h>

/* Level k + 1 from level k (src, w x h): each texel the rounded mean of
 * the 2 x 2 block above it.  When a side is odd (and more than 1), its
 * last row or column has no partner: it is folded into the block before
 * it, which then averages 2 x 3, 3 x 2 or 3 x 3 texels, so that every
 * texel of level k counts and none twice. */
static void halve(const uint8_t *src, int w, int h, uint8_t *dst, int dw, int dh) {
  for (int y = 0; y < dh; y++) {
    const int y0 = 2 * y, y1 = (y == dh - 1) ? h : y0 + 2; /* rows [y0, y1) */
    for (int x = 0; x < dw; x++) {
      const int x0 = 2 * x, x1 = (x == dw - 1) ? w : x0 + 2;
      for (int c = 0; c < 4; c++) {
        uint32_t sum = 0, n = 0;
        for (int yy = y0; yy < y1 && yy < h; yy++)
          for (int xx = x0; xx < x1 && xx < w; xx++, n++)
            sum += src[4 * ((size_t)yy * (size_t)w + (size_t)xx) + (size_t)c];
        dst[4 * ((size_t)y * (size_t)dw + (size_t)x) + (size_t)c] = (uint8_t)((sum + n / 2) / n);
      }
    }
  }
}

zs_status zs_texture_create(int width, int height, const uint8_t *rgba, zs_texture **out,
                            zs_error *err) {
  *out = NULL;
  if (width < 1 || height < 1 || width > ZS_MAX_TEXTURE_SIDE || height > ZS_MAX_TEXTURE_SIDE)
    return zs_error_set(err, ZS_ERR_LIMIT, "texture: %dx%d: each side must be 1 to %d", width,
                        height, ZS_MAX_TEXTURE_SIDE);
  if (!rgba) return zs_error_set(err, ZS_ERR_ARG, "texture: no texels");
  zs_texture *t = calloc(1, sizeof *t);
  if (!t) return zs_error_set(err, ZS_ERR_NOMEM, "texture: out of memory");
  size_t total = 0;
  int w = width, h = height, n = 0;
  for (;;) {
    t->level[n].width = w;
    t->level[n].height = h;
    total += 4 * (size_t)w * (size_t)h;
    n++;
    if (w == 1 && h == 1) break;
    w = w > 1 ? w / 2 : 1;
    h = h > 1 ? h / 2 : 1;
  }
  t->levels = n;
  t->texels = malloc(total);
  if (!t->texels) {
    free(t);
    return zs_error_set(err, ZS_ERR_NOMEM, "texture: out of memory");
  }
  uint8_t *p = t->texels;
  memcpy(p, rgba, 4 * (size_t)width * (size_t)height);
  t->opaque = 1;
  for (size_t i = 3; i < 4 * (size_t)width * (size_t)height; i += 4) t->opaque &= p[i] == 255;
  for (int k = 0; k < n; k++) {
    t->level[k].rgba = p;
    if (k + 1 < n)
      halve(p, t->level[k].width, t->level[k].height,
            p + 4 * (size_t)t->level[k].width * (size_t)t->level[k].height,
            t->level[k + 1].width, t->level[k + 1].height);
    p += 4 * (size_t)t->level[k].width * (size_t)t->level[k].height;
  }
  *out = t;
  return ZS_OK;
}

void zs_texture_destroy(zs_texture *t) {
  if (!t) return;
  free(t->texels);
  free(t);
}

int zs_texture_width(const zs_texture *t) { return t->level[0].width; }
int zs_texture_height(const zs_texture *t) { return t->level[0].height; }
int zs_texture_levels(const zs_texture *t) { return t->levels; }
int zs_texture_opaque(const zs_texture *t) { return t->opaque; }

const uint8_t *zs_texture_level(const zs_texture *t, int k, int *width, int *height) {
  if (k < 0 || k >= t->levels) return NULL;
  if (width) *width = t->level[k].width;
  if (height) *height = t->level[k].height;
  return t->level[k].rgba;
}

zs_material zs_material_default(void) {
  zs_material m;
  memset(&m, 0, sizeof m);
  m.base[0] = m.base[1] = m.base[2] = 0xB4;
  m.base[3] = 255;
  m.double_sided = 1;
  m.wrap_s = m.wrap_t = ZS_WRAP_REPEAT;
  m.filter = ZS_FILTER_DEFAULT;
  return m;
}

static const char *const filter_names[] = {"default", "nearest", "bilinear", "trilinear"};

const char *zs_filter_name(zs_filter f) {
  return (unsigned)f < sizeof filter_names / sizeof *filter_names ? filter_names[f] : "?";
}

int zs_filter_parse(const char *name) {
  for (int i = 0; i < (int)(sizeof filter_names / sizeof *filter_names); i++)
    if (name && strcmp(name, filter_names[i]) == 0) return i;
  return -1;
}
