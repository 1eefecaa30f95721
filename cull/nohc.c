/* Near Optimal Hierarchical Culling (Guthe, Balazs, Klein 2006), on the
 * cost-model paper's test: P(V) from the element's history and the screen
 * coverage drawn so far this frame (coverage.h), learnt per class from
 * nohc's own queries; Cq from the box's projected rectangle. */
#include <math.h>

#include "cull/internal.h"

/* A mesh fills about this share of its box's rectangle. */
static const double nohc_fill = 0.5;

/* A drawn object covers about nohc_fill of its box's rectangle. */
static void add_coverage(frame_ctx *f, int32_t i) {
  double r[4];
  zs_coverage_rect(&f->c->cov, f->t->olo[i], f->t->ohi[i], r);
  zs_device_cpu_work(f->dev, ZS_CPU_COST_EVAL, 1);
  zs_coverage_add(&f->c->cov, r, nohc_fill);
}

int cull_nohc_measure_due(const frame_ctx *f, int32_t i) {
  return f->c->frame >= f->c->os[i].next_query;
}

/* nohc measures an object it draws every NOHC_MEASURE frames (the first
 * time at random, so that the measurements spread over the frames): it
 * draws it inside a query, whose count of written pixels is its history
 * from the next frame on, when a GPU's answer would long be there (the
 * device's count is the query's). */
void cull_nohc_drawn(frame_ctx *f, int32_t i, int measured, uint64_t written) {
  elem_state *es = &f->c->os[i];
  if (measured) {
    es->samples = written > UINT32_MAX ? UINT32_MAX : (uint32_t)written;
    es->next_query = f->c->frame + (es->next_query == 0
                                        ? 1 + (uint32_t)zs_rng_below(&f->c->rng, NOHC_MEASURE)
                                        : (uint32_t)NOHC_MEASURE);
  }
  es->hidden_frames = 0;
  add_coverage(f, i);
}

/* The history of an element: 0 unseen (not in last frame's walk), 1 .. 8
 * hidden that many frames in a row, then an object visible that wrote s
 * pixels in its class log2(s + 1). */
static int32_t history_of(const elem_state *es, int was_visible, int seen_last, int object) {
  if (was_visible && object) {
    int32_t k = 0;
    for (uint32_t s = es->samples; s > 0 && k < NOHC_WROTE - 1; s >>= 1) k++;
    return 1 + NOHC_HIDDEN + k;
  }
  if (seen_last && !was_visible)
    return es->hidden_frames < 1 ? 1 : es->hidden_frames > NOHC_HIDDEN ? NOHC_HIDDEN
                                                                       : (int32_t)es->hidden_frames;
  return 0;
}

/* A termination element of nohc: P(V) from its history and this frame's
 * coverage, then query-and-wait or draw (open, for a node). */
void cull_nohc_visit(frame_ctx *f, elem e, unsigned mask, int was_visible, int seen_last) {
  zs_culler *c = f->c;
  elem_state *es = cull_state(f, e);
  const double *lo, *hi;
  cull_elem_box(f, e, &lo, &hi);
  double r[4];
  zs_coverage_rect(&c->cov, lo, hi, r);
  f->st->cost_evals++;
  zs_device_cpu_work(f->dev, ZS_CPU_COST_EVAL, 1);
  /* P(V): the rate at which elements of its class (history, coverage)
   * were found visible, starting from a prior worth two outcomes: for
   * the hidden, chcpp's 1 - p(i); else the coverage's 1 - P(covered). */
  double cov = zs_coverage_covered(&c->cov, r);
  int32_t h = history_of(es, was_visible, seen_last, is_object(e));
  int32_t k = h * NOHC_BUCKETS + (int32_t)fmin(cov * NOHC_BUCKETS, NOHC_BUCKETS - 1);
  double prior = h >= 1 && h <= NOHC_HIDDEN ? 1.0 - cull_keep_hidden((uint32_t)h) : 1.0 - cov;
  double pv = (c->class_visible[k] + 2.0 * prior) / (c->class_visible[k] + c->class_hidden[k] + 2.0);
  double area = fmax(r[2] - r[0], 0.0) * fmax(r[3] - r[1], 0.0);
  double cr = cull_render_cost(f, e);
  double cq = f->tquery + area * f->tq;                       /* (10), S measured */
  if (cr > pv * cr + cq) {                                    /* (2), (3) */
    es->asked_class = k;
    cull_push_pending(f, &c->iq, &c->ni, &c->cap_iq, e, mask, (uint8_t)was_visible);
    return;
  }
  cull_pull_up_visibility(f, e);
  cull_traverse(f, e, mask);
}
