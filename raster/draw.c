/* The draw stage (draw.h): a draw's vertices transformed (the vertex
 * stage) and its faces rejected, shaded, clipped and set up into a batch
 * (the face stage), with the counters they add.  The device runs it at
 * once (now.c) or queued (defer.c); it calls neither. */
#include <stdlib.h>
#include <string.h>

#include "util/grow.h"
#include "util/compiler.h"
#include "raster/draw.h"
#include "raster/tuning.h"

int zs_vert_scratch_reserve(zs_vert_scratch *v, int32_t n) {
  if (n <= v->cap) return 1;
  void **const arrays[] = {(void **)&v->clip, (void **)&v->eyepos, (void **)&v->outcode,
                           (void **)&v->snap};
  const size_t sizes[] = {sizeof *v->clip, 3 * sizeof *v->eyepos, sizeof *v->outcode,
                          sizeof *v->snap};
  if (!zs_resize_each(arrays, sizes, 4, (size_t)n)) return 0;
  v->cap = n;
  return 1;
}

void zs_vert_scratch_free(zs_vert_scratch *v) {
  free(v->clip);
  free(v->eyepos);
  free(v->outcode);
  free(v->snap);
  memset(v, 0, sizeof *v);
}

size_t zs_vert_scratch_bytes(const zs_vert_scratch *v) {
  return (size_t)v->cap *
         (sizeof(zs_clip_vert) + 3 * sizeof(double) + sizeof(unsigned) + sizeof(zs_snap_vert));
}

void zs_draw_prep_fixed(const zs_device_config *cfg, zs_simd simd, double gx, double gy,
                        int prefetch_write, zs_kernel k, zs_draw_prep *p) {
  memset(p, 0, sizeof *p);
  p->flat = zs_shade_is_surface(cfg->shade) && k == ZS_KERNEL_DRAW;
  p->need_eye = p->flat || cfg->algo == ZS_ALGO_DEPTHSORT;
  p->sp = (zs_setup_params){cfg->width, cfg->height, cfg->cull_back && k != ZS_KERNEL_QUERY,
                            0, 0, k == ZS_KERNEL_QUERY ? ZS_QUERY_DEPTH_BIAS : 0,
                            prefetch_write};
  p->gx = gx;
  p->gy = gy;
  p->vertex_stage = zs_vertex_stage_for(simd);
  p->flat_levels = zs_flat_levels_for(simd);
}

void zs_draw_prepare(const zs_draw_prep *fixed, const double view[16], const double proj[16],
                     const double model[16], zs_draw_prep *p) {
  *p = *fixed;
  if (model) zs_mat_mul(p->mv, view, model);
  else memcpy(p->mv, view, sizeof p->mv);
  zs_mat_mul(p->mvp, proj, p->mv);
}

/* Vertices [i0, i1): to eye space (for the normals of flat shading and
 * the painter's keys) and to clip space, with the outcode, snapped when
 * inside every plane.  Eight at a time with AVX-512 where the device has
 * it (vertex_simd.c, the same bits), the rest here. */
void zs_draw_transform(const zs_draw_prep *pr, const zs_mesh *mesh, zs_vert_scratch *v, int32_t i0,
                       int32_t i1) {
  i0 = pr->vertex_stage(pr, mesh, v, i0, i1);
  for (int32_t i = i0; i < i1; i++) {
    const double *p = &mesh->pos[3 * i];
    double c[4];
    zs_mat_apply(pr->mvp, p, c);
    v->clip[i] = (zs_clip_vert){c[0], c[1], c[2], c[3]};
    v->outcode[i] = zs_clip_outcode(&v->clip[i], pr->gx, pr->gy);
    /* snapped once here for all the faces that share it (set-up snaps
     * the vertices of a clipped face itself) */
    if (v->outcode[i] == 0) zs_snap_vertex(&pr->sp, &v->clip[i], &v->snap[i]);
    if (pr->need_eye) {
      double e[4];
      zs_mat_apply(pr->mv, p, e);
      memcpy(&v->eyepos[3 * i], e, 3 * sizeof e[0]);
    }
  }
}

/* Newell's normal of the face whose nv corners are eye[3 fv[i]]; inlined
 * with nv a constant for triangles and quads, whose loop then unrolls. */
ZS_ALWAYS_INLINE void newell_of_face(const double *eye, const int32_t *fv, const int nv,
                                     double nrm[3]) {
  nrm[0] = nrm[1] = nrm[2] = 0.0;
  for (int i = 0, j = 1; i < nv; i++, j = j + 1 < nv ? j + 1 : 0)
    zs_newell_add(nrm, &eye[3 * fv[i]], &eye[3 * fv[j]]);
}

/* The faces of a draw whose flat colour waits for the levels of a run of
 * them at once (zs_flat_levels_for: why, in shade.c): each face's normal, its
 * colour and its polygons [first, end) in the batch. */
typedef struct flat_run {
  double nx[ZS_FLAT_RUN], ny[ZS_FLAT_RUN], nz[ZS_FLAT_RUN];
  uint32_t rgb[ZS_FLAT_RUN];
  int32_t first[ZS_FLAT_RUN], end[ZS_FLAT_RUN];
  int n;
} flat_run;

/* The run's faces' polygons get their flat colours; the run is empty. */
static void flat_run_finish(flat_run *run, zs_flat_levels_fn flat_levels, zs_batch *b) {
  uint32_t q[ZS_FLAT_RUN];
  flat_levels(run->nx, run->ny, run->nz, run->n, q);
  for (int k = 0; k < run->n; k++) {
    const uint32_t shaded = zs_flat_tint(run->rgb[k], q[k]);
    for (int32_t i = run->first[k]; i < run->end[k]; i++) b->polys[i].rgb = shaded;
  }
  run->n = 0;
}

/* Faces [f0, f1): trivial reject, clipping where a face crosses a plane,
 * set-up; under flat shading, the faces that became polygons join run. */
static zs_status setup_faces(const zs_draw_prep *pr, const zs_vert_scratch *v,
                             const zs_mesh *mesh, int32_t f0, int32_t f1, uint32_t id_base,
                             uint32_t rgb, zs_depthsort *ds, zs_batch *b, zs_face_counts *fc,
                             flat_run *run, zs_error *err) {
  zs_clip_vert in[ZS_MAX_POLY_VERTS], clipped[ZS_CLIP_MAX_VERTS];
  zs_setup_params sp = pr->sp;
  for (int32_t f = f0; f < f1; f++) {
    /* nv: the face's vertices; n: its polygon's, once clipped */
    const int32_t s = mesh->face_start[f], nv = mesh->face_start[f + 1] - s;
    int32_t n = nv;
    fc->in++;
    if (n < 3 || n > ZS_MAX_POLY_VERTS) {
      fc->degenerate++;
      continue;
    }
    const int32_t *fv = &mesh->face_vert[s];
    unsigned and_code = ~0u, or_code = 0;
    for (int i = 0; i < n; i++) {
      if (fv[i] < 0 || fv[i] >= mesh->nverts)
        return zs_error_set(err, ZS_ERR_ARG,
                            "draw: face %d uses vertex %d of %d", (int)f,
                            (int)fv[i], (int)mesh->nverts);
      and_code &= v->outcode[fv[i]];
      or_code |= v->outcode[fv[i]];
    }
    if (and_code) {
      fc->outside++;
      continue;
    }
    sp.id = id_base + (uint32_t)(mesh->face_id ? mesh->face_id[f] : f);
    sp.rgb = rgb != ZS_RGB_MESH ? rgb
             : mesh->face_rgb ? mesh->face_rgb[f] : ZS_DEFAULT_RGB;
    const int32_t first_poly = b->npolys;
    zs_setup_result r;
    if (or_code) {
      for (int i = 0; i < n; i++) in[i] = v->clip[fv[i]];
      fc->clipped++;
      n = zs_clip_polygon(in, n, or_code, pr->gx, pr->gy, clipped);
      if (n == 0) {
        fc->outside++;
        continue;
      }
      r = zs_setup_polygon(b, &sp, clipped, n);
    } else {
      r = zs_setup_snapped(b, &sp, v->snap, fv, n);
    }
    if (pr->flat && b->npolys > first_poly) {
      /* Flat shading, for the faces that became polygons only (not the
       * ones culled, off the window or too small to hold a pixel centre):
       * Newell's normal of the face in eye space gives their colour */
      double nrm[3];
      if (nv == 3)
        newell_of_face(v->eyepos, fv, 3, nrm);
      else if (nv == 4)
        newell_of_face(v->eyepos, fv, 4, nrm);
      else
        newell_of_face(v->eyepos, fv, nv, nrm);
      const int k = run->n++;
      run->nx[k] = nrm[0], run->ny[k] = nrm[1], run->nz[k] = nrm[2];
      run->rgb[k] = sp.rgb, run->first[k] = first_poly, run->end[k] = b->npolys;
      if (run->n == ZS_FLAT_RUN) flat_run_finish(run, pr->flat_levels, b);
    }
    /* The painter orders the faces that meet the circle around the
     * window, drawn or not, turned to the eye or nearly: a roll keeps that
     * set whole, so the faces that turn into the window are in the old
     * order already.  A face drawn outside it (its box met a pixel centre,
     * the face does not) covers no pixel and is painted farthest. */
    if (ZS_UNLIKELY(ds != NULL) && r != ZS_SETUP_NOMEM) { /* the painter only */
      if (zs_depthsort_selects(ds, &sp, r, v->clip, v->snap, fv, or_code ? clipped : NULL, n,
                               in)) {
        /* the sort key: distance along the view axis of the centroid of
         * the face's vertices */
        double zsum = 0.0;
        for (int i = 0; i < nv; i++) zsum += v->eyepos[3 * fv[i] + 2];
        if (!zs_depthsort_note(ds, sp.id, -zsum / nv))
          return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
      }
    }
    switch (r) {
      case ZS_SETUP_DRAWN: fc->rasterized++; break;
      case ZS_SETUP_BACK: fc->culled_back++; break;
      case ZS_SETUP_DEGENERATE: fc->degenerate++; break;
      case ZS_SETUP_OFFSCREEN: fc->offscreen++; break;
      case ZS_SETUP_NOMEM: return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
    }
  }
  return ZS_OK;
}

/* What became of one triangle of a face that reads attributes: a set-up
 * result, or outside a clip plane. */
enum { TRIANGLE_OUTSIDE = -1 };

/* One triangle of a face that reads attributes (surface.h): its record
 * noted, then the triangle set up (clipped first when it crosses a
 * plane) with the record's number for its colour; the record is dropped
 * when the triangle became no polygon. */
static int setup_surface_triangle(const zs_draw_prep *pr, const zs_vert_scratch *v,
                                  const int32_t tri[3], const int32_t corner[3], int32_t f,
                                  zs_setup_params *sp, zs_batch *b, zs_face_counts *fc) {
  unsigned and_code = ~0u, or_code = 0;
  for (int i = 0; i < 3; i++) {
    and_code &= v->outcode[tri[i]];
    or_code |= v->outcode[tri[i]];
  }
  if (and_code) return TRIANGLE_OUTSIDE;
  const int32_t rec = zs_surface_add_rec(pr->surf, pr->surf_draw, f, corner[0], corner[1],
                                         corner[2]);
  if (rec < 0) return ZS_SETUP_NOMEM;
  sp->rgb = ZS_SURFACE_BIT | (uint32_t)rec;
  const int32_t first_poly = b->npolys;
  int r;
  if (or_code) {
    zs_clip_vert in[3], clipped[ZS_CLIP_MAX_VERTS];
    for (int i = 0; i < 3; i++) in[i] = v->clip[tri[i]];
    fc->clipped++;
    const int n = zs_clip_polygon(in, 3, or_code, pr->gx, pr->gy, clipped);
    r = n == 0 ? TRIANGLE_OUTSIDE : (int)zs_setup_polygon(b, sp, clipped, n);
  } else {
    r = (int)zs_setup_snapped(b, sp, v->snap, tri, 3);
  }
  if (b->npolys == first_poly) zs_surface_drop_rec(pr->surf);
  return r;
}

/* The painter's key of a face drawn as triangles, noted as the flat
 * draws note theirs (setup_faces), from the face whole. */
static int note_surface_face(const zs_draw_prep *pr, const zs_vert_scratch *v, const int32_t *fv,
                             int nv, const zs_setup_params *sp, zs_setup_result r,
                             zs_depthsort *ds) {
  zs_clip_vert in[ZS_MAX_POLY_VERTS], clipped[ZS_CLIP_MAX_VERTS];
  unsigned and_code = ~0u, or_code = 0;
  for (int i = 0; i < nv; i++) {
    and_code &= v->outcode[fv[i]];
    or_code |= v->outcode[fv[i]];
  }
  if (and_code) return 1;
  int n = nv;
  if (or_code) {
    for (int i = 0; i < nv; i++) in[i] = v->clip[fv[i]];
    if ((n = zs_clip_polygon(in, nv, or_code, pr->gx, pr->gy, clipped)) == 0) return 1;
  }
  if (!zs_depthsort_selects(ds, sp, r, v->clip, v->snap, fv, or_code ? clipped : NULL, n, in))
    return 1;
  double zsum = 0.0;
  for (int i = 0; i < nv; i++) zsum += v->eyepos[3 * fv[i] + 2];
  return zs_depthsort_note(ds, sp->id, -zsum / nv);
}

/* Faces [f0, f1) of a draw that reads attributes, each as the fan of
 * triangles from its first corner (surface.h).  A face counts once: as
 * rasterized when any of its triangles is, else as its first triangle
 * fared (outside, back, degenerate, off the window); crossing a plane,
 * once for each triangle that does. */
static zs_status setup_surface_faces(const zs_draw_prep *pr, const zs_vert_scratch *v,
                                     const zs_mesh *mesh, int32_t f0, int32_t f1,
                                     uint32_t id_base, zs_depthsort *ds, zs_batch *b,
                                     zs_face_counts *fc, zs_error *err) {
  zs_setup_params sp = pr->sp;
  for (int32_t f = f0; f < f1; f++) {
    const int32_t s = mesh->face_start[f], nv = mesh->face_start[f + 1] - s;
    /* a draw of opaque and transparent faces is set up twice, once for
     * each kind (now.c): each face counts in one */
    if (pr->faces != ZS_FACES_ALL &&
        zs_face_transparent(mesh, f) != (pr->faces == ZS_FACES_TRANSPARENT))
      continue;
    fc->in++;
    if (nv < 3 || nv > ZS_MAX_POLY_VERTS) {
      fc->degenerate++;
      continue;
    }
    const int32_t *fv = &mesh->face_vert[s];
    for (int i = 0; i < nv; i++)
      if (fv[i] < 0 || fv[i] >= mesh->nverts)
        return zs_error_set(err, ZS_ERR_ARG, "draw: face %d uses vertex %d of %d", (int)f,
                            (int)fv[i], (int)mesh->nverts);
    sp.id = id_base + (uint32_t)(mesh->face_id ? mesh->face_id[f] : f);
    int drawn = 0, first = ZS_SETUP_DEGENERATE;
    for (int k = 1; k + 1 < nv; k++) {
      const int32_t tri[3] = {fv[0], fv[k], fv[k + 1]}, corner[3] = {s, s + k, s + k + 1};
      const int r = setup_surface_triangle(pr, v, tri, corner, f, &sp, b, fc);
      if (r == ZS_SETUP_NOMEM) return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
      if (r == ZS_SETUP_DRAWN) drawn = 1;
      if (k == 1) first = r;
    }
    if (drawn) fc->rasterized++;
    else if (first == TRIANGLE_OUTSIDE) fc->outside++;
    else if (first == ZS_SETUP_BACK) fc->culled_back++;
    else if (first == ZS_SETUP_OFFSCREEN) fc->offscreen++;
    else fc->degenerate++;
    if (ZS_UNLIKELY(ds != NULL) &&
        !note_surface_face(pr, v, fv, nv, &sp,
                           drawn ? ZS_SETUP_DRAWN
                                 : first < 0 ? ZS_SETUP_OFFSCREEN : (zs_setup_result)first,
                           ds))
      return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
  }
  return ZS_OK;
}

zs_status zs_draw_setup(const zs_draw_prep *pr, const zs_vert_scratch *v, const zs_mesh *mesh,
                        int32_t f0, int32_t f1, uint32_t id_base, uint32_t rgb, zs_depthsort *ds,
                        zs_batch *b, zs_face_counts *fc, zs_error *err) {
  if (pr->surf) return setup_surface_faces(pr, v, mesh, f0, f1, id_base, ds, b, fc, err);
  flat_run run;
  run.n = 0;
  const zs_status st = setup_faces(pr, v, mesh, f0, f1, id_base, rgb, ds, b, fc, &run, err);
  flat_run_finish(&run, pr->flat_levels, b); /* on an error too: no polygon left uncoloured */
  return st;
}
