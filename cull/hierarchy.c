/* The steps every method that traverses the octree takes (internal.h): the
 * elements and their state, drawing, the traversal queue (a binary heap on
 * the distance from the eye to an element's box: front to back, ties by
 * element), and what is done to an element visited. */

#include "cull/internal.h"
#include "util/grow.h"

/* ---- elements ---- */

void cull_out_of_memory(frame_ctx *f) {
  f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
}

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
  /* chc-prob and chcpp-prob draw every object inside a query, to learn
   * what it writes; nohc some */
  const int measure = f->hooks->measure_due && f->hooks->measure_due(f, i);
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
  if (f->hooks->drawn) f->hooks->drawn(f, i, measure, written);
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

/* ---- the frustum ---- */

/* e's box against the planes left in *mask (none left: inside, untested),
 * each plane test charged to the CPU. */
zs_frustum_result cull_frustum_test(frame_ctx *f, elem e, unsigned *mask) {
  const double *lo, *hi;
  cull_elem_box(f, e, &lo, &hi);
  uint64_t tests = f->st->frustum_tests;
  zs_frustum_result fr =
      *mask ? zs_frustum_test_box(&f->frustum, lo, hi, mask, &f->st->frustum_tests)
            : ZS_FRUSTUM_INSIDE;
  zs_device_cpu_work(f->dev, ZS_CPU_FRUSTUM_TEST, f->st->frustum_tests - tests);
  return fr;
}

int cull_visit_in_frustum(frame_ctx *f, elem e, unsigned *mask) {
  f->st->nodes_visited++;
  zs_device_cpu_work(f->dev, ZS_CPU_NODE, 1);
  return cull_frustum_test(f, e, mask) != ZS_FRUSTUM_OUTSIDE;
}

/* Takes the nearest element of the traversal queue and tests it against
 * the frustum (the planes its parent left in its mask); 0 when outside. */
int cull_next_in_frustum(frame_ctx *f, elem *e, unsigned *mask) {
  heap_entry h = heap_pop(f->c);
  *e = h.e;
  *mask = h.mask;
  const int inside = cull_visit_in_frustum(f, *e, mask);
  cull_decide(f, *e, inside ? ZS_NODE_NO_QUERY : ZS_NODE_OUTSIDE);
  return inside;
}

/* The objects flagged in draw[], in order front to back as the traversal
 * would reach them (by their boxes' distance, ties by element), into
 * c->order; returns how many (-1 when out of memory). */
int32_t cull_order_front_to_back(frame_ctx *f, const uint8_t *draw) {
  zs_culler *c = f->c;
  c->nheap = 0;
  if (!zs_grow((void **)&c->order, &c->cap_order, f->s->ninst + 1, sizeof *c->order)) {
    cull_out_of_memory(f);
    return -1;
  }
  for (int32_t i = 0; i < f->s->ninst; i++)
    if (draw[i] && !cull_heap_push(f, object_elem(i), 0)) {
      cull_out_of_memory(f);
      return -1;
    }
  int32_t n = 0;
  while (c->nheap > 0) c->order[n++] = object_of(heap_pop(c).e);
  return n;
}

/* The objects flagged in draw[], drawn in that order, the ordering itself
 * free: the oracles' way of drawing what they know. */
void cull_draw_front_to_back(frame_ctx *f, const uint8_t *draw) {
  const int32_t n = cull_order_front_to_back(f, draw);
  for (int32_t k = 0; k < n && f->status == ZS_OK; k++) cull_draw_instance(f, f->c->order[k]);
}

/* What node n holds, in the order every traversal takes it: its children
 * that hold anything, by octant, then its objects, in its list. */
int cull_open_node(frame_ctx *f, elem n, unsigned mask, cull_push_fn *push, void *to) {
  const zs_octnode *nd = &f->t->node[n];
  int ok = 1;
  for (int o = 0; o < 8 && ok; o++) {
    int32_t ch = nd->child[o];
    if (ch != ZS_OCTREE_NONE && !f->t->node[ch].empty) ok = push(f, to, ch, mask);
  }
  for (int32_t i = nd->first; i != ZS_OCTREE_NONE && ok; i = f->t->next[i])
    ok = push(f, to, object_elem(i), mask);
  return ok;
}

static int push_on_heap(frame_ctx *f, void *to, elem e, unsigned mask) {
  (void)to;
  return cull_heap_push(f, e, mask);
}

/* TraverseNode of the paper, once per frame per element: an object is
 * rendered; a node pushes its children and its objects on the traversal
 * queue. */
void cull_traverse_node(frame_ctx *f, elem e, unsigned mask) {
  elem_state *es = cull_state(f, e);
  if (es->done == f->c->frame) return;
  es->done = f->c->frame;
  if (is_object(e)) {
    cull_draw_instance(f, object_of(e));
    return;
  }
  if (!cull_open_node(f, e, mask, push_on_heap, NULL)) cull_out_of_memory(f);
}

void cull_pull_up_visibility(frame_ctx *f, elem e) {
  while (e != ZS_OCTREE_NONE && !cull_state(f, e)->visible) {
    cull_state(f, e)->visible = 1;
    e = cull_parent_of(f, e);
  }
}

/* An element found visible, or drawn unasked, is visible up the tree. */
void cull_draw_visible(frame_ctx *f, elem e, unsigned mask) {
  cull_pull_up_visibility(f, e);
  cull_traverse_node(f, e, mask);
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

/* An element taken from the traversal queue: what it was in the last frame
 * (visited then; visible then), and it is visited now, not visible yet.
 * A box that the near plane could cut cannot be asked about: it is taken
 * as visible and traversed at once (returns 0). */
int cull_enter(frame_ctx *f, elem e, unsigned mask, int *was_visible, int *seen_last) {
  elem_state *es = cull_state(f, e);
  *seen_last = es->last_visited == f->c->frame - 1;
  *was_visible = es->visible && *seen_last;
  es->visible = 0;
  es->last_visited = f->c->frame;
  if (!cull_too_close(f, e)) return 1;
  es->pv = 1.0;
  cull_pull_up_visibility(f, e);
  cull_traverse_node(f, e, mask);
  return 0;
}

/* Draws e as if visible without asking (when the query does not pay);
 * its P(V) carries the prediction to the next frame, unless e is an
 * object whose draw is measured (then the draw sets P(V)). */
void cull_draw_unasked(frame_ctx *f, elem e, unsigned mask, double pv) {
  cull_state(f, e)->pv = pv;
  f->hooks->draw_visible(f, e, mask);
}
