/* libFuzzer target: the OBJ reader on arbitrary bytes.  Any input must give
 * ZS_OK with a sane model, or an error with a one-line message; never a
 * crash, a leak or undefined behaviour.
 *
 * An input with a line "#mtl" is two files: the OBJ before that line and a
 * material library after it, written as fuzz.mtl into a folder of this
 * process's own that also holds a 2 x 2 PNG, t.png, and the OBJ is read
 * with that folder as its directory: "mtllib fuzz.mtl" and "map_Kd t.png"
 * then reach the library reader and the texture loader.  Without the line
 * nothing is read from disk.  (The seeds: tests/data/obj holds such files.)
 *
 * A model read must be sane (fuzz_model_check.h). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/load_obj.h"
#include "tests/fuzz/fuzz_dir.h"
#include "tests/fuzz/fuzz_model_check.h"

/* A 2 x 2 RGBA PNG. */
static const uint8_t tiny_png[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
    0x52, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x02, 0x08, 0x06, 0x00, 0x00, 0x00, 0x72,
    0xb6, 0x0d, 0x24, 0x00, 0x00, 0x00, 0x12, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0x63, 0xf8,
    0xcf, 0xc0, 0xf0, 0x1f, 0x08, 0x1b, 0x18, 0x60, 0x0c, 0x00, 0x40, 0x57, 0x06, 0xfb, 0x56,
    0x7c, 0xc5, 0xa6, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

static const char *obj_dir(void) {
  static const char *const files[] = {"t.png", "fuzz.mtl", NULL};
  const int fresh = !fuzz_dir_path[0];
  const char *dir = fuzz_dir("obj", files);
  if (fresh) {
    char png[300];
    snprintf(png, sizeof png, "%s/t.png", dir);
    if (!fuzz_write(png, tiny_png, sizeof tiny_png)) abort();
  }
  return dir;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const char *text = (const char *)data, *dir = NULL;
  size_t len = size;
  static const char mark[] = "#mtl\n";
  for (size_t i = 0; i + sizeof mark - 1 <= size; i++) {
    if ((i == 0 || text[i - 1] == '\n') && memcmp(text + i, mark, sizeof mark - 1) == 0) {
      char path[300];
      dir = obj_dir();
      snprintf(path, sizeof path, "%s/fuzz.mtl", dir);
      if (!fuzz_write(path, text + i + sizeof mark - 1, size - i - (sizeof mark - 1))) abort();
      len = i;
      break;
    }
  }
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  if (zs_obj_parse(text, len, "fuzz.obj", dir, &m, &err) == ZS_OK) {
    fuzz_check_model(&m);
    zs_model_free(&m);
  } else if (strchr(err.msg, '\n') || err.msg[0] == '\0') {
    abort();
  }
  return 0;
}
