/* libFuzzer target: the JSON scene-file reader on arbitrary bytes (mesh
 * files are looked up relative to a directory that does not exist). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "scene/load_scenefile.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  zs_scene s;
  zs_error err;
  zs_error_clear(&err);
  if (zs_scenefile_parse((const char *)data, size, "fuzz.json", "/nonexistent-fuzz-dir", &s, &err) ==
      ZS_OK)
    zs_scene_free(&s);
  else if (strchr(err.msg, '\n') || err.msg[0] == '\0')
    abort();
  return 0;
}
