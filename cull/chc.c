/* chc, coherent hierarchical culling (Bittner, Wimmer, Piringer,
 * Purgathofer 2004), and chc-prob, chc with the cost-model paper's test.
 *
 * Only the termination elements are asked about: the objects (the leaves)
 * and the nodes that were hidden; a node that was visible is opened
 * without a query.  chc draws a leaf visible last frame without waiting:
 * its answer is for the next frame.  chc-prob asks only where the answer
 * pays for itself (cost.c), and so waits for it (the paper's flow: an
 * element asked goes to the query queue, only one not asked is drawn at
 * once); a leaf found hidden is not drawn this frame. */
#include "cull/internal.h"

/* The paper's loop body for a node in the frustum: IssueOcclusionQuery
 * when leafOrWasInvisible, TraverseNode at once when wasVisible (a leaf's
 * query then only tells the next frame). */
static void chc_visit(frame_ctx *f, elem e, unsigned mask) {
  int was_visible, seen_last;
  if (!cull_enter(f, e, mask, &was_visible, &seen_last)) return;
  const int leaf_or_was_invisible = is_object(e) || !was_visible;
  if (leaf_or_was_invisible) cull_issue_query(f, e, mask, (unsigned char)was_visible);
  if (was_visible) cull_traverse_node(f, e, mask);
}

/* Hidden in the frame before: found so, or not reached because a node
 * above it was found so (its parent, which pushed it, was visited before
 * it this frame and set its own flag). */
static void note_hidden_before(frame_ctx *f, elem e) {
  elem_state *es = cull_state(f, e);
  elem up = cull_parent_of(f, e);
  es->hidden_before = es->last_visited == f->c->frame - 1
                          ? !es->visible
                          : up != ZS_OCTREE_NONE && cull_state(f, up)->hidden_before;
}

static void chc_prob_visit(frame_ctx *f, elem e, unsigned mask) {
  int was_visible, seen_last;
  note_hidden_before(f, e);
  if (!cull_enter(f, e, mask, &was_visible, &seen_last)) return;
  if (!is_object(e) && was_visible) {
    cull_traverse_node(f, e, mask);
    return;
  }
  /* (11) from last frame's P(V): es->pv is unchanged so far, but an
   * element under a node found hidden was hidden too, P_{t-1}(V) = 0,
   * whatever it was when last seen (one outside the frustum then keeps
   * that) */
  elem_state *es = cull_state(f, e);
  if (!seen_last && es->hidden_before) es->pv = 0.0;
  double pv = cull_predict(f, es);
  if (cull_query_pays(f, e, pv)) cull_issue_query(f, e, mask, (unsigned char)was_visible);
  else cull_draw_unasked(f, e, mask, pv);
}

static const cull_hooks chc_hooks = {.visit = chc_visit, .draw_visible = cull_draw_visible};
const cull_hooks cull_chc_prob_hooks = {.visit = chc_prob_visit, .draw_visible = cull_draw_visible};
const cull_hooks cull_chc_prob_measured_hooks = {.visit = chc_prob_visit,
                                                 .draw_visible = cull_draw_visible_measured,
                                                 .measure_due = cull_measure_every_draw,
                                                 .drawn = cull_measured_drawn};

static void chc_prob_begin(frame_ctx *f) {
  cull_cost_frame(f, f->c->own, &cull_chc_prob_measured_hooks);
}

const cull_ops cull_chc = {.name = "chc", .frame = cull_traverse_octree, .hooks = &chc_hooks};
const cull_ops cull_chc_prob = {.name = "chc-prob", .create = cull_cost_model_create,
                                .destroy = cull_cost_model_destroy, .frame = cull_traverse_octree,
                                .begin = chc_prob_begin, .hooks = &cull_chc_prob_hooks};
