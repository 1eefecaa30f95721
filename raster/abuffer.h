/* zscan raster — the A-buffer (abuffer.c): the fragments of transparent
 * surfaces kept per row of the frame and composited when the row goes
 * out.
 *
 * WHAT A FRAGMENT IS
 *   A face is transparent when its material's alpha is below 255, its
 *   base texture has a texel of alpha below 255, or a corner's vertex
 *   colour has (surface.h, zs_face_transparent).  Its triangles are drawn
 *   with the fragment kernel (span.h): a pixel whose centre it covers
 *   and where it passes the depth test against the opaque surface drawn
 *   so far (the same less-with-id test as the draw kernel) is kept as
 *   (x, depth, id, colour word) in its row's list; depth, id and colour
 *   buffers are not written, so a transparent surface occludes nothing.
 *   The list's order is the order of drawing; nothing that reaches an
 *   output depends on it.
 *
 * THE RESOLVE (when the row is shaded; zs_abuffer_resolve_row)
 *   1. The fragments behind the row's final opaque surface (not less than
 *      its (depth, id)) are dropped: a later opaque draw may have covered
 *      a fragment kept earlier.
 *   2. Each is shaded as the opaque pixels are (surface.c), with its
 *      alpha: material alpha x vertex alpha x texel alpha, each rounded
 *      to 8 bits as (a b + 127) / 255.
 *   3. They are sorted by (x, depth, id, shaded colour): a total order, so
 *      the result depends on the set of fragments only; of fragments equal
 *      in (x, depth, id), one face drawn twice, the first is kept.
 *   4. Each pixel's are composited front to back over the opaque colour,
 *      in the 8-bit output values (GL's SRC_ALPHA, ONE_MINUS_SRC_ALPHA
 *      blending on an 8-bit framebuffer, in depth order), in integers:
 *        T_0 = 2^16;  S_c += c_i a_i T_i;
 *        T_i+1 = (T_i (255 - a_i) + 127) / 255   (stopping at T = 0)
 *        c = (S_c + 255 o_c T_n + 255 * 2^15) / (255 * 2^16)
 *      with o the opaque colour (the background where there is none).
 *
 * MEMORY
 *   A row keeps at most ZS_FRAGMENTS_PER_PIXEL x width fragments (16
 *   bytes each) in front of the opaque surface at the time they are
 *   drawn; the draw that passes it fails with ZS_ERR_LIMIT, naming the
 *   row.  Opaque frames allocate nothing here. */
#ifndef ZS_RASTER_ABUFFER_H
#define ZS_RASTER_ABUFFER_H

#include <stddef.h>
#include <stdint.h>

#include "zscan/error.h"

typedef struct zs_fragment {
  int32_t x;
  uint32_t depth, id;
  uint32_t word; /* the colour word (a record: surface.h); once shaded, A << 24 | RGB */
} zs_fragment;

typedef struct zs_fragment_row {
  zs_fragment *f;
  int32_t n, cap;
  int32_t limit;   /* ZS_FRAGMENTS_PER_PIXEL x width */
  int32_t failed;  /* past the limit, or out of memory: the draw fails */
} zs_fragment_row;

typedef struct zs_abuffer {
  zs_fragment_row *rows; /* height of them; NULL until a transparent draw */
  int width, height;
  int slots;             /* threads that resolve rows at once */
  uint32_t *scratch;     /* a row of shaded words for each slot */
  struct zs_fragment_work { zs_fragment *f; int32_t cap; } *work; /* each slot's copy of the
                          * row it resolves: the row itself stays as drawn */
} zs_abuffer;

void zs_abuffer_init(zs_abuffer *a, int width, int height, int slots);
/* The rows made ready for a transparent draw (0: out of memory). */
int zs_abuffer_ready(zs_abuffer *a);
/* A new frame: every row emptied (its memory kept). */
void zs_abuffer_clear(zs_abuffer *a);
void zs_abuffer_free(zs_abuffer *a);
size_t zs_abuffer_bytes(const zs_abuffer *a);

/* After a draw: ZS_OK, or the error of the first row that failed (or of
 * the room the resolve needs). */
zs_status zs_abuffer_check(zs_abuffer *a, zs_error *err);

int zs_fragment_row_grow(zs_fragment_row *r, int32_t more);

/* Room for `more` fragments on row r (0: it failed; nothing is kept). */
static inline int zs_fragment_reserve(zs_fragment_row *r, int32_t more) {
  if (r->n + more <= r->cap) return 1;
  return zs_fragment_row_grow(r, more);
}

struct zs_surfaces;

/* Row y resolved (above) over rgb, the row's opaque colours, in place;
 * depth and id: the row's final opaque surface; the fragments shaded
 * from s's records with the slot's cache (slot < a->slots).  It needs no
 * memory: zs_abuffer_check made the room. */
void zs_abuffer_resolve_row(zs_abuffer *a, struct zs_surfaces *s, int slot, int y,
                            const uint32_t *depth, const uint32_t *id, uint32_t *rgb);

#endif
