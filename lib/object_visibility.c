/* Per-object visibility, as `zscan query` prints it (zscan/zscan.h,
 * zs_query_objects; lib/object_visibility.h). */
#include "lib/object_visibility.h"

#include <stdlib.h>

#include "lib/frame.h"
#include "lib/frame_camera.h"
#include "lib/samples.h"
#include "lib/scene_draw.h"

static int by_first_face(const void *a, const void *b) {
  const zs_object_visibility *x = a, *y = b;
  if (x->first_face != y->first_face) return x->first_face < y->first_face ? -1 : 1;
  return (x->object > y->object) - (x->object < y->object);
}

/* One pass for the largest id, one to fill: an id no face, line or point
 * draws (a gap a file's numbering leaves) stays -1. */
zs_status zs_scene_id_objects(const zs_scene *s, int32_t **owner, uint32_t *n, zs_error *err) {
  *owner = NULL;
  *n = 0;
  uint64_t nids = 0;
  for (int32_t i = 0; i < s->ninst; i++) {
    const zs_mesh *m = &s->meshes[s->inst[i].mesh].mesh;
    const uint64_t base = s->inst[i].id_base;
    for (int32_t f = 0; f < m->nfaces; f++)
      if (base + (uint32_t)m->face_id[f] + 1 > nids) nids = base + (uint32_t)m->face_id[f] + 1;
    const uint64_t prims = (uint64_t)m->nlines + (uint64_t)m->npoints;
    if (prims && base + (uint32_t)m->prim_id + prims > nids) nids = base + (uint32_t)m->prim_id + prims;
  }
  if (nids >= ZS_ID_NONE)
    return zs_error_set(err, ZS_ERR_LIMIT, "zs_scene_id_objects: ids beyond %u", ZS_ID_NONE - 1);
  int32_t *o = malloc((size_t)(nids ? nids : 1) * sizeof *o);
  if (!o) return zs_error_set(err, ZS_ERR_NOMEM, "zs_scene_id_objects: out of memory");
  for (uint64_t id = 0; id < nids; id++) o[id] = -1;
  for (int32_t i = 0; i < s->ninst; i++) {
    const zs_mesh *m = &s->meshes[s->inst[i].mesh].mesh;
    const uint32_t base = s->inst[i].id_base;
    for (int32_t f = 0; f < m->nfaces; f++) o[base + (uint32_t)m->face_id[f]] = i;
    const int64_t prims = (int64_t)m->nlines + m->npoints;
    for (int64_t k = 0; k < prims; k++) o[base + (uint32_t)m->prim_id + (uint32_t)k] = i;
  }
  *owner = o;
  *n = (uint32_t)nids;
  return ZS_OK;
}

/* The ids of the finished frame counted to their objects: all of them
 * (only NULL), or those of the objects with only[i] set. */
static void count_owned(const zs_device *dev, int width, int height, const int32_t *owner,
                        uint32_t nids, const uint8_t *only, zs_object_visibility *lines) {
  const uint32_t *ids = zs_device_id_buffer(dev);
  for (size_t p = 0; p < (size_t)width * (size_t)height; p++)
    if (ids[p] < nids && owner[ids[p]] >= 0 && (!only || only[owner[ids[p]]]))
      lines[owner[ids[p]]].visible++;
}

zs_status zs_query_objects_at(const zs_scene *s, const zs_camera *cam, int width, int height,
                              int cull_back, int samples, zs_shade shade,
                              zs_object_visibility **out, int32_t *n, zs_error *err) {
  *out = NULL;
  *n = 0;
  zs_status st = ZS_OK;
  zs_device *dev = NULL;
  const size_t ninst = (size_t)(s->ninst ? s->ninst : 1);
  zs_object_visibility *lines = calloc(ninst, sizeof *lines);
  uint8_t *opaque = malloc(ninst), *clear = malloc(ninst);
  int32_t *owner = NULL;
  double view[16], proj[16];
  if (!lines || !opaque || !clear) st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  if (st == ZS_OK && samples > 1 && !zs_samples_valid(samples))
    st = zs_error_set(err, ZS_ERR_ARG, "samples: %d: expected 1, 2, 4, 8 or 16", samples);
  if (st == ZS_OK) st = zs_frame_camera(s, cam, width, height, view, proj, err);
  zs_device_config cfg = {width, height, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, cull_back, 1, 0, 0, 0};
  if (st == ZS_OK) st = zs_device_create(&cfg, &dev, err);
  /* each instance's first face, the instance of every id, and which
   * instances the render draws transparent */
  int any_clear = 0;
  for (int32_t i = 0; st == ZS_OK && i < s->ninst; i++) {
    const zs_mesh *m = &s->meshes[s->inst[i].mesh].mesh;
    lines[i].name = s->inst[i].name;
    lines[i].object = i;
    lines[i].first_face = UINT32_MAX;
    for (int32_t f = 0; f < m->nfaces; f++) {
      uint32_t id = s->inst[i].id_base + (uint32_t)m->face_id[f];
      if (id < lines[i].first_face) lines[i].first_face = id;
    }
    clear[i] = (uint8_t)zs_shade_draws_transparent(shade, m);
    opaque[i] = !clear[i];
    any_clear |= clear[i];
  }
  uint32_t nids = 0;
  if (st == ZS_OK) st = zs_scene_id_objects(s, &owner, &nids, err);
  /* Sample k is the frame drawn with every pixel's centre moved onto the
   * k-th standard position (lib/samples.h), as an anti-aliased render
   * draws it: what an object owns, and what its box's query passes, are
   * counted per sample, as GL's sample-counting queries count them.
   * An object with transparent faces hides nothing (zs_query_objects),
   * as the culling methods' oracles take it (cull/ideal.c): the frame the
   * boxes are queried against, and whose ids the other objects own, is
   * theirs alone; a transparent object owns the samples where it is the
   * nearest surface of all, from a second frame of everything. */
  const int passes = samples > 1 ? samples : 1;
  const int8_t *pos = samples > 1 ? zs_sample_positions(samples) : NULL;
  for (int k = 0; st == ZS_OK && k < passes; k++) {
    double pk[16];
    if (pos) zs_sample_projection(proj, width, height, pos[2 * k], pos[2 * k + 1], pk);
    const double *pj = pos ? pk : proj;
    zs_device_clear(dev);
    zs_device_set_camera(dev, view, pj);
    if ((st = zs_frame_draw_some(dev, s, opaque, err)) ||
        (st = zs_device_finish(dev, NULL, NULL, err)))
      break;
    count_owned(dev, width, height, owner, nids, NULL, lines);
    for (int32_t i = 0; i < s->ninst; i++) {
      zs_query q;
      if ((st = zs_device_query_begin(dev, &q, err)) ||
          (st = zs_device_query_box(dev, s->inst[i].lo, s->inst[i].hi, err)) ||
          (st = zs_device_query_end(dev, err)))
        break;
      lines[i].box_samples += zs_device_query_result(dev, q);
    }
    if (st != ZS_OK || !any_clear) continue;
    if ((st = zs_frame_draw_all(dev, s, view, pj, err)) ||
        (st = zs_device_finish(dev, NULL, NULL, err)))
      break;
    count_owned(dev, width, height, owner, nids, clear, lines);
  }
  free(owner);
  free(opaque);
  free(clear);
  zs_device_destroy(dev);
  if (st != ZS_OK) {
    free(lines);
    return st;
  }
  qsort(lines, (size_t)s->ninst, sizeof *lines, by_first_face);
  *out = lines;
  *n = s->ninst;
  return ZS_OK;
}
