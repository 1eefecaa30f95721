/* auto: chc-prob with w1 and w2 learnt from the outcomes of its own
 * queries, and plain vfc for the frames after one whose queries (or, in a
 * vfc frame, whose draws) found nothing hidden: a scene without occlusion
 * pays no query cost.  The frame's hooks are chosen when it begins. */
#include <stdlib.h>

#include "cull/internal.h"

/* What auto keeps: chc-prob's cost model, and the mode of the next frame
 * (the first is vfc's). */
typedef struct auto_state {
  cull_cost_model model;
  int use_queries;
} auto_state;

static void *create(void) { return calloc(1, sizeof(auto_state)); }

static void destroy(void *own) {
  auto_state *a = own;
  cull_cost_model_free(&a->model);
  free(a);
}

static void begin(frame_ctx *f) {
  auto_state *a = f->c->own;
  f->st->chosen = a->use_queries ? ZS_CULL_CHC_PROB : ZS_CULL_VFC;
  f->hooks = !a->use_queries              ? &cull_vfc_hooks
             : f->c->cost.measure != 0.0 ? &cull_chc_prob_measured_hooks
                                         : &cull_chc_prob_hooks;
  if (!cull_cost_begin(f, &a->model) || !a->use_queries) return;
  cull_learn_weights(f, 0.5, 0.5, 2.0); /* from one outcome each way */
}

/* Queries pay when the draws show hidden objects (vfc frames), or when the
 * queries found hidden nodes (chc-prob frames). */
static void end(frame_ctx *f) {
  auto_state *a = f->c->own;
  if (f->status != ZS_OK) return;
  a->use_queries = a->use_queries ? f->st->queries_hidden > 0 || f->hidden_objects > 0
                                  : f->hidden_objects > 0;
}

const cull_ops cull_auto = {.name = "auto", .create = create, .destroy = destroy,
                            .frame = cull_traverse_octree, .begin = begin, .end = end};
