/* The batch (batch.h): growing, joining and copying the polygons and
 * edges set-up writes. */
#include <stdlib.h>
#include <string.h>

#include "raster/batch.h"
#include "util/grow.h"

void zs_batch_reset(zs_batch *b) {
  b->npolys = 0;
  b->nedges = 0;
}

void zs_batch_free(zs_batch *b) {
  free(b->polys);
  free(b->edges);
  *b = (zs_batch){0};
}

int zs_batch_reserve(zs_batch *b, int32_t polys, int32_t edges) {
  return zs_grow((void **)&b->polys, &b->cap_polys, (int64_t)b->npolys + polys, sizeof *b->polys) &&
         zs_grow((void **)&b->edges, &b->cap_edges, (int64_t)b->nedges + edges, sizeof *b->edges);
}

void zs_batch_rows(const zs_batch *b, int32_t first, int32_t count, int height, int32_t *lo,
                   int32_t *hi) {
  int32_t l = height, h = -1;
  for (int32_t i = first; i < first + count; i++) {
    if (b->polys[i].row0 < l) l = b->polys[i].row0;
    if (b->polys[i].row1 > h) h = b->polys[i].row1;
  }
  *lo = l < 0 ? 0 : l;
  *hi = h > height - 1 ? height - 1 : h;
}

int32_t zs_batch_edges_of(const zs_batch *b, int32_t first, int32_t count) {
  if (count <= 0) return 0;
  /* the polygons' edges lie together, in the polygons' order */
  const int32_t e1 = first + count < b->npolys ? b->polys[first + count].edge0 : b->nedges;
  return e1 - b->polys[first].edge0;
}

void zs_batch_place(zs_batch *dst, int32_t at_poly, int32_t at_edge, const zs_batch *src,
                    int32_t first, int32_t count) {
  if (count <= 0) return;
  const int32_t e0 = src->polys[first].edge0, nedges = zs_batch_edges_of(src, first, count);
  for (int32_t i = 0; i < count; i++) {
    zs_poly p = src->polys[first + i];
    p.edge0 += at_edge - e0;
    dst->polys[at_poly + i] = p;
  }
  memcpy(dst->edges + at_edge, src->edges + e0, (size_t)nedges * sizeof *src->edges);
}

int zs_batch_append_range(zs_batch *dst, const zs_batch *src, int32_t first, int32_t count) {
  if (count <= 0) return 1;
  const int32_t nedges = zs_batch_edges_of(src, first, count);
  if (!zs_batch_reserve(dst, count, nedges)) return 0;
  zs_batch_place(dst, dst->npolys, dst->nedges, src, first, count);
  dst->npolys += count;
  dst->nedges += nedges;
  return 1;
}

int zs_batch_append(zs_batch *dst, const zs_batch *src) {
  return zs_batch_append_range(dst, src, 0, src->npolys);
}
