/* The A-buffer (abuffer.h): rows of transparent fragments, and their
 * resolve over a row's opaque colours. */
#include <stdlib.h>
#include <string.h>

#include "raster/abuffer.h"
#include "raster/surface.h"

void zs_abuffer_init(zs_abuffer *a, int width, int height, int slots) {
  memset(a, 0, sizeof *a);
  a->width = width;
  a->height = height;
  a->slots = slots > 0 ? slots : 1;
}

int zs_abuffer_ready(zs_abuffer *a) {
  if (a->rows) return 1;
  a->rows = calloc((size_t)a->height, sizeof *a->rows);
  a->scratch = malloc((size_t)a->slots * (size_t)a->width * sizeof *a->scratch);
  a->work = calloc((size_t)a->slots, sizeof *a->work);
  if (!a->rows || !a->scratch || !a->work) {
    zs_abuffer_free(a); /* (the rows calloc'd: no fragments to free) */
    return 0;
  }
  for (int y = 0; y < a->height; y++)
    a->rows[y].limit = ZS_FRAGMENTS_PER_PIXEL * a->width;
  return 1;
}

void zs_abuffer_clear(zs_abuffer *a) {
  if (!a->rows) return;
  for (int y = 0; y < a->height; y++) a->rows[y].n = a->rows[y].failed = 0;
}

void zs_abuffer_free(zs_abuffer *a) {
  if (a->rows)
    for (int y = 0; y < a->height; y++) free(a->rows[y].f);
  if (a->work)
    for (int k = 0; k < a->slots; k++) free(a->work[k].f);
  free(a->rows);
  free(a->scratch);
  free(a->work);
  a->rows = NULL;
  a->scratch = NULL;
  a->work = NULL;
}

size_t zs_abuffer_bytes(const zs_abuffer *a) {
  if (!a->rows) return 0;
  size_t n = (size_t)a->height * sizeof *a->rows +
             (size_t)a->slots * (size_t)a->width * sizeof *a->scratch;
  for (int y = 0; y < a->height; y++) n += (size_t)a->rows[y].cap * sizeof(zs_fragment);
  for (int k = 0; k < a->slots; k++) n += (size_t)a->work[k].cap * sizeof(zs_fragment);
  return n;
}

/* Grows to hold `more`; a row over its limit keeps what it has and
 * fails, as does one out of memory, and takes no more fragments. */
int zs_fragment_row_grow(zs_fragment_row *r, int32_t more) {
  if (r->failed) return 0;
  const int64_t need = (int64_t)r->n + more; /* past the limit by one span at most */
  if (r->n > r->limit || need > INT32_MAX / 2) {
    r->failed = 1;
    return 0;
  }
  int64_t cap = r->cap > 0 ? 2 * (int64_t)r->cap : 256;
  if (cap < need) cap = need;
  zs_fragment *f = realloc(r->f, (size_t)cap * sizeof *f);
  if (!f) {
    r->failed = -1;
    return 0;
  }
  r->f = f;
  r->cap = (int32_t)cap;
  return 1;
}

zs_status zs_abuffer_check(zs_abuffer *a, zs_error *err) {
  if (!a->rows) return ZS_OK;
  int32_t most = 0;
  for (int y = 0; y < a->height; y++) {
    zs_fragment_row *r = &a->rows[y];
    if (r->failed < 0) return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
    if (r->failed || r->n > r->limit)
      return zs_error_set(err, ZS_ERR_LIMIT,
                          "draw: row %d holds more than %d transparent fragments (%d a pixel)",
                          y, (int)r->limit, ZS_FRAGMENTS_PER_PIXEL);
    if (r->n > most) most = r->n;
  }
  /* the resolve's copies made room for now, so that it needs no memory */
  for (int k = 0; k < a->slots; k++) {
    struct zs_fragment_work *w = &a->work[k];
    if (w->cap >= most) continue;
    zs_fragment *f = realloc(w->f, (size_t)most * sizeof *f);
    if (!f) return zs_error_set(err, ZS_ERR_NOMEM, "draw: out of memory");
    w->f = f;
    w->cap = most;
  }
  return ZS_OK;
}

/* (x, depth, id, shaded colour): a total order on what the resolve reads */
static int fragment_cmp(const void *pa, const void *pb) {
  const zs_fragment *a = pa, *b = pb;
  if (a->x != b->x) return a->x < b->x ? -1 : 1;
  if (a->depth != b->depth) return a->depth < b->depth ? -1 : 1;
  if (a->id != b->id) return a->id < b->id ? -1 : 1;
  return a->word < b->word ? -1 : a->word > b->word;
}

/* The fragments of one pixel, sorted, composited over its opaque colour
 * o (abuffer.h gives the arithmetic). */
static uint32_t composite(const zs_fragment *f, int32_t n, uint32_t o) {
  uint64_t sum[3] = {0, 0, 0}, t = 1u << 16;
  for (int32_t i = 0; i < n && t > 0; i++) {
    if (i > 0 && f[i].depth == f[i - 1].depth && f[i].id == f[i - 1].id) continue;
    const uint64_t a = f[i].word >> 24;
    for (int k = 0; k < 3; k++) sum[k] += (uint64_t)(f[i].word >> (16 - 8 * k) & 255) * a * t;
    t = (t * (255 - a) + 127) / 255;
  }
  uint32_t out = 0;
  for (int k = 0; k < 3; k++) {
    const uint64_t oc = o >> (16 - 8 * k) & 255;
    out |= (uint32_t)((sum[k] + 255 * oc * t + (255u << 15)) / (255u << 16)) << (16 - 8 * k);
  }
  return out;
}

void zs_abuffer_resolve_row(zs_abuffer *a, zs_surfaces *s, int slot, int y,
                           const uint32_t *depth, const uint32_t *id, uint32_t *rgb) {
  if (!a->rows || a->rows[y].n == 0) return;
  const zs_fragment_row *r = &a->rows[y];
  /* a row whose draw failed (its error returned) stays opaque: the room
   * was made for rows that held */
  if (r->failed || r->n > a->work[slot].cap) return;
  zs_fragment *f = a->work[slot].f; /* room made by zs_abuffer_check */
  /* 1. in front of the final opaque surface */
  int32_t n = 0;
  for (int32_t i = 0; i < r->n; i++) {
    const zs_fragment g = r->f[i];
    if (g.depth < depth[g.x] || (g.depth == depth[g.x] && g.id < id[g.x])) f[n++] = g;
  }
  /* 2. shaded, a run of one word on consecutive pixels at a time (a
   * span's fragments are kept in a run) */
  uint32_t *out = a->scratch + (size_t)slot * (size_t)a->width;
  for (int32_t i = 0; i < n;) {
    int32_t j = i + 1;
    while (j < n && f[j].word == f[i].word && f[j].x == f[j - 1].x + 1) j++;
    zs_surface_shade_rgba(s, slot, y, f[i].word, f[i].x, f[j - 1].x + 1, out);
    for (int32_t k = i; k < j; k++) f[k].word = out[f[k].x];
    i = j;
  }
  /* 3. sorted; 4. composited a pixel at a time */
  qsort(f, (size_t)n, sizeof *f, fragment_cmp);
  for (int32_t i = 0; i < n;) {
    int32_t j = i + 1;
    while (j < n && f[j].x == f[i].x) j++;
    rgb[f[i].x] = composite(&f[i], j - i, rgb[f[i].x]);
    i = j;
  }
}
