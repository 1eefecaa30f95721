/* rgbα+z layers and their composite (zscan/layer.h). */
#include "zscan/layer.h"
#include "lib/layer_file.h"

#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/outfile.h"

enum { PIXEL_BYTES = 12 };

void zs_layer_free(zs_layer *l) {
  if (!l) return;
  free(l->rgb);
  free(l->alpha);
  free(l->depth);
  free(l->id);
  memset(l, 0, sizeof *l);
}

zs_status zs_layer_alloc(zs_layer *l, int width, int height, const double view[16],
                         const double proj[16], uint32_t background, zs_shade shade,
                         zs_error *err) {
  memset(l, 0, sizeof *l);
  if (width < 1 || height < 1 || width > ZS_MAX_IMAGE_SIDE || height > ZS_MAX_IMAGE_SIDE)
    return zs_error_set(err, ZS_ERR_LIMIT, "layer size %dx%d: each side must be 1 to %d", width,
                        height, ZS_MAX_IMAGE_SIDE);
  const size_t n = (size_t)width * (size_t)height;
  l->rgb = malloc(n * sizeof *l->rgb);
  l->alpha = malloc(n);
  l->depth = malloc(n * sizeof *l->depth);
  l->id = malloc(n * sizeof *l->id);
  if (!l->rgb || !l->alpha || !l->depth || !l->id) {
    zs_layer_free(l);
    return zs_error_set(err, ZS_ERR_NOMEM, "layer %dx%d: out of memory", width, height);
  }
  l->width = width;
  l->height = height;
  memcpy(l->view, view, sizeof l->view);
  memcpy(l->proj, proj, sizeof l->proj);
  l->background = background & 0xFFFFFFu;
  l->shade = shade;
  for (size_t i = 0; i < n; i++) {
    l->rgb[i] = l->background;
    l->alpha[i] = 0;
    l->depth[i] = ZS_DEPTH_FAR;
    l->id[i] = ZS_ID_NONE;
  }
  return ZS_OK;
}

void zs_layer_row_sink(void *user, const zs_row *row) {
  zs_layer *l = user;
  if (row->y < 0 || row->y >= l->height || row->width != l->width) return;
  const size_t off = (size_t)row->y * (size_t)l->width, w = (size_t)l->width;
  for (size_t x = 0; x < w; x++) {
    l->rgb[off + x] = row->rgb[x] & 0xFFFFFFu;
    l->depth[off + x] = row->depth[x];
    l->id[off + x] = row->id[x];
    l->alpha[off + x] = row->id[x] == ZS_ID_NONE ? 0 : 255;
  }
}

zs_status zs_layer_image(const zs_layer *l, zs_image *out, zs_error *err) {
  if (zs_image_alloc(out, l->width, l->height, err)) return err->code;
  memcpy(out->rgb, l->rgb, (size_t)l->width * (size_t)l->height * sizeof *out->rgb);
  return ZS_OK;
}

/* ---- the file ---- */

static void put32(unsigned char *p, uint32_t v) {
  for (int k = 0; k < 4; k++) p[k] = (unsigned char)(v >> (8 * k));
}

static uint32_t get32(const unsigned char *p) {
  return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static int put_matrix(FILE *f, const char *name, const double m[16]) {
  int ok = fputs(name, f) >= 0;
  for (int i = 0; i < 16 && ok; i++) {
    uint64_t bits;
    memcpy(&bits, &m[i], sizeof bits);
    ok = fprintf(f, " %016" PRIx64, bits) > 0;
  }
  return ok && fputc('\n', f) != EOF;
}

zs_status zs_layer_write(const char *path, const zs_layer *l, zs_error *err) {
  return zs_layer_write_in(NULL, path, l, err);
}

zs_status zs_layer_write_in(zs_out_set *set, const char *path, const zs_layer *l, zs_error *err) {
  const size_t w = (size_t)l->width;
  unsigned char *bytes = malloc(w * PIXEL_BYTES);
  if (!bytes) return zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", path);
  zs_out f;
  zs_status st = zs_out_open(&f, path, err);
  if (st) {
    free(bytes);
    return st;
  }
  int ok = fprintf(f.fp, "ZSLAYER 1\n%d %d\n", l->width, l->height) > 0 &&
           put_matrix(f.fp, "view", l->view) && put_matrix(f.fp, "proj", l->proj) &&
           fprintf(f.fp, "background %06" PRIX32 "\nshade %s\n", l->background & 0xFFFFFFu,
                   zs_shade_name(l->shade)) > 0;
  for (int y = 0; y < l->height && ok; y++) {
    const size_t off = (size_t)y * w;
    for (size_t x = 0; x < w; x++) {
      unsigned char *p = bytes + PIXEL_BYTES * x;
      const uint32_t c = l->rgb[off + x];
      p[0] = (unsigned char)(c >> 16), p[1] = (unsigned char)(c >> 8), p[2] = (unsigned char)c;
      p[3] = l->alpha[off + x];
      put32(p + 4, l->depth[off + x]);
      put32(p + 8, l->id[off + x]);
    }
    ok = fwrite(bytes, 1, w * PIXEL_BYTES, f.fp) == w * PIXEL_BYTES;
  }
  free(bytes);
  if (!ok) {
    st = zs_error_set(err, ZS_ERR_IO, "%s: cannot write: %s", path, strerror(errno));
    zs_out_discard(&f);
    return st;
  }
  return zs_out_finish(&f, set, err);
}

/* One header line into buf (without its newline); 0 at the end of the
 * file or a line longer than cap. */
static int header_line(FILE *f, char *buf, size_t cap) {
  size_t n = 0;
  for (int c; (c = fgetc(f)) != EOF;) {
    if (c == '\n') {
      buf[n] = '\0';
      return 1;
    }
    if (n + 1 >= cap) return 0;
    buf[n++] = (char)c;
  }
  return 0;
}

static int hex_digit(char c) {
  return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10
                                         : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                                                : -1;
}

/* "NAME h0 h1 ... h15", each 16 hexadecimal digits. */
static int parse_matrix(const char *line, const char *name, double m[16]) {
  const size_t len = strlen(name);
  if (strncmp(line, name, len) != 0) return 0;
  const char *p = line + len;
  for (int i = 0; i < 16; i++) {
    if (*p++ != ' ') return 0;
    uint64_t bits = 0;
    for (int k = 0; k < 16; k++, p++) {
      const int d = hex_digit(*p);
      if (d < 0) return 0;
      bits = bits << 4 | (uint64_t)d;
    }
    memcpy(&m[i], &bits, sizeof bits);
  }
  return *p == '\0';
}

/* A decimal number of 1 to 5 digits at *p, moved past it; -1 if none. */
static int decimal(const char **p) {
  int v = 0, n = 0;
  for (; **p >= '0' && **p <= '9' && n < 6; (*p)++, n++) v = v * 10 + (**p - '0');
  return n >= 1 && n <= 5 ? v : -1;
}

static zs_status read_header(FILE *f, const char *path, zs_layer *h, zs_error *err) {
  char line[512];
  int w = -1, hh = -1;
  uint32_t bg = 0;
  if (!header_line(f, line, sizeof line) || strcmp(line, "ZSLAYER 1") != 0)
    return zs_error_set(err, ZS_ERR_PARSE, "%s:1: not a zscan layer (ZSLAYER 1)", path);
  const char *p = line;
  if (header_line(f, line, sizeof line) && (w = decimal(&p)) >= 0 && *p == ' ' && (p++, 1))
    hh = decimal(&p);
  if (w < 0 || hh < 0 || *p != '\0')
    return zs_error_set(err, ZS_ERR_PARSE, "%s:2: expected WIDTH HEIGHT", path);
  if (w < 1 || hh < 1 || w > ZS_MAX_IMAGE_SIDE || hh > ZS_MAX_IMAGE_SIDE)
    return zs_error_set(err, ZS_ERR_LIMIT, "%s:2: size %dx%d: each side must be 1 to %d", path,
                        w, hh, ZS_MAX_IMAGE_SIDE);
  if (!header_line(f, line, sizeof line) || !parse_matrix(line, "view", h->view))
    return zs_error_set(err, ZS_ERR_PARSE, "%s:3: expected view and 16 doubles' bits in hex",
                        path);
  if (!header_line(f, line, sizeof line) || !parse_matrix(line, "proj", h->proj))
    return zs_error_set(err, ZS_ERR_PARSE, "%s:4: expected proj and 16 doubles' bits in hex",
                        path);
  int ok = header_line(f, line, sizeof line) && strncmp(line, "background ", 11) == 0 &&
           strlen(line) == 17;
  for (int k = 11; k < 17 && ok; k++) {
    const int d = hex_digit(line[k]);
    ok = d >= 0;
    bg = bg << 4 | (uint32_t)(d < 0 ? 0 : d);
  }
  if (!ok) return zs_error_set(err, ZS_ERR_PARSE, "%s:5: expected background RRGGBB", path);
  int shade = -1;
  if (header_line(f, line, sizeof line) && strncmp(line, "shade ", 6) == 0)
    shade = zs_shade_parse(line + 6);
  if (shade < 0)
    return zs_error_set(err, ZS_ERR_PARSE, "%s:6: expected shade and a shading's name", path);
  h->width = w;
  h->height = hh;
  h->background = bg;
  h->shade = (zs_shade)shade;
  return ZS_OK;
}

/* A pixel as a layer holds it: a face (alpha 255, its id) or the
 * background (alpha 0, ZS_ID_NONE, ZS_DEPTH_FAR); anything else was not
 * written by zscan, and would composite as neither. */
static zs_status check_pixel(const char *path, int x, int y, unsigned alpha, uint32_t depth,
                             uint32_t id, zs_error *err) {
  if (alpha != 0 && alpha != 255)
    return zs_error_set(err, ZS_ERR_PARSE,
                        "%s: pixel (%d, %d): alpha %u: expected 255 (a face) or 0 (the "
                        "background)",
                        path, x, y, alpha);
  if (alpha == 255 && id == ZS_ID_NONE)
    return zs_error_set(err, ZS_ERR_PARSE, "%s: pixel (%d, %d): alpha 255 (a face) without a "
                        "face id", path, x, y);
  if (alpha == 0 && id != ZS_ID_NONE)
    return zs_error_set(err, ZS_ERR_PARSE, "%s: pixel (%d, %d): alpha 0 (the background) with "
                        "face id %u", path, x, y, (unsigned)id);
  if (alpha == 0 && depth != ZS_DEPTH_FAR)
    return zs_error_set(err, ZS_ERR_PARSE, "%s: pixel (%d, %d): the background at depth %u, "
                        "not the far plane's %u", path, x, y, (unsigned)depth,
                        (unsigned)ZS_DEPTH_FAR);
  return ZS_OK;
}

zs_status zs_layer_read(const char *path, zs_layer *out, zs_error *err) {
  memset(out, 0, sizeof *out);
  FILE *f = fopen(path, "rb");
  if (!f) return zs_error_set(err, ZS_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
  zs_layer h = {0};
  zs_status st = read_header(f, path, &h, err);
  const size_t w = (size_t)h.width, row = w * PIXEL_BYTES;
  /* a file shorter than its header says is refused before the pixels are
   * allocated (where its length can be had) */
  const long at = st ? -1 : ftell(f);
  if (at >= 0 && fseek(f, 0, SEEK_END) == 0) {
    const long end = ftell(f);
    if (end >= at && (uint64_t)(end - at) < (uint64_t)row * (uint64_t)h.height)
      st = zs_error_set(err, ZS_ERR_PARSE, "%s: cut short: %d of %d rows of pixels", path,
                        (int)((uint64_t)(end - at) / row), h.height);
    if (fseek(f, at, SEEK_SET) != 0 && !st)
      st = zs_error_set(err, ZS_ERR_IO, "%s: cannot read: %s", path, strerror(errno));
  }
  if (!st)
    st = zs_layer_alloc(out, h.width, h.height, h.view, h.proj, h.background, h.shade, err);
  unsigned char *bytes = st ? NULL : malloc(row);
  if (!st && !bytes) st = zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", path);
  for (int y = 0; !st && y < h.height; y++) {
    if (fread(bytes, 1, row, f) != row) {
      st = zs_error_set(err, ZS_ERR_PARSE, "%s: cut short: %d of %d rows of pixels", path, y,
                        h.height);
      break;
    }
    const size_t off = (size_t)y * w;
    for (size_t x = 0; x < w && !st; x++) {
      const unsigned char *p = bytes + PIXEL_BYTES * x;
      out->rgb[off + x] = (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
      out->alpha[off + x] = p[3];
      out->depth[off + x] = get32(p + 4);
      out->id[off + x] = get32(p + 8);
      st = check_pixel(path, (int)x, y, p[3], out->depth[off + x], out->id[off + x], err);
    }
  }
  if (!st && fgetc(f) != EOF)
    st = zs_error_set(err, ZS_ERR_PARSE, "%s: bytes after the last pixel", path);
  free(bytes);
  fclose(f);
  if (st) zs_layer_free(out);
  return st;
}

/* ---- merging ---- */

zs_status zs_layer_composite(const zs_layer *const *in, int n, zs_layer *out, zs_error *err) {
  memset(out, 0, sizeof *out);
  if (n < 1) return zs_error_set(err, ZS_ERR_ARG, "composite: no layers");
  const zs_layer *a = in[0];
  for (int k = 1; k < n; k++) {
    const zs_layer *b = in[k];
    if (b->width != a->width || b->height != a->height)
      return zs_error_set(err, ZS_ERR_ARG, "layer %d: %dx%d, but layer 0 is %dx%d", k, b->width,
                          b->height, a->width, a->height);
    /* the same bits: one camera, not two close ones */
    if (memcmp(b->view, a->view, sizeof a->view) != 0 ||
        memcmp(b->proj, a->proj, sizeof a->proj) != 0)
      return zs_error_set(err, ZS_ERR_ARG, "layer %d: another camera than layer 0's", k);
    if (b->background != a->background)
      return zs_error_set(err, ZS_ERR_ARG, "layer %d: background %06X, but layer 0's is %06X", k,
                          (unsigned)b->background, (unsigned)a->background);
    if (b->shade != a->shade)
      return zs_error_set(err, ZS_ERR_ARG, "layer %d: shaded %s, but layer 0 %s", k,
                          zs_shade_name(b->shade), zs_shade_name(a->shade));
  }
  if (zs_layer_alloc(out, a->width, a->height, a->view, a->proj, a->background, a->shade, err))
    return err->code;
  const size_t px = (size_t)a->width * (size_t)a->height;
  for (size_t i = 0; i < px; i++) {
    const zs_layer *best = a;
    for (int k = 1; k < n; k++) {
      const zs_layer *b = in[k];
      /* the device's own test: nearer, or as near with a lower id */
      if (b->depth[i] < best->depth[i] || (b->depth[i] == best->depth[i] && b->id[i] < best->id[i]))
        best = b;
    }
    out->rgb[i] = best->rgb[i];
    out->alpha[i] = best->alpha[i];
    out->depth[i] = best->depth[i];
    out->id[i] = best->id[i];
  }
  return ZS_OK;
}
