/* zscan scene — the model: growable mesh arrays, and the splitting of
 * concave and non-planar polygons into pieces the rasterizer can draw.
 *
 * Every array grows geometrically (zs_grow: doubling), so n appends copy O(n)
 * elements in all.  A polygon reserves room for its worst case before it
 * writes anything, so an allocation failure leaves the model as it was.
 */
#include "scene/model.h"
#include "util/grow.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A non-planar polygon is one with a vertex farther than this fraction of
 * its diameter from its Newell plane.  1e-5 keeps whole the quads that are
 * planar but for the rounding of a text file (six decimals in an OBJ),
 * while a curved patch quad, bent by far more, is split so that its depth
 * follows its two triangles as any other renderer would draw them. */
#define PLANARITY_TOLERANCE 1e-5

/* ---- storage ---------------------------------------------------------- */

void zs_model_init(zs_model *m) {
  static const zs_model empty; /* static: all counts 0, all pointers NULL */
  *m = empty;
}

void zs_model_free(zs_model *m) {
  if (!m) return;
  free(m->mesh.pos);
  free(m->mesh.face_start);
  free(m->mesh.face_vert);
  free(m->mesh.face_rgb);
  free(m->mesh.face_id);
  free(m->face_object);
  for (int32_t i = 0; i < m->nobjects; i++) free(m->object_names[i]);
  free(m->object_names);
  free(m->mesh.corner_attr);
  free(m->mesh.normal);
  free(m->mesh.color);
  free(m->mesh.uv);
  free(m->mesh.face_material);
  free(m->mesh.line_vert);
  free(m->mesh.line_rgb);
  free(m->mesh.point_vert);
  free(m->mesh.point_rgb);
  free(m->materials);
  for (int32_t i = 0; i < m->ntextures; i++) zs_texture_destroy(m->textures[i]);
  free(m->textures);
  zs_notes_free(&m->notes);
  zs_model_init(m);
}

/* ---- notes ------------------------------------------------------------ */

/* Room for more bytes and the NUL after them. */
static int notes_reserve(zs_notes *n, int64_t more) {
  return zs_grow((void **)&n->text, &n->cap, (int64_t)n->len + more + 1, 1);
}

int zs_notes_add(zs_notes *n, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int k = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (k < 0 || !notes_reserve(n, (int64_t)k + 1)) return 0;
  char *line = n->text + n->len;
  va_start(ap, fmt);
  vsnprintf(line, (size_t)k + 1, fmt, ap);
  va_end(ap);
  for (int i = 0; i < k; i++)
    if ((unsigned char)line[i] < 0x20 || line[i] == 0x7f) line[i] = ' ';
  line[k] = '\n';
  line[k + 1] = '\0';
  n->len += k + 1;
  return 1;
}

int zs_notes_move(zs_notes *to, zs_notes *from, const char *prefix) {
  if (from->len == 0) {
    zs_notes_free(from);
    return 1;
  }
  if (!prefix && to->len == 0) { /* the whole buffer changes hands */
    zs_notes_free(to);
    *to = *from;
    *from = (zs_notes){NULL, 0, 0};
    return 1;
  }
  const size_t plen = prefix ? strlen(prefix) : 0;
  int64_t lines = 0;
  for (int32_t i = 0; i < from->len; i++) lines += from->text[i] == '\n';
  if ((int64_t)plen * lines > INT32_MAX || !notes_reserve(to, from->len + (int64_t)plen * lines))
    return 0;
  for (const char *s = from->text, *end = from->text + from->len; s < end;) {
    const char *nl = memchr(s, '\n', (size_t)(end - s));
    size_t k = (size_t)(nl - s) + 1; /* every note ends in '\n' */
    memcpy(to->text + to->len, prefix ? prefix : "", plen);
    memcpy(to->text + to->len + plen, s, k);
    to->len += (int32_t)(plen + k);
    s += k;
  }
  to->text[to->len] = '\0';
  zs_notes_free(from);
  return 1;
}

void zs_notes_free(zs_notes *n) {
  free(n->text);
  *n = (zs_notes){NULL, 0, 0};
}

static int reserve_vertices(zs_model *m, int64_t need) {
  return zs_grow((void **)&m->mesh.pos, &m->cap_verts, need, 3 * sizeof *m->mesh.pos);
}

/* Makes room for nfaces faces using nface_verts indices in all.  The
 * per-face arrays share cap_faces, which is raised only once all of them
 * have grown; an array that grew before a later one failed is merely
 * larger than needed. */
static int reserve_faces(zs_model *m, int64_t nfaces, int64_t nface_verts) {
  zs_mesh *mesh = &m->mesh;
  if (nfaces > m->cap_faces) {
    /* Each array grows from cap_faces by the same rule to the same
     * capacity cap; face_start has one entry more, the end of the last
     * face. */
    int32_t cap = m->cap_faces, c_id = cap, c_obj = cap, c_mat = cap;
    if (!zs_grow((void **)&mesh->face_rgb, &cap, nfaces, sizeof *mesh->face_rgb) ||
        !zs_grow((void **)&mesh->face_id, &c_id, nfaces, sizeof *mesh->face_id) ||
        !zs_grow((void **)&m->face_object, &c_obj, nfaces, sizeof *m->face_object) ||
        (mesh->face_material &&
         !zs_grow((void **)&mesh->face_material, &c_mat, nfaces, sizeof *mesh->face_material)))
      return 0;
    int32_t *start = realloc(mesh->face_start, ((size_t)cap + 1) * sizeof *start);
    if (!start) return 0;
    if (!mesh->face_start) start[0] = 0;
    mesh->face_start = start;
    m->cap_faces = cap;
  }
  int32_t c_attr = m->cap_face_verts;
  if (mesh->corner_attr &&
      !zs_grow((void **)&mesh->corner_attr, &c_attr, nface_verts, sizeof *mesh->corner_attr))
    return 0;
  return zs_grow((void **)&mesh->face_vert, &m->cap_face_verts, nface_verts,
                 sizeof *mesh->face_vert);
}

/* The attribute vertex of the polygon being added at position v. */
static int32_t corner_attr_of(const zs_model *m, int32_t v) {
  if (!m->cur_attr) return -1;
  for (int i = 0; i < m->cur_n; i++)
    if (m->cur_idx[i] == v) return m->cur_attr[i];
  return -1;
}

/* The number of vertex indices the faces use so far. */
static int32_t face_vert_count(const zs_model *m) {
  return m->mesh.nfaces > 0 ? m->mesh.face_start[m->mesh.nfaces] : 0;
}

/* Appends one face; the room must have been reserved. */
static void append_face(zs_model *m, const int32_t *v, int n, uint32_t rgb,
                        int32_t id, int32_t obj) {
  zs_mesh *mesh = &m->mesh;
  int32_t f = mesh->nfaces;
  int32_t start = face_vert_count(m);
  memcpy(mesh->face_vert + start, v, (size_t)n * sizeof *v);
  if (mesh->corner_attr)
    for (int i = 0; i < n; i++) mesh->corner_attr[start + i] = corner_attr_of(m, v[i]);
  if (mesh->face_material) mesh->face_material[f] = m->cur_material;
  mesh->face_start[f] = start;
  mesh->face_start[f + 1] = start + n;
  mesh->face_rgb[f] = rgb;
  mesh->face_id[f] = id;
  m->face_object[f] = obj;
  mesh->nfaces = f + 1;
}

int32_t zs_model_add_vertex(zs_model *m, double x, double y, double z) {
  if (!reserve_vertices(m, (int64_t)m->mesh.nverts + 1)) return -1;
  int32_t i = m->mesh.nverts++;
  double *p = m->mesh.pos + 3 * (size_t)i;
  p[0] = x;
  p[1] = y;
  p[2] = z;
  return i;
}

int32_t zs_model_object(zs_model *m, const char *name) {
  if (!name) return -1;
  /* Newest first: a file that switches objects mostly returns to a recent
   * one.  The header has no room for an index, so the search is linear. */
  for (int32_t i = m->nobjects - 1; i >= 0; i--)
    if (strcmp(m->object_names[i], name) == 0) return i;
  if (!zs_grow((void **)&m->object_names, &m->cap_objects, (int64_t)m->nobjects + 1,
               sizeof *m->object_names))
    return -1;
  char *copy = strdup(name);
  if (!copy) return -1;
  m->object_names[m->nobjects] = copy;
  return m->nobjects++;
}

int zs_model_bounds(const zs_model *m, double lo[3], double hi[3]) {
  if (m->mesh.nverts <= 0) return 0;
  for (int k = 0; k < 3; k++) lo[k] = hi[k] = m->mesh.pos[k];
  for (int32_t i = 1; i < m->mesh.nverts; i++) {
    const double *p = m->mesh.pos + 3 * (size_t)i;
    for (int k = 0; k < 3; k++) {
      if (p[k] < lo[k]) lo[k] = p[k];
      if (p[k] > hi[k]) hi[k] = p[k];
    }
  }
  return 1;
}

/* ---- polygon geometry ------------------------------------------------- */

/* Arrays of these are passed without const: before C23, a vec3 * does not
 * convert to a const vec3 * implicitly. */
typedef double vec2[2];
typedef double vec3[3];

/* The cross product of the 2D edges a->b and b->c: > 0 for a left turn. */
static double turn(const double *a, const double *b, const double *c) {
  return (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
}

/* p is relative to the centroid, so the plane of nrm through the centroid
 * passes through the origin. */
static int is_planar(vec3 *p, int n, const vec3 nrm) {
  double len = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
  double diameter = 0.0, far = 0.0;
  for (int i = 0; i < n; i++) {
    double d = fabs(p[i][0] * nrm[0] + p[i][1] * nrm[1] + p[i][2] * nrm[2]);
    if (d / len > far) far = d / len;
    for (int j = i + 1; j < n; j++) {
      double dx = p[i][0] - p[j][0], dy = p[i][1] - p[j][1],
             dz = p[i][2] - p[j][2];
      double dist = sqrt(dx * dx + dy * dy + dz * dz);
      if (dist > diameter) diameter = dist;
    }
  }
  return far <= PLANARITY_TOLERANCE * diameter;
}

/* Drops the axis along which the normal is largest, keeping the other two
 * in cyclic order (and swapping them when that component is negative), so
 * the projected polygon winds counter-clockwise with a positive area. */
static void project(vec3 *p, int n, const vec3 nrm, vec2 *q) {
  int k = 0;
  for (int a = 1; a < 3; a++)
    if (fabs(nrm[a]) > fabs(nrm[k])) k = a;
  int i = (k + 1) % 3, j = (k + 2) % 3;
  if (nrm[k] < 0) {
    int t = i;
    i = j;
    j = t;
  }
  for (int v = 0; v < n; v++) {
    q[v][0] = p[v][i];
    q[v][1] = p[v][j];
  }
}

/* Sign changes of a cyclic sequence, zeros skipped. */
static int sign_changes(const double *d, int n) {
  int changes = 0, first = 0, last = 0;
  for (int i = 0; i < n; i++) {
    int s = (d[i] > 0) - (d[i] < 0);
    if (s == 0) continue;
    if (first == 0) first = s;
    else if (s != last) changes++;
    last = s;
  }
  if (first != 0 && last != first) changes++;
  return changes;
}

/* Whether the counter-clockwise polygon q is convex: no right turn, no
 * edge doubling back, and a boundary that turns around only once.  Left
 * turns alone would accept a pentagram; turning once means the edge
 * directions change sign at most twice in x and twice in y. */
static int is_convex(vec2 *q, int n, double *dx, double *dy) {
  for (int i = 0; i < n; i++) {
    const double *a = q[i], *b = q[(i + 1) % n], *c = q[(i + 2) % n];
    double t = turn(a, b, c);
    if (t < 0) return 0;
    double dot = (b[0] - a[0]) * (c[0] - b[0]) + (b[1] - a[1]) * (c[1] - b[1]);
    if (t == 0 && dot < 0) return 0;
    dx[i] = b[0] - a[0];
    dy[i] = b[1] - a[1];
  }
  return sign_changes(dx, n) <= 2 && sign_changes(dy, n) <= 2;
}

/* Whether p lies in the counter-clockwise triangle abc or on its edges. */
static int in_triangle(const double *p, const double *a, const double *b,
                       const double *c) {
  return turn(a, b, p) >= 0 && turn(b, c, p) >= 0 && turn(c, a, p) >= 0;
}

/* ---- splitting -------------------------------------------------------- */

static void add_fan(zs_model *m, const int32_t *v, int n, uint32_t rgb,
                    int32_t id, int32_t obj) {
  for (int i = 1; i + 1 < n; i++) {
    int32_t tri[3] = {v[0], v[i], v[i + 1]};
    append_face(m, tri, 3, rgb, id, obj);
  }
}

/* Ear clipping of the counter-clockwise projection q.  Vertex b, between a
 * and c in what is left of the polygon, is an ear when it turns left and no
 * other remaining vertex lies in triangle abc; it suffices to test the
 * vertices that do not turn left, since if any vertex is inside, one of
 * those is.  Triangles keep the polygon's vertex order, so its winding.
 * A polygon that intersects itself may have no ear left: then the first
 * vertex that turns left (or, failing that, any vertex) is cut anyway, so
 * the loop always ends with n - 2 triangles. */
static void add_ear_clipped(zs_model *m, const int32_t *v, vec2 *q, int *prev, int *next,
                            int n, uint32_t rgb, int32_t id, int32_t obj) {
  for (int i = 0; i < n; i++) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  int left = n, b = 0, misses = 0;
  while (left > 3) {
    int a = prev[b], c = next[b];
    int ear = turn(q[a], q[b], q[c]) > 0;
    for (int p = next[c]; ear && p != a; p = next[p])
      if (turn(q[prev[p]], q[p], q[next[p]]) <= 0 &&
          in_triangle(q[p], q[a], q[b], q[c]))
        ear = 0;
    if (!ear && ++misses < left) {
      b = c;
      continue;
    }
    if (!ear) {
      /* A whole round without an ear: settle for a convex vertex. */
      for (int i = 0, t = b; i < left; i++, t = next[t]) {
        if (turn(q[prev[t]], q[t], q[next[t]]) > 0) {
          b = t;
          break;
        }
      }
      a = prev[b];
      c = next[b];
    }
    int32_t tri[3] = {v[a], v[b], v[c]};
    append_face(m, tri, 3, rgb, id, obj);
    next[a] = c;
    prev[c] = a;
    left--;
    misses = 0;
    b = c;
  }
  int32_t tri[3] = {v[prev[b]], v[b], v[next[b]]};
  append_face(m, tri, 3, rgb, id, obj);
}

/* A convex planar polygon of any size, as faces of at most
 * ZS_MAX_POLY_VERTS corners: a fan of convex pieces around v[0], each
 * sharing an edge with the next.  The pieces' edges are the same snapped
 * points, so with the fill rule they cover exactly the polygon's pixels. */
static void add_convex(zs_model *m, const int32_t *v, int n, uint32_t rgb, int32_t id,
                       int32_t obj) {
  if (n <= ZS_MAX_POLY_VERTS) {
    append_face(m, v, n, rgb, id, obj);
    return;
  }
  int32_t piece[ZS_MAX_POLY_VERTS];
  piece[0] = v[0];
  for (int first = 1; first + 1 < n; first += ZS_MAX_POLY_VERTS - 2) {
    int k = n - first < ZS_MAX_POLY_VERTS - 1 ? n - first : ZS_MAX_POLY_VERTS - 1;
    memcpy(piece + 1, v + first, (size_t)k * sizeof *piece);
    append_face(m, piece, k + 1, rgb, id, obj);
  }
}

/* Room for splitting one polygon of n corners: on the stack up to
 * ZS_MAX_POLY_VERTS, on the heap beyond. */
typedef struct split_scratch {
  int32_t *v;
  vec3 *p;
  vec2 *q;
  double *dx, *dy;
  int *prev, *next;
  void *heap;
} split_scratch;

enum {
  SCRATCH_BYTES_PER_CORNER = sizeof(int32_t) + sizeof(vec3) + sizeof(vec2) +
                             2 * sizeof(double) + 2 * sizeof(int)
};

static int scratch_take(split_scratch *s, void *stack, int n) {
  /* the largest element types first, so every array stays aligned */
  char *b = n <= ZS_MAX_POLY_VERTS ? stack : malloc((size_t)n * SCRATCH_BYTES_PER_CORNER);
  s->heap = b == stack ? NULL : b;
  if (!b) return 0;
  s->p = (vec3 *)b;
  b += (size_t)n * sizeof(vec3);
  s->q = (vec2 *)b;
  b += (size_t)n * sizeof(vec2);
  s->dx = (double *)b; /* dx and dy: 2n doubles */
  s->dy = s->dx + n;
  b += 2 * (size_t)n * sizeof(double);
  s->v = (int32_t *)b;
  b += (size_t)n * sizeof(int32_t);
  s->prev = (int *)b; /* prev and next: 2n ints */
  s->next = s->prev + n;
  return 1;
}

/* Stores the polygon v (n >= 3, no repeated consecutive index) whole when
 * it is planar and convex (in pieces when it has more corners than a face
 * may), else as triangles. */
static void add_split(zs_model *m, const int32_t *v, int n, split_scratch *sc, uint32_t rgb,
                      int32_t id, int32_t obj) {
  /* Positions relative to the centroid keep the sums below well
   * conditioned for a polygon far from the origin. */
  vec3 *p = sc->p;
  vec3 centre = {0.0, 0.0, 0.0};
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) centre[k] += m->mesh.pos[3 * (size_t)v[i] + k];
  for (int k = 0; k < 3; k++) centre[k] /= n;
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 3; k++)
      p[i][k] = m->mesh.pos[3 * (size_t)v[i] + k] - centre[k];

  vec3 nrm;
  nrm[0] = nrm[1] = nrm[2] = 0.0;
  for (int i = 0; i < n; i++) zs_newell_add(nrm, p[i], p[(i + 1) % n]);
  if (nrm[0] == 0.0 && nrm[1] == 0.0 && nrm[2] == 0.0) {
    /* No area and no plane (collinear points, or a figure eight whose
     * halves cancel): triangles are at least convex. */
    add_fan(m, v, n, rgb, id, obj);
    return;
  }
  vec2 *q = sc->q;
  project(p, n, nrm, q);
  int convex = is_convex(q, n, sc->dx, sc->dy);
  if (convex && is_planar(p, n, nrm))
    add_convex(m, v, n, rgb, id, obj);
  else if (convex)
    add_fan(m, v, n, rgb, id, obj);
  else
    add_ear_clipped(m, v, q, sc->prev, sc->next, n, rgb, id, obj);
}

/* The per-corner or per-face array *p made for the first time, cap
 * entries, those before `used` set to -1. */
static int make_index_array(int32_t **p, int32_t cap, int32_t used) {
  if (*p) return 1;
  *p = malloc((size_t)(cap > 0 ? cap : 1) * sizeof **p);
  if (!*p) return 0;
  for (int32_t i = 0; i < used; i++) (*p)[i] = -1;
  return 1;
}

zs_status zs_model_add_polygon(zs_model *m, const int32_t *idx, int n,
                               uint32_t rgb, int32_t obj) {
  return zs_model_add_face(m, idx, NULL, n, rgb, -1, obj);
}

zs_status zs_model_add_face(zs_model *m, const int32_t *idx, const int32_t *attr, int n,
                            uint32_t rgb, int32_t material, int32_t obj) {
  if (!idx || n < 3) return ZS_ERR_ARG;
  if (obj < -1 || obj >= m->nobjects) return ZS_ERR_ARG;
  if (material < -1 || material >= m->mesh.nmaterials) return ZS_ERR_ARG;
  for (int i = 0; i < n; i++)
    if (idx[i] < 0 || idx[i] >= m->mesh.nverts) return ZS_ERR_ARG;
  if (attr)
    for (int i = 0; i < n; i++)
      if (attr[i] < -1 || attr[i] >= m->mesh.nattrs) return ZS_ERR_ARG;
  if ((attr && !make_index_array(&m->mesh.corner_attr, m->cap_face_verts, face_vert_count(m))) ||
      (material >= 0 &&
       !make_index_array(&m->mesh.face_material, m->cap_faces, m->mesh.nfaces)))
    return ZS_ERR_NOMEM;
  m->cur_idx = idx;
  m->cur_attr = attr;
  m->cur_n = n;
  m->cur_material = material;
  /* Face ids are int32_t: one more face cannot be numbered. */
  if (m->nsource_faces == INT32_MAX) return ZS_ERR_NOMEM;

  /* The worst case is n - 2 triangles (3n - 6 >= n indices). */
  if (!reserve_faces(m, (int64_t)m->mesh.nfaces + (n - 2),
                     (int64_t)face_vert_count(m) + 3 * (int64_t)(n - 2)))
    return ZS_ERR_NOMEM;
  _Alignas(double) char stack[ZS_MAX_POLY_VERTS * SCRATCH_BYTES_PER_CORNER];
  split_scratch sc;
  if (!scratch_take(&sc, stack, n)) return ZS_ERR_NOMEM;

  /* Drop repeated consecutive vertices, the last against the first too. */
  int32_t *v = sc.v;
  int k = 0;
  for (int i = 0; i < n; i++)
    if (k == 0 || idx[i] != v[k - 1]) v[k++] = idx[i];
  while (k > 1 && v[k - 1] == v[0]) k--;

  int32_t id = m->nsource_faces;
  if (k < 3) /* zero area: kept for numbering, as one small face */
    append_face(m, idx, n < ZS_MAX_POLY_VERTS ? n : ZS_MAX_POLY_VERTS, rgb, id, obj);
  else
    add_split(m, v, k, &sc, rgb, id, obj);
  free(sc.heap);
  m->cur_idx = m->cur_attr = NULL;
  m->cur_n = 0;
  m->nsource_faces++;
  m->mesh.prim_id = m->nsource_faces;
  return ZS_OK;
}

/* ---- lines and points ------------------------------------------------- */

/* Room for one more primitive of `per` vertex indices in the parallel
 * arrays *vert and *rgb, which hold n and share *cap; and the mesh's
 * face_start made, so that a mesh of lines alone has its one entry. */
static int reserve_prims(zs_mesh *mesh, int32_t **vert, uint32_t **rgb, int32_t *cap, int32_t n,
                         int per) {
  if (!mesh->face_start && !(mesh->face_start = calloc(1, sizeof *mesh->face_start))) return 0;
  int32_t c_vert = *cap, c_rgb = *cap;
  if (!zs_grow((void **)vert, &c_vert, (int64_t)n + 1, (size_t)per * sizeof **vert) ||
      !zs_grow((void **)rgb, &c_rgb, (int64_t)n + 1, sizeof **rgb))
    return 0;
  *cap = c_vert < c_rgb ? c_vert : c_rgb;
  return 1;
}

zs_status zs_model_add_line(zs_model *m, int32_t a, int32_t b, uint32_t rgb) {
  zs_mesh *mesh = &m->mesh;
  if (a < 0 || a >= mesh->nverts || b < 0 || b >= mesh->nverts) return ZS_ERR_ARG;
  if (!reserve_prims(mesh, &mesh->line_vert, &mesh->line_rgb, &m->cap_lines, mesh->nlines, 2))
    return ZS_ERR_NOMEM;
  mesh->line_vert[2 * mesh->nlines] = a;
  mesh->line_vert[2 * mesh->nlines + 1] = b;
  mesh->line_rgb[mesh->nlines++] = rgb;
  mesh->prim_id = m->nsource_faces;
  return ZS_OK;
}

zs_status zs_model_add_point(zs_model *m, int32_t v, uint32_t rgb) {
  zs_mesh *mesh = &m->mesh;
  if (v < 0 || v >= mesh->nverts) return ZS_ERR_ARG;
  if (!reserve_prims(mesh, &mesh->point_vert, &mesh->point_rgb, &m->cap_points, mesh->npoints, 1))
    return ZS_ERR_NOMEM;
  mesh->point_vert[mesh->npoints] = v;
  mesh->point_rgb[mesh->npoints++] = rgb;
  mesh->prim_id = m->nsource_faces;
  return ZS_OK;
}

/* ---- attributes and materials ----------------------------------------- */

/* Grows the attribute array *p (of `per` elements of `size` bytes a
 * vertex) to cap vertices; made when need_it and missing, the vertices
 * before n set to def. */
static int grow_attr_array(void **p, int32_t cap, int32_t n, int need_it, size_t per,
                           size_t size, const void *def) {
  if (!*p && !need_it) return 1;
  const int fresh = *p == NULL;
  void *q = realloc(*p, (size_t)cap * per * size);
  if (!q) return 0;
  *p = q;
  if (fresh)
    for (int32_t i = 0; i < n; i++) memcpy((char *)q + (size_t)i * per * size, def, per * size);
  return 1;
}

int32_t zs_model_add_attr(zs_model *m, const float *normal, const uint8_t *rgba, const float *uv) {
  static const float no_normal[3] = {0.0f, 0.0f, 0.0f}, no_uv[2] = {0.0f, 0.0f};
  static const uint8_t white[4] = {255, 255, 255, 255};
  zs_mesh *mesh = &m->mesh;
  const int32_t n = mesh->nattrs;
  if (n == INT32_MAX) return -1;
  int32_t cap = m->cap_attrs;
  if (n + 1 > cap) cap = cap > 0 ? (cap > INT32_MAX / 2 ? INT32_MAX : 2 * cap) : 64;
  if (!grow_attr_array((void **)&mesh->normal, cap, n, normal != NULL, 3, sizeof(float),
                       no_normal) ||
      !grow_attr_array((void **)&mesh->color, cap, n, rgba != NULL, 4, 1, white) ||
      !grow_attr_array((void **)&mesh->uv, cap, n, uv != NULL, 2, sizeof(float), no_uv))
    return -1;
  m->cap_attrs = cap;
  if (mesh->normal) memcpy(mesh->normal + 3 * (size_t)n, normal ? normal : no_normal, 3 * sizeof(float));
  if (mesh->color) memcpy(mesh->color + 4 * (size_t)n, rgba ? rgba : white, 4);
  if (mesh->uv) memcpy(mesh->uv + 2 * (size_t)n, uv ? uv : no_uv, 2 * sizeof(float));
  mesh->nattrs = n + 1;
  return n;
}

int32_t zs_model_add_material(zs_model *m, const zs_material *mat) {
  if (!zs_grow((void **)&m->materials, &m->cap_materials, (int64_t)m->mesh.nmaterials + 1,
               sizeof *m->materials))
    return -1;
  m->materials[m->mesh.nmaterials] = *mat;
  m->mesh.materials = m->materials;
  return m->mesh.nmaterials++;
}

int zs_model_own_texture(zs_model *m, zs_texture *tex) {
  if (!zs_grow((void **)&m->textures, &m->cap_textures, (int64_t)m->ntextures + 1,
               sizeof *m->textures)) {
    zs_texture_destroy(tex);
    return 0;
  }
  m->textures[m->ntextures++] = tex;
  return 1;
}
