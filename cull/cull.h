/* zscan cull — visibility culling methods over the loose octree.
 *
 * Every method traverses the same octree of the scene's instances, draws on
 * the same device and reports the same counters, so their costs can be
 * compared in the device's modelled time:
 *
 *   none      draw every instance: the reference image.
 *   vfc       hierarchical view-frustum culling of the nodes' tight boxes,
 *             with plane masking and p/n-vertex tests; objects of a node
 *             that crosses the frustum are tested one by one.
 *   vfc-box   the conservative-visibility paper: an instance is drawn when
 *             its centre lies in the view box around the frustum (six
 *             comparisons after transforming the centre alone); faces whose
 *             screen box misses the window are dropped by the device.
 *             Approximate: instances whose centre lies outside are lost.
 *   hsw       hierarchical stop-and-wait: front to back, every node in the
 *             frustum is queried and its result waited for before going on.
 *   chc       coherent hierarchical culling (Bittner, Wimmer, Piringer,
 *             Purgathofer 2004): a traversal queue (front to back) and a
 *             query queue; only the termination nodes are queried (nodes
 *             that were visible leaves, and nodes that were invisible),
 *             previously visible nodes are opened without a query, visible
 *             leaves are drawn without waiting for their query, results are
 *             taken when ready or when there is nothing else to do, and
 *             visibility is pulled up the tree.
 *   chc-prob  the cost-model paper: chc, but a termination node is queried
 *             only when  Cr > P(V) Cr + Cq   (formulas 2, 3), with
 *               Cr = N Ttri + M Tcall                    (6, extended)
 *               S  = h^2 (Abb / 6) / (2 Dis tan(theta/2))^2   (9)
 *               Cq = T + S rho Tq                        (10)
 *               P_t(V) = w1 P_{t-1}(V) + (1 - w2)(1 - P_{t-1}(V))   (11)
 *             N the polygons and M the objects under the node (Tcall the
 *             cost of a draw call: the paper's (6) leaves it out, as its
 *             GPU was vertex-bound; with Tcall = 0 this is (6) exactly;
 *             zscan's device charges every call, so the default is the
 *             clock's), Abb its tight box's surface
 *             area, Dis the distance from the eye to the box's centre, theta
 *             the vertical field of view, h the viewport height; a node not
 *             queried is drawn as if visible, and a node queried waits in the
 *             query queue and is drawn on its answer, a leaf visible last
 *             frame too (the paper's flow; E(A2) = P(V) Cr + Cq counts its
 *             draw only when visible).  P_{t-1}(V) is what the last frame
 *             saw: 1 or 0 for an element it asked about; for an object it
 *             drew, whether the draw wrote a pixel (every draw goes inside
 *             a query, read the next frame; the paper's P^{t-1}(V) is the
 *             object's visibility in the last frame, and only a draw
 *             that wrote a pixel pulls visibility up); 0 for an element not
 *             reached because a node above it was found hidden; for a node
 *             drawn unasked, its prediction.
 *   ideal     an oracle: draws exactly the instances that own a pixel of
 *             the final image (found by a separate full render that the
 *             clock does not see) and issues no query: the lower bound.
 *   chcpp     CHC++ (Mattausch, Bittner, Wimmer 2008), its first two
 *             features: queries of previously invisible elements wait in a
 *             queue and are issued in batches of ZS_CHCPP_BATCH (one switch
 *             from drawing to querying per batch, not per query); a visible
 *             object is assumed visible for ZS_CHCPP_VISIBLE_FRAMES frames
 *             (the first interval drawn at random, so that the queries do
 *             not all fall due in the same frame), and the queries that do
 *             fall due wait in a second queue, issued when the culler would
 *             otherwise wait for a result.  Multiqueries: a batch is cut
 *             into groups asked under one query each; an element hidden i
 *             frames in a row stays hidden with probability
 *               p(i) = 0.99 - 0.7 e^-i
 *             and a group grows while its expected saving
 *               k / (1 + (1 - P) k)   (P = the product of its p(i))
 *             grows; a group with no sample hides all its members, else
 *             each is asked again on its own.  chcpp-nobatch,
 *             chcpp-nodefer and chcpp-nomulti switch one feature off
 *             (ablation).  CHC++'s tighter bounds are the tight boxes of
 *             the octree's nodes and, for every method, the parts of an
 *             object (cull/parts.h; --bounds box asks about its box).
 *   chcpp-prob  chcpp with chc-prob's test (formulas 2, 3, 6, 9, 10)
 *             before each query chcpp would issue, of a hidden element or
 *             of a visible object that falls due: when the query does not
 *             pay, the element is drawn unasked; P(V) follows (11) from
 *             what the last frame saw, as for chc-prob.
 *             The combination neither paper tried.
 *   nohc      near-optimal hierarchical culling (Guthe, Balazs, Klein
 *             2006): every termination element (an object, visible or
 *             not, or a node that was hidden) is queried, and drawn only
 *             when its answer comes back, when
 *               Cr > P(V) Cr + Cq,   Cq = T + S Tq,
 *             with S the pixels of its box's projected rectangle (not (9)'s
 *             estimate); otherwise it is drawn at once (an object) or
 *             opened (a node).  P(V) is the rate at which elements of its
 *             class were found visible by this culler's own queries, from a
 *             prior worth two answers.  A class is a history times one of
 *             ten buckets of coverage:
 *               history   unseen last frame; hidden i frames in a row (prior
 *                         1 - p(i), chcpp's p); or a visible object by
 *                         log2(s + 1) of the pixels s its last measured draw
 *                         wrote (every 4th frame it draws it inside a query);
 *               coverage  the chance that what is drawn so far covers the
 *                         rectangle: every 16-pixel cell it meets covered,
 *                         each with probability 1 - e^-d, d the projected box
 *                         areas drawn into the cell this frame (front to
 *                         back) times the fill of a mesh in its box (1/2);
 *                         1 - coverage is the prior of the other classes.
 *             Its queries wait in batches of 32, issued when a batch is
 *             full or nothing else is left to do: one change to querying
 *             and back per batch, so its T counts 2/32 of a switch each
 *             (state-switch-aware; chc-prob's T counts two).
 *   ideal-box an oracle as ideal, that draws the instances whose query
 *             bounds (parts or box) have a sample against the full image's
 *             depth buffer: the lower bound of every method that asks.
 *   auto      chc-prob with w1 and w2 learnt from the outcomes of its own
 *             queries, and plain vfc for the frames after one whose queries
 *             found nothing hidden; a vfc frame whose draws show a hidden
 *             object (one that wrote no pixel) turns the queries back on:
 *             a scene without occlusion pays no query cost.
 *   hzb       two-phase culling against a hierarchical depth buffer
 *             (Greene et al., SIGGRAPH 93; Haar and Aaltonen, SIGGRAPH
 *             2015; Karis et al., Nanite, SIGGRAPH 2021): last frame's set
 *             in the frustum drawn front to back in passes, each pass
 *             after the first tested against the pyramid of those before;
 *             its depth pyramid built, the octree traversed a level at a
 *             time against it (a pass a level), what may be visible
 *             drawn; the final depth's pyramid tests the objects drawn
 *             for the next frame's set.  No query; the results stay on
 *             the GPU (cull/two_phase_hzb.c, raster/hzb.c).
 *
 * Exactness.  Every method but vfc-box gives the image of none: a node is
 * skipped only when its tight box, or an object's parts' boxes (which
 * hold its content), have no sample
 * passing the less-or-equal test against a depth buffer that only gets
 * nearer (for hzb: the pyramid's test never hides a box whose query would
 * count a sample); boxes that the near plane could cut are never queried
 * but taken as visible.
 */
#ifndef ZS_CULL_CULL_H
#define ZS_CULL_CULL_H

#include <stdint.h>

#include "cull/octree.h"
#include "raster/raster.h"
#include "scene/scene.h"

typedef enum zs_cull_method {
  ZS_CULL_NONE,
  ZS_CULL_VFC,
  ZS_CULL_VFC_BOX,
  ZS_CULL_HSW,
  ZS_CULL_CHC,
  ZS_CULL_CHC_PROB,
  ZS_CULL_IDEAL,
  ZS_CULL_AUTO,
  ZS_CULL_CHCPP,          /* CHC++: batched and deferred queries */
  ZS_CULL_CHCPP_NOBATCH,  /* ablation: without batching */
  ZS_CULL_CHCPP_NODEFER,  /* ablation: without deferred visible queries */
  ZS_CULL_CHCPP_NOMULTI,  /* ablation: without multiqueries */
  ZS_CULL_CHCPP_PROB,     /* CHC++ with chc-prob's test before each query */
  ZS_CULL_NOHC,           /* near-optimal hierarchical culling's cost model */
  ZS_CULL_IDEAL_BOX,      /* oracle: the instances whose box has a sample */
  ZS_CULL_HZB,            /* two-phase culling against a hierarchical depth buffer */
  ZS_CULL_METHODS
} zs_cull_method;

enum { ZS_CHCPP_BATCH = 50, ZS_CHCPP_VISIBLE_FRAMES = 5 };

/* The method names, in enum order, for usage lines and error messages
 * (test_cull checks them against zs_cull_method_name). */
#define ZS_CULL_METHOD_LIST                                                                   \
  "none vfc vfc-box hsw chc chc-prob ideal auto chcpp chcpp-nobatch chcpp-nodefer chcpp-nomulti " \
  "chcpp-prob nohc ideal-box hzb"

/* "none", "vfc", ...; and back (-1 for an unknown name). */
const char *zs_cull_method_name(zs_cull_method m);
int zs_cull_method_parse(const char *name);

/* The cost model's parameters (chc-prob, chcpp-prob, auto).  w1 and w2
 * default to the rates auto measured over 20 frames of the plant walk
 * (builtin:plant?detail=1), rounded.  With learn > 0 they are learnt from
 * the outcomes of the culler's own queries (the share of the elements
 * asked about when visible that stayed visible, and of those hidden that
 * stayed hidden), starting from w1 and w2 as if learn outcomes had borne
 * them out; auto always learns them, from one outcome each way.
 * Negative times take the device clock's: Ttri = per_polygon, Tcall =
 * per_call + cpu_per_call, T = per_call + 2 cpu_per_query + 2 switch (the
 * work a query costs: its box, its begin/end, and the change to querying
 * and back that a query between draws makes; its latency is what the
 * query queue hides), Tq = per_query_pixel. */
typedef struct zs_cost_params {
  double w1, w2;        /* P(stays visible), P(stays invisible) */
  double ttri_ns, tcall_ns, t_ns, tq_ns;
  double rho;           /* pixels per unit of S: 1, S is in pixels */
  double learn;         /* 0: w1, w2 as given; else the weight of their prior */
  double measure;       /* 1: P_{t-1}(V) of an object drawn is whether its
                         * draw wrote a pixel (a query around every draw);
                         * 0: the prediction it was drawn on */
} zs_cost_params;

void zs_cost_params_default(zs_cost_params *p);

/* What a method did in one frame. */
typedef struct zs_cull_stats {
  uint64_t nodes_visited;   /* nodes taken from the traversal queue */
  uint64_t frustum_tests;   /* box-plane tests */
  uint64_t queries;         /* occlusion queries issued */
  uint64_t queries_hidden;  /* of those, with no sample */
  uint64_t objects_drawn;
  uint64_t faces_drawn;     /* polygons submitted by the draws */
  uint64_t cost_evals;      /* cost-model evaluations */
  uint64_t draws_measured;  /* objects drawn inside a query that counts what
                             * they write (chc-prob, auto's chc-prob frames,
                             * chcpp-prob, nohc); not in queries, which ask
                             * about boxes */
  zs_cull_method chosen;    /* auto: what it ran this frame */
  /* ideal-box only, against its set of the last frame (all 0 in the first
   * frame and for the other methods; cull/churn.h): objects that entered
   * the set, of those the ones outside the frustum in the last frame;
   * objects that left it, of those the ones outside the frustum now; and
   * two floors, in ps, of what a method that learns visibility from the
   * last frame pays over ideal-box for that change */
  uint64_t set_entered, set_entered_outside, set_left, set_left_outside;
  int64_t churn_known_ps, churn_ranked_ps;
  /* hzb only: objects drawn in phase 1 (last frame's set) and in phase 2
   * (found by the pyramid), and of phase 1's the ones the final pyramid
   * hides (drawn though hidden: the set's staleness) */
  uint64_t hzb_phase1, hzb_phase2, hzb_stale;
} zs_cull_stats;

typedef struct zs_culler zs_culler;

/* What a method decided for an octree node in the last frame (for
 * pictures: zscan render --overlay culling). */
typedef enum zs_node_decision {
  ZS_NODE_NOT_REACHED = 0,  /* below a node culled, or not traversed */
  ZS_NODE_OUTSIDE,          /* outside the frustum */
  ZS_NODE_QUERIED_HIDDEN,   /* queried, no sample */
  ZS_NODE_QUERIED_VISIBLE,  /* queried, visible */
  ZS_NODE_NO_QUERY          /* entered without a query */
} zs_node_decision;

/* The decisions of the last frame, one per octree node slot (*n slots);
 * NULL before the first frame of a tree method. */
const uint8_t *zs_culler_decisions(const zs_culler *c, int32_t *n);

/* A culler keeps its per-node state from frame to frame: one per method
 * and walk.  The octree must outlive it. */
zs_status zs_culler_create(zs_cull_method m, const zs_cost_params *cost, zs_culler **out,
                           zs_error *err);
void zs_culler_destroy(zs_culler *c);

/* What a query asks about an object: the union of its parts' boxes
 * (cull/parts.h; the default), or its box. */
typedef enum zs_query_bounds { ZS_BOUNDS_PARTS, ZS_BOUNDS_BOX } zs_query_bounds;

/* "parts" or "box"; -1 for another name. */
int zs_query_bounds_parse(const char *name);

/* Before the culler's first frame. */
zs_status zs_culler_set_bounds(zs_culler *c, zs_query_bounds b, zs_error *err);

/* Draws one frame of scene s (organised in tree t) on dev with the camera
 * view/proj: clears the device, sets the camera, and issues draws and
 * queries.  The caller then calls zs_device_finish.  dev must be in zbuffer
 * mode for the methods that query. */
zs_status zs_culler_frame(zs_culler *c, zs_device *dev, const zs_scene *s, const zs_octree *t,
                          const double view[16], const double proj[16], zs_cull_stats *st,
                          zs_error *err);

#endif
