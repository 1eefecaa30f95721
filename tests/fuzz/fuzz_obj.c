/* libFuzzer target: the OBJ reader on arbitrary bytes.  Any input must give
 * ZS_OK with a sane model, or an error with a one-line message; never a
 * crash, a leak or undefined behaviour. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "scene/load_obj.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  if (zs_obj_parse((const char *)data, size, "fuzz.obj", NULL, &m, &err) == ZS_OK) {
    for (int32_t f = 0; f < m.mesh.nfaces; f++)
      for (int32_t k = m.mesh.face_start[f]; k < m.mesh.face_start[f + 1]; k++)
        if (m.mesh.face_vert[k] < 0 || m.mesh.face_vert[k] >= m.mesh.nverts) abort();
    zs_model_free(&m);
  } else if (strchr(err.msg, '\n') || err.msg[0] == '\0') {
    abort();
  }
  return 0;
}
