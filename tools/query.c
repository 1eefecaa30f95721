/* `zscan query INPUT [view options]`: renders the frame (zbuffer mode),
 * then prints one line per object, in order of its first face,
 *   object NAME visible=N bbox=M
 * N: the pixels of the final image that show one of the object's faces;
 * M: the samples of the object's axis-aligned world box that pass the
 * less-or-equal test against the final depth buffer (raster.h: the box's
 * faces turned to the eye, so each pixel of its outline counts once, the
 * box brought ZS_QUERY_DEPTH_BIAS units nearer; a box that the near plane
 * cuts counts what lies beyond the plane).  Objects are the scene's
 * instances: an OBJ file's o/g groups (groups of one name are one object,
 * groups without faces none), or a scene file's instances.  A last line
 * gives the totals. */
#include "tools/commands.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "raster/raster.h"
#include "scene/scene.h"
#include "tools/cli.h"
#include "lib/frame.h"
#include "lib/input.h"
#include "tools/viewopts.h"

static const char usage[] = "usage: zscan query INPUT [options]\n";

typedef struct object_line {
  int32_t inst;
  uint32_t first_face;
  uint64_t visible, bbox;
} object_line;

static int by_first_face(const void *a, const void *b) {
  const object_line *x = a, *y = b;
  if (x->first_face != y->first_face) return x->first_face < y->first_face ? -1 : 1;
  return (x->inst > y->inst) - (x->inst < y->inst);
}

static zs_status run(const char *input, const zs_view_opts *v, zs_error *err) {
  zs_scene s;
  if (zs_input_load_scene(input, &s, err)) return err->code;
  zs_status st = ZS_OK;
  zs_device *dev = NULL;
  object_line *lines = calloc((size_t)(s.ninst ? s.ninst : 1), sizeof *lines);
  int32_t *owner = NULL;
  double view[16], proj[16];
  if (!lines) st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  zs_view_opts eff = *v; /* the scene's camera and size where v says nothing */
  zs_view_opts_for_scene(v, &s, &eff.cam, &eff.width, &eff.height);
  v = &eff;
  if (st == ZS_OK) st = zs_frame_camera(&s, &v->cam, v->width, v->height, view, proj, err);
  zs_device_config cfg = {v->width, v->height, ZS_ALGO_ZBUFFER, ZS_SHADE_ID, v->cull_back, 1, 0};
  if (st == ZS_OK) st = zs_device_create(&cfg, &dev, err);
  if (st == ZS_OK) {
    zs_device_clear(dev);
    zs_device_set_camera(dev, view, proj);
    st = zs_frame_draw_scene(dev, &s, err);
  }
  if (st == ZS_OK) st = zs_device_finish(dev, NULL, NULL, err);
  /* the instance of every face id, and each instance's first face */
  uint32_t nids = 0;
  for (int32_t i = 0; st == ZS_OK && i < s.ninst; i++) {
    const zs_mesh *m = &s.meshes[s.inst[i].mesh].mesh;
    lines[i].inst = i;
    lines[i].first_face = UINT32_MAX;
    for (int32_t f = 0; f < m->nfaces; f++) {
      uint32_t id = s.inst[i].id_base + (uint32_t)m->face_id[f];
      if (id + 1 > nids) nids = id + 1;
      if (id < lines[i].first_face) lines[i].first_face = id;
    }
  }
  if (st == ZS_OK && !(owner = malloc((size_t)(nids ? nids : 1) * sizeof *owner)))
    st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  for (int32_t i = 0; st == ZS_OK && i < s.ninst; i++) {
    const zs_mesh *m = &s.meshes[s.inst[i].mesh].mesh;
    for (int32_t f = 0; f < m->nfaces; f++) owner[s.inst[i].id_base + (uint32_t)m->face_id[f]] = i;
  }
  if (st == ZS_OK) {
    const uint32_t *ids = zs_device_id_buffer(dev);
    for (size_t p = 0; p < (size_t)v->width * (size_t)v->height; p++)
      if (ids[p] < nids) lines[owner[ids[p]]].visible++;
  }
  for (int32_t i = 0; st == ZS_OK && i < s.ninst; i++) {
    zs_query q;
    if ((st = zs_device_query_begin(dev, &q, err)) ||
        (st = zs_device_query_box(dev, s.inst[i].lo, s.inst[i].hi, err)) ||
        (st = zs_device_query_end(dev, err)))
      break;
    lines[i].bbox = zs_device_query_result(dev, q);
  }
  if (st == ZS_OK) {
    qsort(lines, (size_t)s.ninst, sizeof *lines, by_first_face);
    uint64_t tv = 0, tb = 0;
    for (int32_t k = 0; k < s.ninst; k++) {
      printf("object %s visible=%llu bbox=%llu\n", s.inst[lines[k].inst].name,
             (unsigned long long)lines[k].visible, (unsigned long long)lines[k].bbox);
      tv += lines[k].visible;
      tb += lines[k].bbox;
    }
    printf("total objects=%d visible=%llu bbox=%llu pixels=%llu\n", (int)s.ninst,
           (unsigned long long)tv, (unsigned long long)tb,
           (unsigned long long)((uint64_t)v->width * (uint64_t)v->height));
  }
  free(lines);
  free(owner);
  zs_device_destroy(dev);
  zs_scene_free(&s);
  return st;
}

int zs_cmd_query(int argc, char **argv) {
  if (zs_cli_help_asked(argc, argv)) {
    fputs(usage, stdout);
    fputs(zs_view_opts_usage, stdout);
    return 0;
  }
  const char *input = NULL;
  zs_view_opts v;
  zs_view_opts_default(&v, 1024, 768);
  zs_error err;
  zs_error_clear(&err);
  for (int i = 1; i < argc; i++) {
    int taken = zs_view_opts_parse(&v, argc, argv, &i, &err);
    if (taken < 0) goto fail;
    if (taken) continue;
    if (argv[i][0] == '-' && argv[i][1]) {
      zs_error_set(&err, ZS_ERR_ARG, "unknown option '%s' (see zscan query --help)", argv[i]);
      goto fail;
    }
    if (input) {
      zs_error_set(&err, ZS_ERR_ARG, "more than one INPUT: '%s' and '%s'", input, argv[i]);
      goto fail;
    }
    input = argv[i];
  }
  if (!input) {
    zs_error_set(&err, ZS_ERR_ARG, "missing INPUT (see zscan query --help)");
    goto fail;
  }
  if (run(input, &v, &err)) goto fail;
  return 0;
fail:
  fprintf(stderr, "zscan query: %s\n", err.msg);
  return 1;
}
