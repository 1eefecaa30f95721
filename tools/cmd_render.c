/* `zscan render [INPUT] [options]`: one frame of INPUT to a PNG, with its
 * counters.  See `zscan render --help` (usage below) for the options. */
#include "tools/commands.h"
#include "tools/cmd_render.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cull/cull.h"
#include "cull/octree.h"
#include "raster/raster.h"
#include "util/exactmath.h"
#include "scene/load_assimp.h"
#include "scene/camera.h"
#include "scene/model.h"
#include "tools/cli.h"
#include "util/os.h"
#include "tools/clockfile.h"
#include "tools/costset.h"
#include "lib/frame.h"
#include "lib/frame_camera.h"
#include "lib/image.h"
#include "lib/input.h"
#include "lib/layer_file.h"
#include "lib/outfile.h"
#include "lib/samples.h"
#include "lib/svg.h"
#include "tools/viewopts.h"

static const char usage_head[] =
    "usage: zscan render [INPUT] [options]\n"
    "  INPUT               FILE.obj, FILE.json (a scene), another model format\n"
    "                      (through assimp), or builtin:NAME[,k=v]: default, teapots,\n"
    "                      spheres, city, plant, cubes (default: the teapot field)\n"
    "  -o FILE.png         output image (default zscan.png; - for standard output);\n"
    "                      FILE.svg with --style hidden-line: the lines as vectors\n";
static const char usage_tail[] =
    "  --algo zbuffer|scanline|depthsort   hidden-surface mode (default zbuffer)\n"
    "  --shade MODE        auto (default: flat, or phong for a model with normals,\n"
    "                      colours or textures, and for every model where lights\n"
    "                      are given), flat, unlit, gouraud, phong,\n"
    "                      normal (the eye-space normal as a colour), id, depth,\n"
    "                      overdraw\n"
    "  --filter F          every texture sampled nearest, bilinear or trilinear\n"
    "                      (default: as the model's samplers say)\n"
    "  --light L           a light, replacing the scene's and the headlight\n"
    "                      (repeat for more, up to 16): dir:DX,DY,DZ (the way it\n"
    "                      shines), point:X,Y,Z, spot:X,Y,Z:DX,DY,DZ:INNER,OUTER,\n"
    "                      each with :R,G,B (linear, default 1,1,1), or\n"
    "                      ambient:R,G,B\n"
    "  --samples N         anti-alias: N samples a pixel (2, 4, 8 or 16, at D3D's\n"
    "                      and Vulkan's standard positions), each pixel their mean;\n"
    "                      shaded once a pixel, at its centre (multisampling); not\n"
    "                      with --cull, --layer, --depth, --normals or --shade id,\n"
    "                      which keep one sample a pixel\n"
    "  --supersample       with --samples: shade each sample where it lies\n"
    "  --shadows           every directional and spot light casts shadows (a scene\n"
    "                      without lights gets a key light from the upper left)\n"
    "  --shadow-size N     each shadow map's side, 16 to 8192 texels (default 1024)\n"
    "  --shadow-bias U,S   the maps' depth bias: U depth units (2^-32 of the light's\n"
    "                      depth range) plus S times the surface's depth slope per\n"
    "                      texel (default 4096,2)\n"
    "  --style S           solid: faces (default); hidden-line: the visible edges of\n"
    "                      front faces, ink on paper; solid+wireframe: those edges\n"
    "                      in black over the faces; both need --algo zbuffer,\n"
    "                      hidden-line --shade auto or flat\n"
    "  --line-width W      the model's lines (OBJ l, glTF LINES) and the edges of\n"
    "                      hidden-line and solid+wireframe, W pixels wide, rounded\n"
    "                      as GL rounds an aliased width (default 1, at most 64)\n"
    "  --point-size S      its points (OBJ p, a PLY point cloud), S pixels a side\n"
    "                      (default 1, at most 64)\n"
    "  --point-shape SHAPE square (default, GL's aliased point) or disc\n"
    "  --depth FILE.pfm    also write the depth buffer (window depth, 1 = far)\n"
    "  --normals FILE.pfm  also write the eye-space unit normals (x, y, z a pixel;\n"
    "                      0, 0, 0 where no face is), as --shade normal finds them\n"
    "  --layer FILE.zsl    also write the frame as a layer: colour, coverage, depth\n"
    "                      and face ids (zscan composite merges layers); faces\n"
    "                      only: not with the hidden-line or solid+wireframe style,\n"
    "                      --algo depthsort or --shade id or overdraw\n"
    "  --objects LIST      draw only these objects (0-based, as --stats counts them:\n"
    "                      A, A-B, comma-separated), framed as the whole scene is\n"
    "  --threads N         render threads, 1 to 64 (default 1; depthsort: its walk only)\n"
    "  --simd LEVEL        cap the span fill and the vertex stage at scalar, sse2, avx2\n"
    "                      or avx512 (default best: the widest the CPU has); every\n"
    "                      level draws the same bytes, which this lets a user check\n"
    "                      (on aarch64 every level but scalar is NEON)\n"
    "  --repeat K          render K times; ms_per_frame is the median (default 1)\n"
    "  --stats             print the frame's counters as one JSON line, with the\n"
    "                      camera used (\"camera\": eye, target, up, fovy or ortho,\n"
    "                      near, far, the bounds framed), in full precision\n"
    "  -q, --quiet         no line on stderr (else, without --stats, one: what was\n"
    "                      written, the size, the faces, the time)\n"
    "  -v, --verbose       print the camera used as options that draw the same\n"
    "                      frame again, byte for byte\n"
    "  --camera NAME|N     a camera stored in the model file (glTF, Collada, FBX,\n"
    "                      3DS, ...: its place, aim, lens and planes; its\n"
    "                      horizontal angle spans the image's width); not with\n"
    "                      the options that place a view (--eye ... --fit)\n"
    "  --list-cameras      list the model file's cameras, render nothing\n"
    "  --background RRGGBB flat shading's background (default 1E2228)\n"
    "  --allow-empty       render a model without faces (the background alone)\n"
    "                      instead of refusing it\n"
    "  --skip-missing-textures\n"
    "                      draw a material whose texture cannot be opened or read\n"
    "                      without it, with a warning naming it, instead of\n"
    "                      refusing the input (a corrupt image stays an error)\n"
    "  --cull METHOD       draw through a culling method (vfc, hsw, chc, chc-prob, ...;\n"
    "                      default: draw everything; needs --algo zbuffer and\n"
    "                      --style solid)\n"
    "  --bounds parts|box  with --cull: queries ask about an object's parts'\n"
    "                      boxes (default) or its box\n"
    "  --overlay culling   with --cull: the octree's boxes, coloured by decision:\n"
    "                      grey outside, red queried hidden, green queried visible,\n"
    "                      blue entered without a query\n"
    "  --clock FILE.json   the device clock's constants (zscan calibrate writes one;\n"
    "                      default: the modelled defaults)\n"
    "  --clock-set K=V     set one clock constant, in ns (e.g. query_latency_ns=0)\n"
    "  --cost-set K=V      with --cull: set one parameter of the cost model (w1, w2,\n"
    "                      ttri_ns, tcall_ns, t_ns, tq_ns, rho, learn, measure)\n";



/* The options that name the frame's files, in the order of their paths
 * (out_png, out_pfm, out_normals, out_layer). */
static const char *const output_options[] = {"-o", "--depth", "--normals", "--layer"};

/* What the options ask together, and of the outputs: their formats,
 * their folders, the one stream standard output carries. */
static zs_status check_options(zs_cmd_render_opts *o, int in_memory, zs_error *err) {
  if (o->nlights > 0 && !(o->shade == ZS_SHADE_AUTO || o->shade == ZS_SHADE_GOURAUD ||
                          o->shade == ZS_SHADE_PHONG))
    return zs_error_set(err, ZS_ERR_ARG, "--light: --shade %s draws no lights (auto, gouraud "
                        "and phong do)", zs_shade_name(o->shade));
  if (o->hidden_line && !zs_frame_hidden_line_fits(o->algo, o->shade))
    return zs_error_set(err, ZS_ERR_ARG, "--style hidden-line needs --algo zbuffer and --shade auto or flat");
  if (o->shadows && !(o->shade == ZS_SHADE_AUTO || o->shade == ZS_SHADE_PHONG))
    return zs_error_set(err, ZS_ERR_ARG, "--shadows needs --shade auto or phong (lit at each "
                        "pixel), not %s", zs_shade_name(o->shade));
  if (o->view.cam.has_near && !o->view.cam.ortho && !(o->view.cam.znear > 0.0))
    return zs_error_set(err, ZS_ERR_ARG, "--near: %g: a perspective camera's near plane must be "
                        "above 0", o->view.cam.znear);
  if (o->camera) { /* the file's camera places the view: an option would be half-applied */
    const zs_camera *c = &o->view.cam;
    const char *placed = c->has_eye ? "--eye" : c->has_target ? "--target" : c->has_up ? "--up"
                         : o->view.fovy_given ? "--fovy" : c->ortho ? "--ortho or --grid"
                         : c->has_near ? "--near" : c->has_far ? "--far" : o->view.view ? "--view"
                         : o->view.fit > 0 ? "--fit" : NULL;
    if (placed)
      return zs_error_set(err, ZS_ERR_ARG, "--camera and %s: the file's camera places the view",
                          placed);
  }
  if (o->supersample && o->samples < 2)
    return zs_error_set(err, ZS_ERR_ARG, "--supersample needs --samples 2, 4, 8 or 16");
  if (o->samples > 1) {
    const char *alone = o->shade == ZS_SHADE_ID ? "--shade id (ids do not average)"
                        : o->cull >= 0          ? "--cull"
                        : o->out_layer          ? "--layer"
                        : o->out_pfm            ? "--depth"
                        : o->out_normals        ? "--normals"
                                                : NULL;
    if (alone)
      return zs_error_set(err, ZS_ERR_ARG, "--samples: not with %s: one sample a pixel", alone);
  }
  if (o->wireframe && !zs_frame_wireframe_fits(o->algo, o->shade))
    return zs_error_set(err, ZS_ERR_ARG, "--style solid+wireframe needs --algo zbuffer and a "
                        "shading of the surfaces (not id, depth or overdraw)");
  if (o->wireframe && (o->cull >= 0 || o->out_layer))
    return zs_error_set(err, ZS_ERR_ARG, "--style solid+wireframe: not with %s",
                        o->cull >= 0 ? "--cull" : "--layer");
  if (o->shadows && o->hidden_line)
    return zs_error_set(err, ZS_ERR_ARG, "--shadows: the hidden-line style draws no light");
  if (o->overlay && o->cull < 0)
    return zs_error_set(err, ZS_ERR_ARG, "--overlay culling needs --cull METHOD");
  if (o->cull >= 0 && (o->algo != ZS_ALGO_ZBUFFER || o->hidden_line))
    return zs_error_set(err, ZS_ERR_ARG, "--cull needs --algo zbuffer and --style solid");
  if (in_memory) { /* the image stays in memory: no file, no counters printed */
    const char *extra = o->out_pfm ? "--depth" : o->out_normals ? "--normals"
                        : o->out_layer ? "--layer" : o->stats ? "--stats" : o->out_given ? "-o" : NULL;
    if (extra) return zs_error_set(err, ZS_ERR_ARG, "%s: not here (the image is kept in memory)", extra);
    return ZS_OK;
  }
  o->svg = zs_cli_extension_is(o->out_png, "svg");
  if (o->svg && !o->hidden_line)
    return zs_error_set(err, ZS_ERR_ARG, "-o: %s: an SVG holds hidden lines (--style hidden-line)",
                        o->out_png);
  if (o->svg && o->samples > 1)
    return zs_error_set(err, ZS_ERR_ARG, "--samples: an SVG's lines are vectors, not samples");
  if (!o->svg && zs_cli_output_format("-o", o->out_png, "png", err)) return err->code;
  if (o->out_pfm && zs_cli_output_format("--depth", o->out_pfm, "pfm", err)) return err->code;
  if (zs_cli_output_path("-o", o->out_png, err)) return err->code;
  if (o->out_pfm && zs_cli_output_path("--depth", o->out_pfm, err)) return err->code;
  if (o->out_normals && (zs_cli_output_format("--normals", o->out_normals, "pfm", err) ||
                         zs_cli_output_path("--normals", o->out_normals, err)))
    return err->code;
  if (o->out_layer) {
    if (zs_cli_output_format("--layer", o->out_layer, "zsl", err) ||
        zs_cli_output_path("--layer", o->out_layer, err))
      return err->code;
    /* what a layer holds: the faces' nearest fragments, composited by depth */
    if (o->hidden_line || o->overlay || o->algo == ZS_ALGO_DEPTHSORT ||
        o->shade == ZS_SHADE_OVERDRAW || o->shade == ZS_SHADE_ID)
      return zs_error_set(err, ZS_ERR_ARG, "--layer: %s", o->hidden_line
                          ? "a layer holds faces, not hidden lines (--style solid)"
                          : o->overlay ? "a layer holds faces, not the culling's boxes"
                          : o->algo == ZS_ALGO_DEPTHSORT
                              ? "depthsort's depths are ranks, which do not composite"
                          : o->shade == ZS_SHADE_ID
                              ? "id shading's PNG is marked as ids, which a composite does not keep"
                              : "overdraw's counts do not composite");
  }
  /* standard output carries one stream */
  int to_stdout = zs_out_is_stdout(o->out_png) + (o->out_pfm && zs_out_is_stdout(o->out_pfm)) +
                  (o->out_normals && zs_out_is_stdout(o->out_normals)) +
                  (o->out_layer && zs_out_is_stdout(o->out_layer));
  if (to_stdout > 1 || (to_stdout && o->stats))
    return zs_error_set(err, ZS_ERR_ARG,
                        "standard output (-) takes one stream: only one of -o -, --depth -, "
                        "--normals -, --layer - and --stats");
  /* one file, one output: the later would replace the earlier */
  const char *const *names = output_options;
  const char *const paths[] = {o->out_png, o->out_pfm, o->out_normals, o->out_layer};
  for (int i = 0; i < 4; i++)
    for (int j = i + 1; j < 4; j++)
      if (paths[i] && paths[j] && !zs_out_is_stdout(paths[i]) && strcmp(paths[i], paths[j]) == 0)
        return zs_error_set(err, ZS_ERR_ARG, "%s and %s: both write %s: give each its own file",
                            names[i], names[j], paths[i]);
  return ZS_OK;
}

/* --objects LIST: ranges A or A-B of object numbers, comma-separated. */
static zs_status parse_objects(const char *v, zs_cmd_render_opts *o, zs_error *err) {
  o->nparts = 0;
  for (const char *p = v;;) {
    char *end;
    long lo = -1, hi = -1;
    if (*p >= '0' && *p <= '9') lo = strtol(p, &end, 10), p = end;
    hi = lo;
    if (lo >= 0 && *p == '-') {
      hi = -1;
      if (p[1] >= '0' && p[1] <= '9') hi = strtol(p + 1, &end, 10), p = end;
    }
    if (lo < 0 || hi < lo || lo > INT32_MAX || hi > INT32_MAX || (*p != ',' && *p != '\0'))
      return zs_error_set(err, ZS_ERR_ARG,
                          "--objects: expected object numbers A or A-B (A <= B), "
                          "comma-separated, got '%s'", v);
    if (o->nparts == ZS_CMD_RENDER_MAX_PARTS)
      return zs_error_set(err, ZS_ERR_ARG, "--objects: more than %d ranges",
                          ZS_CMD_RENDER_MAX_PARTS);
    o->part_lo[o->nparts] = (int32_t)lo;
    o->part_hi[o->nparts++] = (int32_t)hi;
    if (*p == '\0') return ZS_OK;
    p++;
  }
}

/* Keeps only the objects --objects names (their face ids unchanged). */
static zs_status keep_objects(const zs_cmd_render_opts *o, zs_scene *s, zs_error *err) {
  for (int k = 0; k < o->nparts; k++)
    if (o->part_hi[k] >= s->ninst)
      return s->ninst == 0
                 ? zs_error_set(err, ZS_ERR_ARG, "--objects: object %d: the scene has none",
                                (int)o->part_hi[k])
                 : zs_error_set(err, ZS_ERR_ARG,
                                "--objects: object %d: the scene has %d objects (0 to %d)",
                                (int)o->part_hi[k], (int)s->ninst, (int)s->ninst - 1);
  int32_t n = 0;
  for (int32_t i = 0; i < s->ninst; i++) {
    int kept = 0;
    for (int k = 0; k < o->nparts && !kept; k++) kept = i >= o->part_lo[k] && i <= o->part_hi[k];
    if (kept) s->inst[n++] = s->inst[i];
    else free(s->inst[i].name);
  }
  s->ninst = n;
  return ZS_OK;
}

zs_status zs_cmd_render_parse(int argc, char **argv, int in_memory, zs_cmd_render_opts *o,
                              zs_error *err) {
  memset(o, 0, sizeof *o);
  o->out_png = "zscan.png";
  zs_view_opts_default(&o->view, 1024, 768);
  o->threads = 1;
  o->repeat = 1;
  o->cull = -1;
  zs_clock_params_default(&o->clock);
  zs_cost_params_default(&o->cost);
  o->background = ZS_BACKGROUND_RGB;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = NULL;
#define VALUE() \
  if (zs_cli_value(argc, argv, &i, &v, err)) return err->code
    int taken = zs_view_opts_parse(&o->view, argc, argv, &i, err);
    if (!taken) taken = zs_cull_option(argc, argv, &i, &o->clock, &o->cost, &o->bounds, err);
    if (taken < 0) return err->code;
    if (taken) continue;
    if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
      VALUE();
      o->out_png = v;
      o->out_given = 1;
    } else if (strcmp(a, "--algo") == 0) {
      VALUE();
      int al = zs_algo_parse(v);
      if (al < 0)
        return zs_error_set(err, ZS_ERR_ARG,
                            "--algo: expected zbuffer, scanline or depthsort, got '%s'", v);
      o->algo = (zs_algo)al;
    } else if (strcmp(a, "--shade") == 0) {
      VALUE();
      int sh = zs_shade_parse(v);
      if (sh < 0)
        return zs_error_set(err, ZS_ERR_ARG,
                            "--shade: expected auto, flat, unlit, gouraud, phong, normal, id, "
                            "depth or overdraw, got '%s'", v);
      o->shade = (zs_shade)sh;
    } else if (strcmp(a, "--light") == 0) {
      VALUE();
      if (o->nlights == ZS_MAX_LIGHTS)
        return zs_error_set(err, ZS_ERR_ARG, "--light: at most %d lights", ZS_MAX_LIGHTS);
      if (zs_cli_light("--light", v, &o->lights[o->nlights], err)) return err->code;
      o->nlights++;
    } else if (strcmp(a, "--samples") == 0) {
      VALUE();
      if (zs_cli_int(a, v, 1, 16, &o->samples, err)) return err->code;
      if (!zs_samples_valid(o->samples))
        return zs_error_set(err, ZS_ERR_ARG, "--samples: expected 1, 2, 4, 8 or 16, got %s", v);
    } else if (strcmp(a, "--line-width") == 0 || strcmp(a, "--point-size") == 0) {
      VALUE();
      double *into = a[2] == 'l' ? &o->line_width : &o->point_size;
      const int most = a[2] == 'l' ? ZS_MAX_LINE_WIDTH : ZS_MAX_POINT_SIZE;
      if (zs_cli_double(a, v, into, err)) return err->code;
      if (!(*into > 0.0 && *into <= most))
        return zs_error_set(err, ZS_ERR_ARG, "%s: expected a number above 0 and at most %d "
                            "(pixels), got %s", a, most, v);
    } else if (strcmp(a, "--point-shape") == 0) {
      VALUE();
      if (strcmp(v, "square") != 0 && strcmp(v, "disc") != 0)
        return zs_error_set(err, ZS_ERR_ARG, "--point-shape: expected square or disc, got '%s'", v);
      o->point_shape = strcmp(v, "disc") == 0 ? ZS_POINT_DISC : ZS_POINT_SQUARE;
    } else if (strcmp(a, "--supersample") == 0) {
      o->supersample = 1;
    } else if (strcmp(a, "--shadows") == 0) {
      o->shadows = 1;
    } else if (strcmp(a, "--shadow-size") == 0) {
      if (zs_cli_int_value(argc, argv, &i, ZS_SHADOW_MIN_SIZE, ZS_SHADOW_MAX_SIZE, &o->shadow_size,
                           err))
        return err->code;
    } else if (strcmp(a, "--shadow-bias") == 0) {
      VALUE();
      if (zs_cli_numbers(a, v, 2, "UNITS,SLOPE (two finite numbers)", o->shadow_bias, err))
        return err->code;
      if (!(o->shadow_bias[0] >= 0 && o->shadow_bias[0] <= 4294967296.0 &&
            o->shadow_bias[1] >= 0 && o->shadow_bias[1] <= 1e6))
        return zs_error_set(err, ZS_ERR_ARG, "--shadow-bias: %s: UNITS 0 to 4294967296 (2^32), "
                            "SLOPE 0 to 1000000", v);
      o->has_shadow_bias = 1;
    } else if (strcmp(a, "--simd") == 0) {
      VALUE();
      static const char *const levels[] = {"best", "scalar", "sse2", "avx2", "avx512"};
      int k = 0;
      while (k < 5 && strcmp(v, levels[k]) != 0) k++;
      if (k == 5)
        return zs_error_set(err, ZS_ERR_ARG,
                            "--simd: expected scalar, sse2, avx2, avx512 or best, got '%s'", v);
      o->spans = (zs_span_fill)k; /* the names in zs_span_fill's order */
    } else if (strcmp(a, "--filter") == 0) {
      VALUE();
      int f = zs_filter_parse(v);
      if (f <= 0)
        return zs_error_set(err, ZS_ERR_ARG,
                            "--filter: expected nearest, bilinear or trilinear, got '%s'", v);
      o->filter = (zs_filter)f;
    } else if (strcmp(a, "--cull") == 0) {
      VALUE();
      if ((o->cull = zs_cull_method_parse(v)) < 0)
        return zs_error_set(err, ZS_ERR_ARG, "--cull: unknown method '%s' (" ZS_CULL_METHOD_LIST ")", v);
    } else if (strcmp(a, "--overlay") == 0) {
      VALUE();
      if (strcmp(v, "culling") != 0)
        return zs_error_set(err, ZS_ERR_ARG, "--overlay: expected culling, got '%s'", v);
      o->overlay = 1;
    } else if (strcmp(a, "--style") == 0) {
      VALUE();
      o->hidden_line = strcmp(v, "hidden-line") == 0;
      o->wireframe = strcmp(v, "solid+wireframe") == 0;
      if (!o->hidden_line && !o->wireframe && strcmp(v, "solid") != 0)
        return zs_error_set(err, ZS_ERR_ARG,
                            "--style: expected solid, hidden-line or solid+wireframe, got '%s'", v);
    } else if (strcmp(a, "--depth") == 0) {
      VALUE();
      o->out_pfm = v;
    } else if (strcmp(a, "--normals") == 0) {
      VALUE();
      o->out_normals = v;
    } else if (strcmp(a, "--layer") == 0) {
      VALUE();
      o->out_layer = v;
    } else if (strcmp(a, "--objects") == 0) {
      VALUE();
      if (parse_objects(v, o, err)) return err->code;
    } else if (strcmp(a, "--threads") == 0) {
      VALUE();
      if (zs_cli_int(a, v, 1, 64, &o->threads, err)) return err->code;
    } else if (strcmp(a, "--repeat") == 0) {
      VALUE();
      if (zs_cli_int(a, v, 1, 100000, &o->repeat, err)) return err->code;
    } else if (strcmp(a, "--stats") == 0) {
      o->stats = 1;
    } else if (strcmp(a, "--allow-empty") == 0) {
      o->allow_empty = 1;
    } else if (strcmp(a, "--skip-missing-textures") == 0) {
      o->skip_missing_textures = 1;
    } else if (strcmp(a, "-v") == 0 || strcmp(a, "--verbose") == 0) {
      o->verbose = 1;
    } else if (strcmp(a, "-q") == 0 || strcmp(a, "--quiet") == 0) {
      o->quiet = 1;
    } else if (strcmp(a, "--camera") == 0) {
      VALUE();
      o->camera = v;
    } else if (strcmp(a, "--list-cameras") == 0) {
      o->list_cameras = 1;
    } else if (strcmp(a, "--background") == 0) {
      VALUE();
      char *end;
      unsigned long rgb = strtoul(v, &end, 16);
      if (strlen(v) != 6 || *end || v[0] == '-' || v[0] == '+')
        return zs_error_set(err, ZS_ERR_ARG, "--background: expected RRGGBB (hex), got '%s'", v);
      o->background = (uint32_t)rgb;
    } else if (zs_cli_operand(a, "zscan render", "INPUT", &o->input, err)) {
      return err->code;
    }
#undef VALUE
  }
  return check_options(o, in_memory, err);
}

/* The culling method's work in the frame (render --cull): what it skipped
 * shows as frustum tests below nodes found inside (none), queries the cost
 * model judged not worth asking (cost_evals less the queries that asked
 * about boxes: queries - draws_measured), objects drawn. */
typedef struct cull_report {
  const char *method;
  const zs_cull_stats *st;
  int32_t octree_nodes;
  int flat;                /* the octree is the root alone (a handful of objects) */
} cull_report;

/* The camera the frame was drawn with, as options that draw it again,
 * byte for byte (%.17g: every double back as it was). */
static void print_camera_options(FILE *f, const zs_camera *c) {
  fprintf(f, "--eye %.17g,%.17g,%.17g --target %.17g,%.17g,%.17g --up %.17g,%.17g,%.17g ",
          c->eye[0], c->eye[1], c->eye[2], c->target[0], c->target[1], c->target[2], c->up[0],
          c->up[1], c->up[2]);
  if (c->ortho)
    fprintf(f, "--ortho %.17g,%.17g,%.17g,%.17g ", c->extent[0], c->extent[1], c->extent[2],
            c->extent[3]);
  else
    fprintf(f, "--fovy %.17g ", c->fovy);
  fprintf(f, "--near %.17g --far %.17g", c->znear, c->zfar);
}

/* The same as a JSON object, with the scene's bounds the framing came from. */
static void print_camera_json(const zs_camera *c, const zs_scene *sc) {
  printf("\"camera\":{\"eye\":[%.17g,%.17g,%.17g],\"target\":[%.17g,%.17g,%.17g],"
         "\"up\":[%.17g,%.17g,%.17g],",
         c->eye[0], c->eye[1], c->eye[2], c->target[0], c->target[1], c->target[2], c->up[0],
         c->up[1], c->up[2]);
  if (c->ortho)
    printf("\"ortho\":[%.17g,%.17g,%.17g,%.17g],", c->extent[0], c->extent[1], c->extent[2],
           c->extent[3]);
  else
    printf("\"fovy\":%.17g,", c->fovy);
  printf("\"near\":%.17g,\"far\":%.17g,\"bounds\":{\"lo\":[%.17g,%.17g,%.17g],"
         "\"hi\":[%.17g,%.17g,%.17g]}},",
         c->znear, c->zfar, sc->lo[0], sc->lo[1], sc->lo[2], sc->hi[0], sc->hi[1], sc->hi[2]);
}

static void print_stats(const zs_cmd_render_opts *o, const zs_scene *sc, const zs_raster_stats *s,
                        const zs_device *dev, uint64_t hash, double ms, double load_ms,
                        int64_t diff_pixels, const cull_report *cr, const zs_camera *used) {
  printf("{\"input\":\"%s\",\"width\":%d,\"height\":%d,\"algo\":\"%s\",",
         o->input ? o->input : "builtin:default", o->view.width, o->view.height,
         zs_algo_name(o->algo));
  print_camera_json(used, sc);
  long long vertices = 0;
  for (int32_t i = 0; i < sc->ninst; i++) vertices += sc->meshes[sc->inst[i].mesh].mesh.nverts;
  printf("\"objects\":%d,\"faces\":%llu,\"triangles\":%llu,\"vertices\":%lld,\"draws\":%llu,",
         (int)sc->ninst, (unsigned long long)zs_scene_faces(sc),
         (unsigned long long)zs_scene_triangles(sc), vertices,
         (unsigned long long)s->draws);
  printf("\"polygons_in\":%llu,\"polygons_outside\":%llu,\"polygons_clipped\":%llu,"
         "\"polygons_culled_back\":%llu,\"polygons_degenerate\":%llu,"
         "\"polygons_offscreen\":%llu,\"polygons_rasterized\":%llu,",
         (unsigned long long)s->polygons_in, (unsigned long long)s->polygons_outside,
         (unsigned long long)s->polygons_clipped, (unsigned long long)s->polygons_culled_back,
         (unsigned long long)s->polygons_degenerate, (unsigned long long)s->polygons_offscreen,
         (unsigned long long)s->polygons_rasterized);
  printf("\"spans\":%llu,\"pixels_tested\":%llu,\"pixels_written\":%llu,"
         "\"image_hash\":\"%016llx\",",
         (unsigned long long)s->spans, (unsigned long long)s->pixels_tested,
         (unsigned long long)s->pixels_written, (unsigned long long)hash);
  if (o->algo == ZS_ALGO_DEPTHSORT) {
    const zs_depthsort_stats *ds = zs_device_depthsort_stats(dev);
    printf("\"depthsort_motion\":\"%s\",\"depthsort_faces\":%llu,\"depthsort_reused\":%llu,"
           "\"depthsort_inserted\":%llu,\"depthsort_comparisons\":%llu,\"diff_pixels\":%lld,",
           zs_motion_class_name(ds->motion), (unsigned long long)ds->faces,
           (unsigned long long)ds->reused, (unsigned long long)ds->inserted,
           (unsigned long long)ds->comparisons, (long long)diff_pixels);
  }
  if (cr)
    printf("\"cull\":\"%s\",\"octree\":\"%s\",\"octree_nodes\":%d,\"nodes_visited\":%llu,\"frustum_tests\":%llu,"
           "\"cost_evals\":%llu,\"queries_hidden\":%llu,\"objects_drawn\":%llu,\"faces_drawn\":%llu,"
           "\"draws_measured\":%llu,",
           cr->method, cr->flat ? "flat" : "loose", (int)cr->octree_nodes, (unsigned long long)cr->st->nodes_visited,
           (unsigned long long)cr->st->frustum_tests, (unsigned long long)cr->st->cost_evals,
           (unsigned long long)cr->st->queries_hidden, (unsigned long long)cr->st->objects_drawn,
           (unsigned long long)cr->st->faces_drawn, (unsigned long long)cr->st->draws_measured);
  const zs_clock_stats *k = zs_device_clock(dev);
  /* modelled times from the integer picoseconds, by integer formatting */
  char t[9][32];
  printf("\"queries\":%llu,\"query_waits\":%llu,\"stalls\":%llu,\"stall_ms\":%s,"
         "\"sync_ms\":%s,\"gpu_ms\":%s,\"cpu_ms\":%s,\"modelled_ms\":%s,",
         (unsigned long long)k->queries, (unsigned long long)k->query_waits,
         (unsigned long long)k->stalls, zs_cli_ms_of_ps(k->stall_ps, t[0]),
         zs_cli_ms_of_ps(k->sync_ps, t[1]), zs_cli_ms_of_ps(k->gpu_ps, t[2]),
         zs_cli_ms_of_ps(k->cpu_ps, t[3]), zs_cli_ms_of_ps(zs_device_frame_ps(dev), t[4]));
  const zs_gpu_split gs = zs_clock_gpu_split(dev);
  printf("\"gpu_draw_ms\":%s,\"gpu_query_ms\":%s,\"gpu_switch_ms\":%s,\"gpu_idle_ms\":%s,",
         zs_cli_ms_of_ps(gs.draw_ps, t[5]), zs_cli_ms_of_ps(gs.query_ps, t[6]),
         zs_cli_ms_of_ps(gs.switch_ps, t[7]), zs_cli_ms_of_ps(gs.idle_ps, t[8]));
  zs_device_memory mem = zs_device_memory_of(dev);
  printf("\"buffer_bytes\":%zu,\"table_bytes\":%zu,\"vertex_bytes\":%zu,", mem.pixel_buffers,
         mem.tables, mem.vertices);
  /* wall-clock times last, in one object: the rest of the line is the same
   * on every run */
  printf("\"threads\":%d,\"repeat\":%d,", o->threads, o->repeat);
  printf("\"timing\":{\"ms_per_frame\":%.3f,\"ms_load\":%.3f", ms, load_ms);
  if (o->algo == ZS_ALGO_DEPTHSORT) printf(",\"sort_ms\":%.3f", zs_device_depthsort_ms(dev));
  printf("}}\n");
}

/* The octree's node boxes (tight), coloured by the culler's decision. */
static zs_status draw_overlay(zs_device *dev, const zs_culler *c, const zs_octree *t,
                             zs_error *err) {
  static const uint32_t colour[] = {0, 0x909090, 0xE03030, 0x30C040, 0x3070F0};
  int32_t n;
  const uint8_t *d = zs_culler_decisions(c, &n);
  for (int32_t i = 0; d && i < n; i++)
    if (d[i] != ZS_NODE_NOT_REACHED && t->node[i].level >= 0 && !t->node[i].empty &&
        zs_device_draw_box_lines(dev, t->node[i].tlo, t->node[i].thi, colour[d[i]], err))
      return err->code;
  return ZS_OK;
}

/* --camera and --list-cameras: the cameras stored in the model file.  The
 * chosen one replaces the view's eye, target, up, lens and planes; its
 * horizontal angle spans the image's width (aspect: width / height). */
static zs_status file_camera(const zs_cmd_render_opts *o, double aspect, zs_view_opts *v,
                             zs_error *err) {
  if (!o->input || strncmp(o->input, "builtin:", 8) == 0)
    return zs_error_set(err, ZS_ERR_ARG, "--camera: a generated scene stores no cameras");
  zs_file_camera *cams;
  int n;
  if (zs_assimp_cameras(o->input, &cams, &n, err)) return err->code;
  if (o->list_cameras) {
    for (int i = 0; i < n; i++) {
      const zs_file_camera *c = &cams[i];
      printf("%d %s: eye %.9g,%.9g,%.9g target %.9g,%.9g,%.9g up %.9g,%.9g,%.9g ", i, c->name,
             c->eye[0], c->eye[1], c->eye[2], c->target[0], c->target[1], c->target[2], c->up[0],
             c->up[1], c->up[2]);
      if (c->ortho_half_width > 0) printf("ortho half width %.9g", c->ortho_half_width);
      else printf("horizontal angle %.9g degrees", c->hfov_deg);
      printf(" near %.9g far %.9g aspect %.9g\n", c->znear, c->zfar, c->aspect);
    }
    if (n == 0) printf("%s: no cameras\n", o->input);
    free(cams);
    return ZS_OK;
  }
  int pick = -1;
  for (int i = 0; i < n && pick < 0; i++)
    if (strcmp(cams[i].name, o->camera) == 0) pick = i;
  if (pick < 0) {
    char *end;
    long k = strtol(o->camera, &end, 10);
    if (*o->camera && !*end && k >= 0 && k < n) pick = (int)k;
  }
  if (pick < 0) {
    free(cams);
    return zs_error_set(err, ZS_ERR_ARG, "--camera %s: %s has %d camera%s%s", o->camera, o->input,
                        n, n == 1 ? "" : "s", n ? " (see --list-cameras)" : "");
  }
  const zs_file_camera *c = &cams[pick];
  zs_camera *u = &v->cam;
  memcpy(u->eye, c->eye, sizeof u->eye);
  memcpy(u->target, c->target, sizeof u->target);
  memcpy(u->up, c->up, sizeof u->up);
  u->has_eye = u->has_target = u->has_up = 1;
  if (c->ortho_half_width > 0) {
    const double w = c->ortho_half_width, h = w / aspect;
    const double extent[4] = {-w, w, -h, h};
    memcpy(u->extent, extent, sizeof extent);
    u->ortho = 1;
  } else if (c->hfov_deg > 0 && c->hfov_deg < 180) {
    /* the vertical angle that gives this horizontal one at this aspect */
    u->fovy = 2.0 * zs_atan_deg(zs_tan_deg(0.5 * c->hfov_deg) / aspect);
    v->fovy_given = 1;
  }
  if (c->znear > 0 && c->zfar > c->znear) {
    u->znear = c->znear;
    u->zfar = c->zfar;
    u->has_near = u->has_far = 1;
  }
  free(cams);
  return ZS_OK;
}

/* The last frame's hidden lines as vectors (lib/svg.h). */
static zs_status write_svg(const zs_cmd_render_opts *o, const zs_device *dev, zs_out_set *set,
                           zs_error *err) {
  int32_t n;
  const zs_line_run *runs = zs_device_line_runs(dev, &n);
  if (n < 0) return zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory for the lines", o->out_png);
  const int line_width = zs_gl_rounded_size(o->line_width > 0.0 ? o->line_width : 1.0,
                                            ZS_MAX_LINE_WIDTH);
  return zs_svg_write_lines(set, o->out_png, o->view.width, o->view.height, runs, n, line_width,
                            ZS_HIDDEN_LINE_PAPER, ZS_HIDDEN_LINE_INK, err);
}

/* The painter's error: pixels whose face differs from the z-buffer's. */
static zs_status painter_error(const zs_cmd_render_opts *o, const zs_scene *model,
                               int64_t *diff_pixels, zs_error *err) {
  zs_frame_opts ref = {.width = o->view.width, .height = o->view.height, .algo = ZS_ALGO_ZBUFFER,
                       .shade = ZS_SHADE_ID, .cull_back = o->view.cull_back, .threads = 1};
  zs_frame_opts mine = ref;
  mine.algo = ZS_ALGO_DEPTHSORT;
  zs_image a = {0, 0, NULL}, b = {0, 0, NULL};
  zs_status st;
  if ((st = zs_frame_render(model, &o->view.cam, &ref, &a, NULL, NULL, err)) == ZS_OK &&
      (st = zs_frame_render(model, &o->view.cam, &mine, &b, NULL, NULL, err)) == ZS_OK) {
    *diff_pixels = 0;
    for (size_t i = 0; i < (size_t)a.width * (size_t)a.height; i++) *diff_pixels += a.rgb[i] != b.rgb[i];
  }
  zs_image_free(&a);
  zs_image_free(&b);
  return st;
}

/* Renders the frame o asks for; keep == NULL: as the command does (the
 * PNG, the depth map, the counters); else the image goes into *keep. */
static zs_status run(const zs_cmd_render_opts *o, zs_image *keep, zs_error *err) {
  /* a file of cameras alone (no meshes) is listed too */
  if (o->list_cameras) return file_camera(o, 1.0, NULL, err);
  zs_scene model;
  double t0 = zs_os_monotonic_ms();
  int flags = (o->allow_empty ? ZS_INPUT_ALLOW_EMPTY : 0) |
              (o->skip_missing_textures ? ZS_INPUT_SKIP_MISSING_TEXTURES : 0);
  if (zs_input_load(o->input, flags, &model, err)) return err->code;
  if (o->algo == ZS_ALGO_DEPTHSORT && zs_scene_has_prims(&model)) {
    zs_scene_free(&model);
    return zs_error_set(err, ZS_ERR_ARG, "%s: lines and points need --algo zbuffer or scanline",
                        o->input ? o->input : "builtin:default");
  }
  double load_ms = zs_os_monotonic_ms() - t0;
  /* what is drawn otherwise than the input asks, a line each */
  if (!keep && !o->quiet)
    for (const char *n = zs_scene_notes(&model); *n;) {
      const char *nl = strchr(n, '\n');
      fprintf(stderr, "zscan render: warning: %.*s\n", (int)(nl - n), n);
      n = nl + 1;
    }
  /* the scene's own camera and size, where the options say nothing */
  zs_cmd_render_opts eff = *o;
  zs_view_opts user = o->view;
  zs_view_opts_for_scene(&user, &model, &eff.view.cam, &eff.view.width, &eff.view.height);
  if (o->camera) { /* a camera of the file, for this size */
    if (file_camera(o, (double)eff.view.width / eff.view.height, &user, err)) {
      zs_scene_free(&model);
      return err->code;
    }
    zs_view_opts_for_scene(&user, &model, &eff.view.cam, &eff.view.width, &eff.view.height);
  }
  o = &eff;

  zs_status st = ZS_OK;
  zs_device *dev = NULL;
  zs_culler *culler = NULL;
  zs_cull_stats cs;
  memset(&cs, 0, sizeof cs);
  zs_octree tree;
  int have_tree = 0;
  zs_image im = {0, 0, NULL};
  zs_layer layer = {0};
  zs_shadow_set shadows = {0};
  zs_raster_stats sample_stats; /* --samples: summed over the samples' frames */
  memset(&sample_stats, 0, sizeof sample_stats);
  float *depth = NULL, *normals = NULL;
  double *times = NULL;
  double view[16], proj[16];
  if ((st = zs_frame_camera(&model, &o->view.cam, o->view.width, o->view.height, view, proj, err))) goto done;
  zs_camera used; /* as the frame is drawn: for --stats and -v */
  zs_frame_complete_camera(&model, &o->view.cam, o->view.width, o->view.height, &used);
  if (o->verbose && !keep) {
    fputs("zscan render: camera: ", stderr);
    print_camera_options(stderr, &used);
    fputc('\n', stderr);
  }
  zs_device_config cfg = {o->view.width,     o->view.height,  o->algo,
                          zs_frame_device_shade(zs_frame_style_of(o->hidden_line, o->wireframe),
                                                o->shade),
                          o->view.cull_back, o->threads, o->background, o->spans, o->filter};
  if ((st = zs_device_create(&cfg, &dev, err))) goto done;
  const zs_shadow_opts so = {o->shadows, o->shadow_size,
                             o->has_shadow_bias ? o->shadow_bias[0] : ZS_SHADOW_BIAS_UNITS,
                             o->has_shadow_bias ? o->shadow_bias[1] : ZS_SHADOW_BIAS_SLOPE};
  /* the shadow maps see the whole scene, so that a part's frame shows the
   * shadows the other parts cast on it */
  if ((st = zs_frame_lights_and_shadows(dev, &model, o->lights, o->nlights, &so, view,
                                        o->threads, &shadows, err)))
    goto done;
  if (shadows.n == 0 && !o->quiet && !keep) { /* asked for, and nothing casts */
    int marked = 0;
    const zs_light *ls = o->nlights ? o->lights : model.lights;
    for (int i = 0; i < (o->nlights ? o->nlights : model.nlights); i++) marked |= ls[i].shadow;
    const int phong = o->shade == ZS_SHADE_AUTO || o->shade == ZS_SHADE_PHONG;
    if (marked && !phong)
      fprintf(stderr, "zscan render: warning: --shade %s shows no shadows (auto and phong do): "
              "the lights marked \"shadow\" cast none\n", zs_shade_name(o->shade));
    else if (o->shadows || o->shadow_size || o->has_shadow_bias)
      fprintf(stderr, "zscan render: warning: %s: no directional or spot light casts shadows\n",
              o->shadows ? "--shadows" : o->shadow_size ? "--shadow-size" : "--shadow-bias");
  }
  /* the camera is the whole scene's: a part's frame composites with the others' */
  if (o->nparts && (st = keep_objects(o, &model, err))) goto done;
  if ((st = zs_device_set_clock(dev, &o->clock, err))) goto done;
  zs_device_keep_line_runs(dev, o->svg && !keep);
  if ((st = zs_image_alloc(&im, o->view.width, o->view.height, err))) goto done;
  if (o->out_layer &&
      (st = zs_layer_alloc(&layer, o->view.width, o->view.height, view, proj, o->background,
                           o->shade, err)))
    goto done;
  zs_layer *into = o->out_layer ? &layer : NULL;
  if (o->out_pfm && !(depth = malloc((size_t)o->view.width * (size_t)o->view.height * sizeof *depth))) {
    st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory for the depth map");
    goto done;
  }
  if (!(times = malloc((size_t)o->repeat * sizeof *times))) {
    st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
    goto done;
  }
  if (o->cull >= 0) {
    if ((st = zs_octree_build(&tree, &model, NULL, err))) goto done;
    have_tree = 1;
  }
  const zs_frame_look look = {zs_frame_style_of(o->hidden_line, o->wireframe), o->line_width,
                              o->point_size, o->point_shape};
  for (int k = 0; k < o->repeat; k++) {
    double start = zs_os_monotonic_ms();
    if (o->cull >= 0) {
      /* each repeat is a fresh first frame: the culler starts again */
      zs_culler_destroy(culler);
      culler = NULL;
      if ((st = zs_culler_create((zs_cull_method)o->cull, &o->cost, &culler, err)) ||
          (st = zs_culler_set_bounds(culler, o->bounds, err)) ||
          (st = zs_culler_frame(culler, dev, &model, &tree, view, proj, &cs, err)))
        goto done;
      /* the lines and points are not culled: every one is drawn */
      if ((st = zs_frame_draw_prims(dev, &model, o->line_width, o->point_size, o->point_shape,
                                    err)))
        goto done;
      if (o->overlay && (st = draw_overlay(dev, culler, &tree, err))) goto done;
      if ((st = zs_frame_finish_into(dev, &im, depth, into, err))) goto done;
    } else if (into) { /* no hidden lines: the faces' frame */
      if ((st = zs_frame_draw_all(dev, &model, view, proj, err)) ||
          (st = zs_frame_draw_prims(dev, &model, o->line_width, o->point_size, o->point_shape,
                                    err)) ||
          (st = zs_frame_finish_into(dev, &im, depth, into, err)))
        goto done;
    } else if (o->samples > 1) {
      if ((st = zs_frame_render_samples(dev, &model, view, proj, &look, o->samples,
                                        o->supersample, &im, &sample_stats, err)))
        goto done;
    } else if ((st = zs_frame_render_on(dev, &model, view, proj, &look, &im, depth,
                                        err))) {
      goto done;
    }
    times[k] = zs_os_monotonic_ms() - start;
  }
  double median = zs_median(times, o->repeat);
  if (keep) {
    *keep = im;
    im = (zs_image){0, 0, NULL};
    goto done;
  }

  if (o->out_normals) { /* one frame more, every face shaded by its normals; before any file */
    if (!(normals = calloc(3 * (size_t)o->view.width * (size_t)o->view.height, sizeof *normals))) {
      st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory for the normals");
      goto done;
    }
    if ((st = zs_frame_render_normals(&cfg, &model, view, proj, normals, err))) goto done;
  }
  /* the files replace theirs together or not at all; standard output,
   * which cannot be taken back, goes last */
  zs_out_set outs = ZS_OUT_SET_EMPTY;
  const char *const *names = output_options;
  const char *const paths[] = {o->out_png, depth ? o->out_pfm : NULL,
                               normals ? o->out_normals : NULL, into ? o->out_layer : NULL};
  for (int last = 0; last < 2 && !st; last++)
    for (int k = 0; k < 4 && !st; k++) {
      if (!paths[k] || zs_out_is_stdout(paths[k]) != last) continue;
      const int w = o->view.width, h = o->view.height;
      st = k == 0   ? (o->svg ? write_svg(o, dev, &outs, err)
                              : zs_png_write_in(&outs, paths[k], &im, o->shade, err))
           : k == 1 ? zs_pfm_write_in(&outs, paths[k], w, h, 1, depth, err)
           : k == 2 ? zs_pfm_write_in(&outs, paths[k], w, h, 3, normals, err)
                    : zs_layer_write_in(&outs, paths[k], &layer, err);
      if (st) zs_out_error_option(err, names[k]);
    }
  if (st) zs_out_set_drop(&outs);
  else st = zs_out_set_land(&outs, err);
  if (st) goto done;
  int64_t diff_pixels = -1;
  if (o->stats && o->algo == ZS_ALGO_DEPTHSORT &&
      (st = painter_error(o, &model, &diff_pixels, err)))
    goto done;
  cull_report cr = {o->cull >= 0 ? zs_cull_method_name((zs_cull_method)o->cull) : NULL, &cs,
                    have_tree ? tree.nnodes : 0, have_tree && tree.flat};
  if (o->stats)
    print_stats(o, &model, o->samples > 1 ? &sample_stats : zs_device_stats(dev), dev, zs_image_hash(&im), median, load_ms,
                diff_pixels, o->cull >= 0 ? &cr : NULL, &used);
  else if (!o->quiet) /* one line for a person; --stats is the line for programs */
    fprintf(stderr, "zscan render: wrote %s: %dx%d, %llu faces, %.1f ms%s%s%s%s%s%s\n",
            zs_out_is_stdout(o->out_png) ? "standard output" : o->out_png, o->view.width,
            o->view.height, (unsigned long long)zs_scene_faces(&model), median,
            o->out_pfm ? ", depth to " : "", o->out_pfm ? o->out_pfm : "",
            o->out_normals ? ", normals to " : "", o->out_normals ? o->out_normals : "",
            o->out_layer ? ", layer to " : "", o->out_layer ? o->out_layer : "");

done:
  zs_culler_destroy(culler);
  if (have_tree) zs_octree_free(&tree);
  free(times);
  free(depth);
  free(normals);
  zs_layer_free(&layer);
  zs_shadow_set_free(&shadows);
  zs_image_free(&im);
  zs_device_destroy(dev);
  zs_scene_free(&model);
  return st;
}

int zs_cmd_render(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage_head, zs_view_opts_usage, usage_tail, NULL)) return 0;
  zs_cmd_render_opts o;
  zs_error err;
  zs_error_clear(&err);
  if (zs_cmd_render_parse(argc, argv, 0, &o, &err)) return zs_cli_fail("zscan render", &err, 1);
  return run(&o, NULL, &err) ? zs_cli_fail("zscan render", &err, 0) : 0;
}

zs_status zs_cmd_render_image(const zs_cmd_render_opts *o, zs_image *out, zs_error *err) {
  return run(o, out, err);
}
