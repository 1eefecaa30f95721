/* zscan cull — what the culling methods share: the elements they traverse,
 * the culler's state, the frame's context, the hooks a method gives the
 * shared code, and the steps every method takes.  Not for use outside
 * cull/.
 *
 * A method is one row of the table of methods (cull.c): its name and its
 * hooks (cull_ops), picked once, when the culler is created.  What a
 * method keeps from frame to frame beyond what the shared steps keep is
 * its own, a struct defined in its file, made and freed by its create and
 * destroy hooks and reached through c->own.  The methods that traverse
 * the octree share one traversal (traverse.c), which calls the hooks; the
 * shared steps (hierarchy.c: elements, drawing, the traversal queue, the
 * frustum; query_queue.c: queries and their answers; query_batch.c: queries
 * held back and issued together; cost.c: the cost-model paper's formulas)
 * name no method.  Each method is in its own file: none.c, vfc_box.c,
 * vfc.c, hsw.c, chc.c (chc, chc-prob), auto.c, chcpp.c (chcpp and its
 * variants), nohc.c, ideal.c (ideal, ideal-box), two_phase_hzb.c (hzb). */
#ifndef ZS_CULL_INTERNAL_H
#define ZS_CULL_INTERNAL_H

#include "cull/cull.h"
#include "cull/frustum.h"
#include "cull/parts.h"
#include "util/rng.h"

/* The hierarchy the methods traverse: the octree's nodes, with each object as
 * a leaf of the node that holds it (so a visible object does not drag its
 * neighbours in, and a hidden one is culled on its own).  An element is a
 * node n >= 0 or an object i, encoded as -(i + 2). */
typedef int32_t elem;
static inline int is_object(elem e) { return e <= -2; }
static inline int32_t object_of(elem e) { return -e - 2; }
static inline elem object_elem(int32_t i) { return -i - 2; }

/* Across frames, per element: CHC's visible and lastVisited, what the
 * cost model predicts from (P(V), and whether it was hidden the frame
 * before), CHC++'s count for p(i) and its next query. */
typedef struct elem_state {
  uint32_t last_visited;   /* frame (frames count from 1) */
  uint32_t done;           /* frame it was rendered (object) or opened (node) */
  uint8_t visible;
  uint8_t hidden_before;   /* chc-prob, auto: hidden in the frame before:
                            * found so, or under a node found so */
  double pv;               /* P(V) for the next frame */
  uint32_t next_query;     /* chcpp: the frame a visible object is asked again
                            * (query_batch.c); nohc: the frame its draw is measured
                            * again, which a visible answer sets as chcpp's */
  uint32_t hidden_frames;  /* frames found hidden in a row (chcpp's p(i), nohc) */
} elem_state;

/* An element whose query is held back (query_batch.c), or a member of a
 * multiquery. */
typedef struct pending {
  elem e;
  unsigned mask;
  uint8_t was_visible;
} pending;

/* Elements whose queries are held back, in the order they came: CHC++'s
 * i-queue and v-queue, nohc's batch, the members of CHC++'s multiqueries;
 * each kept in the state of the method that holds it. */
typedef struct cull_held {
  pending *p;
  int32_t n, cap;
} cull_held;

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
  int32_t group, ngroup;   /* a multiquery: its ngroup members from the
                            * group-th in its method's list; 0: one element */
} query_entry;

typedef struct frame_ctx frame_ctx;

/* What the cost model (cost.c) keeps from frame to frame, in the state of
 * each method that decides by it (chc-prob, auto, chcpp-prob, nohc): the
 * polygons under each node, this frame (N of (6)), and the transitions its
 * queries saw (visible or hidden when asked, then visible or hidden), from
 * which (11)'s w1 and w2 are learnt. */
typedef struct cull_cost_model {
  int64_t *polys;
  int32_t cap_polys;
  uint64_t vv, vh, hv, hh;
} cull_cost_model;

/* What the traversal (traverse.c) and the shared steps call during a frame: per
 * element, per draw, per answer.  A NULL hook does nothing. */
typedef struct cull_hooks {
  /* An element taken from the traversal queue, inside the frustum. */
  void (*visit)(frame_ctx *f, elem e, unsigned mask);
  /* The traversal queue is empty, before any answer is taken. */
  void (*empty)(frame_ctx *f);
  /* Nothing to traverse and no answer ready (waiting: some query is out):
   * issues a query held back rather than wait; 1 when it did, 0 when it
   * holds none.  A method that holds queries back issues them here or in
   * empty, or the traversal ends without them. */
  int (*idle)(frame_ctx *f, int waiting);
  /* An element found visible by its query, or drawn unasked: visibility
   * up the tree, then drawn or opened (cull_draw_visible; with measured
   * draws, cull_draw_visible_measured).  Not NULL for a method that asks. */
  void (*draw_visible)(frame_ctx *f, elem e, unsigned mask);
  /* The answer to a query about one element (q->e). */
  void (*answered)(frame_ctx *f, const query_entry *q, int visible);
  /* The answer to a multiquery (q->ngroup > 0): all that the method does
   * with it.  Not NULL for a method that issues multiqueries. */
  void (*multiquery_answered)(frame_ctx *f, const query_entry *q, int visible);
  /* Whether instance i's draw goes inside a query; after the draw, what
   * it wrote. */
  int (*measure_due)(const frame_ctx *f, int32_t i);
  void (*drawn)(frame_ctx *f, int32_t i, int measured, uint64_t written);
} cull_hooks;

/* A culling method: one row of the table of methods (cull.c). */
typedef struct cull_ops {
  const char *name;        /* as zscan --cull spells it (zs_cull_method_name) */
  /* The method's own state, kept from frame to frame: made when the
   * culler is (NULL when out of memory), reached through c->own, freed
   * with the culler.  NULL hooks: the method keeps none. */
  void *(*create)(void);
  void (*destroy)(void *own);
  /* Draws a frame: cull_traverse_octree for the methods that traverse
   * the octree. */
  void (*frame)(frame_ctx *f);
  /* The traversal's: the method's own set-up of a frame (it may choose the
   * frame's hooks: auto), and what it learns after the frame. */
  void (*begin)(frame_ctx *f);
  void (*end)(frame_ctx *f);
  const cull_hooks *hooks;
} cull_ops;

/* The culler: what the shared steps keep for every method. */
struct zs_culler {
  zs_cull_method method;
  const cull_ops *ops;
  void *own;               /* the method's own state (ops->create's), or NULL */
  zs_cost_params cost;
  uint32_t frame;
  elem_state *ns, *os;     /* nodes, objects */
  int32_t cap_ns, init_ns, cap_os, init_os;
  heap_entry *heap;
  int32_t nheap, cap_heap;
  query_entry *qq;
  int32_t qhead, qtail, cap_qq;
  uint8_t *decision;       /* zs_node_decision per node, this frame */
  int32_t cap_decision, ndecision;
  zs_rng rng;              /* the first intervals of chcpp's and nohc's asking again */
  /* the boxes of the query being issued; the objects' parts (NULL: boxes) */
  double (*qlo)[3], (*qhi)[3];
  int32_t cap_qlo, cap_qhi;
  zs_parts *parts;
  /* objects in the order they are drawn (cull_order_front_to_back) */
  int32_t *order;
  int32_t cap_order;
};

/* The frame's context. */
struct frame_ctx {
  zs_culler *c;
  const cull_hooks *hooks; /* the culler's, or those its method chose for the frame */
  zs_device *dev;
  const zs_scene *s;
  const zs_octree *t;
  const double *view, *proj;
  zs_frustum frustum;
  double eye[3];
  double near_reach;       /* farthest a near-plane corner lies from the eye */
  double tan_half_fovy, height;
  double ttri, tcall, tq, tquery; /* cost model constants, ns */
  double w1, w2;           /* (11)'s weights, this frame */
  cull_cost_model *model;  /* the method's, from cull_cost_begin; NULL: none */
  zs_cull_stats *st;
  uint64_t hidden_objects; /* objects drawn that wrote no pixel (auto) */
  zs_error *err;
  zs_status status;
};

/* The methods (cull.c picks one by zs_cull_method). */
extern const cull_ops cull_none, cull_vfc, cull_vfc_box, cull_hsw, cull_chc, cull_chc_prob,
    cull_ideal, cull_auto, cull_chcpp, cull_chcpp_nobatch, cull_chcpp_nodefer,
    cull_chcpp_nomulti, cull_chcpp_prob, cull_nohc, cull_ideal_box, cull_hzb;
/* The hooks of vfc and chc-prob, for auto's frames. */
extern const cull_hooks cull_vfc_hooks, cull_chc_prob_hooks, cull_chc_prob_measured_hooks;

/* Sets f->status to out of memory. */
void cull_out_of_memory(frame_ctx *f);

/* ---- traverse.c: the traversal of the octree, front to back ---- */

/* The frame of every method that traverses the octree. */
void cull_traverse_octree(frame_ctx *f);
/* Its set-up, for a method with a frame of its own over the tree (hzb):
 * the per-element state for the frame's tree and scene; 0 when out of
 * memory. */
int cull_traversal_begin(frame_ctx *f);
/* Grows an array of per-element state of size bytes an entry (nodes by
 * slot, or objects by instance) to n entries, each that is new a copy of
 * fresh: the first *init have been made before and keep theirs.  0 when
 * out of memory. */
int cull_grow_elements(void **a, int32_t *cap, int32_t *init, int32_t n, size_t size,
                       const void *fresh);

/* ---- hierarchy.c: elements, drawing, the traversal queue ---- */

elem_state *cull_state(frame_ctx *f, elem e);
elem cull_parent_of(const frame_ctx *f, elem e);
/* The box of an element: a node's tight box, an object's own box. */
void cull_elem_box(const frame_ctx *f, elem e, const double **lo, const double **hi);
/* Records the decision on node e for the overlay. */
void cull_decide(frame_ctx *f, elem e, zs_node_decision d);
/* Draws instance i (and counts it). */
void cull_draw_instance(frame_ctx *f, int32_t i);
/* Pushes e on the traversal queue (0 when out of memory). */
int cull_heap_push(frame_ctx *f, elem e, unsigned mask);
/* The objects flagged in draw[] front to back into the culler's order (n
 * of them; -1 when out of memory), and drawn so. */
int32_t cull_order_front_to_back(frame_ctx *f, const uint8_t *draw);
void cull_draw_front_to_back(frame_ctx *f, const uint8_t *draw);
/* e's box against the frustum planes left in *mask, charged to the CPU. */
zs_frustum_result cull_frustum_test(frame_ctx *f, elem e, unsigned *mask);
/* An element visited (counted, charged) and tested so; 0: outside. */
int cull_visit_in_frustum(frame_ctx *f, elem e, unsigned *mask);
/* Pops the nearest element and tests it against the frustum; 0: outside. */
int cull_next_in_frustum(frame_ctx *f, elem *e, unsigned *mask);
/* Hands what node n holds to push, each with mask, in the traversal's
 * order, until push fails (0 then: out of memory). */
typedef int cull_push_fn(frame_ctx *f, void *to, elem e, unsigned mask);
int cull_open_node(frame_ctx *f, elem n, unsigned mask, cull_push_fn *push, void *to);
/* TraverseNode of the paper: an object is drawn, a node pushes what it holds. */
void cull_traverse_node(frame_ctx *f, elem e, unsigned mask);
void cull_pull_up_visibility(frame_ctx *f, elem e);
/* An element found visible: visible up the tree, then traversed. */
void cull_draw_visible(frame_ctx *f, elem e, unsigned mask);
/* Whether the near plane could cut e's box (a query would miss pixels). */
int cull_too_close(const frame_ctx *f, elem e);
/* Marks e visited this frame and says what it was in the last; 0 when it
 * is too close to ask about, and so taken as visible and traversed. */
int cull_enter(frame_ctx *f, elem e, unsigned mask, int *was_visible, int *seen_last);
/* Draws e as if visible without asking; its P(V) goes to the next frame. */
void cull_draw_unasked(frame_ctx *f, elem e, unsigned mask, double pv);

/* ---- query_queue.c: occlusion queries and their answers ---- */

/* Appends the boxes a query over e draws to the culler's query boxes. */
int cull_add_query_boxes(frame_ctx *f, elem e, int32_t *n);
/* The first nbox of those as query q on dev (the frame's device, or an
 * oracle's); the status. */
zs_status cull_query_boxes(frame_ctx *f, zs_device *dev, int32_t nbox, zs_query *q);
/* One query over the boxes of members[0 .. n-1], queued as qe. */
void cull_query_elements(frame_ctx *f, const pending *members, int32_t n, query_entry qe);
void cull_issue_query(frame_ctx *f, elem e, unsigned mask, unsigned char was_visible);
/* Takes the answer at the head of the query queue and acts on it. */
void cull_take_result(frame_ctx *f);

/* ---- query_batch.c: queries held back, issued together ---- */

/* Holds e's query back at the end of h (0 when out of memory). */
int cull_hold(frame_ctx *f, cull_held *h, elem e, unsigned mask, uint8_t was_visible);
/* Issues h's queries, each on its own, in order, and empties h. */
void cull_issue_held(frame_ctx *f, cull_held *h);
void cull_held_free(cull_held *h);
/* The chance that an element hidden i frames in a row stays hidden. */
double cull_keep_hidden(uint32_t i);
/* An object found visible: the frame it is asked about again. */
void cull_ask_again_later(frame_ctx *f, elem e, int was_visible);

/* ---- cost.c: the cost model of the cost-model paper ---- */

/* The state of a method whose own is the cost model's alone (chc-prob),
 * and its parts for a method that keeps more. */
void *cull_cost_model_create(void);
void cull_cost_model_destroy(void *own);
void cull_cost_model_free(cull_cost_model *m);
/* The frame's constants and the polygons under every node, in the
 * method's model (0 when out of memory). */
int cull_cost_begin(frame_ctx *f, cull_cost_model *model);
/* A query's outcome, counted for the learnt weights (with a model). */
void cull_cost_outcome(frame_ctx *f, int was_visible, int visible);
/* (11)'s w1 and w2 of this frame: as given, or learnt (cost.learn > 0);
 * learnt from the queries' outcomes, starting from w1 and w2 as if weight
 * outcomes had borne each out. */
void cull_cost_weights(frame_ctx *f);
/* The frame of a method that decides by the cost model (chc-prob,
 * chcpp-prob): its constants and weights, and its hooks with measured
 * draws (below) when cost.measure is on. */
void cull_cost_frame(frame_ctx *f, cull_cost_model *model, const cull_hooks *measured);
void cull_learn_weights(frame_ctx *f, double w1, double w2, double weight);
/* Cr (6), whether a query pays (2, 3, 6, 9, 10), P(V) (11). */
double cull_render_cost(const frame_ctx *f, elem e);
int cull_query_pays(frame_ctx *f, elem e, double pv);
double cull_predict(const frame_ctx *f, const elem_state *es);
/* Measured draws (cost.measure != 0; chc-prob, chcpp-prob): every object
 * drawn inside a query, whose count is its P(V) for the next frame and its
 * visibility of this one; the hooks of a method that measures them. */
int cull_measure_every_draw(const frame_ctx *f, int32_t i);
void cull_measured_drawn(frame_ctx *f, int32_t i, int measured, uint64_t written);
void cull_draw_visible_measured(frame_ctx *f, elem e, unsigned mask);

#endif
