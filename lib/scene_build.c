/* Scenes built in code (zscan.h, zs_scene_create and zs_scene_add_object):
 * a caller's zs_mesh copied into a model through the same calls the OBJ
 * reader makes (scene/model.h), so a mesh given as arrays and the OBJ file
 * of the same data become the same model and draw the same bytes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "scene/scene.h"
#include "zscan/zscan.h"

zs_status zs_scene_create(zs_scene **out, zs_error *err) {
  *out = malloc(sizeof **out);
  if (!*out) return zs_error_set(err, ZS_ERR_NOMEM, "zs_scene_create: out of memory");
  zs_scene_init(*out);
  return ZS_OK;
}

/* The checks the model's own calls make with a bare ZS_ERR_ARG, made
 * first so that the message names the array and its element. */
static zs_status check_mesh(const zs_mesh *m, zs_error *err) {
  if (m->nverts < 0 || m->nfaces < 0 || m->nattrs < 0 || m->nmaterials < 0 || m->nlines < 0 ||
      m->npoints < 0)
    return zs_error_set(err, ZS_ERR_ARG, "zs_mesh: a negative count");
  if ((m->nverts > 0 && !m->pos) || (m->nfaces > 0 && (!m->face_start || !m->face_vert)) ||
      (m->nlines > 0 && !m->line_vert) || (m->npoints > 0 && !m->point_vert) ||
      (m->nmaterials > 0 && !m->materials))
    return zs_error_set(err, ZS_ERR_ARG, "zs_mesh: an array of %s is NULL",
                        !m->pos && m->nverts ? "positions"
                        : m->nfaces && (!m->face_start || !m->face_vert) ? "faces"
                        : m->nmaterials && !m->materials ? "materials"
                                                         : "lines or points");
  for (int64_t i = 0; i < 3 * (int64_t)m->nverts; i++)
    if (!isfinite(m->pos[i]))
      return zs_error_set(err, ZS_ERR_ARG, "zs_mesh.pos[%lld]: not a finite number",
                          (long long)i);
  if (m->nfaces > 0 && m->face_start[0] != 0)
    return zs_error_set(err, ZS_ERR_ARG, "zs_mesh.face_start[0]: %d, not 0", (int)m->face_start[0]);
  for (int32_t f = 0; f < m->nfaces; f++) {
    const int32_t a = m->face_start[f], b = m->face_start[f + 1];
    if (b - a < 3 || b < a)
      return zs_error_set(err, ZS_ERR_ARG, "zs_mesh face %d: %d corners (at least 3 needed)",
                          (int)f, (int)(b - a));
    for (int32_t k = a; k < b; k++) {
      if (m->face_vert[k] < 0 || m->face_vert[k] >= m->nverts)
        return zs_error_set(err, ZS_ERR_ARG,
                            "zs_mesh.face_vert[%d]: vertex %d out of range (%d vertices)", (int)k,
                            (int)m->face_vert[k], (int)m->nverts);
      const int32_t at = m->corner_attr ? m->corner_attr[k] : m->face_vert[k];
      const int32_t nattrs = m->corner_attr ? m->nattrs : m->nverts;
      if ((m->normal || m->color || m->uv) && (at < -1 || at >= nattrs))
        return zs_error_set(err, ZS_ERR_ARG,
                            "zs_mesh.corner_attr[%d]: attribute vertex %d out of range (%d)",
                            (int)k, (int)at, (int)nattrs);
    }
    if (m->face_material && (m->face_material[f] < -1 || m->face_material[f] >= m->nmaterials))
      return zs_error_set(err, ZS_ERR_ARG,
                          "zs_mesh.face_material[%d]: material %d out of range (%d materials)",
                          (int)f, (int)m->face_material[f], (int)m->nmaterials);
  }
  const int32_t nattrs = m->corner_attr ? m->nattrs : m->nverts;
  for (int64_t i = 0; m->normal && i < 3 * (int64_t)nattrs; i++)
    if (!isfinite(m->normal[i]))
      return zs_error_set(err, ZS_ERR_ARG, "zs_mesh.normal[%lld]: not a finite number",
                          (long long)i);
  for (int64_t i = 0; m->uv && i < 2 * (int64_t)nattrs; i++)
    if (!isfinite(m->uv[i]))
      return zs_error_set(err, ZS_ERR_ARG, "zs_mesh.uv[%lld]: not a finite number", (long long)i);
  for (int32_t k = 0; k < 2 * m->nlines; k++)
    if (m->line_vert[k] < 0 || m->line_vert[k] >= m->nverts)
      return zs_error_set(err, ZS_ERR_ARG,
                          "zs_mesh.line_vert[%d]: vertex %d out of range (%d vertices)", (int)k,
                          (int)m->line_vert[k], (int)m->nverts);
  for (int32_t k = 0; k < m->npoints; k++)
    if (m->point_vert[k] < 0 || m->point_vert[k] >= m->nverts)
      return zs_error_set(err, ZS_ERR_ARG,
                          "zs_mesh.point_vert[%d]: vertex %d out of range (%d vertices)", (int)k,
                          (int)m->point_vert[k], (int)m->nverts);
  for (int32_t i = 0; i < m->nmaterials; i++) {
    const zs_material *mt = &m->materials[i];
    if (mt->shininess > ZS_MAX_SHININESS || (unsigned)mt->wrap_s > ZS_WRAP_MIRROR ||
        (unsigned)mt->wrap_t > ZS_WRAP_MIRROR || (unsigned)mt->filter > ZS_FILTER_TRILINEAR)
      return zs_error_set(err, ZS_ERR_ARG,
                          "zs_mesh.materials[%d]: shininess above %d, or an unknown wrap or filter",
                          (int)i, ZS_MAX_SHININESS);
  }
  return ZS_OK;
}

/* The model of mesh: its positions, attribute vertices, materials, faces
 * (in order: face f is source face f), lines and points. */
static zs_status copy_mesh(const zs_mesh *src, zs_model *m) {
  for (int32_t v = 0; v < src->nverts; v++)
    if (zs_model_add_vertex(m, src->pos[3 * v], src->pos[3 * v + 1], src->pos[3 * v + 2]) < 0)
      return ZS_ERR_NOMEM;
  const int has_attrs = src->normal || src->color || src->uv;
  const int32_t nattrs = !has_attrs ? 0 : src->corner_attr ? src->nattrs : src->nverts;
  for (int32_t a = 0; a < nattrs; a++)
    if (zs_model_add_attr(m, src->normal ? src->normal + 3 * (size_t)a : NULL,
                          src->color ? src->color + 4 * (size_t)a : NULL,
                          src->uv ? src->uv + 2 * (size_t)a : NULL) < 0)
      return ZS_ERR_NOMEM;
  for (int32_t i = 0; i < src->nmaterials; i++)
    if (zs_model_add_material(m, &src->materials[i]) < 0) return ZS_ERR_NOMEM;
  for (int32_t f = 0; f < src->nfaces; f++) {
    const int32_t a = src->face_start[f];
    const int32_t *attr = !has_attrs ? NULL : src->corner_attr ? src->corner_attr + a
                                                               : src->face_vert + a;
    const zs_status st =
        zs_model_add_face(m, src->face_vert + a, attr, src->face_start[f + 1] - a,
                          src->face_rgb ? src->face_rgb[f] & 0xFFFFFFu : ZS_GREY,
                          src->face_material ? src->face_material[f] : -1, -1);
    if (st != ZS_OK) return st;
  }
  for (int32_t k = 0; k < src->nlines; k++)
    if (zs_model_add_line(m, src->line_vert[2 * k], src->line_vert[2 * k + 1],
                          src->line_rgb ? src->line_rgb[k] & 0xFFFFFFu : ZS_GREY) != ZS_OK)
      return ZS_ERR_NOMEM;
  for (int32_t k = 0; k < src->npoints; k++)
    if (zs_model_add_point(m, src->point_vert[k],
                           src->point_rgb ? src->point_rgb[k] & 0xFFFFFFu : ZS_GREY) != ZS_OK)
      return ZS_ERR_NOMEM;
  return zs_model_complete_normals(m) ? ZS_OK : ZS_ERR_NOMEM;
}

zs_status zs_scene_add_object(zs_scene *scene, const zs_mesh *mesh, const double model[16],
                              const char *name, zs_error *err) {
  if (!scene || !mesh) return zs_error_set(err, ZS_ERR_ARG, "zs_scene_add_object: no scene or mesh");
  zs_status st = check_mesh(mesh, err);
  if (st != ZS_OK) return st;
  for (int k = 0; model && k < 16; k++)
    if (!isfinite(model[k]))
      return zs_error_set(err, ZS_ERR_ARG, "zs_scene_add_object: model[%d] is not a finite number",
                          k);
  if (mesh->nfaces == 0 && mesh->nlines == 0 && mesh->npoints == 0)
    return zs_error_set(err, ZS_ERR_ARG, "zs_scene_add_object: no faces, lines or points");
  zs_model m;
  zs_model_init(&m);
  if ((st = copy_mesh(mesh, &m)) != ZS_OK) {
    zs_model_free(&m);
    return st == ZS_ERR_NOMEM ? zs_error_set(err, st, "zs_scene_add_object: out of memory")
                              : zs_error_set(err, st, "zs_scene_add_object: a face refused");
  }
  char fallback[32];
  if (!name) snprintf(fallback, sizeof fallback, "object %d", (int)scene->ninst);
  const int32_t k = zs_scene_add_mesh(scene, &m);
  if (k < 0) {
    zs_model_free(&m);
    return zs_error_set(err, ZS_ERR_NOMEM, "zs_scene_add_object: out of memory");
  }
  if (zs_scene_add_instance(scene, k, model, ZS_RGB_MESH, name ? name : fallback) < 0)
    return zs_error_set(err, ZS_ERR_NOMEM, "zs_scene_add_object: out of memory");
  /* ids, world boxes and bounds of what is there so far; finish keeps an
   * instance's first face id once given, so each add only appends */
  return zs_scene_finish(scene, err);
}
