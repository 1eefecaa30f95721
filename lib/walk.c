/* A scene's camera path walked with one culling method (zscan/walk.h):
 * the frame step of `zscan walk`, for one method. */
#include <stdlib.h>
#include <string.h>

#include "cull/cull.h"
#include "cull/octree.h"
#include "lib/frame_camera.h"
#include "zscan/walk.h"

struct zs_walk {
  zs_scene *scene;
  zs_octree tree;
  int have_tree;
  zs_culler *culler;
  zs_device *dev;
  int width, height, step;
  int32_t frames, next; /* walk frames, and the next one to render */
};

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
  w->frames = scene->path.frames > 0 ? (scene->path.frames + w->step - 1) / w->step : 1;
  zs_octree_params tp;
  zs_octree_params_default(&tp, ZS_OCTREE_LOOSE);
  zs_cost_params cost;
  zs_cost_params_default(&cost);
  zs_device_config cfg = {w->width, w->height, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, 0, 1, 0, 0};
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
  if (w->next > 0) {
    for (int k = 0; k < w->step; k++) zs_scene_advance(w->scene);
    zs_status st = zs_octree_update(&w->tree, w->scene, NULL, err);
    if (st != ZS_OK) return st;
  }
  int32_t f = w->next * w->step;
  double view[16], proj[16];
  zs_cull_stats cs;
  zs_status st = zs_frame_path_camera(w->scene, f, w->width, w->height, view, proj, err);
  if (st == ZS_OK)
    st = zs_culler_frame(w->culler, w->dev, w->scene, &w->tree, view, proj, &cs, err);
  if (st == ZS_OK) st = zs_device_finish(w->dev, NULL, NULL, err);
  if (st != ZS_OK) return st;
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
