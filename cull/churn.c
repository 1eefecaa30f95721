/* The churn of ideal-box's set and its floors (churn.h). */
#include "cull/churn.h"

#include <stdlib.h>
#include <string.h>

#include "util/grow.h"

int cull_churn_begin(zs_churn *ch, int32_t n) {
  if (n != ch->n) ch->have_last = 0;
  ch->n = n;
  if (n > ch->cap) { /* every array to the same capacity */
    void **arr[] = {(void **)&ch->visible[0], (void **)&ch->visible[1], (void **)&ch->inside[0],
                    (void **)&ch->inside[1],  (void **)&ch->pixels[0],  (void **)&ch->pixels[1],
                    (void **)&ch->draw_ps,    (void **)&ch->rank};
    const size_t size[] = {1, 1, 1, 1, sizeof(uint32_t), sizeof(uint32_t), sizeof(int64_t),
                           sizeof(uint64_t)};
    int32_t cap = ch->cap;
    for (size_t k = 0; k < sizeof size / sizeof size[0]; k++) {
      cap = ch->cap; /* each array grows from the same capacity to the same */
      if (!zs_grow(arr[k], &cap, n, size[k])) return 0;
    }
    ch->cap = cap;
  }
  memset(ch->pixels[0], 0, (size_t)n * sizeof **ch->pixels);
  return 1;
}

static int cmp_u64(const void *a, const void *b) {
  uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return (x > y) - (x < y);
}

void cull_churn_compare(zs_churn *ch, int64_t query_ps, zs_cull_stats *st) {
  st->set_entered = st->set_entered_outside = st->set_left = st->set_left_outside = 0;
  st->churn_known_ps = st->churn_ranked_ps = 0;
  if (ch->have_last) {
    const uint8_t *vis = ch->visible[0], *was = ch->visible[1];
    const uint8_t *in = ch->inside[0], *was_in = ch->inside[1];
    int32_t nrank = 0;
    for (int32_t i = 0; i < ch->n; i++) {
      if (vis[i] && !was[i]) {
        st->set_entered++;
        st->set_entered_outside += !was_in[i];
      }
      if (was[i] && !vis[i]) {
        st->set_left++;
        st->set_left_outside += !in[i];
      }
      if (was[i] && in[i]) ch->rank[nrank++] = (uint64_t)ch->pixels[1][i] << 32 | (uint32_t)i;
    }
    const int64_t entered = (int64_t)(st->set_entered - st->set_entered_outside);
    const int64_t left = (int64_t)(st->set_left - st->set_left_outside);
    st->churn_known_ps = (entered + left) * query_ps;
    /* ranked: asking the first k costs k queries, and the objects after
     * them that left are drawn for nothing; the least over k = 0..nrank */
    qsort(ch->rank, (size_t)nrank, sizeof *ch->rank, cmp_u64);
    int64_t unasked = 0;
    for (int32_t j = 0; j < nrank; j++) {
      int32_t i = (int32_t)(ch->rank[j] & 0xFFFFFFFFu);
      if (!vis[i]) unasked += ch->draw_ps[i];
    }
    int64_t best = unasked;
    for (int32_t j = 0; j < nrank; j++) {
      int32_t i = (int32_t)(ch->rank[j] & 0xFFFFFFFFu);
      if (!vis[i]) unasked -= ch->draw_ps[i];
      int64_t cost = (int64_t)(j + 1) * query_ps + unasked;
      if (cost < best) best = cost;
    }
    st->churn_ranked_ps = entered * query_ps + best;
  }
  /* this frame becomes the last */
  uint8_t *v = ch->visible[0], *in = ch->inside[0];
  uint32_t *px = ch->pixels[0];
  ch->visible[0] = ch->visible[1];
  ch->inside[0] = ch->inside[1];
  ch->pixels[0] = ch->pixels[1];
  ch->visible[1] = v;
  ch->inside[1] = in;
  ch->pixels[1] = px;
  ch->have_last = 1;
}

void cull_churn_free(zs_churn *ch) {
  for (int k = 0; k < 2; k++) {
    free(ch->visible[k]);
    free(ch->inside[k]);
    free(ch->pixels[k]);
  }
  free(ch->draw_ps);
  free(ch->rank);
  memset(ch, 0, sizeof *ch);
}
