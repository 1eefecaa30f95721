/* A scene's instances drawn on a device (lib/scene_draw.h). */
#include "lib/scene_draw.h"

zs_status zs_frame_draw_scene(zs_device *dev, const zs_scene *scene, zs_error *err) {
  /* every instance, nothing read between the draws: on two threads they
   * are queued and rendered together (raster.h, deferred drawing) */
  zs_device_defer_draws(dev, 1);
  zs_status st = ZS_OK;
  for (int32_t i = 0; i < scene->ninst && st == ZS_OK; i++) {
    const zs_instance *in = &scene->inst[i];
    st = zs_device_draw(dev, &scene->meshes[in->mesh].mesh, in->model, in->id_base, in->rgb, err);
  }
  if (st == ZS_OK) st = zs_device_flush(dev, err);
  zs_device_defer_draws(dev, 0);
  return st;
}

zs_status zs_frame_draw_all(zs_device *dev, const zs_scene *scene, const double view[16],
                            const double proj[16], zs_error *err) {
  zs_device_clear(dev);
  zs_device_set_camera(dev, view, proj);
  return zs_frame_draw_scene(dev, scene, err);
}

