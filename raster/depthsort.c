/* The painter's algorithm with frame coherence (depthsort.h).
 *
 * Faces are identified across frames by id.  Per id the sorter keeps the
 * key and place of the last frame; the list of the last frame's order is
 * the "old queue" of the paper, and faces not in it (the paper's rank
 * 65535) are the new ones. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/exactmath.h"
#include "util/grow.h"
#include "util/os.h"
#include "raster/depthsort.h"

const char *zs_motion_class_name(zs_motion_class m) {
  static const char *names[] = {"first", "static", "translate", "roll",
                                "slow-rotate", "fast", "dolly"};
  return (unsigned)m < sizeof names / sizeof names[0] ? names[m] : "?";
}

struct zs_depthsort {
  uint32_t *face_ids;    /* this frame's faces in view, as drawn */
  double *face_keys;     /* and their sort keys */
  uint32_t nfaces, cap_faces;
  uint32_t *noted_ids;   /* the last frame's face_ids and face_keys */
  double *noted_keys;
  uint32_t nnoted, cap_noted;
  /* per face id (dense, grown to the largest id seen) */
  double *key_of, *prev_key;
  int32_t *rank_of;      /* this frame's place, back to front */
  uint32_t *seen;        /* frame stamp: present this frame */
  uint32_t *was;         /* frame stamp: kept in this frame's old queue */
  uint32_t cap_ids;
  uint32_t *order, *prev_order, *tmp, *fresh;  /* ids */
  uint32_t n_prev, cap_order;
  uint32_t frame;
  uint32_t ordered_frame; /* the seen stamp of the faces in prev_order */
  double drift;           /* the depth shift since prev_key was written */
  double prev_view[16];
  int has_prev;
  zs_depthsort_stats stats;
  double ms;
  /* The faces ordered are those that meet the circle around the window,
   * centred where the view axis meets the image plane: a roll keeps that
   * set whole.  A point's place on the image plane is u = (x_ndc - cx) *
   * sx, v = (y_ndc - cy) * sy; the circle is u^2 + v^2 <= r2. */
  double cx, cy, sx, sy, r2;
};

zs_depthsort *zs_depthsort_create(void) { return calloc(1, sizeof(zs_depthsort)); }

void zs_depthsort_set_projection(zs_depthsort *ds, const double proj[16], int perspective) {
  /* Where the view axis lands in NDC: (-P02, -P12) under a perspective
   * (x_ndc = (P00 x + P02 z) / -z), (P03, P13) under a parallel
   * projection; the image plane's units are NDC over P00 and P11. */
  ds->cx = perspective ? -proj[2] : proj[3];
  ds->cy = perspective ? -proj[6] : proj[7];
  ds->sx = proj[0] != 0.0 ? 1.0 / proj[0] : 0.0;
  ds->sy = proj[5] != 0.0 ? 1.0 / proj[5] : 0.0;
  ds->r2 = 0.0;
  for (int corner = 0; corner < 4; corner++) { /* the farthest corner */
    double u = ((corner & 1 ? 1.0 : -1.0) - ds->cx) * ds->sx;
    double v = ((corner & 2 ? 1.0 : -1.0) - ds->cy) * ds->sy;
    if (u * u + v * v > ds->r2) ds->r2 = u * u + v * v;
  }
}

void zs_depthsort_clear(zs_depthsort *ds) { ds->nfaces = 0; }
void zs_depthsort_forget(zs_depthsort *ds) { ds->has_prev = 0; }
const zs_depthsort_stats *zs_depthsort_stats_of(const zs_depthsort *ds) { return &ds->stats; }
double zs_depthsort_ms(const zs_depthsort *ds) { return ds->ms; }

void zs_depthsort_destroy(zs_depthsort *ds) {
  if (!ds) return;
  free(ds->face_ids);
  free(ds->face_keys);
  free(ds->noted_ids);
  free(ds->noted_keys);
  free(ds->key_of);
  free(ds->prev_key);
  free(ds->rank_of);
  free(ds->seen);
  free(ds->was);
  free(ds->order);
  free(ds->prev_order);
  free(ds->tmp);
  free(ds->fresh);
  free(ds);
}

int zs_depthsort_note(zs_depthsort *ds, uint32_t id, double key) {
  if (ds->nfaces == ds->cap_faces) {
    uint32_t cap = ds->cap_faces ? 2 * ds->cap_faces : 1024;
    void **const arrays[] = {(void **)&ds->face_ids, (void **)&ds->face_keys};
    const size_t sizes[] = {sizeof *ds->face_ids, sizeof *ds->face_keys};
    if (!zs_resize_each(arrays, sizes, 2, cap)) return 0;
    ds->cap_faces = cap;
  }
  ds->face_ids[ds->nfaces] = id;
  ds->face_keys[ds->nfaces++] = key;
  return 1;
}

/* ---- ordering ---- */

/* "a is painted before b": farther first; at equal keys the higher id
 * first, so that the lower id is painted last and wins. */
static inline int before(const zs_depthsort *ds, uint32_t a, uint32_t b, uint64_t *cmp) {
  ++*cmp;
  double ka = ds->key_of[a], kb = ds->key_of[b];
  return ka > kb || (ka == kb && a > b);
}

/* Bottom-up merge sort of ids[0..n-1] (stable, O(n log n) comparisons). */
static void merge_sort(const zs_depthsort *ds, uint32_t *ids, uint32_t *tmp, uint32_t n,
                       uint64_t *cmp) {
  uint32_t *src = ids, *dst = tmp;
  for (uint32_t width = 1; width < n; width *= 2) {
    for (uint32_t lo = 0; lo < n; lo += 2 * width) {
      uint32_t mid = lo + width < n ? lo + width : n;
      uint32_t hi = lo + 2 * width < n ? lo + 2 * width : n;
      uint32_t i = lo, j = mid, k = lo;
      while (i < mid && j < hi) dst[k++] = before(ds, src[j], src[i], cmp) ? src[j++] : src[i++];
      while (i < mid) dst[k++] = src[i++];
      while (j < hi) dst[k++] = src[j++];
    }
    uint32_t *t = src;
    src = dst;
    dst = t;
  }
  if (src != ids) memcpy(ids, src, (size_t)n * sizeof *ids);
}

/* Insertion sort with a galloping search: each face looks back from its
 * old place in steps 1, 2, 4, ... then halves the last step, so it costs
 * one comparison when in order and O(log d) when d places out: n - 1
 * comparisons on sorted input, never many more than a full sort.  The
 * sort for a nearly sorted old queue. */
static void insertion_sort(const zs_depthsort *ds, uint32_t *ids, uint32_t n, uint64_t *cmp) {
  for (uint32_t i = 1; i < n; i++) {
    uint32_t v = ids[i];
    if (!before(ds, v, ids[i - 1], cmp)) continue;
    /* v goes before ids[i-1]; find the first k with before(v, ids[k]) */
    uint32_t hi = i - 1, step = 1; /* before(v, ids[hi]) holds */
    uint32_t lo = 0;               /* the answer is in [lo, hi] */
    while (step <= hi) {
      if (!before(ds, v, ids[hi - step], cmp)) {
        lo = hi - step + 1;
        break;
      }
      hi -= step;
      step *= 2;
    }
    while (lo < hi) { /* binary search in [lo, hi] */
      uint32_t mid = lo + (hi - lo) / 2;
      if (before(ds, v, ids[mid], cmp)) hi = mid;
      else lo = mid + 1;
    }
    memmove(&ids[lo + 1], &ids[lo], (size_t)(i - lo) * sizeof *ids);
    ids[lo] = v;
  }
}

/* Merges the sorted lists a (na) and b (nb) into out.  The order is a
 * strict total one (ids break ties), so any merge gives the same list;
 * when b is much the shorter (a few new faces among many kept ones) each
 * of its faces finds its place in a by a galloping search from the last
 * one, O(log gap) comparisons instead of one per face of a. */
static void merge(const zs_depthsort *ds, const uint32_t *a, uint32_t na, const uint32_t *b,
                  uint32_t nb, uint32_t *out, uint64_t *cmp) {
  uint32_t i = 0, j = 0, k = 0;
  if ((uint64_t)nb * 16 < na) {
    for (; j < nb; j++) {
      /* the first a[p], p >= i, that b[j] is painted before */
      uint32_t lo = i, step = 1, hi = na; /* the answer is in [lo, hi] */
      while (lo + step - 1 < na) {
        if (before(ds, b[j], a[lo + step - 1], cmp)) {
          hi = lo + step - 1;
          break;
        }
        lo += step;
        step *= 2;
      }
      while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (before(ds, b[j], a[mid], cmp)) hi = mid;
        else lo = mid + 1;
      }
      memcpy(out + k, a + i, (size_t)(lo - i) * sizeof *a);
      k += lo - i;
      i = lo;
      out[k++] = b[j];
    }
  }
  while (i < na && j < nb) out[k++] = before(ds, b[j], a[i], cmp) ? b[j++] : a[i++];
  while (i < na) out[k++] = a[i++];
  while (j < nb) out[k++] = b[j++];
}

/* The camera's motion from the previous view to this one.  M = V V_prev^-1
 * takes old eye coordinates to new ones: rotation R (3x3) and translation
 * t.  Its depth shift (for the kept faces' check) is -t_z. */
static zs_motion_class classify(const double prev[16], const double view[16], double *shift) {
  /* R = Rv Rp^T; t = tv - R tp (both views are rigid). */
  double R[9], t[3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double s = 0.0;
      for (int k = 0; k < 3; k++) s += view[4 * i + k] * prev[4 * j + k];
      R[3 * i + j] = s;
    }
  for (int i = 0; i < 3; i++)
    t[i] = view[4 * i + 3] - (R[3 * i] * prev[3] + R[3 * i + 1] * prev[7] + R[3 * i + 2] * prev[11]);
  *shift = -t[2];
  double cosang = (R[0] + R[4] + R[8] - 1.0) / 2.0;
  if (cosang > 1.0) cosang = 1.0;
  const double eps = 1e-12;
  int rotated = cosang < 1.0 - eps;
  int moved = fabs(t[0]) > eps || fabs(t[1]) > eps || fabs(t[2]) > eps;
  if (!rotated) {
    if (!moved) return ZS_MOTION_STATIC;
    return fabs(t[2]) > eps ? ZS_MOTION_DOLLY : ZS_MOTION_TRANSLATE;
  }
  /* a rotation about the view axis leaves every z: R's third row is (0,0,1) */
  if (fabs(R[6]) < 1e-9 && fabs(R[7]) < 1e-9) return ZS_MOTION_ROLL;
  double s2, c2; /* of 2 degrees */
  zs_sincos_deg(2.0, &s2, &c2);
  return cosang > c2 ? ZS_MOTION_SLOW_ROTATE : ZS_MOTION_FAST;
}

static int reserve_ids(zs_depthsort *ds, uint32_t max_id) {
  if (max_id < ds->cap_ids) return 1;
  uint32_t cap = ds->cap_ids ? ds->cap_ids : 1024;
  while (cap <= max_id) cap *= 2;
  void **const arrays[] = {(void **)&ds->key_of, (void **)&ds->prev_key, (void **)&ds->rank_of,
                           (void **)&ds->seen, (void **)&ds->was};
  const size_t sizes[] = {sizeof *ds->key_of, sizeof *ds->prev_key, sizeof *ds->rank_of,
                          sizeof *ds->seen, sizeof *ds->was};
  if (!zs_resize_each(arrays, sizes, 5, cap)) return 0;
  /* new ids were never seen: stamp 0 is no frame (frames count from 1) */
  memset(ds->seen + ds->cap_ids, 0, (size_t)(cap - ds->cap_ids) * sizeof *ds->seen);
  memset(ds->was + ds->cap_ids, 0, (size_t)(cap - ds->cap_ids) * sizeof *ds->was);
  ds->cap_ids = cap;
  return 1;
}

static int reserve_order(zs_depthsort *ds, uint32_t n) {
  if (n <= ds->cap_order) return 1;
  uint32_t cap = ds->cap_order ? ds->cap_order : 1024;
  while (cap < n) cap *= 2;
  void **const arrays[] = {(void **)&ds->order, (void **)&ds->prev_order, (void **)&ds->tmp,
                           (void **)&ds->fresh};
  const size_t sizes[] = {sizeof *ds->order, sizeof *ds->prev_order, sizeof *ds->tmp,
                          sizeof *ds->fresh};
  if (!zs_resize_each(arrays, sizes, 4, cap)) return 0;
  ds->cap_order = cap;
  return 1;
}

/* Whether this frame noted the faces the last frame noted, in the same
 * order, each at its old depth plus the motion's shift: two arrays
 * streamed side by side, no look-up per face. */
static int same_faces_as_before(const zs_depthsort *ds, double shift) {
  if (ds->nfaces != ds->nnoted) return 0;
  for (uint32_t i = 0; i < ds->nfaces; i++) {
    double expect = ds->noted_keys[i] + shift;
    if (ds->face_ids[i] != ds->noted_ids[i] ||
        fabs(ds->face_keys[i] - expect) > 1e-9 * (1.0 + fabs(expect)))
      return 0;
  }
  return 1;
}

/* This frame's noted faces become the last frame's (the arrays swap). */
static void keep_noted(zs_depthsort *ds) {
  uint32_t *i = ds->noted_ids;
  double *k = ds->noted_keys;
  uint32_t cap = ds->cap_noted;
  ds->noted_ids = ds->face_ids;
  ds->noted_keys = ds->face_keys;
  ds->cap_noted = ds->cap_faces;
  ds->nnoted = ds->nfaces;
  ds->face_ids = i;
  ds->face_keys = k;
  ds->cap_faces = cap;
  ds->nfaces = 0; /* the next frame notes its own */
}

/* The painter's depth of every polygon: its face's rank, back to front.
 * A polygon whose face was not ordered (outside the circle the faces are
 * ordered in: zs_depthsort_selects, below) covers no pixel and is
 * painted farthest. */
static void paint_depths(const zs_depthsort *ds, zs_batch *b) {
  const int64_t n = ds->n_prev;
  for (int32_t i = 0; i < b->npolys; i++) {
    zs_poly *p = &b->polys[i];
    p->zshift = 0;
    p->dzdx = p->dzdy = 0;
    int ordered = p->id < ds->cap_ids && ds->seen[p->id] == ds->ordered_frame;
    p->zc = ordered ? n - 1 - ds->rank_of[p->id] : n;
  }
}

int zs_depthsort_order(zs_depthsort *ds, zs_batch *b, const double view[16]) {
  const double t0 = zs_os_monotonic_ms();
  zs_depthsort_stats st = {ZS_MOTION_FIRST, 0, 0, 0, 0, 0};
  double shift = 0.0;
  if (ds->has_prev) st.motion = classify(ds->prev_view, view, &shift);
  int keep_as_is = st.motion == ZS_MOTION_STATIC || st.motion == ZS_MOTION_TRANSLATE ||
                   st.motion == ZS_MOTION_DOLLY || st.motion == ZS_MOTION_ROLL;
  int coherent = keep_as_is || st.motion == ZS_MOTION_SLOW_ROTATE;
  memcpy(ds->prev_view, view, sizeof ds->prev_view);

  /* The paper's roll (and a still camera over a still scene): the same
   * faces at the same depths.  The old order stands whole, with every
   * rank; nothing per face but the check. */
  if (ds->has_prev && keep_as_is && same_faces_as_before(ds, shift)) {
    ds->drift += shift;
    st.faces = st.reused = ds->n_prev;
    keep_noted(ds);
    paint_depths(ds, b);
    ds->stats = st;
    ds->ms = zs_os_monotonic_ms() - t0;
    return 1;
  }

  uint32_t max_id = 0;
  for (uint32_t i = 0; i < ds->nfaces; i++)
    if (ds->face_ids[i] > max_id) max_id = ds->face_ids[i];
  if (!reserve_ids(ds, max_id) || !reserve_order(ds, ds->nfaces + 1)) return 0;
  uint32_t frame = ++ds->frame;

  /* The faces of this frame, each once, with its key. */
  uint32_t n = 0;
  for (uint32_t i = 0; i < ds->nfaces; i++) {
    uint32_t id = ds->face_ids[i];
    if (ds->seen[id] == frame) continue;
    ds->seen[id] = frame;
    ds->key_of[id] = ds->face_keys[i];
    ds->order[n++] = id; /* scratch: the faces in drawing order */
  }
  keep_noted(ds);
  st.faces = n;
  shift += ds->drift; /* prev_key is as old as the last frame sorted here */

  /* The old queue: last frame's order, less the faces gone, and (when the
   * motion says depths are kept or shifted) less the faces that moved. */
  uint32_t nold = 0, nfresh = 0;
  if (coherent) {
    for (uint32_t i = 0; i < ds->n_prev; i++) {
      uint32_t id = ds->prev_order[i];
      if (id > max_id || ds->seen[id] != frame) continue;
      double expect = ds->prev_key[id] + shift;
      if (keep_as_is && fabs(ds->key_of[id] - expect) > 1e-9 * (1.0 + fabs(expect))) continue;
      ds->was[id] = frame; /* in the old queue */
      ds->tmp[nold++] = id;
    }
    /* Mostly new faces (fast motion): coherence has nothing to offer.
     * Else the new ones, unless every face is in the old queue. */
    if (2 * (uint64_t)(n - nold) > n) coherent = 0;
    else if (nold < n)
      for (uint32_t i = 0; i < n; i++)
        if (ds->was[ds->order[i]] != frame) ds->fresh[nfresh++] = ds->order[i];
  }
  if (!coherent) {
    st.full_sort = 1;
    if (st.motion != ZS_MOTION_FIRST) st.motion = ZS_MOTION_FAST;
    merge_sort(ds, ds->order, ds->tmp, n, &st.comparisons);
    st.inserted = n;
  } else {
    st.reused = nold;
    st.inserted = nfresh;
    if (!keep_as_is) insertion_sort(ds, ds->tmp, nold, &st.comparisons);
    if (nfresh == 0) { /* the old queue is the order: no merge, no copy */
      uint32_t *t = ds->order;
      ds->order = ds->tmp;
      ds->tmp = t;
    } else {
      merge_sort(ds, ds->fresh, ds->prev_order, nfresh, &st.comparisons);
      merge(ds, ds->tmp, nold, ds->fresh, nfresh, ds->order, &st.comparisons);
    }
  }

  /* Ranks, and the memory for the next frame: this order and these keys
   * are the next frame's old ones.  When the old order was kept whole
   * (nothing gone, nothing new, nothing moved) every rank stands. */
  int ranks_stand = coherent && keep_as_is && nfresh == 0 && nold == ds->n_prev;
  if (!ranks_stand)
    for (uint32_t i = 0; i < n; i++) ds->rank_of[ds->order[i]] = (int32_t)i;
  uint32_t *t = ds->prev_order;
  ds->prev_order = ds->order;
  ds->order = t;
  double *k = ds->prev_key;
  ds->prev_key = ds->key_of;
  ds->key_of = k;
  ds->n_prev = n;
  ds->ordered_frame = frame;
  ds->drift = 0.0;
  paint_depths(ds, b);
  ds->has_prev = 1;
  ds->stats = st;
  ds->ms = zs_os_monotonic_ms() - t0;
  return 1;
}

/* ---- which faces the painter orders (the face stage asks, draw.c) ---- */

/* Whether the polygon p[0..n-1] (clip space, w > 0) meets depth sort's
 * circle around the window: some edge passes within its radius (a corner
 * inside is an edge's end inside), or the polygon holds its centre (by
 * the crossings of the ray from the centre along +u). */
static int meets_sort_circle(const zs_depthsort *ds, const zs_clip_vert *p, int n) {
  double u0 = (p[n - 1].x / p[n - 1].w - ds->cx) * ds->sx;
  double v0 = (p[n - 1].y / p[n - 1].w - ds->cy) * ds->sy;
  int inside = 0;
  for (int i = 0; i < n; i++) {
    double u = (p[i].x / p[i].w - ds->cx) * ds->sx;
    double v = (p[i].y / p[i].w - ds->cy) * ds->sy;
    /* the point of the edge (u0, v0)-(u, v) nearest the centre */
    double du = u - u0, dv = v - v0, len2 = du * du + dv * dv;
    double t = len2 > 0.0 ? -(u0 * du + v0 * dv) / len2 : 0.0;
    t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
    double nu = u0 + t * du, nv = v0 + t * dv;
    if (nu * nu + nv * nv <= ds->r2) return 1;
    if ((v0 > 0.0) != (v > 0.0) && u0 - v0 * du / dv > 0.0) inside = !inside;
    u0 = u;
    v0 = v;
  }
  return inside;
}

/* Whether a face that set-up found turned away or without area may be
 * turned to the eye after all: its area in pixels from the unsnapped
 * corners is at most what snapping to 1/256 pixel can move it by (half a
 * subpixel a coordinate: under 1/256 of the lengths of the corners'
 * neighbour chords, which no rotation changes).  Set-up's back test is on
 * snapped corners, so a face far off or seen edge-on turns from drawn to
 * back or to no area as the view rolls; this test does not. */
static int nearly_turned_to_eye(const zs_setup_params *sp, const zs_clip_vert *p, int n) {
  double X[ZS_CLIP_MAX_VERTS], Y[ZS_CLIP_MAX_VERTS];
  for (int i = 0; i < n; i++) { /* window pixels, y down, as snapped */
    zs_window_xy(sp->width, sp->height, &p[i], &X[i], &Y[i]);
    Y[i] = sp->height - Y[i];
  }
  double area2 = 0.0, chords = 0.0;
  for (int i = 0, j = n - 1, k = n - 2; i < n; k = j, j = i++) {
    area2 += X[j] * Y[i] - X[i] * Y[j];
    double cx = X[i] - X[k], cy = Y[i] - Y[k]; /* the chord around corner j */
    chords += sqrt(cx * cx + cy * cy);
  }
  return area2 <= chords / 256.0 + n / 65536.0; /* back faces: area2 > 0 */
}

/* Whether depth sort orders a face set-up has seen (result r): whether
 * it meets the circle, and, where back faces are culled, is or may be
 * turned to the eye.  An unclipped face (clipped NULL; its corners fv,
 * snapped in v->snap) drawn with a corner in the window does, and one
 * plainly turned away does not; else the tests run on the clipped polygon
 * or on the corners copied to scratch. */
int zs_depthsort_selects(const zs_depthsort *ds, const zs_setup_params *sp, zs_setup_result r,
                         const zs_clip_vert *clip, const zs_snap_vert *snap, const int32_t *fv,
                         const zs_clip_vert *clipped, int n, zs_clip_vert *scratch) {
  const zs_clip_vert *poly = clipped;
  if (!clipped) {
    const zs_snap_vert *sn = snap; /* corner i at sn[fv[i]] */
    if (r == ZS_SETUP_BACK && sp->cull_back) {
      /* Most back faces are plainly so: twice their snapped area (in
       * subpixels) beyond four times their L1 perimeter (which bounds
       * twice the chords) plus the corners, more than snapping can take
       * away and nearly_turned_to_eye allow. */
      int64_t area2 = 0, perimeter = 0;
      for (int i = 0, j = n - 1; i < n; j = i++) {
        const zs_snap_vert *si = &sn[fv[i]], *sj = &sn[fv[j]];
        area2 += (int64_t)sj->x * si->y - (int64_t)si->x * sj->y;
        perimeter += llabs((int64_t)si->x - sj->x) + llabs((int64_t)si->y - sj->y);
      }
      if (area2 > 4 * perimeter + n + 1) return 0;
    }
    if (r == ZS_SETUP_DRAWN) {
      const int64_t wx = (int64_t)sp->width * ZS_SUBPIXEL_ONE;
      const int64_t wy = (int64_t)sp->height * ZS_SUBPIXEL_ONE;
      for (int i = 0; i < n; i++) {
        const zs_snap_vert *si = &sn[fv[i]];
        if (si->x >= 0 && si->x <= wx && si->y >= 0 && si->y <= wy) return 1;
      }
    }
    for (int i = 0; i < n; i++) scratch[i] = clip[fv[i]];
    poly = scratch;
  }
  if ((r == ZS_SETUP_BACK || r == ZS_SETUP_DEGENERATE) && sp->cull_back &&
      !nearly_turned_to_eye(sp, poly, n))
    return 0;
  return meets_sort_circle(ds, poly, n);
}
