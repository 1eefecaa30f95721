/* The oracles: ideal draws exactly the objects that own a pixel of the
 * full image, ideal-box those whose query bounds have a sample against its
 * depth buffer, both front to back.  Neither asks the device a query:
 * they are the floors. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cull/internal.h"
#include "raster/grow.h"

/* The oracle of ideal: which instances own a pixel of the full image; with
 * boxes (ideal-box), also which instances' tight boxes have a sample
 * against its depth buffer (a box holds its instance, so every owner is
 * one of them). */
void cull_ideal_frame(frame_ctx *f, const double view[16], const double proj[16], int boxes) {
  zs_culler *c = f->c;
  if (f->s->ninst == 0) return; /* nothing to draw, nothing to own a pixel */
  const zs_device_config *cfg = zs_device_config_of(f->dev);
  if (!c->oracle) {
    zs_device_config oc = *cfg;
    oc.algo = ZS_ALGO_ZBUFFER;
    oc.shade = ZS_SHADE_ID;
    if ((f->status = zs_device_create(&oc, &c->oracle, f->err))) return;
  }
  if (!zs_grow((void **)&c->owns_pixel, &c->cap_inst, f->s->ninst, 1)) {
    f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
    return;
  }
  /* the churn's arrays hold the pixels each instance owns for both */
  if (!cull_churn_begin(&c->churn, f->s->ninst)) {
    f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
    return;
  }
  /* ideal-box's churn: the floor of each object's draw at this camera, in
   * the method's clock (churn.h); what it sets up and tests does not
   * depend on the order of drawing */
  const zs_clock_params *ck = zs_device_clock_params(f->dev);
  const int64_t call_ps = llround(ck->per_call_ns * 1000.0);
  const int64_t polygon_ps = llround(ck->per_polygon_ns * 1000.0);
  const int64_t pixel_ps = llround(ck->per_pixel_ns * 1000.0);
  zs_device_clear(c->oracle);
  zs_device_set_camera(c->oracle, view, proj);
  for (int32_t i = 0; i < f->s->ninst && f->status == ZS_OK; i++) {
    const zs_instance *in = &f->s->inst[i];
    const zs_raster_stats before = *zs_device_stats(c->oracle);
    f->status = zs_device_draw(c->oracle, &f->s->meshes[in->mesh].mesh, in->model, in->id_base,
                               in->rgb, f->err);
    if (boxes) {
      const zs_raster_stats *after = zs_device_stats(c->oracle);
      c->churn.draw_ps[i] =
          call_ps + polygon_ps * (int64_t)(zs_polygons_set_up(after) - zs_polygons_set_up(&before)) +
          pixel_ps * (int64_t)(after->pixels_tested - before.pixels_tested);
    }
  }
  if (f->status) return;
  /* The instance each face id belongs to (ids are id_base + face id). */
  if (!c->owner) {
    uint32_t n = 0;
    for (int32_t i = 0; i < f->s->ninst; i++) {
      const zs_mesh *m = &f->s->meshes[f->s->inst[i].mesh].mesh;
      for (int32_t k = 0; k < m->nfaces; k++) {
        uint32_t id = f->s->inst[i].id_base + (uint32_t)(m->face_id ? m->face_id[k] : k);
        if (id + 1 > n) n = id + 1;
      }
    }
    if (!(c->owner = malloc((size_t)(n ? n : 1) * sizeof *c->owner))) {
      f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
      return;
    }
    c->nowner = n;
    for (int32_t i = 0; i < f->s->ninst; i++) {
      const zs_mesh *m = &f->s->meshes[f->s->inst[i].mesh].mesh;
      for (int32_t k = 0; k < m->nfaces; k++)
        c->owner[f->s->inst[i].id_base + (uint32_t)(m->face_id ? m->face_id[k] : k)] = i;
    }
  }
  const uint32_t *ids = zs_device_id_buffer(c->oracle);
  size_t npx = (size_t)cfg->width * (size_t)cfg->height;
  uint32_t *owned = c->churn.pixels[0]; /* zeroed by cull_churn_begin */
  for (size_t p = 0; p < npx; p++)
    if (ids[p] < c->nowner) owned[c->owner[ids[p]]]++;
  for (int32_t i = 0; i < f->s->ninst; i++) c->owns_pixel[i] = owned[i] > 0;
  for (int32_t i = 0; boxes && i < f->s->ninst && f->status == ZS_OK; i++) {
    zs_query q;
    if (c->owns_pixel[i]) continue;
    int32_t nbox = 0;
    if (!cull_add_query_boxes(f, object_elem(i), &nbox)) {
      f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
      return;
    }
    if ((f->status = zs_device_query_begin(c->oracle, &q, f->err)) ||
        (f->status = zs_device_query_boxes(c->oracle, (const double(*)[3])c->qlo,
                                           (const double(*)[3])c->qhi, nbox, f->err)) ||
        (f->status = zs_device_query_end(c->oracle, f->err)))
      return;
    c->owns_pixel[i] = zs_device_query_result(c->oracle, q) > 0;
  }
  if (boxes) { /* the set against the last frame's */
    for (int32_t i = 0; i < f->s->ninst; i++) {
      unsigned mask = ZS_FRUSTUM_ALL_PLANES;
      uint64_t tests = 0;
      c->churn.visible[0][i] = c->owns_pixel[i];
      c->churn.inside[0][i] = zs_frustum_test_box(&f->frustum, f->s->inst[i].lo,
                                                   f->s->inst[i].hi, &mask, &tests) !=
                              ZS_FRUSTUM_OUTSIDE;
    }
    cull_churn_compare(&c->churn, call_ps, f->st);
  }
  /* front to back, as every method that traverses draws: drawn in the
   * scene's order, nearer objects would come after farther ones and write
   * over them, and the floor would cost more than vfc where few objects
   * hide (tests/test_cull.c checks it on the cubes' walk, which zscan walk
   * builtin:cubes --cull vfc,ideal measures) */
  cull_draw_front_to_back(f, c->owns_pixel);
}
