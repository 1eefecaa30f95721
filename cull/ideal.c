/* The oracles: ideal draws exactly the objects that own a pixel of the
 * full image, ideal-box those whose query bounds have a sample against its
 * depth buffer, both front to back.  Neither asks the device a query:
 * they are the floors.  The full image is drawn on an oracle device of
 * their own, which the clock does not see. */
#include <math.h>
#include <stdlib.h>

#include "cull/churn.h"
#include "cull/internal.h"
#include "util/grow.h"

/* What the oracles keep from frame to frame: their device, which draws
 * the full image, the instances they draw, the instance of each face id
 * (made in the first frame), and ideal-box's set from frame to frame. */
typedef struct oracle {
  zs_device *dev;
  uint8_t *owns_pixel;     /* per instance: drawn this frame */
  int32_t cap_owns_pixel;
  int32_t *owner;          /* face id -> instance */
  uint32_t nowner;
  zs_churn churn;          /* its pixels[0] count the pixels each instance owns, for both */
} oracle;

static void *oracle_create(void) { return calloc(1, sizeof(oracle)); }

static void oracle_destroy(void *own) {
  oracle *o = own;
  zs_device_destroy(o->dev);
  free(o->owns_pixel);
  free(o->owner);
  cull_churn_free(&o->churn);
  free(o);
}

/* The oracle device (ids, z-buffer), the flags and the churn's arrays,
 * cleared and set to the camera; 0 when it fails. */
static int oracle_begin(frame_ctx *f, oracle *o) {
  if (!o->dev) {
    zs_device_config oc = *zs_device_config_of(f->dev);
    oc.algo = ZS_ALGO_ZBUFFER;
    oc.shade = ZS_SHADE_ID;
    if ((f->status = zs_device_create(&oc, &o->dev, f->err))) return 0;
  }
  if (!zs_grow((void **)&o->owns_pixel, &o->cap_owns_pixel, f->s->ninst, 1) ||
      !cull_churn_begin(&o->churn, f->s->ninst)) {
    cull_out_of_memory(f);
    return 0;
  }
  zs_device_clear(o->dev);
  zs_device_set_camera(o->dev, f->view, f->proj);
  return 1;
}

static void oracle_draw(frame_ctx *f, oracle *o, int32_t i) {
  const zs_instance *in = &f->s->inst[i];
  f->status = zs_device_draw(o->dev, &f->s->meshes[in->mesh].mesh, in->model, in->id_base, in->rgb,
                             f->err);
}

/* ideal-box's churn needs the floor of each object's draw at this camera,
 * in the method's clock (churn.h); what it sets up and tests does not
 * depend on the order of drawing. */
static void oracle_draw_timed(frame_ctx *f, oracle *o, int32_t i) {
  const zs_clock_params *ck = zs_device_clock_params(f->dev);
  const zs_raster_stats before = *zs_device_stats(o->dev);
  oracle_draw(f, o, i);
  const zs_raster_stats *after = zs_device_stats(o->dev);
  o->churn.draw_ps[i] =
      llround(ck->per_call_ns * 1000.0) +
      llround(ck->per_polygon_ns * 1000.0) *
          (int64_t)(zs_polygons_set_up(after) - zs_polygons_set_up(&before)) +
      llround(ck->per_pixel_ns * 1000.0) * (int64_t)(after->pixels_tested - before.pixels_tested);
}

/* The instance each face id belongs to (ids are id_base + face id). */
static int make_owners(frame_ctx *f, oracle *o) {
  uint32_t n = 0;
  for (int32_t i = 0; i < f->s->ninst; i++) {
    const zs_mesh *m = &f->s->meshes[f->s->inst[i].mesh].mesh;
    for (int32_t k = 0; k < m->nfaces; k++) {
      uint32_t id = f->s->inst[i].id_base + (uint32_t)(m->face_id ? m->face_id[k] : k);
      if (id + 1 > n) n = id + 1;
    }
  }
  if (!(o->owner = malloc((size_t)(n ? n : 1) * sizeof *o->owner))) return 0;
  o->nowner = n;
  for (int32_t i = 0; i < f->s->ninst; i++) {
    const zs_mesh *m = &f->s->meshes[f->s->inst[i].mesh].mesh;
    for (int32_t k = 0; k < m->nfaces; k++)
      o->owner[f->s->inst[i].id_base + (uint32_t)(m->face_id ? m->face_id[k] : k)] = i;
  }
  return 1;
}

/* Whether instance i draws transparent faces on the method's device:
 * they occlude nothing, so the oracle's image of ids leaves it out. */
static int draws_transparent(const frame_ctx *f, int32_t i) {
  return zs_device_draws_transparent(f->dev, &f->s->meshes[f->s->inst[i].mesh].mesh);
}

static int find_sampled_where(frame_ctx *f, oracle *o, int only_transparent);

/* Draws the full image on the oracle and flags the instances that own a
 * pixel of it; an instance with transparent faces is not drawn there
 * (it would hide what shows through it) and is flagged when its query
 * bounds have a sample against that image (its opaque faces then hide
 * nothing from the oracle: it may draw more, never less); 0 when it
 * fails. */
static int find_owners(frame_ctx *f, oracle *o, void (*draw)(frame_ctx *f, oracle *o, int32_t i)) {
  if (!oracle_begin(f, o)) return 0;
  for (int32_t i = 0; i < f->s->ninst && f->status == ZS_OK; i++)
    if (!draws_transparent(f, i)) draw(f, o, i);
  if (f->status) return 0;
  if (!o->owner && !make_owners(f, o)) {
    cull_out_of_memory(f);
    return 0;
  }
  const zs_device_config *cfg = zs_device_config_of(f->dev);
  const uint32_t *ids = zs_device_id_buffer(o->dev);
  size_t npx = (size_t)cfg->width * (size_t)cfg->height;
  uint32_t *owned = o->churn.pixels[0]; /* zeroed by cull_churn_begin */
  for (size_t p = 0; p < npx; p++)
    if (ids[p] < o->nowner) owned[o->owner[ids[p]]]++;
  for (int32_t i = 0; i < f->s->ninst; i++) o->owns_pixel[i] = owned[i] > 0;
  return find_sampled_where(f, o, 1);
}

/* Flags also the instances (only_transparent: those with transparent
 * faces) whose query bounds have a sample against the full image's depth
 * buffer (a box holds its instance, so every owner is one of them); 0
 * when it fails. */
static int find_sampled_where(frame_ctx *f, oracle *o, int only_transparent) {
  for (int32_t i = 0; i < f->s->ninst && f->status == ZS_OK; i++) {
    zs_query q;
    if (o->owns_pixel[i] || (only_transparent && !draws_transparent(f, i))) continue;
    int32_t nbox = 0;
    if (!cull_add_query_boxes(f, object_elem(i), &nbox)) {
      cull_out_of_memory(f);
      return 0;
    }
    if ((f->status = cull_query_boxes(f, o->dev, nbox, &q))) return 0;
    o->owns_pixel[i] = zs_device_query_result(o->dev, q) > 0;
  }
  return f->status == ZS_OK;
}

/* ideal-box's set against the last frame's (churn.h). */
static void compare_sets(frame_ctx *f, oracle *o) {
  for (int32_t i = 0; i < f->s->ninst; i++) {
    unsigned mask = ZS_FRUSTUM_ALL_PLANES;
    uint64_t tests = 0;
    o->churn.visible[0][i] = o->owns_pixel[i];
    o->churn.inside[0][i] = zs_frustum_test_box(&f->frustum, f->s->inst[i].lo, f->s->inst[i].hi,
                                                &mask, &tests) != ZS_FRUSTUM_OUTSIDE;
  }
  const int64_t query_ps = llround(zs_device_clock_params(f->dev)->per_call_ns * 1000.0);
  cull_churn_compare(&o->churn, query_ps, f->st);
}

/* Front to back, as every method that traverses draws: drawn in the
 * scene's order, nearer objects would come after farther ones and write
 * over them, and the floor would cost more than vfc where few objects
 * hide (tests/test_cull.c checks it on the cubes' walk, which zscan walk
 * builtin:cubes --cull vfc,ideal measures).  With no instance, nothing is
 * drawn and nothing owns a pixel. */
static void ideal_frame(frame_ctx *f) {
  oracle *o = f->c->own;
  if (f->s->ninst > 0 && find_owners(f, o, oracle_draw)) cull_draw_front_to_back(f, o->owns_pixel);
}

static void ideal_box_frame(frame_ctx *f) {
  oracle *o = f->c->own;
  if (f->s->ninst == 0 || !find_owners(f, o, oracle_draw_timed) || !find_sampled_where(f, o, 0))
    return;
  compare_sets(f, o);
  cull_draw_front_to_back(f, o->owns_pixel);
}

const cull_ops cull_ideal = {.name = "ideal", .create = oracle_create, .destroy = oracle_destroy,
                             .frame = ideal_frame};
const cull_ops cull_ideal_box = {.name = "ideal-box", .create = oracle_create,
                                 .destroy = oracle_destroy, .frame = ideal_box_frame};
