/* zscan raster — the draw stage (draw.c): a draw's vertices transformed
 * (the vertex stage) and its faces rejected, shaded, clipped and set up
 * into a batch (the face stage), with the counters they add.  It knows
 * nothing of the device: what it needs is fixed in a zs_draw_prep, its
 * part per kernel chosen once at create (zs_draw_prep_fixed) and the
 * matrices per draw (zs_draw_prepare). */
#ifndef ZS_RASTER_DRAW_H
#define ZS_RASTER_DRAW_H

#include "raster/depthsort.h"
#include "raster/shade.h"
#include "raster/surface.h"
#include "raster/traversal.h"

/* A draw's vertices after transformation (draw.c): clip coordinates,
 * eye coordinates (flat shading, the painter's keys), outcodes, and the
 * snapped window position of each vertex inside every plane. */
typedef struct zs_vert_scratch {
  zs_clip_vert *clip;
  double *eyepos;
  unsigned *outcode;
  zs_snap_vert *snap;
  int32_t cap;
} zs_vert_scratch;

int zs_vert_scratch_reserve(zs_vert_scratch *v, int32_t n); /* 0: out of memory */
void zs_vert_scratch_free(zs_vert_scratch *v);
size_t zs_vert_scratch_bytes(const zs_vert_scratch *v);

typedef struct zs_draw_prep zs_draw_prep;

/* The vertex stage of vertices [i0, i1) at a SIMD level, the same bits as
 * draw.c's loop; returns the first vertex left to that loop
 * (vertex_simd.c, zs_vertex_stage_for). */
typedef int32_t (*zs_vertex_stage_fn)(const zs_draw_prep *p, const zs_mesh *mesh,
                                      zs_vert_scratch *v, int32_t i0, int32_t i1);
zs_vertex_stage_fn zs_vertex_stage_for(zs_simd simd);

/* What a draw fixes before its vertices and faces are processed: its
 * matrices, and the part fixed at create for its kernel. */
struct zs_draw_prep {
  double mv[16], mvp[16];
  zs_setup_params sp;
  double gx, gy;                    /* the guard band, as zs_clip_outcode takes it */
  int flat, need_eye;
  zs_vertex_stage_fn vertex_stage;  /* the SIMD level's, before draw.c's loop */
  zs_flat_levels_fn flat_levels;
  /* a draw that reads attributes: where its triangles are noted
   * (surface.h), and its number there; NULL for any other draw */
  zs_surfaces *surf;
  int32_t surf_draw;
  int faces;                        /* of a draw that reads attributes, which
                                     * faces are set up: ZS_FACES_* */
};

enum { ZS_FACES_ALL, ZS_FACES_OPAQUE, ZS_FACES_TRANSPARENT };

/* The counters the set-up of a range of faces adds. */
typedef struct zs_face_counts {
  uint64_t in, outside, clipped, culled_back, degenerate, offscreen, rasterized;
} zs_face_counts;

/* sum += fc: the parts of a draw set up over threads, in part order. */
static inline void zs_face_counts_add(zs_face_counts *sum, const zs_face_counts *fc) {
  sum->in += fc->in;
  sum->outside += fc->outside;
  sum->clipped += fc->clipped;
  sum->culled_back += fc->culled_back;
  sum->degenerate += fc->degenerate;
  sum->offscreen += fc->offscreen;
  sum->rasterized += fc->rasterized;
}

/* The fixed part for kernel k on a device of config cfg (its SIMD level
 * simd, its guard band gx, gy, prefetch_write from set-up's question). */
void zs_draw_prep_fixed(const zs_device_config *cfg, zs_simd simd, double gx, double gy,
                        int prefetch_write, zs_kernel k, zs_draw_prep *p);
/* A draw's preparation: the fixed part with the camera and the model
 * matrix (NULL: identity). */
void zs_draw_prepare(const zs_draw_prep *fixed, const double view[16], const double proj[16],
                     const double model[16], zs_draw_prep *p);
/* Vertices [i0, i1) of mesh transformed into v. */
void zs_draw_transform(const zs_draw_prep *p, const zs_mesh *mesh, zs_vert_scratch *v,
                       int32_t i0, int32_t i1);
/* Faces [f0, f1) set up into b (the painter's keys noted in ds, NULL when
 * not the painter); a face with a vertex out of range stops it with an
 * error. */
zs_status zs_draw_setup(const zs_draw_prep *p, const zs_vert_scratch *v, const zs_mesh *mesh,
                        int32_t f0, int32_t f1, uint32_t id_base, uint32_t rgb, zs_depthsort *ds,
                        zs_batch *b, zs_face_counts *fc, zs_error *err);

#endif
