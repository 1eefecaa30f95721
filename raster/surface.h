/* zscan raster — surface shading (surface.c): the shadings that read a
 * mesh's attributes (auto on a mesh that has them, unlit, gouraud, phong,
 * normal), shaded once per pixel after visibility.
 *
 * THE RECORDS
 *   A draw that reads attributes notes itself (zs_surface_draw: its mesh,
 *   matrices, colour and lights) and each triangle it sets up (a record:
 *   the draw, the face and the triangle's three corners).  Its polygons
 *   carry ZS_SURFACE_BIT | record in place of a colour, so the span
 *   kernels write that word into the colour buffer as they write a
 *   colour: the depth test, the traversals and their SIMD copies are the
 *   same code for every shading.  When the frame's rows go out, each
 *   pixel whose word names a record is shaded from it; a word without the
 *   bit is a colour (a flat draw's, the background, hidden lines' ink).
 *   Which triangle owns a pixel is decided by depth and id alone
 *   (raster.h, DEPTH), so the record a pixel names, and its colour, do
 *   not depend on the mode, the traversal, the threads or the order of
 *   the draws; the record's number does, and it never reaches an output.
 *
 * POLYGONS OF MORE THAN THREE CORNERS
 *   are shaded as the fan of triangles (c0, ck, ck+1) from their first
 *   corner, as Mesa draws GL_POLYGON: each triangle is set up on its own,
 *   with its own depth plane, and they cover the polygon's pixels, each
 *   once (the top-left rule gives a centre on a diagonal to one side).
 *
 * INTERPOLATION (exact)
 *   From the triangle's clip coordinates c_i = (X_i, Y_i, W_i), X and Y in
 *   image pixels times w, the planes lambda_i(x, y) = (c_j x c_k) . (x,
 *   y, 1), with (i, j, k) cyclic, are proportional to the perspective-
 *   correct barycentric coordinates at every point of the triangle (w > 0),
 *   clipped or not (Olano and Greer's 2D homogeneous rasterization).  They
 *   are scaled by a power of two so that their magnitudes stay below 2^38
 *   over the triangle's box in the window and rounded to integers once
 *   per triangle; at pixel (x, y) they are evaluated exactly in 64 bits
 *   at its centre, negative values (a pixel centre given to the triangle
 *   by snapping) taken as 0, and the weights b_i = floor(2^24 lambda_i /
 *   S), S = the sum, b_2 = 2^24 - b_0 - b_1.  An attribute at the pixel
 *   is (sum b_i a_i + 2^23) >> 24 of the corners' values in fixed point:
 *   8-bit colours, 16-bit linear light, texture coordinates in 2^-16,
 *   normals in 2^-30. */
#ifndef ZS_RASTER_SURFACE_H
#define ZS_RASTER_SURFACE_H

#include <stdint.h>

#include "raster/light.h"
#include "raster/raster.h"

#define ZS_SURFACE_BIT 0x80000000u /* a colour word that names a record */

enum { ZS_SURFACE_SLOTS = 64 }; /* threads that may shade rows at once */

typedef struct zs_surface_draw {
  zs_mesh mesh;      /* a copy of the caller's: its arrays must outlive the frame */
  double mv[16], mvp[16];
  double nrm[9];     /* the normal matrix: mv's 3 x 3, inverted and transposed */
  uint32_t rgb;      /* ZS_RGB_MESH, or the colour of every face */
  zs_shade shade;    /* UNLIT, GOURAUD, PHONG or NORMAL */
  int32_t lights;    /* the light set it was drawn under */
  int32_t shadow_at; /* its first matrix in zs_surfaces.shadow_mvp, -1: none */
} zs_surface_draw;

typedef struct zs_surface_rec {
  int32_t draw, face;
  int32_t corner[3]; /* the triangle's corners, as indices of face_vert */
} zs_surface_rec;

/* A frame's draws and records, with the light sets they were drawn under. */
typedef struct zs_surfaces {
  zs_surface_draw *draws;
  int32_t ndraws, cap_draws;
  zs_surface_rec *recs;
  int32_t nrecs, cap_recs;
  zs_light_set *sets;
  int32_t nsets, cap_sets;
  int sets_stale;      /* the lights or the camera changed since the last set */
  zs_light lights[ZS_MAX_LIGHTS];
  int nlights;
  int lights_given;    /* zs_device_set_lights set lights of the caller's */
  int width, height;
  zs_filter filter;    /* the device's override, or ZS_FILTER_DEFAULT */
  int normals_out;     /* every shading prepares normals: the rows' are read */
  zs_shadow_map shadows[ZS_MAX_SHADOW_MAPS]; /* the device's, checked */
  double shadow_vp[ZS_MAX_SHADOW_MAPS][16];  /* each map's proj x view */
  int nshadows;
  double (*shadow_mvp)[16]; /* a draw's nshadows matrices from its shadow_at:
                       * each map's proj x view x the draw's model */
  int32_t nshadow_mvp, cap_shadow_mvp;
  void *cache[ZS_SURFACE_SLOTS]; /* prepared triangles, one cache for each
                       * thread that shades rows (surface.c) */
} zs_surfaces;

void zs_surfaces_init(zs_surfaces *s, int width, int height, zs_filter filter);
void zs_surfaces_free(zs_surfaces *s);
/* A new frame: no draws, no records (the lights stay). */
void zs_surfaces_clear(zs_surfaces *s);
size_t zs_surfaces_bytes(const zs_surfaces *s);

/* Whether a draw of mesh under shade reads attributes (auto: when the
 * mesh has any, or lights were given: a lit scene lights every mesh). */
int zs_surface_reads(const zs_surfaces *s, zs_shade shade, const zs_mesh *mesh);

/* Notes a draw (its matrices and the lights in force under view; model
 * NULL: the identity); returns its number, -1 when out of memory. */
int32_t zs_surface_add_draw(zs_surfaces *s, const zs_mesh *mesh, const double view[16],
                            const double model[16], const double mv[16], const double mvp[16],
                            int perspective, uint32_t rgb, zs_shade shade);

/* The shadow maps of the draws from the next on (checked by the device:
 * zscan.h, zs_device_set_shadow_maps). */
void zs_surfaces_set_shadow_maps(zs_surfaces *s, const zs_shadow_map *maps, int n);

/* Notes a triangle; returns its record's number, -1 when out of memory. */
static inline int32_t zs_surface_add_rec(zs_surfaces *s, int32_t draw, int32_t face,
                                         int32_t c0, int32_t c1, int32_t c2);
/* Forgets the last record (its triangle drew nothing). */
static inline void zs_surface_drop_rec(zs_surfaces *s) { s->nrecs--; }

/* Face f's material, or NULL when the mesh has none (a face_material out
 * of range: material 0). */
static inline const zs_material *zs_face_material(const zs_mesh *m, int32_t f) {
  if (!m->materials || m->nmaterials <= 0) return NULL;
  const int32_t k = m->face_material ? m->face_material[f] : 0;
  return &m->materials[k >= 0 && k < m->nmaterials ? k : 0];
}

/* Face f's base colour (zscan.h, zs_device_draw): the draw's rgb unless it
 * is ZS_RGB_MESH, else its material's, else white under vertex colours
 * (they are the colour), else the face's own. */
static inline uint32_t zs_face_base_rgb(const zs_mesh *m, const zs_material *mat, int32_t f,
                                        uint32_t rgb) {
  return rgb != ZS_RGB_MESH ? rgb
         : mat ? (uint32_t)mat->base[0] << 16 | (uint32_t)mat->base[1] << 8 | mat->base[2]
         : m->color ? 0xFFFFFFu
         : m->face_rgb ? m->face_rgb[f] : ZS_DEFAULT_RGB;
}

/* The attribute vertex of corner c (an index of face_vert), -1 for none
 * (zscan.h, zs_mesh: corner_attr, else the position's own). */
static inline int32_t zs_corner_attr(const zs_mesh *m, int32_t c) {
  const int32_t a = m->corner_attr ? m->corner_attr[c] : m->face_vert[c];
  return a < m->nattrs ? a : -1;
}

/* Whether face f of m is transparent (zscan.h): its material's alpha or
 * its base texture's (with texture coordinates to read it), or a corner's
 * vertex colour alpha, below 255. */
int zs_face_transparent(const zs_mesh *m, int32_t f);
/* Whether any face of m may be: a material or a vertex colour is. */
int zs_mesh_transparent(const zs_mesh *m);

/* The words of a run [x0, x1) of row y naming one record (word) shaded
 * into out[x0 .. x1) as A << 24 | RGB, with their alpha (abuffer.h). */
void zs_surface_shade_rgba(zs_surfaces *s, int slot, int y, uint32_t word, int x0, int x1,
                           uint32_t *out);

/* Row y's colour words (rgb) shaded into out, width pixels (out may be
 * rgb itself); slot: the calling thread's own cache, 0 .. 63.  Rows may
 * be shaded on several threads at once, each with a slot of its own. */
void zs_surface_shade_row(zs_surfaces *s, int slot, int y, const uint32_t *rgb, uint32_t *out);
/* Whether every shading prepares normals, for zs_surface_normal_row (the
 * triangles prepared so far are dropped). */
void zs_surfaces_set_normals_out(zs_surfaces *s, int on);
/* Row y's eye-space unit normals, x, y, z a pixel, into xyz: the normal
 * ZS_SHADE_NORMAL colours at a pixel naming a record, 0, 0, 0 at any
 * other (s->normals_out set, so that every shading prepares them). */
void zs_surface_normal_row(zs_surfaces *s, int slot, int y, const uint32_t *rgb, float *xyz);

int zs_surface_grow_recs(zs_surfaces *s);

static inline int32_t zs_surface_add_rec(zs_surfaces *s, int32_t draw, int32_t face,
                                         int32_t c0, int32_t c1, int32_t c2) {
  if (s->nrecs == s->cap_recs && !zs_surface_grow_recs(s)) return -1;
  zs_surface_rec *r = &s->recs[s->nrecs];
  r->draw = draw;
  r->face = face;
  r->corner[0] = c0;
  r->corner[1] = c1;
  r->corner[2] = c2;
  return s->nrecs++;
}

#endif
