/* Lines' and points' fragments kept for scanline mode's rows
 * (prim_rows.h). */
#include "raster/prim_rows.h"

#include <stdlib.h>
#include <string.h>

#include "util/grow.h"

void zs_prim_rows_keep(zs_prim_rows *p, uint32_t x, uint32_t y, uint32_t z, uint32_t id,
                       uint32_t rgb) {
  if (p->n >= p->cap) {
    void **const arrays[] = {(void **)&p->x, (void **)&p->y, (void **)&p->z, (void **)&p->id,
                             (void **)&p->rgb};
    const size_t sizes[] = {4, 4, 4, 4, 4};
    const int64_t cap = p->cap > 0 ? 2 * (int64_t)p->cap : 1024;
    if (cap > INT32_MAX || !zs_resize_each(arrays, sizes, 5, (size_t)cap)) {
      p->nomem = 1;
      return;
    }
    p->cap = (int32_t)cap;
  }
  const int32_t k = p->n++;
  p->x[k] = x, p->y[k] = y, p->z[k] = z, p->id[k] = id, p->rgb[k] = rgb;
}

int zs_prim_rows_sort(zs_prim_rows *p, int height) {
  if (!zs_grow((void **)&p->order, &p->cap_order, p->n > 0 ? p->n : 1, sizeof *p->order))
    return 0;
  int32_t *first = realloc(p->row_first, ((size_t)height + 1) * sizeof *first);
  if (!first) return 0;
  p->row_first = first;
  p->rows = height;
  /* a counting sort: stable, so each row keeps the order drawn */
  memset(first, 0, ((size_t)height + 1) * sizeof *first);
  for (int32_t k = 0; k < p->n; k++) first[p->y[k] + 1]++;
  for (int y = 0; y < height; y++) first[y + 1] += first[y];
  for (int32_t k = 0; k < p->n; k++) p->order[first[p->y[k]]++] = k;
  for (int y = height; y > 0; y--) first[y] = first[y - 1]; /* back to the starts */
  first[0] = 0;
  return 1;
}

uint64_t zs_prim_rows_apply(const zs_prim_rows *p, int y, uint32_t *depth, uint32_t *id,
                            uint32_t *rgb, uint32_t *count) {
  if (p->n == 0 || y < 0 || y >= p->rows) return 0;
  uint64_t written = 0;
  for (int32_t j = p->row_first[y]; j < p->row_first[y + 1]; j++) {
    const int32_t k = p->order[j];
    const uint32_t x = p->x[k], z = p->z[k], i = p->id[k];
    if (count) count[x]++;
    /* raster.h, DEPTH: in front, or as near with the lower id */
    if (z > depth[x] || (z == depth[x] && i >= id[x])) continue;
    depth[x] = z;
    id[x] = i;
    rgb[x] = p->rgb[k];
    written++;
  }
  return written;
}

void zs_prim_rows_clear(zs_prim_rows *p) {
  p->n = 0;
  p->nomem = 0;
}

void zs_prim_rows_free(zs_prim_rows *p) {
  free(p->x);
  free(p->y);
  free(p->z);
  free(p->id);
  free(p->rgb);
  free(p->row_first);
  free(p->order);
  memset(p, 0, sizeof *p);
}

size_t zs_prim_rows_bytes(const zs_prim_rows *p) {
  return 5 * 4 * (size_t)p->cap + (size_t)p->cap_order * sizeof *p->order +
         (p->row_first ? ((size_t)p->rows + 1) * sizeof *p->row_first : 0);
}
