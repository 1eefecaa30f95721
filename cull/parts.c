/* Tighter bounds for the occlusion queries of objects (parts.h). */
#include "cull/parts.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cull/box.h"
#include "util/grow.h"

/* A mesh's parts: the vertices of each (a vertex of faces in two parts is
 * in both), as one list with offsets. */
typedef struct mesh_parts {
  int done;
  int n;                          /* parts with faces */
  int32_t start[ZS_PARTS_MAX + 1];
  int32_t *vert;
} mesh_parts;

/* An instance's boxes (lo[0 .. n-1], then hi[0 .. n-1], in one block of
 * its mesh's parts), and its placement when they were made. */
typedef struct inst_parts {
  int n;                          /* 0: not made yet */
  int cap;                        /* boxes box holds room for, lo and hi */
  double at_model[16];
  double (*box)[3];
} inst_parts;

struct zs_parts {
  mesh_parts *mesh;
  int32_t cap_mesh;
  inst_parts *inst;
  int32_t cap_inst;
};

zs_parts *zs_parts_create(void) { return calloc(1, sizeof(zs_parts)); }

void zs_parts_destroy(zs_parts *p) {
  if (!p) return;
  for (int32_t m = 0; m < p->cap_mesh; m++) free(p->mesh[m].vert);
  for (int32_t i = 0; i < p->cap_inst; i++) free(p->inst[i].box);
  free(p->mesh);
  free(p->inst);
  free(p);
}

/* A group of faces: face[first .. first + count - 1] of the split order. */
typedef struct group {
  int32_t first, count;
  zs_box box;
  /* its best split: faces whose centroid bin along axis is <= bin go
   * first; gain is the volume it saves */
  int axis, bin;
  double gain;
} group;

enum { BINS = 16 };

static int bin_of(const double *centroid, const zs_box *cb, int axis) {
  double w = cb->hi[axis] - cb->lo[axis];
  int b = w > 0.0 ? (int)((centroid[axis] - cb->lo[axis]) / w * BINS) : 0;
  return b < 0 ? 0 : b >= BINS ? BINS - 1 : b;
}

/* The bounds of the centroids of g's faces. */
static zs_box centroid_bounds(const group *g, const int32_t *face, const double *centroid) {
  zs_box cb = zs_box_empty();
  for (int32_t j = 0; j < g->count; j++) {
    const double *c = centroid + 3 * face[g->first + j];
    zs_box_add(&cb, c, c);
  }
  return cb;
}

/* The split of g that leaves the least volume, binned along each axis. */
static void best_split(group *g, const int32_t *face, const double *centroid, const zs_box *fbox) {
  g->gain = 0.0;
  if (g->count < 2) return;
  zs_box cb = centroid_bounds(g, face, centroid);
  for (int a = 0; a < 3; a++) {
    zs_box bin[BINS], left[BINS];
    int32_t n[BINS] = {0};
    for (int b = 0; b < BINS; b++) bin[b] = zs_box_empty();
    for (int32_t j = 0; j < g->count; j++) {
      int32_t f = face[g->first + j];
      int b = bin_of(centroid + 3 * f, &cb, a);
      zs_box_add_box(&bin[b], &fbox[f]);
      n[b]++;
    }
    left[0] = bin[0];
    for (int b = 1; b < BINS; b++) left[b] = left[b - 1], zs_box_add_box(&left[b], &bin[b]);
    zs_box right = zs_box_empty();
    int32_t nright = 0;
    for (int b = BINS - 1; b > 0; b--) { /* split after bin b - 1 */
      zs_box_add_box(&right, &bin[b]);
      nright += n[b];
      if (nright == 0 || nright == g->count) continue;
      double gain = zs_box_volume(&g->box) - zs_box_volume(&left[b - 1]) - zs_box_volume(&right);
      if (gain > g->gain) g->gain = gain, g->axis = a, g->bin = b - 1;
    }
  }
}

/* Splits the faces of m into at most one group per ZS_FACES_PER_PART
 * faces (and ZS_PARTS_MAX), each time splitting the group whose split
 * saves the most volume, while a split saves at least 0.2 % of the mesh's
 * box. */
static int make_mesh_parts(mesh_parts *mp, const zs_mesh *m) {
  int32_t nf = m->nfaces > 0 ? m->nfaces : 1;
  int32_t *face = malloc((size_t)nf * sizeof *face);
  double *centroid = malloc((size_t)nf * 3 * sizeof *centroid);
  zs_box *fbox = malloc((size_t)nf * sizeof *fbox);
  int32_t *seen = malloc((size_t)(m->nverts > 0 ? m->nverts : 1) * sizeof *seen);
  int32_t total = m->face_start[m->nfaces];
  mp->vert = malloc((size_t)(total > 0 ? total : 1) * sizeof *mp->vert);
  if (!face || !centroid || !fbox || !seen || !mp->vert) {
    free(face), free(centroid), free(fbox), free(seen);
    return 0;
  }
  group g[ZS_PARTS_MAX];
  g[0] = (group){0, m->nfaces, zs_box_empty(), 0, 0, 0.0};
  for (int32_t f = 0; f < m->nfaces; f++) {
    face[f] = f;
    fbox[f] = zs_box_empty();
    int32_t a = m->face_start[f], b = m->face_start[f + 1];
    for (int k = 0; k < 3; k++) centroid[3 * f + k] = 0.0;
    for (int32_t j = a; j < b; j++) {
      const double *p = m->pos + 3 * m->face_vert[j];
      zs_box_add(&fbox[f], p, p);
      for (int k = 0; k < 3; k++) centroid[3 * f + k] += p[k] / (b - a);
    }
    zs_box_add_box(&g[0].box, &fbox[f]);
  }
  int ng = 1;
  const double worth = 0.002 * zs_box_volume(&g[0].box);
  const int most = m->nfaces / ZS_FACES_PER_PART < ZS_PARTS_MAX ? m->nfaces / ZS_FACES_PER_PART
                                                                  : ZS_PARTS_MAX;
  if (most > 1) best_split(&g[0], face, centroid, fbox);
  while (ng < most) {
    int best = 0;
    for (int i = 1; i < ng; i++)
      if (g[i].gain > g[best].gain) best = i;
    if (!(g[best].gain > worth)) break;
    /* partition: the faces of the low bins first */
    group *s = &g[best];
    zs_box cb = centroid_bounds(s, face, centroid);
    int32_t lo = s->first, hi = s->first + s->count - 1;
    while (lo <= hi) {
      if (bin_of(centroid + 3 * face[lo], &cb, s->axis) <= s->bin) lo++;
      else {
        int32_t t = face[lo];
        face[lo] = face[hi], face[hi--] = t;
      }
    }
    group a = {s->first, lo - s->first, zs_box_empty(), 0, 0, 0.0};
    group b = {lo, s->first + s->count - lo, zs_box_empty(), 0, 0, 0.0};
    for (int32_t j = 0; j < a.count; j++) zs_box_add_box(&a.box, &fbox[face[a.first + j]]);
    for (int32_t j = 0; j < b.count; j++) zs_box_add_box(&b.box, &fbox[face[b.first + j]]);
    best_split(&a, face, centroid, fbox);
    best_split(&b, face, centroid, fbox);
    g[best] = a;
    g[ng++] = b;
  }
  /* each group's vertices, once each */
  for (int32_t v = 0; v < m->nverts; v++) seen[v] = -1;
  int32_t n = 0;
  mp->n = 0;
  for (int i = 0; i < ng; i++) {
    if (g[i].count == 0) continue;
    mp->start[mp->n] = n;
    for (int32_t j = 0; j < g[i].count; j++) {
      int32_t f = face[g[i].first + j];
      for (int32_t k = m->face_start[f]; k < m->face_start[f + 1]; k++)
        if (seen[m->face_vert[k]] != i) {
          seen[m->face_vert[k]] = i;
          mp->vert[n++] = m->face_vert[k];
        }
    }
    mp->n++;
  }
  mp->start[mp->n] = n;
  mp->done = 1;
  free(face), free(centroid), free(fbox), free(seen);
  return 1;
}


/* The world boxes of the parts of instance in, transformed as
 * zs_scene_instance_bounds transforms its vertices. */
static int make_inst_parts(inst_parts *ip, const mesh_parts *mp, const zs_mesh *m,
                           const zs_instance *in) {
  const double *t = in->model;
  const int n = mp->n < 2 ? 1 : mp->n;
  if (n > ip->cap) { /* an instance not seen before */
    double(*box)[3] = realloc(ip->box, (size_t)(2 * n) * sizeof *box);
    if (!box) return 0;
    ip->box = box;
    ip->cap = n;
  }
  double(*lo)[3] = ip->box, (*hi)[3] = ip->box + n;
  for (int k = 0; k < mp->n; k++) {
    for (int32_t j = mp->start[k]; j < mp->start[k + 1]; j++) {
      const double *p = m->pos + 3 * (size_t)mp->vert[j];
      for (int r = 0; r < 3; r++) {
        double w = t[4 * r] * p[0] + t[4 * r + 1] * p[1] + t[4 * r + 2] * p[2] + t[4 * r + 3];
        if (j == mp->start[k] || w < lo[k][r]) lo[k][r] = w;
        if (j == mp->start[k] || w > hi[k][r]) hi[k][r] = w;
      }
    }
  }
  ip->n = n;
  if (mp->n < 2) { /* one part, or none: the object's own box */
    memcpy(lo[0], in->lo, sizeof lo[0]);
    memcpy(hi[0], in->hi, sizeof hi[0]);
  }
  memcpy(ip->at_model, in->model, sizeof ip->at_model);
  return 1;
}

int zs_parts_of(zs_parts *p, const zs_scene *s, int32_t i, const double (**lo)[3],
                const double (**hi)[3], int *n) {
  int32_t old = p->cap_inst;
  if (!zs_grow((void **)&p->inst, &p->cap_inst, s->ninst, sizeof *p->inst)) return 0;
  memset(p->inst + old, 0, (size_t)(p->cap_inst - old) * sizeof *p->inst);
  old = p->cap_mesh;
  if (!zs_grow((void **)&p->mesh, &p->cap_mesh, s->nmeshes, sizeof *p->mesh)) return 0;
  memset(p->mesh + old, 0, (size_t)(p->cap_mesh - old) * sizeof *p->mesh);
  const zs_instance *in = &s->inst[i];
  const zs_mesh *m = &s->meshes[in->mesh].mesh;
  mesh_parts *mp = &p->mesh[in->mesh];
  if (!mp->done && !make_mesh_parts(mp, m)) return 0;
  inst_parts *ip = &p->inst[i];
  if ((ip->n == 0 || memcmp(ip->at_model, in->model, sizeof ip->at_model) != 0) &&
      !make_inst_parts(ip, mp, m, in))
    return 0;
  *lo = (const double(*)[3])ip->box;
  *hi = (const double(*)[3])(ip->box + ip->n);
  *n = ip->n;
  return 1;
}
