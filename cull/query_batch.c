/* Queries held back and issued together (internal.h): a list of held
 * elements, which CHC++'s i-queue and v-queue and nohc's batch each are,
 * issued one query each; CHC++'s chance that a hidden element stays
 * hidden, which its multiqueries and nohc's prior use; and the frame a
 * visible object is asked about again. */
#include <stdlib.h>

#include "cull/internal.h"
#include "util/exactmath.h"
#include "util/grow.h"

int cull_hold(frame_ctx *f, cull_held *h, elem e, unsigned mask, uint8_t was_visible) {
  if (!zs_grow((void **)&h->p, &h->cap, h->n + 1, sizeof *h->p)) {
    cull_out_of_memory(f);
    return 0;
  }
  h->p[h->n++] = (pending){e, mask, was_visible};
  return 1;
}

void cull_issue_held(frame_ctx *f, cull_held *h) {
  for (int32_t i = 0; i < h->n && f->status == ZS_OK; i++)
    cull_issue_query(f, h->p[i].e, h->p[i].mask, h->p[i].was_visible);
  h->n = 0;
}

void cull_held_free(cull_held *h) {
  free(h->p);
  *h = (cull_held){0};
}

/* The chance that an element hidden i frames in a row stays hidden. */
double cull_keep_hidden(uint32_t i) { return 0.99 - 0.7 * zs_exp(-(double)i); }

/* A visible object is asked again ZS_CHCPP_VISIBLE_FRAMES frames on; one
 * that was hidden, after a random first interval, so that the queries do
 * not all fall due in the same frame. */
void cull_ask_again_later(frame_ctx *f, elem e, int was_visible) {
  zs_culler *c = f->c;
  cull_state(f, e)->next_query =
      c->frame + (was_visible ? (uint32_t)ZS_CHCPP_VISIBLE_FRAMES
                              : 1 + (uint32_t)zs_rng_below(&c->rng, ZS_CHCPP_VISIBLE_FRAMES));
}
