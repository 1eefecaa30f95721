/* The cost model of the cost-model paper (internal.h; its formulas are
 * stated in cull.h): what drawing an element costs (6), what asking about
 * it costs (9, 10), whether asking pays (2, 3), and the chance that it is
 * visible (11), with the weights given or learnt from the queries'
 * outcomes; and measured draws, which tell P(V) what an object's draw
 * wrote.  chc-prob, auto, chcpp-prob and nohc (its own P(V) and S) decide
 * by it. */
#include <math.h>
#include <stdlib.h>

#include "cull/internal.h"
#include "util/grow.h"

void *cull_cost_model_create(void) { return calloc(1, sizeof(cull_cost_model)); }

void cull_cost_model_free(cull_cost_model *m) { free(m->polys); }

void cull_cost_model_destroy(void *own) {
  cull_cost_model_free(own);
  free(own);
}

/* Polygons under every node: its objects' faces plus its children's. */
static int count_polygons(frame_ctx *f) {
  cull_cost_model *c = f->model;
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

/* The constants: as given, or (negative) the device clock's. */
int cull_cost_begin(frame_ctx *f, cull_cost_model *model) {
  const zs_cost_params *p = &f->c->cost;
  f->model = model;
  const zs_clock_params *k = zs_device_clock_params(f->dev);
  f->ttri = p->ttri_ns >= 0 ? p->ttri_ns : k->per_polygon_ns;
  f->tcall = p->tcall_ns >= 0 ? p->tcall_ns : k->per_call_ns + k->cpu_per_call_ns;
  f->tquery = p->t_ns >= 0 ? p->t_ns : k->per_call_ns + 2.0 * k->cpu_per_query_ns + 2.0 * k->switch_ns;
  f->tq = p->tq_ns >= 0 ? p->tq_ns : k->per_query_pixel_ns;
  if (!count_polygons(f)) {
    cull_out_of_memory(f);
    return 0;
  }
  return 1;
}

/* A rate learnt from counted outcomes (stay of stay + change), starting
 * from prior as if weight outcomes had been seen. */
static double learnt_rate(uint64_t stay, uint64_t change, double prior, double weight) {
  return ((double)stay + weight * prior) / ((double)(stay + change) + weight);
}

void cull_learn_weights(frame_ctx *f, double w1, double w2, double weight) {
  const cull_cost_model *m = f->model;
  f->w1 = learnt_rate(m->vv, m->vh, w1, weight);
  f->w2 = learnt_rate(m->hh, m->hv, w2, weight);
}

void cull_cost_outcome(frame_ctx *f, int was_visible, int visible) {
  cull_cost_model *m = f->model;
  if (!m) return;
  if (was_visible) visible ? m->vv++ : m->vh++;
  else visible ? m->hv++ : m->hh++;
}

void cull_cost_weights(frame_ctx *f) {
  const zs_cost_params *p = &f->c->cost;
  if (p->learn > 0.0) {
    cull_learn_weights(f, p->w1, p->w2, p->learn);
  } else {
    f->w1 = p->w1;
    f->w2 = p->w2;
  }
}

void cull_cost_frame(frame_ctx *f, cull_cost_model *model, const cull_hooks *measured) {
  if (!cull_cost_begin(f, model)) return;
  cull_cost_weights(f);
  if (f->c->cost.measure != 0.0) f->hooks = measured;
}

/* (11): the chance that an element is visible this frame, from its state. */
double cull_predict(const frame_ctx *f, const elem_state *es) {
  return f->w1 * es->pv + (1.0 - f->w2) * (1.0 - es->pv);
}

/* (6), extended: Cr = N Ttri + M Tcall, N the polygons and M the objects
 * under e. */
double cull_render_cost(const frame_ctx *f, elem e) {
  int64_t n = is_object(e) ? f->s->meshes[f->s->inst[object_of(e)].mesh].mesh.nfaces
                           : f->model->polys[e];
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

int cull_measure_every_draw(const frame_ctx *f, int32_t i) {
  (void)f, (void)i;
  return 1;
}

/* P_{t-1}(V) of (11) for the next frame: whether the draw wrote a pixel
 * (the query's count, long there when the next frame reads it), not the
 * prediction it was drawn on; and only a draw that wrote a pixel pulls
 * visibility up. */
void cull_measured_drawn(frame_ctx *f, int32_t i, int measured, uint64_t written) {
  (void)measured;
  f->c->os[i].pv = written > 0 ? 1.0 : 0.0;
  if (written > 0) cull_pull_up_visibility(f, object_elem(i));
}

/* An object's visibility is what its draw writes (cull_measured_drawn);
 * a node's goes up the tree as without measured draws. */
void cull_draw_visible_measured(frame_ctx *f, elem e, unsigned mask) {
  if (!is_object(e)) cull_pull_up_visibility(f, e);
  cull_traverse_node(f, e, mask);
}
