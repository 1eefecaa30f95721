/* Tests of lib/image.c (PNG and PFM files, the image hash),
 * tools/cmd_diff.c (zs_image_diff and `zscan diff`) and tools/crosscheck.c
 * (face ids against another renderer's).  Every file is written
 * below the build directory, in test_image_out/. */
#include "tests/testutil.h"
#include "util/os.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/rng.h"
#include "tools/crosscheck.h"
#include "tools/commands.h"
#include "lib/frame.h"
#include "lib/frame_camera.h"
#include "lib/image.h"
#include "lib/input.h"

/* ---- Helpers ---- */

enum { PATH_MAX_LEN = 4096 };

/* The directory of this suite's files, created on first use. */
static const char *out_dir(void) {
  static char dir[PATH_MAX_LEN];
  if (!dir[0]) {
    snprintf(dir, sizeof dir, "%s", zs_test_bin("test_image_out"));
    int e = zs_os_mkdir(dir);
    if (e != 0 && e != EEXIST) ck_abort_msg("cannot create %s: %s", dir, strerror(e));
  }
  return dir;
}

/* buf = out_dir()/name; the file is removed so each test starts clean. */
static char *out_file(char *buf, const char *name) {
  int n = snprintf(buf, PATH_MAX_LEN, "%s/%s", out_dir(), name);
  ck_assert(n > 0 && n < PATH_MAX_LEN);
  remove(buf);
  return buf;
}

static int file_exists(const char *path) {
  struct stat st;
  return stat(path, &st) == 0;
}


static void spit(const char *path, const void *data, size_t size) {
  FILE *fp = fopen(path, "wb");
  ck_assert_ptr_nonnull(fp);
  ck_assert_uint_eq(fwrite(data, 1, size, fp), size);
  ck_assert_int_eq(fclose(fp), 0);
}

/* Files of out_dir() whose name holds ".tmp." — temporaries left behind. */
static int count_temporaries(void) {
  DIR *d = opendir(out_dir());
  ck_assert_ptr_nonnull(d);
  int n = 0;
  for (struct dirent *e; (e = readdir(d)) != NULL;)
    if (strstr(e->d_name, ".tmp.")) n++;
  closedir(d);
  return n;
}

/* A w x h image of random pixels. */
static zs_image random_image(int w, int h, uint64_t seed) {
  zs_image im;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_image_alloc(&im, w, h, &err), ZS_OK);
  zs_rng rng;
  zs_rng_seed(&rng, seed);
  for (int i = 0; i < w * h; i++) im.rgb[i] = (uint32_t)zs_rng_below(&rng, 1u << 24);
  return im;
}

static void assert_same_pixels(const zs_image *a, const zs_image *b) {
  ck_assert_int_eq(a->width, b->width);
  ck_assert_int_eq(a->height, b->height);
  for (int i = 0; i < a->width * a->height; i++)
    ck_assert_msg(a->rgb[i] == b->rgb[i], "pixel %d: %06x != %06x", i,
                  (unsigned)a->rgb[i], (unsigned)b->rgb[i]);
}

/* ---- PNG writing and reading ---- */

START_TEST(png_round_trip_is_exact) {
  char path[PATH_MAX_LEN];
  out_file(path, "round_trip.png");
  zs_image im = random_image(37, 23, 1), back;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_write(path, &im, &err), ZS_OK);
  ck_assert_int_eq(zs_png_read(path, &back, &err), ZS_OK);
  assert_same_pixels(&im, &back);
  ck_assert(zs_image_hash(&im) == zs_image_hash(&back));
  ck_assert_int_eq(count_temporaries(), 0);
  zs_image_free(&im);
  zs_image_free(&back);
}
END_TEST

START_TEST(png_top_byte_is_ignored) {
  char path[PATH_MAX_LEN];
  out_file(path, "top_byte.png");
  zs_image im = random_image(5, 4, 2), back;
  for (int i = 0; i < 20; i++) im.rgb[i] |= 0xAB000000u;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_write(path, &im, &err), ZS_OK);
  ck_assert_int_eq(zs_png_read(path, &back, &err), ZS_OK);
  for (int i = 0; i < 20; i++) ck_assert_uint_eq(back.rgb[i], im.rgb[i] & 0xFFFFFFu);
  zs_image_free(&im);
  zs_image_free(&back);
}
END_TEST

START_TEST(png_stream_matches_png_write) {
  char whole[PATH_MAX_LEN], streamed[PATH_MAX_LEN];
  out_file(whole, "whole.png");
  out_file(streamed, "streamed.png");
  zs_image im = random_image(64, 48, 3);
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_write(whole, &im, &err), ZS_OK);

  zs_png_stream *s;
  ck_assert_int_eq(zs_png_stream_open(&s, streamed, 64, 48, &err), ZS_OK);
  for (int y = 0; y < 48; y++) {
    ck_assert(!file_exists(streamed)); /* nothing under the name yet */
    ck_assert_int_eq(zs_png_stream_row(s, im.rgb + y * 64, &err), ZS_OK);
  }
  ck_assert_int_eq(zs_png_stream_close(s, 1, &err), ZS_OK);

  zs_test_assert_same_file(whole, streamed);
  zs_image_free(&im);
}
END_TEST

START_TEST(png_write_is_deterministic) {
  char first[PATH_MAX_LEN], second[PATH_MAX_LEN];
  out_file(first, "first.png");
  out_file(second, "second.png");
  zs_image im = random_image(50, 30, 4);
  for (int i = 0; i < 50 * 10; i++) im.rgb[i] = 0x336699; /* flat part too */
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_write(first, &im, &err), ZS_OK);
  ck_assert_int_eq(zs_png_write(second, &im, &err), ZS_OK);
  zs_test_assert_same_file(first, second);
  size_t n1;
  unsigned char *b1 = zs_test_slurp(first, &n1);
  /* Only IHDR, IDAT and IEND: walk the chunks after the signature. */
  size_t pos = 8;
  char types[16][5];
  int nchunks = 0;
  while (pos + 8 <= n1 && nchunks < 16) {
    uint32_t len = (uint32_t)b1[pos] << 24 | (uint32_t)b1[pos + 1] << 16 |
                   (uint32_t)b1[pos + 2] << 8 | b1[pos + 3];
    memcpy(types[nchunks], b1 + pos + 4, 4);
    types[nchunks][4] = '\0';
    nchunks++;
    pos += 12 + len;
  }
  ck_assert_uint_eq(pos, n1);
  ck_assert_int_ge(nchunks, 3);
  ck_assert_str_eq(types[0], "IHDR");
  for (int i = 1; i < nchunks - 1; i++) ck_assert_str_eq(types[i], "IDAT");
  ck_assert_str_eq(types[nchunks - 1], "IEND");
  free(b1);
  zs_image_free(&im);
}
END_TEST

START_TEST(png_write_replaces_existing_file) {
  char path[PATH_MAX_LEN];
  out_file(path, "replaced.png");
  zs_image a = random_image(8, 8, 5), b = random_image(3, 9, 6), back;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_write(path, &a, &err), ZS_OK);
  ck_assert_int_eq(zs_png_write(path, &b, &err), ZS_OK);
  ck_assert_int_eq(zs_png_read(path, &back, &err), ZS_OK);
  assert_same_pixels(&b, &back);
  ck_assert_int_eq(count_temporaries(), 0);
  zs_image_free(&a);
  zs_image_free(&b);
  zs_image_free(&back);
}
END_TEST

START_TEST(png_write_to_missing_directory_fails) {
  char path[PATH_MAX_LEN + 32];
  snprintf(path, sizeof path, "%s/no_such_dir/x.png", out_dir());
  zs_image im = random_image(4, 4, 7);
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_write(path, &im, &err), ZS_ERR_IO);
  char want[2 * PATH_MAX_LEN + 128];
  snprintf(want, sizeof want, "%s: no such directory: %s/no_such_dir", path, out_dir());
  ck_assert_str_eq(err.msg, want);
  ck_assert(!file_exists(path));

  zs_png_stream *s = (zs_png_stream *)&im; /* must be set to NULL */
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_stream_open(&s, path, 4, 4, &err), ZS_ERR_IO);
  ck_assert_ptr_null(s);
  ck_assert_str_eq(err.msg, want);

  snprintf(path, sizeof path, "%s/no_such_dir/x.pfm", out_dir());
  float values[4] = {0};
  zs_error_clear(&err);
  ck_assert_int_eq(zs_pfm_write(path, 2, 2, values, &err), ZS_ERR_IO);
  ck_assert_ptr_nonnull(strstr(err.msg, path));
  ck_assert(!file_exists(path));
  zs_image_free(&im);
}
END_TEST

START_TEST(png_stream_failures_leave_no_file) {
  char path[PATH_MAX_LEN];
  out_file(path, "stream_fail.png");
  zs_image old = random_image(6, 5, 8), back;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_write(path, &old, &err), ZS_OK);
  uint32_t row[6] = {0};

  /* Discarded: the old file stays. */
  zs_png_stream *s;
  ck_assert_int_eq(zs_png_stream_open(&s, path, 6, 5, &err), ZS_OK);
  ck_assert_int_eq(zs_png_stream_row(s, row, &err), ZS_OK);
  ck_assert_int_eq(count_temporaries(), 1);
  ck_assert_int_eq(zs_png_stream_close(s, 0, &err), ZS_OK);
  ck_assert_int_eq(count_temporaries(), 0);

  /* Committed with rows missing: an error, and the old file stays. */
  ck_assert_int_eq(zs_png_stream_open(&s, path, 6, 5, &err), ZS_OK);
  ck_assert_int_eq(zs_png_stream_row(s, row, &err), ZS_OK);
  ck_assert_int_eq(zs_png_stream_close(s, 1, &err), ZS_ERR_ARG);
  ck_assert_ptr_nonnull(strstr(err.msg, path));
  ck_assert_ptr_nonnull(strstr(err.msg, "only 1 of 5 rows"));
  ck_assert_int_eq(count_temporaries(), 0);

  /* A row too many: an error at once, the temporary gone at once. */
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_stream_open(&s, path, 6, 1, &err), ZS_OK);
  ck_assert_int_eq(zs_png_stream_row(s, row, &err), ZS_OK);
  ck_assert_int_eq(zs_png_stream_row(s, row, &err), ZS_ERR_ARG);
  ck_assert_ptr_nonnull(strstr(err.msg, "more than 1 rows"));
  ck_assert_int_eq(count_temporaries(), 0);
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_stream_row(s, row, &err), ZS_ERR_ARG); /* stays failed */
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_stream_close(s, 1, &err), ZS_ERR_ARG);
  ck_assert_int_eq(count_temporaries(), 0);

  ck_assert_int_eq(zs_png_read(path, &back, &err), ZS_OK);
  assert_same_pixels(&old, &back);
  ck_assert_int_eq(zs_png_stream_close(NULL, 1, &err), ZS_OK);
  zs_image_free(&old);
  zs_image_free(&back);
}
END_TEST

START_TEST(png_bad_sizes_are_refused) {
  char path[PATH_MAX_LEN];
  out_file(path, "bad_size.png");
  zs_error err;
  zs_image im;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_image_alloc(&im, 0, 5, &err), ZS_ERR_LIMIT);
  ck_assert_ptr_null(im.rgb);
  zs_image_free(&im);
  zs_error_clear(&err);
  ck_assert_int_eq(zs_image_alloc(&im, 5, 16385, &err), ZS_ERR_LIMIT);
  zs_png_stream *s;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_stream_open(&s, path, -1, 5, &err), ZS_ERR_LIMIT);
  ck_assert_ptr_null(s);
  ck_assert(!file_exists(path));
  ck_assert_int_eq(count_temporaries(), 0);
}
END_TEST

START_TEST(png_truncated_is_refused) {
  char good[PATH_MAX_LEN], cut[PATH_MAX_LEN];
  out_file(good, "good.png");
  out_file(cut, "truncated.png");
  zs_image im = random_image(9, 7, 9), back;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_write(good, &im, &err), ZS_OK);
  size_t n;
  unsigned char *bytes = zs_test_slurp(good, &n);
  /* Every proper prefix of the file is refused with a message. */
  for (size_t len = 0; len < n; len++) {
    spit(cut, bytes, len);
    zs_error_clear(&err);
    back.rgb = (uint32_t *)bytes; /* must be reset */
    zs_status st = zs_png_read(cut, &back, &err);
    ck_assert_msg(st != ZS_OK, "a prefix of %zu of %zu bytes was accepted", len, n);
    ck_assert_ptr_null(back.rgb);
    ck_assert_ptr_nonnull(strstr(err.msg, cut));
    if (len >= 8) /* past the signature: the data ran out */
      ck_assert_msg(strstr(err.msg, "truncated") != NULL, "%zu: %s", len, err.msg);
  }
  free(bytes);
  zs_image_free(&im);
}
END_TEST

START_TEST(png_corrupt_is_refused) {
  char path[PATH_MAX_LEN];
  out_file(path, "corrupt.png");
  zs_image im = random_image(9, 7, 10), back;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_write(path, &im, &err), ZS_OK);
  size_t n;
  unsigned char *bytes = zs_test_slurp(path, &n);
  bytes[8 + 25 + 8 + 2] ^= 0x40; /* a byte of the first IDAT's data */
  spit(path, bytes, n);
  ck_assert_int_ne(zs_png_read(path, &back, &err), ZS_OK);
  ck_assert_ptr_nonnull(strstr(err.msg, path));
  ck_assert_ptr_null(back.rgb);
  free(bytes);
  zs_image_free(&im);
}
END_TEST

START_TEST(png_non_png_is_refused) {
  char path[PATH_MAX_LEN];
  out_file(path, "not_a.png");
  const char text[] = "P3\n1 1\n255\n0 0 0\n";
  spit(path, text, sizeof text - 1);
  zs_image back;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_read(path, &back, &err), ZS_ERR_PARSE);
  char want[PATH_MAX_LEN + 32];
  snprintf(want, sizeof want, "%s: not a PNG file", path);
  ck_assert_str_eq(err.msg, want);

  out_file(path, "missing.png");
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_read(path, &back, &err), ZS_ERR_IO);
  snprintf(want, sizeof want, "%s: cannot open: %s", path, strerror(ENOENT));
  ck_assert_str_eq(err.msg, want);
}
END_TEST

/* Writes a PNG with libpng itself, in any format: rows are the raw,
 * packed samples of each row. */
static void write_raw_png(const char *path, int w, int h, int color, int depth,
                          int interlace, unsigned char **rows,
                          const png_color *palette, int npalette,
                          const png_byte *trans, int ntrans,
                          const png_color_16 *trans_color) {
  FILE *fp = fopen(path, "wb");
  ck_assert_ptr_nonnull(fp);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
  png_infop info = png_create_info_struct(png);
  ck_assert_ptr_nonnull(info);
  if (setjmp(png_jmpbuf(png))) ck_abort_msg("libpng failed writing %s", path);
  png_init_io(png, fp);
  png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, depth, color,
               interlace, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (palette) png_set_PLTE(png, info, palette, npalette);
  if (trans || trans_color) png_set_tRNS(png, info, trans, ntrans, trans_color);
  png_set_rows(png, info, rows);
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, NULL);
  png_destroy_write_struct(&png, &info);
  ck_assert_int_eq(fclose(fp), 0);
}

static zs_image read_ok(const char *path) {
  zs_image im;
  zs_error err;
  zs_error_clear(&err);
  zs_status st = zs_png_read(path, &im, &err);
  ck_assert_msg(st == ZS_OK, "%s", err.msg);
  return im;
}

START_TEST(png_reads_grey_formats) {
  char path[PATH_MAX_LEN];
  out_file(path, "formats.png");

  /* 8-bit grey. */
  unsigned char g8[2][2] = {{0, 50}, {128, 255}};
  unsigned char *rows[3] = {g8[0], g8[1]};
  write_raw_png(path, 2, 2, PNG_COLOR_TYPE_GRAY, 8, PNG_INTERLACE_NONE, rows,
                NULL, 0, NULL, 0, NULL);
  zs_image im = read_ok(path);
  ck_assert_uint_eq(im.rgb[0], 0x000000);
  ck_assert_uint_eq(im.rgb[1], 0x323232);
  ck_assert_uint_eq(im.rgb[2], 0x808080);
  ck_assert_uint_eq(im.rgb[3], 0xFFFFFF);
  zs_image_free(&im);

  /* 16-bit grey, big-endian samples, scaled with rounding: 0x12FF -> 0x13. */
  unsigned char g16[1][6] = {{0x00, 0x00, 0xFF, 0xFF, 0x12, 0xFF}};
  rows[0] = g16[0];
  write_raw_png(path, 3, 1, PNG_COLOR_TYPE_GRAY, 16, PNG_INTERLACE_NONE, rows,
                NULL, 0, NULL, 0, NULL);
  im = read_ok(path);
  ck_assert_uint_eq(im.rgb[0], 0x000000);
  ck_assert_uint_eq(im.rgb[1], 0xFFFFFF);
  ck_assert_uint_eq(im.rgb[2], 0x131313);
  zs_image_free(&im);

  /* 8-bit grey + alpha: alpha dropped, not composited. */
  unsigned char ga[1][4] = {{100, 0, 200, 77}};
  rows[0] = ga[0];
  write_raw_png(path, 2, 1, PNG_COLOR_TYPE_GRAY_ALPHA, 8, PNG_INTERLACE_NONE,
                rows, NULL, 0, NULL, 0, NULL);
  im = read_ok(path);
  ck_assert_uint_eq(im.rgb[0], 0x646464);
  ck_assert_uint_eq(im.rgb[1], 0xC8C8C8);
  zs_image_free(&im);

  /* 1-bit grey with a transparent colour: 0 black, 1 white. */
  unsigned char g1[2][1] = {{0xA0}, {0x40}}; /* 1 0 1, 0 1 0 */
  rows[0] = g1[0];
  rows[1] = g1[1];
  png_color_16 black = {0, 0, 0, 0, 0};
  write_raw_png(path, 3, 2, PNG_COLOR_TYPE_GRAY, 1, PNG_INTERLACE_NONE, rows,
                NULL, 0, NULL, 0, &black);
  im = read_ok(path);
  uint32_t want1[6] = {0xFFFFFF, 0, 0xFFFFFF, 0, 0xFFFFFF, 0};
  for (int i = 0; i < 6; i++) ck_assert_uint_eq(im.rgb[i], want1[i]);
  zs_image_free(&im);
}
END_TEST

START_TEST(png_reads_palette) {
  char path[PATH_MAX_LEN];
  out_file(path, "palette.png");
  png_color palette[3] = {{255, 0, 0}, {0, 255, 0}, {10, 20, 30}};
  png_byte trans[3] = {0, 128, 255};
  unsigned char p4[2][2] = {{0x01, 0x20}, {0x21, 0x00}}; /* 0 1 2, 2 1 0 */
  unsigned char *rows[2] = {p4[0], p4[1]};
  for (int with_trns = 0; with_trns <= 1; with_trns++) {
    write_raw_png(path, 3, 2, PNG_COLOR_TYPE_PALETTE, 4, PNG_INTERLACE_NONE,
                  rows, palette, 3, with_trns ? trans : NULL,
                  with_trns ? 3 : 0, NULL);
    zs_image im = read_ok(path);
    uint32_t want[6] = {0xFF0000, 0x00FF00, 0x0A141E,
                        0x0A141E, 0x00FF00, 0xFF0000};
    for (int i = 0; i < 6; i++) ck_assert_uint_eq(im.rgb[i], want[i]);
    zs_image_free(&im);
  }
}
END_TEST

START_TEST(png_reads_interlaced_rgb_and_rgba) {
  char path[PATH_MAX_LEN];
  out_file(path, "interlaced.png");
  enum { W = 13, H = 11 };
  zs_image want = random_image(W, H, 11);
  static unsigned char rgb8[H][3 * W], rgba16[H][8 * W];
  unsigned char *rows[H];
  for (int y = 0; y < H; y++) {
    for (int x = 0; x < W; x++) {
      uint32_t p = want.rgb[y * W + x];
      unsigned char c[3] = {(unsigned char)(p >> 16), (unsigned char)(p >> 8),
                            (unsigned char)p};
      for (int k = 0; k < 3; k++) {
        rgb8[y][3 * x + k] = c[k];
        rgba16[y][8 * x + 2 * k] = c[k]; /* v * 257 scales back to v */
        rgba16[y][8 * x + 2 * k + 1] = c[k];
      }
      rgba16[y][8 * x + 6] = (unsigned char)(x * 19);
      rgba16[y][8 * x + 7] = (unsigned char)(y * 23);
    }
  }
  for (int y = 0; y < H; y++) rows[y] = rgb8[y];
  write_raw_png(path, W, H, PNG_COLOR_TYPE_RGB, 8, PNG_INTERLACE_ADAM7, rows,
                NULL, 0, NULL, 0, NULL);
  zs_image im = read_ok(path);
  assert_same_pixels(&want, &im);
  zs_image_free(&im);

  for (int y = 0; y < H; y++) rows[y] = rgba16[y];
  write_raw_png(path, W, H, PNG_COLOR_TYPE_RGB_ALPHA, 16, PNG_INTERLACE_ADAM7,
                rows, NULL, 0, NULL, 0, NULL);
  im = read_ok(path);
  assert_same_pixels(&want, &im);
  zs_image_free(&im);
  zs_image_free(&want);
}
END_TEST

START_TEST(png_read_refuses_oversized) {
  char path[PATH_MAX_LEN];
  out_file(path, "too_wide.png");
  static unsigned char zeros[16385];
  unsigned char *rows[1] = {zeros};
  write_raw_png(path, 16385, 1, PNG_COLOR_TYPE_GRAY, 8, PNG_INTERLACE_NONE,
                rows, NULL, 0, NULL, 0, NULL);
  zs_image im;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_read(path, &im, &err), ZS_ERR_LIMIT);
  ck_assert_ptr_nonnull(strstr(err.msg, path));
  ck_assert_ptr_nonnull(strstr(err.msg, "16385x1"));
  ck_assert_ptr_null(im.rgb);
}
END_TEST

/* ---- PFM ---- */

START_TEST(pfm_header_size_and_values) {
  char path[PATH_MAX_LEN];
  out_file(path, "depth.pfm");
  enum { W = 3, H = 2 };
  const float values[W * H] = {0.0f, 0.5f, 1.0f,     /* row 0, the top */
                               -2.25f, 1e-3f, 3e9f}; /* row 1 */
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_pfm_write(path, W, H, values, &err), ZS_OK);
  ck_assert_int_eq(count_temporaries(), 0);
  size_t n;
  unsigned char *bytes = zs_test_slurp(path, &n);
  const char header[] = "Pf\n3 2\n-1.0\n";
  size_t hn = sizeof header - 1;
  ck_assert_uint_eq(n, hn + 4 * W * H);
  ck_assert(memcmp(bytes, header, hn) == 0);
  /* Parse it: little-endian floats, the bottom row first. */
  for (int i = 0; i < W * H; i++) {
    const unsigned char *b = bytes + hn + 4 * i;
    uint32_t bits = (uint32_t)b[0] | (uint32_t)b[1] << 8 |
                    (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
    float v;
    memcpy(&v, &bits, sizeof v);
    int file_row = i / W, x = i % W;
    int y = H - 1 - file_row;
    ck_assert_msg(v == values[y * W + x], "value %d: %g", i, (double)v);
  }
  free(bytes);
}
END_TEST

/* ---- The hash ---- */

START_TEST(hash_of_a_tiny_image) {
  /* The size as two 32-bit little-endian numbers, then the pixels
   * 0x666F6F, 0x626172 as the bytes "foo" "bar".  FNV-1a 64:
   * h = 0xcbf29ce484222325; for each byte c: h ^= c, h *= 0x100000001b3. */
  static const unsigned char bytes[14] = {2, 0, 0, 0, 1, 0, 0, 0, 'f', 'o', 'o', 'b', 'a', 'r'};
  uint32_t px[2] = {0x666F6F, 0x626172};
  zs_image im = {2, 1, px};
  ck_assert(zs_image_hash(&im) == 0xb950327571a622ffull);
  ck_assert(zs_image_hash(&im) == zs_test_fnv1a(bytes, sizeof bytes));
  px[0] |= 0xFF000000u; /* the top byte is not a channel */
  ck_assert(zs_image_hash(&im) == 0xb950327571a622ffull);
  zs_image empty = {0, 0, NULL};
  ck_assert(zs_image_hash(&empty) == 0xa8c7f832281a39c5ull);
}
END_TEST

/* Two blank frames of 64x48 and 48x64: the same bytes of pixels, but not
 * the same picture, so not the same hash. */
START_TEST(hash_covers_the_size) {
  zs_image a, b;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_image_alloc(&a, 64, 48, &err), ZS_OK);
  ck_assert_int_eq(zs_image_alloc(&b, 48, 64, &err), ZS_OK);
  ck_assert_uint_eq(zs_image_hash(&a), 0x99a9700217e536d5ull);
  ck_assert_uint_eq(zs_image_hash(&b), 0xc7c76065af5c4375ull);
  zs_image_free(&a);
  zs_image_free(&b);
}
END_TEST

/* ---- zs_image_diff ---- */

START_TEST(image_diff_counts_and_max) {
  uint32_t pa[6] = {0x102030, 0x000000, 0xFFFFFF, 0x808080, 0x123456, 0x010203};
  uint32_t pb[6] = {0x102030, 0x000005, 0xFFFFFF, 0x80C080, 0x123456, 0x010204};
  zs_image a = {3, 2, pa}, b = {3, 2, pb}, d;
  zs_diff_result res;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_image_diff(&a, &b, &d, &res, &err), ZS_OK);
  ck_assert_uint_eq(res.differing, 3);
  ck_assert_uint_eq(res.total, 6);
  ck_assert_int_eq(res.max_channel_diff, 0x40);
  /* Equal pixels: luma / 4.  0x102030: (77*16 + 150*32 + 29*48 + 128) / 256
   * = 7552 / 256 = 29, / 4 = 7.  White: 255 / 4 = 63 = 0x3F. */
  ck_assert_uint_eq(d.rgb[0], 0x070707);
  ck_assert_uint_eq(d.rgb[1], 0xFF0000);
  ck_assert_uint_eq(d.rgb[2], 0x3F3F3F);
  ck_assert_uint_eq(d.rgb[3], 0xFF0000);
  ck_assert_uint_eq(d.rgb[5], 0xFF0000);
  zs_image_free(&d);

  ck_assert_int_eq(zs_image_diff(&a, &a, NULL, &res, &err), ZS_OK);
  ck_assert_uint_eq(res.differing, 0);
  ck_assert_int_eq(res.max_channel_diff, 0);

  zs_image c = {2, 3, pb};
  ck_assert_int_eq(zs_image_diff(&a, &c, &d, &res, &err), ZS_ERR_ARG);
  ck_assert_str_eq(err.msg, "images differ in size: 3x2 and 2x3");
  ck_assert_ptr_null(d.rgb);
}
END_TEST

/* ---- zscan diff ---- */

typedef struct captured {
  int status;
  char out[4096], err[4096];
} captured;

static void read_text(const char *path, char *buf, size_t size) {
  size_t n = 0;
  unsigned char *bytes = zs_test_slurp(path, &n);
  ck_assert_ptr_nonnull(bytes);
  ck_assert_uint_lt(n, size);
  memcpy(buf, bytes, n);
  buf[n] = '\0';
  free(bytes);
}

/* Runs zs_cmd_diff(argv) with standard output and error sent to files. */
static captured run_diff(int argc, char **argv) {
  char out_path[PATH_MAX_LEN], err_path[PATH_MAX_LEN];
  out_file(out_path, "diff_stdout.txt");
  out_file(err_path, "diff_stderr.txt");
  fflush(stdout);
  fflush(stderr);
  int saved_out = dup(STDOUT_FILENO), saved_err = dup(STDERR_FILENO);
  int fo = open(out_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  int fe = open(err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ck_assert(saved_out >= 0 && saved_err >= 0 && fo >= 0 && fe >= 0);
  dup2(fo, STDOUT_FILENO);
  dup2(fe, STDERR_FILENO);
  close(fo);
  close(fe);
  captured c;
  c.status = zs_cmd_diff(argc, argv);
  fflush(stdout);
  fflush(stderr);
  dup2(saved_out, STDOUT_FILENO);
  dup2(saved_err, STDERR_FILENO);
  close(saved_out);
  close(saved_err);
  read_text(out_path, c.out, sizeof c.out);
  read_text(err_path, c.err, sizeof c.err);
  return c;
}

START_TEST(cmd_diff_exit_status_and_report) {
  char pa[PATH_MAX_LEN], pb[PATH_MAX_LEN], pd[PATH_MAX_LEN], missing[PATH_MAX_LEN];
  out_file(pa, "diff_a.png");
  out_file(pb, "diff_b.png");
  out_file(pd, "diff_d.png");
  out_file(missing, "diff_missing.png");
  zs_image a = random_image(10, 4, 12), b = random_image(10, 4, 12);
  b.rgb[3] ^= 0x000010;            /* blue differs by 16 */
  a.rgb[17] &= 0x00FFFF;
  b.rgb[17] = a.rgb[17] | 0xC00000; /* red differs by 192 */
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_write(pa, &a, &err), ZS_OK);
  ck_assert_int_eq(zs_png_write(pb, &b, &err), ZS_OK);

  char *same[] = {"diff", pa, pa};
  captured c = run_diff(3, same);
  ck_assert_int_eq(c.status, 0);
  ck_assert_str_eq(c.out, "pixels_differing 0 of 40\nmax_channel_diff 0\n");
  ck_assert_str_eq(c.err, "");

  char *differ[] = {"diff", pa, pb, "-o", pd};
  c = run_diff(5, differ);
  ck_assert_int_eq(c.status, 1);
  ck_assert_str_eq(c.out, "pixels_differing 2 of 40\nmax_channel_diff 192\n");
  zs_image d = read_ok(pd);
  ck_assert_int_eq(d.width, 10);
  /* the heat map: changed pixels from yellow (small) to red (large),
   * the others a faded grey */
  ck_assert_uint_eq(d.rgb[3] & 0xFF00FF, 0xFF0000);
  ck_assert_uint_eq(d.rgb[17] & 0xFF00FF, 0xFF0000);
  ck_assert_uint_gt(d.rgb[3] >> 8 & 0xFF, d.rgb[17] >> 8 & 0xFF); /* 16 more yellow than 192 */
  ck_assert_uint_eq(d.rgb[4] >> 16, d.rgb[4] & 0xFF); /* grey */
  ck_assert_uint_ge(d.rgb[4] & 0xFF, 160);
  zs_image_free(&d);

  char *absent[] = {"diff", pa, missing};
  c = run_diff(3, absent);
  ck_assert_int_eq(c.status, 1); /* bad input; 2 is for usage errors */
  ck_assert_str_eq(c.out, "");
  char want[3 * PATH_MAX_LEN];
  snprintf(want, sizeof want, "zscan diff: %s: cannot open: %s\n", missing,
           strerror(ENOENT));
  ck_assert_str_eq(c.err, want);

  char *bad_option[] = {"diff", pa, pb, "--bogus"};
  c = run_diff(4, bad_option);
  ck_assert_int_eq(c.status, 2);
  ck_assert_ptr_nonnull(strstr(c.err, "zscan diff: unknown option '--bogus'"));

  char *one_file[] = {"diff", pa};
  c = run_diff(2, one_file);
  ck_assert_int_eq(c.status, 2);

  char *no_o_arg[] = {"diff", pa, pb, "-o"};
  c = run_diff(4, no_o_arg);
  ck_assert_int_eq(c.status, 2);

  zs_image small = random_image(3, 3, 13);
  ck_assert_int_eq(zs_png_write(pb, &small, &err), ZS_OK);
  c = run_diff(3, differ);
  ck_assert_int_eq(c.status, 1); /* pictures of different sizes differ */
  snprintf(want, sizeof want,
           "zscan diff: %s and %s: images differ in size: 10x4 and 3x3\n", pa, pb);
  ck_assert_str_eq(c.err, want);
  ck_assert_str_eq(c.out, "");

  zs_image_free(&a);
  zs_image_free(&b);
  zs_image_free(&small);
}
END_TEST

START_TEST(cmd_diff_lists_face_ids) {
  char pa[PATH_MAX_LEN], pb[PATH_MAX_LEN];
  out_file(pa, "ids_a.png");
  out_file(pb, "ids_b.png");
  /* id images: value = face id + 1, 0 = background */
  uint32_t va[5] = {0, 5, 7, 0x010000, 9};
  uint32_t vb[5] = {3, 5, 8, 0x010000, 9};
  zs_image a = {5, 1, va}, b = {5, 1, vb};
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_write_shaded(pa, &a, ZS_SHADE_ID, &err), ZS_OK);
  ck_assert_int_eq(zs_png_write_shaded(pb, &b, ZS_SHADE_ID, &err), ZS_OK);
  char *args[] = {"diff", "--ids", pa, pb};
  captured c = run_diff(4, args);
  ck_assert_int_eq(c.status, 1);
  ck_assert_str_eq(c.out,
                   "pixels_differing 2 of 5\nmax_channel_diff 3\n"
                   "faces_involved 4: background 2 6 7\n");

  char *same[] = {"diff", pa, pa, "--ids"};
  c = run_diff(4, same);
  ck_assert_int_eq(c.status, 0);
  ck_assert_str_eq(c.out,
                   "pixels_differing 0 of 5\nmax_channel_diff 0\nfaces_involved 0:\n");

  /* 25 differing pixels, 50 ids: the first 20, then "...". */
  uint32_t wa[25], wb[25];
  for (int i = 0; i < 25; i++) {
    wa[i] = (uint32_t)(1000 + i);
    wb[i] = (uint32_t)(2000 + i);
  }
  zs_image a2 = {25, 1, wa}, b2 = {25, 1, wb};
  ck_assert_int_eq(zs_png_write_shaded(pa, &a2, ZS_SHADE_ID, &err), ZS_OK);
  ck_assert_int_eq(zs_png_write_shaded(pb, &b2, ZS_SHADE_ID, &err), ZS_OK);
  c = run_diff(4, args);
  ck_assert_int_eq(c.status, 1);
  char want[1024];
  int len = snprintf(want, sizeof want, "faces_involved 50:");
  for (int i = 0; i < 20; i++) len += snprintf(want + len, sizeof want - len, " %d", 999 + i);
  snprintf(want + len, sizeof want - len, " ...\n");
  ck_assert_ptr_nonnull(strstr(c.out, want));
}
END_TEST

/* An ordinary picture's colours are not face ids: --ids refuses it, and
 * says which file, while a plain diff of the same files still works. */
START_TEST(cmd_diff_ids_refuses_plain_pictures) {
  char pa[PATH_MAX_LEN], pb[PATH_MAX_LEN];
  out_file(pa, "marked.png");
  out_file(pb, "plain.png");
  uint32_t v[3] = {0, 5, 7};
  zs_image im = {3, 1, v};
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_png_write_shaded(pa, &im, ZS_SHADE_ID, &err), ZS_OK);
  ck_assert_int_eq(zs_png_write_shaded(pb, &im, ZS_SHADE_FLAT, &err), ZS_OK);

  /* the mark is read back; the pixels are the same either way */
  zs_image back;
  int ids = -1;
  ck_assert_int_eq(zs_png_read_marked(pa, &back, &ids, &err), ZS_OK);
  ck_assert_int_eq(ids, 1);
  ck_assert_uint_eq(zs_image_hash(&back), zs_image_hash(&im));
  zs_image_free(&back);
  ck_assert_int_eq(zs_png_read_marked(pb, &back, &ids, &err), ZS_OK);
  ck_assert_int_eq(ids, 0);
  zs_image_free(&back);

  for (int order = 0; order < 2; order++) {
    char *args[] = {"diff", "--ids", order ? pb : pa, order ? pa : pb};
    captured c = run_diff(4, args);
    ck_assert_int_eq(c.status, 1);
    ck_assert_str_eq(c.out, "");
    char want[PATH_MAX_LEN + 128];
    snprintf(want, sizeof want,
             "zscan diff: --ids: %s is not a --shade id render written by zscan; "
             "its colours are not face ids\n", pb);
    ck_assert_str_eq(c.err, want);
  }
  char *plain[] = {"diff", pa, pb};
  captured c = run_diff(3, plain);
  ck_assert_int_eq(c.status, 0);
  ck_assert_str_eq(c.out, "pixels_differing 0 of 3\nmax_channel_diff 0\n");
}
END_TEST

/* ---- tools/crosscheck.c: coverage told apart from depth ties ---- */

/* Face 0 and face 1 are the same square (a tie everywhere); face 2 a
 * square beside it; face 3 a larger square well behind both. */
static const char crosscheck_obj[] =
    "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
    "v 1.5 -0.5 0\nv 2.5 -0.5 0\nv 2.5 0.5 0\nv 1.5 0.5 0\n"
    "v -1.5 -1.5 -2\nv 1.5 -1.5 -2\nv 1.5 1.5 -2\nv -1.5 1.5 -2\n"
    "f 1 2 3 4\nf 1 2 3 4\nf 5 6 7 8\nf 9 10 11 12\n";

START_TEST(crosscheck_tells_ties_from_coverage) {
  enum { W = 96, H = 64 };
  char path[PATH_MAX_LEN], list_path[PATH_MAX_LEN];
  spit(out_file(path, "crosscheck.obj"), crosscheck_obj, sizeof crosscheck_obj - 1);
  zs_scene s;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_input_load_scene(path, &s, &err) == ZS_OK, "%s", err.msg);
  double view[16], proj[16];
  ck_assert_int_eq(zs_frame_camera(&s, &s.camera, W, H, view, proj, &err), ZS_OK);
  zs_frame_opts o = {.width = W, .height = H, .algo = ZS_ALGO_ZBUFFER, .shade = ZS_SHADE_ID, .threads = 1};
  zs_image im;
  ck_assert_int_eq(zs_frame_render(&s, &s.camera, &o, &im, NULL, NULL, &err), ZS_OK);
  /* zscan's own faces: nothing differs */
  zs_crosscheck x;
  ck_assert_int_eq(zs_crosscheck_faces(&s, view, proj, W, H, im.rgb, NULL, &x, &err), ZS_OK);
  ck_assert_uint_eq(x.pixels, W * H);
  ck_assert_uint_eq(x.differ, 0);
  ck_assert_uint_eq(x.ties, 0);
  /* pixels where zscan shows face 0 (the lower id wins the tie with 1) */
  int shown0[W * H], n0 = 0, covered = 0;
  for (int i = 0; i < W * H; i++) {
    if (im.rgb[i] == 1) shown0[n0++] = i;
    covered += im.rgb[i] != 0;
    ck_assert_uint_ne(im.rgb[i], 2); /* face 1 never shows */
  }
  ck_assert_int_gt(n0, 100);
  ck_assert_uint_eq(x.covered, (uint64_t)covered);
  /* the other renderer's answers at four of them: face 1 (the same plane:
   * a tie), face 2 (does not cover it), face 3 (covers it, far behind),
   * the background */
  int at[4] = {shown0[n0 / 5], shown0[2 * n0 / 5], shown0[3 * n0 / 5], shown0[4 * n0 / 5]};
  im.rgb[at[0]] = 2, im.rgb[at[1]] = 3, im.rgb[at[2]] = 4, im.rgb[at[3]] = 0;
  FILE *list = fopen(out_file(list_path, "crosscheck.txt"), "w");
  ck_assert_ptr_nonnull(list);
  ck_assert_int_eq(zs_crosscheck_faces(&s, view, proj, W, H, im.rgb, list, &x, &err), ZS_OK);
  ck_assert_int_eq(fclose(list), 0);
  ck_assert_uint_eq(x.differ, 4);
  ck_assert_uint_eq(x.ties, 1);
  size_t size;
  char *text = (char *)zs_test_slurp(list_path, &size);
  text = realloc(text, size + 1);
  text[size] = 0;
  char want[4][128];
  const char *what[4] = {"1, tie (depth +0)", "2, coverage", "3, coverage", "none, coverage"};
  for (int k = 0; k < 4; k++) {
    snprintf(want[k], sizeof want[k], "  pixel %d,%d: zscan face 0, other face %s\n", at[k] % W,
             at[k] / W, what[k]);
    ck_assert_msg(strstr(text, want[k]), "missing \"%s\" in:\n%s", want[k], text);
  }
  int lines = 0;
  for (const char *c = text; *c; c++) lines += *c == '\n';
  ck_assert_int_eq(lines, 4);
  free(text);
  zs_image_free(&im);
  zs_scene_free(&s);
}
END_TEST

static Suite *suite(void) {
  Suite *s = suite_create("image");
  TCase *png = tcase_create("png");
  tcase_add_test(png, png_round_trip_is_exact);
  tcase_add_test(png, png_top_byte_is_ignored);
  tcase_add_test(png, png_stream_matches_png_write);
  tcase_add_test(png, png_write_is_deterministic);
  tcase_add_test(png, png_write_replaces_existing_file);
  tcase_add_test(png, png_write_to_missing_directory_fails);
  tcase_add_test(png, png_stream_failures_leave_no_file);
  tcase_add_test(png, png_bad_sizes_are_refused);
  tcase_add_test(png, png_truncated_is_refused);
  tcase_add_test(png, png_corrupt_is_refused);
  tcase_add_test(png, png_non_png_is_refused);
  tcase_add_test(png, png_reads_grey_formats);
  tcase_add_test(png, png_reads_palette);
  tcase_add_test(png, png_reads_interlaced_rgb_and_rgba);
  tcase_add_test(png, png_read_refuses_oversized);
  suite_add_tcase(s, png);
  TCase *other = tcase_create("pfm_hash_diff");
  tcase_add_test(other, pfm_header_size_and_values);
  tcase_add_test(other, hash_of_a_tiny_image);
  tcase_add_test(other, hash_covers_the_size);
  tcase_add_test(other, image_diff_counts_and_max);
  tcase_add_test(other, cmd_diff_exit_status_and_report);
  tcase_add_test(other, cmd_diff_lists_face_ids);
  tcase_add_test(other, cmd_diff_ids_refuses_plain_pictures);
  tcase_add_test(other, crosscheck_tells_ties_from_coverage);
  suite_add_tcase(s, other);
  return s;
}

int main(void) { return zs_test_run(suite()); }
