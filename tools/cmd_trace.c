/* `zscan trace INPUT [options]`: renders INPUT in scanline mode and prints
 * the data structures of the lecture (the sorted polygon table, the sorted
 * edge table, then per scanline the active polygons, the active edge pairs,
 * the spans filled, and the row of ids and of the z-buffer), as text or as
 * JSON lines (trace_walk.h), and can draw a picture per scanline. */
#include "tools/commands.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "raster/raster.h"
#include "tools/cli.h"
#include "tools/glyphs.h"
#include "lib/image.h"
#include "lib/input.h"
#include "lib/outfile.h"
#include "tools/cmd_trace_page.h"
#include "tools/trace_walk.h"
#include "tools/viewopts.h"
#include "util/os.h"

static const char usage[] =
    "usage: zscan trace INPUT [options]\n"
    "  --rows Y0:Y1        only these rows (inclusive; default all)\n"
    "  --format text|json  text (default) or JSON lines: the tables, then one\n"
    "                      object per scanline, last the frame: its id image's\n"
    "                      hash and counters, as zscan render --shade id --stats\n"
    "  --png-dir DIR       also a picture per scanline: the frame so far, the\n"
    "                      scanline, its active edges and spans, the polygons'\n"
    "                      outlines, the z-buffer, row and column numbers, a legend\n"
    "  --scale S           picture pixels per image pixel (default 16)\n"
    "  --brief             the exact fractions only, without the fixed-point lines\n"
    "  --algo scanline|zbuffer  the scanline z-buffer row by row (default), or the\n"
    "                      plain z-buffer polygon by polygon: the whole depth grid\n"
    "                      (view z) and frame buffer after each polygon drawn\n"
    "  --html FILE.html    a page to step through the walk in a browser: the pixel\n"
    "                      grid, the sorted and active tables with the exact\n"
    "                      fractions, the row's z-buffer and who won each pixel;\n"
    "                      #row=N opens at scanline N; everything inline\n"
    "  vertex colours      a mesh with them (OBJ v x y z r g b) seen orthographically\n"
    "                      (--grid, --ortho) adds Gouraud intensities: I = a corner's\n"
    "                      red channel (0 to 255); I and dI per edge, Il dIl Ir dIr\n"
    "                      dIx per pair, I per pixel, in the pictures and page too\n"
    "  --quiet             no progress of the pictures on stderr\n";


/* ---- step pictures ---- */

static uint32_t id_colour(uint32_t id) {
  if (id == ZS_ID_NONE) return 0x202020;
  static const uint32_t pal[8] = {0x4E79A7, 0xF28E2B, 0x59A14F, 0xE15759,
                                  0x76B7B2, 0xEDC948, 0xB07AA1, 0xFF9DA7};
  return pal[id % 8];
}

static void rect(zs_image *im, int x0, int y0, int x1, int y1, uint32_t c, int filled) {
  for (int y = y0; y < y1; y++)
    for (int x = x0; x < x1; x++) {
      if (x < 0 || y < 0 || x >= im->width || y >= im->height) continue;
      if (filled || y == y0 || y == y1 - 1 || x == x0 || x == x1 - 1)
        im->rgb[(size_t)y * (size_t)im->width + (size_t)x] = c;
    }
}

/* A line from (x0, y0) to (x1, y1), picture pixels, one pixel wide. */
static void line(zs_image *im, double x0, double y0, double x1, double y1, uint32_t c) {
  double dx = x1 - x0, dy = y1 - y0;
  double len = fabs(dx) > fabs(dy) ? fabs(dx) : fabs(dy);
  int n = (int)len + 1;
  for (int i = 0; i <= n; i++) {
    int x = (int)floor(x0 + dx * i / n), y = (int)floor(y0 + dy * i / n);
    if (x >= 0 && y >= 0 && x < im->width && y < im->height)
      im->rgb[(size_t)y * (size_t)im->width + (size_t)x] = c;
  }
}

/* Halfway to white: an outline that shows over its own polygon's fill. */
static uint32_t light(uint32_t c) { return ((c & 0xFEFEFE) >> 1) + 0x7F7F7F; }

enum { PICTURE_PAPER = 0x101010, LABEL_INK = 0xD0D0D0 };

/* The rows done of the Gouraud intensities as grey levels (I, 0 to 255),
 * from (x0, y0), the current row outlined. */
static void intensity_panel(const zs_tracer *t, zs_image *im, int x0, int y0, int y) {
  const int w = t->o->view.width, h = t->o->view.height, s = t->o->scale;
  for (int r = 0; r < h; r++)
    for (int x = 0; x < w; x++) {
      const double v = r <= y ? t->inten[(size_t)r * (size_t)w + (size_t)x] : NAN;
      uint32_t c = 0x202020;
      if (!isnan(v)) {
        const uint32_t g = v <= 0 ? 0 : v >= 255 ? 255 : (uint32_t)(v + 0.5);
        c = g << 16 | g << 8 | g;
      }
      rect(im, x0 + x * s, y0 + r * s, x0 + (x + 1) * s, y0 + (r + 1) * s, c, 1);
    }
  rect(im, x0, y0 + y * s, x0 + w * s, y0 + (y + 1) * s, 0xFFFF00, 0);
}

/* The step picture of scanline y, in picture pixels (s per image pixel):
 *
 *   column numbers           |
 *   row  the frame so far,   | the z-buffer as grey | with vertex colours:
 *   nos  outlines, scanline, | (near is light)      | the intensities I as
 *        spans, crossings    |                      | grey
 *   legend: the polygons' colours; XL, XR, SPAN, ROW; Z NEAR = LIGHT; I
 */
static void write_picture(zs_tracer *t, int y) {
  const int w = t->o->view.width, h = t->o->view.height, s = t->o->scale;
  const int k = s >= 12 ? 2 : 1; /* the labels' cell size */
  const int line_h = (ZS_GLYPH_H + 3) * k;
  const int left = 3 * ZS_GLYPH_ADVANCE * k + 2 * k, top = line_h;
  /* the numbers every `every` columns, as they fit */
  int every = 1, every_row = 1;
  while (every * s < 3 * ZS_GLYPH_ADVANCE * k) every++;
  while (every_row * s < (ZS_GLYPH_H + 1) * k) every_row++;
  zs_image im;
  zs_error err;
  zs_error_clear(&err);
  const int panels = t->shading ? 3 : 2; /* frame, z-buffer, and the intensities */
  if (zs_image_alloc(&im, left + panels * w * s + (panels - 1) * s,
                     top + h * s + (panels + 1) * line_h + k, &err)) {
    t->failed = 1;
    t->err = err;
    return;
  }
  for (size_t i = 0; i < (size_t)im.width * (size_t)im.height; i++) im.rgb[i] = PICTURE_PAPER;
  const int ox = left, oy = top, dx = left + (w + 1) * s; /* the frame's and depth's corners */
  for (int r = 0; r <= y; r++)
    for (int x = 0; x < w; x++) {
      size_t i = (size_t)r * (size_t)w + (size_t)x;
      rect(&im, ox + x * s, oy + r * s, ox + (x + 1) * s, oy + (r + 1) * s, id_colour(t->ids[i]), 1);
      uint32_t g = t->ids[i] == ZS_ID_NONE ? 0 : 255 - (t->depth[i] >> 24);
      rect(&im, dx + x * s, oy + r * s, dx + (x + 1) * s, oy + (r + 1) * s, g << 16 | g << 8 | g, 1);
    }
  for (int r = y + 1; r < h; r++)
    for (int x = 0; x < w; x++) {
      rect(&im, ox + x * s, oy + r * s, ox + (x + 1) * s, oy + (r + 1) * s, 0x202020, 1);
      rect(&im, dx + x * s, oy + r * s, dx + (x + 1) * s, oy + (r + 1) * s, 0, 1);
    }
  if (t->shading) intensity_panel(t, &im, left + 2 * (w + 1) * s, oy, y);
  /* the pixel grid, faint, and the row and column numbers */
  char num[16];
  for (int r = 0; r < h; r++) {
    for (int x = 0; x < w; x++)
      rect(&im, ox + x * s, oy + r * s, ox + (x + 1) * s, oy + (r + 1) * s, 0x303030, 0);
    /* the current row's number always, the others as they fit beside it */
    if (r != y && (r % every_row || abs(r - y) < every_row)) continue;
    snprintf(num, sizeof num, "%3d", r % 1000);
    zs_glyphs_draw(&im, k, oy + r * s + (s - ZS_GLYPH_H * k) / 2, k, r == y ? 0xFFFF00 : LABEL_INK,
                   num);
  }
  for (int x = 0; x < w; x += every) {
    snprintf(num, sizeof num, "%d", x % 1000);
    int len = (int)strlen(num) * ZS_GLYPH_ADVANCE * k - k;
    zs_glyphs_draw(&im, ox + x * s + (s - len) / 2, k, k, LABEL_INK, num);
  }
  /* the outlines: the edges of the edge table (pixel centre c at c + 0.5) */
  for (int i = 0; i < t->noutline; i++) {
    const double *e = t->outline[i];
    line(&im, ox + e[0] * s, oy + e[1] * s, ox + e[2] * s, oy + e[3] * s,
         light(id_colour(t->outline_id[i])));
  }
  /* the scanline, its spans, and the exact edge crossings at its centre */
  rect(&im, ox, oy + y * s, ox + w * s, oy + (y + 1) * s, 0xFFFF00, 0);
  for (int i = 0; i < t->nspans; i++)
    rect(&im, ox + t->spans[i].x0 * s, oy + y * s + 2, ox + (t->spans[i].x1 + 1) * s,
         oy + (y + 1) * s - 2, 0xFFFFFF, 0);
  for (int i = 0; i < t->npairs; i++) {
    int xl = ox + (int)((t->pairs[i].xl_real + 0.5) * s), xr = ox + (int)((t->pairs[i].xr_real + 0.5) * s);
    rect(&im, xl - 1, oy + y * s, xl + 2, oy + (y + 1) * s, 0xFF3030, 1);
    rect(&im, xr - 1, oy + y * s, xr + 2, oy + (y + 1) * s, 0x30A0FF, 1);
  }
  /* the legend: the polygons' colours by id (up to 16), the marks, depth */
  int ly = oy + h * s + k, lx = left;
  const int sw = ZS_GLYPH_H * k; /* a swatch's side */
  lx = zs_glyphs_draw(&im, lx, ly, k, LABEL_INK, "ID ");
  for (uint32_t id = 0; id <= t->max_id && id < 16; id++) {
    rect(&im, lx, ly, lx + sw, ly + sw, id_colour(id), 1);
    snprintf(num, sizeof num, "%u ", id);
    lx = zs_glyphs_draw(&im, lx + sw + k, ly, k, LABEL_INK, num);
  }
  ly += line_h;
  lx = left;
  static const struct { const char *name; uint32_t c; int filled; } marks[4] = {
      {"XL ", 0xFF3030, 1}, {"XR ", 0x30A0FF, 1}, {"SPAN ", 0xFFFFFF, 0}, {"ROW", 0xFFFF00, 0}};
  for (int m = 0; m < 4; m++) {
    rect(&im, lx, ly, lx + sw, ly + sw, marks[m].c, marks[m].filled);
    lx = zs_glyphs_draw(&im, lx + sw + k, ly, k, LABEL_INK, marks[m].name);
  }
  ly += line_h;
  lx = zs_glyphs_draw(&im, left, ly, k, LABEL_INK, "Z ");
  for (int g = 0; g < 4; g++) { /* far (dark) to near (light) */
    uint32_t v = (uint32_t)(64 + 63 * g);
    rect(&im, lx + g * sw, ly, lx + (g + 1) * sw, ly + sw, v << 16 | v << 8 | v, 1);
  }
  zs_glyphs_draw(&im, lx + 4 * sw + 2 * k, ly, k, LABEL_INK, "NEAR = LIGHT");
  if (t->shading) {
    ly += line_h;
    lx = zs_glyphs_draw(&im, left, ly, k, LABEL_INK, "I ");
    for (int g = 0; g < 4; g++) { /* 0 (black) to 255 (white) */
      uint32_t v = (uint32_t)(85 * g);
      rect(&im, lx + g * sw, ly, lx + (g + 1) * sw, ly + sw, v << 16 | v << 8 | v, 1);
    }
    zs_glyphs_draw(&im, lx + 4 * sw + 2 * k, ly, k, LABEL_INK, "255 = WHITE");
  }
  char path[4200];
  snprintf(path, sizeof path, "%s/scanline-%04d.png", t->o->png_dir, y);
  if (zs_png_write(path, &im, &err)) {
    zs_out_error_option(&err, "--png-dir");
    t->failed = 1;
    t->err = err;
  }
  zs_image_free(&im);
}


/* The walk's hook after each row traced: its picture, and the progress. */
static void picture(zs_tracer *t, int y) {
  write_picture(t, y);
  zs_progress_step(&t->progress, ++t->pictures);
}

/* ---- the command ---- */

static zs_status parse(int argc, char **argv, zs_trace_opts *o, zs_error *err) {
  memset(o, 0, sizeof *o);
  zs_view_opts_default(&o->view, 32, 24);
  o->row0 = 0;
  o->row1 = ZS_MAX_IMAGE_SIDE;
  o->scale = 16;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = NULL;
    int taken = zs_view_opts_parse(&o->view, argc, argv, &i, err);
    if (taken < 0) return err->code;
    if (taken) continue;
    if (strcmp(a, "--rows") == 0) {
      if (zs_cli_value(argc, argv, &i, &v, err)) return err->code;
      char *end;
      long y0 = strtol(v, &end, 10), y1;
      if (end == v || *end != ':')
        return zs_error_set(err, ZS_ERR_ARG, "--rows: expected Y0:Y1, got '%s'", v);
      const char *p = end + 1;
      y1 = strtol(p, &end, 10);
      if (end == p || *end || y0 < 0 || y1 < y0 || y1 >= ZS_MAX_IMAGE_SIDE)
        return zs_error_set(err, ZS_ERR_ARG, "--rows: expected 0 <= Y0 <= Y1, got '%s'", v);
      o->row0 = (int)y0;
      o->row1 = (int)y1;
      o->rows_given = 1;
    } else if (strcmp(a, "--quiet") == 0) {
      o->quiet = 1;
    } else if (strcmp(a, "--brief") == 0) {
      o->brief = 1;
    } else if (strcmp(a, "--algo") == 0) {
      if (zs_cli_value(argc, argv, &i, &v, err)) return err->code;
      if (strcmp(v, "scanline") != 0 && strcmp(v, "zbuffer") != 0)
        return zs_error_set(err, ZS_ERR_ARG, "--algo: expected scanline or zbuffer, got '%s'", v);
      o->zbuffer = v[0] == 'z';
    } else if (strcmp(a, "--html") == 0) {
      if (zs_cli_output_value(argc, argv, &i, &v, err) || zs_cli_output_format(a, v, "html", err))
        return err->code;
      o->html = v;
      o->as_array = 1;
      o->json = 1; /* the page reads the JSON trace */
    } else if (strcmp(a, "--format") == 0) {
      if (zs_cli_value(argc, argv, &i, &v, err)) return err->code;
      if (strcmp(v, "json") == 0) o->json = 1;
      else if (strcmp(v, "text") != 0)
        return zs_error_set(err, ZS_ERR_ARG, "--format: expected text or json, got '%s'", v);
    } else if (strcmp(a, "--png-dir") == 0) {
      if (zs_cli_value(argc, argv, &i, &v, err)) return err->code;
      o->png_dir = v;
    } else if (strcmp(a, "--scale") == 0) {
      if (zs_cli_int_value(argc, argv, &i, 1, 64, &o->scale, err)) return err->code;
    } else if (zs_cli_operand(a, "zscan trace", "INPUT", &o->input, err)) {
      return err->code;
    }
  }
  if (!o->input) return zs_error_set(err, ZS_ERR_ARG, "missing INPUT (see zscan trace --help)");
  if (o->png_dir) {
    if (zs_out_dir("--png-dir", o->png_dir, err)) return err->code;
    if ((int64_t)o->view.width * o->view.height * o->scale * o->scale > (int64_t)1 << 26)
      return zs_error_set(err, ZS_ERR_LIMIT,
                          "--png-dir: %dx%d at scale %d makes pictures too large; lower --scale",
                          o->view.width, o->view.height, o->scale);
  }
  return ZS_OK;
}

/* The Gouraud intensities of a scene with vertex colours: under an
 * orthographic view only, where they are linear on the screen as the
 * textbook steps them (zscan interpolates perspective-correct). */

int zs_cmd_trace(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, zs_view_opts_usage, NULL)) return 0;
  zs_trace_opts o;
  zs_error err;
  zs_error_clear(&err);
  int parsing = 1; /* a usage error exits 2 (tools/cli.h) */
  zs_scene model;
  zs_tracer t;
  memset(&t, 0, sizeof t);
  zs_memfile page_json = {NULL, NULL, 0}; /* --html: the JSON trace, gathered */
  int have_model = 0, rc = 1;
  if (parse(argc, argv, &o, &err)) goto fail;
  parsing = 0;
  if (zs_input_load_scene(o.input, &model, &err)) goto fail;
  have_model = 1;
  zs_view_opts asked = o.view; /* (the result must not alias what is read) */
  zs_view_opts_for_scene(&asked, &model, &o.view.cam, &o.view.width, &o.view.height);
  if (o.rows_given && o.row0 >= o.view.height) {
    zs_error_set(&err, ZS_ERR_ARG, "--rows %d:%d: the image has rows 0 to %d", o.row0, o.row1,
                 o.view.height - 1);
    goto fail;
  }
  if (o.png_dir) {
    int first = o.row0 > 0 ? o.row0 : 0;
    int last = o.row1 >= 0 && o.row1 < o.view.height - 1 ? o.row1 : o.view.height - 1;
    zs_progress_start(&t.progress, "trace", "picture", last - first + 1, o.quiet);
    t.picture = picture;
  }
  if (o.html && zs_memfile_open(&page_json) != 0) {
    zs_error_set(&err, ZS_ERR_NOMEM, "out of memory");
    goto fail;
  }
  if (zs_trace_walk(&t, &o, &model, o.html ? page_json.f : stdout, &err)) goto fail;
  if (o.html) {
    if (zs_memfile_close(&page_json) != 0) {
      zs_error_set(&err, ZS_ERR_NOMEM, "out of memory");
      goto fail;
    }
    zs_out page;
    if (zs_out_open(&page, o.html, &err)) {
      zs_out_error_option(&err, "--html");
      goto fail;
    }
    fprintf(page.fp, "%s[%s]%s", zs_cmd_trace_page_head, page_json.data, zs_cmd_trace_page_tail);
    if (zs_out_commit(&page, &err)) {
      zs_out_error_option(&err, "--html");
      goto fail;
    }
  }
  rc = 0;
  goto done;
fail:
  rc = zs_cli_fail("zscan trace", &err, parsing);
done:
  if (page_json.f) fclose(page_json.f);
  free(page_json.data);
  zs_tracer_free(&t);
  if (have_model) zs_scene_free(&model);
  return rc;
}
