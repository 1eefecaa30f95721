/* Visibility culling over the loose octree (cull.h).
 *
 * One traversal serves vfc, hsw, chc, chc-prob and auto.  The traversal
 * queue is a binary heap on the distance from the eye to a node's tight box
 * (front to back, ties by node index), so nearer occluders are drawn before
 * the nodes behind them are queried.  The query queue is a FIFO.  Per node
 * the culler keeps, across frames, the fields of Bittner et al.: visible,
 * lastVisited, and the cost model's P(V); per frame it remembers which
 * nodes it has rendered and traversed, so that a node whose query returns
 * after it was drawn is not drawn twice.
 */
#include "cull/cull.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cull/coverage.h"
#include "cull/frustum.h"
#include "cull/parts.h"
#include "raster/grow.h"
#include "raster/rng.h"

static const char *const method_names[ZS_CULL_METHODS] = {
    "none", "vfc", "vfc-box", "hsw", "chc", "chc-prob", "ideal", "auto",
    "chcpp", "chcpp-nobatch", "chcpp-nodefer", "chcpp-nomulti", "chcpp-prob", "nohc",
    "ideal-box"};

const char *zs_cull_method_name(zs_cull_method m) {
  return (unsigned)m < ZS_CULL_METHODS ? method_names[m] : "?";
}

int zs_cull_method_parse(const char *name) {
  for (int i = 0; i < ZS_CULL_METHODS; i++)
    if (strcmp(name, method_names[i]) == 0) return i;
  return -1;
}

void zs_cost_params_default(zs_cost_params *p) {
  /* w1, w2: the transition rates auto measured over 20 frames of the plant
   * walk (builtin:plant?detail=1), rounded */
  *p = (zs_cost_params){0.93, 0.97, -1.0, -1.0, -1.0, -1.0, 1.0};
}

/* The hierarchy the methods walk: the octree's nodes, with each object as
 * a leaf of the node that holds it (so a visible object does not drag its
 * neighbours in, and a hidden one is culled on its own).  An element is a
 * node n >= 0 or an object i, encoded as -(i + 2). */
typedef int32_t elem;
static inline int is_object(elem e) { return e <= -2; }
static inline int32_t object_of(elem e) { return -e - 2; }
static inline elem object_elem(int32_t i) { return -i - 2; }

/* Across frames, per element. */
typedef struct elem_state {
  uint32_t last_visited;   /* frame (frames count from 1) */
  uint32_t done;           /* frame it was rendered (object) or opened (node) */
  uint8_t visible;
  double pv;               /* P(V) for the next frame */
  uint32_t next_query;     /* chcpp: the frame a visible object is asked again;
                            * nohc: the frame its draw is measured again */
  uint32_t hidden_frames;  /* chcpp: frames found hidden in a row */
  uint32_t samples;        /* nohc: pixels its last draw wrote */
  int32_t asked_class;     /* nohc: history class its query was decided on, or -1 */
} elem_state;

/* chcpp: an element waiting for its query to be issued. */
typedef struct pending {
  elem e;
  unsigned mask;
  uint8_t was_visible;
} pending;

/* nohc: the share of its box's rectangle a mesh fills, for the coverage
 * it adds (cull/coverage.h); draws measured every NOHC_MEASURE frames;
 * queries in batches of NOHC_BATCH; the classes of
 * history (unseen; hidden 1 .. NOHC_HIDDEN frames in a row; visible, by
 * log2(s + 1) of the pixels s it wrote) times NOHC_BUCKETS of coverage. */
enum {
  NOHC_MEASURE = 4,
  NOHC_BATCH = 32,
  NOHC_HIDDEN = 8,
  NOHC_WROTE = 24,
  NOHC_HISTORIES = 1 + NOHC_HIDDEN + NOHC_WROTE,
  NOHC_BUCKETS = 10,
  NOHC_CLASSES = NOHC_HISTORIES * NOHC_BUCKETS
};
static const double nohc_fill = 0.5;

typedef struct heap_entry {
  double key;
  elem e;
  unsigned mask;           /* frustum planes still to test */
} heap_entry;

typedef struct query_entry {
  elem e;
  zs_query q;
  unsigned mask;           /* frustum planes its content still tests */
  uint8_t was_visible;     /* its state before this frame (auto's learning) */
  int32_t group, ngroup;   /* chcpp multiquery: members gm[group ..], 0: single */
} query_entry;

struct zs_culler {
  zs_cull_method method;
  zs_cost_params cost;
  uint32_t frame;
  elem_state *ns, *os;     /* nodes, objects */
  int32_t cap_ns, init_ns, cap_os, init_os;
  heap_entry *heap;
  int32_t nheap, cap_heap;
  query_entry *qq;
  int32_t qhead, qtail, cap_qq;
  int64_t *polys;          /* polygons under each node, this frame */
  int32_t cap_polys;
  uint8_t *decision;       /* zs_node_decision per node, this frame */
  int32_t cap_decision, ndecision;
  /* ideal */
  zs_device *oracle;
  uint8_t *owns_pixel;
  int32_t cap_inst;
  int32_t *owner;          /* face id -> instance */
  uint32_t nowner;
  /* auto: transitions seen by its queries, and the mode of the next frame */
  uint64_t vv, vh, hv, hh;
  int use_queries;
  /* chcpp: the queue of invisible elements to batch, of visible objects
   * whose query is due; the rng of the first visible intervals */
  pending *iq, *vq, *gm;   /* gm: the members of this frame's multiqueries */
  int32_t ni, nv, ngm, cap_iq, cap_vq, cap_gm;
  int multi;               /* multiqueries on */
  zs_rng rng;
  /* nohc: the coverage grid of this frame; per history class, how often an
   * object asked about was found visible and hidden */
  zs_coverage cov;
  /* the boxes of the query being issued; the objects' parts (NULL: boxes) */
  double (*qlo)[3], (*qhi)[3];
  int32_t cap_qlo, cap_qhi;
  zs_parts *parts;
  uint32_t class_visible[NOHC_CLASSES], class_hidden[NOHC_CLASSES];
};

/* ---- the frame's context ---- */

typedef struct frame_ctx {
  zs_culler *c;
  zs_device *dev;
  const zs_scene *s;
  const zs_octree *t;
  zs_frustum frustum;
  double eye[3];
  double near_reach;       /* farthest a near-plane corner lies from the eye */
  double tan_half_fovy, height;
  double ttri, tcall, tq, tquery; /* cost model constants, ns */
  zs_cull_stats *st;
  uint64_t hidden_objects; /* auto: objects drawn that wrote no pixel */
  zs_error *err;
  zs_status status;
} frame_ctx;


zs_status zs_culler_create(zs_cull_method m, const zs_cost_params *cost, zs_culler **out,
                           zs_error *err) {
  *out = NULL;
  if ((unsigned)m >= ZS_CULL_METHODS) return zs_error_set(err, ZS_ERR_ARG, "unknown culling method");
  zs_culler *c = calloc(1, sizeof *c);
  if (!c) return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  c->method = m;
  zs_rng_seed(&c->rng, 0xC4C); /* chcpp's first visible intervals: a fixed seed */
  if (cost) c->cost = *cost;
  else zs_cost_params_default(&c->cost);
  if (!(c->parts = zs_parts_create())) {
    free(c);
    return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  }
  *out = c;
  return ZS_OK;
}

int zs_query_bounds_parse(const char *name) {
  return strcmp(name, "parts") == 0 ? ZS_BOUNDS_PARTS : strcmp(name, "box") == 0 ? ZS_BOUNDS_BOX : -1;
}

zs_status zs_culler_set_bounds(zs_culler *c, zs_query_bounds b, zs_error *err) {
  if (b != ZS_BOUNDS_PARTS && b != ZS_BOUNDS_BOX)
    return zs_error_set(err, ZS_ERR_ARG, "unknown query bounds");
  if (c->frame > 0) return zs_error_set(err, ZS_ERR_ARG, "query bounds: set before the first frame");
  if (b == ZS_BOUNDS_BOX) {
    zs_parts_destroy(c->parts);
    c->parts = NULL;
  } else if (!c->parts && !(c->parts = zs_parts_create())) {
    return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  }
  return ZS_OK;
}

void zs_culler_destroy(zs_culler *c) {
  if (!c) return;
  free(c->ns);
  free(c->os);
  free(c->heap);
  free(c->qq);
  free(c->polys);
  free(c->decision);
  free(c->iq);
  free(c->vq);
  free(c->gm);
  free(c->owns_pixel);
  free(c->owner);
  zs_coverage_free(&c->cov);
  free(c->qlo);
  free(c->qhi);
  zs_parts_destroy(c->parts);
  zs_device_destroy(c->oracle);
  free(c);
}

const uint8_t *zs_culler_decisions(const zs_culler *c, int32_t *n) {
  *n = c->ndecision;
  return c->decision;
}

/* ---- elements ---- */

static elem_state *state(frame_ctx *f, elem e) {
  return is_object(e) ? &f->c->os[object_of(e)] : &f->c->ns[e];
}

/* The box of an element: a node's tight box, an object's own box. */
static void elem_box(const frame_ctx *f, elem e, const double **lo, const double **hi) {
  if (is_object(e)) {
    *lo = f->t->olo[object_of(e)];
    *hi = f->t->ohi[object_of(e)];
  } else {
    *lo = f->t->node[e].tlo;
    *hi = f->t->node[e].thi;
  }
}

static void decide(frame_ctx *f, elem e, zs_node_decision d) {
  if (!is_object(e) && e < f->c->ndecision) f->c->decision[e] = (uint8_t)d;
}

static elem parent_of(const frame_ctx *f, elem e) {
  return is_object(e) ? f->t->home[object_of(e)] : f->t->node[e].parent;
}

static double box_distance2(const double eye[3], const double *lo, const double *hi) {
  double d2 = 0.0;
  for (int k = 0; k < 3; k++) {
    double v = eye[k] < lo[k] ? lo[k] - eye[k] : eye[k] > hi[k] ? eye[k] - hi[k] : 0.0;
    d2 += v * v;
  }
  return d2;
}

/* A drawn object covers about nohc_fill of its box's rectangle. */
static void add_coverage(frame_ctx *f, int32_t i) {
  double r[4];
  zs_coverage_rect(&f->c->cov, f->t->olo[i], f->t->ohi[i], r);
  zs_device_cpu_work(f->dev, ZS_CPU_COST_EVAL, 1);
  zs_coverage_add(&f->c->cov, r, nohc_fill);
}

/* ---- drawing ---- */

static void draw_instance(frame_ctx *f, int32_t i) {
  if (f->status != ZS_OK) return;
  const zs_instance *in = &f->s->inst[i];
  const zs_mesh *m = &f->s->meshes[in->mesh].mesh;
  const int nohc = f->c->method == ZS_CULL_NOHC;
  elem_state *es = nohc ? &f->c->os[i] : NULL; /* (none and the oracles keep no state) */
  /* nohc measures an object it draws every NOHC_MEASURE frames (the first
   * time at random, so that the measurements spread over the frames): it
   * draws it inside a query, whose count of written pixels is its history
   * from the next frame on, when a GPU's answer would long be there (the
   * device's count is the query's). */
  const int measure = nohc && f->c->frame >= es->next_query;
  uint64_t before = zs_device_stats(f->dev)->pixels_written;
  zs_query q;
  if (measure && (f->status = zs_device_query_begin(f->dev, &q, f->err))) return;
  f->status = zs_device_draw(f->dev, m, in->model, in->id_base, in->rgb, f->err);
  if (measure && f->status == ZS_OK) f->status = zs_device_query_end(f->dev, f->err);
  f->st->objects_drawn++;
  f->st->faces_drawn += (uint64_t)m->nfaces;
  uint64_t written = zs_device_stats(f->dev)->pixels_written - before;
  if (written == 0) f->hidden_objects++;
  if (measure) {
    es->samples = written > UINT32_MAX ? UINT32_MAX : (uint32_t)written;
    es->next_query = f->c->frame + (es->next_query == 0
                                        ? 1 + (uint32_t)zs_rng_below(&f->c->rng, NOHC_MEASURE)
                                        : (uint32_t)NOHC_MEASURE);
  }
  if (nohc) {
    es->hidden_frames = 0;
    add_coverage(f, i);
  }
}

/* ---- the traversal queue: a min-heap on (distance, element) ---- */

static int heap_less(const heap_entry *a, const heap_entry *b) {
  return a->key < b->key || (a->key == b->key && a->e < b->e);
}

static int heap_push(frame_ctx *f, elem e, unsigned mask) {
  zs_culler *c = f->c;
  if (!zs_grow((void **)&c->heap, &c->cap_heap, c->nheap + 1, sizeof *c->heap)) return 0;
  const double *lo, *hi;
  elem_box(f, e, &lo, &hi);
  int32_t i = c->nheap++;
  heap_entry h = {box_distance2(f->eye, lo, hi), e, mask};
  while (i > 0 && heap_less(&h, &c->heap[(i - 1) / 2])) {
    c->heap[i] = c->heap[(i - 1) / 2];
    i = (i - 1) / 2;
  }
  c->heap[i] = h;
  return 1;
}

static heap_entry heap_pop(zs_culler *c) {
  heap_entry top = c->heap[0], last = c->heap[--c->nheap];
  int32_t i = 0;
  for (;;) {
    int32_t l = 2 * i + 1, r = l + 1, m = i;
    const heap_entry *best = &last;
    if (l < c->nheap && heap_less(&c->heap[l], best)) m = l, best = &c->heap[l];
    if (r < c->nheap && heap_less(&c->heap[r], best)) m = r;
    if (m == i) break;
    c->heap[i] = c->heap[m];
    i = m;
  }
  if (c->nheap > 0) c->heap[i] = last;
  return top;
}

/* TraverseNode of the paper, once per frame per element: an object is
 * rendered; a node pushes its children and its objects. */
static void traverse(frame_ctx *f, elem e, unsigned mask) {
  elem_state *es = state(f, e);
  if (es->done == f->c->frame) return;
  es->done = f->c->frame;
  if (is_object(e)) {
    draw_instance(f, object_of(e));
    return;
  }
  const zs_octnode *nd = &f->t->node[e];
  int ok = 1;
  for (int o = 0; o < 8 && ok; o++) {
    int32_t ch = nd->child[o];
    if (ch != ZS_OCTREE_NONE && !f->t->node[ch].empty) ok = heap_push(f, ch, mask);
  }
  for (int32_t i = nd->first; i != ZS_OCTREE_NONE && ok; i = f->t->next[i])
    ok = heap_push(f, object_elem(i), mask);
  if (!ok) f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
}

static void pull_up_visibility(frame_ctx *f, elem e) {
  while (e != ZS_OCTREE_NONE && !state(f, e)->visible) {
    state(f, e)->visible = 1;
    e = parent_of(f, e);
  }
}

/* A box that the near plane could cut, or that holds the eye: its query
 * would miss what lies before the plane, so it is not asked. */
static int too_close(const frame_ctx *f, elem e) {
  const double *lo, *hi;
  elem_box(f, e, &lo, &hi);
  return box_distance2(f->eye, lo, hi) <= f->near_reach * f->near_reach;
}

/* ---- the cost model (chc-prob, auto) ---- */

/* (6), extended: Cr = N Ttri + M Tcall, N the polygons and M the objects
 * under e. */
static double render_cost(const frame_ctx *f, elem e) {
  int64_t n = is_object(e) ? f->s->meshes[f->s->inst[object_of(e)].mesh].mesh.nfaces
                           : f->c->polys[e];
  int64_t calls = is_object(e) ? 1 : f->t->node[e].count;
  return (double)n * f->ttri + (double)calls * f->tcall;
}

/* Formulas 2, 3, 6, 9, 10: whether querying e pays, given P(V) = pv. */
static int query_pays(frame_ctx *f, elem e, double pv) {
  const double *lo, *hi;
  elem_box(f, e, &lo, &hi);
  f->st->cost_evals++;
  zs_device_cpu_work(f->dev, ZS_CPU_COST_EVAL, 1);
  double cr = render_cost(f, e);
  double dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
  double abb = 2.0 * (dx * dy + dy * dz + dz * dx);
  double dis = 0.0;
  for (int k = 0; k < 3; k++) {
    double v = 0.5 * (lo[k] + hi[k]) - f->eye[k];
    dis += v * v;
  }
  dis = sqrt(dis);
  double den = 2.0 * dis * f->tan_half_fovy;
  double s = den > 0 ? f->height * f->height * (abb / 6.0) / (den * den) : INFINITY; /* (9) */
  double cq = f->tquery + s * f->c->cost.rho * f->tq;                                /* (10) */
  return cr > pv * cr + cq;                                                          /* (2), (3) */
}

/* (11): the chance that an element is visible this frame, from its state. */
static double predict(const elem_state *es, double w1, double w2) {
  return w1 * es->pv + (1.0 - w2) * (1.0 - es->pv);
}

/* ---- the methods ---- */

/* Appends the boxes a query over element e draws: a node's tight box; an
 * object's parts (parts.h) or its box. */
static int add_query_boxes(frame_ctx *f, elem e, int32_t *n) {
  zs_culler *c = f->c;
  const double(*plo)[3], (*phi)[3];
  const double *lo, *hi;
  int k = 1;
  if (is_object(e) && c->parts) {
    if (!zs_parts_of(c->parts, f->s, object_of(e), &plo, &phi, &k)) return 0;
  } else {
    elem_box(f, e, &lo, &hi);
    plo = (const double(*)[3])lo;
    phi = (const double(*)[3])hi;
  }
  if (!zs_grow((void **)&c->qlo, &c->cap_qlo, *n + k, sizeof *c->qlo) ||
      !zs_grow((void **)&c->qhi, &c->cap_qhi, *n + k, sizeof *c->qhi))
    return 0;
  memcpy(c->qlo + *n, plo, (size_t)k * sizeof *c->qlo);
  memcpy(c->qhi + *n, phi, (size_t)k * sizeof *c->qhi);
  *n += k;
  return 1;
}

/* One query over the boxes of members[0 .. n-1], as one draw call, queued
 * as entry qe. */
static void query_elements(frame_ctx *f, const pending *members, int32_t n, query_entry qe) {
  zs_culler *c = f->c;
  int32_t nbox = 0;
  int ok = zs_grow((void **)&c->qq, &c->cap_qq, c->qtail + 1, sizeof *c->qq);
  for (int32_t i = 0; i < n && ok; i++) ok = add_query_boxes(f, members[i].e, &nbox);
  if (!ok) {
    f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
    return;
  }
  if ((f->status = zs_device_query_begin(f->dev, &qe.q, f->err)) ||
      (f->status = zs_device_query_boxes(f->dev, (const double(*)[3])c->qlo,
                                         (const double(*)[3])c->qhi, nbox, f->err)) ||
      (f->status = zs_device_query_end(f->dev, f->err)))
    return;
  f->st->queries++;
  c->qq[c->qtail++] = qe;
}

static void issue_query(frame_ctx *f, elem e, unsigned mask, unsigned char was_visible) {
  pending one = {e, mask, was_visible};
  query_elements(f, &one, 1, (query_entry){e, 0, mask, was_visible, 0, 0});
}

/* Takes the answer of the query at the head of the queue (waiting for it
 * if need be) and acts on it. */

static void take_result(frame_ctx *f) {
  zs_culler *c = f->c;
  query_entry q = c->qq[c->qhead++];
  int visible = zs_device_query_result(f->dev, q.q) > 0;
  if (q.ngroup > 0) { /* a multiquery */
    if (visible) { /* someone is visible: ask each on its own */
      for (int32_t i = 0; i < q.ngroup && f->status == ZS_OK; i++)
        issue_query(f, c->gm[q.group + i].e, c->gm[q.group + i].mask, c->gm[q.group + i].was_visible);
      return;
    }
    for (int32_t i = 0; i < q.ngroup; i++) { /* all hidden, with one query */
      elem e = c->gm[q.group + i].e;
      state(f, e)->pv = 0.0;
      state(f, e)->hidden_frames++;
      decide(f, e, ZS_NODE_QUERIED_HIDDEN);
      f->st->queries_hidden++;
    }
    return;
  }
  state(f, q.e)->pv = visible ? 1.0 : 0.0; /* observed: the next frame predicts from it */
  int32_t k = state(f, q.e)->asked_class;
  if (k >= 0) { /* nohc: how its history class turned out */
    visible ? c->class_visible[k]++ : c->class_hidden[k]++;
    state(f, q.e)->asked_class = -1;
  }
  if (q.was_visible) visible ? c->vv++ : c->vh++;
  else visible ? c->hv++ : c->hh++;
  decide(f, q.e, visible ? ZS_NODE_QUERIED_VISIBLE : ZS_NODE_QUERIED_HIDDEN);
  if (!visible) {
    state(f, q.e)->hidden_frames++;
    f->st->queries_hidden++;
    return;
  }
  state(f, q.e)->hidden_frames = 0;
  if (is_object(q.e)) { /* chcpp: asked again in a while; at first, at random */
    elem_state *es = state(f, q.e);
    es->next_query = c->frame + (q.was_visible ? (uint32_t)ZS_CHCPP_VISIBLE_FRAMES
                                               : 1 + (uint32_t)zs_rng_below(&c->rng, ZS_CHCPP_VISIBLE_FRAMES));
  }
  pull_up_visibility(f, q.e);
  traverse(f, q.e, q.mask);
}

/* Takes the nearest element of the traversal queue and tests it against
 * the frustum (the planes its parent left in its mask); 0 when outside. */
static int next_in_frustum(frame_ctx *f, elem *e, unsigned *mask) {
  heap_entry h = heap_pop(f->c);
  *e = h.e;
  *mask = h.mask;
  f->st->nodes_visited++;
  zs_device_cpu_work(f->dev, ZS_CPU_NODE, 1);
  const double *lo, *hi;
  elem_box(f, *e, &lo, &hi);
  uint64_t tests = f->st->frustum_tests;
  zs_frustum_result fr =
      *mask ? zs_frustum_test_box(&f->frustum, lo, hi, mask, &f->st->frustum_tests)
            : ZS_FRUSTUM_INSIDE;
  zs_device_cpu_work(f->dev, ZS_CPU_FRUSTUM_TEST, f->st->frustum_tests - tests);
  decide(f, *e, fr == ZS_FRUSTUM_OUTSIDE ? ZS_NODE_OUTSIDE : ZS_NODE_NO_QUERY);
  return fr != ZS_FRUSTUM_OUTSIDE;
}

/* ---- CHC++ ---- */

static int push_pending(frame_ctx *f, pending **q, int32_t *n, int32_t *cap, elem e, unsigned mask,
                        uint8_t was_visible) {
  if (!zs_grow((void **)q, cap, *n + 1, sizeof **q)) {
    f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
    return 0;
  }
  (*q)[(*n)++] = (pending){e, mask, was_visible};
  return 1;
}

/* The chance that an element hidden i frames in a row stays hidden. */
static double keep_hidden(uint32_t i) { return 0.99 - 0.7 * exp(-(double)i); }

/* One query over the boxes of members gm[first .. first + n - 1]. */
static void issue_multiquery(frame_ctx *f, int32_t first, int32_t n) {
  zs_culler *c = f->c;
  query_elements(f, c->gm + first, n, (query_entry){c->gm[first].e, 0, c->gm[first].mask, 0, first, n});
}

/* Issues every query of the invisible queue, one after the other: one
 * change from drawing to querying for the whole batch; with multiqueries,
 * in groups that grow while their expected saving grows. */
static void flush_invisible(frame_ctx *f) {
  zs_culler *c = f->c;
  int32_t i = 0;
  while (i < c->ni && f->status == ZS_OK) {
    int32_t k = 1;
    double p = keep_hidden(state(f, c->iq[i].e)->hidden_frames);
    while (c->multi && i + k < c->ni) {
      double p2 = p * keep_hidden(state(f, c->iq[i + k].e)->hidden_frames);
      double now = k / (1.0 + (1.0 - p) * k), next = (k + 1) / (1.0 + (1.0 - p2) * (k + 1));
      if (!(next > now)) break;
      p = p2;
      k++;
    }
    if (k == 1) {
      issue_query(f, c->iq[i].e, c->iq[i].mask, c->iq[i].was_visible);
    } else {
      if (!zs_grow((void **)&c->gm, &c->cap_gm, c->ngm + k, sizeof *c->gm)) {
        f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
        return;
      }
      memcpy(c->gm + c->ngm, c->iq + i, (size_t)k * sizeof *c->gm);
      issue_multiquery(f, c->ngm, k);
      c->ngm += k;
    }
    i += k;
  }
  c->ni = 0;
}

/* Issues the oldest due query of a visible object (filling idle time). */
static void issue_one_visible(frame_ctx *f) {
  zs_culler *c = f->c;
  pending p = c->vq[0];
  memmove(c->vq, c->vq + 1, (size_t)(--c->nv) * sizeof *c->vq);
  issue_query(f, p.e, p.mask, p.was_visible);
}

/* Draws e as if visible without asking (chcpp-prob, when the query does
 * not pay); its P(V) carries the prediction to the next frame. */
static void draw_unasked(frame_ctx *f, elem e, unsigned mask, double pv) {
  state(f, e)->pv = pv;
  pull_up_visibility(f, e);
  traverse(f, e, mask);
}

/* prob: chcpp-prob, the cost model's test (formulas 2, 3) before every
 * query CHC++ would issue. */
static void walk_chcpp(frame_ctx *f, int batch, int defer, int prob) {
  zs_culler *c = f->c;
  const uint32_t frame = c->frame;
  c->nheap = 0;
  c->qhead = c->qtail = 0;
  c->ni = c->nv = c->ngm = 0;
  if (!f->t->node[ZS_OCTREE_ROOT].empty && !heap_push(f, ZS_OCTREE_ROOT, ZS_FRUSTUM_ALL_PLANES))
    f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
  while (f->status == ZS_OK &&
         (c->nheap > 0 || c->qhead < c->qtail || c->ni > 0 || c->nv > 0)) {
    /* Results: take the ready ones; with nothing to traverse, fill the
     * wait with due visible queries, then the batch, then wait. */
    while (f->status == ZS_OK && c->qhead < c->qtail) {
      if (zs_device_query_ready(f->dev, c->qq[c->qhead].q)) take_result(f);
      else if (c->nheap > 0) break;
      else if (c->nv > 0) issue_one_visible(f);
      else if (c->ni > 0) flush_invisible(f);
      else take_result(f);
    }
    if (f->status != ZS_OK) break;
    if (c->nheap == 0) {
      if (c->ni > 0) flush_invisible(f);
      else if (c->nv > 0) issue_one_visible(f);
      continue;
    }

    elem e;
    unsigned mask;
    if (!next_in_frustum(f, &e, &mask)) continue;
    elem_state *es = state(f, e);
    int was_visible = es->visible && es->last_visited == frame - 1;
    double pv = predict(es, c->cost.w1, c->cost.w2);
    es->visible = 0;
    es->last_visited = frame;
    if (too_close(f, e)) {
      es->pv = 1.0;
      pull_up_visibility(f, e);
      traverse(f, e, mask);
      continue;
    }
    if (!was_visible) { /* a termination element that was hidden: ask */
      if (prob && !query_pays(f, e, pv)) draw_unasked(f, e, mask, pv);
      else if (!batch) issue_query(f, e, mask, 0);
      else if (push_pending(f, &c->iq, &c->ni, &c->cap_iq, e, mask, 0) && c->ni >= ZS_CHCPP_BATCH)
        flush_invisible(f);
      continue;
    }
    if (is_object(e)) { /* a visible leaf: drawn now, asked when due */
      if (!defer) issue_query(f, e, mask, 1);
      else if (es->next_query > frame) pull_up_visibility(f, e); /* assumed visible this frame */
      else if (prob && !query_pays(f, e, pv)) { /* due, but not worth asking */
        es->pv = pv;
        pull_up_visibility(f, e);
      } else push_pending(f, &c->vq, &c->nv, &c->cap_vq, e, mask, 1);
    }
    traverse(f, e, mask);
  }
}

/* ---- nohc ---- */

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
static void nohc_visit(frame_ctx *f, elem e, unsigned mask, int was_visible, int seen_last) {
  zs_culler *c = f->c;
  elem_state *es = state(f, e);
  const double *lo, *hi;
  elem_box(f, e, &lo, &hi);
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
  double prior = h >= 1 && h <= NOHC_HIDDEN ? 1.0 - keep_hidden((uint32_t)h) : 1.0 - cov;
  double pv = (c->class_visible[k] + 2.0 * prior) / (c->class_visible[k] + c->class_hidden[k] + 2.0);
  double area = fmax(r[2] - r[0], 0.0) * fmax(r[3] - r[1], 0.0);
  double cr = render_cost(f, e);
  double cq = f->tquery + area * f->tq;                       /* (10), S measured */
  if (cr > pv * cr + cq) {                                    /* (2), (3) */
    es->asked_class = k;
    push_pending(f, &c->iq, &c->ni, &c->cap_iq, e, mask, (uint8_t)was_visible);
    return;
  }
  pull_up_visibility(f, e);
  traverse(f, e, mask);
}

static void walk_tree(frame_ctx *f, zs_cull_method m) {
  zs_culler *c = f->c;
  const zs_octree *t = f->t;
  const uint32_t frame = c->frame;
  double w1 = c->cost.w1, w2 = c->cost.w2;
  if (m == ZS_CULL_AUTO) { /* learnt from the outcomes, with one prior each way */
    w1 = (double)(c->vv + 1) / (double)(c->vv + c->vh + 2);
    w2 = (double)(c->hh + 1) / (double)(c->hv + c->hh + 2);
  }
  c->nheap = 0;
  c->qhead = c->qtail = 0;
  c->ni = 0;
  c->multi = 0;
  if (!t->node[ZS_OCTREE_ROOT].empty && !heap_push(f, ZS_OCTREE_ROOT, ZS_FRUSTUM_ALL_PLANES))
    f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");

  while (f->status == ZS_OK && (c->nheap > 0 || c->qhead < c->qtail || c->ni > 0)) {
    /* nohc: its queries wait in a batch of NOHC_BATCH, issued when full
     * or when there is nothing else to do: one change from drawing to
     * querying and back per batch, which its cost model counts */
    if (c->ni > 0 && (c->ni >= NOHC_BATCH || c->nheap == 0)) flush_invisible(f);
    /* Part 1: results that are ready, or any when nothing else is left. */
    while (f->status == ZS_OK && c->qhead < c->qtail &&
           (c->nheap == 0 || zs_device_query_ready(f->dev, c->qq[c->qhead].q)))
      take_result(f);
    if (c->nheap == 0 || f->status != ZS_OK) continue;

    /* Part 2: the nearest element waiting. */
    elem e;
    unsigned mask;
    if (!next_in_frustum(f, &e, &mask)) continue;
    elem_state *es = state(f, e);

    if (m == ZS_CULL_VFC) {
      es->visible = 1;
      es->last_visited = frame;
      traverse(f, e, mask);
      continue;
    }
    if (m == ZS_CULL_HSW) {
      if (too_close(f, e)) traverse(f, e, mask);
      else {
        issue_query(f, e, mask, 0);
        if (f->status == ZS_OK) take_result(f); /* stop and wait */
      }
      continue;
    }

    /* chc, chc-prob, auto, nohc */
    int seen_last = es->last_visited == frame - 1;
    int was_visible = es->visible && seen_last;
    double pv = predict(es, w1, w2);
    es->visible = 0;
    es->last_visited = frame;
    if (too_close(f, e)) { /* cannot be asked: taken as visible */
      es->pv = 1.0;
      pull_up_visibility(f, e);
      traverse(f, e, mask);
      continue;
    }
    /* termination elements: objects (the leaves), and nodes that were
     * hidden; nodes that were visible are opened without a query */
    if (m == ZS_CULL_NOHC && (is_object(e) || !was_visible)) {
      nohc_visit(f, e, mask, was_visible, seen_last);
      continue;
    }
    if (is_object(e) || !was_visible) {
      if (m != ZS_CULL_CHC && !query_pays(f, e, pv)) {
        draw_unasked(f, e, mask, pv);
        continue;
      }
      issue_query(f, e, mask, (unsigned char)was_visible);
    }
    if (was_visible) traverse(f, e, mask);
  }
}

/* Polygons under every node: its objects' faces plus its children's. */
static int count_polygons(frame_ctx *f) {
  zs_culler *c = f->c;
  const zs_octree *t = f->t;
  if (!zs_grow((void **)&c->polys, &c->cap_polys, t->nslots, sizeof *c->polys)) return 0;
  /* children have larger levels: sum level by level, deepest first */
  int deepest = 0;
  for (int32_t n = 0; n < t->nslots; n++) {
    c->polys[n] = 0;
    if (t->node[n].level > deepest) deepest = t->node[n].level;
  }
  for (int32_t n = 0; n < t->nslots; n++)
    if (t->node[n].level >= 0)
      for (int32_t o = t->node[n].first; o != ZS_OCTREE_NONE; o = t->next[o])
        c->polys[n] += f->s->meshes[f->s->inst[o].mesh].mesh.nfaces;
  for (int level = deepest; level > 0; level--)
    for (int32_t n = 0; n < t->nslots; n++)
      if (t->node[n].level == level) c->polys[t->node[n].parent] += c->polys[n];
  return 1;
}

/* The oracle of ideal: which instances own a pixel of the full image; with
 * boxes (ideal-box), also which instances' tight boxes have a sample
 * against its depth buffer (a box holds its instance, so every owner is
 * one of them). */
static void ideal_frame(frame_ctx *f, const double view[16], const double proj[16], int boxes) {
  zs_culler *c = f->c;
  const zs_device_config *cfg = zs_device_config_of(f->dev);
  if (!c->oracle) {
    zs_device_config oc = *cfg;
    oc.algo = ZS_ALGO_ZBUFFER;
    oc.shade = ZS_SHADE_ID;
    if ((f->status = zs_device_create(&oc, &c->oracle, f->err))) return;
  }
  if (!zs_grow((void **)&c->owns_pixel, &c->cap_inst, f->s->ninst, 1)) {
    f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
    return;
  }
  zs_device_clear(c->oracle);
  zs_device_set_camera(c->oracle, view, proj);
  for (int32_t i = 0; i < f->s->ninst && f->status == ZS_OK; i++) {
    const zs_instance *in = &f->s->inst[i];
    f->status = zs_device_draw(c->oracle, &f->s->meshes[in->mesh].mesh, in->model, in->id_base,
                               in->rgb, f->err);
  }
  if (f->status) return;
  /* The instance each face id belongs to (ids are id_base + face id). */
  if (!c->owner) {
    uint32_t n = 0;
    for (int32_t i = 0; i < f->s->ninst; i++) {
      const zs_mesh *m = &f->s->meshes[f->s->inst[i].mesh].mesh;
      for (int32_t k = 0; k < m->nfaces; k++) {
        uint32_t id = f->s->inst[i].id_base + (uint32_t)(m->face_id ? m->face_id[k] : k);
        if (id + 1 > n) n = id + 1;
      }
    }
    if (!(c->owner = malloc((size_t)(n ? n : 1) * sizeof *c->owner))) {
      f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
      return;
    }
    c->nowner = n;
    for (int32_t i = 0; i < f->s->ninst; i++) {
      const zs_mesh *m = &f->s->meshes[f->s->inst[i].mesh].mesh;
      for (int32_t k = 0; k < m->nfaces; k++)
        c->owner[f->s->inst[i].id_base + (uint32_t)(m->face_id ? m->face_id[k] : k)] = i;
    }
  }
  memset(c->owns_pixel, 0, (size_t)f->s->ninst);
  const uint32_t *ids = zs_device_id_buffer(c->oracle);
  size_t npx = (size_t)cfg->width * (size_t)cfg->height;
  for (size_t p = 0; p < npx; p++)
    if (ids[p] < c->nowner) c->owns_pixel[c->owner[ids[p]]] = 1;
  for (int32_t i = 0; boxes && i < f->s->ninst && f->status == ZS_OK; i++) {
    zs_query q;
    if (c->owns_pixel[i]) continue;
    int32_t nbox = 0;
    if (!add_query_boxes(f, object_elem(i), &nbox)) {
      f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
      return;
    }
    if ((f->status = zs_device_query_begin(c->oracle, &q, f->err)) ||
        (f->status = zs_device_query_boxes(c->oracle, (const double(*)[3])c->qlo,
                                           (const double(*)[3])c->qhi, nbox, f->err)) ||
        (f->status = zs_device_query_end(c->oracle, f->err)))
      return;
    c->owns_pixel[i] = zs_device_query_result(c->oracle, q) > 0;
  }
  for (int32_t i = 0; i < f->s->ninst; i++)
    if (c->owns_pixel[i]) draw_instance(f, i);
}

zs_status zs_culler_frame(zs_culler *c, zs_device *dev, const zs_scene *s, const zs_octree *t,
                          const double view[16], const double proj[16], zs_cull_stats *st,
                          zs_error *err) {
  memset(st, 0, sizeof *st);
  c->frame++;
  frame_ctx f;
  memset(&f, 0, sizeof f);
  f.c = c;
  f.dev = dev;
  f.s = s;
  f.t = t;
  f.st = st;
  f.err = err;
  st->chosen = c->method;
  zs_device_clear(dev);
  zs_device_set_camera(dev, view, proj);
  zs_frustum_from_matrices(&f.frustum, view, proj);
  for (int i = 0; i < 3; i++)
    f.eye[i] = -(view[i] * view[3] + view[4 + i] * view[7] + view[8 + i] * view[11]);

  switch (c->method) {
    case ZS_CULL_NONE:
      for (int32_t i = 0; i < s->ninst && f.status == ZS_OK; i++) draw_instance(&f, i);
      return f.status;
    case ZS_CULL_VFC_BOX: {
      zs_view_box vb;
      zs_view_box_make(&vb, view, proj);
      for (int32_t i = 0; i < s->ninst && f.status == ZS_OK; i++) {
        double centre[3];
        for (int k = 0; k < 3; k++) centre[k] = 0.5 * (s->inst[i].lo[k] + s->inst[i].hi[k]);
        st->frustum_tests++;
        zs_device_cpu_work(dev, ZS_CPU_FRUSTUM_TEST, 1);
        if (zs_view_box_contains(&vb, centre)) draw_instance(&f, i);
      }
      return f.status;
    }
    case ZS_CULL_IDEAL:
    case ZS_CULL_IDEAL_BOX:
      ideal_frame(&f, view, proj, c->method == ZS_CULL_IDEAL_BOX);
      return f.status;
    default:
      break;
  }

  /* the tree methods */
  if (!zs_grow((void **)&c->ns, &c->cap_ns, t->nslots, sizeof *c->ns))
    return zs_error_set(err, ZS_ERR_NOMEM, "culling: out of memory");
  if (!zs_grow((void **)&c->os, &c->cap_os, s->ninst, sizeof *c->os))
    return zs_error_set(err, ZS_ERR_NOMEM, "culling: out of memory");
  /* Elements new to the culler start unseen, P(V) 1/2.  (A node slot the
   * octree frees and reuses keeps its state: at worst a node is opened
   * without a query once, which costs time, never pixels.) */
  for (; c->init_ns < t->nslots; c->init_ns++) c->ns[c->init_ns] = (elem_state){0, 0, 0, 0.5, 0, 0, 0, -1};
  for (; c->init_os < s->ninst; c->init_os++) c->os[c->init_os] = (elem_state){0, 0, 0, 0.5, 0, 0, 0, -1};
  /* The near plane's corners lie at most near * sqrt(1 + tx^2 + ty^2) from
   * the eye (tx, ty the tangents of the half fields of view). */
  const zs_device_config *cfg = zs_device_config_of(dev);
  double a = proj[10], b = proj[11];
  double znear = proj[14] != 0.0 ? b / (a - 1.0) : 0.0;
  double tx = 1.0 / proj[0], ty = 1.0 / proj[5];
  /* orthographic: the near plane may cut any box; ask none (exact, as vfc) */
  f.near_reach = proj[14] != 0.0 ? 1.0001 * znear * sqrt(1.0 + tx * tx + ty * ty) : INFINITY;
  f.tan_half_fovy = ty;
  f.height = cfg->height;
  const zs_clock_params *k = zs_device_clock_params(dev);
  f.ttri = c->cost.ttri_ns >= 0 ? c->cost.ttri_ns : k->per_polygon_ns;
  f.tcall = c->cost.tcall_ns >= 0 ? c->cost.tcall_ns : k->per_call_ns + k->cpu_per_call_ns;
  f.tquery = c->cost.t_ns >= 0 ? c->cost.t_ns
                                : k->per_call_ns + 2.0 * k->cpu_per_query_ns + 2.0 * k->switch_ns;
  f.tq = c->cost.tq_ns >= 0 ? c->cost.tq_ns : k->per_query_pixel_ns;
  if (c->method == ZS_CULL_NOHC && c->cost.t_ns < 0) /* a batch pays its two switches once */
    f.tquery = k->per_call_ns + 2.0 * k->cpu_per_query_ns + 2.0 * k->switch_ns / NOHC_BATCH;

  zs_cull_method m = c->method;
  if (m == ZS_CULL_CHCPP || m == ZS_CULL_CHCPP_NOBATCH || m == ZS_CULL_CHCPP_NODEFER ||
      m == ZS_CULL_CHCPP_NOMULTI || m == ZS_CULL_CHCPP_PROB) {
    c->multi = m != ZS_CULL_CHCPP_NOMULTI;
    if (m == ZS_CULL_CHCPP_PROB && !count_polygons(&f))
      return zs_error_set(err, ZS_ERR_NOMEM, "culling: out of memory");
    if (!zs_grow((void **)&c->decision, &c->cap_decision, t->nslots, 1))
      return zs_error_set(err, ZS_ERR_NOMEM, "culling: out of memory");
    c->ndecision = t->nslots;
    memset(c->decision, ZS_NODE_NOT_REACHED, (size_t)t->nslots);
    walk_chcpp(&f, m != ZS_CULL_CHCPP_NOBATCH, m != ZS_CULL_CHCPP_NODEFER, m == ZS_CULL_CHCPP_PROB);
    return f.status;
  }
  if (m == ZS_CULL_AUTO) {
    st->chosen = c->use_queries ? ZS_CULL_CHC_PROB : ZS_CULL_VFC;
    if (!c->use_queries) m = ZS_CULL_VFC;
  }
  if ((m == ZS_CULL_CHC_PROB || m == ZS_CULL_NOHC || c->method == ZS_CULL_AUTO) &&
      !count_polygons(&f))
    return zs_error_set(err, ZS_ERR_NOMEM, "culling: out of memory");
  if (m == ZS_CULL_NOHC) { /* an empty coverage grid */
    if (!zs_coverage_reset(&c->cov, cfg->width, cfg->height, view, proj))
      return zs_error_set(err, ZS_ERR_NOMEM, "culling: out of memory");
  }
  if (!zs_grow((void **)&c->decision, &c->cap_decision, t->nslots, 1))
    return zs_error_set(err, ZS_ERR_NOMEM, "culling: out of memory");
  c->ndecision = t->nslots;
  memset(c->decision, ZS_NODE_NOT_REACHED, (size_t)t->nslots);
  walk_tree(&f, m);
  if (c->method == ZS_CULL_AUTO && f.status == ZS_OK) {
    /* Queries pay when the draws show hidden objects (vfc frames), or
     * when the queries found hidden nodes (chc-prob frames). */
    c->use_queries = c->use_queries ? st->queries_hidden > 0 || f.hidden_objects > 0
                                    : f.hidden_objects > 0;
  }
  return f.status;
}
