/* The culler (cull.h): the table of methods, creating a culler with its
 * method's hooks and state (internal.h), and a frame's shared set-up
 * before the method draws it. */
#include <stdlib.h>
#include <string.h>

#include "cull/internal.h"

/* Every method, by zs_cull_method: its name and hooks, one row each; the
 * one place a method is looked up, by number or by name. */
static const cull_ops *const methods[ZS_CULL_METHODS] = {
    [ZS_CULL_NONE] = &cull_none,
    [ZS_CULL_VFC] = &cull_vfc,
    [ZS_CULL_VFC_BOX] = &cull_vfc_box,
    [ZS_CULL_HSW] = &cull_hsw,
    [ZS_CULL_CHC] = &cull_chc,
    [ZS_CULL_CHC_PROB] = &cull_chc_prob,
    [ZS_CULL_IDEAL] = &cull_ideal,
    [ZS_CULL_AUTO] = &cull_auto,
    [ZS_CULL_CHCPP] = &cull_chcpp,
    [ZS_CULL_CHCPP_NOBATCH] = &cull_chcpp_nobatch,
    [ZS_CULL_CHCPP_NODEFER] = &cull_chcpp_nodefer,
    [ZS_CULL_CHCPP_NOMULTI] = &cull_chcpp_nomulti,
    [ZS_CULL_CHCPP_PROB] = &cull_chcpp_prob,
    [ZS_CULL_NOHC] = &cull_nohc,
    [ZS_CULL_IDEAL_BOX] = &cull_ideal_box,
    [ZS_CULL_HZB] = &cull_hzb};

const char *zs_cull_method_name(zs_cull_method m) {
  return (unsigned)m < ZS_CULL_METHODS ? methods[m]->name : "?";
}

int zs_cull_method_parse(const char *name) {
  for (int i = 0; i < ZS_CULL_METHODS; i++)
    if (strcmp(name, methods[i]->name) == 0) return i;
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
  c->ops = methods[m];
  zs_rng_seed(&c->rng, 0xC4C); /* chcpp's first visible intervals: a fixed seed */
  if (cost) c->cost = *cost;
  else zs_cost_params_default(&c->cost);
  if (!(c->parts = zs_parts_create()) || (c->ops->create && !(c->own = c->ops->create()))) {
    zs_culler_destroy(c);
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
  if (c->own) c->ops->destroy(c->own);
  free(c->ns);
  free(c->os);
  free(c->heap);
  free(c->qq);
  free(c->decision);
  free(c->order);
  free(c->qlo);
  free(c->qhi);
  zs_parts_destroy(c->parts);
  free(c);
}

const uint8_t *zs_culler_decisions(const zs_culler *c, int32_t *n) {
  *n = c->ndecision;
  return c->decision;
}

zs_status zs_culler_frame(zs_culler *c, zs_device *dev, const zs_scene *s, const zs_octree *t,
                          const double view[16], const double proj[16], zs_cull_stats *st,
                          zs_error *err) {
  static const cull_hooks no_hooks;
  memset(st, 0, sizeof *st);
  c->frame++;
  frame_ctx f;
  memset(&f, 0, sizeof f);
  f.c = c;
  f.hooks = c->ops->hooks ? c->ops->hooks : &no_hooks;
  f.dev = dev;
  f.s = s;
  f.t = t;
  f.view = view;
  f.proj = proj;
  f.st = st;
  f.err = err;
  st->chosen = c->method;
  zs_device_clear(dev);
  zs_device_set_camera(dev, view, proj);
  zs_frustum_from_matrices(&f.frustum, view, proj);
  zs_mat_eye_of_view(view, f.eye);
  c->ops->frame(&f);
  return f.status;
}
