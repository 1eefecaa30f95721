/* The steps every culling method takes (internal.h): the elements and
 * their state, drawing, the traversal queue (a binary heap on the distance
 * from the eye to an element's box: front to back, ties by element), the
 * query queue (a FIFO) and its answers, and the cost model of the
 * cost-model paper. */
#include <math.h>
#include <string.h>

#include "cull/internal.h"
#include "raster/exactmath.h"
#include "raster/grow.h"

/* ---- elements ---- */

elem_state *cull_state(frame_ctx *f, elem e) {
  return is_object(e) ? &f->c->os[object_of(e)] : &f->c->ns[e];
}

/* The box of an element: a node's tight box, an object's own box. */
void cull_elem_box(const frame_ctx *f, elem e, const double **lo, const double **hi) {
  if (is_object(e)) {
    *lo = f->t->olo[object_of(e)];
    *hi = f->t->ohi[object_of(e)];
  } else {
    *lo = f->t->node[e].tlo;
    *hi = f->t->node[e].thi;
  }
}

void cull_decide(frame_ctx *f, elem e, zs_node_decision d) {
  if (!is_object(e) && e < f->c->ndecision) f->c->decision[e] = (uint8_t)d;
}

elem cull_parent_of(const frame_ctx *f, elem e) {
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

/* ---- drawing ---- */

void cull_draw_instance(frame_ctx *f, int32_t i) {
  if (f->status != ZS_OK) return;
  const zs_instance *in = &f->s->inst[i];
  const zs_mesh *m = &f->s->meshes[in->mesh].mesh;
  const int nohc = f->c->method == ZS_CULL_NOHC;
  /* nohc draws some objects inside a query, to learn what they write;
   * chc-prob and chcpp-prob every object they draw */
  const int measure = f->measure_draws || (nohc && cull_nohc_measure_due(f, i));
  uint64_t before = zs_device_stats(f->dev)->pixels_written;
  zs_query q;
  if (measure && (f->status = zs_device_query_begin(f->dev, &q, f->err))) return;
  f->status = zs_device_draw(f->dev, m, in->model, in->id_base, in->rgb, f->err);
  if (measure && f->status == ZS_OK) f->status = zs_device_query_end(f->dev, f->err);
  f->st->objects_drawn++;
  f->st->draws_measured += (uint64_t)measure;
  f->st->faces_drawn += (uint64_t)m->nfaces;
  uint64_t written = zs_device_stats(f->dev)->pixels_written - before;
  if (written == 0) f->hidden_objects++;
  if (nohc) cull_nohc_drawn(f, i, measure, written);
  /* P_{t-1}(V) of (11) for the next frame: whether the draw wrote a pixel
   * (the query's count, long there when the next frame reads it), not
   * the prediction it was drawn on */
  if (f->measure_draws) {
    f->c->os[i].pv = written > 0 ? 1.0 : 0.0;
    if (written > 0) cull_pull_up_visibility(f, object_elem(i));
  }
}

/* ---- the traversal queue: a min-heap on (distance, element) ---- */

static int heap_less(const heap_entry *a, const heap_entry *b) {
  return a->key < b->key || (a->key == b->key && a->e < b->e);
}

int cull_heap_push(frame_ctx *f, elem e, unsigned mask) {
  zs_culler *c = f->c;
  if (!zs_grow((void **)&c->heap, &c->cap_heap, c->nheap + 1, sizeof *c->heap)) return 0;
  const double *lo, *hi;
  cull_elem_box(f, e, &lo, &hi);
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

/* The objects flagged in draw[], drawn front to back as the traversal
 * would reach them (by their boxes' distance, ties by element), the
 * ordering itself free: the oracles' way of drawing what they know. */
void cull_draw_front_to_back(frame_ctx *f, const uint8_t *draw) {
  zs_culler *c = f->c;
  c->nheap = 0;
  for (int32_t i = 0; i < f->s->ninst; i++)
    if (draw[i] && !cull_heap_push(f, object_elem(i), 0)) {
      f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
      return;
    }
  while (c->nheap > 0 && f->status == ZS_OK) cull_draw_instance(f, object_of(heap_pop(c).e));
}

/* TraverseNode of the paper, once per frame per element: an object is
 * rendered; a node pushes its children and its objects. */
void cull_traverse(frame_ctx *f, elem e, unsigned mask) {
  elem_state *es = cull_state(f, e);
  if (es->done == f->c->frame) return;
  es->done = f->c->frame;
  if (is_object(e)) {
    cull_draw_instance(f, object_of(e));
    return;
  }
  const zs_octnode *nd = &f->t->node[e];
  int ok = 1;
  for (int o = 0; o < 8 && ok; o++) {
    int32_t ch = nd->child[o];
    if (ch != ZS_OCTREE_NONE && !f->t->node[ch].empty) ok = cull_heap_push(f, ch, mask);
  }
  for (int32_t i = nd->first; i != ZS_OCTREE_NONE && ok; i = f->t->next[i])
    ok = cull_heap_push(f, object_elem(i), mask);
  if (!ok) f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
}

void cull_pull_up_visibility(frame_ctx *f, elem e) {
  while (e != ZS_OCTREE_NONE && !cull_state(f, e)->visible) {
    cull_state(f, e)->visible = 1;
    e = cull_parent_of(f, e);
  }
}

/* An element found visible or drawn unasked is visible up the tree; a
 * measured object's visibility is what its draw writes
 * (cull_draw_instance pulls it up only if it wrote a pixel). */
void cull_pull_up_before_draw(frame_ctx *f, elem e) {
  if (!(is_object(e) && f->measure_draws)) cull_pull_up_visibility(f, e);
}

/* A box that the near plane could cut, or that holds the eye, once grown
 * by the query's margin (raster.h): its query would miss what lies before
 * the plane, so it is not asked.  (The grown box lies within sqrt(3)
 * margins of the box.) */
int cull_too_close(const frame_ctx *f, elem e) {
  const double *lo, *hi;
  cull_elem_box(f, e, &lo, &hi);
  const double reach = f->near_reach + 1.7320508075688772 * zs_device_query_margin(f->dev, lo, hi);
  return box_distance2(f->eye, lo, hi) <= reach * reach;
}

/* ---- the cost model (chc-prob, auto) ---- */

/* (6), extended: Cr = N Ttri + M Tcall, N the polygons and M the objects
 * under e. */
double cull_render_cost(const frame_ctx *f, elem e) {
  int64_t n = is_object(e) ? f->s->meshes[f->s->inst[object_of(e)].mesh].mesh.nfaces
                           : f->c->polys[e];
  int64_t calls = is_object(e) ? 1 : f->t->node[e].count;
  return (double)n * f->ttri + (double)calls * f->tcall;
}

/* Formulas 2, 3, 6, 9, 10: whether querying e pays, given P(V) = pv. */
int cull_query_pays(frame_ctx *f, elem e, double pv) {
  const double *lo, *hi;
  cull_elem_box(f, e, &lo, &hi);
  f->st->cost_evals++;
  zs_device_cpu_work(f->dev, ZS_CPU_COST_EVAL, 1);
  double cr = cull_render_cost(f, e);
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

/* A rate learnt from counted outcomes (stay of stay + change), starting
 * from prior as if weight outcomes had been seen. */
static double learnt_rate(uint64_t stay, uint64_t change, double prior, double weight) {
  return ((double)stay + weight * prior) / ((double)(stay + change) + weight);
}

/* w1 and w2: as given, or with cost.learn > 0 learnt from what this
 * culler's queries found, starting from the given ones as if cost.learn
 * outcomes had borne each out.  auto always learns them, from one outcome
 * each way. */
void cull_weights(const zs_culler *c, zs_cull_method m, double *w1, double *w2) {
  if (m == ZS_CULL_AUTO) {
    *w1 = learnt_rate(c->vv, c->vh, 0.5, 2.0);
    *w2 = learnt_rate(c->hh, c->hv, 0.5, 2.0);
  } else if (c->cost.learn > 0.0) {
    *w1 = learnt_rate(c->vv, c->vh, c->cost.w1, c->cost.learn);
    *w2 = learnt_rate(c->hh, c->hv, c->cost.w2, c->cost.learn);
  } else {
    *w1 = c->cost.w1;
    *w2 = c->cost.w2;
  }
}

/* (11): the chance that an element is visible this frame, from its state. */
double cull_predict(const elem_state *es, double w1, double w2) {
  return w1 * es->pv + (1.0 - w2) * (1.0 - es->pv);
}

/* ---- the methods ---- */

/* Appends the boxes a query over element e draws: a node's tight box; an
 * object's parts (parts.h) or its box. */
int cull_add_query_boxes(frame_ctx *f, elem e, int32_t *n) {
  zs_culler *c = f->c;
  const double(*plo)[3], (*phi)[3];
  const double *lo, *hi;
  int k = 1;
  if (is_object(e) && c->parts) {
    if (!zs_parts_of(c->parts, f->s, object_of(e), &plo, &phi, &k)) return 0;
  } else {
    cull_elem_box(f, e, &lo, &hi);
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
void cull_query_elements(frame_ctx *f, const pending *members, int32_t n, query_entry qe) {
  zs_culler *c = f->c;
  int32_t nbox = 0;
  int ok = zs_grow((void **)&c->qq, &c->cap_qq, c->qtail + 1, sizeof *c->qq);
  for (int32_t i = 0; i < n && ok; i++) ok = cull_add_query_boxes(f, members[i].e, &nbox);
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

void cull_issue_query(frame_ctx *f, elem e, unsigned mask, unsigned char was_visible) {
  pending one = {e, mask, was_visible};
  cull_query_elements(f, &one, 1, (query_entry){e, 0, mask, was_visible, 0, 0});
}

/* Takes the answer of the query at the head of the queue (waiting for it
 * if need be) and acts on it. */

void cull_take_result(frame_ctx *f) {
  zs_culler *c = f->c;
  query_entry q = c->qq[c->qhead++];
  int visible = zs_device_query_result(f->dev, q.q) > 0;
  if (q.ngroup > 0) { /* a multiquery */
    if (visible) { /* someone is visible: ask each on its own */
      for (int32_t i = 0; i < q.ngroup && f->status == ZS_OK; i++)
        cull_issue_query(f, c->gm[q.group + i].e, c->gm[q.group + i].mask, c->gm[q.group + i].was_visible);
      return;
    }
    for (int32_t i = 0; i < q.ngroup; i++) { /* all hidden, with one query */
      elem e = c->gm[q.group + i].e;
      cull_state(f, e)->pv = 0.0;
      cull_state(f, e)->hidden_frames++;
      cull_decide(f, e, ZS_NODE_QUERIED_HIDDEN);
      f->st->queries_hidden++;
    }
    return;
  }
  cull_state(f, q.e)->pv = visible ? 1.0 : 0.0; /* observed: the next frame predicts from it */
  int32_t k = cull_state(f, q.e)->asked_class;
  if (k >= 0) { /* nohc: how its history class turned out */
    visible ? c->class_visible[k]++ : c->class_hidden[k]++;
    cull_state(f, q.e)->asked_class = -1;
  }
  if (q.was_visible) visible ? c->vv++ : c->vh++;
  else visible ? c->hv++ : c->hh++;
  cull_decide(f, q.e, visible ? ZS_NODE_QUERIED_VISIBLE : ZS_NODE_QUERIED_HIDDEN);
  if (!visible) {
    cull_state(f, q.e)->hidden_frames++;
    f->st->queries_hidden++;
    return;
  }
  cull_state(f, q.e)->hidden_frames = 0;
  if (is_object(q.e)) { /* chcpp: asked again in a while; at first, at random */
    elem_state *es = cull_state(f, q.e);
    es->next_query = c->frame + (q.was_visible ? (uint32_t)ZS_CHCPP_VISIBLE_FRAMES
                                               : 1 + (uint32_t)zs_rng_below(&c->rng, ZS_CHCPP_VISIBLE_FRAMES));
  }
  cull_pull_up_before_draw(f, q.e);
  cull_traverse(f, q.e, q.mask);
}

/* Takes the nearest element of the traversal queue and tests it against
 * the frustum (the planes its parent left in its mask); 0 when outside. */
int cull_next_in_frustum(frame_ctx *f, elem *e, unsigned *mask) {
  heap_entry h = heap_pop(f->c);
  *e = h.e;
  *mask = h.mask;
  f->st->nodes_visited++;
  zs_device_cpu_work(f->dev, ZS_CPU_NODE, 1);
  const double *lo, *hi;
  cull_elem_box(f, *e, &lo, &hi);
  uint64_t tests = f->st->frustum_tests;
  zs_frustum_result fr =
      *mask ? zs_frustum_test_box(&f->frustum, lo, hi, mask, &f->st->frustum_tests)
            : ZS_FRUSTUM_INSIDE;
  zs_device_cpu_work(f->dev, ZS_CPU_FRUSTUM_TEST, f->st->frustum_tests - tests);
  cull_decide(f, *e, fr == ZS_FRUSTUM_OUTSIDE ? ZS_NODE_OUTSIDE : ZS_NODE_NO_QUERY);
  return fr != ZS_FRUSTUM_OUTSIDE;
}

/* ---- CHC++ ---- */

int cull_push_pending(frame_ctx *f, pending **q, int32_t *n, int32_t *cap, elem e, unsigned mask,
                        uint8_t was_visible) {
  if (!zs_grow((void **)q, cap, *n + 1, sizeof **q)) {
    f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
    return 0;
  }
  (*q)[(*n)++] = (pending){e, mask, was_visible};
  return 1;
}

/* The chance that an element hidden i frames in a row stays hidden. */
double cull_keep_hidden(uint32_t i) { return 0.99 - 0.7 * zs_exp(-(double)i); }

/* One query over the boxes of members gm[first .. first + n - 1]. */
static void issue_multiquery(frame_ctx *f, int32_t first, int32_t n) {
  zs_culler *c = f->c;
  cull_query_elements(f, c->gm + first, n, (query_entry){c->gm[first].e, 0, c->gm[first].mask, 0, first, n});
}

/* Issues every query of the invisible queue, one after the other: one
 * change from drawing to querying for the whole batch; with multiqueries,
 * in groups that grow while their expected saving grows. */
void cull_flush_invisible(frame_ctx *f) {
  zs_culler *c = f->c;
  int32_t i = 0;
  while (i < c->ni && f->status == ZS_OK) {
    int32_t k = 1;
    double p = cull_keep_hidden(cull_state(f, c->iq[i].e)->hidden_frames);
    while (c->multi && i + k < c->ni) {
      double p2 = p * cull_keep_hidden(cull_state(f, c->iq[i + k].e)->hidden_frames);
      double now = k / (1.0 + (1.0 - p) * k), next = (k + 1) / (1.0 + (1.0 - p2) * (k + 1));
      if (!(next > now)) break;
      p = p2;
      k++;
    }
    if (k == 1) {
      cull_issue_query(f, c->iq[i].e, c->iq[i].mask, c->iq[i].was_visible);
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

/* Draws e as if visible without asking (when the query does not pay);
 * its P(V) carries the prediction to the next frame, unless e is an
 * object whose draw is measured (then the draw sets P(V) and, if it wrote
 * a pixel, pulls visibility up). */
void cull_draw_unasked(frame_ctx *f, elem e, unsigned mask, double pv) {
  cull_state(f, e)->pv = pv;
  cull_pull_up_before_draw(f, e);
  cull_traverse(f, e, mask);
}

/* Polygons under every node: its objects' faces plus its children's. */
int cull_count_polygons(frame_ctx *f) {
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
