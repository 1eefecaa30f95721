/* zscan's lines and points against llvmpipe's (crosscheck_prims.h). */
#include "tools/crosscheck_prims.h"

#include <stdlib.h>

#include "raster/raster.h"
#include "scene/model.h"
#include "lib/scene_draw.h"
#include "scene/scene.h"
#include "tools/mesa.h"
#include "util/rng.h"

typedef struct ids_out {
  uint32_t *ids;
} ids_out;

static void keep_ids(void *user, const zs_row *row) {
  ids_out *o = user;
  for (int x = 0; x < row->width; x++) {
    const uint32_t id = row->id[x];
    o->ids[(size_t)row->y * (size_t)row->width + (size_t)x] = id == ZS_ID_NONE ? 0 : id + 1;
  }
}

/* The scene: vertices in window pixels (y up, as GL's window), z the
 * primitive's own depth. */
static zs_status make_scene(int w, int h, uint64_t seed, int nlines, int npoints, zs_scene *s,
                            zs_error *err) {
  zs_rng rng;
  zs_rng_seed(&rng, seed);
  zs_model m;
  zs_model_init(&m);
  zs_status st = ZS_OK;
  const int n = nlines + npoints;
  for (int k = 0; k < n && st == ZS_OK; k++) {
    const double z = -1.0 - (double)k; /* one unit apart: depths never tie */
    const int ends = k < nlines ? 2 : 1;
    int32_t v[2];
    for (int e = 0; e < ends; e++) {
      v[e] = zs_model_add_vertex(&m, zs_rng_range(&rng, 0.0, w), zs_rng_range(&rng, 0.0, h), z);
      if (v[e] < 0) st = ZS_ERR_NOMEM;
    }
    if (st == ZS_OK)
      st = k < nlines ? zs_model_add_line(&m, v[0], v[1], 0) : zs_model_add_point(&m, v[0], 0);
  }
  zs_scene_init(s);
  if (st == ZS_OK && zs_scene_add_mesh(s, &m) < 0) st = ZS_ERR_NOMEM;
  if (st == ZS_OK && zs_scene_add_instance(s, 0, NULL, ZS_RGB_MESH, "prims") < 0) st = ZS_ERR_NOMEM;
  zs_model_free(&m);
  if (st != ZS_OK) return zs_error_set(err, st, "crosscheck lines: out of memory");
  return zs_scene_finish(s, err);
}

/* Whether pixel (x, y) (image rows) lies within reach of an end of
 * primitive id - 1 (a line's, or the point). */
static int near_end(const zs_mesh *m, uint32_t id, int x, int y, int h, double reach) {
  if (id == 0) return 0;
  const int32_t k = (int32_t)id - 1 - m->prim_id;
  const int ends = k < m->nlines ? 2 : 1;
  for (int e = 0; e < ends; e++) {
    const int32_t v = k < m->nlines ? m->line_vert[2 * k + e] : m->point_vert[k - m->nlines];
    const double ex = m->pos[3 * v] - (x + 0.5), ey = (h - m->pos[3 * v + 1]) - (y + 0.5);
    if (ex <= reach && ex >= -reach && ey <= reach && ey >= -reach) return 1;
  }
  return 0;
}

/* Whether line id - 1 of width passes within ZS_CROSSCHECK_EDGE pixels
 * of the centre of pixel (x, y) at one side of its band (the exact line,
 * across its major axis), where the snapped ends decide. */
static int on_edge(const zs_mesh *m, uint32_t id, int x, int y, int h, double width) {
  if (id == 0) return 0;
  const int32_t k = (int32_t)id - 1 - m->prim_id;
  if (k >= m->nlines) return 0;
  const double *p = &m->pos[3 * m->line_vert[2 * k]], *q = &m->pos[3 * m->line_vert[2 * k + 1]];
  const double px = p[0], py = h - p[1], qx = q[0], qy = h - q[1];
  const int major_x = (qx - px) * (qx - px) >= (qy - py) * (qy - py);
  const double c = major_x ? x + 0.5 : y + 0.5, mc = major_x ? y + 0.5 : x + 0.5;
  const double a0 = major_x ? px : py, a1 = major_x ? qx : qy;
  const double m0 = major_x ? py : px, m1 = major_x ? qy : qx;
  const double at = m0 + (m1 - m0) * (c - a0) / (a1 - a0);
  const double w = width < 1.0 ? 1.0 : (double)(int)(width + 0.5);
  const double lo = mc - (at - w / 2), hi = mc - (at + w / 2);
  return (lo < 0 ? -lo : lo) < ZS_CROSSCHECK_EDGE || (hi < 0 ? -hi : hi) < ZS_CROSSCHECK_EDGE;
}

zs_status zs_crosscheck_prims(int w, int h, uint64_t seed, int nlines, int npoints, double width,
                              double size, zs_prim_check *out, zs_error *err) {
  *out = (zs_prim_check){0, 0, 0, 0};
  zs_scene s;
  zs_status st = make_scene(w, h, seed, nlines, npoints, &s, err);
  if (st != ZS_OK) return st;
  double view[16], proj[16];
  zs_mat_identity(view);
  zs_mat_ortho(proj, 0.0, w, 0.0, h, 0.0, nlines + npoints + 2.0);
  uint32_t *mine = malloc((size_t)w * (size_t)h * sizeof *mine);
  uint32_t *gl = malloc((size_t)w * (size_t)h * sizeof *gl);
  zs_device *dev = NULL;
  zs_mesa *mesa = NULL;
  const zs_device_config cfg = {.width = w, .height = h, .shade = ZS_SHADE_ID, .threads = 1};
  if (!mine || !gl) st = zs_error_set(err, ZS_ERR_NOMEM, "crosscheck lines: out of memory");
  if (st == ZS_OK) st = zs_device_create(&cfg, &dev, err);
  if (st == ZS_OK) {
    ids_out o = {mine};
    zs_device_clear(dev);
    zs_device_set_camera(dev, view, proj);
    st = zs_frame_draw_prims(dev, &s, width, size, ZS_POINT_SQUARE, err);
    if (st == ZS_OK) st = zs_device_finish(dev, keep_ids, &o, err);
  }
  if (st == ZS_OK) st = zs_mesa_create(w, h, &mesa, err);
  if (st == ZS_OK) st = zs_mesa_prim_ids(mesa, &s, view, proj, width, size, gl, err);
  const zs_mesh *m = &s.meshes[0].mesh;
  const double reach = (width > size ? width : size) / 2.0 + 1.0;
  for (int y = 0; st == ZS_OK && y < h; y++)
    for (int x = 0; x < w; x++) {
      const size_t i = (size_t)y * (size_t)w + (size_t)x;
      out->covered += mine[i] != 0;
      if (mine[i] == gl[i]) continue;
      out->differ++;
      if (near_end(m, mine[i], x, y, h, reach) || near_end(m, gl[i], x, y, h, reach))
        out->at_ends++;
      else if (on_edge(m, mine[i], x, y, h, width) || on_edge(m, gl[i], x, y, h, width))
        out->rounding++;
    }
  zs_mesa_destroy(mesa);
  zs_device_destroy(dev);
  free(mine);
  free(gl);
  zs_scene_free(&s);
  return st;
}
