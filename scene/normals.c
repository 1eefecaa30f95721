/* zscan scene — normals for the corners that have none (scene/model.h,
 * zs_model_compute_normals).
 *
 * A corner's normal is the sum of the Newell normals of the faces at its
 * position whose planes lie within the crease angle of its own face's,
 * summed in face order, so that corners that see the same faces get the
 * same bits and can share one attribute vertex.  The work is done in
 * three passes over arrays made once: the faces' planes, then the faces
 * and the corners of each position (compressed rows), then the positions
 * in order, each corner against the faces of its position only:
 * O(corners * valence), and O(corners) where a position is smooth (see
 * SMOOTH_MARGIN_DEG).  Nothing in the model changes until every
 * allocation but the new attribute vertices has succeeded.
 */
#include "scene/model.h"
#include "util/exactmath.h"
#include "util/matrix.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Between these creases a position whose faces all lie within half the
 * crease (less this margin) of its first face's is smooth: every pair of
 * its faces passes the crease test, so its corners share one sum computed
 * once (a fan of a thousand triangles costs a thousand additions, not a
 * million).  The margin, far above the rounding of either test, makes
 * sure the shortcut never takes a pair that the exact test would refuse;
 * near 0 and 180 degrees the margin would not cover that rounding. */
#define SMOOTH_MIN_DEG 0.1
#define SMOOTH_MAX_DEG 179.0
#define SMOOTH_MARGIN_DEG 1e-3

/* A face's plane.  n is its Newell normal; s is n times a power of two
 * that brings its largest component into [0.5, 1), so that the crease test
 * on s gives the bits of the test on n (scaling by 2^k commutes with
 * rounding) without overflowing for large faces. */
typedef struct plane {
  double n[3], s[3];
  double len; /* |s| */
  int live;   /* a finite, non-zero area */
} plane;

/* A corner that needs a normal, and its face. */
typedef struct corner {
  int32_t k, f;
} corner;

/* The corners of one position that end alike: one attribute vertex. */
typedef struct group {
  int32_t src; /* the attribute vertex they had, -1 for none */
  float n[3];
  int32_t attr;
} group;

typedef struct ctx {
  zs_model *m;
  double cos_crease, cos_half; /* cos_half: 2 when there is no shortcut */
  int32_t nattrs0;             /* attribute vertices before */
  plane *pl;
  int32_t *fstart, *fend, *fadj; /* faces of each position */
  int32_t *cstart, *cend;        /* needy corners of each position */
  corner *clist;
  int32_t *out;                  /* the new corner_attr */
  uint8_t *claimed;              /* nattrs0: an old vertex given a normal */
  float *claim_n;                /* its normal */
  int32_t nclaimed;
  group *groups;                 /* room for the corners of one position */
} ctx;

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The attribute vertex corner k reads (zscan.h, zs_mesh), -1 for none. */
static int32_t source_attr(const zs_mesh *mesh, int32_t k) {
  int32_t a;
  if (mesh->corner_attr) a = mesh->corner_attr[k];
  else a = mesh->nattrs > 0 && mesh->nattrs == mesh->nverts ? mesh->face_vert[k] : -1;
  return a >= 0 && a < mesh->nattrs ? a : -1;
}

static int lacks_normal(const zs_mesh *mesh, int32_t a) {
  if (a < 0 || !mesh->normal) return 1;
  const float *n = mesh->normal + 3 * (size_t)a;
  return n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f;
}

/* v as a unit vector in float; 0 when it has no direction (zero, or not
 * finite).  The power-of-two scaling first keeps the squares in range. */
static int unit_float(const double v[3], float out[3]) {
  double big = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
  if (!(big > 0.0) || !isfinite(big)) return 0;
  int e;
  frexp(big, &e);
  double x[3];
  for (int i = 0; i < 3; i++) x[i] = ldexp(v[i], -e);
  double len = sqrt(dot3(x, x));
  for (int i = 0; i < 3; i++) out[i] = (float)(x[i] / len);
  return 1;
}

static void face_plane(const zs_mesh *mesh, int32_t f, plane *p) {
  const int32_t *fv = mesh->face_vert + mesh->face_start[f];
  int n = mesh->face_start[f + 1] - mesh->face_start[f];
  p->n[0] = p->n[1] = p->n[2] = 0.0;
  for (int i = 0; i < n; i++)
    zs_newell_add(p->n, mesh->pos + 3 * (size_t)fv[i], mesh->pos + 3 * (size_t)fv[(i + 1) % n]);
  double big = fmax(fabs(p->n[0]), fmax(fabs(p->n[1]), fabs(p->n[2])));
  p->live = big > 0.0 && isfinite(big);
  if (!p->live) return;
  int e;
  frexp(big, &e);
  for (int i = 0; i < 3; i++) p->s[i] = ldexp(p->n[i], -e);
  p->len = sqrt(dot3(p->s, p->s));
}

/* dot(na, nb) >= cos(crease) |na| |nb|, on the scaled normals. */
static int within_crease(const plane *a, const plane *b, double cos_crease) {
  return dot3(a->s, b->s) >= cos_crease * a->len * b->len;
}

/* Counting rows: start[v] .. start[v + 1] has room for count[v] entries
 * (start has n + 1 entries); end[v] starts at start[v]. */
static int rows_from_counts(int32_t *start, int32_t *end, int32_t n) {
  int64_t total = 0;
  for (int32_t v = 0; v < n; v++) {
    int32_t c = start[v];
    start[v] = end[v] = (int32_t)total;
    total += c;
    if (total > INT32_MAX) return 0;
  }
  start[n] = (int32_t)total;
  return 1;
}

/* The faces of each position, each once and in face order, and the
 * corners of live faces that need a normal. */
static int build_rows(ctx *c) {
  const zs_mesh *mesh = &c->m->mesh;
  const int32_t nv = mesh->nverts, total = mesh->face_start[mesh->nfaces];
  for (int32_t k = 0; k < total; k++) c->fstart[mesh->face_vert[k]]++;
  for (int32_t f = 0; f < mesh->nfaces; f++)
    for (int32_t k = mesh->face_start[f]; k < mesh->face_start[f + 1]; k++)
      if (c->pl[f].live && lacks_normal(mesh, source_attr(mesh, k)))
        c->cstart[mesh->face_vert[k]]++;
  if (!rows_from_counts(c->fstart, c->fend, nv) || !rows_from_counts(c->cstart, c->cend, nv))
    return 0;
  for (int32_t f = 0; f < mesh->nfaces; f++) {
    for (int32_t k = mesh->face_start[f]; k < mesh->face_start[f + 1]; k++) {
      int32_t v = mesh->face_vert[k];
      /* a face that comes back to a position is listed there once */
      if (c->fend[v] == c->fstart[v] || c->fadj[c->fend[v] - 1] != f) c->fadj[c->fend[v]++] = f;
      if (c->pl[f].live && lacks_normal(mesh, source_attr(mesh, k)))
        c->clist[c->cend[v]++] = (corner){k, f};
    }
  }
  return 1;
}

/* Whether every face of position v lies within half the crease (less the
 * margin) of the first: then every pair passes the crease test. */
static int smooth_position(const ctx *c, int32_t v) {
  if (c->cos_half > 1.0) return 0;
  const plane *axis = NULL;
  for (int32_t i = c->fstart[v]; i < c->fend[v]; i++) {
    const plane *g = &c->pl[c->fadj[i]];
    if (!g->live) continue;
    if (!axis) axis = g;
    else if (!within_crease(axis, g, c->cos_half)) return 0;
  }
  return 1;
}

/* The sum of the Newell normals at position v of the faces within the
 * crease of face f (all of them when all is set), in face order. */
static void position_sum(const ctx *c, int32_t v, int32_t f, int all, double sum[3]) {
  sum[0] = sum[1] = sum[2] = 0.0;
  const plane *own = &c->pl[f];
  for (int32_t i = c->fstart[v]; i < c->fend[v]; i++) {
    int32_t g = c->fadj[i];
    const plane *pg = &c->pl[g];
    if (!pg->live || (!all && g != f && !within_crease(own, pg, c->cos_crease))) continue;
    for (int j = 0; j < 3; j++) sum[j] += pg->n[j];
  }
}

/* The attribute vertex for corners that had src and end with normal n: src
 * itself the first time, and again for the same normal; else a new one
 * with src's colour and texture coordinates.  -1 when out of memory. */
static int32_t group_attr(ctx *c, int32_t src, const float n[3]) {
  if (src >= 0 && !c->claimed[src]) {
    c->claimed[src] = 1;
    c->nclaimed++;
    memcpy(c->claim_n + 3 * (size_t)src, n, 3 * sizeof *n);
    return src;
  }
  if (src >= 0 && memcmp(c->claim_n + 3 * (size_t)src, n, 3 * sizeof *n) == 0) return src;
  const zs_mesh *mesh = &c->m->mesh;
  uint8_t rgba[4];
  float uv[2];
  /* copied first: adding the vertex may move the arrays */
  if (src >= 0 && mesh->color) memcpy(rgba, mesh->color + 4 * (size_t)src, sizeof rgba);
  if (src >= 0 && mesh->uv) memcpy(uv, mesh->uv + 2 * (size_t)src, sizeof uv);
  return zs_model_add_attr(c->m, n, src >= 0 && mesh->color ? rgba : NULL,
                           src >= 0 && mesh->uv ? uv : NULL);
}

/* Gives the needy corners of position v their attribute vertices. */
static int do_position(ctx *c, int32_t v) {
  if (c->cend[v] == c->cstart[v]) return 1;
  const int all = smooth_position(c, v);
  double smooth_sum[3];
  if (all) position_sum(c, v, c->clist[c->cstart[v]].f, 1, smooth_sum);
  int ng = 0;
  for (int32_t i = c->cstart[v]; i < c->cend[v]; i++) {
    const corner *cn = &c->clist[i];
    double sum[3];
    if (all) memcpy(sum, smooth_sum, sizeof sum);
    else position_sum(c, v, cn->f, 0, sum);
    float n[3];
    /* faces that cancel out (or overflow): the corner's own face */
    if (!unit_float(sum, n)) unit_float(c->pl[cn->f].s, n);
    int32_t src = c->out[cn->k]; /* as it was: the model grows meanwhile */
    int g = 0;
    while (g < ng && !(c->groups[g].src == src && memcmp(c->groups[g].n, n, sizeof n) == 0)) g++;
    if (g == ng) {
      group *gr = &c->groups[ng++];
      gr->src = src;
      memcpy(gr->n, n, sizeof n);
      if ((gr->attr = group_attr(c, src, n)) < 0) return 0;
    }
    c->out[cn->k] = c->groups[g].attr;
  }
  return 1;
}

/* The corners' new attribute vertices in c->out (made here with the
 * capacity of face_vert, as the model grows corner_attr alongside it),
 * new vertices added to the model; the old ones' normals are written by
 * commit.  0 when out of memory. */
static int assign(ctx *c) {
  zs_model *m = c->m;
  const zs_mesh *mesh = &m->mesh;
  const int32_t nv = mesh->nverts, total = mesh->face_start[mesh->nfaces];
  c->out = malloc((size_t)(m->cap_face_verts > total ? m->cap_face_verts : total) * sizeof *c->out);
  c->claimed = calloc((size_t)(c->nattrs0 > 0 ? c->nattrs0 : 1), 1);
  c->claim_n = malloc((size_t)(c->nattrs0 > 0 ? c->nattrs0 : 1) * 3 * sizeof *c->claim_n);
  int32_t most = 1;
  for (int32_t v = 0; v < nv; v++)
    if (c->cend[v] - c->cstart[v] > most) most = c->cend[v] - c->cstart[v];
  c->groups = malloc((size_t)most * sizeof *c->groups);
  if (!c->out || !c->claimed || !c->claim_n || !c->groups) return 0;
  for (int32_t k = 0; k < total; k++) c->out[k] = source_attr(mesh, k);
  for (int32_t v = 0; v < nv; v++)
    if (!do_position(c, v)) return 0;
  return 1;
}

/* Writes the normals of the old vertices that took one and installs the
 * new corner_attr; 0 (the model unchanged) when the normal array cannot
 * be made. */
static int commit(ctx *c) {
  zs_model *m = c->m;
  zs_mesh *mesh = &m->mesh;
  if (!mesh->normal && c->nclaimed > 0) {
    mesh->normal = calloc((size_t)m->cap_attrs * 3, sizeof *mesh->normal);
    if (!mesh->normal) return 0;
  }
  for (int32_t a = 0; a < c->nattrs0; a++)
    if (c->claimed[a])
      memcpy(mesh->normal + 3 * (size_t)a, c->claim_n + 3 * (size_t)a, 3 * sizeof(float));
  free(mesh->corner_attr);
  mesh->corner_attr = c->out;
  c->out = NULL;
  return 1;
}

static void ctx_free(ctx *c) {
  free(c->pl);
  free(c->fstart);
  free(c->fend);
  free(c->fadj);
  free(c->cstart);
  free(c->cend);
  free(c->clist);
  free(c->out);
  free(c->claimed);
  free(c->claim_n);
  free(c->groups);
}

/* The rows of build_rows: counts zeroed, ends and lists to be filled. */
static int alloc_rows(ctx *c) {
  const size_t nv = (size_t)c->m->mesh.nverts;
  const size_t total = (size_t)c->m->mesh.face_start[c->m->mesh.nfaces];
  return (c->fstart = calloc(nv + 1, sizeof *c->fstart)) &&
         (c->fend = malloc(nv * sizeof *c->fend)) && (c->fadj = malloc(total * sizeof *c->fadj)) &&
         (c->cstart = calloc(nv + 1, sizeof *c->cstart)) &&
         (c->cend = malloc(nv * sizeof *c->cend)) && (c->clist = malloc(total * sizeof *c->clist));
}

/* Whether some corner of a live face needs a normal. */
static int any_needy(const ctx *c) {
  const zs_mesh *mesh = &c->m->mesh;
  for (int32_t f = 0; f < mesh->nfaces; f++)
    for (int32_t k = mesh->face_start[f]; c->pl[f].live && k < mesh->face_start[f + 1]; k++)
      if (lacks_normal(mesh, source_attr(mesh, k))) return 1;
  return 0;
}

int zs_model_compute_normals(zs_model *m, double crease_deg) {
  zs_mesh *mesh = &m->mesh;
  if (mesh->nfaces <= 0 || mesh->nverts <= 0) return 1;
  /* No angle between two normals is below 0 or beyond 180 degrees: a
   * crease below (or NaN) smooths nothing, one beyond everything. */
  if (!(crease_deg >= 0.0)) crease_deg = 0.0;
  if (crease_deg > 180.0) crease_deg = 180.0;
  ctx c = {.m = m, .nattrs0 = mesh->nattrs, .cos_half = 2.0};
  double s;
  zs_sincos_deg(crease_deg, &s, &c.cos_crease);
  if (crease_deg >= SMOOTH_MIN_DEG && crease_deg <= SMOOTH_MAX_DEG)
    zs_sincos_deg(crease_deg / 2 - SMOOTH_MARGIN_DEG, &s, &c.cos_half);
  int ok = (c.pl = malloc((size_t)mesh->nfaces * sizeof *c.pl)) != NULL;
  for (int32_t f = 0; ok && f < mesh->nfaces; f++) face_plane(mesh, f, &c.pl[f]);
  ok = ok && (!any_needy(&c) || (alloc_rows(&c) && build_rows(&c) && assign(&c) && commit(&c)));
  ctx_free(&c);
  return ok;
}

/* Whether some face's material (-1 or no array: material 0) has a texture. */
static int any_textured_face(const zs_mesh *mesh) {
  for (int32_t f = 0; mesh->nmaterials > 0 && f < mesh->nfaces; f++) {
    const int32_t k = mesh->face_material && mesh->face_material[f] >= 0 ? mesh->face_material[f] : 0;
    if (mesh->materials[k].base_texture) return 1;
  }
  return 0;
}

int zs_model_complete_normals(zs_model *m) {
  const zs_mesh *mesh = &m->mesh;
  if (!mesh->corner_attr && !any_textured_face(mesh)) return 1;
  return zs_model_compute_normals(m, 60.0);
}
