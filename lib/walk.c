/* A scene's camera path walked with one culling method (zscan/walk.h),
 * and the frame step it shares with `zscan walk` (lib/walk.h). */
#include "lib/walk.h"

#include <stdlib.h>
#include <string.h>

#include "lib/frame_camera.h"

struct zs_walk {
  zs_scene *scene;
  zs_octree tree;
  int have_tree;
  zs_culler *culler;
  zs_device *dev;
  int width, height, step;
  int32_t frames, next; /* walk frames, and the next one to render */
};

int32_t zs_walk_step_count(const zs_scene *s, int step) {
  return s->path.frames > 0 ? (s->path.frames + step - 1) / step : 1;
}

zs_status zs_walk_step_scene(zs_scene *s, zs_octree *tree, int32_t k, int step, int width,
                             int height, double view[16], double proj[16], zs_error *err) {
  if (k > 0) {
    for (int i = 0; i < step; i++) zs_scene_advance(s);
    zs_status st = zs_octree_update(tree, s, NULL, err);
    if (st != ZS_OK) return st;
  }
  return zs_frame_path_camera(s, k * step, width, height, view, proj, err);
}

zs_status zs_walk_step_method(zs_culler *c, zs_device *dev, const zs_scene *s,
                              const zs_octree *tree, const double view[16],
                              const double proj[16], zs_cull_stats *cs, zs_row_sink sink,
                              void *user, zs_error *err) {
  zs_status st = zs_culler_frame(c, dev, s, tree, view, proj, cs, err);
  return st != ZS_OK ? st : zs_device_finish(dev, sink, user, err);
}

void zs_walk_destroy(zs_walk *w) {
  if (!w) return;
  if (w->have_tree) zs_octree_free(&w->tree);
  zs_culler_destroy(w->culler);
  zs_device_destroy(w->dev);
  free(w);
}

zs_status zs_walk_create(zs_scene *scene, const zs_walk_opts *opts, zs_walk **out,
                         zs_error *err) {
  static const zs_walk_opts none;
  const zs_walk_opts *o = opts ? opts : &none;
  *out = NULL;
  int method = zs_cull_method_parse(o->method ? o->method : "none");
  if (method < 0)
    return zs_error_set(err, ZS_ERR_ARG, "culling method '%s': expected one of %s", o->method,
                        ZS_CULL_METHOD_LIST);
  if (o->step < 0 || o->width < 0 || o->height < 0)
    return zs_error_set(err, ZS_ERR_ARG, "zs_walk_create: negative size or step");
  zs_walk *w = calloc(1, sizeof *w);
  if (!w) return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  w->scene = scene;
  zs_frame_size(scene, o->width, o->height, &w->width, &w->height);
  w->step = o->step ? o->step : 1;
  w->frames = zs_walk_step_count(scene, w->step);
  zs_octree_params tp;
  zs_octree_params_default(&tp, ZS_OCTREE_LOOSE);
  zs_cost_params cost;
  zs_cost_params_default(&cost);
  zs_device_config cfg = {w->width, w->height, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, 1, 0, 0, 0};
  zs_status st = zs_octree_build(&w->tree, scene, &tp, err);
  w->have_tree = st == ZS_OK;
  if (st == ZS_OK) st = zs_culler_create((zs_cull_method)method, &cost, &w->culler, err);
  if (st == ZS_OK) st = zs_device_create(&cfg, &w->dev, err);
  if (st != ZS_OK) {
    zs_walk_destroy(w);
    return st;
  }
  *out = w;
  return ZS_OK;
}

int32_t zs_walk_frames(const zs_walk *w) { return w->frames; }

zs_device *zs_walk_device(zs_walk *w) { return w->dev; }

zs_status zs_walk_next(zs_walk *w, zs_walk_frame *out, zs_error *err) {
  memset(out, 0, sizeof *out);
  double view[16], proj[16];
  zs_cull_stats cs;
  zs_status st = zs_walk_step_scene(w->scene, &w->tree, w->next, w->step, w->width, w->height,
                                    view, proj, err);
  if (st == ZS_OK)
    st = zs_walk_step_method(w->culler, w->dev, w->scene, &w->tree, view, proj, &cs, NULL, NULL,
                             err);
  if (st != ZS_OK) return st;
  int32_t f = w->next * w->step;
  w->next++;
  *out = (zs_walk_frame){f,
                         zs_device_frame_ps(w->dev) * 1e-9,
                         zs_device_clock(w->dev)->stall_ps * 1e-9,
                         cs.queries,
                         cs.queries_hidden,
                         cs.objects_drawn,
                         cs.faces_drawn,
                         cs.nodes_visited};
  return ZS_OK;
}
