/* `zscan path SCENE [--frames N] [--named NAME] [--size WxH]`: prints one
 * line per frame, "frame F eye x,y,z target x,y,z up x,y,z", the cameras
 * a walk of SCENE uses (its path, completed from its bounds as every
 * command completes it), or those of a named path (static, translate,
 * roll, yaw, fast) from the scene's camera. */
#include "tools/commands.h"

#include <stdio.h>
#include <string.h>

#include "scene/paths.h"
#include "scene/scene.h"
#include "lib/frame_camera.h"
#include "tools/cli.h"
#include "lib/input.h"

static const char usage[] =
    "usage: zscan path SCENE [--frames N] [--named static|translate|roll|yaw|fast] [--size WxH]\n";

int zs_cmd_path(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, NULL)) return 0;
  const char *spec = NULL, *named = NULL;
  int frames = 0, w = 0, h = 0;
  zs_error err;
  zs_error_clear(&err);
  int parsing = 1; /* a usage error exits 2 (tools/cli.h) */
  zs_scene s;
  int loaded = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (strcmp(a, "--frames") == 0) {
      if (zs_cli_int_value(argc, argv, &i, 1, 1000000, &frames, &err)) goto fail;
    } else if (strcmp(a, "--named") == 0) {
      if (zs_cli_value(argc, argv, &i, &named, &err)) goto fail;
    } else if (strcmp(a, "--size") == 0) {
      if (zs_cli_size_value(argc, argv, &i, 16384, &w, &h, &err)) goto fail;
    } else if (zs_cli_operand(a, "zscan path", "SCENE", &spec, &err)) {
      goto fail;
    }
  }
  if (!spec) {
    zs_error_set(&err, ZS_ERR_ARG, "missing SCENE (see zscan path --help)");
    goto fail;
  }
  parsing = 0;
  if (zs_input_load_scene(spec, &s, &err)) goto fail;
  loaded = 1;
  if (!w) zs_frame_size(&s, 0, 0, &w, &h);
  if (named && zs_frame_named_path(&s, named, frames ? frames : 100, w, h, &err)) goto fail;
  int n = frames ? frames : s.path.nkeys > 0 ? s.path.frames : 1;
  for (int f = 0; f < n; f++) {
    zs_camera key = s.camera, cam;
    if (s.path.nkeys > 0) zs_path_camera(&s, f, &key);
    zs_frame_complete_camera(&s, &key, w, h, &cam);
    char line[512];
    zs_path_format(line, sizeof line, f, &cam);
    fputs(line, stdout); /* the line ends in its newline */
  }
  zs_scene_free(&s);
  return 0;
fail:
  if (loaded) zs_scene_free(&s);
  return zs_cli_fail("zscan path", &err, parsing);
}
