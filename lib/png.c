/* zscan lib — PNG files, through libpng; see lib/image.h.
 *
 * libpng reports errors by calling an error function that must not
 * return; ours copies the message and longjmp()s back to the setjmp() of
 * the caller.  Every libpng call that may fail is made inside a small
 * helper of the form
 *
 *     if (setjmp(png_jmpbuf(png))) return 1;
 *     ... libpng calls ...
 *     return 0;
 *
 * whose only state lives behind pointers, so no local variable is ever
 * read after a longjmp (the C standard leaves such variables
 * indeterminate unless they are volatile).
 */
#include "lib/image.h"

#include "lib/outfile.h"

#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "raster/raster.h"

enum { REASON_MAX = 256 };

/* Packs width pixels 0xRRGGBB into bytes R, G, B. */
static void pack_rgb(const uint32_t *rgb, unsigned char *bytes, int width) {
  for (int x = 0; x < width; x++) {
    bytes[3 * x + 0] = (unsigned char)(rgb[x] >> 16);
    bytes[3 * x + 1] = (unsigned char)(rgb[x] >> 8);
    bytes[3 * x + 2] = (unsigned char)rgb[x];
  }
}

/* Unpacks width pixels of bytes R, G, B into 0xRRGGBB. */
static void unpack_rgb(const unsigned char *bytes, uint32_t *rgb, int width) {
  for (int x = 0; x < width; x++)
    rgb[x] = (uint32_t)bytes[3 * x] << 16 | (uint32_t)bytes[3 * x + 1] << 8 |
             (uint32_t)bytes[3 * x + 2];
}

/* ---- libpng callbacks ----
 * The error pointer of every png_struct is a char[REASON_MAX] that receives
 * the message.  Warnings are dropped: the library never prints. */

static void on_png_error(png_structp png, png_const_charp msg) {
  char *reason = png_get_error_ptr(png);
  snprintf(reason, REASON_MAX, "%s", msg);
  png_longjmp(png, 1);
}

static void on_png_warning(png_structp png, png_const_charp msg) {
  (void)png;
  (void)msg;
}

/* ---- Writing PNG, row by row ---- */

struct zs_png_stream {
  char *path;            /* the target, for messages */
  zs_out file;           /* where the bytes go (lib/outfile.h) */
  zs_out_set *set;       /* what the file is finished into; NULL: committed */
  png_structp png;       /* NULL after a failure */
  png_infop info;
  int width, height;
  int rows;              /* rows written so far */
  unsigned char *bytes;  /* one row as R, G, B bytes */
  zs_status failure;     /* ZS_OK, or the status of the first failure */
  char reason[REASON_MAX];
};

static void write_data(png_structp png, png_bytep data, size_t n) {
  zs_png_stream *s = png_get_io_ptr(png);
  if (fwrite(data, 1, n, s->file.fp) != n) {
    char msg[REASON_MAX];
    snprintf(msg, sizeof msg, "cannot write: %s", strerror(errno));
    png_error(png, msg);
  }
}

static void flush_data(png_structp png) {
  (void)png; /* the file is flushed when it is closed */
}

/* Records the failure, removes the temporary and releases libpng; the
 * stream stays allocated until zs_png_stream_close. */
static zs_status stream_fail(zs_png_stream *s, zs_status code, zs_error *err) {
  s->failure = code;
  zs_out_discard(&s->file);
  if (s->png) png_destroy_write_struct(&s->png, &s->info);
  return zs_error_set(err, code, "%s: %s", s->path, s->reason);
}

static int png_begin(zs_png_stream *s, int ids) {
  if (setjmp(png_jmpbuf(s->png))) return 1;
  png_set_write_fn(s->png, s, write_data, flush_data);
  png_set_IHDR(s->png, s->info, (png_uint_32)s->width,
               (png_uint_32)s->height, 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  if (ids) {
    png_text mark = {.compression = PNG_TEXT_COMPRESSION_NONE,
                     .key = (png_charp)ZS_PNG_SHADE_KEY,
                     .text = (png_charp)ZS_PNG_SHADE_IDS,
                     .text_length = sizeof ZS_PNG_SHADE_IDS - 1};
    png_set_text(s->png, s->info, &mark, 1);
  }
  png_set_compression_level(s->png, 6);
  png_set_filter(s->png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
  png_write_info(s->png, s->info);
  return 0;
}

static int png_put_row(zs_png_stream *s) {
  if (setjmp(png_jmpbuf(s->png))) return 1;
  png_write_row(s->png, s->bytes);
  return 0;
}

static int png_end(zs_png_stream *s) {
  if (setjmp(png_jmpbuf(s->png))) return 1;
  png_write_end(s->png, NULL);
  return 0;
}

static void stream_free(zs_png_stream *s) {
  zs_out_discard(&s->file);
  if (s->png) png_destroy_write_struct(&s->png, &s->info);
  free(s->bytes);
  free(s->path);
  free(s);
}

/* Opens the stream; ids = 1 marks the file as face ids (lib/image.h). */
static zs_status stream_open(zs_png_stream **out, const char *path, int width,
                             int height, int ids, zs_out_set *set, zs_error *err) {
  *out = NULL;
  if (!zs_image_size_ok(width, height))
    return zs_error_set(err, ZS_ERR_LIMIT,
                        "%s: image size %dx%d: each side must be 1 .. %d",
                        path, width, height, ZS_MAX_IMAGE_SIDE);
  zs_png_stream *s = calloc(1, sizeof *s);
  if (!s) return zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", path);
  s->width = width;
  s->height = height;
  s->set = set;
  s->path = strdup(path);
  s->bytes = malloc(3 * (size_t)width);
  if (!s->path || !s->bytes) {
    stream_free(s);
    return zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", path);
  }
  zs_status st = zs_out_open(&s->file, path, err);
  if (st != ZS_OK) {
    stream_free(s);
    return st;
  }
  s->png = png_create_write_struct(PNG_LIBPNG_VER_STRING, s->reason,
                                   on_png_error, on_png_warning);
  if (s->png) s->info = png_create_info_struct(s->png);
  if (!s->info) {
    stream_free(s);
    return zs_error_set(err, ZS_ERR_NOMEM, "%s: cannot set up libpng", path);
  }
  if (png_begin(s, ids)) {
    st = stream_fail(s, ZS_ERR_IO, err);
    stream_free(s);
    return st;
  }
  *out = s;
  return ZS_OK;
}

zs_status zs_png_stream_open(zs_png_stream **out, const char *path, int width,
                             int height, zs_error *err) {
  return stream_open(out, path, width, height, 0, NULL, err);
}

zs_status zs_png_stream_row(zs_png_stream *s, const uint32_t *rgb,
                            zs_error *err) {
  if (s->failure != ZS_OK)
    return zs_error_set(err, s->failure, "%s: %s", s->path, s->reason);
  if (s->rows >= s->height) {
    snprintf(s->reason, sizeof s->reason, "more than %d rows written",
             s->height);
    return stream_fail(s, ZS_ERR_ARG, err);
  }
  pack_rgb(rgb, s->bytes, s->width);
  if (png_put_row(s)) return stream_fail(s, ZS_ERR_IO, err);
  s->rows++;
  return ZS_OK;
}

zs_status zs_png_stream_close(zs_png_stream *s, int commit, zs_error *err) {
  if (!s) return ZS_OK;
  zs_status st = ZS_OK;
  if (!commit) {
    /* discarded: stream_free removes the temporary */
  } else if (s->failure != ZS_OK) {
    st = zs_error_set(err, s->failure, "%s: %s", s->path, s->reason);
  } else if (s->rows < s->height) {
    snprintf(s->reason, sizeof s->reason, "only %d of %d rows written",
             s->rows, s->height);
    st = stream_fail(s, ZS_ERR_ARG, err);
  } else if (png_end(s)) {
    st = stream_fail(s, ZS_ERR_IO, err);
  } else {
    st = zs_out_finish(&s->file, s->set, err);
  }
  stream_free(s);
  return st;
}

/* Writes im whole; ids = 1 marks it as face ids (lib/image.h). */
static zs_status png_write(const char *path, const zs_image *im, int ids, zs_out_set *set,
                           zs_error *err) {
  zs_png_stream *s;
  zs_status st = stream_open(&s, path, im->width, im->height, ids, set, err);
  if (st != ZS_OK) return st;
  for (int y = 0; y < im->height && st == ZS_OK; y++)
    st = zs_png_stream_row(s, im->rgb + (size_t)y * (size_t)im->width, err);
  zs_status closed = zs_png_stream_close(s, st == ZS_OK, err);
  return st != ZS_OK ? st : closed;
}

zs_status zs_png_write(const char *path, const zs_image *im, zs_error *err) {
  return png_write(path, im, 0, NULL, err);
}

zs_status zs_png_write_shaded(const char *path, const zs_image *im, zs_shade shade,
                              zs_error *err) {
  return png_write(path, im, shade == ZS_SHADE_ID, NULL, err);
}

zs_status zs_png_write_in(zs_out_set *set, const char *path, const zs_image *im, zs_shade shade,
                          zs_error *err) {
  return png_write(path, im, shade == ZS_SHADE_ID, set, err);
}

/* ---- Reading PNG ---- */

typedef struct png_reader {
  FILE *fp;
  png_structp png;
  png_infop info;
  int passes;        /* 1, or 7 for an interlaced image */
  int ids;           /* the file carries the face-id mark */
  zs_status failure; /* ZS_ERR_IO for a read error, else ZS_ERR_PARSE */
  char reason[REASON_MAX];
} png_reader;

static void read_data(png_structp png, png_bytep data, size_t n) {
  png_reader *r = png_get_io_ptr(png);
  if (fread(data, 1, n, r->fp) == n) return;
  if (ferror(r->fp)) {
    char msg[REASON_MAX];
    snprintf(msg, sizeof msg, "cannot read: %s", strerror(errno));
    r->failure = ZS_ERR_IO;
    png_error(png, msg);
  }
  png_error(png, "truncated PNG (unexpected end of file)");
}

/* Reads the header and asks libpng for 8-bit RGB rows, whatever the file
 * holds. */
static int png_read_header(png_reader *r) {
  if (setjmp(png_jmpbuf(r->png))) return 1;
  png_read_info(r->png, r->info);
  png_textp text;
  int ntext = 0;
  png_get_text(r->png, r->info, &text, &ntext);
  for (int i = 0; i < ntext; i++)
    if (strcmp(text[i].key, ZS_PNG_SHADE_KEY) == 0 && text[i].text &&
        strcmp(text[i].text, ZS_PNG_SHADE_IDS) == 0)
      r->ids = 1;
  int color = png_get_color_type(r->png, r->info);
  int depth = png_get_bit_depth(r->png, r->info);
  if (color == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(r->png);
  if (color == PNG_COLOR_TYPE_GRAY && depth < 8)
    png_set_expand_gray_1_2_4_to_8(r->png);
  if (depth == 16) png_set_scale_16(r->png);
  if ((color & PNG_COLOR_MASK_ALPHA) ||
      png_get_valid(r->png, r->info, PNG_INFO_tRNS))
    png_set_strip_alpha(r->png);
  if (!(color & PNG_COLOR_MASK_COLOR)) png_set_gray_to_rgb(r->png);
  r->passes = png_set_interlace_handling(r->png);
  png_read_update_info(r->png, r->info);
  return 0;
}

/* Reads every row into im.  An interlaced image is rebuilt over seven
 * passes in buf, which then holds all rows; otherwise buf is one row. */
static int png_read_pixels(png_reader *r, zs_image *im, unsigned char *buf) {
  if (setjmp(png_jmpbuf(r->png))) return 1;
  size_t stride = 3 * (size_t)im->width;
  for (int pass = 0; pass < r->passes; pass++) {
    for (int y = 0; y < im->height; y++) {
      unsigned char *row = r->passes > 1 ? buf + (size_t)y * stride : buf;
      png_read_row(r->png, row, NULL);
      if (pass == r->passes - 1)
        unpack_rgb(row, im->rgb + (size_t)y * (size_t)im->width, im->width);
    }
  }
  png_read_end(r->png, NULL);
  return 0;
}

/* Checks the signature, then decodes; r->fp is open, r->png not yet made. */
static zs_status png_decode(png_reader *r, const char *path, zs_image *out,
                            zs_error *err) {
  unsigned char sig[8];
  size_t got = fread(sig, 1, sizeof sig, r->fp);
  if (got != sizeof sig && ferror(r->fp))
    return zs_error_set(err, ZS_ERR_IO, "%s: cannot read: %s", path,
                        strerror(errno));
  if (got != sizeof sig || png_sig_cmp(sig, 0, sizeof sig) != 0)
    return zs_error_set(err, ZS_ERR_PARSE, "%s: not a PNG file", path);

  r->png = png_create_read_struct(PNG_LIBPNG_VER_STRING, r->reason,
                                  on_png_error, on_png_warning);
  if (r->png) r->info = png_create_info_struct(r->png);
  if (!r->info)
    return zs_error_set(err, ZS_ERR_NOMEM, "%s: cannot set up libpng", path);
  png_set_read_fn(r->png, r, read_data);
  png_set_sig_bytes(r->png, sizeof sig);

  if (png_read_header(r))
    return zs_error_set(err, r->failure, "%s: %s", path, r->reason);
  png_uint_32 width = png_get_image_width(r->png, r->info);
  png_uint_32 height = png_get_image_height(r->png, r->info);
  if (width > ZS_MAX_IMAGE_SIDE || height > ZS_MAX_IMAGE_SIDE)
    return zs_error_set(err, ZS_ERR_LIMIT,
                        "%s: image is %lux%lu, more than %d pixels a side",
                        path, (unsigned long)width, (unsigned long)height,
                        ZS_MAX_IMAGE_SIDE);
  if (png_get_channels(r->png, r->info) != 3 ||
      png_get_bit_depth(r->png, r->info) != 8 ||
      png_get_rowbytes(r->png, r->info) != 3 * (size_t)width)
    return zs_error_set(err, ZS_ERR_UNSUPPORTED,
                        "%s: cannot convert this PNG to 8-bit RGB", path);

  zs_status st = zs_image_alloc(out, (int)width, (int)height, err);
  if (st != ZS_OK) return st;
  size_t rows = r->passes > 1 ? height : 1;
  unsigned char *buf = malloc(rows * 3 * (size_t)width);
  if (!buf) {
    zs_image_free(out);
    return zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", path);
  }
  if (png_read_pixels(r, out, buf)) {
    zs_image_free(out);
    st = zs_error_set(err, r->failure, "%s: %s", path, r->reason);
  }
  free(buf);
  return st;
}

zs_status zs_png_read_marked(const char *path, zs_image *out, int *ids,
                             zs_error *err) {
  if (ids) *ids = 0;
  out->width = 0;
  out->height = 0;
  out->rgb = NULL;
  png_reader r = {.fp = NULL, .png = NULL, .info = NULL, .passes = 1,
                  .ids = 0, .failure = ZS_ERR_PARSE, .reason = ""};
  r.fp = fopen(path, "rb");
  if (!r.fp)
    return zs_error_set(err, ZS_ERR_IO, "%s: cannot open: %s", path,
                        strerror(errno));
  zs_status st = png_decode(&r, path, out, err);
  if (r.png) png_destroy_read_struct(&r.png, &r.info, NULL);
  fclose(r.fp);
  if (st == ZS_OK && ids) *ids = r.ids;
  return st;
}

zs_status zs_png_read(const char *path, zs_image *out, zs_error *err) {
  return zs_png_read_marked(path, out, NULL, err);
}
