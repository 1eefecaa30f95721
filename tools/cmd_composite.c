/* zscan tools — `zscan composite`: layers merged by depth.
 *
 *   zscan composite L1.zsl L2.zsl ... -o out.png [--layer out.zsl]
 *
 * Each layer is a frame `zscan render --layer` wrote (zscan/layer.h); at
 * every pixel the composite shows the layer whose fragment is nearest,
 * the lower face id among equals, as the z-buffer would have.  Layers of
 * other sizes, cameras or backgrounds than the first are refused (exit
 * 1); nothing is written then. */
#include "tools/commands.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/image.h"
#include "lib/layer_file.h"
#include "lib/outfile.h"
#include "tools/cli.h"
#include "zscan/layer.h"

enum { MAX_LAYERS = 256 };

static const char usage[] =
    "usage: zscan composite L1.zsl L2.zsl ... -o OUT.png [--layer OUT.zsl]\n"
    "  merges layers that zscan render --layer wrote, each the frame of a part of a\n"
    "  scene from one camera: at each pixel the nearest fragment, the lower face id\n"
    "  among equals, as the z-buffer would have drawn the whole (up to 256 layers)\n"
    "  -o OUT.png         the composite image\n"
    "  --layer OUT.zsl    the composite as a layer too\n"
    "  -q, --quiet        no line on stderr\n";

int zs_cmd_composite(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, NULL)) return 0;
  zs_error err;
  zs_error_clear(&err);
  const char *out_png = NULL, *out_layer = NULL, *in[MAX_LAYERS];
  int n = 0, quiet = 0;
  zs_status st = ZS_OK;
  for (int i = 1; i < argc && !st; i++) {
    const char *a = argv[i];
    if (strcmp(a, "-o") == 0) {
      if (!(st = zs_cli_output_value(argc, argv, &i, &out_png, &err)))
        st = zs_cli_output_format("-o", out_png, "png", &err);
    } else if (strcmp(a, "--layer") == 0) {
      if (!(st = zs_cli_output_value(argc, argv, &i, &out_layer, &err)))
        st = zs_cli_output_format("--layer", out_layer, "zsl", &err);
    } else if (strcmp(a, "-q") == 0 || strcmp(a, "--quiet") == 0) {
      quiet = 1;
    } else if (a[0] == '-' && a[1] != '\0') {
      st = zs_error_set(&err, ZS_ERR_ARG, "unknown option '%s' (see zscan composite --help)", a);
    } else if (n == MAX_LAYERS) {
      st = zs_error_set(&err, ZS_ERR_ARG, "more than %d layers", MAX_LAYERS);
    } else {
      in[n++] = a;
    }
  }
  if (!st && n == 0)
    st = zs_error_set(&err, ZS_ERR_ARG, "no layers (see zscan composite --help)");
  if (!st && !out_png && !out_layer)
    st = zs_error_set(&err, ZS_ERR_ARG, "-o OUT.png or --layer OUT.zsl: nothing to write");
  if (!st && out_png && out_layer && zs_out_is_stdout(out_png) && zs_out_is_stdout(out_layer))
    st = zs_error_set(&err, ZS_ERR_ARG, "standard output (-) takes one stream: -o - or --layer -");
  if (st) return zs_cli_fail("zscan composite", &err, 1);

  zs_layer *layers = calloc((size_t)n, sizeof *layers);
  const zs_layer **ptrs = calloc((size_t)n, sizeof *ptrs);
  zs_layer merged = {0};
  zs_image im = {0, 0, NULL};
  int nread = 0;
  if (!layers || !ptrs) st = zs_error_set(&err, ZS_ERR_NOMEM, "out of memory");
  for (; nread < n && !st; nread++) {
    if ((st = zs_layer_read(in[nread], &layers[nread], &err))) break;
    ptrs[nread] = &layers[nread];
  }
  if (!st && (st = zs_layer_composite(ptrs, n, &merged, &err)) == ZS_ERR_ARG) {
    /* the files named, not the indices: "layer K: ..., layer 0 ..." */
    int k = -1, at = 0;
    if (sscanf(err.msg, "layer %d:%n", &k, &at) == 1 && k > 0 && k < n) {
      char msg[sizeof err.msg];
      const char *rest = err.msg + at, *zero = strstr(rest, "layer 0");
      if (zero)
        snprintf(msg, sizeof msg, "%s:%.*s%s%s", in[k], (int)(zero - rest), rest, in[0],
                 zero + 7);
      else
        snprintf(msg, sizeof msg, "%s:%s", in[k], rest);
      zs_error_clear(&err);
      zs_error_set(&err, ZS_ERR_ARG, "%s", msg);
    }
  }
  /* both files replaced or neither; standard output, which cannot be
   * taken back, last */
  zs_out_set outs = ZS_OUT_SET_EMPTY;
  const int png_last = out_png && zs_out_is_stdout(out_png);
  for (int k = 0; k < 2 && !st; k++) {
    if (k == png_last && out_png) {
      if (!(st = zs_layer_image(&merged, &im, &err)) &&
          (st = zs_png_write_in(&outs, out_png, &im, merged.shade, &err)))
        zs_out_error_option(&err, "-o");
    } else if (k != png_last && out_layer &&
               (st = zs_layer_write_in(&outs, out_layer, &merged, &err))) {
      zs_out_error_option(&err, "--layer");
    }
  }
  if (st) zs_out_set_drop(&outs);
  else st = zs_out_set_land(&outs, &err);
  if (!st && !quiet) {
    uint64_t covered = 0;
    for (size_t i = 0; i < (size_t)merged.width * (size_t)merged.height; i++)
      covered += merged.alpha[i] != 0;
    fprintf(stderr, "zscan composite: %d layers, %dx%d, %llu pixels covered%s%s%s%s\n", n,
            merged.width, merged.height, (unsigned long long)covered, out_png ? ", to " : "",
            out_png ? out_png : "", out_layer ? ", layer to " : "", out_layer ? out_layer : "");
  }
  for (int k = 0; k < nread; k++) zs_layer_free(&layers[k]);
  free(layers);
  free(ptrs);
  zs_layer_free(&merged);
  zs_image_free(&im);
  return st ? zs_cli_fail("zscan composite", &err, 0) : 0;
}
