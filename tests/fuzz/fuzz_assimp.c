/* libFuzzer target: the models read through assimp (scene/load_assimp.c:
 * its meshes, attributes, materials, samplers, embedded textures and node
 * transforms) on arbitrary bytes.  The first byte picks the format, by
 * the file's extension: PLY, glTF, OFF, STL, GLB or Collada; the rest is
 * the file, written into a folder of this process's own and read from
 * there, as zscan reads a model.  Any input must give a sane model
 * (fuzz_model_check.h) or an error with a one-line message; never a
 * crash, a leak or undefined behaviour in zscan's code.  (The seeds:
 * tools/fuzz.sh prefixes tests/data's models with their format's byte.)
 *
 * Not among CI's targets: assimp 5.2's own readers fail within a minute
 * of fuzzing (heap overflows in its glTF reader, a SEGV and allocations
 * of gigabytes in its PLY reader), which zscan cannot mend.  What it
 * found that zscan can refuse first is refused, each case in
 * tests/data/bad_models (a PLY header with a NUL byte, without
 * end_header, with a line outside the header's grammar; an empty face;
 * a NaN normal or colour).  ZS_FUZZ_ASSIMP=1 tools/fuzz.sh runs it.
 * Leaks inside assimp are suppressed (tests/fuzz/assimp.supp). */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "scene/load_assimp.h"
#include "tests/fuzz/fuzz_dir.h"
#include "tests/fuzz/fuzz_model_check.h"

static const char *const formats[] = {"ply", "gltf", "off", "stl", "glb", "dae"};
enum { NFORMATS = sizeof formats / sizeof formats[0] };

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size < 1 || !zs_assimp_available()) return 0;
  static const char *const files[] = {"fuzz.ply", "fuzz.gltf", "fuzz.off", "fuzz.stl",
                                      "fuzz.glb", "fuzz.dae", NULL};
  char path[300];
  snprintf(path, sizeof path, "%s/fuzz.%s", fuzz_dir("assimp", files),
           formats[data[0] % NFORMATS]);
  if (!fuzz_write(path, data + 1, size - 1)) abort();
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  if (zs_assimp_load(path, &m, &err) == ZS_OK) {
    fuzz_check_model(&m);
    zs_model_free(&m);
  } else if (strchr(err.msg, '\n') || err.msg[0] == '\0') {
    abort();
  }
  remove(path);
  return 0;
}
