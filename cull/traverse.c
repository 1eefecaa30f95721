/* The traversal of the octree that every method but none, vfc-box, the
 * oracles and hzb (which takes only its set-up) takes (internal.h).  The traversal queue (front to back) and the
 * query queue (a FIFO) are the same for all; the method's hooks decide
 * what is done to an element taken from the traversal queue, and which
 * queries it holds back and when it issues them.  Per element the culler
 * keeps, across frames, the fields of Bittner et al.: visible,
 * lastVisited, and the cost model's P(V); per frame it remembers which
 * elements it has drawn and opened, so that an element whose query
 * returns after it was drawn is not drawn twice. */
#include <math.h>
#include <string.h>

#include "cull/internal.h"
#include "util/grow.h"

/* The culler's state for the frame's tree and scene, the near plane's
 * reach and the decisions' overlay; 0 when out of memory. */
int cull_grow_elements(void **a, int32_t *cap, int32_t *init, int32_t n, size_t size,
                       const void *fresh) {
  if (!zs_grow(a, cap, n, size)) return 0;
  for (; *init < n; (*init)++) memcpy((char *)*a + (size_t)*init * size, fresh, size);
  return 1;
}

int cull_traversal_begin(frame_ctx *f) {
  /* Elements new to the culler start unseen, P(V) 1/2.  (A node slot the
   * octree frees and reuses keeps its state: at worst a node is opened
   * without a query once, which costs time, never pixels.) */
  static const elem_state fresh = {.pv = 0.5};
  zs_culler *c = f->c;
  const zs_octree *t = f->t;
  if (!cull_grow_elements((void **)&c->ns, &c->cap_ns, &c->init_ns, t->nslots, sizeof *c->ns,
                          &fresh) ||
      !cull_grow_elements((void **)&c->os, &c->cap_os, &c->init_os, f->s->ninst, sizeof *c->os,
                          &fresh) ||
      !zs_grow((void **)&c->decision, &c->cap_decision, t->nslots, 1)) {
    cull_out_of_memory(f);
    return 0;
  }
  c->ndecision = t->nslots;
  memset(c->decision, ZS_NODE_NOT_REACHED, (size_t)t->nslots);
  /* The near plane's corners lie at most near * sqrt(1 + tx^2 + ty^2) from
   * the eye (tx, ty the tangents of the half fields of view). */
  const double *proj = f->proj;
  double a = proj[10], b = proj[11];
  double znear = proj[14] != 0.0 ? b / (a - 1.0) : 0.0;
  double tx = 1.0 / proj[0], ty = 1.0 / proj[5];
  /* orthographic: the near plane may cut any box; ask none (exact, as vfc) */
  f->near_reach = proj[14] != 0.0 ? 1.0001 * znear * sqrt(1.0 + tx * tx + ty * ty) : INFINITY;
  f->tan_half_fovy = ty;
  f->height = zs_device_config_of(f->dev)->height;
  c->nheap = 0;
  c->qhead = c->qtail = 0;
  return 1;
}

/* Until nothing is left to traverse, to take or to ask: answers that are
 * ready are taken first; with nothing to traverse, the method issues a
 * query it holds back rather than wait, and the traversal ends when it
 * holds none; else the nearest element waiting is visited. */
static void traverse(frame_ctx *f) {
  zs_culler *c = f->c;
  const cull_hooks *h = f->hooks;
  if (!f->t->node[ZS_OCTREE_ROOT].empty && !cull_heap_push(f, ZS_OCTREE_ROOT, ZS_FRUSTUM_ALL_PLANES))
    cull_out_of_memory(f);
  while (f->status == ZS_OK) {
    if (c->nheap == 0 && h->empty) h->empty(f);
    while (f->status == ZS_OK && c->qhead < c->qtail) {
      if (zs_device_query_ready(f->dev, c->qq[c->qhead].q)) cull_take_result(f);
      else if (c->nheap > 0) break;
      else if (!(h->idle && h->idle(f, 1))) cull_take_result(f); /* wait */
    }
    if (f->status != ZS_OK) break;
    if (c->nheap == 0) { /* and no query out */
      if (h->idle && h->idle(f, 0)) continue;
      break;
    }
    elem e;
    unsigned mask;
    if (cull_next_in_frustum(f, &e, &mask)) h->visit(f, e, mask);
  }
}

void cull_traverse_octree(frame_ctx *f) {
  const cull_ops *ops = f->c->ops;
  if (!cull_traversal_begin(f)) return;
  if (ops->begin) ops->begin(f);
  if (f->status != ZS_OK) return;
  traverse(f);
  if (ops->end) ops->end(f);
}
