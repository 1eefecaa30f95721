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
 * A model read must be sane: indices in range, no attribute arrays without
 * corner attributes, finite normals and texture coordinates, a material
 * for every face when there are any, textures the model owns, and a normal
 * at every corner of a face with area (computing normals again adds
 * nothing). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/load_obj.h"

/* A 2 x 2 RGBA PNG. */
static const uint8_t tiny_png[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
    0x52, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x02, 0x08, 0x06, 0x00, 0x00, 0x00, 0x72,
    0xb6, 0x0d, 0x24, 0x00, 0x00, 0x00, 0x12, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0x63, 0xf8,
    0xcf, 0xc0, 0xf0, 0x1f, 0x08, 0x1b, 0x18, 0x60, 0x0c, 0x00, 0x40, 0x57, 0x06, 0xfb, 0x56,
    0x7c, 0xc5, 0xa6, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

static int write_bytes(const char *path, const void *data, size_t n) {
  FILE *f = fopen(path, "wb");
  if (!f) return 0;
  int ok = fwrite(data, 1, n, f) == n;
  return fclose(f) == 0 && ok;
}

static char dir[256]; /* this process's folder, made at the first need */

static void remove_dir(void) {
  static const char *const files[] = {"t.png", "fuzz.mtl"};
  for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
    char path[300];
    snprintf(path, sizeof path, "%s/%s", dir, files[i]);
    remove(path);
  }
  remove(dir);
}

static const char *fuzz_dir(void) {
  if (dir[0]) return dir;
  const char *tmp = getenv("TMPDIR");
  snprintf(dir, sizeof dir, "%s/zscan-fuzz-obj-XXXXXX", tmp && *tmp ? tmp : "/tmp");
  if (!mkdtemp(dir)) abort();
  atexit(remove_dir);
  char png[300];
  snprintf(png, sizeof png, "%s/t.png", dir);
  if (!write_bytes(png, tiny_png, sizeof tiny_png)) abort();
  return dir;
}

static void check(int ok) {
  if (!ok) abort();
}

static int all_finite(const float *v, int n) {
  for (int i = 0; i < n; i++)
    if (!(v[i] - v[i] == 0.0f)) return 0;
  return 1;
}

static void check_model(zs_model *m) {
  const zs_mesh *mesh = &m->mesh;
  for (int32_t f = 0; f < mesh->nfaces; f++) {
    for (int32_t k = mesh->face_start[f]; k < mesh->face_start[f + 1]; k++) {
      check(mesh->face_vert[k] >= 0 && mesh->face_vert[k] < mesh->nverts);
      check(!mesh->corner_attr ||
            (mesh->corner_attr[k] >= -1 && mesh->corner_attr[k] < mesh->nattrs));
    }
    check(!mesh->face_material ||
          (mesh->face_material[f] >= 0 && mesh->face_material[f] < mesh->nmaterials));
  }
  if (!mesh->corner_attr) check(mesh->nattrs == 0 && !mesh->normal && !mesh->color && !mesh->uv);
  check(mesh->nfaces == 0 || (mesh->face_material != NULL) == (mesh->nmaterials > 0));
  for (int32_t a = 0; a < mesh->nattrs; a++) {
    check(!mesh->normal || all_finite(mesh->normal + 3 * (size_t)a, 3));
    check(!mesh->uv || all_finite(mesh->uv + 2 * (size_t)a, 2));
  }
  for (int32_t i = 0; i < mesh->nmaterials; i++) {
    const zs_texture *t = mesh->materials[i].base_texture;
    int owned = t == NULL;
    for (int32_t j = 0; j < m->ntextures; j++) owned |= m->textures[j] == t;
    check(owned);
  }
  if (mesh->corner_attr) {
    int32_t n = mesh->nattrs;
    check(zs_model_compute_normals(m, 60.0));
    check(m->mesh.nattrs == n);
  }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const char *text = (const char *)data, *dir = NULL;
  size_t len = size;
  static const char mark[] = "#mtl\n";
  for (size_t i = 0; i + sizeof mark - 1 <= size; i++) {
    if ((i == 0 || text[i - 1] == '\n') && memcmp(text + i, mark, sizeof mark - 1) == 0) {
      char path[300];
      dir = fuzz_dir();
      snprintf(path, sizeof path, "%s/fuzz.mtl", dir);
      if (!write_bytes(path, text + i + sizeof mark - 1, size - i - (sizeof mark - 1))) abort();
      len = i;
      break;
    }
  }
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  if (zs_obj_parse(text, len, "fuzz.obj", dir, &m, &err) == ZS_OK) {
    check_model(&m);
    zs_model_free(&m);
  } else if (strchr(err.msg, '\n') || err.msg[0] == '\0') {
    abort();
  }
  return 0;
}
