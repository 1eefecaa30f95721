/* The Gouraud intensities of the trace (cmd_trace_gouraud.h).
 *
 * An edge from (X0, Y0) to (X1, Y1), 1/256 pixel, with intensities I0 and
 * I1 crosses the centre of row y, Yc = 256 y + 128, at
 *   I = I0 + (I1 - I0) (Yc - Y0) / (Y1 - Y0),
 * and one row down adds 256 (I1 - I0) / (Y1 - Y0): the textbook's Il,
 * dIl (and Ir, dIr).  Across the span I changes by (Ir - Il) / (xr - xl)
 * a column, with xl and xr the exact crossings the walk holds. */
#include "tools/cmd_trace_gouraud.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "raster/setup.h"
#include "util/exactmath.h"
#include "util/matrix.h"

/* ---- exact fractions, with their value in double beside ---- */

/* a * b, a + b, a - b into *out, 0 where they would not fit (in plain C:
 * the builtins call a helper on some 32-bit targets) */
static int mul_ok(int64_t a, int64_t b, int64_t *out) {
  if (a == INT64_MIN || b == INT64_MIN) return 0;
  const int64_t ma = a < 0 ? -a : a, mb = b < 0 ? -b : b;
  if (mb != 0 && ma > INT64_MAX / mb) return 0;
  *out = a * b;
  return 1;
}

static int add_ok(int64_t a, int64_t b, int64_t *out) {
  if ((b > 0 && a > INT64_MAX - b) || (b < 0 && a < INT64_MIN - b)) return 0;
  *out = a + b;
  return 1;
}

static int sub_ok(int64_t a, int64_t b, int64_t *out) {
  return b != INT64_MIN && add_ok(a, -b, out);
}

static zs_q q_inexact(double v) { return (zs_q){0, 1, 0, v}; }

/* n / d, reduced, d > 0 (d != 0; n and d above INT64_MIN) */
static zs_q q_make(int64_t n, int64_t d) {
  if (d < 0) n = -n, d = -d;
  int64_t g = zs_gcd64(n, d);
  if (g > 1) n /= g, d /= g;
  return (zs_q){n, d, 1, (double)n / (double)d};
}

static zs_q q_int(int64_t n) { return q_make(n, 1); }

static int fits(int64_t v) { return v != INT64_MIN; } /* so that -v does too */

static zs_q q_add(zs_q a, zs_q b) {
  int64_t g, x, y, n, d;
  if (!a.exact || !b.exact) return q_inexact(a.v + b.v);
  g = zs_gcd64(a.d, b.d);
  if (!mul_ok(a.n, b.d / g, &x) || !mul_ok(b.n, a.d / g, &y) || !add_ok(x, y, &n) ||
      !mul_ok(a.d, b.d / g, &d) || !fits(n))
    return q_inexact(a.v + b.v);
  return q_make(n, d);
}

static zs_q q_neg(zs_q a) { return a.exact ? (zs_q){-a.n, a.d, 1, -a.v} : q_inexact(-a.v); }

static zs_q q_sub(zs_q a, zs_q b) { return q_add(a, q_neg(b)); }

static zs_q q_mul(zs_q a, zs_q b) {
  int64_t n, d;
  if (!a.exact || !b.exact) return q_inexact(a.v * b.v);
  const int64_t g1 = zs_gcd64(a.n, b.d), g2 = zs_gcd64(b.n, a.d); /* at least 1: d > 0 */
  if (!mul_ok(a.n / g1, b.n / g2, &n) || !mul_ok(a.d / g2, b.d / g1, &d) || !fits(n))
    return q_inexact(a.v * b.v);
  return q_make(n, d);
}

/* a / b, b not 0 */
static zs_q q_div(zs_q a, zs_q b) {
  if (!b.exact) return q_inexact(a.v / b.v);
  return q_mul(a, q_make(b.d, b.n));
}

void zs_q_str(char *buf, size_t size, zs_q q) {
  if (!q.exact) snprintf(buf, size, "%.9g", q.v);
  else if (q.d == 1) snprintf(buf, size, "%lld", (long long)q.n);
  else snprintf(buf, size, "%lld/%lld", (long long)q.n, (long long)q.d);
}

/* ---- the corners ---- */

static int by_id(const void *a, const void *b) {
  const zs_gouraud_corner *p = a, *q = b;
  if (p->id != q->id) return p->id < q->id ? -1 : 1;
  return (p->order > q->order) - (p->order < q->order);
}

/* The corner's snapped place, as set-up snaps it (0: off the window by
 * far, or behind the eye: a face there is clipped, and its edges end
 * where no corner lies). */
static int snap_corner(const double mvp[16], const double pos[3], int width, int height,
                       int32_t *X, int32_t *Y) {
  double c[4], xw, yw;
  zs_mat_apply(mvp, pos, c);
  const zs_clip_vert v = {c[0], c[1], c[2], c[3]};
  if (!(v.w > 0.0)) return 0;
  zs_window_xy(width, height, &v, &xw, &yw);
  if (!(fabs(xw) < 1 << 20 && fabs(yw) < 1 << 20)) return 0;
  const zs_setup_params sp = {.width = width, .height = height};
  zs_snap_vert s;
  zs_snap_vertex(&sp, &v, &s);
  *X = s.x;
  *Y = s.y;
  return 1;
}

/* The (X, Y) cross product of b - a and c - a (0: it would not fit). */
static int cross_xy(const zs_gouraud_corner *a, const zs_gouraud_corner *b,
                    const zs_gouraud_corner *c, int64_t *out) {
  int64_t m0, m1;
  return mul_ok((int64_t)b->X - a->X, (int64_t)c->Y - a->Y, &m0) &&
         mul_ok((int64_t)b->Y - a->Y, (int64_t)c->X - a->X, &m1) && sub_ok(m0, m1, out);
}

/* The determinant of the rows b - a, c - a, k - a in (X, Y, I) (0: it
 * would not fit). */
static int det3(const zs_gouraud_corner *a, const zs_gouraud_corner *b,
                const zs_gouraud_corner *c, const zs_gouraud_corner *k, int64_t *out) {
  /* by the last column: (c x k) Ib - (b x k) Ic + (b x c) Ik, about a */
  int64_t ck, bk, bc, t0, t1, t2;
  return cross_xy(a, c, k, &ck) && cross_xy(a, b, k, &bk) && cross_xy(a, b, c, &bc) &&
         mul_ok(ck, (int64_t)b->I - a->I, &t0) && mul_ok(bk, (int64_t)c->I - a->I, &t1) &&
         mul_ok(bc, (int64_t)k->I - a->I, &t2) && sub_ok(t0, t1, out) && add_ok(*out, t2, out);
}

/* Whether a face's corners c[0 .. n-1] lie on one plane in (X, Y, I):
 * each on the plane of c[0], c[1] and the first corner not in a line with
 * them (taken so for a face in a line, or where a product would not fit). */
static int flat_face(const zs_gouraud_corner *c, int n) {
  int j = 2;
  int64_t v;
  while (j < n && cross_xy(&c[0], &c[1], &c[j], &v) && v == 0) j++;
  for (int k = 2; k < n && j < n; k++)
    if (k != j && det3(&c[0], &c[1], &c[j], &c[k], &v) && v != 0) return 0;
  return 1;
}

/* The corners of one face, appended; its intensity: the colour's red,
 * white where the corner has none (as surface.c takes it). */
static int add_face(zs_gouraud *g, int32_t *cap, const zs_mesh *m, int32_t f, uint32_t id,
                    const double mvp[16], int width, int height) {
  const int32_t s = m->face_start[f], n = m->face_start[f + 1] - s;
  if (g->ncorners + n > *cap) {
    int32_t c = (g->ncorners + n) * 2;
    zs_gouraud_corner *p = realloc(g->corner, (size_t)c * sizeof *p);
    if (!p) return 0;
    g->corner = p;
    *cap = c;
  }
  zs_gouraud_corner *first = &g->corner[g->ncorners];
  int32_t got = 0;
  for (int32_t k = s; k < s + n; k++) {
    const int32_t v = m->face_vert[k];
    if (v < 0 || v >= m->nverts) continue;
    const int32_t a = m->corner_attr ? m->corner_attr[k] : v;
    zs_gouraud_corner c = {id, 0, 0, a >= 0 && a < m->nattrs ? m->color[4 * (size_t)a] : 255,
                           g->ncorners};
    if (!snap_corner(mvp, &m->pos[3 * (size_t)v], width, height, &c.X, &c.Y)) continue;
    g->corner[g->ncorners++] = c;
    got++;
  }
  if (got > 3 && !flat_face(first, got) && !g->nbent++) g->bent_id = id;
  return 1;
}

int zs_gouraud_scene_has(const zs_scene *scene) {
  for (int32_t i = 0; i < scene->ninst; i++)
    if (scene->meshes[scene->inst[i].mesh].mesh.color) return 1;
  return 0;
}

int zs_gouraud_corners(zs_gouraud *g, const zs_scene *scene, const double view[16],
                       const double proj[16], int width, int height) {
  memset(g, 0, sizeof *g);
  int32_t cap = 0;
  for (int32_t i = 0; i < scene->ninst; i++) {
    const zs_instance *in = &scene->inst[i];
    const zs_mesh *m = &scene->meshes[in->mesh].mesh;
    if (!m->color) continue;
    /* the device's own order of products (draw.c, zs_draw_prepare) */
    double mv[16], mvp[16];
    zs_mat_mul(mv, view, in->model);
    zs_mat_mul(mvp, proj, mv);
    for (int32_t f = 0; f < m->nfaces; f++) {
      const uint32_t id = in->id_base + (uint32_t)(m->face_id ? m->face_id[f] : f);
      if (!add_face(g, &cap, m, f, id, mvp, width, height)) return 0;
    }
  }
  if (g->ncorners) qsort(g->corner, (size_t)g->ncorners, sizeof *g->corner, by_id);
  return 1;
}

/* ---- the edges ---- */

/* The intensity of polygon id's corner at (X, Y), -1 for none. */
static int32_t corner_I(const zs_gouraud *g, uint32_t id, int32_t X, int32_t Y) {
  int32_t lo = 0, hi = g->ncorners;
  while (lo < hi) { /* the first corner of id */
    int32_t mid = lo + (hi - lo) / 2;
    if (g->corner[mid].id < id) lo = mid + 1;
    else hi = mid;
  }
  for (int32_t i = lo; i < g->ncorners && g->corner[i].id == id; i++)
    if (g->corner[i].X == X && g->corner[i].Y == Y) return g->corner[i].I;
  return -1;
}

int zs_gouraud_edges(zs_gouraud *g, const zs_trace_poly *polys, int npolys,
                     const zs_trace_edge *edges, int nedges) {
  free(g->edges);
  free(g->edge_I);
  g->nedges = 0;
  g->edges = malloc((size_t)(nedges ? nedges : 1) * sizeof *g->edges);
  g->edge_I = malloc((size_t)(nedges ? nedges : 1) * sizeof *g->edge_I);
  if (!g->edges || !g->edge_I) return 0;
  if (nedges) memcpy(g->edges, edges, (size_t)nedges * sizeof *edges);
  g->nedges = nedges;
  for (int i = 0; i < nedges; i++) {
    const zs_trace_edge *e = &edges[i];
    g->edge_I[i][0] = corner_I(g, e->id, e->X0, e->Y0);
    g->edge_I[i][1] = corner_I(g, e->id, e->X1, e->Y1);
  }
  /* a polygon with an end of no corner (clipped) has none at all */
  for (int p = 0; p < npolys; p++) {
    const int32_t e0 = polys[p].first_edge, e1 = e0 + polys[p].nleft + polys[p].nright;
    int whole = 1;
    for (int32_t k = e0; k < e1 && k < nedges; k++)
      whole &= g->edge_I[k][0] >= 0 && g->edge_I[k][1] >= 0;
    for (int32_t k = e0; k < e1 && k < nedges && !whole; k++) g->edge_I[k][0] = g->edge_I[k][1] = -1;
  }
  return 1;
}

int zs_gouraud_edge_at(const zs_gouraud *g, int32_t k, int32_t y, zs_q *I, zs_q *dI) {
  if (k < 0 || k >= g->nedges || g->edge_I[k][0] < 0 || g->edge_I[k][1] < 0) return 0;
  const zs_trace_edge *e = &g->edges[k];
  const int64_t I0 = g->edge_I[k][0], dI01 = (int64_t)g->edge_I[k][1] - I0;
  const int64_t D = (int64_t)e->Y1 - e->Y0, down = 256 * (int64_t)y + 128 - e->Y0;
  if (D <= 0) return 0;
  *I = q_make(I0 * D + dI01 * down, D);
  *dI = q_make(256 * dI01, D);
  return 1;
}

/* The walk's exact crossing x - rem / d, pixel-centre units. */
static zs_q crossing(int64_t x, int64_t rem, int64_t d) {
  int64_t xd, n;
  if (!mul_ok(x, d, &xd) || !sub_ok(xd, rem, &n) || !fits(n))
    return q_inexact((double)x - (double)rem / (double)d);
  return q_make(n, d);
}

int zs_gouraud_pair_of(const zs_gouraud *g, const zs_trace_pair *p, int32_t y,
                       zs_gouraud_pair *out) {
  if (!zs_gouraud_edge_at(g, p->left, y, &out->Il, &out->dIl) ||
      !zs_gouraud_edge_at(g, p->right, y, &out->Ir, &out->dIr))
    return 0;
  const zs_q width = q_sub(crossing(p->xr, p->remr, p->dr), crossing(p->xl, p->reml, p->dl));
  out->has_dIx = width.exact ? width.n != 0 : width.v != 0.0;
  out->dIx = out->has_dIx ? q_div(q_sub(out->Ir, out->Il), width) : q_int(0);
  return 1;
}

double zs_gouraud_at(const zs_gouraud_pair *gp, const zs_trace_pair *p, int64_t x) {
  const zs_q off = q_sub(q_int(x), crossing(p->xl, p->reml, p->dl));
  return q_add(gp->Il, q_mul(off, gp->dIx)).v;
}

void zs_gouraud_free(zs_gouraud *g) {
  free(g->corner);
  free(g->edges);
  free(g->edge_I);
  memset(g, 0, sizeof *g);
}
