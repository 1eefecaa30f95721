/* Drawing at once: a draw's vertices and faces through the draw stage
 * (draw.c) into the device's batch, then, in zbuffer mode, the batch
 * rasterized into the full frame.  Which set-up and which rasterization
 * a device uses is chosen once, at create (device.c, choose_stages): one
 * thread or split over the pool, the frame traversed now or the batch
 * kept for finish.  Every choice gives the same bytes: work split over
 * threads is summed in a fixed order. */
#include <stdlib.h>

#include "raster/device.h"
#include "raster/pool.h"

/* ---- rasterizing the batch ---- */

int zs_rasterize_frame(zs_device *d, const zs_traversal *tr, zs_scan_counts *out) {
  zs_target t = zs_raster_frame_target(d);
  int ok = zs_polyorder_batch(tr, &d->batch, &t, 0, d->cfg.height, &d->scratch, out);
  zs_batch_reset(&d->batch);
  return ok;
}

int zs_rasterize_later(zs_device *d, const zs_traversal *tr, zs_scan_counts *out) {
  (void)d;
  (void)tr;
  *out = (zs_scan_counts){0, 0, 0};
  return 1;
}

/* A batch scanned in bands of rows, one per thread: each band writes only
 * its rows and counts into its own counters; they are summed in band
 * order, so images, counters and modelled times are the same for every
 * number of threads. */
typedef struct band_job {
  zs_device *d;
  const zs_traversal *tr;
  zs_target t;
  zs_scan_counts counts[ZS_MAX_BANDS];
  int ok[ZS_MAX_BANDS];
  int nbands, row0, rows;  /* the bands split rows [row0, row0 + rows) */
} band_job;

static void rasterize_band(void *ctx, int band) {
  band_job *j = ctx;
  int y0 = j->row0 + (int)zs_part_start(j->rows, band, j->nbands);
  int y1 = j->row0 + (int)zs_part_start(j->rows, band + 1, j->nbands);
  j->counts[band] = (zs_scan_counts){0, 0, 0};
  j->ok[band] = zs_polyorder_batch(j->tr, &j->d->batch, &j->t, y0, y1,
                                   &j->d->band_scratch[band], &j->counts[band]);
}

int zs_rasterize_banded(zs_device *d, const zs_traversal *tr, zs_scan_counts *out) {
  if (d->batch.npolys < ZS_BANDED_MIN_POLYS) return zs_rasterize_frame(d, tr, out);
  /* The rows the batch covers: bands over the whole frame would leave
   * most of them idle for an object that covers a few rows, and each band
   * still reads every polygon. */
  int32_t lo, hi;
  zs_batch_rows(&d->batch, 0, d->batch.npolys, d->cfg.height, &lo, &hi);
  int rows = hi - lo + 1, nbands = zs_band_count(d->cfg.threads, rows);
  if (nbands < 2) return zs_rasterize_frame(d, tr, out);
  band_job j;
  j.d = d;
  j.tr = tr;
  j.t = zs_raster_frame_target(d);
  j.nbands = nbands;
  j.row0 = lo;
  j.rows = rows;
  zs_pool_run(d->pool, rasterize_band, &j, nbands);
  *out = (zs_scan_counts){0, 0, 0};
  int ok = 1;
  for (int b = 0; b < nbands; b++) {
    ok &= j.ok[b];
    zs_scan_counts_add(out, &j.counts[b]);
  }
  zs_batch_reset(&d->batch);
  return ok;
}

/* ---- set-ups ---- */

zs_status zs_set_up_whole(zs_device *d, const zs_mesh *mesh, const zs_draw_prep *prep,
                          uint32_t id_base, uint32_t rgb, zs_face_counts *fc, zs_error *err) {
  zs_draw_transform(prep, mesh, &d->verts, 0, mesh->nverts);
  return zs_draw_setup(prep, &d->verts, mesh, 0, mesh->nfaces, id_base, rgb, d->painter,
                       &d->batch, fc, err);
}

/* A large draw in zbuffer mode, split over the threads: the vertices in
 * ranges, then the faces in ranges, each set up into a batch of its own;
 * the batches are joined in face order, so the scan, the picture and the
 * counters are those of one thread. */
typedef struct setup_job {
  zs_device *d;
  const zs_mesh *mesh;
  const zs_draw_prep *prep;
  int nparts;
  uint32_t id_base, rgb;
  zs_batch *batch[ZS_MAX_THREADS];
  zs_face_counts fc[ZS_MAX_THREADS];
  zs_status st[ZS_MAX_THREADS];
  zs_error err[ZS_MAX_THREADS];
} setup_job;

static void transform_part(void *ctx, int part) {
  setup_job *j = ctx;
  int64_t n = j->mesh->nverts;
  zs_draw_transform(j->prep, j->mesh, &j->d->verts, (int32_t)zs_part_start(n, part, j->nparts),
                    (int32_t)zs_part_start(n, part + 1, j->nparts));
}

static void setup_part(void *ctx, int part) {
  setup_job *j = ctx;
  int64_t n = j->mesh->nfaces;
  j->fc[part] = (zs_face_counts){0, 0, 0, 0, 0, 0, 0};
  zs_error_clear(&j->err[part]);
  j->st[part] = zs_draw_setup(j->prep, &j->d->verts, j->mesh,
                              (int32_t)zs_part_start(n, part, j->nparts),
                              (int32_t)zs_part_start(n, part + 1, j->nparts), j->id_base, j->rgb,
                              NULL, j->batch[part], &j->fc[part], &j->err[part]);
}

zs_status zs_set_up_split(zs_device *d, const zs_mesh *mesh, const zs_draw_prep *prep,
                          uint32_t id_base, uint32_t rgb, zs_face_counts *fc, zs_error *err) {
  if (mesh->nfaces < ZS_PARALLEL_SETUP_FACES)
    return zs_set_up_whole(d, mesh, prep, id_base, rgb, fc, err);
  setup_job *j = malloc(sizeof *j);
  if (!j) return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
  *j = (setup_job){d, mesh, prep, d->cfg.threads, id_base, rgb,
                   {NULL}, {{0, 0, 0, 0, 0, 0, 0}}, {ZS_OK}, {{0, {0}}}};
  j->batch[0] = &d->batch;
  for (int t = 1; t < j->nparts; t++) j->batch[t] = &d->setup_parts[t];
  zs_pool_run(d->pool, transform_part, j, j->nparts);
  zs_pool_run(d->pool, setup_part, j, j->nparts);
  zs_status st = ZS_OK;
  for (int t = 0; t < j->nparts; t++) {
    if (st == ZS_OK) { /* as one thread would: counted up to the first error */
      zs_face_counts_add(fc, &j->fc[t]);
      if ((st = j->st[t]) != ZS_OK) zs_error_set(err, st, "%s", j->err[t].msg);
      else if (t > 0 && !zs_batch_append(&d->batch, j->batch[t]))
        st = zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
    }
    if (t > 0) zs_batch_reset(j->batch[t]);
  }
  free(j);
  return st;
}

/* ---- a draw ---- */

/* A draw with transparent faces (abuffer.h): its opaque faces set up and
 * rasterized as any draw's, then its transparent ones into a batch of
 * their own, traversed with the fragment kernel into the A-buffer against
 * the depth drawn so far: the full frame in zbuffer mode, nothing (a far
 * row) in scanline mode, whose rows are drawn at finish; the resolve
 * drops what the final opaque surface hides. */
static zs_status draw_with_transparency(zs_device *d, const zs_mesh *mesh, zs_draw_prep *prep,
                                        uint32_t id_base, uint32_t rgb,
                                        const zs_kernel_state *ks, zs_command *c,
                                        zs_error *err) {
  if (d->painter)
    return zs_error_set(err, ZS_ERR_ARG,
                        "draw: transparent faces need the zbuffer or scanline mode, not "
                        "depthsort");
  if (!zs_abuffer_ready(&d->abuf)) return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
  prep->faces = ZS_FACES_OPAQUE;
  zs_status st = zs_set_up_whole(d, mesh, prep, id_base, rgb, &c->faces, err);
  if (st != ZS_OK) return st;
  if (!d->rasterize(d, &ks->traversal, &c->scan))
    return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
  prep->faces = ZS_FACES_TRANSPARENT;
  st = zs_draw_setup(prep, &d->verts, mesh, 0, mesh->nfaces, id_base, rgb, NULL, &d->frag_batch,
                     &c->faces, err);
  zs_target t = zs_raster_frame_target(d);
  if (d->cfg.algo != ZS_ALGO_ZBUFFER) {
    zs_clear_pixels(d->row_depth, d->row_id, d->row_rgb, NULL, (size_t)d->cfg.width, 0);
    t = (zs_target){d->row_depth, d->row_id, NULL, NULL, 0, d->cfg.width, 0, NULL, 0,
                    d->abuf.rows};
  }
  zs_scan_counts counts = {0, 0, 0};
  if (st == ZS_OK &&
      !zs_polyorder_batch(&d->state_of[ZS_KERNEL_FRAGMENT].traversal, &d->frag_batch, &t, 0,
                          d->cfg.height, &d->scratch, &counts))
    st = zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
  zs_batch_reset(&d->frag_batch);
  if (st != ZS_OK) return st;
  zs_scan_counts_add(&c->scan, &counts);
  return zs_abuffer_check(&d->abuf, err);
}

zs_status zs_draw_at_once(zs_device *d, const zs_mesh *mesh, const double model[16],
                          uint32_t id_base, uint32_t rgb, const zs_kernel_state *ks,
                          zs_command *c, zs_error *err) {
  if (mesh->nverts < 0 || mesh->nfaces < 0)
    return zs_error_set(err, ZS_ERR_ARG, "draw: negative mesh size");
  if (!zs_vert_scratch_reserve(&d->verts, mesh->nverts > 0 ? mesh->nverts : 1))
    return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
  c->reached = ZS_COUNTED;
  c->vertices = mesh->nverts;
  zs_draw_prep prep;
  zs_draw_prepare(&ks->prep, d->view, d->proj, model, &prep);
  zs_status st;
  if (d->reads_attrs && ks == &d->state_of[ZS_KERNEL_DRAW] &&
      zs_surface_reads(&d->surf, d->cfg.shade, mesh)) {
    /* its triangles noted for the rows' shading (surface.h), on one
     * thread, so that the records keep one list */
    prep.surf = &d->surf;
    double shade_mvp[16]; /* where the shading's planes are evaluated */
    if (d->has_shade_proj) zs_mat_mul(shade_mvp, d->shade_proj, prep.mv);
    prep.surf_draw = zs_surface_add_draw(&d->surf, mesh, d->view, model, prep.mv,
                                         d->has_shade_proj ? shade_mvp : prep.mvp,
                                         d->perspective, rgb, d->cfg.shade);
    if (prep.surf_draw < 0) return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
    if (d->cfg.shade != ZS_SHADE_NORMAL && zs_mesh_transparent(mesh)) {
      st = draw_with_transparency(d, mesh, &prep, id_base, rgb, ks, c, err);
      if (st == ZS_OK) c->reached = ZS_COMPLETED;
      return st;
    }
    st = zs_set_up_whole(d, mesh, &prep, id_base, rgb, &c->faces, err);
  } else {
    st = d->set_up(d, mesh, &prep, id_base, rgb, &c->faces, err);
  }
  if (st != ZS_OK) return st;
  if (!d->rasterize(d, &ks->traversal, &c->scan))
    return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
  c->reached = ZS_COMPLETED;
  return ZS_OK;
}
