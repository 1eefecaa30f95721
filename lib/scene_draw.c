/* A scene's instances drawn on a device (lib/scene_draw.h). */
#include "lib/scene_draw.h"

zs_status zs_frame_draw_scene(zs_device *dev, const zs_scene *scene, zs_error *err) {
  return zs_frame_draw_some(dev, scene, NULL, err);
}

zs_status zs_frame_draw_some(zs_device *dev, const zs_scene *scene, const uint8_t *drawn,
                             zs_error *err) {
  /* the instances, nothing read between the draws: on two threads they
   * are queued and rendered together (raster.h, deferred drawing) */
  zs_device_defer_draws(dev, 1);
  zs_status st = ZS_OK;
  for (int32_t i = 0; i < scene->ninst && st == ZS_OK; i++) {
    const zs_instance *in = &scene->inst[i];
    if (drawn && !drawn[i]) continue;
    st = zs_device_draw(dev, &scene->meshes[in->mesh].mesh, in->model, in->id_base, in->rgb, err);
  }
  if (st == ZS_OK) st = zs_device_flush(dev, err);
  zs_device_defer_draws(dev, 0);
  return st;
}

int zs_scene_has_prims(const zs_scene *scene) {
  for (int32_t i = 0; i < scene->ninst; i++) {
    const zs_mesh *m = &scene->meshes[scene->inst[i].mesh].mesh;
    if (m->nlines > 0 || m->npoints > 0) return 1;
  }
  return 0;
}

zs_status zs_frame_draw_prims(zs_device *dev, const zs_scene *scene, double line_width,
                              double point_size, zs_point_shape shape, zs_error *err) {
  zs_status st = ZS_OK;
  if (line_width == 0.0) line_width = 1.0; /* 0: the default, as zs_render_opts says */
  if (point_size == 0.0) point_size = 1.0;
  for (int32_t i = 0; i < scene->ninst && st == ZS_OK; i++) {
    const zs_instance *in = &scene->inst[i];
    const zs_mesh *m = &scene->meshes[in->mesh].mesh;
    if (m->nlines > 0)
      st = zs_device_draw_lines(dev, m, in->model, in->id_base, in->rgb, line_width, err);
    if (st == ZS_OK && m->npoints > 0)
      st = zs_device_draw_points(dev, m, in->model, in->id_base, in->rgb, point_size, shape, err);
  }
  return st;
}

zs_status zs_frame_draw_all(zs_device *dev, const zs_scene *scene, const double view[16],
                            const double proj[16], zs_error *err) {
  zs_device_clear(dev);
  zs_device_set_camera(dev, view, proj);
  return zs_frame_draw_scene(dev, scene, err);
}

