/* Mesh primitives (box, solids of revolution, sphere, cylinder, cone, torus)
 * and the mesh specs of zs_gen_mesh.  See generate.h.
 *
 * Winding.  A lathe's vertex (i, j) is profile point i turned by j /
 * segments turns about +y, i.e. (r cos a, y, -r sin a): j runs counter-
 * clockwise seen from +y.  The quad (i, j), (i, j+1), (i+1, j+1), (i+1, j)
 * then has the normal (ring direction) x (profile direction), which points
 * to the right of the profile, away from the solid.  A cap takes each ring
 * edge in the direction opposite to the side face beside it, so every
 * directed edge is used once.  The torus is the same construction with the
 * arc in place of the profile and the tube's circle in place of the ring.
 *
 * Also the generators' mesh kit (gen_internal.h): fresh models, boxes by
 * their corners, rods, rings and lathe profiles built point by point. */
#include <math.h>
#include <string.h>
#include <stdlib.h>

#include "util/exactmath.h"
#include "util/grow.h"
#include "util/matrix.h"
#include "scene/gen_internal.h"
#include "scene/teapot.h"

/* Appends the vertex (x, y, z) placed by xf; -1 when out of memory. */
static int32_t put(zs_model *m, const double *xf, double x, double y, double z) {
  if (!xf) return zs_model_add_vertex(m, x, y, z);
  double p[3] = {x, y, z}, q[4];
  zs_mat_apply(xf, p, q);
  return zs_model_add_vertex(m, q[0], q[1], q[2]);
}

static zs_status poly(zs_model *m, const int32_t *idx, int n, uint32_t rgb, int32_t obj) {
  return zs_model_add_polygon(m, idx, n, rgb, obj);
}

zs_status zs_gen_hexahedron(zs_model *m, const double c[8][3], uint32_t rgb, int32_t obj) {
  int32_t first = m->mesh.nverts;
  for (int b = 0; b < 8; b++)
    if (zs_model_add_vertex(m, c[b][0], c[b][1], c[b][2]) < 0) return ZS_ERR_NOMEM;
  /* Corner b: bit 0 the +x side, bit 1 +y, bit 2 +z.  Each quad runs
   * counter-clockwise seen from outside, e.g. -x: 0 -> 4 is +z, 4 -> 6 is
   * +y, and z x y = -x. */
  static const int quads[6][4] = {
      {0, 4, 6, 2}, /* -x */
      {1, 3, 7, 5}, /* +x */
      {0, 1, 5, 4}, /* -y */
      {2, 6, 7, 3}, /* +y */
      {0, 2, 3, 1}, /* -z */
      {4, 5, 7, 6}  /* +z */
  };
  for (int f = 0; f < 6; f++) {
    int32_t idx[4];
    for (int k = 0; k < 4; k++) idx[k] = first + quads[f][k];
    zs_status st = zs_model_add_polygon(m, idx, 4, rgb, obj);
    if (st != ZS_OK) return st;
  }
  return ZS_OK;
}

zs_status zs_gen_box(zs_model *m, const double lo[3], const double hi[3],
                     const double xform[16], uint32_t rgb, int32_t obj) {
  for (int a = 0; a < 3; a++)
    if (!(lo[a] <= hi[a])) return ZS_ERR_ARG;
  double c[8][3];
  for (int b = 0; b < 8; b++) {
    double p[3] = {(b & 1) ? hi[0] : lo[0], (b & 2) ? hi[1] : lo[1], (b & 4) ? hi[2] : lo[2]};
    double q[4];
    if (xform) zs_mat_apply(xform, p, q);
    memcpy(c[b], xform ? q : p, sizeof c[b]);
  }
  return zs_gen_hexahedron(m, c, rgb, obj);
}

/* Closes a ring of n vertices ring[0 .. n-1] (counter-clockwise about the
 * direction the cap faces when forward, clockwise when not): one polygon,
 * or a fan around a centre vertex c placed by xf when n is too many
 * corners for one face. */
static zs_status cap(zs_model *m, const int32_t *ring, int n, int forward,
                     const double *xf, const double c[3], uint32_t rgb, int32_t obj) {
  if (n <= ZS_MAX_POLY_VERTS) {
    int32_t idx[ZS_MAX_POLY_VERTS];
    for (int j = 0; j < n; j++) idx[j] = forward ? ring[j] : ring[n - 1 - j];
    return poly(m, idx, n, rgb, obj);
  }
  int32_t centre = put(m, xf, c[0], c[1], c[2]);
  if (centre < 0) return ZS_ERR_NOMEM;
  for (int j = 0; j < n; j++) {
    int32_t a = ring[j], b = ring[(j + 1) % n];
    int32_t tri[3] = {centre, forward ? a : b, forward ? b : a};
    zs_status st = poly(m, tri, 3, rgb, obj);
    if (st != ZS_OK) return st;
  }
  return ZS_OK;
}

/* The faces between two rings (or poles) a and b of n vertices each, the
 * travel going from a to b; a pole is one vertex (a_pole, b_pole). */
static zs_status band(zs_model *m, int32_t a, int a_pole, int32_t b, int b_pole, int n,
                      uint32_t rgb, int32_t obj) {
  if (a_pole && b_pole) return ZS_OK;
  for (int j = 0; j < n; j++) {
    int j1 = (j + 1) % n;
    int32_t q[4] = {a_pole ? a : a + j, a_pole ? a : a + j1, b_pole ? b : b + j1,
                    b_pole ? b : b + j};
    zs_status st;
    if (a_pole) {
      int32_t t[3] = {q[0], q[2], q[3]};
      st = poly(m, t, 3, rgb, obj);
    } else if (b_pole) {
      int32_t t[3] = {q[0], q[1], q[2]};
      st = poly(m, t, 3, rgb, obj);
    } else {
      st = poly(m, q, 4, rgb, obj);
    }
    if (st != ZS_OK) return st;
  }
  return ZS_OK;
}

static zs_status ring_indices(int32_t first, int n, int32_t **out) {
  int32_t *r = malloc((size_t)n * sizeof *r);
  if (!r) return ZS_ERR_NOMEM;
  for (int j = 0; j < n; j++) r[j] = first + j;
  *out = r;
  return ZS_OK;
}

zs_status zs_gen_lathe(zs_model *m, const double *profile, int n, int segments,
                       int caps, const double xform[16], uint32_t rgb, int32_t obj) {
  if (!profile || n < 2 || segments < 3) return ZS_ERR_ARG;
  for (int i = 0; i < n; i++)
    if (!(profile[2 * i] >= 0.0) || !isfinite(profile[2 * i]) ||
        !isfinite(profile[2 * i + 1]))
      return ZS_ERR_ARG;
  /* A closed profile (last point = first) turns into a ring-shaped solid:
   * its last ring is its first. */
  int loop = n >= 4 && profile[0] == profile[2 * n - 2] && profile[1] == profile[2 * n - 1];
  int rings = loop ? n - 1 : n;
  for (int i = 0; i < rings && loop; i++)
    if (profile[2 * i] == 0.0) return ZS_ERR_ARG;
  int32_t *first = malloc((size_t)n * sizeof *first);
  double *cs = malloc((size_t)segments * 2 * sizeof *cs);
  if (!first || !cs) {
    free(first);
    free(cs);
    return ZS_ERR_NOMEM;
  }
  for (int j = 0; j < segments; j++)
    zs_sincos_turns((double)j / segments, &cs[2 * j], &cs[2 * j + 1]);

  zs_status st = ZS_OK;
  for (int i = 0; i < rings && st == ZS_OK; i++) {
    double r = profile[2 * i], y = profile[2 * i + 1];
    first[i] = m->mesh.nverts;
    if (r == 0.0) {
      if (put(m, xform, 0.0, y, 0.0) < 0) st = ZS_ERR_NOMEM;
      continue;
    }
    for (int j = 0; j < segments && st == ZS_OK; j++)
      if (put(m, xform, r * cs[2 * j + 1], y, -r * cs[2 * j]) < 0) st = ZS_ERR_NOMEM;
  }
  if (loop) first[n - 1] = first[0];
  for (int i = 0; i + 1 < n && st == ZS_OK; i++)
    st = band(m, first[i], profile[2 * i] == 0.0, first[i + 1], profile[2 * i + 2] == 0.0,
              segments, rgb, obj);
  /* The start cap faces against the travel (ring backwards), the end cap
   * along it. */
  for (int end = 0; end < 2 && caps && !loop && st == ZS_OK; end++) {
    int i = end ? n - 1 : 0;
    if (profile[2 * i] == 0.0) continue;
    int32_t *ring;
    st = ring_indices(first[i], segments, &ring);
    if (st != ZS_OK) break;
    double c[3] = {0.0, profile[2 * i + 1], 0.0};
    st = cap(m, ring, segments, end, xform, c, rgb, obj);
    free(ring);
  }
  free(first);
  free(cs);
  return st;
}

zs_status zs_gen_sphere(zs_model *m, int slices, int stacks, const double xform[16],
                        uint32_t rgb, int32_t obj) {
  if (slices < 3 || stacks < 2) return ZS_ERR_ARG;
  double *profile = malloc((size_t)(stacks + 1) * 2 * sizeof *profile);
  if (!profile) return ZS_ERR_NOMEM;
  /* From the south pole up: angle i / stacks half turns from -y. */
  for (int i = 0; i <= stacks; i++) {
    double s, c;
    zs_sincos_turns(0.5 * i / stacks, &s, &c);
    profile[2 * i] = s;
    profile[2 * i + 1] = -c;
  }
  profile[0] = profile[2 * stacks] = 0.0; /* exact poles */
  zs_status st = zs_gen_lathe(m, profile, stacks + 1, slices, 0, xform, rgb, obj);
  free(profile);
  /* a smooth surface: its normals from its faces (model.h), every facet
   * within the crease of its neighbours from 8 slices and 4 stacks on */
  if (st == ZS_OK && !zs_model_compute_normals(m, ZS_GEN_SMOOTH_CREASE_DEG)) st = ZS_ERR_NOMEM;
  return st;
}

zs_status zs_gen_cylinder(zs_model *m, double r0, double r1, int segments, int caps,
                          const double xform[16], uint32_t rgb, int32_t obj) {
  if (!(r0 >= 0.0 && r1 >= 0.0) || (r0 == 0.0 && r1 == 0.0)) return ZS_ERR_ARG;
  const double profile[4] = {r0, 0.0, r1, 1.0};
  return zs_gen_lathe(m, profile, 2, segments, caps, xform, rgb, obj);
}

zs_status zs_gen_torus(zs_model *m, double major, double minor, double sweep,
                       int segments, int sides, int caps, const double xform[16],
                       uint32_t rgb, int32_t obj) {
  if (!(minor > 0.0 && major > minor && sweep > 0.0 && sweep <= 1.0) || segments < 1 ||
      sides < 3 || (sweep == 1.0 && segments < 3))
    return ZS_ERR_ARG;
  int whole = sweep == 1.0;
  int rings = whole ? segments : segments + 1;
  int32_t first = m->mesh.nverts;
  for (int k = 0; k < rings; k++) {
    double sp, cp;
    zs_sincos_turns(sweep * k / segments, &sp, &cp);
    /* Centre line c = (R - R cos p, R sin p, 0); n1 = (-cos p, sin p, 0)
     * points away from the arc's centre, n2 = +z; n1 x n2 is the tangent. */
    for (int j = 0; j < sides; j++) {
      double sa, ca;
      zs_sincos_turns((double)j / sides, &sa, &ca);
      double x = major - major * cp - minor * ca * cp;
      double y = major * sp + minor * ca * sp;
      double z = minor * sa;
      if (put(m, xform, x, y, z) < 0) return ZS_ERR_NOMEM;
    }
  }
  for (int k = 0; k < segments; k++) {
    int32_t a = first + k * sides, b = first + ((k + 1) % rings) * sides;
    zs_status st = band(m, a, 0, b, 0, sides, rgb, obj);
    if (st != ZS_OK) return st;
  }
  if (whole || !caps) return ZS_OK;
  for (int end = 0; end < 2; end++) {
    int k = end ? segments : 0;
    int32_t *ring;
    if (ring_indices(first + k * sides, sides, &ring)) return ZS_ERR_NOMEM;
    double sp, cp;
    zs_sincos_turns(sweep * k / segments, &sp, &cp);
    double c[3] = {major - major * cp, major * sp, 0.0};
    zs_status st = cap(m, ring, sides, end, xform, c, rgb, obj);
    free(ring);
    if (st != ZS_OK) return st;
  }
  return ZS_OK;
}

/* ---- the generators' mesh kit ------------------------------------------ */

int32_t zs_gen_model(zs_model *m, const char *name, zs_error *err) {
  zs_model_init(m);
  int32_t obj = zs_model_object(m, name);
  if (obj < 0) ZS_GEN_NOMEM(err, name);
  return obj;
}

zs_status zs_gen_box_at(zs_model *m, double x0, double y0, double z0, double x1, double y1,
                        double z1, const double *xf, uint32_t rgb) {
  const double lo[3] = {x0, y0, z0}, hi[3] = {x1, y1, z1};
  return zs_gen_box(m, lo, hi, xf, rgb, 0);
}

zs_status zs_gen_rod(zs_model *m, const double a[3], const double b[3], double r,
                     int segments, uint32_t rgb) {
  double xf[16];
  zs_gen_between(xf, a, b, r);
  return zs_gen_cylinder(m, 1.0, 1.0, segments, 1, xf, rgb, 0);
}

zs_status zs_gen_ring_y(zs_model *m, double major, double minor, double y, int around,
                        int sides, const double *xf, uint32_t rgb) {
  /* The torus primitive's ring lies in the xy plane around (major, 0, 0):
   * its centre to the origin, its axis (+z) onto +y, up to y. */
  double move[16], turn[16], up[16], t[16];
  zs_mat_translate(move, -major, 0.0, 0.0);
  zs_mat_rotate_turns(turn, -0.25, 1.0, 0.0, 0.0);
  zs_mat_translate(up, 0.0, y, 0.0);
  zs_gen_mul3(t, up, turn, move);
  if (xf) {
    double u[16];
    zs_mat_mul(u, xf, t);
    memcpy(t, u, sizeof t);
  }
  return zs_gen_torus(m, major, minor, 1.0, around, sides, 0, t, rgb, 0);
}

int zs_gen_pt(zs_gen_profile *pr, double r, double y) {
  if (!zs_grow((void **)&pr->pt, &pr->cap, (int64_t)pr->n + 1, 2 * sizeof *pr->pt)) return 0;
  pr->pt[2 * pr->n] = r;
  pr->pt[2 * pr->n + 1] = y;
  pr->n++;
  return 1;
}

int zs_gen_line_to(zs_gen_profile *pr, double r, double y, int steps) {
  double r0 = pr->pt[2 * pr->n - 2], y0 = pr->pt[2 * pr->n - 1];
  for (int i = 1; i <= steps; i++)
    if (!zs_gen_pt(pr, r0 + (r - r0) * i / steps, y0 + (y - y0) * i / steps)) return 0;
  return 1;
}

zs_status zs_gen_profile_lathe(zs_model *m, zs_gen_profile *pr, int complete, int around,
                               int caps, const double *xf, uint32_t rgb) {
  zs_status st = complete && pr->n ? zs_gen_lathe(m, pr->pt, pr->n, around, caps, xf, rgb, 0)
                                   : ZS_ERR_NOMEM;
  free(pr->pt);
  pr->pt = NULL;
  pr->n = pr->cap = 0;
  return st;
}

/* ---- mesh specs -------------------------------------------------------- */

static zs_status done(zs_status st, const zs_gen_args *a, zs_error *err) {
  if (st == ZS_OK) return ZS_OK;
  if (st == ZS_ERR_NOMEM) return ZS_GEN_NOMEM(err, a->spec);
  return zs_error_set(err, st, "%s: cannot build the mesh", a->spec);
}

static zs_status mesh_teapot(const zs_gen_args *a, zs_model *m, zs_error *err) {
  int32_t obj = zs_gen_model(m, "teapot", err);
  if (obj < 0) return err->code;
  return zs_teapot_add(m, zs_gen_int(a, "level"), NULL, ZS_GREY, obj, err);
}

static zs_status mesh_sphere(const zs_gen_args *a, zs_model *m, zs_error *err) {
  int32_t obj = zs_gen_model(m, "sphere", err);
  if (obj < 0) return err->code;
  return done(zs_gen_sphere(m, zs_gen_int(a, "slices"), zs_gen_int(a, "stacks"), NULL,
                            ZS_GREY, obj),
              a, err);
}

static zs_status box_of(const zs_gen_args *a, zs_model *m, const char *name, double x,
                        double y, double z, zs_error *err) {
  int32_t obj = zs_gen_model(m, name, err);
  if (obj < 0) return err->code;
  const double lo[3] = {-0.5 * x, -0.5 * y, -0.5 * z}, hi[3] = {0.5 * x, 0.5 * y, 0.5 * z};
  return done(zs_gen_box(m, lo, hi, NULL, ZS_GREY, obj), a, err);
}

static zs_status mesh_box(const zs_gen_args *a, zs_model *m, zs_error *err) {
  return box_of(a, m, "box", zs_gen_real(a, "x"), zs_gen_real(a, "y"), zs_gen_real(a, "z"),
                err);
}

static zs_status mesh_cube(const zs_gen_args *a, zs_model *m, zs_error *err) {
  double s = zs_gen_real(a, "size");
  return box_of(a, m, "cube", s, s, s, err);
}

/* Cylinder and cone: the unit shapes scaled to radius x height, centred. */
static zs_status round_of(const zs_gen_args *a, zs_model *m, const char *name, double r1,
                          zs_error *err) {
  int32_t obj = zs_gen_model(m, name, err);
  if (obj < 0) return err->code;
  double r = zs_gen_real(a, "radius"), h = zs_gen_real(a, "height");
  double xf[16];
  zs_mat_identity(xf);
  xf[0] = xf[10] = r;
  xf[5] = h;
  xf[7] = -0.5 * h;
  return done(zs_gen_cylinder(m, 1.0, r1, zs_gen_int(a, "segments"), zs_gen_int(a, "caps"),
                              xf, ZS_GREY, obj),
              a, err);
}

static zs_status mesh_cylinder(const zs_gen_args *a, zs_model *m, zs_error *err) {
  return round_of(a, m, "cylinder", 1.0, err);
}

static zs_status mesh_cone(const zs_gen_args *a, zs_model *m, zs_error *err) {
  return round_of(a, m, "cone", 0.0, err);
}

static zs_status mesh_torus(const zs_gen_args *a, zs_model *m, zs_error *err) {
  double major = zs_gen_real(a, "major"), minor = zs_gen_real(a, "minor");
  if (!(minor < major))
    return zs_error_set(err, ZS_ERR_ARG, "%s: minor must be less than major", a->spec);
  if (zs_gen_model(m, "torus", err) < 0) return err->code;
  return done(zs_gen_ring_y(m, major, minor, 0.0, zs_gen_int(a, "segments"),
                            zs_gen_int(a, "sides"), NULL, ZS_GREY),
              a, err);
}

#define SIZE(key, def) {key, ZS_GEN_REAL, 1e-6, 1e6, def}

static const zs_gen_param teapot_params[] = {
    {"level", ZS_GEN_INT, 1, ZS_TEAPOT_MAX_LEVEL, ZS_TEAPOT_DEFAULT_LEVEL}};
static const zs_gen_param sphere_params[] = {{"slices", ZS_GEN_INT, 3, 1024, 24},
                                             {"stacks", ZS_GEN_INT, 2, 1024, 24}};
static const zs_gen_param box_params[] = {SIZE("x", 1), SIZE("y", 1), SIZE("z", 1)};
static const zs_gen_param cube_params[] = {SIZE("size", 1)};
static const zs_gen_param round_params[] = {{"segments", ZS_GEN_INT, 3, 4096, 16},
                                            {"caps", ZS_GEN_INT, 0, 1, 1},
                                            SIZE("radius", 1),
                                            SIZE("height", 2)};
static const zs_gen_param torus_params[] = {SIZE("major", 1), SIZE("minor", 0.25),
                                            {"segments", ZS_GEN_INT, 3, 4096, 32},
                                            {"sides", ZS_GEN_INT, 3, 4096, 16}};

#define N(a) ((int)(sizeof a / sizeof a[0]))

const zs_gen_def zs_gen_mesh_defs[] = {
    {"teapot", teapot_params, N(teapot_params), NULL, mesh_teapot},
    {"sphere", sphere_params, N(sphere_params), NULL, mesh_sphere},
    {"box", box_params, N(box_params), NULL, mesh_box},
    {"cube", cube_params, N(cube_params), NULL, mesh_cube},
    {"cylinder", round_params, N(round_params), NULL, mesh_cylinder},
    {"cone", round_params, N(round_params), NULL, mesh_cone},
    {"torus", torus_params, N(torus_params), NULL, mesh_torus},
};
const int zs_gen_mesh_ndefs = N(zs_gen_mesh_defs);
