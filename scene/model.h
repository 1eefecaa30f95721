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

#define ZS_GREY 0xB4B4B4u /* the colour of faces without a material */

typedef struct zs_model {
  zs_mesh mesh;           /* arrays owned by the model */
  int32_t *face_object;   /* per mesh face, -1 for none */
  char **object_names;    /* nobjects names, owned */
  int32_t nobjects;
  int32_t nsource_faces;  /* faces as numbered in the source (ids 0 .. n-1) */
  /* capacities (private) */
  int32_t cap_verts, cap_faces, cap_face_verts, cap_objects;
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

/* Axis-aligned bounds of all vertices; returns 0 when there are none. */
int zs_model_bounds(const zs_model *m, double lo[3], double hi[3]);

#endif
