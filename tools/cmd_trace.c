/* `zscan trace INPUT [options]`: renders INPUT in scanline mode and prints
 * the data structures of the lecture (the sorted polygon table, the sorted
 * edge table, then per scanline the active polygons, the active edge pairs,
 * the spans filled, and the row of ids and of the z-buffer), as text or as
 * JSON lines, and can draw a picture per scanline.
 *
 * Units: rows and columns of the image (row 0 at the top); x values in
 * pixel-centre units (column c has its centre at x = c), shown exactly as
 * fractions where the DDA holds them exactly; depth as window depth in
 * [0, 1], 0 at the near plane, beside the fixed-point integers; with vertex
 * colours, the Gouraud intensities beside them (cmd_trace_gouraud.h). */
#include "tools/commands.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "raster/raster.h"
#include "tools/cli.h"
#include "tools/glyphs.h"
#include "lib/frame.h"
#include "lib/frame_camera.h"
#include "lib/image.h"
#include "lib/input.h"
#include "lib/outfile.h"
#include "tools/cmd_trace_gouraud.h"
#include "util/exactmath.h"
#include "tools/cmd_trace_page.h"
#include "tools/viewopts.h"

static const char usage[] =
    "usage: zscan trace INPUT [options]\n"
    "  --rows Y0:Y1        only these rows (inclusive; default all)\n"
    "  --format text|json  text (default) or JSON lines: the tables, then one\n"
    "                      object per scanline\n"
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

typedef struct trace_opts {
  const char *input, *png_dir;
  zs_view_opts view;
  int row0, row1, json, scale, quiet, brief, rows_given;
  const char *html; /* --html FILE: the page */
  int zbuffer;      /* --algo zbuffer: the plain z-buffer, a step per polygon */
} trace_opts;

/* What the observer saw of the row being finished, kept until the sink
 * hands over the row's ids and depths. */
typedef struct tracer {
  const trace_opts *o;
  double proj10, proj11;  /* the projection's depth row, for view-space z */
  int ortho;
  FILE *out;
  zs_trace_pair *pairs;
  zs_trace_span *spans;
  int npairs, nspans, cap;
  int failed;
  /* the step pictures: the frame so far */
  uint32_t *ids, *depth;
  zs_progress progress; /* of the pictures, on stderr */
  int lines;            /* JSON objects written */
  int pictures;
  /* the polygons' outlines: the edge table's edges, picture units */
  double (*outline)[4];
  uint32_t *outline_id;
  int noutline;
  uint32_t max_id; /* the largest polygon id, for the legend */
  /* Gouraud intensities (cmd_trace_gouraud.h), when the input has vertex
   * colours and the view is orthographic: the row's pairs', each pixel's
   * (NAN: none), and for the pictures the frame's so far */
  int shading;
  zs_gouraud gouraud;
  zs_gouraud_pair *gpairs;
  int *has_gpair;
  int gcap;
  double *row_I, *inten;
  zs_error err;
} tracer;

/* ---- numbers as the lecture writes them ---- */

/* zs_gcd64, 1 where both are 0 (a zero over any denominator). */
static int64_t gcd64(int64_t a, int64_t b) {
  const int64_t g = zs_gcd64(a, b);
  return g ? g : 1;
}

/* x - rem / d as "n" or "n/m" (reduced) */
static void fraction(char *buf, size_t n, int64_t x, int64_t rem, int64_t d) {
  int64_t num = x * d - rem, g = gcd64(num, d);
  if (d / g == 1) snprintf(buf, n, "%lld", (long long)(num / g));
  else snprintf(buf, n, "%lld/%lld", (long long)(num / g), (long long)(d / g));
}

/* (X1 - X0) / (Y1 - Y0) as a reduced fraction */
static void slope(char *buf, size_t n, int64_t dx, int64_t dy) {
  int64_t g = gcd64(dx, dy);
  if (dy / g == 1) snprintf(buf, n, "%lld", (long long)(dx / g));
  else snprintf(buf, n, "%lld/%lld", (long long)(dx / g), (long long)(dy / g));
}

static int in_rows(const trace_opts *o, int y) { return y >= o->row0 && y <= o->row1; }

/* ---- the tables ---- */

static int cmp_row0_poly(const void *a, const void *b) {
  const zs_trace_poly *p = a, *q = b;
  return (p->row0 > q->row0) - (p->row0 < q->row0);
}

static int cmp_row0_edge(const void *a, const void *b) {
  const zs_trace_edge *p = a, *q = b;
  return (p->row0 > q->row0) - (p->row0 < q->row0);
}

/* The numbers v[0..n-1] into o under names[0..n-1], in turn. */
static void add_numbers(cJSON *o, const char *const *names, const double *v, int n) {
  for (int i = 0; i < n; i++) cJSON_AddNumberToObject(o, names[i], v[i]);
}

static cJSON *json_poly(const zs_trace_poly *p) {
  cJSON *o = cJSON_CreateObject();
  static const char *const names[] = {"id",  "row", "dy",       "z0",       "dzx",
                                      "dzy", "origin_x", "origin_y", "zshift"};
  const double v[] = {p->id,  p->row0, p->row1 - p->row0, p->z0,     p->dzx,
                      p->dzy, p->ox,   p->oy,             p->zshift};
  add_numbers(o, names, v, 9);
  char hex[8];
  snprintf(hex, sizeof hex, "#%06x", p->rgb & 0xFFFFFF);
  cJSON_AddStringToObject(o, "colour", hex);
  return o;
}

/* The Gouraud intensity of batch edge k at its top row, and per row, as
 * numbers and fractions beside its x and dx (when it has one). */
static void json_edge_I(cJSON *o, const tracer *t, const zs_trace_edge *e, int32_t k) {
  zs_q I, dI;
  char s[64];
  if (!t->shading || !zs_gouraud_edge_at(&t->gouraud, k, e->row0, &I, &dI)) return;
  cJSON_AddNumberToObject(o, "I", I.v);
  cJSON_AddNumberToObject(o, "dI", dI.v);
  zs_q_str(s, sizeof s, I);
  cJSON_AddStringToObject(o, "I_fraction", s);
  zs_q_str(s, sizeof s, dI);
  cJSON_AddStringToObject(o, "dI_fraction", s);
}

static cJSON *json_edge(const tracer *t, const zs_trace_edge *e, int32_t k) {
  cJSON *o = cJSON_CreateObject();
  char s[64];
  cJSON_AddNumberToObject(o, "id", e->id);
  cJSON_AddStringToObject(o, "side", e->side ? "right" : "left");
  cJSON_AddNumberToObject(o, "row", e->row0);
  cJSON_AddNumberToObject(o, "dy", e->row1 - e->row0);
  cJSON_AddNumberToObject(o, "x", e->x_top);
  cJSON_AddNumberToObject(o, "dx", e->dx);
  slope(s, sizeof s, (int64_t)e->X1 - e->X0, (int64_t)e->Y1 - e->Y0);
  cJSON_AddStringToObject(o, "dx_fraction", s);
  /* the snapped end points in pixel-centre units (column c at x = c) */
  const double ends[4] = {e->X0 / (double)ZS_SUBPIXEL_ONE - 0.5, e->Y0 / (double)ZS_SUBPIXEL_ONE - 0.5,
                          e->X1 / (double)ZS_SUBPIXEL_ONE - 0.5, e->Y1 / (double)ZS_SUBPIXEL_ONE - 0.5};
  cJSON_AddItemToObject(o, "ends", cJSON_CreateDoubleArray(ends, 4));
  json_edge_I(o, t, e, k);
  return o;
}

/* One JSON line; for the page (--html), one element of its array. */
static void print_json(tracer *t, cJSON *o) {
  char *s = cJSON_PrintUnformatted(o);
  if (s) fprintf(t->out, t->o->html ? "%s%s\n" : "%.0s%s\n", t->lines++ ? "," : "", s);
  else t->failed = 1;
  free(s);
  cJSON_Delete(o);
}

/* The text edge table's I and dI columns (and the line's end). */
static void print_edge_I(const tracer *t, const zs_trace_edge *e, int32_t k) {
  zs_q I, dI;
  char a[64] = "-", b[64] = "-";
  if (t->shading && zs_gouraud_edge_at(&t->gouraud, k, e->row0, &I, &dI)) {
    zs_q_str(a, sizeof a, I);
    zs_q_str(b, sizeof b, dI);
  }
  fprintf(t->out, t->shading ? " %10s %10s\n" : "%.0s%.0s\n", a, b);
}

static void on_tables(void *user, const zs_trace_poly *polys, int npolys,
                      const zs_trace_edge *edges, int nedges) {
  tracer *t = user;
  /* The walk buckets by first row, keeping batch order inside a bucket:
   * a stable sort by row gives the same order. */
  zs_trace_poly *p = malloc((size_t)(npolys ? npolys : 1) * sizeof *p);
  zs_trace_edge *e = malloc((size_t)(nedges ? nedges : 1) * sizeof *e);
  int32_t *ek = malloc((size_t)(nedges ? nedges : 1) * sizeof *ek); /* e[i] is edges[ek[i]] */
  if (!p || !e || !ek ||
      (t->shading && !zs_gouraud_edges(&t->gouraud, polys, npolys, edges, nedges))) {
    free(p);
    free(e);
    free(ek);
    t->failed = 1;
    return;
  }
  if (npolys) memcpy(p, polys, (size_t)npolys * sizeof *p);
  if (nedges) memcpy(e, edges, (size_t)nedges * sizeof *e);
  for (int i = 0; i < nedges; i++) ek[i] = i;
  /* insertion sort: stable, and the tables of a teaching scene are short */
  for (int i = 1; i < npolys; i++)
    for (int j = i; j > 0 && cmp_row0_poly(&p[j - 1], &p[j]) > 0; j--) {
      zs_trace_poly tmp = p[j];
      p[j] = p[j - 1];
      p[j - 1] = tmp;
    }
  for (int i = 1; i < nedges; i++)
    for (int j = i; j > 0 && cmp_row0_edge(&e[j - 1], &e[j]) > 0; j--) {
      zs_trace_edge tmp = e[j];
      e[j] = e[j - 1];
      e[j - 1] = tmp;
      int32_t k = ek[j];
      ek[j] = ek[j - 1];
      ek[j - 1] = k;
    }
  if (t->o->png_dir && nedges) { /* kept for the step pictures */
    t->outline = malloc((size_t)nedges * sizeof *t->outline);
    t->outline_id = malloc((size_t)nedges * sizeof *t->outline_id);
    if (!t->outline || !t->outline_id) t->failed = 1;
    for (int i = 0; i < nedges && !t->failed; i++) {
      const double one = ZS_SUBPIXEL_ONE;
      t->outline[i][0] = e[i].X0 / one, t->outline[i][1] = e[i].Y0 / one;
      t->outline[i][2] = e[i].X1 / one, t->outline[i][3] = e[i].Y1 / one;
      t->outline_id[i] = e[i].id;
      if (e[i].id > t->max_id) t->max_id = e[i].id;
      t->noutline = i + 1;
    }
  }
  if (t->o->json) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "width", t->o->view.width);
    cJSON_AddNumberToObject(o, "height", t->o->view.height);
    cJSON *pa = cJSON_AddArrayToObject(o, "polygon_table");
    for (int i = 0; i < npolys; i++) cJSON_AddItemToArray(pa, json_poly(&p[i]));
    cJSON *ea = cJSON_AddArrayToObject(o, "edge_table");
    for (int i = 0; i < nedges; i++) cJSON_AddItemToArray(ea, json_edge(t, &e[i], ek[i]));
    print_json(t, o);
  } else {
    FILE *f = t->out;
    fprintf(f, "sorted polygon table (bucketed by first row; dy = rows after it)\n");
    fprintf(f, "  %4s %6s %4s %12s %12s %12s  %s\n", "row", "id", "dy", "z0", "dzx", "dzy",
            "colour");
    for (int i = 0; i < npolys; i++)
      fprintf(f, "  %4d %6u %4d %12.9f %12.9f %12.9f  #%06x   z0 at pixel (%d, %d)\n", p[i].row0,
              p[i].id, p[i].row1 - p[i].row0, p[i].z0, p[i].dzx, p[i].dzy, p[i].rgb & 0xFFFFFF,
              p[i].ox, p[i].oy);
    fprintf(f, "sorted edge table (bucketed by top row; x at that row's centre)\n");
    fprintf(f, "  %4s %6s %5s %10s %10s %4s", "row", "id", "side", "x", "dx", "dy");
    fprintf(f, t->shading ? " %10s %10s\n" : "%.0s%.0s\n", "I", "dI");
    for (int i = 0; i < nedges; i++) {
      char s[64];
      slope(s, sizeof s, (int64_t)e[i].X1 - e[i].X0, (int64_t)e[i].Y1 - e[i].Y0);
      fprintf(f, "  %4d %6u %5s %10.6f %10s %4d", e[i].row0, e[i].id,
              e[i].side ? "right" : "left", e[i].x_top, s, e[i].row1 - e[i].row0);
      print_edge_I(t, &e[i], ek[i]);
    }
  }
  free(p);
  free(e);
  free(ek);
}

/* ---- each scanline ---- */

/* The Gouraud intensities of the row's pairs, beside them. */
static void gouraud_pairs(tracer *t, int y) {
  if (t->npairs > t->gcap) {
    zs_gouraud_pair *g = realloc(t->gpairs, (size_t)t->npairs * sizeof *g);
    if (g) t->gpairs = g;
    int *h = realloc(t->has_gpair, (size_t)t->npairs * sizeof *h);
    if (h) t->has_gpair = h;
    if (!g || !h) {
      t->failed = 1;
      return;
    }
    t->gcap = t->npairs;
  }
  for (int i = 0; i < t->npairs; i++)
    t->has_gpair[i] = zs_gouraud_pair_of(&t->gouraud, &t->pairs[i], y, &t->gpairs[i]);
}

/* Each pixel's intensity on the finished row: from the pair of the
 * polygon that won it (NAN where none did, or it has none). */
static void gouraud_pixels(tracer *t, const zs_row *row) {
  for (int x = 0; x < row->width; x++) {
    t->row_I[x] = NAN;
    for (int i = 0; i < t->npairs && row->id[x] != ZS_ID_NONE; i++) {
      const zs_trace_pair *p = &t->pairs[i];
      if (t->has_gpair[i] && p->id == row->id[x] && p->xl <= x && x < p->xr) {
        t->row_I[x] = zs_gouraud_at(&t->gpairs[i], p, x);
        break;
      }
    }
  }
  if (t->inten)
    memcpy(t->inten + (size_t)row->y * (size_t)row->width, t->row_I,
           (size_t)row->width * sizeof *t->row_I);
}

static void on_row(void *user, const zs_trace_row *row) {
  tracer *t = user;
  if (row->npairs > t->cap || row->nspans > t->cap) {
    int cap = row->npairs > row->nspans ? row->npairs : row->nspans;
    zs_trace_pair *p = realloc(t->pairs, (size_t)cap * sizeof *p);
    if (p) t->pairs = p;
    zs_trace_span *s = realloc(t->spans, (size_t)cap * sizeof *s);
    if (s) t->spans = s;
    if (!p || !s) {
      t->failed = 1;
      return;
    }
    t->cap = cap;
  }
  /* (memcpy from NULL is undefined even for 0 bytes: rows with nothing
   * active hand over no arrays) */
  if (row->npairs) memcpy(t->pairs, row->pairs, (size_t)row->npairs * sizeof *row->pairs);
  if (row->nspans) memcpy(t->spans, row->spans, (size_t)row->nspans * sizeof *row->spans);
  t->npairs = row->npairs;
  t->nspans = row->nspans;
  if (t->shading) gouraud_pairs(t, row->y);
}

/* The pair's Gouraud intensities, as numbers and fractions (dIx null
 * where the span has no width). */
static void json_pair_I(cJSON *o, const zs_gouraud_pair *g) {
  static const char *const names[] = {"Il", "dIl", "Ir", "dIr", "dIx"};
  const zs_q v[] = {g->Il, g->dIl, g->Ir, g->dIr, g->dIx};
  char s[64], key[32];
  for (int i = 0; i < 5; i++) {
    const int none = i == 4 && !g->has_dIx;
    cJSON_AddItemToObject(o, names[i], none ? cJSON_CreateNull() : cJSON_CreateNumber(v[i].v));
    zs_q_str(s, sizeof s, v[i]);
    snprintf(key, sizeof key, "%s_fraction", names[i]);
    cJSON_AddItemToObject(o, key, none ? cJSON_CreateNull() : cJSON_CreateString(s));
  }
}

static cJSON *json_pair(const tracer *t, int i) {
  const zs_trace_pair *p = &t->pairs[i];
  cJSON *o = cJSON_CreateObject();
  char s[64];
  static const char *const names[] = {"id", "xl", "dxl", "dyl", "xr",
                                      "dxr", "dyr", "zl", "dzx", "dzy"};
  const double v[] = {p->id,  p->xl_real, p->dxl,     p->dyl, p->xr_real,
                      p->dxr, p->dyr,     p->zl_real, p->dzx, p->dzy};
  add_numbers(o, names, v, 10);
  fraction(s, sizeof s, p->xl, p->reml, p->dl);
  cJSON_AddStringToObject(o, "xl_fraction", s);
  fraction(s, sizeof s, p->xr, p->remr, p->dr);
  cJSON_AddStringToObject(o, "xr_fraction", s);
  slope(s, sizeof s, p->dxl_num, p->dl);
  cJSON_AddStringToObject(o, "dxl_fraction", s);
  slope(s, sizeof s, p->dxr_num, p->dr);
  cJSON_AddStringToObject(o, "dxr_fraction", s);
  cJSON *fx = cJSON_AddObjectToObject(o, "fixed");
  static const char *const fixed[] = {"xl", "xr", "zl", "zshift"};
  const double f[] = {(double)p->xl, (double)p->xr, (double)p->zl, p->zshift};
  add_numbers(fx, fixed, f, 4);
  if (t->shading && t->has_gpair[i]) json_pair_I(o, &t->gpairs[i]);
  return o;
}

/* The view-space z of a stored depth (the lecture's z when the eye looks
 * down -z: larger is nearer): invert z_ndc = 2 d - 1 through the
 * projection's third row. */
static double view_z(const tracer *t, uint32_t depth) {
  double ndc = 2.0 * (depth == ZS_DEPTH_FAR ? 1.0 : depth / 4294967296.0) - 1.0;
  return t->ortho ? (ndc - t->proj11) / t->proj10 : -t->proj11 / (ndc + t->proj10);
}

/* " | Il .. dIl .. | Ir .. dIr .. | dIx ..", the textbook's fractions */
static void print_pair_I(FILE *f, const zs_gouraud_pair *g) {
  char il[64], dil[64], ir[64], dir[64], dix[64] = "-";
  zs_q_str(il, sizeof il, g->Il);
  zs_q_str(dil, sizeof dil, g->dIl);
  zs_q_str(ir, sizeof ir, g->Ir);
  zs_q_str(dir, sizeof dir, g->dIr);
  if (g->has_dIx) zs_q_str(dix, sizeof dix, g->dIx);
  fprintf(f, " | Il %s dIl %s | Ir %s dIr %s | dIx %s", il, dil, ir, dir, dix);
}

static void print_row(tracer *t, const zs_row *row) {
  const int w = row->width;
  if (t->o->json) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "y", row->y);
    cJSON *ap = cJSON_AddArrayToObject(o, "active_polygons");
    cJSON *ae = cJSON_AddArrayToObject(o, "active_edges");
    for (int i = 0; i < t->npairs; i++) {
      cJSON *p = cJSON_CreateObject();
      cJSON_AddNumberToObject(p, "id", t->pairs[i].id);
      cJSON_AddNumberToObject(p, "dy", t->pairs[i].dy);
      cJSON_AddItemToArray(ap, p);
      cJSON_AddItemToArray(ae, json_pair(t, i));
    }
    cJSON *sp = cJSON_AddArrayToObject(o, "spans");
    for (int i = 0; i < t->nspans; i++) {
      cJSON *s = cJSON_CreateObject();
      cJSON_AddNumberToObject(s, "x0", t->spans[i].x0);
      cJSON_AddNumberToObject(s, "x1", t->spans[i].x1);
      cJSON_AddNumberToObject(s, "id", t->spans[i].id);
      cJSON_AddItemToArray(sp, s);
    }
    cJSON *ids = cJSON_AddArrayToObject(o, "ids");
    cJSON *zs = cJSON_AddArrayToObject(o, "z");
    cJSON *zv = cJSON_AddArrayToObject(o, "z_view");
    for (int x = 0; x < w; x++) {
      int bg = row->id[x] == ZS_ID_NONE;
      /* the polygon's id, as in the spans; null where no polygon won */
      cJSON_AddItemToArray(ids, bg ? cJSON_CreateNull() : cJSON_CreateNumber(row->id[x]));
      cJSON_AddItemToArray(zs, bg ? cJSON_CreateNull() : cJSON_CreateNumber(row->depth[x] / 4294967296.0));
      cJSON_AddItemToArray(zv, cJSON_CreateNumber(view_z(t, row->depth[x])));
    }
    if (t->shading) {
      cJSON *iv = cJSON_AddArrayToObject(o, "I");
      for (int x = 0; x < w; x++)
        cJSON_AddItemToArray(iv, isnan(t->row_I[x]) ? cJSON_CreateNull() : cJSON_CreateNumber(t->row_I[x]));
    }
    print_json(t, o);
    return;
  }
  FILE *f = t->out;
  fprintf(f, "scanline %d\n  active polygons:", row->y);
  for (int i = 0; i < t->npairs; i++) fprintf(f, " %u (dy %d)", t->pairs[i].id, t->pairs[i].dy);
  fprintf(f, "%s\n  active edges:\n", t->npairs ? "" : " none");
  for (int i = 0; i < t->npairs; i++) {
    const zs_trace_pair *p = &t->pairs[i];
    char xl[64], xr[64], dxl[64], dxr[64];
    fraction(xl, sizeof xl, p->xl, p->reml, p->dl);
    fraction(xr, sizeof xr, p->xr, p->remr, p->dr);
    slope(dxl, sizeof dxl, p->dxl_num, p->dl);
    slope(dxr, sizeof dxr, p->dxr_num, p->dr);
    fprintf(f, "    id %u: xl %s dxl %s dyl %d | xr %s dxr %s dyr %d | zl %.9f dzx %.9f dzy %.9f",
            p->id, xl, dxl, p->dyl, xr, dxr, p->dyr, p->zl_real, p->dzx, p->dzy);
    if (t->shading && t->has_gpair[i]) print_pair_I(f, &t->gpairs[i]);
    fputc('\n', f);
    if (!t->o->brief)
      fprintf(f, "          fixed: first column %lld (rem %lld/%lld), past the last %lld (rem %lld/%lld), "
                 "zl %lld >> %d\n",
              (long long)p->xl, (long long)p->reml, (long long)p->dl, (long long)p->xr,
              (long long)p->remr, (long long)p->dr, (long long)p->zl, 32 + p->zshift);
  }
  fprintf(f, "  spans:");
  for (int i = 0; i < t->nspans; i++)
    fprintf(f, " [%d,%d] id %u", t->spans[i].x0, t->spans[i].x1, t->spans[i].id);
  /* the same numbering as the spans and the tables: the polygon's id, and
   * - where no polygon won */
  fprintf(f, "%s\n  ids:", t->nspans ? "" : " none");
  for (int x = 0; x < w; x++) {
    if (row->id[x] == ZS_ID_NONE) fprintf(f, " -");
    else fprintf(f, " %u", row->id[x]);
  }
  fprintf(f, "\n  z:  ");
  for (int x = 0; x < w; x++) {
    if (row->id[x] == ZS_ID_NONE) fprintf(f, " far");
    else fprintf(f, " %.4f", row->depth[x] / 4294967296.0);
  }
  fprintf(f, "\n  z_view:");
  for (int x = 0; x < w; x++) {
    double z = view_z(t, row->depth[x]);
    fprintf(f, " %.4g", fabs(z) < 1e-6 ? 0.0 : z); /* a depth quantum from 0 */
  }
  if (t->shading) {
    fprintf(f, "\n  I:  ");
    for (int x = 0; x < w; x++) {
      if (isnan(t->row_I[x])) fprintf(f, " -");
      else fprintf(f, " %.2f", t->row_I[x]);
    }
  }
  fprintf(f, "\n");
}

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
static void intensity_panel(const tracer *t, zs_image *im, int x0, int y0, int y) {
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
static void write_picture(tracer *t, int y) {
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

static void on_sink(void *user, const zs_row *row) {
  tracer *t = user;
  if (t->ids) {
    memcpy(t->ids + (size_t)row->y * (size_t)row->width, row->id, (size_t)row->width * 4);
    memcpy(t->depth + (size_t)row->y * (size_t)row->width, row->depth, (size_t)row->width * 4);
  }
  if (t->shading && !t->failed) gouraud_pixels(t, row);
  if (!in_rows(t->o, row->y) || t->failed) return;
  print_row(t, row);
  if (t->o->png_dir) {
    write_picture(t, row->y);
    zs_progress_step(&t->progress, ++t->pictures);
  }
}

/* ---- the plain z-buffer, polygon by polygon ---- */

/* After each polygon drawn, the whole depth grid (view z, as the lecture
 * draws it) and frame buffer (ids; - or null for none). */
static void print_step(tracer *t, zs_device *dev, int step, uint32_t id) {
  const zs_device_config *cfg = zs_device_config_of(dev);
  const uint32_t *depth = zs_device_depth_buffer(dev), *ids = zs_device_id_buffer(dev);
  const int w = cfg->width, h = cfg->height;
  if (t->o->json) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "step", step);
    cJSON_AddNumberToObject(o, "id", id);
    cJSON *zv = cJSON_AddArrayToObject(o, "z_view"), *iv = cJSON_AddArrayToObject(o, "ids");
    for (int i = 0; i < w * h; i++) {
      cJSON_AddItemToArray(zv, cJSON_CreateNumber(view_z(t, depth[i])));
      cJSON_AddItemToArray(iv, ids[i] == ZS_ID_NONE ? cJSON_CreateNull() : cJSON_CreateNumber(ids[i]));
    }
    print_json(t, o);
    return;
  }
  fprintf(t->out, "after polygon %u (step %d): view z, then ids\n", id, step);
  for (int y = 0; y < h; y++) {
    fprintf(t->out, "  ");
    for (int x = 0; x < w; x++) {
      double z = view_z(t, depth[y * w + x]);
      fprintf(t->out, " %6.4g", fabs(z) < 1e-6 ? 0.0 : z);
    }
    fprintf(t->out, "    ");
    for (int x = 0; x < w; x++) {
      uint32_t v = ids[y * w + x];
      if (v == ZS_ID_NONE) fprintf(t->out, " -");
      else fprintf(t->out, " %u", v);
    }
    fputc('\n', t->out);
  }
}

/* Draws the scene one polygon (face of an instance) at a time, in the
 * scene's order, and shows the buffers after each. */
static zs_status zbuffer_steps(tracer *t, zs_device *dev, const zs_scene *s, zs_error *err) {
  const zs_device_config *cfg = zs_device_config_of(dev);
  if (t->o->json) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "width", cfg->width);
    cJSON_AddNumberToObject(o, "height", cfg->height);
    cJSON_AddStringToObject(o, "mode", "zbuffer");
    print_json(t, o);
  }
  int step = 0;
  for (int32_t i = 0; i < s->ninst; i++) {
    const zs_instance *in = &s->inst[i];
    const zs_mesh *m = &s->meshes[in->mesh].mesh;
    for (int32_t f = 0; f < m->nfaces; f++) {
      /* the one face, over the mesh's own arrays */
      zs_mesh one = *m;
      one.face_start = m->face_start + f;
      one.nfaces = 1;
      one.face_rgb = m->face_rgb ? m->face_rgb + f : NULL;
      one.face_id = m->face_id ? m->face_id + f : NULL;
      one.face_material = m->face_material ? m->face_material + f : NULL;
      if (zs_device_draw(dev, &one, in->model, in->id_base, in->rgb, err)) return err->code;
      uint32_t id = in->id_base + (uint32_t)(m->face_id ? m->face_id[f] : f);
      print_step(t, dev, ++step, id);
      if (t->failed) return zs_error_set(err, ZS_ERR_NOMEM, "out of memory while tracing");
    }
  }
  return ZS_OK;
}

/* ---- the command ---- */

static zs_status parse(int argc, char **argv, trace_opts *o, zs_error *err) {
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
static zs_status start_gouraud(tracer *t, const zs_scene *s, const double view[16],
                               const double proj[16], zs_error *err) {
  const int w = t->o->view.width, h = t->o->view.height;
  if (!t->ortho) {
    fprintf(stderr, "zscan trace: note: no Gouraud intensities under a perspective view "
                    "(zscan interpolates perspective-correct); --grid or --ortho shows them\n");
    return ZS_OK;
  }
  if (!zs_gouraud_corners(&t->gouraud, s, view, proj, w, h))
    return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  t->shading = zs_gouraud_any(&t->gouraud);
  if (!t->shading) return ZS_OK;
  t->row_I = malloc((size_t)w * sizeof *t->row_I);
  if (t->o->png_dir) t->inten = malloc((size_t)w * (size_t)h * sizeof *t->inten);
  if (!t->row_I || (t->o->png_dir && !t->inten))
    return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  if (t->gouraud.nbent)
    fprintf(stderr, "zscan trace: note: polygon %u%s: its corners' I are not on one plane; zscan "
                    "shades it as the fan from its first corner, the tables along its edges\n",
            t->gouraud.bent_id, t->gouraud.nbent > 1 ? " (and others)" : "");
  return ZS_OK;
}

int zs_cmd_trace(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, zs_view_opts_usage, NULL)) return 0;
  trace_opts o;
  zs_error err;
  zs_error_clear(&err);
  int parsing = 1; /* a usage error exits 2 (tools/cli.h) */
  zs_scene model;
  zs_device *dev = NULL;
  tracer t;
  memset(&t, 0, sizeof t);
  char *page_data = NULL; /* --html: the JSON trace, gathered */
  size_t page_size = 0;
  FILE *mem = NULL;
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
  double view[16], proj[16];
  if (zs_frame_camera(&model, &o.view.cam, o.view.width, o.view.height, view, proj, &err))
    goto fail;
  zs_device_config cfg = {o.view.width, o.view.height, o.zbuffer ? ZS_ALGO_ZBUFFER : ZS_ALGO_SCANLINE,
                          ZS_SHADE_ID, o.view.cull_back, 1, ZS_BACKGROUND_RGB, 0, 0};
  if (zs_device_create(&cfg, &dev, &err)) goto fail;
  t.o = &o;
  t.out = stdout;
  t.ortho = proj[14] == 0.0;
  t.proj10 = proj[10];
  t.proj11 = proj[11];
  if (!o.zbuffer && zs_gouraud_scene_has(&model) && start_gouraud(&t, &model, view, proj, &err))
    goto fail;
  if (o.png_dir) {
    int first = o.row0 > 0 ? o.row0 : 0;
    int last = o.row1 >= 0 && o.row1 < o.view.height - 1 ? o.row1 : o.view.height - 1;
    zs_progress_start(&t.progress, "trace", "picture", last - first + 1, o.quiet);
    size_t n = (size_t)o.view.width * (size_t)o.view.height;
    t.ids = malloc(n * sizeof *t.ids);
    t.depth = malloc(n * sizeof *t.depth);
    if (!t.ids || !t.depth) {
      zs_error_set(&err, ZS_ERR_NOMEM, "out of memory");
      goto fail;
    }
  }
  zs_trace_observer obs = {on_tables, on_row, &t};
  if (!o.zbuffer) zs_device_set_trace(dev, &obs);
  zs_device_clear(dev);
  zs_device_set_camera(dev, view, proj);
  if (o.html && !(t.out = mem = open_memstream(&page_data, &page_size))) {
    zs_error_set(&err, ZS_ERR_NOMEM, "out of memory");
    goto fail;
  }
  if (o.zbuffer) {
    if (zbuffer_steps(&t, dev, &model, &err) || zs_device_finish(dev, NULL, NULL, &err)) goto fail;
  } else {
    if (zs_frame_draw_scene(dev, &model, &err)) goto fail;
    if (zs_device_finish(dev, on_sink, &t, &err)) goto fail;
  }
  if (t.failed) {
    if (t.err.code) err = t.err;
    else zs_error_set(&err, ZS_ERR_NOMEM, "out of memory while tracing");
    goto fail;
  }
  if (o.html) {
    fclose(mem);
    mem = NULL;
    zs_out page;
    if (zs_out_open(&page, o.html, &err)) {
      zs_out_error_option(&err, "--html");
      goto fail;
    }
    fprintf(page.fp, "%s[%s]%s", zs_cmd_trace_page_head, page_data, zs_cmd_trace_page_tail);
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
  if (mem) fclose(mem);
  free(page_data);
  free(t.pairs);
  free(t.spans);
  free(t.ids);
  free(t.depth);
  free(t.outline);
  free(t.outline_id);
  free(t.gpairs);
  free(t.has_gpair);
  free(t.row_I);
  free(t.inten);
  zs_gouraud_free(&t.gouraud);
  zs_device_destroy(dev);
  if (have_model) zs_scene_free(&model);
  return rc;
}
