/* zscan scene — textures from image files; see texture_file.h.
 *
 * Both libraries report a fatal error through a function that must not
 * return; ours copy the message and longjmp() back to the setjmp() of a
 * small helper whose only state lives behind a pointer, so no local
 * variable is read after a longjmp (as in lib/image.c).
 *
 * The texels are the file's values: no gamma, no colour profile.  PNG
 * goes through libpng's low-level reader, not its simplified png_image
 * API, because that one converts to sRGB whatever the file's gamma says
 * (and takes a 16-bit file without gAMA for linear light), which would
 * change the stored values.  JPEG uses libjpeg-turbo's accurate integer
 * IDCT, whose SIMD and C paths agree to the bit, and its default (fancy)
 * upsampling.  libjpeg recovers from damaged data with a warning and made
 * up pixels; every such warning is an error here.
 */
#include "scene/texture_file.h"

#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* jpeglib.h needs size_t and FILE declared first */
#include <jerror.h>
#include <jpeglib.h>

enum { REASON_MAX = 256 };

static zs_status size_error(zs_error *err, const char *name, unsigned long w, unsigned long h) {
  return zs_error_set(err, ZS_ERR_LIMIT, "%s: %lux%lu texture: each side must be 1 to %d", name,
                      w, h, ZS_MAX_TEXTURE_SIDE);
}

/* The texture from w x h decoded texels, the message naming the file. */
static zs_status make_texture(const char *name, int w, int h, const uint8_t *rgba,
                              zs_texture **out, zs_error *err) {
  zs_error e;
  zs_error_clear(&e);
  zs_status st = zs_texture_create(w, h, rgba, out, &e);
  if (st != ZS_OK) return zs_error_set(err, st, "%s: %s", name, e.msg);
  return ZS_OK;
}

/* ---- PNG ---- */

typedef struct png_job {
  png_structp png;
  png_infop info;
  const uint8_t *data;
  size_t len, pos;
  png_uint_32 width, height;
  uint8_t *rgba;
  png_bytep *rows;
  char reason[REASON_MAX];
} png_job;

static void on_png_error(png_structp png, png_const_charp msg) {
  png_job *j = png_get_error_ptr(png);
  snprintf(j->reason, sizeof j->reason, "%s", msg);
  png_longjmp(png, 1);
}

static void on_png_warning(png_structp png, png_const_charp msg) {
  (void)png; /* ancillary chunks libpng skips; the texels are intact */
  (void)msg;
}

static void png_read_mem(png_structp png, png_bytep dst, size_t n) {
  png_job *j = png_get_io_ptr(png);
  if (n > j->len - j->pos) png_error(png, "unexpected end of file");
  memcpy(dst, j->data + j->pos, n);
  j->pos += n;
}

/* Reads the header and asks for 8-bit RGBA rows, whatever the file holds
 * (the 16-bit values rounded to 8: 0x8080 -> 0x80). */
static int png_header(png_job *j) {
  if (setjmp(png_jmpbuf(j->png))) return 1;
  png_set_read_fn(j->png, j, png_read_mem);
  png_read_info(j->png, j->info);
  j->width = png_get_image_width(j->png, j->info);
  j->height = png_get_image_height(j->png, j->info);
  int color = png_get_color_type(j->png, j->info);
  int depth = png_get_bit_depth(j->png, j->info);
  int trns = png_get_valid(j->png, j->info, PNG_INFO_tRNS) != 0;
  if (color == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(j->png);
  if (color == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(j->png);
  if (trns) png_set_tRNS_to_alpha(j->png);
  if (depth == 16) png_set_scale_16(j->png);
  if (!(color & PNG_COLOR_MASK_COLOR)) png_set_gray_to_rgb(j->png);
  if (!(color & PNG_COLOR_MASK_ALPHA) && !trns)
    png_set_add_alpha(j->png, 0xFF, PNG_FILLER_AFTER);
  (void)png_set_interlace_handling(j->png);
  png_read_update_info(j->png, j->info);
  return 0;
}

static int png_pixels(png_job *j) {
  if (setjmp(png_jmpbuf(j->png))) return 1;
  png_read_image(j->png, j->rows);
  png_read_end(j->png, NULL); /* the chunks after the image, checked too */
  return 0;
}

static uint32_t be32(const uint8_t *p) {
  return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static zs_status png_decode(png_job *j, const char *name, zs_texture **out, zs_error *err) {
  /* The size from the header chunk, which comes first: libpng reads on
   * to the image data before it tells the size. */
  if (j->len >= 24 && memcmp(j->data + 12, "IHDR", 4) == 0) {
    const uint32_t w = be32(j->data + 16), h = be32(j->data + 20);
    if (w < 1 || h < 1 || w > ZS_MAX_TEXTURE_SIDE || h > ZS_MAX_TEXTURE_SIDE)
      return size_error(err, name, w, h);
  }
  j->png = png_create_read_struct(PNG_LIBPNG_VER_STRING, j, on_png_error, on_png_warning);
  if (j->png) j->info = png_create_info_struct(j->png);
  if (!j->info) return zs_error_set(err, ZS_ERR_NOMEM, "%s: cannot set up libpng", name);
  if (png_header(j))
    return zs_error_set(err, ZS_ERR_PARSE, "%s: corrupt PNG: %s", name, j->reason);
  if (j->width < 1 || j->height < 1 || j->width > ZS_MAX_TEXTURE_SIDE ||
      j->height > ZS_MAX_TEXTURE_SIDE)
    return size_error(err, name, j->width, j->height);
  if (png_get_channels(j->png, j->info) != 4 || png_get_bit_depth(j->png, j->info) != 8 ||
      png_get_rowbytes(j->png, j->info) != 4 * (size_t)j->width)
    return zs_error_set(err, ZS_ERR_UNSUPPORTED, "%s: cannot convert this PNG to 8-bit RGBA",
                        name);
  j->rgba = malloc(4 * (size_t)j->width * j->height);
  j->rows = malloc(sizeof *j->rows * j->height);
  if (!j->rgba || !j->rows) return zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", name);
  for (png_uint_32 y = 0; y < j->height; y++) j->rows[y] = j->rgba + 4 * (size_t)j->width * y;
  if (png_pixels(j))
    return zs_error_set(err, ZS_ERR_PARSE, "%s: corrupt PNG: %s", name, j->reason);
  return make_texture(name, (int)j->width, (int)j->height, j->rgba, out, err);
}

static zs_status load_png(const uint8_t *data, size_t len, const char *name, zs_texture **out,
                          zs_error *err) {
  png_job j;
  memset(&j, 0, sizeof j);
  j.data = data;
  j.len = len;
  zs_status st = png_decode(&j, name, out, err);
  if (j.png) png_destroy_read_struct(&j.png, j.info ? &j.info : NULL, NULL);
  free(j.rows);
  free(j.rgba);
  return st;
}

/* ---- JPEG ---- */

typedef struct jpeg_job {
  struct jpeg_decompress_struct d; /* first: d.err leads back to the job */
  struct jpeg_error_mgr mgr;
  jmp_buf jump;
  int created;
  const uint8_t *data;
  size_t len;
  uint8_t *rgba;
  char reason[JMSG_LENGTH_MAX];
} jpeg_job;

static void on_jpeg_error(j_common_ptr c) {
  jpeg_job *j = (jpeg_job *)(void *)c; /* d is the job's first member */
  c->err->format_message(c, j->reason);
  longjmp(j->jump, 1);
}

/* Level -1 is a warning: damaged data that libjpeg would paper over, or
 * a file cut short (it would fill the rest with grey).  Only the
 * warnings about markers that change no texel are let pass. */
static void on_jpeg_message(j_common_ptr c, int level) {
  if (level >= 0) return; /* trace output */
  int code = c->err->msg_code;
  if (code == JWRN_JFIF_MAJOR || code == JWRN_ADOBE_XFORM) return;
  on_jpeg_error(c);
}

static void on_jpeg_output(j_common_ptr c) { (void)c; /* the library never prints */ }

static int jpeg_header(jpeg_job *j) {
  if (setjmp(j->jump)) return 1;
  jpeg_create_decompress(&j->d);
  j->created = 1;
  jpeg_mem_src(&j->d, j->data, (unsigned long)j->len);
  (void)jpeg_read_header(&j->d, TRUE);
  return 0;
}

static int jpeg_pixels(jpeg_job *j) {
  if (setjmp(j->jump)) return 1;
  j->d.out_color_space = JCS_EXT_RGBA;
  j->d.dct_method = JDCT_ISLOW;
  (void)jpeg_start_decompress(&j->d);
  if (j->d.output_components != 4 || j->d.output_width != j->d.image_width ||
      j->d.output_height != j->d.image_height)
    ERREXIT(&j->d, JERR_CONVERSION_NOTIMPL);
  while (j->d.output_scanline < j->d.output_height) {
    JSAMPROW row = j->rgba + 4 * (size_t)j->d.output_width * j->d.output_scanline;
    (void)jpeg_read_scanlines(&j->d, &row, 1);
  }
  (void)jpeg_finish_decompress(&j->d); /* reads on to the end marker */
  return 0;
}

static zs_status jpeg_decode(jpeg_job *j, const char *name, zs_texture **out, zs_error *err) {
  j->d.err = jpeg_std_error(&j->mgr);
  j->mgr.error_exit = on_jpeg_error;
  j->mgr.emit_message = on_jpeg_message;
  j->mgr.output_message = on_jpeg_output;
  if (jpeg_header(j))
    return zs_error_set(err, ZS_ERR_PARSE, "%s: corrupt JPEG: %s", name, j->reason);
  const JDIMENSION w = j->d.image_width, h = j->d.image_height;
  if (w < 1 || h < 1 || w > ZS_MAX_TEXTURE_SIDE || h > ZS_MAX_TEXTURE_SIDE)
    return size_error(err, name, w, h);
  if (j->d.jpeg_color_space == JCS_CMYK || j->d.jpeg_color_space == JCS_YCCK)
    return zs_error_set(err, ZS_ERR_UNSUPPORTED,
                        "%s: CMYK JPEG: not supported (only greyscale and colour)", name);
  j->rgba = malloc(4 * (size_t)w * h);
  if (!j->rgba) return zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", name);
  if (jpeg_pixels(j))
    return zs_error_set(err, ZS_ERR_PARSE, "%s: corrupt JPEG: %s", name, j->reason);
  return make_texture(name, (int)w, (int)h, j->rgba, out, err);
}

static zs_status load_jpeg(const uint8_t *data, size_t len, const char *name, zs_texture **out,
                           zs_error *err) {
  jpeg_job *j = calloc(1, sizeof *j); /* a jmp_buf and the decoder: not for the stack */
  if (!j) return zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", name);
  j->data = data;
  j->len = len;
  zs_status st = jpeg_decode(j, name, out, err);
  if (j->created) jpeg_destroy_decompress(&j->d);
  free(j->rgba);
  free(j);
  return st;
}

/* ---- By signature ---- */

static const uint8_t png_sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
static const uint8_t jpeg_sig[3] = {0xFF, 0xD8, 0xFF};

/* 1 for PNG, 2 for JPEG, 0 for neither, from the first n bytes. */
static int sniff(const uint8_t *p, size_t n) {
  if (n >= sizeof png_sig && memcmp(p, png_sig, sizeof png_sig) == 0) return 1;
  if (n >= sizeof jpeg_sig && memcmp(p, jpeg_sig, sizeof jpeg_sig) == 0) return 2;
  return 0;
}

zs_status zs_texture_decode(const void *data, size_t len, const char *name, zs_texture **out,
                            zs_error *err) {
  *out = NULL;
  switch (data ? sniff(data, len) : 0) {
  case 1: return load_png(data, len, name, out, err);
  case 2: return load_jpeg(data, len, name, out, err);
  default: return zs_error_set(err, ZS_ERR_PARSE, "%s: not a PNG or JPEG image", name);
  }
}

zs_status zs_texture_load(const char *path, zs_texture **out, zs_error *err) {
  *out = NULL;
  FILE *fp = fopen(path, "rb");
  if (!fp) return zs_error_set(err, ZS_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
  /* the signature first, so that a file of another kind is not read whole */
  size_t cap = 4096, len = 0;
  uint8_t *buf = malloc(cap);
  zs_status st = ZS_OK;
  if (!buf) st = zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", path);
  while (st == ZS_OK) {
    if (len == cap) {
      uint8_t *grown = cap <= SIZE_MAX / 2 ? realloc(buf, 2 * cap) : NULL;
      if (!grown) {
        st = zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", path);
        break;
      }
      buf = grown;
      cap *= 2;
    }
    size_t want = len < sizeof png_sig ? sizeof png_sig - len : cap - len;
    size_t got = fread(buf + len, 1, want, fp);
    len += got;
    if (got < want && ferror(fp)) {
      st = zs_error_set(err, ZS_ERR_IO, "%s: cannot read: %s", path, strerror(errno));
    } else if (len <= sizeof png_sig && (got < want || len == sizeof png_sig) &&
               !sniff(buf, len)) {
      st = zs_error_set(err, ZS_ERR_PARSE, "%s: not a PNG or JPEG image", path);
    } else if (got < want) {
      break; /* the end of the file */
    }
  }
  fclose(fp);
  if (st == ZS_OK) st = zs_texture_decode(buf, len, path, out, err);
  free(buf);
  return st;
}
