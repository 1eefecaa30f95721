/* zscan tools — `zscan diff`: comparing two images.
 *
 *   zscan diff A.png B.png [-o diff.png] [--side-by-side all.png] [--ids]
 *              [--max-channel-diff N] [--max-diff-pixels N]
 *
 * prints to standard output
 *
 *   pixels_differing N of TOTAL
 *   max_channel_diff M
 *   faces_involved K: ID ID ...        (with --ids only)
 *
 * and exits 0 when the images are the same, 1 when they differ or one
 * cannot be read (one line "zscan diff: reason" on standard error), 2 on a
 * usage error.  Images of
 * different sizes are an error.  The same means: no pixel whose largest
 * channel difference exceeds --max-channel-diff (default 0), or no more
 * such pixels than --max-diff-pixels (default 0); N counts those pixels.
 *
 * M is the largest |a - b| over the R, G and B channels of all pixels.
 *
 * --ids reads the images as `--shade id` renderings, where a pixel is the
 * face id + 1 as a 24-bit number 0xRRGGBB and 0 is the background; it
 * refuses (exit 1) a PNG without the mark zscan writes on those renderings
 * (lib/image.h), as an ordinary picture's colours are not face ids.  K is the
 * number of distinct values seen at the differing pixels, in either image;
 * they are listed in ascending order as face ids (value - 1), "background"
 * (value 0) first, at most 20 of them followed by "..." when there are
 * more.  With no differing pixel the line is "faces_involved 0:".
 *
 * -o writes a heat map (zs_image_compare): the pixels that do not differ a
 * faded grey of A, those that do from yellow (1) to red (255);
 * --side-by-side writes A, B and the heat map in one picture, side by side.
 */
#include "tools/commands.h"
#include "util/compiler.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/image.h"
#include "lib/outfile.h"
#include "tools/cli.h"

#define RGB_MASK 0xFFFFFFu

enum {
  EXIT_SAME = 0,
  EXIT_DIFFERENT = 1,
  EXIT_USAGE = 2,
  MAX_IDS_LISTED = 20,
  ID_VALUES = 1 << 24 /* every 24-bit pixel value */
};

/* ---- The command ---- */

typedef struct diff_args {
  const char *a, *b; /* the images */
  const char *out;   /* -o, or NULL */
  const char *side;  /* --side-by-side, or NULL */
  int ids;           /* --ids */
  int max_channel_diff;
  long long max_diff_pixels;
} diff_args;

static const char usage[] =
    "usage: zscan diff A.png B.png [options]\n"
    "  prints pixels_differing N of TOTAL and max_channel_diff M; exits 0 when the\n"
    "  images are the same (within the tolerances), 1 when they differ or one cannot\n"
    "  be read, 2 on a usage error\n"
    "  -o DIFF.png              a heat map: pixels that do not differ faded grey, those\n"
    "                           that do from yellow (a difference of 1) to red (255)\n"
    "  --side-by-side OUT.png   A, B and the heat map in one picture\n"
    "  --max-channel-diff N     a pixel differs only when a channel differs by more\n"
    "                           than N (0 .. 255; default 0)\n"
    "  --max-diff-pixels N      the images are the same with up to N such pixels\n"
    "                           (default 0)\n"
    "  --ids                    read both as --shade id renders: also list the faces\n"
    "                           involved (faces_involved K: ID ...); a PNG that\n"
    "                           zscan did not write with --shade id is refused\n";

static int fail(const char *fmt, ...) ZS_PRINTF_LIKE(1, 2);

/* Prints "zscan diff: reason" on stderr; returns the error exit status. */
static int fail(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fputs("zscan diff: ", stderr);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  return EXIT_USAGE;
}

/* Returns 0, or EXIT_USAGE after printing why. */
static int parse_args(int argc, char **argv, diff_args *args) {
  *args = (diff_args){NULL, NULL, NULL, NULL, 0, 0, 0};
  zs_error err;
  zs_error_clear(&err);
  for (int i = 1; i < argc; i++) {
    const char *arg = argv[i], *v = NULL;
    if (strcmp(arg, "-o") == 0 || strcmp(arg, "--side-by-side") == 0) {
      if (zs_cli_output_value(argc, argv, &i, &v, &err) ||
          zs_cli_output_format(arg, v, "png", &err))
        return fail("%s", err.msg);
      *(arg[1] == 'o' ? &args->out : &args->side) = v;
    } else if (strcmp(arg, "--max-channel-diff") == 0) {
      if (zs_cli_value(argc, argv, &i, &v, &err) ||
          zs_cli_int(arg, v, 0, 255, &args->max_channel_diff, &err))
        return fail("%s", err.msg);
    } else if (strcmp(arg, "--max-diff-pixels") == 0) {
      double n;
      if (zs_cli_value(argc, argv, &i, &v, &err) || zs_cli_double(arg, v, &n, &err))
        return fail("%s", err.msg);
      if (!(n >= 0 && n <= 1e15 && n == (double)(long long)n))
        return fail("%s: expected a whole number of pixels, got '%s'", arg, v);
      args->max_diff_pixels = (long long)n;
    } else if (strcmp(arg, "--ids") == 0) {
      args->ids = 1;
    } else if (arg[0] == '-' && arg[1] != '\0') {
      return fail("unknown option '%s' (see zscan diff --help)", arg);
    } else if (!args->a) {
      args->a = arg;
    } else if (!args->b) {
      args->b = arg;
    } else {
      return fail("too many files ('%s') (see zscan diff --help)", arg);
    }
  }
  if (!args->b) return fail("two images needed (see zscan diff --help)");
  return 0;
}

/* A, B and the heat map side by side, 8 pixels of white between them. */
static zs_status side_by_side(const zs_image *a, const zs_image *b, const zs_image *heat,
                              zs_image *out, zs_error *err) {
  enum { GAP = 8 };
  const zs_image *parts[3] = {a, b, heat};
  if (zs_image_alloc(out, 3 * a->width + 2 * GAP, a->height, err)) return err->code;
  for (size_t i = 0; i < (size_t)out->width * (size_t)out->height; i++) out->rgb[i] = 0xFFFFFF;
  for (int k = 0; k < 3; k++)
    for (int y = 0; y < a->height; y++)
      memcpy(out->rgb + (size_t)y * (size_t)out->width + (size_t)k * (size_t)(a->width + GAP),
             parts[k]->rgb + (size_t)y * (size_t)a->width, (size_t)a->width * sizeof *out->rgb);
  return ZS_OK;
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
  if (zs_cli_help(argc, argv, usage, NULL)) return EXIT_SAME;
  diff_args args;
  if (parse_args(argc, argv, &args) != 0) return EXIT_USAGE;

  zs_error err;
  zs_error_clear(&err);
  zs_image a = {0, 0, NULL}, b = {0, 0, NULL}, diff = {0, 0, NULL}, all = {0, 0, NULL};
  zs_diff_result res;
  int status = EXIT_DIFFERENT; /* a file that cannot be read is bad input */
  int ids_a, ids_b;
  if (zs_png_read_marked(args.a, &a, &ids_a, &err) != ZS_OK ||
      zs_png_read_marked(args.b, &b, &ids_b, &err) != ZS_OK)
    goto done;
  if (args.ids && !(ids_a && ids_b)) {
    fail("--ids: %s is not a --shade id render written by zscan; its colours are not face ids",
         ids_a ? args.b : args.a);
    goto done;
  }
  if (zs_image_compare(&a, &b, args.max_channel_diff, args.out || args.side ? &diff : NULL, &res,
                       &err) != ZS_OK) {
    /* the sizes: say which files */
    fail("%s and %s: %s", args.a, args.b, err.msg);
    zs_error_clear(&err);
    goto done;
  }
  if (args.out && zs_png_write(args.out, &diff, &err) != ZS_OK) {
    zs_out_error_option(&err, "-o");
    goto done;
  }
  if (args.side && (side_by_side(&a, &b, &diff, &all, &err) ||
                    zs_png_write(args.side, &all, &err))) {
    zs_out_error_option(&err, "--side-by-side");
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
  status = (long long)res.differing > args.max_diff_pixels ? EXIT_DIFFERENT : EXIT_SAME;

done:
  if (err.code != ZS_OK) fail("%s", err.msg);
  zs_image_free(&a);
  zs_image_free(&b);
  zs_image_free(&diff);
  zs_image_free(&all);
  return status;
}
