/* auto: chc-prob with w1 and w2 learnt from the outcomes of its own
 * queries, and plain vfc for the frames after one whose queries (or, in a
 * vfc frame, whose draws) found nothing hidden: a scene without occlusion
 * pays no query cost.  The frame's hooks are chosen when it begins. */
#include "cull/internal.h"

static void begin(frame_ctx *f) {
  const zs_culler *c = f->c;
  f->st->chosen = c->use_queries ? ZS_CULL_CHC_PROB : ZS_CULL_VFC;
  f->hooks = !c->use_queries           ? &cull_vfc_hooks
             : c->cost.measure != 0.0 ? &cull_chc_prob_measured_hooks
                                      : &cull_chc_prob_hooks;
  if (!cull_cost_begin(f) || !c->use_queries) return;
  cull_learn_weights(f, 0.5, 0.5, 2.0); /* from one outcome each way */
}

/* Queries pay when the draws show hidden objects (vfc frames), or when the
 * queries found hidden nodes (chc-prob frames). */
static void end(frame_ctx *f) {
  zs_culler *c = f->c;
  if (f->status != ZS_OK) return;
  c->use_queries = c->use_queries ? f->st->queries_hidden > 0 || f->hidden_objects > 0
                                  : f->hidden_objects > 0;
}

const cull_ops cull_auto = {.name = "auto",
                            .frame = cull_traverse_octree,
                            .begin = begin,
                            .end = end};
