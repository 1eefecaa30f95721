/* zscan's unlit colours against llvmpipe's (crosscheck_colours.h). */
#include "tools/crosscheck_colours.h"

#include <stdlib.h>
#include <string.h>

#include "lib/frame.h"
#include "lib/frame_camera.h"
#include "lib/input.h"
#include "scene/scene.h"
#include "tools/mesa.h"

const zs_colour_case zs_colour_cases[] = {
    {"builtin:default", 1, ZS_FILTER_NEAREST, 0.999, 2},
    {"builtin:spheres?count=300", 1, ZS_FILTER_NEAREST, 0.999, 2},
    {"tests/data/models/rgb_quad.ply", 0, ZS_FILTER_NEAREST, 0.999, 2},
    {"scene/examples/checker/checker_plane.json", 0, ZS_FILTER_NEAREST, 0.995, 0},
    {"scene/examples/teapot_textured.json", 0, ZS_FILTER_NEAREST, 0.995, 0},
    {"/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf", 0, ZS_FILTER_NEAREST,
     0.995, 0},
    {"scene/examples/checker/checker_plane.json", 0, ZS_FILTER_BILINEAR, 0.95, 8},
    {"scene/examples/checker/checker_plane.json", 0, ZS_FILTER_TRILINEAR, 0.95, 8},
    {"scene/examples/teapot_textured.json", 0, ZS_FILTER_TRILINEAR, 0.95, 8},
};
const int zs_ncolour_cases = (int)(sizeof zs_colour_cases / sizeof zs_colour_cases[0]);

/* Every attribute vertex of every mesh (or, for a mesh without any, every
 * vertex) gets a colour from its number. */
static zs_status paint(zs_scene *s, zs_error *err) {
  for (int32_t i = 0; i < s->nmeshes; i++) {
    zs_mesh *m = &s->meshes[i].mesh;
    if (m->nattrs == 0 && !m->corner_attr) m->nattrs = m->nverts;
    free(m->color);
    if (!(m->color = malloc(4 * (size_t)(m->nattrs ? m->nattrs : 1))))
      return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
    for (int32_t a = 0; a < m->nattrs; a++) {
      const uint32_t h = (uint32_t)a * 2654435761u;
      m->color[4 * a] = (uint8_t)(h >> 24), m->color[4 * a + 1] = (uint8_t)(h >> 16);
      m->color[4 * a + 2] = (uint8_t)(h >> 8), m->color[4 * a + 3] = 255;
    }
    s->meshes[i].cap_attrs = m->nattrs;
  }
  return ZS_OK;
}

static void compare(const zs_colour_case *c, const uint32_t *ours, const uint32_t *ids,
                    const uint32_t *gl, size_t n, zs_colour_check *out) {
  *out = (zs_colour_check){0, 0, 0, 0};
  for (size_t i = 0; i < n; i++) {
    if (ids[i] == 0) continue; /* the background */
    out->covered++;
    int d = 0;
    for (int k = 0; k < 24; k += 8) {
      const int e = abs((int)(ours[i] >> k & 255) - (int)(gl[i] >> k & 255));
      if (e > d) d = e;
    }
    if (d > out->worst) out->worst = d;
    out->close += d <= c->max_diff;
    out->exact += d == 0;
  }
}

zs_status zs_crosscheck_colours(const zs_colour_case *c, const char *path, int w, int h,
                                zs_colour_check *out, zs_error *err) {
  if (!zs_mesa_available())
    return zs_error_set(err, ZS_ERR_UNSUPPORTED, "mesa: zscan was built without OSMesa");
  zs_scene s;
  zs_status st = zs_input_load_scene(path, &s, err);
  if (st) return st;
  double view[16], proj[16];
  uint32_t *gl = NULL;
  zs_mesa *mesa = NULL;
  zs_image ours = {0}, ids = {0};
  if (c->paint) st = paint(&s, err);
  if (!st) st = zs_frame_camera(&s, &s.camera, w, h, view, proj, err);
  if (!st && !(gl = malloc((size_t)w * (size_t)h * sizeof *gl)))
    st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  if (!st) st = zs_mesa_create(w, h, &mesa, err);
  if (!st) st = zs_mesa_unlit(mesa, &s, view, proj, c->filter, gl, err);
  zs_frame_opts o = {.width = w, .height = h, .algo = ZS_ALGO_ZBUFFER, .shade = ZS_SHADE_UNLIT,
                     .threads = 1, .filter = c->filter};
  if (!st) st = zs_frame_render(&s, &s.camera, &o, &ours, NULL, NULL, err);
  o.shade = ZS_SHADE_ID;
  if (!st) st = zs_frame_render(&s, &s.camera, &o, &ids, NULL, NULL, err);
  if (!st) compare(c, ours.rgb, ids.rgb, gl, (size_t)w * (size_t)h, out);
  if (mesa) zs_mesa_destroy(mesa);
  free(gl);
  zs_image_free(&ours);
  zs_image_free(&ids);
  zs_scene_free(&s);
  return st;
}
