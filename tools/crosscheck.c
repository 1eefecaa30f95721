/* zscan's faces against another renderer's (crosscheck.h). */
#include "tools/crosscheck.h"

#include <stdlib.h>
#include <string.h>

#include "raster/raster.h"
#include "lib/frame.h"

/* A differing pixel where both sides show a face: which face the other
 * renderer shows, and what zscan makes of that face there. */
typedef struct candidate {
  uint32_t other;  /* the other renderer's face id */
  uint32_t pixel;
  int64_t delta;   /* its zscan depth minus the shown face's; -1: not covered */
} candidate;

static int by_other_then_pixel(const void *a, const void *b) {
  const candidate *x = a, *y = b;
  if (x->other != y->other) return x->other < y->other ? -1 : 1;
  return (x->pixel > y->pixel) - (x->pixel < y->pixel);
}

static int by_pixel(const void *a, const void *b) {
  const candidate *x = a, *y = b;
  return (x->pixel > y->pixel) - (x->pixel < y->pixel);
}

static int is_tie(const candidate *c) {
  return c->delta >= 0 && c->delta <= (int64_t)ZS_CROSSCHECK_TIE_DEPTH;
}

/* One distinct face id of the candidates, and its faces as a mesh of
 * their own: nfaces faces whose face_start entries begin at fstart[first +
 * k] (k-th id, so that each has its closing entry) and whose vertex
 * indices begin at fvert[vfirst]. */
typedef struct wanted {
  uint32_t id;
  int32_t inst;           /* -1: no face has this id */
  int32_t nfaces, nverts;
  int32_t first, vfirst;
} wanted;

static int by_id(const void *key, const void *elem) {
  uint32_t k = *(const uint32_t *)key, id = ((const wanted *)elem)->id;
  return (k > id) - (k < id);
}

static uint32_t face_id_of(const zs_instance *in, const zs_mesh *m, int32_t f) {
  return in->id_base + (uint32_t)(m->face_id ? m->face_id[f] : f);
}

/* The faces of each wanted id gathered into fstart and fvert: counted on
 * the first pass, written on the second (faces may share an id). */
static zs_status gather_faces(const zs_scene *s, wanted *want, size_t nw, int32_t **fstart,
                              int32_t **fvert, zs_error *err) {
  for (int pass = 0; pass < 2; pass++) {
    for (int32_t i = 0; i < s->ninst; i++) {
      const zs_instance *in = &s->inst[i];
      const zs_mesh *m = &s->meshes[in->mesh].mesh;
      for (int32_t f = 0; f < m->nfaces; f++) {
        uint32_t id = face_id_of(in, m, f);
        wanted *w = bsearch(&id, want, nw, sizeof *want, by_id);
        if (!w || (w->inst >= 0 && w->inst != i)) continue;
        w->inst = i;
        const int32_t n = m->face_start[f + 1] - m->face_start[f];
        if (pass == 1) {
          int32_t *start = *fstart + w->first + (w - want);
          memcpy(*fvert + w->vfirst + start[w->nfaces], &m->face_vert[m->face_start[f]],
                 (size_t)n * sizeof **fvert);
          start[w->nfaces + 1] = start[w->nfaces] + n;
        }
        w->nfaces++, w->nverts += n;
      }
    }
    if (pass == 1) break;
    int32_t faces = 0, verts = 0;
    for (size_t k = 0; k < nw; k++) {
      want[k].first = faces, want[k].vfirst = verts;
      faces += want[k].nfaces, verts += want[k].nverts;
      want[k].nfaces = want[k].nverts = 0;
    }
    *fstart = calloc((size_t)faces + nw, sizeof **fstart);
    *fvert = malloc((size_t)(verts ? verts : 1) * sizeof **fvert);
    if (!*fstart || !*fvert) return zs_error_set(err, ZS_ERR_NOMEM, "crosscheck: out of memory");
  }
  return ZS_OK;
}

/* Fills delta for cand[0 .. n-1] (sorted by face): each distinct face is
 * drawn alone into dev and its depth read at its pixels. */
static zs_status depths_alone(zs_device *dev, const zs_scene *s, const double view[16],
                              const double proj[16], const uint32_t *shown_depth,
                              candidate *cand, size_t n, zs_error *err) {
  size_t nw = 0;
  for (size_t i = 0; i < n; i++) nw += i == 0 || cand[i].other != cand[i - 1].other;
  wanted *want = calloc(nw ? nw : 1, sizeof *want);
  int32_t *fstart = NULL, *fvert = NULL;
  zs_status st = want ? ZS_OK : zs_error_set(err, ZS_ERR_NOMEM, "crosscheck: out of memory");
  for (size_t i = 0, k = 0; i < n && !st; i++)
    if (i == 0 || cand[i].other != cand[i - 1].other) want[k++] = (wanted){cand[i].other, -1, 0, 0, 0, 0};
  if (!st) st = gather_faces(s, want, nw, &fstart, &fvert, err);
  const uint32_t *id = zs_device_id_buffer(dev), *depth = zs_device_depth_buffer(dev);
  for (size_t i = 0, k = 0; i < n && !st; k++) {
    const wanted *w = &want[k];
    if (w->inst >= 0) {
      const zs_instance *in = &s->inst[w->inst];
      const zs_mesh *m = &s->meshes[in->mesh].mesh;
      zs_mesh alone = {.pos = m->pos, .nverts = m->nverts, .face_start = fstart + w->first + k,
                       .face_vert = fvert + w->vfirst, .nfaces = w->nfaces};
      zs_device_clear(dev);
      zs_device_set_camera(dev, view, proj);
      if ((st = zs_device_draw(dev, &alone, in->model, 0, 0, err)) || (st = zs_device_flush(dev, err)))
        break;
    }
    for (; i < n && cand[i].other == w->id; i++) {
      uint32_t p = cand[i].pixel;
      cand[i].delta = w->inst < 0 || id[p] == ZS_ID_NONE
                          ? -1
                          : (int64_t)depth[p] - (int64_t)shown_depth[p];
    }
  }
  free(want), free(fstart), free(fvert);
  return st;
}

static void print_face(FILE *f, uint32_t id_plus_1) {
  if (id_plus_1 == 0) fprintf(f, "none");
  else fprintf(f, "%u", id_plus_1 - 1);
}

zs_status zs_crosscheck_faces(const zs_scene *s, const double view[16], const double proj[16],
                              int w, int h, const uint32_t *other, FILE *list,
                              zs_crosscheck *out, zs_error *err) {
  *out = (zs_crosscheck){(uint64_t)w * (uint64_t)h, 0, 0, 0};
  zs_device_config cfg = {w, h, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, 1, 0, 0, 0};
  zs_device *dev = NULL, *alone = NULL;
  candidate *cand = NULL;
  zs_status st = zs_device_create(&cfg, &dev, err);
  if (!st) st = zs_device_create(&cfg, &alone, err);
  if (!st) st = zs_frame_render_on(dev, s, view, proj, 0, NULL, NULL, err);
  const uint32_t *ids = st ? NULL : zs_device_id_buffer(dev);
  size_t n = 0;
  if (!st) {
    for (size_t i = 0; i < out->pixels; i++) {
      uint32_t z = ids[i] == ZS_ID_NONE ? 0 : ids[i] + 1;
      out->covered += z != 0;
      if (z != other[i]) out->differ++, n += z != 0 && other[i] != 0;
    }
    if (!(cand = malloc((n ? n : 1) * sizeof *cand)))
      st = zs_error_set(err, ZS_ERR_NOMEM, "crosscheck: out of memory");
  }
  if (!st) {
    size_t k = 0;
    for (size_t i = 0; i < out->pixels; i++)
      if (ids[i] != ZS_ID_NONE && other[i] != 0 && ids[i] + 1 != other[i])
        cand[k++] = (candidate){other[i] - 1, (uint32_t)i, -1};
    qsort(cand, n, sizeof *cand, by_other_then_pixel);
    st = depths_alone(alone, s, view, proj, zs_device_depth_buffer(dev), cand, n, err);
  }
  if (!st) {
    for (size_t i = 0; i < n; i++) out->ties += (uint64_t)is_tie(&cand[i]);
    if (list) { /* every differing pixel, in pixel order */
      qsort(cand, n, sizeof *cand, by_pixel);
      for (size_t i = 0, k = 0; i < out->pixels; i++) {
        uint32_t z = ids[i] == ZS_ID_NONE ? 0 : ids[i] + 1;
        if (z == other[i]) continue;
        fprintf(list, "  pixel %d,%d: zscan face ", (int)(i % (size_t)w), (int)(i / (size_t)w));
        print_face(list, z);
        fprintf(list, ", other face ");
        print_face(list, other[i]);
        if (k < n && cand[k].pixel == i && is_tie(&cand[k]))
          fprintf(list, ", tie (depth +%lld)\n", (long long)cand[k].delta);
        else
          fprintf(list, ", coverage\n");
        if (k < n && cand[k].pixel == i) k++;
      }
    }
  }
  free(cand);
  zs_device_destroy(dev);
  zs_device_destroy(alone);
  return st;
}
