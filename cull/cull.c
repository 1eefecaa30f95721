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

#include "cull/frustum.h"

static const char *const method_names[ZS_CULL_METHODS] = {"none", "vfc",      "vfc-box", "hsw",
                                                          "chc",  "chc-prob", "ideal",   "auto"};

const char *zs_cull_method_name(zs_cull_method m) {
  return (unsigned)m < ZS_CULL_METHODS ? method_names[m] : "?";
}

int zs_cull_method_parse(const char *name) {
  for (int i = 0; i < ZS_CULL_METHODS; i++)
    if (strcmp(name, method_names[i]) == 0) return i;
  return -1;
}

void zs_cost_params_default(zs_cost_params *p) {
  *p = (zs_cost_params){0.95, 0.9, -1.0, -1.0, -1.0, 1.0};
}

/* Across frames, per octree node. */
typedef struct node_state {
  uint32_t last_visited;   /* frame (frames count from 1) */
  uint32_t rendered;       /* frame its own objects were drawn */
  uint32_t traversed;      /* frame its children were pushed */
  uint8_t visible;
  double pv;               /* P(V) for the next frame */
} node_state;

typedef struct heap_entry {
  double key;
  int32_t node;
  unsigned mask;           /* frustum planes still to test */
} heap_entry;

typedef struct query_entry {
  int32_t node;
  zs_query q;
  unsigned mask;           /* frustum planes its children still test */
  uint8_t was_visible;     /* its state before this frame (auto's learning) */
} query_entry;

struct zs_culler {
  zs_cull_method method;
  zs_cost_params cost;
  uint32_t frame;
  node_state *ns;
  int32_t cap_ns, init_ns; /* slots allocated, slots initialised */
  heap_entry *heap;
  int32_t nheap, cap_heap;
  query_entry *qq;
  int32_t qhead, qtail, cap_qq;
  int64_t *polys;          /* polygons under each node, this frame */
  int32_t cap_polys;
  /* ideal */
  zs_device *oracle;
  uint8_t *owns_pixel;
  int32_t cap_inst;
  int32_t *owner;          /* face id -> instance */
  uint32_t nowner;
  /* auto: transitions seen by its queries, and the mode of the next frame */
  uint64_t vv, vh, hv, hh;
  int use_queries;
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
  double ttri, tq, tquery; /* cost model constants, ns */
  zs_cull_stats *st;
  uint64_t hidden_objects; /* auto: objects drawn that wrote no pixel */
  zs_error *err;
  zs_status status;
} frame_ctx;

static int grow(void **p, int32_t *cap, int32_t need, size_t size) {
  if (need <= *cap) return 1;
  int32_t n = *cap ? *cap : 64;
  while (n < need) n *= 2;
  void *q = realloc(*p, (size_t)n * size);
  if (!q) return 0;
  *p = q;
  *cap = n;
  return 1;
}

zs_status zs_culler_create(zs_cull_method m, const zs_cost_params *cost, zs_culler **out,
                           zs_error *err) {
  *out = NULL;
  if ((unsigned)m >= ZS_CULL_METHODS) return zs_error_set(err, ZS_ERR_ARG, "unknown culling method");
  zs_culler *c = calloc(1, sizeof *c);
  if (!c) return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  c->method = m;
  if (cost) c->cost = *cost;
  else zs_cost_params_default(&c->cost);
  *out = c;
  return ZS_OK;
}

void zs_culler_destroy(zs_culler *c) {
  if (!c) return;
  free(c->ns);
  free(c->heap);
  free(c->qq);
  free(c->polys);
  free(c->owns_pixel);
  free(c->owner);
  zs_device_destroy(c->oracle);
  free(c);
}

/* ---- drawing ---- */

static void draw_instance(frame_ctx *f, int32_t i) {
  if (f->status != ZS_OK) return;
  const zs_instance *in = &f->s->inst[i];
  const zs_mesh *m = &f->s->meshes[in->mesh].mesh;
  uint64_t before = zs_device_stats(f->dev)->pixels_written;
  f->status = zs_device_draw(f->dev, m, in->model, in->id_base, in->rgb, f->err);
  f->st->objects_drawn++;
  f->st->faces_drawn += (uint64_t)m->nfaces;
  if (zs_device_stats(f->dev)->pixels_written == before) f->hidden_objects++;
}

/* Draws the objects node n holds (once per frame), each if its own box
 * meets the frustum. */
static void render_node(frame_ctx *f, int32_t n, unsigned mask) {
  node_state *ns = &f->c->ns[n];
  if (ns->rendered == f->c->frame) return;
  ns->rendered = f->c->frame;
  const zs_octree *t = f->t;
  for (int32_t o = t->node[n].first; o != ZS_OCTREE_NONE; o = t->next[o]) {
    unsigned m = mask;
    if (m && zs_frustum_test_box(&f->frustum, t->olo[o], t->ohi[o], &m, &f->st->frustum_tests) ==
                 ZS_FRUSTUM_OUTSIDE)
      continue;
    draw_instance(f, o);
  }
}

/* ---- the traversal queue: a min-heap on (distance, node) ---- */

static int heap_less(const heap_entry *a, const heap_entry *b) {
  return a->key < b->key || (a->key == b->key && a->node < b->node);
}

static int heap_push(frame_ctx *f, int32_t node, unsigned mask) {
  zs_culler *c = f->c;
  if (!grow((void **)&c->heap, &c->cap_heap, c->nheap + 1, sizeof *c->heap)) return 0;
  const zs_octnode *nd = &f->t->node[node];
  double d2 = 0.0; /* squared distance from the eye to the tight box */
  for (int k = 0; k < 3; k++) {
    double v = f->eye[k] < nd->tlo[k] ? nd->tlo[k] - f->eye[k]
               : f->eye[k] > nd->thi[k] ? f->eye[k] - nd->thi[k] : 0.0;
    d2 += v * v;
  }
  int32_t i = c->nheap++;
  heap_entry e = {d2, node, mask};
  while (i > 0 && heap_less(&e, &c->heap[(i - 1) / 2])) {
    c->heap[i] = c->heap[(i - 1) / 2];
    i = (i - 1) / 2;
  }
  c->heap[i] = e;
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

/* TraverseNode of the paper: draw the node's own objects, push its
 * children (once per frame). */
static void traverse_node(frame_ctx *f, int32_t n, unsigned mask) {
  render_node(f, n, mask);
  node_state *ns = &f->c->ns[n];
  if (ns->traversed == f->c->frame) return;
  ns->traversed = f->c->frame;
  for (int o = 0; o < 8; o++) {
    int32_t ch = f->t->node[n].child[o];
    if (ch != ZS_OCTREE_NONE && !f->t->node[ch].empty && !heap_push(f, ch, mask))
      f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
  }
}

static void pull_up_visibility(frame_ctx *f, int32_t n) {
  while (n != ZS_OCTREE_NONE && !f->c->ns[n].visible) {
    f->c->ns[n].visible = 1;
    n = f->t->node[n].parent;
  }
}

static int is_leaf(const zs_octree *t, int32_t n) {
  for (int o = 0; o < 8; o++)
    if (t->node[n].child[o] != ZS_OCTREE_NONE) return 0;
  return 1;
}

/* A box that the near plane could cut, or that holds the eye: its query
 * would miss what lies before the plane, so it is not asked. */
static int too_close(const frame_ctx *f, const zs_octnode *nd) {
  double d2 = 0.0;
  for (int k = 0; k < 3; k++) {
    double v = f->eye[k] < nd->tlo[k] ? nd->tlo[k] - f->eye[k]
               : f->eye[k] > nd->thi[k] ? f->eye[k] - nd->thi[k] : 0.0;
    d2 += v * v;
  }
  return d2 <= f->near_reach * f->near_reach;
}

/* ---- the cost model (chc-prob, auto) ---- */

/* Formulas 2, 3, 6, 9, 10: whether querying n pays, given P(V) = pv. */
static int query_pays(frame_ctx *f, int32_t n, double pv) {
  const zs_octnode *nd = &f->t->node[n];
  f->st->cost_evals++;
  zs_device_cpu_work(f->dev, ZS_CPU_COST_EVAL, 1);
  double cr = (double)f->c->polys[n] * f->ttri;                   /* (6) */
  double dx = nd->thi[0] - nd->tlo[0], dy = nd->thi[1] - nd->tlo[1], dz = nd->thi[2] - nd->tlo[2];
  double abb = 2.0 * (dx * dy + dy * dz + dz * dx);
  double dis = 0.0;
  for (int k = 0; k < 3; k++) {
    double v = 0.5 * (nd->tlo[k] + nd->thi[k]) - f->eye[k];
    dis += v * v;
  }
  dis = sqrt(dis);
  double den = 2.0 * dis * f->tan_half_fovy;
  double s = den > 0 ? f->height * f->height * (abb / 6.0) / (den * den) : INFINITY; /* (9) */
  double cq = f->tquery + s * f->c->cost.rho * f->tq;                                /* (10) */
  return cr > pv * cr + cq;                                                          /* (2), (3) */
}

/* (11): the chance that n is visible this frame, from its state. */
static double predict(const node_state *ns, double w1, double w2) {
  return w1 * ns->pv + (1.0 - w2) * (1.0 - ns->pv);
}

/* ---- the methods ---- */

static void query_node(frame_ctx *f, int32_t n, unsigned mask, unsigned char was_visible) {
  zs_culler *c = f->c;
  if (!grow((void **)&c->qq, &c->cap_qq, c->qtail + 1, sizeof *c->qq)) {
    f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
    return;
  }
  zs_query q;
  const zs_octnode *nd = &f->t->node[n];
  if ((f->status = zs_device_query_begin(f->dev, &q, f->err)) ||
      (f->status = zs_device_query_box(f->dev, nd->tlo, nd->thi, f->err)) ||
      (f->status = zs_device_query_end(f->dev, f->err)))
    return;
  f->st->queries++;
  c->qq[c->qtail++] = (query_entry){n, q, mask, was_visible};
}

/* Takes the answer of the query at the head of the queue (waiting for it
 * if need be) and acts on it. */
static void take_result(frame_ctx *f) {
  zs_culler *c = f->c;
  query_entry e = c->qq[c->qhead++];
  uint64_t samples = zs_device_query_result(f->dev, e.q);
  node_state *ns = &c->ns[e.node];
  int visible = samples > 0;
  ns->pv = visible ? 1.0 : 0.0; /* observed: the next frame predicts from it */
  if (e.was_visible) visible ? c->vv++ : c->vh++;
  else visible ? c->hv++ : c->hh++;
  if (!visible) {
    f->st->queries_hidden++;
    return;
  }
  pull_up_visibility(f, e.node);
  traverse_node(f, e.node, e.mask);
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
  if (!t->node[ZS_OCTREE_ROOT].empty && !heap_push(f, ZS_OCTREE_ROOT, ZS_FRUSTUM_ALL_PLANES))
    f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");
  const int chc_like = m == ZS_CULL_CHC || m == ZS_CULL_CHC_PROB || m == ZS_CULL_AUTO;

  while (f->status == ZS_OK && (c->nheap > 0 || c->qhead < c->qtail)) {
    /* Part 1: results that are ready, or any when nothing else is left. */
    while (f->status == ZS_OK && c->qhead < c->qtail &&
           (c->nheap == 0 || zs_device_query_ready(f->dev, c->qq[c->qhead].q)))
      take_result(f);
    if (c->nheap == 0 || f->status != ZS_OK) continue;

    /* Part 2: the nearest node waiting. */
    heap_entry e = heap_pop(c);
    int32_t n = e.node;
    const zs_octnode *nd = &t->node[n];
    node_state *ns = &c->ns[n];
    f->st->nodes_visited++;
    zs_device_cpu_work(f->dev, ZS_CPU_NODE, 1);
    unsigned mask = e.mask;
    uint64_t tests = f->st->frustum_tests;
    zs_frustum_result fr = mask ? zs_frustum_test_box(&f->frustum, nd->tlo, nd->thi, &mask,
                                                      &f->st->frustum_tests)
                                : ZS_FRUSTUM_INSIDE;
    zs_device_cpu_work(f->dev, ZS_CPU_FRUSTUM_TEST, f->st->frustum_tests - tests);
    if (fr == ZS_FRUSTUM_OUTSIDE) continue;

    if (m == ZS_CULL_VFC) {
      ns->visible = 1;
      ns->last_visited = frame;
      traverse_node(f, n, mask);
      continue;
    }
    if (m == ZS_CULL_HSW) {
      if (too_close(f, nd)) {
        traverse_node(f, n, mask);
        continue;
      }
      query_node(f, n, mask, 0);
      if (f->status == ZS_OK) take_result(f); /* stop and wait */
      continue;
    }
    if (!chc_like) continue;

    int was_visible = ns->visible && ns->last_visited == frame - 1;
    int leaf = is_leaf(t, n);
    double pv = predict(ns, w1, w2);
    ns->visible = 0;
    ns->last_visited = frame;
    if (too_close(f, nd)) { /* cannot be asked: taken as visible */
      ns->pv = 1.0;
      pull_up_visibility(f, n);
      traverse_node(f, n, mask);
      continue;
    }
    int termination = !was_visible || leaf;
    if (termination) {
      int ask = 1;
      if (m != ZS_CULL_CHC) ask = query_pays(f, n, pv);
      if (ask) {
        query_node(f, n, mask, (unsigned char)was_visible);
      } else { /* drawn as if visible; its P(V) carries the prediction */
        ns->pv = pv;
        pull_up_visibility(f, n);
        traverse_node(f, n, mask);
        continue;
      }
    }
    if (was_visible) traverse_node(f, n, mask);
  }
}

/* Polygons under every node: its objects' faces plus its children's. */
static int count_polygons(frame_ctx *f) {
  zs_culler *c = f->c;
  const zs_octree *t = f->t;
  if (!grow((void **)&c->polys, &c->cap_polys, t->nslots, sizeof *c->polys)) return 0;
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

/* The oracle of ideal: which instances own a pixel of the full image. */
static void ideal_frame(frame_ctx *f, const double view[16], const double proj[16]) {
  zs_culler *c = f->c;
  const zs_device_config *cfg = zs_device_config_of(f->dev);
  if (!c->oracle) {
    zs_device_config oc = *cfg;
    oc.algo = ZS_ALGO_ZBUFFER;
    oc.shade = ZS_SHADE_ID;
    if ((f->status = zs_device_create(&oc, &c->oracle, f->err))) return;
  }
  if (!grow((void **)&c->owns_pixel, &c->cap_inst, f->s->ninst, 1)) {
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
      ideal_frame(&f, view, proj);
      return f.status;
    default:
      break;
  }

  /* the tree methods */
  if (!grow((void **)&c->ns, &c->cap_ns, t->nslots, sizeof *c->ns))
    return zs_error_set(err, ZS_ERR_NOMEM, "culling: out of memory");
  /* Slots new to the culler start unseen, P(V) 1/2.  (A slot the octree
   * frees and reuses keeps its state: at worst a node is drawn without a
   * query once, which costs time, never pixels.) */
  for (; c->init_ns < t->nslots; c->init_ns++) c->ns[c->init_ns] = (node_state){0, 0, 0, 0, 0.5};
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
  f.tquery = c->cost.t_ns >= 0 ? c->cost.t_ns : k->per_call_ns + k->cpu_per_query_ns;
  f.tq = c->cost.tq_ns >= 0 ? c->cost.tq_ns : k->per_query_pixel_ns;

  zs_cull_method m = c->method;
  if (m == ZS_CULL_AUTO) {
    st->chosen = c->use_queries ? ZS_CULL_CHC_PROB : ZS_CULL_VFC;
    if (!c->use_queries) m = ZS_CULL_VFC;
  }
  if ((m == ZS_CULL_CHC_PROB || c->method == ZS_CULL_AUTO) && !count_polygons(&f))
    return zs_error_set(err, ZS_ERR_NOMEM, "culling: out of memory");
  walk_tree(&f, m);
  if (c->method == ZS_CULL_AUTO && f.status == ZS_OK) {
    /* Queries pay when the draws show hidden objects (vfc frames), or
     * when the queries found hidden nodes (chc-prob frames). */
    c->use_queries = c->use_queries ? st->queries_hidden > 0 || f.hidden_objects > 0
                                    : f.hidden_objects > 0;
  }
  return f.status;
}
