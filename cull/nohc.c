/* Near Optimal Hierarchical Culling (Guthe, Balazs, Klein 2006), on the
 * cost-model paper's test: P(V) from the element's history and the screen
 * coverage drawn so far this frame (coverage.h), learnt per class from
 * nohc's own queries; Cq from the box's projected rectangle. */
#include <math.h>
#include <stdlib.h>

#include "cull/coverage.h"
#include "cull/internal.h"

/* Draws measured every NOHC_MEASURE frames; queries in batches of
 * NOHC_BATCH; the classes of history (unseen; hidden 1 .. NOHC_HIDDEN
 * frames in a row; visible, by log2(s + 1) of the pixels s it wrote, up to
 * NOHC_WROTE) times NOHC_BUCKETS of coverage. */
enum {
  NOHC_MEASURE = 4,
  NOHC_BATCH = 32,
  NOHC_HIDDEN = 8,
  NOHC_WROTE = 24,
  NOHC_HISTORIES = 1 + NOHC_HIDDEN + NOHC_WROTE,
  NOHC_BUCKETS = 10,
  NOHC_CLASSES = NOHC_HISTORIES * NOHC_BUCKETS
};

/* Per element, across frames. */
typedef struct nohc_elem {
  uint32_t samples;        /* an object: pixels its last measured draw wrote */
  int32_t asked_class;     /* the class its query was decided on, or -1 */
} nohc_elem;

/* What nohc keeps: its cost model, its batch of held queries, this
 * frame's coverage grid, per class how often an element asked about was
 * found visible and hidden, and its own per-element state (nodes by slot,
 * objects by instance, as the culler's). */
typedef struct nohc_state {
  cull_cost_model model;
  cull_held batch;
  zs_coverage cov;
  uint32_t class_visible[NOHC_CLASSES], class_hidden[NOHC_CLASSES];
  nohc_elem *nodes, *objects;
  int32_t cap_nodes, init_nodes, cap_objects, init_objects;
} nohc_state;

static void *create(void) { return calloc(1, sizeof(nohc_state)); }

static void destroy(void *own) {
  nohc_state *s = own;
  cull_cost_model_free(&s->model);
  cull_held_free(&s->batch);
  zs_coverage_free(&s->cov);
  free(s->nodes);
  free(s->objects);
  free(s);
}

static nohc_elem *nohc_elem_of(const frame_ctx *f, elem e) {
  const nohc_state *s = f->c->own;
  return is_object(e) ? &s->objects[object_of(e)] : &s->nodes[e];
}

/* A mesh fills about this share of its box's rectangle. */
static const double nohc_fill = 0.5;

/* A drawn object covers about nohc_fill of its box's rectangle. */
static void add_coverage(frame_ctx *f, int32_t i) {
  nohc_state *s = f->c->own;
  double r[4];
  zs_coverage_rect(&s->cov, f->t->olo[i], f->t->ohi[i], r);
  zs_device_cpu_work(f->dev, ZS_CPU_COST_EVAL, 1);
  zs_coverage_add(&s->cov, r, nohc_fill);
}

static int measure_due(const frame_ctx *f, int32_t i) {
  return f->c->frame >= f->c->os[i].next_query;
}

/* nohc measures an object it draws every NOHC_MEASURE frames (the first
 * time at random, so that the measurements spread over the frames): it
 * draws it inside a query, whose count of written pixels is its history
 * from the next frame on, when a GPU's answer would long be there (the
 * device's count is the query's). */
static void drawn(frame_ctx *f, int32_t i, int measured, uint64_t written) {
  elem_state *es = &f->c->os[i];
  if (measured) {
    const uint32_t samples = written > UINT32_MAX ? UINT32_MAX : (uint32_t)written;
    nohc_elem_of(f, object_elem(i))->samples = samples;
    es->next_query = f->c->frame + (es->next_query == 0
                                        ? 1 + (uint32_t)zs_rng_below(&f->c->rng, NOHC_MEASURE)
                                        : (uint32_t)NOHC_MEASURE);
  }
  es->hidden_frames = 0;
  add_coverage(f, i);
}

/* The history of an element: 0 unseen (not in last frame's traversal), 1 .. 8
 * hidden that many frames in a row, then an object visible that wrote s
 * pixels in its class log2(s + 1). */
static int32_t history_of(const elem_state *es, const nohc_elem *ne, int was_visible, int seen_last,
                          int object) {
  if (was_visible && object) {
    int32_t k = 0;
    for (uint32_t s = ne->samples; s > 0 && k < NOHC_WROTE - 1; s >>= 1) k++;
    return 1 + NOHC_HIDDEN + k;
  }
  if (seen_last && !was_visible)
    return es->hidden_frames < 1 ? 1 : es->hidden_frames > NOHC_HIDDEN ? NOHC_HIDDEN
                                                                       : (int32_t)es->hidden_frames;
  return 0;
}

/* A termination element: P(V) from its history and this frame's coverage,
 * then query-and-wait or draw (open, for a node). */
static void decide(frame_ctx *f, elem e, unsigned mask, int was_visible, int seen_last) {
  nohc_state *s = f->c->own;
  elem_state *es = cull_state(f, e);
  nohc_elem *ne = nohc_elem_of(f, e);
  const double *lo, *hi;
  cull_elem_box(f, e, &lo, &hi);
  double r[4];
  zs_coverage_rect(&s->cov, lo, hi, r);
  f->st->cost_evals++;
  zs_device_cpu_work(f->dev, ZS_CPU_COST_EVAL, 1);
  /* P(V): the rate at which elements of its class (history, coverage)
   * were found visible, starting from a prior worth two outcomes: for
   * the hidden, chcpp's 1 - p(i); else the coverage's 1 - P(covered). */
  double cov = zs_coverage_covered(&s->cov, r);
  int32_t h = history_of(es, ne, was_visible, seen_last, is_object(e));
  int32_t k = h * NOHC_BUCKETS + (int32_t)fmin(cov * NOHC_BUCKETS, NOHC_BUCKETS - 1);
  double prior = h >= 1 && h <= NOHC_HIDDEN ? 1.0 - cull_keep_hidden((uint32_t)h) : 1.0 - cov;
  const uint32_t seen = s->class_visible[k] + s->class_hidden[k];
  double pv = (s->class_visible[k] + 2.0 * prior) / (seen + 2.0);
  double area = fmax(r[2] - r[0], 0.0) * fmax(r[3] - r[1], 0.0);
  double cr = cull_render_cost(f, e);
  double cq = f->tquery + area * f->tq;                       /* (10), S the rectangle's */
  if (cr > pv * cr + cq) {                                    /* (2), (3) */
    ne->asked_class = k;
    /* its batch: issued when full or when nothing else is left to do */
    if (cull_hold(f, &s->batch, e, mask, (uint8_t)was_visible) && s->batch.n >= NOHC_BATCH)
      cull_issue_held(f, &s->batch);
    return;
  }
  cull_pull_up_visibility(f, e);
  cull_traverse_node(f, e, mask);
}

/* Every termination element (an object, visible or not, or a node that
 * was hidden) is decided on; a node that was visible is opened. */
static void visit(frame_ctx *f, elem e, unsigned mask) {
  int was_visible, seen_last;
  if (!cull_enter(f, e, mask, &was_visible, &seen_last)) return;
  if (is_object(e) || !was_visible) decide(f, e, mask, was_visible, seen_last);
  else cull_traverse_node(f, e, mask);
}

/* Nothing left to traverse: the batch goes out, part-full. */
static void empty(frame_ctx *f) {
  nohc_state *s = f->c->own;
  if (s->batch.n > 0) cull_issue_held(f, &s->batch);
}

/* How the element's history class turned out; a visible object's next
 * measured draw falls when chcpp would ask about it again (query_batch.c). */
static void answered(frame_ctx *f, const query_entry *q, int visible) {
  nohc_state *s = f->c->own;
  nohc_elem *ne = nohc_elem_of(f, q->e);
  int32_t k = ne->asked_class;
  if (k >= 0) {
    visible ? s->class_visible[k]++ : s->class_hidden[k]++;
    ne->asked_class = -1;
  }
  if (visible && is_object(q->e)) cull_ask_again_later(f, q->e, q->was_visible);
}

/* Its elements' state for the frame's tree and scene (new ones unmeasured
 * and not asked about), the cost model's constants, with T counting 2/32
 * of a switch (a batch pays its two switches once), and an empty coverage
 * grid. */
static void begin(frame_ctx *f) {
  static const nohc_elem fresh = {0, -1};
  nohc_state *s = f->c->own;
  s->batch.n = 0;
  if (!cull_grow_elements((void **)&s->nodes, &s->cap_nodes, &s->init_nodes, f->t->nslots,
                          sizeof *s->nodes, &fresh) ||
      !cull_grow_elements((void **)&s->objects, &s->cap_objects, &s->init_objects, f->s->ninst,
                          sizeof *s->objects, &fresh)) {
    cull_out_of_memory(f);
    return;
  }
  if (!cull_cost_begin(f, &s->model)) return;
  const zs_clock_params *k = zs_device_clock_params(f->dev);
  if (f->c->cost.t_ns < 0)
    f->tquery = k->per_call_ns + 2.0 * k->cpu_per_query_ns + 2.0 * k->switch_ns / NOHC_BATCH;
  const zs_device_config *cfg = zs_device_config_of(f->dev);
  if (!zs_coverage_reset(&s->cov, cfg->width, cfg->height, f->view, f->proj))
    cull_out_of_memory(f);
}

static const cull_hooks hooks = {.visit = visit,
                                 .empty = empty,
                                 .draw_visible = cull_draw_visible,
                                 .answered = answered,
                                 .measure_due = measure_due,
                                 .drawn = drawn};
const cull_ops cull_nohc = {.name = "nohc", .create = create, .destroy = destroy,
                            .frame = cull_traverse_octree, .begin = begin, .hooks = &hooks};
