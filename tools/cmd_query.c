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
 * gives the totals.  With --samples N both count samples, N a pixel: the
 * frame drawn once at each of the standard positions (lib/samples.h). */
#include "tools/commands.h"

#include <cjson/cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "raster/raster.h"
#include "scene/scene.h"
#include "lib/samples.h"
#include "tools/cli.h"
#include "lib/input.h"
#include "lib/object_visibility.h"
#include "tools/viewopts.h"

static const char usage[] =
    "usage: zscan query INPUT [options]\n"
    "  --format text|json  one line per object and a total (default text), or one\n"
    "                      JSON object: {\"objects\": [{\"name\", \"visible\",\n"
    "                      \"bbox\"}, ...], \"total\": {...}}\n"
    "  --samples N         count samples, N a pixel (1, 2, 4, 8 or 16, at the\n"
    "                      positions zscan render --samples draws), as GL's\n"
    "                      sample-counting queries do (default 1: pixels)\n";

/* The objects as one JSON object (names escaped by cJSON). */
static zs_status print_json(const char *input, const zs_object_visibility *lines, int32_t n,
                            uint64_t tv, uint64_t tb, int w, int h, int samples, zs_error *err) {
  cJSON *root = cJSON_CreateObject();
  cJSON_AddStringToObject(root, "input", input);
  cJSON_AddNumberToObject(root, "width", w);
  cJSON_AddNumberToObject(root, "height", h);
  cJSON *objects = cJSON_AddArrayToObject(root, "objects");
  for (int32_t k = 0; k < n && objects; k++) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "name", lines[k].name);
    cJSON_AddNumberToObject(o, "visible", (double)lines[k].visible);
    cJSON_AddNumberToObject(o, "bbox", (double)lines[k].box_samples);
    cJSON_AddItemToArray(objects, o);
  }
  cJSON *total = cJSON_AddObjectToObject(root, "total");
  if (total) {
    cJSON_AddNumberToObject(total, "objects", n);
    cJSON_AddNumberToObject(total, "visible", (double)tv);
    cJSON_AddNumberToObject(total, "bbox", (double)tb);
    cJSON_AddNumberToObject(total, "pixels", (double)w * h);
    if (samples > 1) cJSON_AddNumberToObject(total, "samples_per_pixel", samples);
  }
  char *text = cJSON_PrintUnformatted(root);
  cJSON_Delete(root);
  if (!text) return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  puts(text);
  cJSON_free(text);
  return ZS_OK;
}

static zs_status run(const char *input, int json, int samples, const zs_view_opts *v,
                     zs_error *err) {
  zs_scene s;
  if (zs_input_load_scene(input, &s, err)) return err->code;
  zs_view_opts eff = *v; /* the scene's camera and size where v says nothing */
  zs_view_opts_for_scene(v, &s, &eff.cam, &eff.width, &eff.height);
  zs_object_visibility *lines;
  int32_t n;
  zs_status st = zs_query_objects_at(&s, &eff.cam, eff.width, eff.height, eff.cull_back, samples,
                                     ZS_SHADE_AUTO, &lines, &n, err); /* as render draws it */
  if (st == ZS_OK) {
    uint64_t tv = 0, tb = 0;
    for (int32_t k = 0; k < n; k++) {
      if (!json)
        printf("object %s visible=%llu bbox=%llu\n", lines[k].name,
               (unsigned long long)lines[k].visible, (unsigned long long)lines[k].box_samples);
      tv += lines[k].visible;
      tb += lines[k].box_samples;
    }
    if (json)
      st = print_json(input, lines, n, tv, tb, eff.width, eff.height, samples, err);
    else if (samples > 1)
      printf("total objects=%d visible=%llu bbox=%llu pixels=%llu samples=%d\n", (int)n,
             (unsigned long long)tv, (unsigned long long)tb,
             (unsigned long long)((uint64_t)eff.width * (uint64_t)eff.height), samples);
    else
      printf("total objects=%d visible=%llu bbox=%llu pixels=%llu\n", (int)n,
             (unsigned long long)tv, (unsigned long long)tb,
             (unsigned long long)((uint64_t)eff.width * (uint64_t)eff.height));
    free(lines);
  }
  zs_scene_free(&s);
  return st;
}

int zs_cmd_query(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, zs_view_opts_usage, NULL)) return 0;
  const char *input = NULL;
  int json = 0, samples = 1;
  zs_view_opts v;
  zs_view_opts_default(&v, 1024, 768);
  zs_error err;
  zs_error_clear(&err);
  int parsing = 1; /* a usage error exits 2 (tools/cli.h) */
  for (int i = 1; i < argc; i++) {
    int taken = zs_view_opts_parse(&v, argc, argv, &i, &err);
    if (taken < 0) goto fail;
    if (taken) continue;
    if (strcmp(argv[i], "--format") == 0) {
      const char *f;
      if (zs_cli_value(argc, argv, &i, &f, &err)) goto fail;
      if (strcmp(f, "text") != 0 && strcmp(f, "json") != 0) {
        zs_error_set(&err, ZS_ERR_ARG, "--format: expected text or json, got '%s'", f);
        goto fail;
      }
      json = f[0] == 'j';
      continue;
    }
    if (strcmp(argv[i], "--samples") == 0) {
      if (zs_cli_int_value(argc, argv, &i, 1, 16, &samples, &err)) goto fail;
      if (!zs_samples_valid(samples)) {
        zs_error_set(&err, ZS_ERR_ARG, "--samples: expected 1, 2, 4, 8 or 16, got %d", samples);
        goto fail;
      }
      continue;
    }
    if (zs_cli_operand(argv[i], "zscan query", "INPUT", &input, &err)) goto fail;
  }
  if (!input) {
    zs_error_set(&err, ZS_ERR_ARG, "missing INPUT (see zscan query --help)");
    goto fail;
  }
  parsing = 0;
  if (run(input, json, samples, &v, &err)) goto fail;
  return 0;
fail:
  return zs_cli_fail("zscan query", &err, parsing);
}
