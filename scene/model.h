/* zscan scene — a model: one mesh the device can draw, with its objects.
 *
 * A zs_model owns the arrays of its zs_mesh and grows them as vertices and
 * faces are added.  Faces keep the number they had in their source (face_id):
 * a concave or non-planar polygon is split into convex pieces here, at load
 * time, and every piece keeps the polygon's number, so `--shade id` and the
 * depth tie-break speak of the faces of the file.
 *
 * Objects are named groups of faces (OBJ `o`/`g`, a generated teapot, a
 * scene instance); face_object[f] is the object of mesh face f, -1 for none.
 */
#ifndef ZS_SCENE_MODEL_H
#define ZS_SCENE_MODEL_H

#include <stdint.h>

#include "util/matrix.h"
#include "util/compiler.h"

#define ZS_GREY 0xB4B4B4u /* the colour of faces without a material */

/* The notes of a load (zs_scene_notes): lines of text, each ending in
 * '\n', about what was drawn otherwise than the file asked (a texture
 * skipped because it cannot be opened).  text is NULL when there are
 * none, else NUL-terminated after its len bytes. */
typedef struct zs_notes {
  char *text;
  int32_t len, cap;
} zs_notes;

/* Appends one note: the line fmt makes, with every control character
 * written as a space (a name from a file cannot break it in two), and
 * '\n'.  0 when out of memory (the notes then stay as they were). */
int zs_notes_add(zs_notes *n, const char *fmt, ...) ZS_PRINTF_LIKE(2, 3);

/* Appends every note of *from to *to, each after prefix (NULL: none), and
 * frees *from (left empty).  0 when out of memory (both stay as they
 * were). */
int zs_notes_move(zs_notes *to, zs_notes *from, const char *prefix);

void zs_notes_free(zs_notes *n);

typedef struct zs_model {
  zs_mesh mesh;           /* arrays owned by the model */
  int32_t *face_object;   /* per mesh face, -1 for none */
  char **object_names;    /* nobjects names, owned */
  int32_t nobjects;
  int32_t nsource_faces;  /* faces as numbered in the source (ids 0 .. n-1) */
  zs_material *materials; /* mesh.materials, owned (mesh.nmaterials of them) */
  zs_texture **textures;  /* the textures the materials use, owned */
  int32_t ntextures;
  zs_notes notes;         /* of its load, until a scene takes them */
  /* capacities (private) */
  int32_t cap_verts, cap_faces, cap_face_verts, cap_objects;
  int32_t cap_attrs, cap_materials, cap_textures, cap_lines, cap_points;
  /* the polygon being added: its corners' positions and attributes, from
   * which each piece of it takes its corners' attributes (private) */
  const int32_t *cur_idx, *cur_attr;
  int cur_n;
  int32_t cur_material;
} zs_model;

void zs_model_init(zs_model *m);
void zs_model_free(zs_model *m);

/* Appends a vertex; returns its index, or -1 when out of memory. */
int32_t zs_model_add_vertex(zs_model *m, double x, double y, double z);

/* Returns the index of the object named name, adding it when new; -1 when
 * out of memory.  Objects keep the order of their first appearance. */
int32_t zs_model_object(zs_model *m, const char *name);

/* Adds source face number m->nsource_faces (then increments it): the
 * polygon of n >= 3 vertex indices, colour rgb, in object obj (-1: none).
 * A convex planar polygon is stored whole (as a fan of convex pieces of
 * at most ZS_MAX_POLY_VERTS corners when it has more); a concave or
 * non-planar one is split into triangles.  Every piece carries the face's
 * id.  n may be any count.  Repeated
 * consecutive vertices are dropped; a polygon left with fewer than 3
 * distinct vertices is kept as a zero-area face (it draws nothing but keeps
 * the numbering).  Returns ZS_OK, ZS_ERR_ARG for an index out of range or
 * n < 3, ZS_ERR_NOMEM. */
zs_status zs_model_add_polygon(zs_model *m, const int32_t *idx, int n,
                               uint32_t rgb, int32_t obj);

/* Adds the line from position a to position b (mesh.line_vert), colour
 * rgb, or the point at position v (mesh.point_vert).  Their ids follow the
 * faces' (mesh.prim_id = nsource_faces, kept up to date): lines and
 * points are numbered in the order they are added.  ZS_ERR_ARG for an
 * index out of range, ZS_ERR_NOMEM. */
zs_status zs_model_add_line(zs_model *m, int32_t a, int32_t b, uint32_t rgb);
zs_status zs_model_add_point(zs_model *m, int32_t v, uint32_t rgb);

/* Whether the model has anything to draw: a face, a line or a point. */
static inline int zs_model_drawable(const zs_model *m) {
  return m->nsource_faces > 0 || m->mesh.nlines > 0 || m->mesh.npoints > 0;
}

/* Appends an attribute vertex (zscan.h, zs_mesh): normal (3 floats),
 * rgba (4 bytes) and uv (2 floats), each NULL for none ((0, 0, 0), white
 * and opaque, (0, 0)).  An array is made at the first vertex that has its
 * attribute, with the defaults for the vertices before.  Returns its
 * index, or -1 when out of memory. */
int32_t zs_model_add_attr(zs_model *m, const float *normal, const uint8_t *rgba, const float *uv);

/* Appends a material (copied); returns its index, -1 when out of memory. */
int32_t zs_model_add_material(zs_model *m, const zs_material *mat);

/* Hands tex to the model, which destroys it with itself; returns 0 (and
 * destroys tex) when out of memory. */
int zs_model_own_texture(zs_model *m, zs_texture *tex);

/* zs_model_add_polygon with attributes: corner i takes attribute vertex
 * attr[i] (-1: none; attr NULL: none for any corner) and the face the
 * material `material` (-1: none).  Every piece of a split polygon keeps
 * its corners' attributes.  ZS_ERR_ARG also for an attribute index or a
 * material out of range. */
zs_status zs_model_add_face(zs_model *m, const int32_t *idx, const int32_t *attr, int n,
                            uint32_t rgb, int32_t material, int32_t obj);

/* Gives every corner without a normal (attribute -1, or a normal of (0,
 * 0, 0)) the normal of its surface there: the sum of the Newell normals
 * (twice the area times the unit normal, so larger faces weigh more) of
 * the faces that meet at its position and whose planes turn from its
 * face's by at most crease_deg degrees (a cube keeps its edges at 60,
 * a sphere's facets merge).  Corners left as they are when their face has
 * no area.  Attribute vertices are made or split as needed, and shared
 * between corners that end with the same attributes.  0 when out of
 * memory (the model then stays as it was, but for attribute vertices
 * added at its end). */
int zs_model_compute_normals(zs_model *m, double crease_deg);

/* What a model read from a file (or given as arrays) gets when some of
 * its corners have attributes or some face a texture: the normals it
 * lacks, computed with a crease of 60 degrees (a cube keeps its edges).
 * A model with neither is drawn flat and stays as it is.  0 when out of
 * memory. */
int zs_model_complete_normals(zs_model *m);

/* Axis-aligned bounds of all vertices; returns 0 when there are none. */
int zs_model_bounds(const zs_model *m, double lo[3], double hi[3]);

#endif
