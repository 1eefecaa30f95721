/* The query queue (internal.h): the boxes a query over an element draws,
 * issuing queries into the queue (a FIFO, the paper's QueryQueue), and
 * taking their answers.  What a method does on an answer beyond the
 * shared steps is its answered hook; a multiquery's answer is all its
 * method's (multiquery_answered). */
#include <string.h>

#include "cull/internal.h"
#include "util/grow.h"

/* Appends the boxes a query over element e draws: a node's tight box; an
 * object's parts (parts.h) or its box. */
int cull_add_query_boxes(frame_ctx *f, elem e, int32_t *n) {
  zs_culler *c = f->c;
  const double(*plo)[3], (*phi)[3];
  const double *lo, *hi;
  int k = 1;
  if (is_object(e) && c->parts) {
    if (!zs_parts_of(c->parts, f->s, object_of(e), &plo, &phi, &k)) return 0;
  } else {
    cull_elem_box(f, e, &lo, &hi);
    plo = (const double(*)[3])lo;
    phi = (const double(*)[3])hi;
  }
  if (!zs_grow((void **)&c->qlo, &c->cap_qlo, *n + k, sizeof *c->qlo) ||
      !zs_grow((void **)&c->qhi, &c->cap_qhi, *n + k, sizeof *c->qhi))
    return 0;
  memcpy(c->qlo + *n, plo, (size_t)k * sizeof *c->qlo);
  memcpy(c->qhi + *n, phi, (size_t)k * sizeof *c->qhi);
  *n += k;
  return 1;
}

zs_status cull_query_boxes(frame_ctx *f, zs_device *dev, int32_t nbox, zs_query *q) {
  const zs_culler *c = f->c;
  zs_status st;
  if ((st = zs_device_query_begin(dev, q, f->err)) ||
      (st = zs_device_query_boxes(dev, (const double(*)[3])c->qlo, (const double(*)[3])c->qhi, nbox,
                                  f->err)) ||
      (st = zs_device_query_end(dev, f->err)))
    return st;
  return ZS_OK;
}

/* One query over the boxes of members[0 .. n-1], as one draw call, queued
 * as entry qe. */
void cull_query_elements(frame_ctx *f, const pending *members, int32_t n, query_entry qe) {
  zs_culler *c = f->c;
  int32_t nbox = 0;
  int ok = zs_grow((void **)&c->qq, &c->cap_qq, c->qtail + 1, sizeof *c->qq);
  for (int32_t i = 0; i < n && ok; i++) ok = cull_add_query_boxes(f, members[i].e, &nbox);
  if (!ok) {
    cull_out_of_memory(f);
    return;
  }
  if ((f->status = cull_query_boxes(f, f->dev, nbox, &qe.q))) return;
  f->st->queries++;
  c->qq[c->qtail++] = qe;
}

void cull_issue_query(frame_ctx *f, elem e, unsigned mask, unsigned char was_visible) {
  pending one = {e, mask, was_visible};
  cull_query_elements(f, &one, 1, (query_entry){e, 0, mask, was_visible, 0, 0});
}

/* Takes the answer of the query at the head of the queue (waiting for it
 * if need be) and acts on it: a visible element is drawn or opened. */
void cull_take_result(frame_ctx *f) {
  zs_culler *c = f->c;
  query_entry q = c->qq[c->qhead++];
  int visible = zs_device_query_result(f->dev, q.q) > 0;
  if (q.ngroup > 0) {
    f->hooks->multiquery_answered(f, &q, visible);
    return;
  }
  elem_state *es = cull_state(f, q.e);
  es->pv = visible ? 1.0 : 0.0; /* observed: the next frame predicts from it */
  if (f->hooks->answered) f->hooks->answered(f, &q, visible);
  cull_cost_outcome(f, q.was_visible, visible);
  cull_decide(f, q.e, visible ? ZS_NODE_QUERIED_VISIBLE : ZS_NODE_QUERIED_HIDDEN);
  if (!visible) {
    es->hidden_frames++;
    f->st->queries_hidden++;
    return;
  }
  es->hidden_frames = 0;
  f->hooks->draw_visible(f, q.e, q.mask);
}
