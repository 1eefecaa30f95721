/* Surface shading (surface.h): the records of a frame's attribute draws,
 * and the rows' pixels shaded from them after visibility is settled.
 *
 * A run of pixels naming one record is shaded by a loop chosen for its
 * draw's shading and whether its material is textured (once per
 * triangle, when it is prepared), from the triangle prepared once: its
 * integer planes and its corners' attributes in fixed point.  The
 * prepared triangles are kept in a cache indexed by record, so the
 * rows below a triangle's first find it ready; what a pixel gets does not
 * depend on the cache, which only saves the work. */
#include "raster/surface.h"
#include "util/compiler.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "raster/texture.h"
#include "util/exactmath.h"
#include "util/lights.h"
#include "util/grow.h"
#include "util/srgb.h"

enum {
  BARY_BITS = 24,        /* the weights b_i, in 2^-24 */
  PLANE_BITS = 37,       /* |lambda_i| below 2^37 over the triangle's box */
  /* prepared triangles kept (a power of two): more than a row of a
   * frame of small triangles meets, so that the rows below find them
   * (zscan bench raster --shade unlit --no-tilings counts the
   * preparations in its time: builtin:plant and builtin:city meet 256
   * slots' collisions most) */
  CACHE_SLOTS = 4096,
  UV_ONE = 1 << 16       /* texture coordinates in 2^-16 */
};
#define NORMAL_ONE 1073741824.0 /* normals in 2^-30 */


/* ---- the records ---- */

void zs_surfaces_init(zs_surfaces *s, int width, int height, zs_filter filter) {
  memset(s, 0, sizeof *s);
  s->width = width;
  s->height = height;
  s->filter = filter;
  s->nlights = zs_lights_default(s->lights);
  s->sets_stale = 1;
}

static void cache_empty(void *cache);

void zs_surfaces_clear(zs_surfaces *s) {
  s->ndraws = s->nrecs = s->nsets = s->nshadow_mvp = 0;
  s->sets_stale = 1;
  for (int i = 0; i < ZS_SURFACE_SLOTS; i++) /* the records' numbers start again */
    if (s->cache[i]) cache_empty(s->cache[i]);
}

void zs_surfaces_set_normals_out(zs_surfaces *s, int on) {
  s->normals_out = on != 0;
  for (int i = 0; i < ZS_SURFACE_SLOTS; i++)
    if (s->cache[i]) cache_empty(s->cache[i]);
}

void zs_surfaces_set_shadow_maps(zs_surfaces *s, const zs_shadow_map *maps, int n) {
  s->nshadows = n;
  for (int j = 0; j < n; j++) {
    s->shadows[j] = maps[j];
    zs_mat_mul(s->shadow_vp[j], maps[j].proj, maps[j].view);
  }
  s->sets_stale = 1;
  for (int i = 0; i < ZS_SURFACE_SLOTS; i++)
    if (s->cache[i]) cache_empty(s->cache[i]);
}

void zs_surfaces_free(zs_surfaces *s) {
  free(s->shadow_mvp);
  free(s->draws);
  free(s->recs);
  free(s->sets);
  for (int i = 0; i < ZS_SURFACE_SLOTS; i++) free(s->cache[i]);
  memset(s, 0, sizeof *s);
}

int zs_surface_grow_recs(zs_surfaces *s) {
  if (s->nrecs >= (int32_t)(ZS_SURFACE_BIT - 1 > INT32_MAX ? INT32_MAX : ZS_SURFACE_BIT - 1))
    return 0;
  return zs_grow((void **)&s->recs, &s->cap_recs, (int64_t)s->nrecs + 1, sizeof *s->recs);
}

static int material_transparent(const zs_mesh *m, const zs_material *mat) {
  return !mat->ignore_alpha &&
         (mat->base[3] < 255 ||
          (mat->base_texture && m->uv && !zs_texture_opaque(mat->base_texture)));
}

int zs_face_transparent(const zs_mesh *m, int32_t f) {
  const zs_material *mat = zs_face_material(m, f);
  if (mat && mat->ignore_alpha) return 0;
  if (mat && material_transparent(m, mat)) return 1;
  if (!m->color) return 0;
  const int32_t s = m->face_start[f], nv = m->face_start[f + 1] - s;
  if (nv < 3 || nv > ZS_MAX_POLY_VERTS) return 0;
  for (int32_t c = s; c < s + nv; c++) {
    const int32_t a = zs_corner_attr(m, c);
    if (a >= 0 && m->color[4 * (size_t)a + 3] < 255) return 1;
  }
  return 0;
}

int zs_mesh_transparent(const zs_mesh *m) {
  int all_ignore = m->materials && m->nmaterials > 0;
  for (int32_t k = 0; m->materials && k < m->nmaterials; k++) {
    if (material_transparent(m, &m->materials[k])) return 1;
    all_ignore &= m->materials[k].ignore_alpha;
  }
  for (int32_t a = 0; m->color && !all_ignore && a < m->nattrs; a++)
    if (m->color[4 * (size_t)a + 3] < 255) return 1;
  return 0;
}

int zs_surface_reads(const zs_surfaces *s, zs_shade shade, const zs_mesh *mesh) {
  if (shade == ZS_SHADE_AUTO)
    return mesh->normal || mesh->color || mesh->uv || s->lights_given || zs_mesh_transparent(mesh);
  return shade >= ZS_SHADE_UNLIT;
}

/* mv's 3 x 3 cofactors, signed by its determinant: the inverse transpose
 * up to a positive factor, which the normalisation of each normal drops. */
static void normal_matrix(const double mv[16], double n[9]) {
  const double a = mv[0], b = mv[1], c = mv[2], d = mv[4], e = mv[5], f = mv[6], g = mv[8],
               h = mv[9], i = mv[10];
  const double co[9] = {e * i - f * h, f * g - d * i, d * h - e * g,
                        c * h - b * i, a * i - c * g, b * g - a * h,
                        b * f - c * e, c * d - a * f, a * e - b * d};
  const double det = a * co[0] + b * co[1] + c * co[2];
  for (int k = 0; k < 9; k++) n[k] = det < 0 ? -co[k] : co[k];
}

int32_t zs_surface_add_draw(zs_surfaces *s, const zs_mesh *mesh, const double view[16],
                            const double model[16], const double mv[16], const double mvp[16],
                            int perspective, uint32_t rgb, zs_shade shade) {
  if (s->sets_stale || s->nsets == 0) {
    if (!zs_grow((void **)&s->sets, &s->cap_sets, (int64_t)s->nsets + 1, sizeof *s->sets))
      return -1;
    zs_light_set_make(s->lights, s->nlights, view, perspective, s->shadows, s->nshadows,
                      &s->sets[s->nsets++]);
    s->sets_stale = 0;
  }
  if (!zs_grow((void **)&s->draws, &s->cap_draws, (int64_t)s->ndraws + 1, sizeof *s->draws))
    return -1;
  zs_surface_draw *d = &s->draws[s->ndraws];
  d->mesh = *mesh;
  memcpy(d->mv, mv, sizeof d->mv);
  memcpy(d->mvp, mvp, sizeof d->mvp);
  normal_matrix(mv, d->nrm);
  d->rgb = rgb;
  d->shade = shade == ZS_SHADE_AUTO ? ZS_SHADE_PHONG : shade;
  d->lights = s->nsets - 1;
  d->shadow_at = -1;
  if (s->nshadows > 0 && d->shade == ZS_SHADE_PHONG) {
    if (!zs_grow((void **)&s->shadow_mvp, &s->cap_shadow_mvp,
                 (int64_t)s->nshadow_mvp + s->nshadows, sizeof *s->shadow_mvp))
      return -1;
    d->shadow_at = s->nshadow_mvp;
    for (int j = 0; j < s->nshadows; j++) {
      double *m = s->shadow_mvp[s->nshadow_mvp++];
      if (model) zs_mat_mul(m, s->shadow_vp[j], model);
      else memcpy(m, s->shadow_vp[j], sizeof s->shadow_vp[j]);
    }
  }
  return s->ndraws++;
}

static size_t cache_bytes(void);

size_t zs_surfaces_bytes(const zs_surfaces *s) {
  size_t caches = 0;
  for (int i = 0; i < ZS_SURFACE_SLOTS; i++) caches += s->cache[i] ? cache_bytes() : 0;
  return (size_t)s->cap_draws * sizeof *s->draws + (size_t)s->cap_recs * sizeof *s->recs +
         (size_t)s->cap_shadow_mvp * sizeof *s->shadow_mvp +
         (size_t)s->cap_sets * sizeof *s->sets + caches;
}

/* ---- a triangle prepared ---- */

typedef struct tri tri;
typedef void (*run_fn)(const tri *t, int y, int x0, int x1, uint32_t *out);

struct tri {
  run_fn run, run_alpha;         /* opaque, and with alpha (the A-buffer's) */
  int32_t ox, oy;                /* the planes' origin pixel */
  int64_t A[3], B[3], C[3];      /* lambda_i = A_i (x - ox) + B_i (y - oy) + C_i */
  int32_t col[3][4];             /* unlit: base x vertex colour, 8 bits; lit:
                                  * the same in 16-bit linear light */
  int32_t d16[3][3], s16[3][3];  /* gouraud: each corner's diffuse and specular */
  int64_t s[3], t[3];            /* texture coordinates, 2^-16 */
  int32_t n[3][3];               /* eye-space unit normals, 2^-30 */
  double p[3][3];                /* eye-space positions */
  zs_sampler sampler;
  int mipmapped;                 /* the filter needs the level of detail */
  /* the level of detail's sums that do not change over the triangle
   * (lod_at): those of A_i, B_i and each times s_i and t_i */
  double Sx, Sy, Nsx, Nsy, Ntx, Nty;
  uint32_t cutoff;               /* the material's alpha cut-off, 0: none */
  zs_reflectance refl;
  const zs_light_set *lights;
  /* Phong under shadow maps: for each shadowed light k, its index in the
   * light set, its map, the corners' clip coordinates in the map's camera
   * and the triangle's depth bias there */
  int nshadowed;
  int32_t sh_light[ZS_MAX_SHADOW_MAPS];
  const zs_shadow_map *sh_map[ZS_MAX_SHADOW_MAPS];
  double sh_clip[ZS_MAX_SHADOW_MAPS][3][4];
  int64_t sh_bias[ZS_MAX_SHADOW_MAPS];
};

/* v rounded to an integer, within +-2^62: a slope beyond the box's
 * budget (a box one pixel wide bounds nothing across it) is never
 * multiplied by more than 0 there, but must still be the same number on
 * every machine, and llrint leaves an out-of-range result unspecified. */
static int64_t to_int(double v) {
  const double lim = 4611686018427387904.0; /* 2^62 */
  if (!(v > -lim)) return v != v ? 0 : -((int64_t)1 << 62);
  if (!(v < lim)) return (int64_t)1 << 62;
  return llrint(v);
}

/* The perspective-correct planes of a triangle with clip coordinates c
 * (surface.h, INTERPOLATION), in integers, for a width x height window. */
static void make_planes(tri *t, const double c[3][4], int width, int height) {
  double h[3][3]; /* (X, Y, W): image pixels times w */
  int behind = 0;
  double lo[2] = {0, 0}, hi[2] = {0, 0};
  for (int i = 0; i < 3; i++) {
    h[i][0] = (c[i][0] + c[i][3]) * (0.5 * width);
    h[i][1] = (c[i][3] - c[i][1]) * (0.5 * height);
    h[i][2] = c[i][3];
    if (!(c[i][3] > 0.0)) {
      behind = 1;
      continue;
    }
    const double px = h[i][0] / h[i][2], py = h[i][1] / h[i][2];
    if (i == 0 || px < lo[0]) lo[0] = px;
    if (i == 0 || py < lo[1]) lo[1] = py;
    if (i == 0 || px > hi[0]) hi[0] = px;
    if (i == 0 || py > hi[1]) hi[1] = py;
  }
  /* the pixels the triangle may own: its projected box, widened by the
   * snapping, within the window (the window whole when a corner lies
   * behind the eye and the box is unbounded) */
  int32_t x0 = 0, y0 = 0, x1 = width - 1, y1 = height - 1;
  if (!behind) {
    if (lo[0] - 2 > x0) x0 = (int32_t)(lo[0] - 2);
    if (lo[1] - 2 > y0) y0 = (int32_t)(lo[1] - 2);
    if (hi[0] + 2 < x1) x1 = (int32_t)(hi[0] + 2);
    if (hi[1] + 2 < y1) y1 = (int32_t)(hi[1] + 2);
    if (x1 < x0) x1 = x0;
    if (y1 < y0) y1 = y0;
  }
  double e[3][3];
  for (int i = 0; i < 3; i++) {
    const double *a = h[(i + 1) % 3], *b = h[(i + 2) % 3];
    e[i][0] = a[1] * b[2] - a[2] * b[1];
    e[i][1] = a[2] * b[0] - a[0] * b[2];
    e[i][2] = a[0] * b[1] - a[1] * b[0];
  }
  const double det = h[0][0] * e[0][0] + h[0][1] * e[0][1] + h[0][2] * e[0][2];
  t->ox = x0;
  t->oy = y0;
  if (!(det != 0.0) || !isfinite(det)) { /* edge-on: the first corner's values */
    for (int i = 0; i < 3; i++) t->A[i] = t->B[i] = 0, t->C[i] = i == 0;
    return;
  }
  const double sign = det < 0 ? -1.0 : 1.0;
  double at0[3], biggest = 0.0;
  for (int i = 0; i < 3; i++) {
    for (int k = 0; k < 3; k++) e[i][k] = e[i][k] * sign;
    at0[i] = e[i][0] * (x0 + 0.5) + e[i][1] * (y0 + 0.5) + e[i][2];
  }
  const double dx = (double)(x1 - x0), dy = (double)(y1 - y0);
  for (int corner = 0; corner < 4; corner++) {
    double sum = 0.0;
    for (int i = 0; i < 3; i++)
      sum += fabs(at0[i] + e[i][0] * (corner & 1 ? dx : 0.0) + e[i][1] * (corner & 2 ? dy : 0.0));
    if (sum > biggest) biggest = sum;
  }
  const int ex = zs_binary_exponent(biggest); /* biggest < 2^ex */
  const double scale = zs_pow2(PLANE_BITS - ex);
  for (int i = 0; i < 3; i++) {
    t->A[i] = to_int(e[i][0] * scale);
    t->B[i] = to_int(e[i][1] * scale);
    t->C[i] = to_int(at0[i] * scale);
  }
}

/* The planes' values at pixel (x, y), exactly; going right a pixel adds
 * A_i, as exactly. */
static inline void planes_at(const tri *t, int x, int y, int64_t raw[3]) {
  const int64_t dx = x - t->ox, dy = y - t->oy;
  for (int i = 0; i < 3; i++) raw[i] = t->A[i] * dx + t->B[i] * dy + t->C[i];
}

/* The weights b (2^-24, summing to 2^24) of the planes' values raw at a
 * pixel; l gets those values with negatives as 0. */
static inline void weights_of(const int64_t raw[3], int64_t l[3], int64_t b[3]) {
  int64_t sum = 0;
  for (int i = 0; i < 3; i++) {
    int64_t v = raw[i];
    if (v < 0) v = 0;
    if (v > ((int64_t)1 << (PLANE_BITS + 1))) v = (int64_t)1 << (PLANE_BITS + 1);
    l[i] = v;
    sum += v;
  }
  if (sum <= 0) {
    b[0] = (int64_t)1 << BARY_BITS, b[1] = b[2] = 0;
    return;
  }
  b[0] = (l[0] << BARY_BITS) / sum;
  b[1] = (l[1] << BARY_BITS) / sum;
  b[2] = ((int64_t)1 << BARY_BITS) - b[0] - b[1];
}

static inline int64_t interp(const int64_t b[3], int64_t a0, int64_t a1, int64_t a2) {
  return (b[0] * a0 + b[1] * a1 + b[2] * a2 + ((int64_t)1 << (BARY_BITS - 1))) >> BARY_BITS;
}

/* floor(128 log2(m)) for a mantissa m in [0.5, 1), by its top 8 bits:
 * entry i is that of m = 0.5 + (i + 0.5) / 512, made once with a
 * logarithm and written out, so no pixel's level of detail passes through
 * one (1/256 of a level at most from the logarithm of m itself). */
static const int16_t log2_mantissa128[256] = {
    -128, -127, -127, -126, -125, -125, -124, -123, -122, -122, -121, -120, -120, -119, -118, -118,
    -117, -116, -116, -115, -114, -114, -113, -112, -112, -111, -110, -110, -109, -108, -108, -107,
    -106, -106, -105, -105, -104, -103, -103, -102, -101, -101, -100, -100,  -99,  -98,  -98,  -97,
     -96,  -96,  -95,  -95,  -94,  -93,  -93,  -92,  -92,  -91,  -90,  -90,  -89,  -89,  -88,  -88,
     -87,  -86,  -86,  -85,  -85,  -84,  -84,  -83,  -82,  -82,  -81,  -81,  -80,  -80,  -79,  -79,
     -78,  -77,  -77,  -76,  -76,  -75,  -75,  -74,  -74,  -73,  -73,  -72,  -72,  -71,  -70,  -70,
     -69,  -69,  -68,  -68,  -67,  -67,  -66,  -66,  -65,  -65,  -64,  -64,  -63,  -63,  -62,  -62,
     -61,  -61,  -60,  -60,  -59,  -59,  -58,  -58,  -57,  -57,  -56,  -56,  -55,  -55,  -54,  -54,
     -53,  -53,  -52,  -52,  -51,  -51,  -51,  -50,  -50,  -49,  -49,  -48,  -48,  -47,  -47,  -46,
     -46,  -45,  -45,  -44,  -44,  -44,  -43,  -43,  -42,  -42,  -41,  -41,  -40,  -40,  -40,  -39,
     -39,  -38,  -38,  -37,  -37,  -36,  -36,  -36,  -35,  -35,  -34,  -34,  -33,  -33,  -33,  -32,
     -32,  -31,  -31,  -30,  -30,  -30,  -29,  -29,  -28,  -28,  -27,  -27,  -27,  -26,  -26,  -25,
     -25,  -25,  -24,  -24,  -23,  -23,  -22,  -22,  -22,  -21,  -21,  -20,  -20,  -20,  -19,  -19,
     -18,  -18,  -18,  -17,  -17,  -17,  -16,  -16,  -15,  -15,  -15,  -14,  -14,  -13,  -13,  -13,
     -12,  -12,  -11,  -11,  -11,  -10,  -10,  -10,   -9,   -9,   -8,   -8,   -8,   -7,   -7,   -7,
      -6,   -6,   -5,   -5,   -5,   -4,   -4,   -4,   -3,   -3,   -2,   -2,   -2,   -1,   -1,   -1,
};

/* The level of detail at the pixel whose plane values are l (texture.h,
 * LEVEL OF DETAIL), in 1/256 level: from the derivatives of s = N / S
 * along x, dN/dx S - N dS/dx over S^2, and along y. */
static inline int32_t lod_at(const tri *t, const int64_t l[3]) {
  double S = 0, Ns = 0, Nt = 0;
  for (int i = 0; i < 3; i++) {
    const double li = (double)l[i], si = (double)t->s[i], ti = (double)t->t[i];
    S += li, Ns += li * si, Nt += li * ti;
  }
  const double Sx = t->Sx, Sy = t->Sy, Nsx = t->Nsx, Nsy = t->Nsy, Ntx = t->Ntx, Nty = t->Nty;
  if (!(S > 0)) return 0;
  const zs_texlevel *l0 = &t->sampler.tex->level[0];
  const double ku = l0->width / (S * S * UV_ONE), kv = l0->height / (S * S * UV_ONE);
  const double sx = (Nsx * S - Ns * Sx) * ku, sy = (Nsy * S - Ns * Sy) * ku;
  const double tx = (Ntx * S - Nt * Sx) * kv, ty = (Nty * S - Nt * Sy) * kv;
  const double rx = sx * sx + tx * tx, ry = sy * sy + ty * ty;
  const double rho2 = rx > ry ? rx : ry;
  if (!(rho2 > 1.0)) return 0; /* magnified (and NaN) */
  if (rho2 > 0x1p60) return 256 * ZS_TEXTURE_MAX_LEVELS; /* past every level */
  /* log2(rho) = log2(rho^2) / 2 in 1/256 of a level: 128 (e + log2 m) for
   * rho^2 = m 2^e, m in [0.5, 1), read off the double's bits (what frexp
   * gives, rho^2 being normal here): e from the exponent field, and the
   * top 8 bits of the fraction, (m - 0.5) 512 truncated, the table's entry */
  uint64_t bits;
  memcpy(&bits, &rho2, sizeof bits);
  const int e = (int)(bits >> 52 & 0x7FF) - 1022;
  return 128 * e + log2_mantissa128[bits >> 44 & 255];
}

static inline void texel_at(const tri *t, const int64_t l[3], const int64_t b[3],
                            uint8_t out[4]) {
  const int32_t lod = t->mipmapped ? lod_at(t, l) : 0;
  zs_sample(&t->sampler, interp(b, t->s[0], t->s[1], t->s[2]),
            interp(b, t->t[0], t->t[1], t->t[2]), lod, out);
}

static inline uint32_t clamp16(int64_t v) { return v < 0 ? 0 : v > 65535 ? 65535 : (uint32_t)v; }

static inline uint32_t rgb_of(uint32_t r, uint32_t g, uint32_t b) { return r << 16 | g << 8 | b; }

/* A linear value (0 .. 1, clamped) in 1/65535, rounded. */
static inline uint32_t to16(double v) {
  if (!(v > 0.0)) return 0;
  if (v >= 1.0) return 65535;
  return (uint32_t)(v * 65535.0 + 0.5);
}

/* The unit normal at a pixel of weights b: the corners' normals
 * interpolated and normalised (in double, one sqrt and a division each);
 * 0 where they cancel. */
static inline void unit_normal_at(const tri *t, const int64_t b[3], double u[3]) {
  double len2 = 0.0;
  for (int k = 0; k < 3; k++) {
    u[k] = (double)interp(b, t->n[0][k], t->n[1][k], t->n[2][k]);
    len2 += u[k] * u[k];
  }
  const double len = sqrt(len2);
  for (int k = 0; k < 3; k++) u[k] = len > 0.0 ? u[k] / len : 0.0;
}

/* ---- shadows (zscan.h, zs_shadow_map) ---- */

#define DEPTH_ONE 4294967296.0 /* window depth 1 in the device's units */

/* A light-space clip position's window x, y, z in map m (z in depth
 * units), as the device maps its clip coordinates; 0 when w <= 0. */
static inline int map_window(const zs_shadow_map *m, const double c[4], double out[3]) {
  const double w = c[3];
  if (!(w > 0.0)) return 0;
  out[0] = (c[0] + w) * (0.5 * m->width) / w;
  out[1] = (w - c[1]) * (0.5 * m->height) / w;
  out[2] = (c[2] + w) * (0.5 * DEPTH_ONE) / w;
  return 1;
}

/* The triangle's bias in map m from its corners' clip coordinates c:
 * units + slope (|dz/dx| + |dz/dy|), rounded down (zscan.h).  The
 * triangle's plane holds the clip points a X + b Y + c Z + d W = 0, (a, b,
 * c, d) the 4-D cross product of the corners, so in the window z is affine
 * in x and y with slopes -a / c and -b / c (scaled to texels and depth
 * units) wherever the plane lies in front of the light, a corner behind it
 * or not; 2^32 where the triangle is edge-on to the light. */
static int64_t shadow_bias(const zs_shadow_map *m, const double c[3][4]) {
  const double *u = c[0], *v = c[1], *w = c[2];
  /* the 3 x 3 minors of the rows u, v, w without column k */
#define MINOR(i, j, k)                                                             \
  (u[i] * (v[j] * w[k] - v[k] * w[j]) - u[j] * (v[i] * w[k] - v[k] * w[i]) +      \
   u[k] * (v[i] * w[j] - v[j] * w[i]))
  const double pa = MINOR(1, 2, 3), pb = -MINOR(0, 2, 3), pc = MINOR(0, 1, 3);
#undef MINOR
  if (!(pc != 0.0)) return (int64_t)DEPTH_ONE;
  /* z in depth units over x, y in texels: (DEPTH_ONE / 2) / (width / 2) */
  const double sx = fabs(pa / pc) * DEPTH_ONE / m->width,
               sy = fabs(pb / pc) * DEPTH_ONE / m->height;
  const double bias = m->bias_units + m->bias_slope * (sx + sy);
  return bias < DEPTH_ONE ? (int64_t)bias : (int64_t)DEPTH_ONE;
}

/* Of the 3 x 3 texels about the one a receiver at clip position c falls
 * in, those that light it (zscan.h, zs_shadow_map): 0 .. 9. */
static inline int shadow_lit(const zs_shadow_map *m, const double c[4], int64_t bias) {
  double v[3];
  if (!map_window(m, c, v)) return 9;
  if (!(v[0] > -2.0 && v[0] < m->width + 2.0 && v[1] > -2.0 && v[1] < m->height + 2.0))
    return 9; /* off the map, every tap with it (and NaN) */
  const int64_t r = (v[2] > 0.0 ? v[2] < DEPTH_ONE ? (int64_t)v[2] : (int64_t)DEPTH_ONE : 0) - bias;
  const int tx = (int)floor(v[0]), ty = (int)floor(v[1]);
  int lit = 0;
  for (int y = ty - 1; y <= ty + 1; y++)
    for (int x = tx - 1; x <= tx + 1; x++)
      lit += x < 0 || y < 0 || x >= m->width || y >= m->height ||
             r <= (int64_t)m->depth[(size_t)y * (size_t)m->width + (size_t)x];
  return lit;
}

/* Each light's share of the pixel of weights b into lit (1: no map). */
static inline void shadows_at(const tri *t, const int64_t b[3], double *lit) {
  for (int e = 0; e < t->lights->n; e++) lit[e] = 1.0;
  for (int k = 0; k < t->nshadowed; k++) {
    const double (*c)[4] = t->sh_clip[k];
    double p[4];
    for (int j = 0; j < 4; j++)
      p[j] = ((double)b[0] * c[0][j] + (double)b[1] * c[1][j] + (double)b[2] * c[2][j]) * 0x1p-24;
    lit[t->sh_light[k]] = shadow_lit(t->sh_map[k], p, t->sh_bias[k]) / 9.0;
  }
}

/* The pixels [x0, x1) of row y, one loop per shading and texturing; the
 * constants fold each copy's branches away. */
/* alpha: the pixels' alpha goes out too, as A << 24 (abuffer.h) */
ZS_ALWAYS_INLINE void shade_run(const tri *t, int y, int x0, int x1, uint32_t *out,
                                const zs_shade sh, const int textured, const int shadowed,
                                const int alpha) {
  int64_t raw[3];
  planes_at(t, x0, y, raw);
  for (int x = x0; x < x1; x++, raw[0] += t->A[0], raw[1] += t->A[1], raw[2] += t->A[2]) {
    int64_t l[3], b[3];
    uint8_t tx[4] = {255, 255, 255, 255};
    weights_of(raw, l, b);
    if (textured) texel_at(t, l, b, tx);
    uint32_t a8 = 0;
    if (alpha) {
      a8 = (uint32_t)interp(b, t->col[0][3], t->col[1][3], t->col[2][3]);
      if (textured) a8 = (a8 * tx[3] + 127) / 255;
      if (t->cutoff) a8 = a8 >= t->cutoff ? 255 : 0; /* glTF's MASK */
    }
    if (sh == ZS_SHADE_UNLIT) {
      uint32_t c[3];
      for (int k = 0; k < 3; k++) {
        c[k] = (uint32_t)interp(b, t->col[0][k], t->col[1][k], t->col[2][k]);
        if (textured) c[k] = (c[k] * tx[k] + 127) / 255;
      }
      out[x] = (a8 << 24) | rgb_of(c[0], c[1], c[2]);
    } else if (sh == ZS_SHADE_GOURAUD) {
      uint32_t c[3];
      for (int k = 0; k < 3; k++) {
        int64_t d = interp(b, t->d16[0][k], t->d16[1][k], t->d16[2][k]);
        if (textured) d = (d * zs_srgb_to_linear16[tx[k]] + 32767) / 65535;
        c[k] = zs_linear16_to_srgb(clamp16(d + interp(b, t->s16[0][k], t->s16[1][k], t->s16[2][k])));
      }
      out[x] = (a8 << 24) | rgb_of(c[0], c[1], c[2]);
    } else if (sh == ZS_SHADE_PHONG) {
      double n[3], p[3], base[3], d[3], s[3];
      for (int k = 0; k < 3; k++) {
        n[k] = (double)interp(b, t->n[0][k], t->n[1][k], t->n[2][k]);
        p[k] = ((double)b[0] * t->p[0][k] + (double)b[1] * t->p[1][k] +
                (double)b[2] * t->p[2][k]) * 0x1p-24;
        int64_t c = interp(b, t->col[0][k], t->col[1][k], t->col[2][k]);
        if (textured) c = (c * zs_srgb_to_linear16[tx[k]] + 32767) / 65535;
        base[k] = (double)c / 65535.0;
      }
      double lit[ZS_MAX_LIGHTS];
      if (shadowed) shadows_at(t, b, lit);
      zs_light_at(t->lights, &t->refl, p, n, base, shadowed ? lit : NULL, d, s);
      out[x] = (a8 << 24) | rgb_of(zs_linear16_to_srgb(to16(d[0] + s[0])), zs_linear16_to_srgb(to16(d[1] + s[1])),
                      zs_linear16_to_srgb(to16(d[2] + s[2])));
    } else { /* ZS_SHADE_NORMAL */
      double n[3];
      unit_normal_at(t, b, n);
      uint32_t c[3];
      for (int k = 0; k < 3; k++) {
        const double v = n[k] * 127.5 + 128.0;
        c[k] = v < 0.0 ? 0 : v >= 255.0 ? 255 : (uint32_t)v;
      }
      out[x] = (a8 << 24) | rgb_of(c[0], c[1], c[2]);
    }
  }
}

/* Each shading's copies: with a texture or without, under shadow maps
 * or not; opaque (the colour words of rows) or with alpha (the A-buffer's
 * fragments).  Chosen once per triangle, when it is prepared. */
#define RUN(name, sh, tex, shadowed)                                                \
  static void name(const tri *t, int y, int x0, int x1, uint32_t *out) {            \
    shade_run(t, y, x0, x1, out, sh, tex, shadowed, 0);                            \
  }                                                                                 \
  static void name##_alpha(const tri *t, int y, int x0, int x1, uint32_t *out) {    \
    shade_run(t, y, x0, x1, out, sh, tex, shadowed, 1);                            \
  }
RUN(run_unlit, ZS_SHADE_UNLIT, 0, 0)
RUN(run_unlit_tex, ZS_SHADE_UNLIT, 1, 0)
RUN(run_gouraud, ZS_SHADE_GOURAUD, 0, 0)
RUN(run_gouraud_tex, ZS_SHADE_GOURAUD, 1, 0)
RUN(run_phong, ZS_SHADE_PHONG, 0, 0)
RUN(run_phong_tex, ZS_SHADE_PHONG, 1, 0)
RUN(run_phong_shadowed, ZS_SHADE_PHONG, 0, 1)
RUN(run_phong_tex_shadowed, ZS_SHADE_PHONG, 1, 1)
#undef RUN
/* the normal shading draws every face opaque: no alpha copy */
static void run_normal(const tri *t, int y, int x0, int x1, uint32_t *out) {
  shade_run(t, y, x0, x1, out, ZS_SHADE_NORMAL, 0, 0, 0);
}

/* index: shading (unlit, gouraud, phong, normal), textured, shadowed, alpha */
static run_fn run_for(zs_shade sh, int textured, int shadowed, int alpha) {
  static const run_fn runs[4][2][2][2] = {
      {{{run_unlit, run_unlit_alpha}, {run_unlit, run_unlit_alpha}},
       {{run_unlit_tex, run_unlit_tex_alpha}, {run_unlit_tex, run_unlit_tex_alpha}}},
      {{{run_gouraud, run_gouraud_alpha}, {run_gouraud, run_gouraud_alpha}},
       {{run_gouraud_tex, run_gouraud_tex_alpha}, {run_gouraud_tex, run_gouraud_tex_alpha}}},
      {{{run_phong, run_phong_alpha}, {run_phong_shadowed, run_phong_shadowed_alpha}},
       {{run_phong_tex, run_phong_tex_alpha},
        {run_phong_tex_shadowed, run_phong_tex_shadowed_alpha}}},
      {{{run_normal, run_normal}, {run_normal, run_normal}},
       {{run_normal, run_normal}, {run_normal, run_normal}}}};
  const int i = sh == ZS_SHADE_UNLIT ? 0 : sh == ZS_SHADE_GOURAUD ? 1 : sh == ZS_SHADE_NORMAL ? 3 : 2;
  return runs[i][textured != 0][shadowed != 0][alpha != 0];
}

/* A texture coordinate in 2^-16, finite and within 2^40 so llrint is
 * defined. */
static int64_t uv_fixed(double u) {
  if (!isfinite(u)) return 0;
  if (u > 1099511627776.0) u = 1099511627776.0;
  if (u < -1099511627776.0) u = -1099511627776.0;
  return llrint(u * UV_ONE);
}

/* The triangle's texture coordinates moved by a whole period of the wrap
 * (so the texels stay those of the coordinates given) towards 0, and
 * clamped to +-2^31 (a triangle over 32,768 repeats of its texture is
 * sampled as if it spanned that many). */
static void settle_uv(int64_t v[3], zs_wrap w) {
  int64_t lo = v[0];
  for (int i = 1; i < 3; i++)
    if (v[i] < lo) lo = v[i];
  int64_t period = w == ZS_WRAP_MIRROR ? 2 * (int64_t)UV_ONE : (int64_t)UV_ONE;
  int64_t off = 0;
  if (w == ZS_WRAP_CLAMP) off = 0;
  else off = (lo >= 0 ? lo / period : -((-lo + period - 1) / period)) * period;
  for (int i = 0; i < 3; i++) {
    int64_t u = v[i] - off;
    if (w == ZS_WRAP_CLAMP) u = u < -2 * UV_ONE ? -2 * UV_ONE : u > 3 * UV_ONE ? 3 * UV_ONE : u;
    v[i] = u > INT32_MAX ? INT32_MAX : u < -INT32_MAX ? -INT32_MAX : u;
  }
}

static double lin(uint8_t c) { return zs_srgb_to_linear16[c] / 65535.0; }

static void prepare(const zs_surfaces *s, int32_t rec, tri *t) {
  const zs_surface_rec *r = &s->recs[rec];
  const zs_surface_draw *dr = &s->draws[r->draw];
  const zs_mesh *m = &dr->mesh;
  /* what the shading reads: unlit neither normals nor eye-space positions
   * (most of a small triangle's preparation), normal no positions but for
   * a corner without a normal */
  const int lit = dr->shade == ZS_SHADE_GOURAUD || dr->shade == ZS_SHADE_PHONG;
  const int normals = dr->shade != ZS_SHADE_UNLIT || s->normals_out;
  double clip[3][4];
  const double *pos3[3];
  for (int i = 0; i < 3; i++) {
    const double *pos = pos3[i] = &m->pos[3 * (size_t)m->face_vert[r->corner[i]]];
    double e[4];
    zs_mat_apply(dr->mvp, pos, clip[i]);
    if (normals) {
      zs_mat_apply(dr->mv, pos, e);
      memcpy(t->p[i], e, sizeof t->p[i]);
    }
  }
  make_planes(t, clip, s->width, s->height);

  const zs_material *mat = zs_face_material(m, r->face);
  const uint32_t rgb = zs_face_base_rgb(m, mat, r->face, dr->rgb);
  const uint8_t base8[3] = {(uint8_t)(rgb >> 16), (uint8_t)(rgb >> 8), (uint8_t)rgb};

  t->cutoff = mat ? mat->alpha_cutoff : 0;
  /* the geometric normal, for corners without one */
  double geo[3] = {0, 0, 1};
  if (normals) {
    const double a[3] = {t->p[1][0] - t->p[0][0], t->p[1][1] - t->p[0][1], t->p[1][2] - t->p[0][2]};
    const double b[3] = {t->p[2][0] - t->p[0][0], t->p[2][1] - t->p[0][1], t->p[2][2] - t->p[0][2]};
    geo[0] = a[1] * b[2] - a[2] * b[1];
    geo[1] = a[2] * b[0] - a[0] * b[2];
    geo[2] = a[0] * b[1] - a[1] * b[0];
  }
  /* a texture without texture coordinates is not applied (glTF's rule) */
  const int textured = mat && mat->base_texture && m->uv && dr->shade != ZS_SHADE_NORMAL;
  if (textured) {
    zs_filter f = s->filter != ZS_FILTER_DEFAULT ? s->filter : mat->filter;
    t->sampler = (zs_sampler){mat->base_texture, mat->wrap_s, mat->wrap_t,
                              f == ZS_FILTER_DEFAULT ? ZS_FILTER_TRILINEAR : f};
    t->mipmapped = t->sampler.filter != ZS_FILTER_NEAREST;
  }
  if (lit) {
    t->refl.double_sided = mat ? mat->double_sided : 1;
    t->refl.shininess = mat ? mat->shininess : 0;
    for (int k = 0; k < 3; k++) {
      t->refl.emissive[k] = mat ? lin(mat->emissive[k]) : 0.0;
      t->refl.specular[k] = mat ? lin(mat->specular[k]) : 0.0;
    }
    t->lights = &s->sets[dr->lights];
  }
  /* the shadowed lights: the corners in each one's map, and the bias */
  t->nshadowed = 0;
  if (dr->shade == ZS_SHADE_PHONG && dr->shadow_at >= 0)
    for (int e = 0; e < t->lights->n; e++) {
      const int j = t->lights->light[e].shadow;
      if (j < 0) continue;
      const int k = t->nshadowed++;
      t->sh_light[k] = e;
      t->sh_map[k] = &s->shadows[j];
      for (int i = 0; i < 3; i++)
        zs_mat_apply(s->shadow_mvp[dr->shadow_at + j], pos3[i], t->sh_clip[k][i]);
      t->sh_bias[k] = shadow_bias(t->sh_map[k], t->sh_clip[k]);
    }

  double nrm[3][3];
  for (int i = 0; i < 3; i++) {
    const int32_t a = zs_corner_attr(m, r->corner[i]);
    /* normal */
    if (normals) {
      double n[3] = {0, 0, 0};
      if (a >= 0 && m->normal) {
        const float *f = &m->normal[3 * (size_t)a];
        for (int k = 0; k < 3; k++)
          n[k] = dr->nrm[3 * k] * f[0] + dr->nrm[3 * k + 1] * f[1] + dr->nrm[3 * k + 2] * f[2];
      }
      double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!(len > 0.0) || !isfinite(len)) {
        memcpy(n, geo, sizeof n);
        len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      }
      for (int k = 0; k < 3; k++) {
        nrm[i][k] = len > 0.0 && isfinite(len) ? n[k] / len : k == 2;
        t->n[i][k] = (int32_t)llrint(nrm[i][k] * NORMAL_ONE);
      }
    }
    /* colour */
    const uint8_t *vc = a >= 0 && m->color ? &m->color[4 * (size_t)a] : NULL;
    for (int k = 0; k < 3; k++) {
      const uint32_t v = vc ? vc[k] : 255;
      t->col[i][k] = dr->shade == ZS_SHADE_UNLIT
                         ? (int32_t)((base8[k] * v + 127) / 255)
                         : (int32_t)(((uint32_t)zs_srgb_to_linear16[base8[k]] *
                                          zs_srgb_to_linear16[v] + 32767) / 65535);
    }
    /* alpha, linear: the material's times the vertex colour's */
    t->col[i][3] = (int32_t)(((mat ? mat->base[3] : 255u) * (vc ? vc[3] : 255u) + 127) / 255);
    /* texture coordinates, t down the image */
    if (textured) {
      const float *uv = a >= 0 ? &m->uv[2 * (size_t)a] : NULL;
      t->s[i] = uv ? uv_fixed(uv[0]) : 0;
      t->t[i] = uv ? uv_fixed(1.0 - (double)uv[1]) : 0;
    }
  }
  if (textured) {
    settle_uv(t->s, t->sampler.wrap_s);
    settle_uv(t->t, t->sampler.wrap_t);
    /* summed in lod_at's order, so the level is what summing there gave */
    t->Sx = t->Sy = t->Nsx = t->Nsy = t->Ntx = t->Nty = 0.0;
    for (int i = 0; i < 3; i++) {
      const double a = (double)t->A[i], b = (double)t->B[i];
      const double si = (double)t->s[i], ti = (double)t->t[i];
      t->Sx += a, t->Sy += b;
      t->Nsx += a * si, t->Nsy += b * si, t->Ntx += a * ti, t->Nty += b * ti;
    }
  }
  if (dr->shade == ZS_SHADE_GOURAUD) {
    for (int i = 0; i < 3; i++) {
      double base[3], d[3], sp[3];
      for (int k = 0; k < 3; k++) base[k] = t->col[i][k] / 65535.0;
      zs_light_at(t->lights, &t->refl, t->p[i], nrm[i], base, NULL, d, sp);
      for (int k = 0; k < 3; k++) {
        t->d16[i][k] = (int32_t)to16(d[k]);
        t->s16[i][k] = (int32_t)to16(sp[k]);
      }
    }
  }
  t->run = run_for(dr->shade, textured, t->nshadowed > 0, 0);
  t->run_alpha = run_for(dr->shade, textured, t->nshadowed > 0, 1);
}

/* A slot's cache: which record each entry holds (-1: none) apart from
 * the triangles, so that emptying it each frame writes 16 KiB, not a
 * line of every triangle. */
typedef struct tri_cache {
  int32_t holds[CACHE_SLOTS];
  tri tri[CACHE_SLOTS];
} tri_cache;

static void cache_empty(void *cache) {
  tri_cache *c = cache;
  memset(c->holds, 0xFF, sizeof c->holds);
}

static size_t cache_bytes(void) { return sizeof(tri_cache); }

/* The triangle of record rec, prepared: from the slot's cache, else into
 * spare. */
static const tri *prepared(zs_surfaces *s, int slot, int32_t rec, tri *spare) {
  void **mine = &s->cache[slot];
  if (!*mine && (*mine = malloc(sizeof(tri_cache)))) cache_empty(*mine);
  tri_cache *cache = *mine;
  if (!cache) {
    prepare(s, rec, spare);
    return spare;
  }
  const int32_t i = rec & (CACHE_SLOTS - 1);
  if (cache->holds[i] != rec) {
    prepare(s, rec, &cache->tri[i]);
    cache->holds[i] = rec;
  }
  return &cache->tri[i];
}

/* What a row's run of equal words [x0, x1) becomes: t its triangle, or
 * NULL for a colour v drawn as it is. */
typedef void (*run_visit)(const tri *t, uint32_t v, int y, int x0, int x1, void *out);

/* Row y cut into runs of equal words, each visited once with its triangle
 * prepared; visit is a constant where this is inlined, so each caller gets
 * its own loop. */
ZS_ALWAYS_INLINE void each_run(zs_surfaces *s, int slot, int y, const uint32_t *rgb,
                               run_visit visit, void *out) {
  const int w = s->width;
  int x = 0;
  while (x < w) {
    const uint32_t v = rgb[x];
    int x1 = x + 1;
    /* four words a step while all four are v (a run is most often the
     * background's or a large face's), then one */
    const uint64_t vv = (uint64_t)v << 32 | v;
    for (uint64_t a, b; x1 + 4 <= w; x1 += 4) {
      memcpy(&a, rgb + x1, sizeof a);
      memcpy(&b, rgb + x1 + 2, sizeof b);
      if ((a ^ vv) | (b ^ vv)) break;
    }
    while (x1 < w && rgb[x1] == v) x1++;
    if (v & ZS_SURFACE_BIT) {
      tri spare;
      visit(prepared(s, slot, (int32_t)(v & ~ZS_SURFACE_BIT), &spare), v, y, x, x1, out);
    } else {
      visit(NULL, v, y, x, x1, out);
    }
    x = x1;
  }
}

static inline void shade_visit(const tri *t, uint32_t v, int y, int x0, int x1, void *out) {
  uint32_t *o = out;
  if (t) t->run(t, y, x0, x1, o);
  else
    for (int i = x0; i < x1; i++) o[i] = v;
}

static inline void normal_visit(const tri *t, uint32_t v, int y, int x0, int x1, void *out) {
  (void)v;
  float *xyz = out;
  if (!t) {
    memset(xyz + 3 * (size_t)x0, 0, 3 * (size_t)(x1 - x0) * sizeof *xyz);
    return;
  }
  int64_t raw[3];
  planes_at(t, x0, y, raw);
  for (int i = x0; i < x1; i++, raw[0] += t->A[0], raw[1] += t->A[1], raw[2] += t->A[2]) {
    int64_t l[3], b[3];
    double n[3];
    weights_of(raw, l, b);
    unit_normal_at(t, b, n);
    for (int k = 0; k < 3; k++) xyz[3 * (size_t)i + k] = (float)n[k];
  }
}

void zs_surface_shade_row(zs_surfaces *s, int slot, int y, const uint32_t *rgb, uint32_t *out) {
  each_run(s, slot, y, rgb, shade_visit, out);
}

void zs_surface_shade_rgba(zs_surfaces *s, int slot, int y, uint32_t word, int x0, int x1,
                           uint32_t *out) {
  tri spare;
  const tri *t = prepared(s, slot, (int32_t)(word & ~ZS_SURFACE_BIT), &spare);
  t->run_alpha(t, y, x0, x1, out);
}

void zs_surface_normal_row(zs_surfaces *s, int slot, int y, const uint32_t *rgb, float *xyz) {
  each_run(s, slot, y, rgb, normal_visit, xyz);
}
