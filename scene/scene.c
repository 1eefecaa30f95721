/* zscan scene — the scene container, moving instances and camera paths
 * (see scene.h).
 *
 * Numbering.  zs_scene_add_instance leaves id_base at ZS_ID_NONE, "not
 * numbered yet"; zs_scene_finish gives each such instance the first id
 * after those of the instances before it: the number of their source faces
 * when each mesh numbers its faces 0 .. nsource_faces-1, as meshes do.
 * zs_scene_from_model numbers its instances itself (id_base 0: each keeps
 * the file's face numbers, so a part's ids run up to the file's count, and
 * an instance added later starts after them).  finish keeps a number once
 * given, so calling it again changes nothing.
 *
 * Motion.  A moving instance travels along d, the unit world direction of
 * its local axis (the model matrix's linear part applied to the axis); the
 * sign of motion.speed is the current sense.  A frame's step s = speed * d
 * is cut at the fraction t of it where the world box first touches the
 * scene's bounds; the instance then turns back (speed changes sign) and
 * travels the rest, 1 - t, the other way: a net displacement of
 * (2 t - 1) s, as a ball bounces off a wall.  The box is moved with the
 * matrix, so it stays the box of the transformed vertices up to rounding,
 * and every run performs the same operations in the same order.
 *
 * Paths.  Between keys k and k+1 the eye and the target follow the cubic
 * Hermite curve with Catmull-Rom tangents in frame units,
 *   m_k = (P_{k+1} - P_{k-1}) / (f_{k+1} - f_{k-1}),
 * where the end keys are duplicated one interval further out (P_{-1} = P_0
 * at f_0 - (f_1 - f_0), likewise after the last), so the curve passes
 * through every key and its velocity is continuous (C1) at the keys even
 * when they are unevenly spaced.  up follows the same curve, then is made
 * orthogonal to the view direction and unit length.
 */
#include "scene/scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/grow.h"
#include "util/matrix.h"
#include "scene/paths.h"

/* ---- storage ---------------------------------------------------------- */

void zs_scene_init(zs_scene *s) {
  static const zs_scene empty;
  *s = empty;
  zs_camera_default(&s->camera);
}

void zs_scene_free(zs_scene *s) {
  if (!s) return;
  for (int32_t i = 0; i < s->nmeshes; i++) zs_model_free(&s->meshes[i]);
  free(s->meshes);
  for (int32_t i = 0; i < s->ninst; i++) free(s->inst[i].name);
  free(s->inst);
  free(s->path.keys);
  zs_notes_free(&s->notes);
  zs_scene_init(s);
}

int32_t zs_scene_add_mesh(zs_scene *s, zs_model *m) {
  if (!zs_grow((void **)&s->meshes, &s->cap_meshes, (int64_t)s->nmeshes + 1, sizeof *s->meshes) ||
      !zs_notes_move(&s->notes, &m->notes, NULL))
    return -1;
  s->meshes[s->nmeshes] = *m;
  zs_model_init(m);
  return s->nmeshes++;
}

int32_t zs_scene_add_instance(zs_scene *s, int32_t mesh, const double model[16], uint32_t rgb,
                              const char *name) {
  if (!zs_grow((void **)&s->inst, &s->cap_inst, (int64_t)s->ninst + 1, sizeof *s->inst))
    return -1;
  char *copy = strdup(name ? name : "");
  if (!copy) return -1;
  zs_instance *in = &s->inst[s->ninst];
  memset(in, 0, sizeof *in);
  in->mesh = mesh;
  if (model) memcpy(in->model, model, sizeof in->model);
  else zs_mat_identity(in->model);
  in->rgb = rgb;
  in->name = copy;
  in->id_base = ZS_ID_NONE;
  return s->ninst++;
}

/* ---- bounds and numbering --------------------------------------------- */

uint64_t zs_scene_faces(const zs_scene *s) {
  uint64_t n = 0;
  for (int32_t i = 0; i < s->ninst; i++) {
    int32_t m = s->inst[i].mesh;
    if (m >= 0 && m < s->nmeshes && s->meshes[m].nsource_faces > 0)
      n += (uint64_t)s->meshes[m].nsource_faces;
  }
  return n;
}

uint64_t zs_scene_triangles(const zs_scene *s) {
  uint64_t n = 0;
  for (int32_t i = 0; i < s->ninst; i++) {
    const zs_mesh *m = &s->meshes[s->inst[i].mesh].mesh;
    n += (uint64_t)(m->face_start[m->nfaces] - 2LL * m->nfaces);
  }
  return n;
}

/* p' = the affine part of model applied to p (instances are affine). */
static void apply_affine(const double m[16], const double p[3], double out[3]) {
  for (int r = 0; r < 3; r++)
    out[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
}

void zs_scene_instance_bounds(const zs_scene *s, int32_t i, double lo[3], double hi[3]) {
  const zs_instance *in = &s->inst[i];
  const zs_mesh *mesh = &s->meshes[in->mesh].mesh;
  if (mesh->nverts <= 0) {
    /* no vertices: the box is the instance's origin */
    const double o[3] = {0.0, 0.0, 0.0};
    apply_affine(in->model, o, lo);
    memcpy(hi, lo, 3 * sizeof *hi);
    return;
  }
  for (int32_t v = 0; v < mesh->nverts; v++) {
    double w[3];
    apply_affine(in->model, mesh->pos + 3 * (size_t)v, w);
    for (int k = 0; k < 3; k++) {
      if (v == 0 || w[k] < lo[k]) lo[k] = w[k];
      if (v == 0 || w[k] > hi[k]) hi[k] = w[k];
    }
  }
}

/* The ids a mesh's faces, lines and points take from an instance's
 * id_base: nsource_faces, or more when its face ids are not 0 .. n-1 (the
 * parts of zs_scene_from_model keep their file's face numbers), or its
 * lines' and points' (which follow prim_id). */
static uint64_t id_span(const zs_model *m) {
  int64_t span = m->nsource_faces > 0 ? m->nsource_faces : 0;
  for (int32_t f = 0; f < m->mesh.nfaces; f++)
    if (m->mesh.face_id && (int64_t)m->mesh.face_id[f] + 1 > span) span = m->mesh.face_id[f] + 1;
  const int64_t prims = (int64_t)m->mesh.prim_id + m->mesh.nlines + m->mesh.npoints;
  if (m->mesh.nlines + (int64_t)m->mesh.npoints > 0 && prims > span) span = prims;
  return (uint64_t)span;
}

/* Checks an instance: its mesh exists, its matrix is finite. */
static zs_status check_instance(const zs_scene *s, const zs_instance *in, zs_error *err) {
  if (in->mesh < 0 || in->mesh >= s->nmeshes)
    return zs_error_set(err, ZS_ERR_ARG, "instance %s: mesh %d does not exist (%d meshes)",
                        in->name, (int)in->mesh, (int)s->nmeshes);
  for (int k = 0; k < 16; k++)
    if (!isfinite(in->model[k]))
      return zs_error_set(err, ZS_ERR_ARG, "instance %s: model matrix is not finite", in->name);
  return ZS_OK;
}

zs_status zs_scene_finish(zs_scene *s, zs_error *err) {
  uint64_t *span = malloc(((size_t)s->nmeshes + 1) * sizeof *span);
  if (!span) return zs_error_set(err, ZS_ERR_NOMEM, "scene: out of memory");
  for (int32_t m = 0; m < s->nmeshes; m++) span[m] = id_span(&s->meshes[m]);
  /* next: one past the highest id taken so far; ids stay below ZS_ID_NONE */
  uint64_t next = 0;
  zs_status st = ZS_OK;
  for (int32_t i = 0; i < s->ninst && st == ZS_OK; i++) {
    zs_instance *in = &s->inst[i];
    if ((st = check_instance(s, in, err)) != ZS_OK) break;
    if (in->id_base == ZS_ID_NONE) in->id_base = next < ZS_ID_NONE ? (uint32_t)next : ZS_ID_NONE;
    uint64_t end = (uint64_t)in->id_base + span[in->mesh];
    if (in->id_base == ZS_ID_NONE || end > ZS_ID_NONE)
      st = zs_error_set(err, ZS_ERR_LIMIT, "instance %s: more than %u face ids in the scene",
                        in->name, (unsigned)ZS_ID_NONE);
    if (end > next) next = end;
    zs_scene_instance_bounds(s, i, in->lo, in->hi);
  }
  free(span);
  if (st != ZS_OK || s->has_bounds) return st;
  for (int k = 0; k < 3; k++) s->lo[k] = s->hi[k] = 0.0;
  for (int32_t i = 0; i < s->ninst; i++) {
    for (int k = 0; k < 3; k++) {
      if (i == 0 || s->inst[i].lo[k] < s->lo[k]) s->lo[k] = s->inst[i].lo[k];
      if (i == 0 || s->inst[i].hi[k] > s->hi[k]) s->hi[k] = s->inst[i].hi[k];
    }
  }
  return ZS_OK;
}

/* ---- a scene from one model ------------------------------------------- */

/* Faces of a model grouped by object: the faces of group g (object g, or
 * the faces of no object for g = nobjects) are face[first[g] ..
 * first[g+1]-1], in mesh order (a counting sort). */
typedef struct face_groups {
  int32_t *first; /* ngroups + 1 */
  int32_t *face;  /* mesh.nfaces */
} face_groups;

static int group_faces(const zs_model *m, face_groups *g) {
  int32_t ng = m->nobjects + 1, nf = m->mesh.nfaces;
  g->first = calloc((size_t)ng + 1, sizeof *g->first);
  g->face = malloc(((size_t)nf + 1) * sizeof *g->face);
  if (!g->first || !g->face) return 0;
  for (int32_t f = 0; f < nf; f++) {
    int32_t o = m->face_object[f];
    g->first[(o >= 0 ? o : ng - 1) + 1]++;
  }
  for (int32_t i = 0; i < ng; i++) g->first[i + 1] += g->first[i];
  int32_t *next = malloc((size_t)ng * sizeof *next);
  if (!next) return 0;
  memcpy(next, g->first, (size_t)ng * sizeof *next);
  for (int32_t f = 0; f < nf; f++) {
    int32_t o = m->face_object[f];
    g->face[next[o >= 0 ? o : ng - 1]++] = f;
  }
  free(next);
  return 1;
}

/* Copies the faces face[0 .. n-1] of src into dst with the vertices they
 * use, renumbered in order of first use; face ids stay those of src.
 * remap has an entry per vertex of src, all -1, and is left so. */
static zs_status extract_faces(const zs_model *src, const int32_t *face, int32_t n, zs_model *dst,
                               int32_t *remap, int32_t *remap_attr, zs_error *err) {
  const zs_mesh *m = &src->mesh;
  zs_status st = ZS_OK;
  int32_t last_id = -1;
  /* every material, at the same numbers (their textures stay the
   * source's, handed on by zs_scene_from_model) */
  for (int32_t i = 0; i < m->nmaterials && st == ZS_OK; i++)
    if (zs_model_add_material(dst, &m->materials[i]) < 0) st = ZS_ERR_NOMEM;
  for (int32_t i = 0; i < n && st == ZS_OK; i++) {
    int32_t f = face[i], start = m->face_start[f];
    int32_t k = m->face_start[f + 1] - start;
    int32_t idx[ZS_MAX_POLY_VERTS], attr[ZS_MAX_POLY_VERTS];
    for (int32_t j = 0; j < k && j < ZS_MAX_POLY_VERTS; j++) {
      int32_t v = m->face_vert[start + j];
      if (remap[v] < 0) {
        const double *p = m->pos + 3 * (size_t)v;
        remap[v] = zs_model_add_vertex(dst, p[0], p[1], p[2]);
        if (remap[v] < 0) st = ZS_ERR_NOMEM;
      }
      idx[j] = remap[v];
      /* the corner's attribute vertex, copied at its first use */
      int32_t a = m->corner_attr ? m->corner_attr[start + j] : m->nattrs > 0 ? v : -1;
      if (a >= m->nattrs) a = -1;
      if (a >= 0 && remap_attr[a] < 0) {
        remap_attr[a] = zs_model_add_attr(dst, m->normal ? &m->normal[3 * (size_t)a] : NULL,
                                          m->color ? &m->color[4 * (size_t)a] : NULL,
                                          m->uv ? &m->uv[2 * (size_t)a] : NULL);
        if (remap_attr[a] < 0) st = ZS_ERR_NOMEM;
      }
      attr[j] = a >= 0 ? remap_attr[a] : -1;
    }
    if (st != ZS_OK) break;
    /* Mesh faces are convex and planar already (zs_model split them), so
     * each is stored whole; it then takes back its source face's id. */
    int32_t before = dst->mesh.nfaces;
    const int32_t mat = m->face_material && m->nmaterials > 0 ? m->face_material[f] : -1;
    st = zs_model_add_face(dst, idx, m->nattrs > 0 ? attr : NULL, (int)k, m->face_rgb[f],
                           mat >= 0 && mat < m->nmaterials ? mat : -1, -1);
    for (int32_t g = before; g < dst->mesh.nfaces; g++) dst->mesh.face_id[g] = m->face_id[f];
    /* the pieces of one source face are consecutive: count its id once */
    if (st == ZS_OK) dst->nsource_faces += (m->face_id[f] != last_id) - 1;
    last_id = m->face_id[f];
  }
  for (int32_t i = 0; i < n; i++) {
    int32_t f = face[i];
    for (int32_t j = m->face_start[f]; j < m->face_start[f + 1]; j++) {
      remap[m->face_vert[j]] = -1;
      const int32_t a = m->corner_attr ? m->corner_attr[j] : m->nattrs > 0 ? m->face_vert[j] : -1;
      if (a >= 0 && a < m->nattrs) remap_attr[a] = -1;
    }
  }
  if (st != ZS_OK)
    return zs_error_set(err, st, "scene: %s", st == ZS_ERR_NOMEM ? "out of memory" : "bad face");
  return ZS_OK;
}

/* The model's lines and points into dst, with the vertices they use
 * (remap: -1 per vertex of m, left so), numbered as in m. */
static zs_status extract_prims(const zs_model *src, zs_model *dst, int32_t *remap) {
  const zs_mesh *m = &src->mesh;
  zs_status st = ZS_OK;
  for (int32_t k = 0; k < 2 * m->nlines + m->npoints && st == ZS_OK; k++) {
    const int32_t v = k < 2 * m->nlines ? m->line_vert[k] : m->point_vert[k - 2 * m->nlines];
    if (remap[v] < 0 && (remap[v] = zs_model_add_vertex(dst, m->pos[3 * (size_t)v],
                                                        m->pos[3 * (size_t)v + 1],
                                                        m->pos[3 * (size_t)v + 2])) < 0)
      st = ZS_ERR_NOMEM;
  }
  for (int32_t k = 0; k < m->nlines && st == ZS_OK; k++)
    st = zs_model_add_line(dst, remap[m->line_vert[2 * k]], remap[m->line_vert[2 * k + 1]],
                           m->line_rgb ? m->line_rgb[k] : ZS_GREY);
  for (int32_t k = 0; k < m->npoints && st == ZS_OK; k++)
    st = zs_model_add_point(dst, remap[m->point_vert[k]], m->point_rgb ? m->point_rgb[k] : ZS_GREY);
  dst->mesh.prim_id = m->prim_id;
  for (int32_t k = 0; k < 2 * m->nlines + m->npoints; k++)
    remap[k < 2 * m->nlines ? m->line_vert[k] : m->point_vert[k - 2 * m->nlines]] = -1;
  return st;
}

zs_status zs_scene_from_model(zs_scene *s, zs_model *m, zs_error *err) {
  zs_status st = ZS_OK;
  face_groups g = {NULL, NULL};
  int32_t *remap = malloc(((size_t)m->mesh.nverts + 1) * sizeof *remap);
  int32_t *remap_attr = malloc(((size_t)m->mesh.nattrs + 1) * sizeof *remap_attr);
  if (!remap || !remap_attr || !group_faces(m, &g))
    st = zs_error_set(err, ZS_ERR_NOMEM, "scene: out of memory");
  for (int32_t v = 0; st == ZS_OK && v < m->mesh.nverts; v++) remap[v] = -1;
  for (int32_t a = 0; st == ZS_OK && a < m->mesh.nattrs; a++) remap_attr[a] = -1;
  if (st == ZS_OK && !zs_notes_move(&s->notes, &m->notes, NULL))
    st = zs_error_set(err, ZS_ERR_NOMEM, "scene: out of memory");
  int textures_handed = 0;
  /* objects in order, then the faces of no object */
  for (int32_t o = 0; st == ZS_OK && o <= m->nobjects; o++) {
    int32_t n = g.first[o + 1] - g.first[o];
    if (n == 0) continue; /* an object without faces draws nothing */
    zs_model part;
    zs_model_init(&part);
    st = extract_faces(m, g.face + g.first[o], n, &part, remap, remap_attr, err);
    if (st == ZS_OK && !textures_handed) {
      /* the first part owns the model's textures; every part's materials
       * point at them, and the scene frees its meshes together */
      part.textures = m->textures;
      part.ntextures = m->ntextures;
      part.cap_textures = m->cap_textures;
      m->textures = NULL;
      m->ntextures = m->cap_textures = 0;
      textures_handed = 1;
    }
    int32_t mi = st == ZS_OK ? zs_scene_add_mesh(s, &part) : -1;
    zs_model_free(&part);
    if (st != ZS_OK) break;
    const char *name = o < m->nobjects ? m->object_names[o] : "(none)";
    int32_t ii = mi >= 0 ? zs_scene_add_instance(s, mi, NULL, ZS_RGB_MESH, name) : -1;
    if (ii < 0) {
      st = zs_error_set(err, ZS_ERR_NOMEM, "scene: out of memory");
      break;
    }
    s->inst[ii].id_base = 0; /* ids are the model's own face numbers */
  }
  /* the lines and points, of whatever object: one more instance */
  if (st == ZS_OK && m->mesh.nlines + (int64_t)m->mesh.npoints > 0) {
    zs_model part;
    zs_model_init(&part);
    st = extract_prims(m, &part, remap);
    int32_t mi = st == ZS_OK ? zs_scene_add_mesh(s, &part) : -1;
    int32_t ii = mi >= 0 ? zs_scene_add_instance(s, mi, NULL, ZS_RGB_MESH, "(lines and points)") : -1;
    zs_model_free(&part);
    if (ii < 0) st = zs_error_set(err, ZS_ERR_NOMEM, "scene: out of memory");
    else s->inst[ii].id_base = 0;
  }
  free(g.first);
  free(g.face);
  free(remap);
  free(remap_attr);
  zs_model_free(m);
  return st;
}

/* ---- motion ----------------------------------------------------------- */

/* The unit world direction of instance in's local motion axis, or 0 when
 * it has none (a zero axis, or a matrix that flattens it). */
static int world_direction(const zs_instance *in, double d[3]) {
  double len2 = 0.0;
  for (int r = 0; r < 3; r++) {
    d[r] = in->model[4 * r] * in->motion.axis[0] + in->model[4 * r + 1] * in->motion.axis[1] +
           in->model[4 * r + 2] * in->motion.axis[2];
    len2 += d[r] * d[r];
  }
  if (!(len2 > 0.0) || !isfinite(len2)) return 0;
  double len = sqrt(len2);
  for (int r = 0; r < 3; r++) d[r] /= len;
  return 1;
}

/* The fraction t in [0, 1] of the step that keeps the box lo..hi within
 * the bounds blo..bhi (1: the whole step fits). */
static double fitting_fraction(const double lo[3], const double hi[3], const double blo[3],
                               const double bhi[3], const double step[3]) {
  double t = 1.0;
  for (int k = 0; k < 3; k++) {
    double room;
    if (step[k] > 0.0) room = bhi[k] - hi[k];
    else if (step[k] < 0.0) room = blo[k] - lo[k]; /* <= 0 when inside */
    else continue;
    double tk = room / step[k];
    if (tk < t) t = tk;
  }
  return t < 0.0 ? 0.0 : t;
}

static void advance_instance(zs_scene *s, zs_instance *in) {
  double d[3];
  if (!in->motion.moving || in->motion.speed == 0.0 || !world_direction(in, d)) return;
  double step[3];
  for (int k = 0; k < 3; k++) step[k] = in->motion.speed * d[k];
  double t = fitting_fraction(in->lo, in->hi, s->lo, s->hi, step);
  double f = 1.0;
  if (t < 1.0) {
    f = 2.0 * t - 1.0; /* to the wall and back */
    in->motion.speed = -in->motion.speed;
  }
  for (int k = 0; k < 3; k++) {
    double delta = f * step[k];
    in->model[4 * k + 3] += delta;
    in->lo[k] += delta;
    in->hi[k] += delta;
  }
}

void zs_scene_advance(zs_scene *s) {
  for (int32_t i = 0; i < s->ninst; i++) advance_instance(s, &s->inst[i]);
}

/* ---- camera paths ----------------------------------------------------- */

/* The index k of the last key with frame <= f (0 when f is before all). */
static int32_t key_before(const zs_path *p, double f) {
  int32_t lo = 0, hi = p->nkeys - 1;
  while (lo < hi) {
    int32_t mid = lo + (hi - lo + 1) / 2;
    if (p->keys[mid].frame <= f) lo = mid;
    else hi = mid - 1;
  }
  return lo;
}

/* The vector field of a key: 0 eye, 1 target, 2 up. */
static const double *key_vec(const zs_keyframe *k, int which) {
  return which == 0 ? k->eye : which == 1 ? k->target : k->up;
}

/* The Catmull-Rom tangent (per frame) of field which at key k. */
static void tangent(const zs_path *p, int32_t k, int which, double out[3]) {
  int32_t n = p->nkeys;
  const zs_keyframe *a = &p->keys[k > 0 ? k - 1 : 0];
  const zs_keyframe *b = &p->keys[k + 1 < n ? k + 1 : n - 1];
  /* a duplicated end key sits one interval beyond the end */
  double fa = k > 0 ? a->frame : 2.0 * p->keys[0].frame - p->keys[1].frame;
  double fb = k + 1 < n ? b->frame : 2.0 * p->keys[n - 1].frame - p->keys[n - 2].frame;
  const double *va = key_vec(a, which), *vb = key_vec(b, which);
  for (int i = 0; i < 3; i++) out[i] = (vb[i] - va[i]) / (fb - fa);
}

/* Makes up unit length and orthogonal to the view eye -> target; leaves
 * it merely normalised when that is not possible (up along the view), and
 * at +y when it is zero.  Returns 0 in those two cases. */
static int orthonormal_up(const double eye[3], const double target[3], double up[3]) {
  double d[3], dl2 = 0.0, u[3], ul2 = 0.0, dot = 0.0;
  for (int i = 0; i < 3; i++) {
    d[i] = target[i] - eye[i];
    dl2 += d[i] * d[i];
  }
  if (dl2 > 0.0) {
    for (int i = 0; i < 3; i++) dot += up[i] * d[i];
    for (int i = 0; i < 3; i++) u[i] = up[i] - dot / dl2 * d[i];
    for (int i = 0; i < 3; i++) ul2 += u[i] * u[i];
  }
  double l2 = 0.0;
  for (int i = 0; i < 3; i++) l2 += up[i] * up[i];
  int ok = dl2 > 0.0 && ul2 > 1e-24 * l2;
  if (ok) memcpy(up, u, sizeof u);
  else ul2 = l2;
  if (!(ul2 > 0.0)) {
    up[0] = 0.0, up[1] = 1.0, up[2] = 0.0;
    return 0;
  }
  double len = sqrt(ul2);
  for (int i = 0; i < 3; i++) up[i] /= len;
  return ok;
}

static int path_eval_at(const zs_path *p, double f, zs_keyframe *out);

void zs_path_eval(const zs_path *p, double f, zs_keyframe *out) {
  if (path_eval_at(p, f, out)) return;
  /* The view runs along the up vector here (a key looking straight down
   * with up +y, say): no image orientation follows from this frame alone.
   * It takes the orientation of the path a thousandth of a frame before
   * (or after), where the view leans a little: the limit the frames
   * around it approach, so the picture does not turn at this frame. */
  static const double nudge[] = {-1e-3, 1e-3, -0.25, 0.25};
  for (size_t i = 0; i < sizeof nudge / sizeof nudge[0]; i++) {
    zs_keyframe near;
    if (!path_eval_at(p, f + nudge[i], &near)) continue;
    memcpy(out->up, near.up, sizeof out->up);
    if (orthonormal_up(out->eye, out->target, out->up)) return;
  }
}

static int path_eval_at(const zs_path *p, double f, zs_keyframe *out) {
  int32_t n = p->nkeys;
  int32_t k = key_before(p, f);
  if (n == 1 || f <= p->keys[0].frame || k == n - 1) {
    /* held before the first key and after the last */
    *out = p->keys[f <= p->keys[0].frame ? 0 : k];
  } else {
    const zs_keyframe *a = &p->keys[k], *b = &p->keys[k + 1];
    double h = (double)b->frame - (double)a->frame;
    double u = (f - a->frame) / h, u2 = u * u, u3 = u2 * u;
    double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u;
    double h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
    for (int which = 0; which < 3; which++) {
      double ma[3], mb[3];
      tangent(p, k, which, ma);
      tangent(p, k + 1, which, mb);
      const double *pa = key_vec(a, which), *pb = key_vec(b, which);
      double *o = which == 0 ? out->eye : which == 1 ? out->target : out->up;
      for (int i = 0; i < 3; i++)
        o[i] = h00 * pa[i] + h10 * h * ma[i] + h01 * pb[i] + h11 * h * mb[i];
    }
  }
  out->frame = (int32_t)floor(f);
  return orthonormal_up(out->eye, out->target, out->up);
}

void zs_path_camera(const zs_scene *s, int32_t f, zs_camera *out) {
  *out = s->camera;
  if (s->path.nkeys <= 0) return;
  zs_keyframe k;
  zs_path_eval(&s->path, (double)f, &k);
  memcpy(out->eye, k.eye, sizeof out->eye);
  memcpy(out->target, k.target, sizeof out->target);
  memcpy(out->up, k.up, sizeof out->up);
  out->has_eye = out->has_target = out->has_up = 1;
}
