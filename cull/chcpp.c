/* CHC++ (Mattausch, Bittner, Wimmer 2008): queries of hidden elements in
 * batches, queries of visible objects deferred to fill idle time and
 * spread by a random first interval (batch.c), multiqueries, and
 * (chcpp-prob) the cost-model paper's test before each query.  Its
 * variants switch one feature off (chcpp-nobatch, -nodefer, -nomulti):
 * each is chcpp's visit with its own way of asking about an element that
 * was hidden and about a visible object. */
#include <string.h>

#include "cull/internal.h"

/* How a variant asks about an element (its query, or not). */
typedef void ask_fn(frame_ctx *f, elem e, unsigned mask);

/* ---- an element that was hidden ---- */

static void ask_now(frame_ctx *f, elem e, unsigned mask) { cull_issue_query(f, e, mask, 0); }

static void ask_in_batch(frame_ctx *f, elem e, unsigned mask) {
  if (cull_hold(f, e, mask, 0) && f->c->ni >= ZS_CHCPP_BATCH) cull_issue_held_grouped(f);
}

static void ask_in_batch_single(frame_ctx *f, elem e, unsigned mask) {
  if (cull_hold(f, e, mask, 0) && f->c->ni >= ZS_CHCPP_BATCH) cull_issue_held(f);
}

/* chcpp-prob: when the query does not pay, drawn unasked. */
static void ask_in_batch_if_it_pays(frame_ctx *f, elem e, unsigned mask) {
  double pv = cull_predict(f, cull_state(f, e));
  if (cull_query_pays(f, e, pv)) ask_in_batch(f, e, mask);
  else cull_draw_unasked(f, e, mask, pv);
}

/* ---- a visible object, drawn now ---- */

static void ask_visible_now(frame_ctx *f, elem e, unsigned mask) { cull_issue_query(f, e, mask, 1); }

/* Assumed visible until its query falls due; then the query waits in the
 * queue of visible objects. */
static void ask_visible_when_due(frame_ctx *f, elem e, unsigned mask) {
  zs_culler *c = f->c;
  if (cull_state(f, e)->next_query > c->frame) cull_pull_up_visibility(f, e);
  else cull_push_pending(f, &c->vq, &c->nv, &c->cap_vq, e, mask, 1);
}

static void ask_visible_when_due_if_it_pays(frame_ctx *f, elem e, unsigned mask) {
  zs_culler *c = f->c;
  elem_state *es = cull_state(f, e);
  double pv = cull_predict(f, es);
  if (es->next_query > c->frame) {
    cull_pull_up_visibility(f, e);
  } else if (!cull_query_pays(f, e, pv)) { /* due, but not worth asking */
    es->pv = pv;
    cull_pull_up_visibility(f, e);
  } else {
    cull_push_pending(f, &c->vq, &c->nv, &c->cap_vq, e, mask, 1);
  }
}

/* ---- the visit and the idle time ---- */

static inline void visit(frame_ctx *f, elem e, unsigned mask, ask_fn *ask_hidden,
                         ask_fn *ask_visible) {
  int was_visible, seen_last;
  if (!cull_enter(f, e, mask, &was_visible, &seen_last)) return;
  if (!was_visible) { /* a termination element that was hidden: ask */
    ask_hidden(f, e, mask);
    return;
  }
  if (is_object(e)) ask_visible(f, e, mask); /* a visible leaf: drawn now, asked when due */
  cull_traverse_node(f, e, mask);
}

static void visit_chcpp(frame_ctx *f, elem e, unsigned m) { visit(f, e, m, ask_in_batch, ask_visible_when_due); }
static void visit_nobatch(frame_ctx *f, elem e, unsigned m) { visit(f, e, m, ask_now, ask_visible_when_due); }
static void visit_nodefer(frame_ctx *f, elem e, unsigned m) { visit(f, e, m, ask_in_batch, ask_visible_now); }
static void visit_nomulti(frame_ctx *f, elem e, unsigned m) {
  visit(f, e, m, ask_in_batch_single, ask_visible_when_due);
}
static void visit_prob(frame_ctx *f, elem e, unsigned m) {
  visit(f, e, m, ask_in_batch_if_it_pays, ask_visible_when_due_if_it_pays);
}

/* Issues the oldest due query of a visible object (filling idle time). */
static void issue_one_visible(frame_ctx *f) {
  zs_culler *c = f->c;
  pending p = c->vq[0];
  memmove(c->vq, c->vq + 1, (size_t)(--c->nv) * sizeof *c->vq);
  cull_issue_query(f, p.e, p.mask, p.was_visible);
}

/* Waiting for an answer: a due visible query first, else the batch; with
 * no query out, the batch first. */
static inline int idle(frame_ctx *f, int waiting, void (*issue_batch)(frame_ctx *)) {
  zs_culler *c = f->c;
  if (waiting && c->nv > 0) issue_one_visible(f);
  else if (c->ni > 0) issue_batch(f);
  else if (c->nv > 0) issue_one_visible(f);
  else return 0;
  return 1;
}

static int idle_grouped(frame_ctx *f, int waiting) { return idle(f, waiting, cull_issue_held_grouped); }
static int idle_single(frame_ctx *f, int waiting) { return idle(f, waiting, cull_issue_held); }

static void answered(frame_ctx *f, const query_entry *q, int visible) {
  if (visible && is_object(q->e)) cull_ask_again_later(f, q->e, q->was_visible);
}

#define CHCPP_HOOKS(visit_fn, idle_fn) \
  {.visit = visit_fn, .idle = idle_fn, .answered = answered, .draw_visible = cull_draw_visible}
static const cull_hooks chcpp = CHCPP_HOOKS(visit_chcpp, idle_grouped);
static const cull_hooks nobatch = CHCPP_HOOKS(visit_nobatch, idle_grouped);
static const cull_hooks nodefer = CHCPP_HOOKS(visit_nodefer, idle_grouped);
static const cull_hooks nomulti = CHCPP_HOOKS(visit_nomulti, idle_single);
static const cull_hooks prob = CHCPP_HOOKS(visit_prob, idle_grouped);
static const cull_hooks prob_measured = {.visit = visit_prob,
                                         .idle = idle_grouped,
                                         .answered = answered,
                                         .draw_visible = cull_draw_visible_measured,
                                         .measure_due = cull_measure_every_draw,
                                         .drawn = cull_measured_drawn};

static void begin_prob(frame_ctx *f) { cull_cost_frame(f, f->c->own, &prob_measured); }

const cull_ops cull_chcpp = {.name = "chcpp", .frame = cull_traverse_octree, .hooks = &chcpp};
const cull_ops cull_chcpp_nobatch = {.name = "chcpp-nobatch",
                                     .frame = cull_traverse_octree,
                                     .hooks = &nobatch};
const cull_ops cull_chcpp_nodefer = {.name = "chcpp-nodefer",
                                     .frame = cull_traverse_octree,
                                     .hooks = &nodefer};
const cull_ops cull_chcpp_nomulti = {.name = "chcpp-nomulti",
                                     .frame = cull_traverse_octree,
                                     .hooks = &nomulti};
const cull_ops cull_chcpp_prob = {.name = "chcpp-prob",
                                  .create = cull_cost_model_create,
                                  .destroy = cull_cost_model_destroy,
                                  .frame = cull_traverse_octree,
                                  .begin = begin_prob,
                                  .hooks = &prob};
