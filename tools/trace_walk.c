/* zscan tools — the walk of `zscan trace` and of the teaching page's
 * module, traced (trace_walk.h). */
#include "tools/trace_walk.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/frame.h"
#include "lib/frame_camera.h"
#include "lib/image.h"
#include "lib/scene_draw.h"
#include "raster/raster.h"
#include "util/exactmath.h"

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

static int in_rows(const zs_trace_opts *o, int y) { return y >= o->row0 && y <= o->row1; }

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
static void json_edge_I(cJSON *o, const zs_tracer *t, const zs_trace_edge *e, int32_t k) {
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

static cJSON *json_edge(const zs_tracer *t, const zs_trace_edge *e, int32_t k) {
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
static void print_json(zs_tracer *t, cJSON *o) {
  char *s = cJSON_PrintUnformatted(o);
  if (s) fprintf(t->out, t->o->as_array ? "%s%s\n" : "%.0s%s\n", t->lines++ ? "," : "", s);
  else t->failed = 1;
  free(s);
  cJSON_Delete(o);
}

/* The text edge table's I and dI columns (and the line's end). */
static void print_edge_I(const zs_tracer *t, const zs_trace_edge *e, int32_t k) {
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
  zs_tracer *t = user;
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
static void gouraud_pairs(zs_tracer *t, int y) {
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
static void gouraud_pixels(zs_tracer *t, const zs_row *row) {
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
  zs_tracer *t = user;
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

static cJSON *json_pair(const zs_tracer *t, int i) {
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
static double view_z(const zs_tracer *t, uint32_t depth) {
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

static void print_row(zs_tracer *t, const zs_row *row) {
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


/* The id image's row (id + 1, 0 for none), as `zscan render --shade id`
 * writes it, for the frame's hash. */
static void keep_frame_row(zs_tracer *t, const zs_row *row) {
  uint32_t *f = t->frame + (size_t)row->y * (size_t)row->width;
  for (int x = 0; x < row->width; x++) f[x] = row->id[x] == ZS_ID_NONE ? 0 : row->id[x] + 1;
}

/* The plain z-buffer's finished rows: only the frame is kept. */
static void on_frame_row(void *user, const zs_row *row) { keep_frame_row(user, row); }

static void on_sink(void *user, const zs_row *row) {
  zs_tracer *t = user;
  if (t->ids) {
    memcpy(t->ids + (size_t)row->y * (size_t)row->width, row->id, (size_t)row->width * 4);
    memcpy(t->depth + (size_t)row->y * (size_t)row->width, row->depth, (size_t)row->width * 4);
  }
  keep_frame_row(t, row);
  if (t->shading && !t->failed) gouraud_pixels(t, row);
  if (!in_rows(t->o, row->y) || t->failed) return;
  print_row(t, row);
  if (t->picture) t->picture(t, row->y);
}


/* ---- the plain z-buffer, polygon by polygon ---- */

/* After each polygon drawn, the whole depth grid (view z, as the lecture
 * draws it) and frame buffer (ids; - or null for none). */
static void print_step(zs_tracer *t, zs_device *dev, int step, uint32_t id) {
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
static zs_status zbuffer_steps(zs_tracer *t, zs_device *dev, const zs_scene *s, zs_error *err) {
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


static zs_status start_gouraud(zs_tracer *t, const zs_scene *s, const double view[16],
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


/* The last line: the frame's hash and counters, which the teaching page's
 * module and the native command must print alike. */
static void print_frame(zs_tracer *t, const zs_device *dev) {
  const zs_raster_stats *s = zs_device_stats(dev);
  zs_image im = {t->o->view.width, t->o->view.height, t->frame};
  char hash[24];
  snprintf(hash, sizeof hash, "%016llx", (unsigned long long)zs_image_hash(&im));
  cJSON *o = cJSON_CreateObject(), *f = cJSON_AddObjectToObject(o, "frame");
  cJSON_AddStringToObject(f, "image_hash", hash);
  static const char *const names[] = {"polygons_rasterized", "spans", "pixels_tested",
                                      "pixels_written"};
  const double v[] = {(double)s->polygons_rasterized, (double)s->spans, (double)s->pixels_tested,
                      (double)s->pixels_written};
  add_numbers(f, names, v, 4);
  print_json(t, o);
}

zs_status zs_trace_walk(zs_tracer *t, const zs_trace_opts *o, const zs_scene *model, FILE *out,
                        zs_error *err) {
  double view[16], proj[16];
  if (zs_frame_camera(model, &o->view.cam, o->view.width, o->view.height, view, proj, err))
    return err->code;
  zs_device_config cfg = {o->view.width, o->view.height, o->zbuffer ? ZS_ALGO_ZBUFFER : ZS_ALGO_SCANLINE,
                          ZS_SHADE_ID, o->view.cull_back, 1, ZS_BACKGROUND_RGB, 0, 0};
  zs_device *dev = NULL;
  if (zs_device_create(&cfg, &dev, err)) return err->code;
  t->o = o;
  t->out = out;
  t->ortho = proj[14] == 0.0;
  t->proj10 = proj[10];
  t->proj11 = proj[11];
  const size_t n = (size_t)o->view.width * (size_t)o->view.height;
  zs_status st = ZS_OK;
  if (!(t->frame = malloc(n * sizeof *t->frame))) {
    st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
    goto done;
  }
  if (!o->zbuffer && zs_gouraud_scene_has(model) && (st = start_gouraud(t, model, view, proj, err)))
    goto done;
  if (o->png_dir) { /* the frame so far, for the pictures */
    t->ids = malloc(n * sizeof *t->ids);
    t->depth = malloc(n * sizeof *t->depth);
    if (!t->ids || !t->depth) {
      st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
      goto done;
    }
  }
  zs_trace_observer obs = {on_tables, on_row, t};
  if (!o->zbuffer) zs_device_set_trace(dev, &obs);
  zs_device_clear(dev);
  zs_device_set_camera(dev, view, proj);
  if (o->zbuffer) {
    if ((st = zbuffer_steps(t, dev, model, err)) || (st = zs_device_finish(dev, on_frame_row, t, err)))
      goto done;
  } else {
    if ((st = zs_frame_draw_scene(dev, model, err)) || (st = zs_device_finish(dev, on_sink, t, err)))
      goto done;
  }
  if (o->json && !t->failed) print_frame(t, dev);
  if (t->failed) {
    if (t->err.code) *err = t->err;
    else zs_error_set(err, ZS_ERR_NOMEM, "out of memory while tracing");
    st = err->code;
  }
done:
  zs_device_destroy(dev);
  return st;
}

void zs_tracer_free(zs_tracer *t) {
  free(t->pairs);
  free(t->spans);
  free(t->ids);
  free(t->depth);
  free(t->frame);
  free(t->outline);
  free(t->outline_id);
  free(t->gpairs);
  free(t->has_gpair);
  free(t->row_I);
  free(t->inten);
  zs_gouraud_free(&t->gouraud);
}
