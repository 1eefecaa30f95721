/* zscan tools — `zscan render`'s options and frame, for the command and
 * for the golden runner, which renders its cases as render would. */
#ifndef ZS_TOOLS_CMD_RENDER_H
#define ZS_TOOLS_CMD_RENDER_H

#include "cull/cull.h"
#include "raster/raster.h"
#include "tools/viewopts.h"
#include "zscan/zscan.h"

enum { ZS_CMD_RENDER_MAX_PARTS = 64 }; /* ranges in --objects */

typedef struct zs_cmd_render_opts {
  const char *input, *out_png, *out_pfm;
  const char *out_normals; /* --normals FILE.pfm */
  const char *out_layer;   /* --layer FILE.zsl */
  int nparts;              /* --objects: the ranges of objects drawn (0: all) */
  int32_t part_lo[ZS_CMD_RENDER_MAX_PARTS], part_hi[ZS_CMD_RENDER_MAX_PARTS];
  int out_given; /* -o was given */
  int svg;       /* -o FILE.svg: the hidden lines as vectors */
  uint32_t background; /* flat shading's background, 0xRRGGBB */
  int verbose;         /* -v: the camera used, as options, on stderr */
  int quiet;           /* -q: no line on stderr */
  const char *camera;  /* --camera NAME|INDEX: a camera of the model file */
  int list_cameras;    /* --list-cameras */
  zs_view_opts view;
  zs_algo algo;
  zs_shade shade;
  zs_filter filter;    /* --filter: every texture's; 0: each material's */
  zs_span_fill spans;  /* --simd: the widest span fill and vertex stage */
  zs_light lights[ZS_MAX_LIGHTS]; /* --light, in the order given */
  int nlights;
  int shadows;         /* --shadows: every directional and spot light casts them */
  int shadow_size;     /* --shadow-size: texels a side; 0: the default */
  int has_shadow_bias; /* --shadow-bias UNITS,SLOPE */
  double shadow_bias[2];
  int samples;         /* --samples: 0 or 1, 2, 4, 8, 16 */
  int supersample;     /* --supersample: shaded at each sample */
  int wireframe;       /* --style solid+wireframe */
  double line_width;   /* --line-width: pixels; 0: 1 */
  double point_size;   /* --point-size: pixels; 0: 1 */
  zs_point_shape point_shape; /* --point-shape */
  int threads, repeat, stats, hidden_line, cull, overlay, allow_empty;
  int skip_missing_textures; /* --skip-missing-textures */
  zs_query_bounds bounds;
  zs_clock_params clock;
  zs_cost_params cost;
} zs_cmd_render_opts;

/* Parses render's argv (argv[0] "render"); in_memory: for an image kept in
 * memory, so -o, --depth and --stats are refused and no path is checked. */
zs_status zs_cmd_render_parse(int argc, char **argv, int in_memory, zs_cmd_render_opts *o,
                              zs_error *err);

/* The frame o asks for, exactly as `zscan render` draws it, into *out
 * (allocated here). */
zs_status zs_cmd_render_image(const zs_cmd_render_opts *o, zs_image *out, zs_error *err);

#endif
