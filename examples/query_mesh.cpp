// query_mesh: a mesh built in memory, drawn by a zscan device, and an
// occlusion query on a box behind it and on a box beside it: how many of
// each box's pixels would be seen.
#include <cstdio>
#include <vector>

#include <zscan/zscan.h>

int main() {
  // A square wall at z = 0, two units wide, facing the eye (counter-clockwise).
  std::vector<double> pos = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  std::vector<int32_t> start = {0, 4}, verts = {0, 1, 2, 3};
  zs_mesh wall = {};
  wall.pos = pos.data();
  wall.nverts = 4;
  wall.face_start = start.data();
  wall.face_vert = verts.data();
  wall.nfaces = 1;

  zs_error err = {};
  zs_device_config cfg = {};  // 0 everywhere: 1024x768, zbuffer, flat, one thread
  cfg.width = 320;
  cfg.height = 240;
  zs_device *dev = nullptr;
  if (zs_device_create(&cfg, &dev, &err) != ZS_OK) {
    std::fprintf(stderr, "query_mesh: %s\n", err.msg);
    return 1;
  }
  double view[16], proj[16];
  const double eye[3] = {0, 0, 5}, target[3] = {0, 0, 0}, up[3] = {0, 1, 0};
  zs_mat_look_at(view, eye, target, up);
  zs_mat_perspective(proj, 45.0, 320.0 / 240.0, 0.5, 50.0);
  zs_device_set_camera(dev, view, proj);
  zs_device_clear(dev);
  zs_status st = zs_device_draw(dev, &wall, nullptr, 0, 0xC0C0C0, &err);

  // One box hidden behind the wall, one beside it in plain view.
  const double hidden_lo[3] = {-0.3, -0.3, -2.0}, hidden_hi[3] = {0.3, 0.3, -1.4};
  const double seen_lo[3] = {1.3, -0.3, -0.3}, seen_hi[3] = {1.9, 0.3, 0.3};
  zs_query q[2];
  const double *lo[2] = {hidden_lo, seen_lo}, *hi[2] = {hidden_hi, seen_hi};
  for (int i = 0; i < 2 && st == ZS_OK; i++) {
    st = zs_device_query_begin(dev, &q[i], &err);
    if (st == ZS_OK) st = zs_device_query_box(dev, lo[i], hi[i], &err);
    if (st == ZS_OK) st = zs_device_query_end(dev, &err);
  }
  if (st == ZS_OK) st = zs_device_finish(dev, nullptr, nullptr, &err);
  if (st != ZS_OK) {
    std::fprintf(stderr, "query_mesh: %s\n", err.msg);
    zs_device_destroy(dev);
    return 1;
  }
  std::printf("wall: %llu pixels written\n",
              (unsigned long long)zs_device_stats(dev)->pixels_written);
  std::printf("box behind the wall: %llu samples\n",
              (unsigned long long)zs_device_query_result(dev, q[0]));
  std::printf("box beside the wall: %llu samples\n",
              (unsigned long long)zs_device_query_result(dev, q[1]));
  zs_device_destroy(dev);
  return 0;
}
