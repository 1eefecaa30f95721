/* What the fuzz targets of model readers check of a model read: indices
 * in range, no attribute arrays without corner attributes, finite normals
 * and texture coordinates, a material for every face when there are any,
 * textures the model owns, and a normal at every corner of a face with
 * area (computing normals again adds nothing); abort() where one fails. */
#ifndef ZS_FUZZ_MODEL_CHECK_H
#define ZS_FUZZ_MODEL_CHECK_H

#include <stdlib.h>

#include "scene/model.h"

static inline void fuzz_check(int ok) {
  if (!ok) abort();
}

static inline int fuzz_all_finite(const float *v, int n) {
  for (int i = 0; i < n; i++)
    if (!(v[i] - v[i] == 0.0f)) return 0;
  return 1;
}

static inline void fuzz_check_model(zs_model *m) {
  const zs_mesh *mesh = &m->mesh;
  for (int32_t f = 0; f < mesh->nfaces; f++) {
    for (int32_t k = mesh->face_start[f]; k < mesh->face_start[f + 1]; k++) {
      fuzz_check(mesh->face_vert[k] >= 0 && mesh->face_vert[k] < mesh->nverts);
      fuzz_check(!mesh->corner_attr ||
                 (mesh->corner_attr[k] >= -1 && mesh->corner_attr[k] < mesh->nattrs));
    }
    fuzz_check(!mesh->face_material ||
               (mesh->face_material[f] >= 0 && mesh->face_material[f] < mesh->nmaterials));
  }
  if (!mesh->corner_attr)
    fuzz_check(mesh->nattrs == 0 && !mesh->normal && !mesh->color && !mesh->uv);
  fuzz_check(mesh->nfaces == 0 || (mesh->face_material != NULL) == (mesh->nmaterials > 0));
  for (int32_t a = 0; a < mesh->nattrs; a++) {
    fuzz_check(!mesh->normal || fuzz_all_finite(mesh->normal + 3 * (size_t)a, 3));
    fuzz_check(!mesh->uv || fuzz_all_finite(mesh->uv + 2 * (size_t)a, 2));
  }
  for (int32_t i = 0; i < mesh->nmaterials; i++) {
    const zs_texture *t = mesh->materials[i].base_texture;
    int owned = t == NULL;
    for (int32_t j = 0; j < m->ntextures; j++) owned |= m->textures[j] == t;
    fuzz_check(owned);
  }
  if (mesh->corner_attr) {
    int32_t n = mesh->nattrs;
    fuzz_check(zs_model_compute_normals(m, 60.0));
    fuzz_check(m->mesh.nattrs == n);
  }
}

#endif
