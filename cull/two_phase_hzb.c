/* hzb: two-phase occlusion culling against a hierarchical depth buffer,
 * as GPU-driven pipelines cull (Haar and Aaltonen, SIGGRAPH 2015; Karis
 * et al., Nanite, SIGGRAPH 2021; the pyramid: Greene, Kass and Miller
 * 1993).  No occlusion query is asked; the pyramid's answers stay on the
 * GPU and drive the next draws, so nothing waits for a latency.
 *
 *   1. the objects visible last frame that lie in the frustum are drawn,
 *      front to back; a large set in passes, each pass after the first
 *      tested against the pyramid of the passes before it, so that what
 *      has been hidden since the last frame is left out (phase_one);
 *   2. the pyramid of that depth is built (raster/hzb.c);
 *   3. the octree is traversed a level at a time from the root, each level's
 *      elements in the frustum tested against the pyramid in one pass; a
 *      node that fails is skipped whole, one that may be visible opens,
 *      and an object that may be visible and was not drawn in 1 is drawn;
 *   4. the pyramid of the final depth is built and every object drawn
 *      this frame tested against it: those that may be visible are next
 *      frame's set.
 *
 * Exact: an object is left out only when its boxes are hidden behind the
 * depth drawn so far, which the rest of the frame only brings nearer
 * (zs_device_hzb_test never hides a box its query would see). */
#include <stdlib.h>
#include <string.h>

#include "cull/internal.h"
#include "util/grow.h"

/* The elements of one level, and where each one's boxes start. */
typedef struct level {
  elem *e;
  unsigned *mask;
  int32_t *box0;
  int32_t n, cap;
} level;

static int level_push(level *l, elem e, unsigned mask) {
  if (l->n == l->cap) {
    const int32_t cap = l->cap ? 2 * l->cap : 256;
    void **const arrays[] = {(void **)&l->e, (void **)&l->mask, (void **)&l->box0};
    const size_t sizes[] = {sizeof *l->e, sizeof *l->mask, sizeof *l->box0};
    if (!zs_resize_each(arrays, sizes, 3, (size_t)cap + 1)) return 0; /* box0: one more */
    l->cap = cap;
  }
  l->e[l->n] = e;
  l->mask[l->n++] = mask;
  return 1;
}

static void level_free(level *l) {
  free(l->e);
  free(l->mask);
  free(l->box0);
}

/* What hzb keeps from frame to frame: the objects drawn in each phase
 * this frame, the levels of the traversal (the one tested and the next),
 * and which of a level's boxes, then elements, may be visible. */
typedef struct hzb_state {
  uint8_t *drawn;          /* per object: phase 1's flags, then phase 3's */
  int32_t cap_drawn;
  level cur, next;
  uint8_t *maybe;
  int32_t cap_maybe;
} hzb_state;

static void *hzb_create(void) { return calloc(1, sizeof(hzb_state)); }

static void hzb_destroy(void *own) {
  hzb_state *h = own;
  free(h->drawn);
  level_free(&h->cur);
  level_free(&h->next);
  free(h->maybe);
  free(h);
}

static int push_on_level(frame_ctx *f, void *to, elem e, unsigned mask) {
  (void)f;
  return level_push(to, e, mask);
}

/* The pyramid of the depth drawn so far; 0 when it fails. */
static int build_pyramid(frame_ctx *f) {
  return (f->status = zs_device_hzb_build(f->dev, f->err)) == ZS_OK;
}

/* Tests the boxes of elements [0, n) of l (their parts' boxes for
 * objects) against the pyramid in one pass; h->maybe[k]: any may be
 * visible.  0 when it fails. */
static int test_level(frame_ctx *f, hzb_state *h, level *l) {
  zs_culler *c = f->c;
  if (l->n == 0) return 1;
  int32_t nbox = 0;
  for (int32_t k = 0; k < l->n; k++) {
    l->box0[k] = nbox;
    if (!cull_add_query_boxes(f, l->e[k], &nbox)) {
      cull_out_of_memory(f);
      return 0;
    }
  }
  l->box0[l->n] = nbox;
  if (!zs_grow((void **)&h->maybe, &h->cap_maybe, nbox > 0 ? nbox : 1, 1)) {
    cull_out_of_memory(f);
    return 0;
  }
  if (nbox > 0) {
    zs_status st = zs_device_hzb_test(f->dev, (const double(*)[3])c->qlo,
                                      (const double(*)[3])c->qhi, nbox, h->maybe, f->err);
    if (st != ZS_OK) {
      f->status = st;
      return 0;
    }
  }
  /* element k may be visible when any of its boxes may be */
  for (int32_t k = 0; k < l->n; k++) {
    uint8_t any = 0;
    for (int32_t b = l->box0[k]; b < l->box0[k + 1]; b++) any |= h->maybe[b];
    h->maybe[k] = any; /* k <= box0[k]: read before written */
  }
  return 1;
}

/* Whether object i lies in the frustum (the CPU's test, charged). */
static int in_frustum(frame_ctx *f, int32_t i) {
  unsigned mask = ZS_FRUSTUM_ALL_PLANES;
  return cull_frustum_test(f, object_elem(i), &mask) != ZS_FRUSTUM_OUTSIDE;
}

/* Phase 1 in passes: a pass for each HZB_PASS_OBJECTS objects of last
 * frame's set, at most HZB_PASSES.  A later pass costs a pyramid and a
 * test, and pays only where it leaves out enough of last frame's set that
 * has been hidden since, which a small set seldom holds.  The choice is
 * measured with zscan walk --cull hzb --reference off on the teapots, the
 * plant and scene/examples/open_layer.json, the number of passes fixed
 * (docs/CULLING.md, "The passes of phase 1", holds the figures). */
enum { HZB_PASS_OBJECTS = 128, HZB_PASSES = 4 };

/* Phase 1: last frame's set where in the frustum, front to back, in
 * passes: the first pass's objects each tested as it is drawn, so that
 * the GPU starts at once; each later pass's tested first, then against
 * the pyramid of what the passes before drew, which leaves out what has
 * been hidden since. */
static void phase_one(frame_ctx *f, hzb_state *h, uint8_t *draw1) {
  zs_culler *c = f->c;
  level *l = &h->cur;
  for (int32_t i = 0; i < f->s->ninst; i++) draw1[i] = c->os[i].visible;
  const int32_t n = cull_order_front_to_back(f, draw1);
  const int passes = n / HZB_PASS_OBJECTS < 1 ? 1
                     : n / HZB_PASS_OBJECTS > HZB_PASSES ? HZB_PASSES : n / HZB_PASS_OBJECTS;
  for (int p = 0; p < passes && f->status == ZS_OK; p++) {
    const int32_t a = (int32_t)((int64_t)n * p / passes), b = (int32_t)((int64_t)n * (p + 1) / passes);
    if (p == 0) {
      for (int32_t k = a; k < b && f->status == ZS_OK; k++)
        if ((draw1[c->order[k]] = (uint8_t)in_frustum(f, c->order[k])))
          cull_draw_instance(f, c->order[k]);
      continue;
    }
    l->n = 0;
    for (int32_t k = a; k < b; k++)
      if ((draw1[c->order[k]] = (uint8_t)in_frustum(f, c->order[k])) &&
          !level_push(l, object_elem(c->order[k]), 0)) {
        cull_out_of_memory(f);
        return;
      }
    if (!build_pyramid(f) || !test_level(f, h, l)) return;
    for (int32_t k = 0; k < l->n && f->status == ZS_OK; k++) {
      const int32_t i = object_of(l->e[k]);
      if ((draw1[i] = h->maybe[k])) cull_draw_instance(f, i);
    }
  }
  f->st->hzb_phase1 = f->st->objects_drawn;
}

/* Phase 3: the octree a level at a time; draw2 the objects to draw. */
static void phase_two(frame_ctx *f, hzb_state *h, const uint8_t *draw1, uint8_t *draw2) {
  const zs_octree *t = f->t;
  level *cur = &h->cur, *next = &h->next;
  cur->n = next->n = 0;
  if (!t->node[ZS_OCTREE_ROOT].empty && !level_push(cur, ZS_OCTREE_ROOT, ZS_FRUSTUM_ALL_PLANES)) {
    cull_out_of_memory(f);
    return;
  }
  while (cur->n > 0 && f->status == ZS_OK) {
    /* the frustum first, on the CPU as the other methods do */
    int32_t kept = 0;
    for (int32_t k = 0; k < cur->n; k++) {
      const elem e = cur->e[k];
      if (is_object(e) && draw1[object_of(e)]) continue; /* drawn in phase 1 */
      unsigned mask = cur->mask[k];
      if (!cull_visit_in_frustum(f, e, &mask)) {
        cull_decide(f, e, ZS_NODE_OUTSIDE);
        continue;
      }
      cur->e[kept] = e;
      cur->mask[kept++] = mask;
    }
    cur->n = kept;
    if (!test_level(f, h, cur)) return;
    next->n = 0;
    for (int32_t k = 0; k < cur->n; k++) {
      const elem e = cur->e[k];
      cull_decide(f, e, h->maybe[k] ? ZS_NODE_QUERIED_VISIBLE : ZS_NODE_QUERIED_HIDDEN);
      if (!h->maybe[k]) continue;
      if (is_object(e)) {
        draw2[object_of(e)] = 1;
        continue;
      }
      if (!cull_open_node(f, e, cur->mask[k], push_on_level, next)) {
        cull_out_of_memory(f);
        return;
      }
    }
    level swap = *cur;
    *cur = *next;
    *next = swap;
  }
}

/* Phase 4: next frame's set, from the final depth. */
static void next_set(frame_ctx *f, hzb_state *h, const uint8_t *draw1, const uint8_t *draw2) {
  level *l = &h->cur;
  if (!build_pyramid(f)) return;
  l->n = 0;
  for (int32_t i = 0; i < f->s->ninst; i++) {
    f->c->os[i].visible = 0;
    if ((draw1[i] || draw2[i]) && !level_push(l, object_elem(i), 0)) {
      cull_out_of_memory(f);
      return;
    }
  }
  if (!test_level(f, h, l)) return;
  for (int32_t k = 0; k < l->n; k++) {
    const int32_t i = object_of(l->e[k]);
    f->c->os[i].visible = h->maybe[k];
    f->st->hzb_stale += draw1[i] && !h->maybe[k];
  }
}

static void frame(frame_ctx *f) {
  hzb_state *h = f->c->own;
  if (!cull_traversal_begin(f)) return;
  const int32_t n = f->s->ninst;
  if (!zs_grow((void **)&h->drawn, &h->cap_drawn, 2 * (int64_t)n + 1, 1)) {
    cull_out_of_memory(f);
    return;
  }
  uint8_t *draw1 = h->drawn, *draw2 = h->drawn + n;
  memset(draw2, 0, (size_t)n);
  phase_one(f, h, draw1);
  if (f->status == ZS_OK && build_pyramid(f)) phase_two(f, h, draw1, draw2);
  if (f->status == ZS_OK) {
    cull_draw_front_to_back(f, draw2);
    f->st->hzb_phase2 = f->st->objects_drawn - f->st->hzb_phase1;
  }
  if (f->status == ZS_OK) next_set(f, h, draw1, draw2);
}

const cull_ops cull_hzb = {.name = "hzb", .create = hzb_create, .destroy = hzb_destroy,
                           .frame = frame};
