/* CHC++ (Mattausch, Bittner, Wimmer 2008): queries of previously
 * invisible elements wait in the i-queue and go out in batches, as
 * multiqueries; queries of previously visible objects are asked only when
 * due (each assumed visible for some frames, the first interval random)
 * and wait in the v-queue to fill the time the traversal would wait for
 * an answer; and (chcpp-prob) the cost-model paper's test before each
 * query.  Its variants switch one feature off (chcpp-nobatch, -nodefer,
 * -nomulti): each is chcpp's visit with its own way of asking about an
 * element that was hidden and about a visible object. */
#include <stdlib.h>
#include <string.h>

#include "cull/internal.h"
#include "util/grow.h"

/* What CHC++ keeps: the i-queue (previously invisible elements, whose
 * queries wait for a batch), the v-queue (previously visible objects
 * whose query has fallen due), the members of this frame's multiqueries,
 * and chcpp-prob's cost model. */
typedef struct chcpp_state {
  cull_held i_queue, v_queue, members;
  cull_cost_model model;
} chcpp_state;

static void *create(void) { return calloc(1, sizeof(chcpp_state)); }

static void destroy(void *own) {
  chcpp_state *s = own;
  cull_held_free(&s->i_queue);
  cull_held_free(&s->v_queue);
  cull_held_free(&s->members);
  cull_cost_model_free(&s->model);
  free(s);
}

/* ---- multiqueries ---- */

/* How many of the i-queue's elements from the i-th on go under one query:
 * the group grows while its expected saving k / (1 + (1 - P) k) grows, P
 * the chance that all its members stay hidden (the product of their
 * p(i), cull_keep_hidden). */
static int32_t group_size(frame_ctx *f, const cull_held *iq, int32_t i) {
  int32_t k = 1;
  double p = cull_keep_hidden(cull_state(f, iq->p[i].e)->hidden_frames);
  while (i + k < iq->n) {
    double p2 = p * cull_keep_hidden(cull_state(f, iq->p[i + k].e)->hidden_frames);
    double now = k / (1.0 + (1.0 - p) * k), next = (k + 1) / (1.0 + (1.0 - p2) * (k + 1));
    if (!(next > now)) break;
    p = p2;
    k++;
  }
  return k;
}

/* One query over the boxes of the k elements of the i-queue from the i-th
 * on; its members wait for the answer (query_individual_nodes). */
static void issue_multiquery(frame_ctx *f, chcpp_state *s, int32_t i, int32_t k) {
  cull_held *m = &s->members;
  if (!zs_grow((void **)&m->p, &m->cap, m->n + k, sizeof *m->p)) {
    cull_out_of_memory(f);
    return;
  }
  memcpy(m->p + m->n, s->i_queue.p + i, (size_t)k * sizeof *m->p);
  const pending *first = &m->p[m->n];
  cull_query_elements(f, first, k, (query_entry){first->e, 0, first->mask, 0, m->n, k});
  m->n += k;
}

/* The paper's IssueMultiQueries: the i-queue in groups, a group of one as
 * a plain query. */
static void issue_multiqueries(frame_ctx *f, chcpp_state *s) {
  const cull_held *iq = &s->i_queue;
  int32_t i = 0;
  while (i < iq->n && f->status == ZS_OK) {
    int32_t k = group_size(f, iq, i);
    if (k == 1) cull_issue_query(f, iq->p[i].e, iq->p[i].mask, iq->p[i].was_visible);
    else issue_multiquery(f, s, i, k);
    i += k;
  }
  s->i_queue.n = 0;
}

/* The paper's QueryIndividualNodes, for a multiquery's answer: with a
 * sample, each member is asked again on its own; without, all are
 * hidden, for one query. */
static void query_individual_nodes(frame_ctx *f, const query_entry *q, int visible) {
  const chcpp_state *s = f->c->own;
  const pending *m = s->members.p + q->group;
  for (int32_t i = 0; i < q->ngroup && f->status == ZS_OK; i++) {
    if (visible) {
      cull_issue_query(f, m[i].e, m[i].mask, m[i].was_visible);
      continue;
    }
    cull_state(f, m[i].e)->pv = 0.0;
    cull_state(f, m[i].e)->hidden_frames++;
    cull_decide(f, m[i].e, ZS_NODE_QUERIED_HIDDEN);
    f->st->queries_hidden++;
  }
}

/* How a variant asks about an element (its query, or not). */
typedef void ask_fn(frame_ctx *f, elem e, unsigned mask);

/* ---- an element that was hidden ---- */

static void ask_now(frame_ctx *f, elem e, unsigned mask) { cull_issue_query(f, e, mask, 0); }

/* The paper's QueryPreviouslyInvisibleNode: into the i-queue, which goes
 * out when it holds a batch. */
static void ask_in_batch(frame_ctx *f, elem e, unsigned mask) {
  chcpp_state *s = f->c->own;
  if (cull_hold(f, &s->i_queue, e, mask, 0) && s->i_queue.n >= ZS_CHCPP_BATCH)
    issue_multiqueries(f, s);
}

static void ask_in_batch_single(frame_ctx *f, elem e, unsigned mask) {
  chcpp_state *s = f->c->own;
  if (cull_hold(f, &s->i_queue, e, mask, 0) && s->i_queue.n >= ZS_CHCPP_BATCH)
    cull_issue_held(f, &s->i_queue);
}

/* chcpp-prob: when the query does not pay (2, 3), drawn unasked. */
static void ask_in_batch_if_it_pays(frame_ctx *f, elem e, unsigned mask) {
  double pv = cull_predict(f, cull_state(f, e));
  if (cull_query_pays(f, e, pv)) ask_in_batch(f, e, mask);
  else cull_draw_unasked(f, e, mask, pv);
}

/* ---- a visible object, drawn now ---- */

static void ask_visible_now(frame_ctx *f, elem e, unsigned mask) { cull_issue_query(f, e, mask, 1); }

/* Assumed visible until its query falls due; then the query waits in the
 * v-queue. */
static void ask_visible_when_due(frame_ctx *f, elem e, unsigned mask) {
  chcpp_state *s = f->c->own;
  if (cull_state(f, e)->next_query > f->c->frame) cull_pull_up_visibility(f, e);
  else cull_hold(f, &s->v_queue, e, mask, 1);
}

static void ask_visible_when_due_if_it_pays(frame_ctx *f, elem e, unsigned mask) {
  chcpp_state *s = f->c->own;
  elem_state *es = cull_state(f, e);
  double pv = cull_predict(f, es);
  if (es->next_query > f->c->frame) {
    cull_pull_up_visibility(f, e);
  } else if (!cull_query_pays(f, e, pv)) { /* due, but not worth asking (2, 3) */
    es->pv = pv;
    cull_pull_up_visibility(f, e);
  } else {
    cull_hold(f, &s->v_queue, e, mask, 1);
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

/* Issues the oldest due query of the v-queue (filling idle time). */
static void issue_one_visible(frame_ctx *f, chcpp_state *s) {
  cull_held *vq = &s->v_queue;
  pending p = vq->p[0];
  memmove(vq->p, vq->p + 1, (size_t)(--vq->n) * sizeof *vq->p);
  cull_issue_query(f, p.e, p.mask, p.was_visible);
}

static void issue_batch_single(frame_ctx *f, chcpp_state *s) { cull_issue_held(f, &s->i_queue); }

/* Waiting for an answer: a due visible query first, else the batch; with
 * no query out, the batch first. */
static inline int idle(frame_ctx *f, int waiting, void (*issue_batch)(frame_ctx *, chcpp_state *)) {
  chcpp_state *s = f->c->own;
  if (waiting && s->v_queue.n > 0) issue_one_visible(f, s);
  else if (s->i_queue.n > 0) issue_batch(f, s);
  else if (s->v_queue.n > 0) issue_one_visible(f, s);
  else return 0;
  return 1;
}

static int idle_grouped(frame_ctx *f, int waiting) { return idle(f, waiting, issue_multiqueries); }
static int idle_single(frame_ctx *f, int waiting) { return idle(f, waiting, issue_batch_single); }

static void answered(frame_ctx *f, const query_entry *q, int visible) {
  if (visible && is_object(q->e)) cull_ask_again_later(f, q->e, q->was_visible);
}

#define CHCPP_HOOKS(visit_fn, idle_fn)                                                        \
  {.visit = visit_fn, .idle = idle_fn, .answered = answered,                                 \
   .multiquery_answered = query_individual_nodes, .draw_visible = cull_draw_visible}
static const cull_hooks chcpp = CHCPP_HOOKS(visit_chcpp, idle_grouped);
static const cull_hooks nobatch = CHCPP_HOOKS(visit_nobatch, idle_grouped);
static const cull_hooks nodefer = CHCPP_HOOKS(visit_nodefer, idle_grouped);
static const cull_hooks nomulti = CHCPP_HOOKS(visit_nomulti, idle_single);
static const cull_hooks prob = CHCPP_HOOKS(visit_prob, idle_grouped);
static const cull_hooks prob_measured = {.visit = visit_prob,
                                         .idle = idle_grouped,
                                         .answered = answered,
                                         .multiquery_answered = query_individual_nodes,
                                         .draw_visible = cull_draw_visible_measured,
                                         .measure_due = cull_measure_every_draw,
                                         .drawn = cull_measured_drawn};

/* Every frame starts with the queues empty (a frame that failed may have
 * left some). */
static void begin(frame_ctx *f) {
  chcpp_state *s = f->c->own;
  s->i_queue.n = s->v_queue.n = s->members.n = 0;
}

static void begin_prob(frame_ctx *f) {
  chcpp_state *s = f->c->own;
  begin(f);
  cull_cost_frame(f, &s->model, &prob_measured);
}

#define CHCPP_OPS(name_str, hooks_table, begin_fn)                                            \
  {.name = name_str, .create = create, .destroy = destroy, .frame = cull_traverse_octree,    \
   .begin = begin_fn, .hooks = &hooks_table}
const cull_ops cull_chcpp = CHCPP_OPS("chcpp", chcpp, begin);
const cull_ops cull_chcpp_nobatch = CHCPP_OPS("chcpp-nobatch", nobatch, begin);
const cull_ops cull_chcpp_nodefer = CHCPP_OPS("chcpp-nodefer", nodefer, begin);
const cull_ops cull_chcpp_nomulti = CHCPP_OPS("chcpp-nomulti", nomulti, begin);
const cull_ops cull_chcpp_prob = CHCPP_OPS("chcpp-prob", prob, begin_prob);
