/* CHC++ (Mattausch, Bittner, Wimmer 2008): queries of hidden elements in
 * batches, queries of visible objects deferred to fill idle time and
 * spread by a random first interval, multiqueries, and (chcpp-prob) the
 * cost-model paper's test before each query.  Each feature can be
 * switched off (chcpp-nobatch, -nodefer, -nomulti). */
#include <string.h>

#include "cull/internal.h"

/* Issues the oldest due query of a visible object (filling idle time). */
static void issue_one_visible(frame_ctx *f) {
  zs_culler *c = f->c;
  pending p = c->vq[0];
  memmove(c->vq, c->vq + 1, (size_t)(--c->nv) * sizeof *c->vq);
  cull_issue_query(f, p.e, p.mask, p.was_visible);
}

/* prob: chcpp-prob, the cost model's test (formulas 2, 3) before every
 * query CHC++ would issue. */
void cull_walk_chcpp(frame_ctx *f, int batch, int defer, int prob) {
  zs_culler *c = f->c;
  const uint32_t frame = c->frame;
  double w1, w2; /* (11)'s, for chcpp-prob */
  cull_weights(c, c->method, &w1, &w2);
  c->nheap = 0;
  c->qhead = c->qtail = 0;
  c->ni = c->nv = c->ngm = 0;
  if (!f->t->node[ZS_OCTREE_ROOT].empty && !cull_heap_push(f, ZS_OCTREE_ROOT, ZS_FRUSTUM_ALL_PLANES))
    f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
  while (f->status == ZS_OK &&
         (c->nheap > 0 || c->qhead < c->qtail || c->ni > 0 || c->nv > 0)) {
    /* Results: take the ready ones; with nothing to traverse, fill the
     * wait with due visible queries, then the batch, then wait. */
    while (f->status == ZS_OK && c->qhead < c->qtail) {
      if (zs_device_query_ready(f->dev, c->qq[c->qhead].q)) cull_take_result(f);
      else if (c->nheap > 0) break;
      else if (c->nv > 0) issue_one_visible(f);
      else if (c->ni > 0) cull_flush_invisible(f);
      else cull_take_result(f);
    }
    if (f->status != ZS_OK) break;
    if (c->nheap == 0) {
      if (c->ni > 0) cull_flush_invisible(f);
      else if (c->nv > 0) issue_one_visible(f);
      continue;
    }

    elem e;
    unsigned mask;
    if (!cull_next_in_frustum(f, &e, &mask)) continue;
    elem_state *es = cull_state(f, e);
    int was_visible = es->visible && es->last_visited == frame - 1;
    double pv = cull_predict(es, w1, w2);
    es->visible = 0;
    es->last_visited = frame;
    if (cull_too_close(f, e)) {
      es->pv = 1.0;
      cull_pull_up_visibility(f, e);
      cull_traverse(f, e, mask);
      continue;
    }
    if (!was_visible) { /* a termination element that was hidden: ask */
      if (prob && !cull_query_pays(f, e, pv)) cull_draw_unasked(f, e, mask, pv);
      else if (!batch) cull_issue_query(f, e, mask, 0);
      else if (cull_push_pending(f, &c->iq, &c->ni, &c->cap_iq, e, mask, 0) && c->ni >= ZS_CHCPP_BATCH)
        cull_flush_invisible(f);
      continue;
    }
    if (is_object(e)) { /* a visible leaf: drawn now, asked when due */
      if (!defer) cull_issue_query(f, e, mask, 1);
      else if (es->next_query > frame) cull_pull_up_visibility(f, e); /* assumed visible this frame */
      else if (prob && !cull_query_pays(f, e, pv)) { /* due, but not worth asking */
        es->pv = pv;
        cull_pull_up_visibility(f, e);
      } else cull_push_pending(f, &c->vq, &c->nv, &c->cap_vq, e, mask, 1);
    }
    cull_traverse(f, e, mask);
  }
}
