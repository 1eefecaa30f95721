/* Queries held back and issued together (internal.h): CHC++'s batch of
 * the elements that were hidden (one change from drawing to querying for
 * the whole batch; chcpp and nohc), its multiqueries (a group of hidden
 * elements under one query, while the group's expected saving grows), and
 * the frame a visible object is asked about again. */
#include <string.h>

#include "cull/internal.h"
#include "util/exactmath.h"
#include "util/grow.h"

int cull_push_pending(frame_ctx *f, pending **q, int32_t *n, int32_t *cap, elem e, unsigned mask,
                      uint8_t was_visible) {
  if (!zs_grow((void **)q, cap, *n + 1, sizeof **q)) {
    cull_out_of_memory(f);
    return 0;
  }
  (*q)[(*n)++] = (pending){e, mask, was_visible};
  return 1;
}

int cull_hold(frame_ctx *f, elem e, unsigned mask, uint8_t was_visible) {
  zs_culler *c = f->c;
  return cull_push_pending(f, &c->iq, &c->ni, &c->cap_iq, e, mask, was_visible);
}

void cull_issue_held(frame_ctx *f) {
  zs_culler *c = f->c;
  for (int32_t i = 0; i < c->ni && f->status == ZS_OK; i++)
    cull_issue_query(f, c->iq[i].e, c->iq[i].mask, c->iq[i].was_visible);
  c->ni = 0;
}

/* The chance that an element hidden i frames in a row stays hidden. */
double cull_keep_hidden(uint32_t i) { return 0.99 - 0.7 * zs_exp(-(double)i); }

/* How many of the held elements from the i-th on go under one query: the
 * group grows while its expected saving k / (1 + (1 - P) k) grows, P the
 * chance that all its members stay hidden. */
static int32_t group_size(frame_ctx *f, int32_t i) {
  const zs_culler *c = f->c;
  int32_t k = 1;
  double p = cull_keep_hidden(cull_state(f, c->iq[i].e)->hidden_frames);
  while (i + k < c->ni) {
    double p2 = p * cull_keep_hidden(cull_state(f, c->iq[i + k].e)->hidden_frames);
    double now = k / (1.0 + (1.0 - p) * k), next = (k + 1) / (1.0 + (1.0 - p2) * (k + 1));
    if (!(next > now)) break;
    p = p2;
    k++;
  }
  return k;
}

/* One query over the boxes of the k held elements from the i-th on; its
 * members wait in gm for the answer (query_queue.c). */
static void issue_multiquery(frame_ctx *f, int32_t i, int32_t k) {
  zs_culler *c = f->c;
  if (!zs_grow((void **)&c->gm, &c->cap_gm, c->ngm + k, sizeof *c->gm)) {
    cull_out_of_memory(f);
    return;
  }
  memcpy(c->gm + c->ngm, c->iq + i, (size_t)k * sizeof *c->gm);
  const pending *first = &c->gm[c->ngm];
  cull_query_elements(f, first, k, (query_entry){first->e, 0, first->mask, 0, c->ngm, k});
  c->ngm += k;
}

void cull_issue_held_grouped(frame_ctx *f) {
  zs_culler *c = f->c;
  int32_t i = 0;
  while (i < c->ni && f->status == ZS_OK) {
    int32_t k = group_size(f, i);
    if (k == 1) cull_issue_query(f, c->iq[i].e, c->iq[i].mask, c->iq[i].was_visible);
    else issue_multiquery(f, i, k);
    i += k;
  }
  c->ni = 0;
}

/* A visible object is asked again ZS_CHCPP_VISIBLE_FRAMES frames on; one
 * that was hidden, after a random first interval, so that the queries do
 * not all fall due in the same frame. */
void cull_ask_again_later(frame_ctx *f, elem e, int was_visible) {
  zs_culler *c = f->c;
  cull_state(f, e)->next_query =
      c->frame + (was_visible ? (uint32_t)ZS_CHCPP_VISIBLE_FRAMES
                              : 1 + (uint32_t)zs_rng_below(&c->rng, ZS_CHCPP_VISIBLE_FRAMES));
}
