/* zscan tools — `zscan diff`: comparing two images.
 *
 *   zscan diff A.png B.png [-o diff.png] [--ids]
 *
 * prints to standard output
 *
 *   pixels_differing N of TOTAL
 *   max_channel_diff M
 *   faces_involved K: ID ID ...        (with --ids only)
 *
 * and exits 0 when the images are identical, 1 when they differ, 2 on an
 * error (one line "zscan diff: reason" on standard error).  Images of
 * different sizes are an error.
 *
 * M is the largest |a - b| over the R, G and B channels of all pixels.
 *
 * --ids reads the images as `--shade id` renderings, where a pixel is the
 * face id + 1 as a 24-bit number 0xRRGGBB and 0 is the background.  K is the
 * number of distinct values seen at the differing pixels, in either image;
 * they are listed in ascending order as face ids (value - 1), "background"
 * (value 0) first, at most 20 of them followed by "..." when there are
 * more.  With no differing pixel the line is "faces_involved 0:".
 *
 * -o writes a difference image (see zs_image_diff).
 */
#include "tools/commands.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/image.h"
#include "lib/outfile.h"

#define RGB_MASK 0xFFFFFFu

enum {
  EXIT_SAME = 0,
  EXIT_DIFFERENT = 1,
  EXIT_ERROR = 2,
  MAX_IDS_LISTED = 20,
  ID_VALUES = 1 << 24 /* every 24-bit pixel value */
};

/* ---- The command ---- */

typedef struct diff_args {
  const char *a, *b; /* the images */
  const char *out;   /* -o, or NULL */
  int ids;           /* --ids */
} diff_args;

static int fail(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* Prints "zscan diff: reason" on stderr; returns the error exit status. */
static int fail(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fputs("zscan diff: ", stderr);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  return EXIT_ERROR;
}

/* Returns 0, or EXIT_ERROR after printing why. */
static int parse_args(int argc, char **argv, diff_args *args) {
  static const char usage[] = "usage: zscan diff A.png B.png [-o diff.png] [--ids]";
  args->a = args->b = args->out = NULL;
  args->ids = 0;
  for (int i = 1; i < argc; i++) {
    const char *arg = argv[i];
    if (strcmp(arg, "-o") == 0) {
      if (i + 1 >= argc) return fail("-o needs a file name; %s", usage);
      args->out = argv[++i];
    } else if (strcmp(arg, "--ids") == 0) {
      args->ids = 1;
    } else if (arg[0] == '-' && arg[1] != '\0') {
      return fail("unknown option '%s'; %s", arg, usage);
    } else if (!args->a) {
      args->a = arg;
    } else if (!args->b) {
      args->b = arg;
    } else {
      return fail("too many files ('%s'); %s", arg, usage);
    }
  }
  if (!args->b) return fail("two images needed; %s", usage);
  return 0;
}

static void mark(uint64_t *seen, uint32_t value) {
  seen[value / 64] |= (uint64_t)1 << (value % 64);
}

static int popcount64(uint64_t x) {
  int n = 0;
  for (; x; x &= x - 1) n++;
  return n;
}

/* Prints "faces_involved K: ..." for the pixel values of a and b at the
 * pixels where they differ.  Returns 0, or -1 when out of memory. */
static int print_ids(const zs_image *a, const zs_image *b) {
  size_t words = ID_VALUES / 64;
  uint64_t *seen = calloc(words, sizeof *seen); /* one bit per value */
  if (!seen) return -1;
  size_t n = (size_t)a->width * (size_t)a->height;
  for (size_t i = 0; i < n; i++) {
    uint32_t pa = a->rgb[i] & RGB_MASK, pb = b->rgb[i] & RGB_MASK;
    if (pa != pb) {
      mark(seen, pa);
      mark(seen, pb);
    }
  }
  unsigned long involved = 0;
  for (size_t w = 0; w < words; w++) involved += (unsigned long)popcount64(seen[w]);

  printf("faces_involved %lu:", involved);
  unsigned long listed = 0;
  for (size_t w = 0; w < words && listed < MAX_IDS_LISTED; w++) {
    if (seen[w] == 0) continue;
    for (int bit = 0; bit < 64 && listed < MAX_IDS_LISTED; bit++) {
      if (!(seen[w] >> bit & 1)) continue;
      unsigned long value = (unsigned long)(w * 64 + (size_t)bit);
      if (value == 0)
        printf(" background");
      else
        printf(" %lu", value - 1);
      listed++;
    }
  }
  if (involved > listed) printf(" ...");
  printf("\n");
  free(seen);
  return 0;
}

int zs_cmd_diff(int argc, char **argv) {
  diff_args args;
  if (parse_args(argc, argv, &args) != 0) return EXIT_ERROR;

  zs_error err;
  zs_error_clear(&err);
  zs_image a = {0, 0, NULL}, b = {0, 0, NULL}, diff = {0, 0, NULL};
  zs_diff_result res;
  int status = EXIT_ERROR;
  if (zs_png_read(args.a, &a, &err) != ZS_OK ||
      zs_png_read(args.b, &b, &err) != ZS_OK)
    goto done;
  if (zs_image_diff(&a, &b, args.out ? &diff : NULL, &res, &err) != ZS_OK) {
    /* the sizes: say which files */
    fail("%s and %s: %s", args.a, args.b, err.msg);
    zs_error_clear(&err);
    goto done;
  }
  if (args.out && zs_png_write(args.out, &diff, &err) != ZS_OK) {
    zs_out_error_option(&err, "-o");
    goto done;
  }

  printf("pixels_differing %llu of %llu\n", (unsigned long long)res.differing,
         (unsigned long long)res.total);
  printf("max_channel_diff %d\n", res.max_channel_diff);
  if (args.ids && print_ids(&a, &b) != 0) {
    zs_error_set(&err, ZS_ERR_NOMEM, "out of memory");
    goto done;
  }
  if (fflush(stdout) != 0 || ferror(stdout)) {
    zs_error_set(&err, ZS_ERR_IO, "cannot write the report: %s",
                 strerror(errno));
    goto done;
  }
  status = res.differing > 0 ? EXIT_DIFFERENT : EXIT_SAME;

done:
  if (err.code != ZS_OK) fail("%s", err.msg);
  zs_image_free(&a);
  zs_image_free(&b);
  zs_image_free(&diff);
  return status;
}
