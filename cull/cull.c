/* Visibility culling over the loose octree (cull.h): the culler, and the
 * walks of vfc, hsw, chc, chc-prob, auto and nohc (its decisions: nohc.c).
 * The steps they share are in hierarchy.c (internal.h).
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
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cull/internal.h"
#include "raster/grow.h"

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
  *p = (zs_cost_params){0.93, 0.97, -1.0, -1.0, -1.0, -1.0, 1.0, 0.0, 1.0};
}

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
  cull_churn_free(&c->churn);
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

static void walk_tree(frame_ctx *f, zs_cull_method m) {
  zs_culler *c = f->c;
  const zs_octree *t = f->t;
  const uint32_t frame = c->frame;
  double w1, w2;
  cull_weights(c, m, &w1, &w2);
  c->nheap = 0;
  c->qhead = c->qtail = 0;
  c->ni = 0;
  c->multi = 0;
  if (!t->node[ZS_OCTREE_ROOT].empty && !cull_heap_push(f, ZS_OCTREE_ROOT, ZS_FRUSTUM_ALL_PLANES))
    f->status = zs_error_set(f->err, ZS_ERR_NOMEM, "culling: out of memory");

  while (f->status == ZS_OK && (c->nheap > 0 || c->qhead < c->qtail || c->ni > 0)) {
    /* nohc: its queries wait in a batch of NOHC_BATCH, issued when full
     * or when there is nothing else to do: one change from drawing to
     * querying and back per batch, which its cost model counts */
    if (c->ni > 0 && (c->ni >= NOHC_BATCH || c->nheap == 0)) cull_flush_invisible(f);
    /* Part 1: results that are ready, or any when nothing else is left. */
    while (f->status == ZS_OK && c->qhead < c->qtail &&
           (c->nheap == 0 || zs_device_query_ready(f->dev, c->qq[c->qhead].q)))
      cull_take_result(f);
    if (c->nheap == 0 || f->status != ZS_OK) continue;

    /* Part 2: the nearest element waiting. */
    elem e;
    unsigned mask;
    if (!cull_next_in_frustum(f, &e, &mask)) continue;
    elem_state *es = cull_state(f, e);

    if (m == ZS_CULL_VFC) {
      es->visible = 1;
      es->last_visited = frame;
      cull_traverse(f, e, mask);
      continue;
    }
    if (m == ZS_CULL_HSW) {
      if (cull_too_close(f, e)) cull_traverse(f, e, mask);
      else {
        cull_issue_query(f, e, mask, 0);
        if (f->status == ZS_OK) cull_take_result(f); /* stop and wait */
      }
      continue;
    }

    /* chc, chc-prob, auto, nohc */
    int seen_last = es->last_visited == frame - 1;
    int was_visible = es->visible && seen_last;
    /* Hidden in the frame before: found so, or not reached because a node
     * above it was found so (its parent, which pushed it, was visited
     * before it this frame and set its own flag) */
    elem up = cull_parent_of(f, e);
    es->hidden_before = seen_last ? !es->visible
                                  : up != ZS_OCTREE_NONE && cull_state(f, up)->hidden_before;
    es->visible = 0;
    es->last_visited = frame;
    if (cull_too_close(f, e)) { /* cannot be asked: taken as visible */
      es->pv = 1.0;
      cull_pull_up_visibility(f, e);
      cull_traverse(f, e, mask);
      continue;
    }
    /* termination elements: objects (the leaves), and nodes that were
     * hidden; nodes that were visible are opened without a query */
    if (m == ZS_CULL_NOHC && (is_object(e) || !was_visible)) {
      cull_nohc_visit(f, e, mask, was_visible, seen_last);
      continue;
    }
    if (is_object(e) || !was_visible) {
      /* (11) from last frame's P(V): es->pv is unchanged so far, but an
       * element under a node found hidden was hidden too, P_{t-1}(V) = 0,
       * whatever it was when last seen (one outside the frustum then keeps
       * that) */
      if (!seen_last && es->hidden_before) es->pv = 0.0;
      double pv = cull_predict(es, w1, w2);
      if (m != ZS_CULL_CHC && !cull_query_pays(f, e, pv)) {
        cull_draw_unasked(f, e, mask, pv);
        continue;
      }
      cull_issue_query(f, e, mask, (unsigned char)was_visible);
      /* CHC draws a leaf visible last frame without waiting: its answer is
       * for the next frame.  The cost model's methods ask only where the
       * answer pays for itself, so they wait for it (the paper's flow: an
       * element asked goes to the query queue, only one not asked is drawn
       * at once), and a leaf found hidden is not drawn this frame. */
      if (m != ZS_CULL_CHC) continue;
    }
    if (was_visible) cull_traverse(f, e, mask);
  }
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
      for (int32_t i = 0; i < s->ninst && f.status == ZS_OK; i++) cull_draw_instance(&f, i);
      return f.status;
    case ZS_CULL_VFC_BOX: {
      zs_view_box vb;
      zs_view_box_make(&vb, view, proj);
      for (int32_t i = 0; i < s->ninst && f.status == ZS_OK; i++) {
        double centre[3];
        for (int k = 0; k < 3; k++) centre[k] = 0.5 * (s->inst[i].lo[k] + s->inst[i].hi[k]);
        st->frustum_tests++;
        zs_device_cpu_work(dev, ZS_CPU_FRUSTUM_TEST, 1);
        if (zs_view_box_contains(&vb, centre)) cull_draw_instance(&f, i);
      }
      return f.status;
    }
    case ZS_CULL_IDEAL:
    case ZS_CULL_IDEAL_BOX:
      cull_ideal_frame(&f, view, proj, c->method == ZS_CULL_IDEAL_BOX);
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
  for (; c->init_ns < t->nslots; c->init_ns++) c->ns[c->init_ns] = (elem_state){.pv = 0.5, .asked_class = -1};
  for (; c->init_os < s->ninst; c->init_os++) c->os[c->init_os] = (elem_state){.pv = 0.5, .asked_class = -1};
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
    if (m == ZS_CULL_CHCPP_PROB && !cull_count_polygons(&f))
      return zs_error_set(err, ZS_ERR_NOMEM, "culling: out of memory");
    if (!zs_grow((void **)&c->decision, &c->cap_decision, t->nslots, 1))
      return zs_error_set(err, ZS_ERR_NOMEM, "culling: out of memory");
    c->ndecision = t->nslots;
    memset(c->decision, ZS_NODE_NOT_REACHED, (size_t)t->nslots);
    f.measure_draws = m == ZS_CULL_CHCPP_PROB && c->cost.measure != 0.0;
    cull_walk_chcpp(&f, m != ZS_CULL_CHCPP_NOBATCH, m != ZS_CULL_CHCPP_NODEFER, m == ZS_CULL_CHCPP_PROB);
    return f.status;
  }
  if (m == ZS_CULL_AUTO) {
    st->chosen = c->use_queries ? ZS_CULL_CHC_PROB : ZS_CULL_VFC;
    if (!c->use_queries) m = ZS_CULL_VFC;
  }
  if ((m == ZS_CULL_CHC_PROB || m == ZS_CULL_NOHC || c->method == ZS_CULL_AUTO) &&
      !cull_count_polygons(&f))
    return zs_error_set(err, ZS_ERR_NOMEM, "culling: out of memory");
  if (m == ZS_CULL_NOHC) { /* an empty coverage grid */
    if (!zs_coverage_reset(&c->cov, cfg->width, cfg->height, view, proj))
      return zs_error_set(err, ZS_ERR_NOMEM, "culling: out of memory");
  }
  if (!zs_grow((void **)&c->decision, &c->cap_decision, t->nslots, 1))
    return zs_error_set(err, ZS_ERR_NOMEM, "culling: out of memory");
  c->ndecision = t->nslots;
  memset(c->decision, ZS_NODE_NOT_REACHED, (size_t)t->nslots);
  f.measure_draws = (m == ZS_CULL_CHC_PROB || m == ZS_CULL_AUTO) && c->cost.measure != 0.0;
  walk_tree(&f, m);
  if (c->method == ZS_CULL_AUTO && f.status == ZS_OK) {
    /* Queries pay when the draws show hidden objects (vfc frames), or
     * when the queries found hidden nodes (chc-prob frames). */
    c->use_queries = c->use_queries ? st->queries_hidden > 0 || f.hidden_objects > 0
                                    : f.hidden_objects > 0;
  }
  return f.status;
}
