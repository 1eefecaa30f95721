/* The city of the conservative-visibility paper (PCVR): "buildings,
 * streets, cars: 25 objects, 23,400 triangles", walked through at street
 * level at 1024 x 768.
 *
 * LAYOUT (metres, y up, the city centred on the origin)
 *   blocks x blocks square blocks BLOCK wide between streets STREET wide
 *   (kerb to kerb); streets run along x and along z on every side of every
 *   block.  A block is a raised plate (pavement and lots); its inner
 *   BLOCK - 2 PAVEMENT square is cut into 2 x 2 lots, one building each.
 *   - building: a box of 11 .. 15 by 11 .. 15 m (set back at random in its
 *     lot) of FLOOR m floors, a window box on every floor of every facade
 *     (one per 3 m of facade), a roof slab, and on top a machine room (six
 *     floors or more) or, half of the time, a water tank.  The heights,
 *     3 .. 12 floors, are spread evenly over the buildings and shuffled, so
 *     every city has as many tall buildings as low ones and about the same
 *     number of triangles.  Walls in one of eight facade colours.  Each
 *     building is one object and one mesh.
 *   - cars: 2 blocks^2, each on its own street segment (between two
 *     crossings), in the right-hand lane, heading either way; a body, a
 *     cabin and four wheels (200 triangles), in a palette colour.  With
 *     moving = N the first N drive along their street (local x) at 0.2 ..
 *     0.5 m per frame, turning back at the edge of the city.
 *   - streets: one object: the ground slab, the block plates, dashed
 *     centre lines, and a street light in the middle of every block side.
 *   Objects: 4 blocks^2 buildings + 2 blocks^2 cars + 1 (blocks 2: 25).
 *   Triangles (blocks 2): 23,596 at the default seed; 23,419 on average
 *   over seeds 1 .. 200 (22,036 .. 24,620): the paper's 23,400.
 *   The random draws, in order: the order of the heights; per building
 *   (block by block, lot by lot) its size, set-back, facade colour and roof
 *   choice; the street segment order; per car its direction, place, colour
 *   and speed.
 *
 * VIEW AND WALK
 *   The camera stands at the west end of a middle street looking down it.
 *   The walk, at eye height EYE, goes down that street to the middle
 *   crossing, turns north, west along the north street, south, and east
 *   along the south street (open views along the streets, the view closed
 *   by buildings at every turn), then rises over the city.
 */
#include <math.h>
#include <stdlib.h>

#include "util/matrix.h"
#include "scene/gen_internal.h"

#define BLOCK 40.0
#define STREET 12.0
#define PAVEMENT 3.0
#define FLOOR 3.2
#define EYE 1.7
#define KERB 0.15 /* height of the block plates */

enum { MIN_FLOORS = 3, MAX_FLOORS = 12 };

static const uint32_t FACADES[8] = {0xC9B79Cu, 0xA65E46u, 0xD8D2C4u, 0x8C8C8Cu,
                                    0xB89F7Au, 0x7E8C8Au, 0xE0C9A6u, 0x9A6A55u};
#define GLASS_RGB 0x34495Eu
#define ROOF_RGB 0x6B6B6Bu
#define ROOFTOP_RGB 0x8A8A8Au
#define ROAD_RGB 0x45484Du
#define PLATE_RGB 0xA9A59Cu
#define MARK_RGB 0xE8E4D8u
#define POLE_RGB 0x5B6066u
#define LAMP_RGB 0xF2E6B8u
#define TYRE_RGB 0x222222u

static zs_status box(zs_model *m, double x0, double y0, double z0, double x1, double y1,
                     double z1, uint32_t rgb) {
  return zs_gen_box_at(m, x0, y0, z0, x1, y1, z1, NULL, rgb);
}

/* The upright rod of radius r from (x, y0, z) up to y1. */
static zs_status post(zs_model *m, double x, double z, double y0, double y1, double r,
                      int segments, uint32_t rgb) {
  const double a[3] = {x, y0, z}, b[3] = {x, y1, z};
  return zs_gen_rod(m, a, b, r, segments, rgb);
}

/* ---- buildings --------------------------------------------------------- */

/* Window boxes along one facade: the wall is the plane `axis` = w (axis 0:
 * x, 2: z), facing the side `out` (+1 or -1), spanning u0 .. u1 along the
 * other horizontal axis; floor 0 starts at height base. */
static zs_status windows(zs_model *m, int axis, double w, int out, double u0, double u1,
                         int floors, double base) {
  int n = (int)floor((u1 - u0 - 1.0) / 3.0);
  if (n < 1) n = 1;
  double bay = (u1 - u0) / n;
  /* The boxes stand 8 cm out of the wall. */
  double w0 = out > 0 ? w : w - 0.08, w1 = out > 0 ? w + 0.08 : w;
  for (int f = 0; f < floors; f++) {
    double y0 = base + f * FLOOR + 0.9, y1 = y0 + 1.8;
    for (int i = 0; i < n; i++) {
      double u = u0 + (i + 0.5) * bay;
      zs_status st = axis == 0 ? box(m, w0, y0, u - 0.7, w1, y1, u + 0.7, GLASS_RGB)
                               : box(m, u - 0.7, y0, w0, u + 0.7, y1, w1, GLASS_RGB);
      if (st != ZS_OK) return st;
    }
  }
  return ZS_OK;
}

/* One building of `floors` floors in the lot x0 .. x0 + lot, z0 .. z0 +
 * lot, on the plate. */
static zs_status building(zs_rng *rng, zs_model *m, double x0, double z0, double lot,
                          int floors) {
  double wx = zs_rng_range(rng, 11.0, 15.0);
  double wz = zs_rng_range(rng, 11.0, 15.0);
  double bx = x0 + zs_rng_range(rng, 0.5, lot - wx - 0.5);
  double bz = z0 + zs_rng_range(rng, 0.5, lot - wz - 0.5);
  uint32_t wall = FACADES[zs_rng_below(rng, 8)];
  int tank = zs_rng_below(rng, 2) == 0;
  double x1 = bx + wx, z1 = bz + wz, top = KERB + floors * FLOOR + 0.8;

  zs_status st = box(m, bx, KERB, bz, x1, top, z1, wall);
  if (st == ZS_OK) st = windows(m, 2, bz, -1, bx, x1, floors, KERB);
  if (st == ZS_OK) st = windows(m, 2, z1, +1, bx, x1, floors, KERB);
  if (st == ZS_OK) st = windows(m, 0, bx, -1, bz, z1, floors, KERB);
  if (st == ZS_OK) st = windows(m, 0, x1, +1, bz, z1, floors, KERB);
  if (st == ZS_OK)
    st = box(m, bx + 0.25, top, bz + 0.25, x1 - 0.25, top + 0.1, z1 - 0.25, ROOF_RGB);
  if (st != ZS_OK) return st;
  if (floors >= 6) {
    /* A machine room over the middle of the roof. */
    double cx = bx + 0.5 * wx, cz = bz + 0.5 * wz;
    return box(m, cx - 0.2 * wx, top + 0.1, cz - 0.2 * wz, cx + 0.2 * wx, top + 2.6,
               cz + 0.2 * wz, ROOFTOP_RGB);
  }
  if (tank)
    return post(m, bx + 0.3 * wx, bz + 0.3 * wz, top + 0.1, top + 3.0, 1.4, 12, ROOFTOP_RGB);
  return ZS_OK;
}

/* ---- cars -------------------------------------------------------------- */

/* A car along +x, centred on the origin, its wheels on y = 0. */
static zs_status car(zs_model *m, uint32_t paint) {
  zs_status st = box(m, -2.1, 0.3, -0.85, 2.1, 1.0, 0.85, paint);
  /* The cabin: narrower at the roof. */
  const double lo_b[3] = {-1.2, 1.0, -0.8}, hi_b[3] = {0.9, 1.0, 0.8};
  const double lo_t[3] = {-0.9, 1.55, -0.7}, hi_t[3] = {0.5, 1.55, 0.7};
  double c[8][3];
  for (int b = 0; b < 8; b++) {
    const double *lo = (b & 2) ? lo_t : lo_b, *hi = (b & 2) ? hi_t : hi_b;
    c[b][0] = (b & 1) ? hi[0] : lo[0];
    c[b][1] = lo[1];
    c[b][2] = (b & 4) ? hi[2] : lo[2];
  }
  if (st == ZS_OK) st = zs_gen_hexahedron(m, c, GLASS_RGB, 0);
  /* Wheels: cylinders turned from +y onto +z. */
  for (int w = 0; w < 4 && st == ZS_OK; w++) {
    double x = (w & 1) ? 1.35 : -1.35, z = (w & 2) ? 0.62 : -0.86;
    double size[16], turn[16], move[16], xf[16];
    zs_mat_scale(size, 0.32, 0.24, 0.32);
    zs_mat_rotate_turns(turn, 0.25, 1.0, 0.0, 0.0);
    zs_mat_translate(move, x, 0.32, z);
    zs_gen_mul3(xf, move, turn, size);
    st = zs_gen_cylinder(m, 1.0, 1.0, 12, 1, xf, TYRE_RGB, 0);
  }
  return st;
}

/* ---- streets ----------------------------------------------------------- */

typedef struct city {
  int n;          /* blocks per side */
  double half;    /* half the city's width, street edge to street edge */
} city;

/* The centre line of street k (0 .. n), along either axis. */
static double street_centre(const city *c, int k) {
  return -c->half + k * (BLOCK + STREET) + 0.5 * STREET;
}

/* The low corner of block i (0 .. n-1), along either axis. */
static double block_start(const city *c, int i) {
  return -c->half + STREET + i * (BLOCK + STREET);
}

static zs_status streets(const city *c, zs_model *m) {
  double e = c->half + 20.0;
  zs_status st = box(m, -e, -0.5, -e, e, 0.0, e, ROAD_RGB);
  for (int i = 0; i < c->n && st == ZS_OK; i++)
    for (int j = 0; j < c->n && st == ZS_OK; j++) {
      double x0 = block_start(c, i), z0 = block_start(c, j);
      st = box(m, x0, 0.0, z0, x0 + BLOCK, KERB, z0 + BLOCK, PLATE_RGB);
      /* A light in the middle of every side, on the pavement, its arm over
       * the road. */
      for (int side = 0; side < 4 && st == ZS_OK; side++)
        {
          double u = BLOCK / 2.0;
          double px, pz, ax, az; /* the pole, and the arm's direction */
          switch (side) {
            case 0: px = x0 + u; pz = z0 + 0.8; ax = 0; az = -1; break;
            case 1: px = x0 + u; pz = z0 + BLOCK - 0.8; ax = 0; az = 1; break;
            case 2: px = x0 + 0.8; pz = z0 + u; ax = -1; az = 0; break;
            default: px = x0 + BLOCK - 0.8; pz = z0 + u; ax = 1; az = 0; break;
          }
          st = post(m, px, pz, KERB, KERB + 6.0, 0.1, 8, POLE_RGB);
          double tx = px + 1.6 * ax, tz = pz + 1.6 * az;
          if (st == ZS_OK)
            st = box(m, fmin(px, tx) - 0.06, KERB + 5.9, fmin(pz, tz) - 0.06, fmax(px, tx) + 0.06,
                     KERB + 6.0, fmax(pz, tz) + 0.06, POLE_RGB);
          if (st == ZS_OK)
            st = box(m, tx - 0.3, KERB + 5.7, tz - 0.3, tx + 0.3, KERB + 5.9, tz + 0.3, LAMP_RGB);
        }
    }
  /* Dashed centre lines on every street segment between two crossings. */
  for (int k = 0; k <= c->n && st == ZS_OK; k++)
    for (int i = 0; i < c->n && st == ZS_OK; i++) {
      double s = street_centre(c, k), b = block_start(c, i);
      for (int d = 0; d < 6 && st == ZS_OK; d++) {
        double u = b + 2.0 + d * 6.5;
        st = box(m, u, 0.0, s - 0.08, u + 3.0, 0.02, s + 0.08, MARK_RGB);
        if (st == ZS_OK) st = box(m, s - 0.08, 0.0, u, s + 0.08, 0.02, u + 3.0, MARK_RGB);
      }
    }
  return st;
}

/* Keys at eye height along a walk through the points p (x, z) joined by
 * straight, axis-parallel legs: one at the start, then at every turn one
 * TURN metres before it, looking into the next leg, and one TURN metres
 * after it, looking along it; the last at the end.  Returns the count. */
#define TURN 6.0
#define LOOK 30.0
static int walk(const double (*p)[2], int n, zs_gen_key *keys) {
  int k = 0;
  for (int i = 0; i < n; i++) {
    /* d: the unit direction of the leg into p[i] (or out of it, at the
     * start); r: its right-hand side, 2 m out. */
    int from = i > 0 ? i - 1 : 0, to = i > 0 ? i : 1;
    double d[2] = {p[to][0] - p[from][0], p[to][1] - p[from][1]};
    double len = fabs(d[0]) + fabs(d[1]);
    d[0] /= len;
    d[1] /= len;
    double r[2] = {-2.0 * d[1], 2.0 * d[0]};
    if (i == 0 || i == n - 1) {
      double ex = p[i][0] + r[0], ez = p[i][1] + r[1];
      keys[k++] = (zs_gen_key){{ex, EYE, ez}, {ex + LOOK * d[0], EYE + 1.0, ez + LOOK * d[1]}};
      continue;
    }
    double o[2] = {p[i + 1][0] - p[i][0], p[i + 1][1] - p[i][1]};
    double olen = fabs(o[0]) + fabs(o[1]);
    o[0] /= olen;
    o[1] /= olen;
    double ro[2] = {-2.0 * o[1], 2.0 * o[0]};
    double bx = p[i][0] + r[0] - TURN * d[0], bz = p[i][1] + r[1] - TURN * d[1];
    keys[k++] = (zs_gen_key){{bx, EYE, bz},
                             {p[i][0] + LOOK * o[0], EYE + 1.0, p[i][1] + LOOK * o[1]}};
    double ax = p[i][0] + ro[0] + TURN * o[0], az = p[i][1] + ro[1] + TURN * o[1];
    keys[k++] = (zs_gen_key){{ax, EYE, az}, {ax + LOOK * o[0], EYE + 1.0, az + LOOK * o[1]}};
  }
  return k;
}

/* ---- the scene --------------------------------------------------------- */

/* Four buildings on every block, each its own mesh. */
static zs_status add_buildings(const zs_gen_args *a, const city *c, zs_rng *rng, zs_scene *s,
                               zs_error *err) {
  int n = c->n;
  /* The heights: MIN_FLOORS .. MAX_FLOORS spread evenly over the
   * buildings, in a shuffled order, so the city always has as many tall
   * as low ones (and about the same number of triangles). */
  int nb = 4 * n * n, b = 0;
  int *floors = malloc((size_t)nb * sizeof *floors);
  if (!floors) return ZS_GEN_NOMEM(err, a->spec);
  for (int k = 0; k < nb; k++)
    floors[k] = MIN_FLOORS + (MAX_FLOORS - MIN_FLOORS + 1) * k / nb;
  zs_rng_shuffle(rng, floors, (size_t)nb, sizeof *floors);

  double lot = 0.5 * (BLOCK - 2.0 * PAVEMENT);
  zs_model m;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++)
      for (int l = 0; l < 4; l++) {
        double x0 = block_start(c, i) + PAVEMENT + (l & 1) * lot;
        double z0 = block_start(c, j) + PAVEMENT + (l >> 1) * lot;
        int32_t mesh = -1;
        if (zs_gen_model(&m, "building", err) >= 0) {
          if (building(rng, &m, x0, z0, lot, floors[b++]) == ZS_OK)
            mesh = zs_gen_add_mesh(s, &m, err);
          else
            ZS_GEN_NOMEM(err, a->spec);
        }
        zs_model_free(&m); /* empty unless building() failed */
        if (mesh < 0 || zs_gen_add_instance(s, mesh, NULL, ZS_RGB_MESH, err,
                                            "building_%d_%d_%d", i, j, l) < 0) {
          free(floors);
          return err->code;
        }
      }
  free(floors);
  return ZS_OK;
}

/* ncars cars on distinct street segments, the first `moving` driving. */
static zs_status add_cars(const zs_gen_args *a, const city *c, zs_rng *rng, int ncars,
                          int moving, zs_scene *s, zs_error *err) {
  int n = c->n;
  /* Street segments: along x (axis 0) or z, on street k, between crossings
   * i and i+1; numbered (axis (n+1) + k) n + i. */
  int nseg = 2 * (n + 1) * n;
  int *seg = malloc((size_t)nseg * sizeof *seg);
  if (!seg) return ZS_GEN_NOMEM(err, a->spec);
  for (int i = 0; i < nseg; i++) seg[i] = i;
  zs_rng_shuffle(rng, seg, (size_t)nseg, sizeof *seg);
  zs_model m;
  for (int k = 0; k < ncars; k++) {
    int axis = seg[k] / ((n + 1) * n), street = seg[k] / n % (n + 1), i = seg[k] % n;
    int forward = zs_rng_below(rng, 2) == 0;
    double along = block_start(c, i) + zs_rng_range(rng, 4.0, BLOCK - 4.0);
    uint32_t paint = zs_gen_palette((int)zs_rng_below(rng, ZS_GEN_PALETTE_SIZE));
    double speed = zs_rng_range(rng, 0.2, 0.5);
    /* Driving on the right: heading +x, the right-hand side is +z. */
    double lane = street_centre(c, street) + (forward ? 3.0 : -3.0);
    double heading = forward ? 0.0 : 0.5;
    double x = along, z = lane;
    if (axis == 1) {
      /* Along z: heading +z is a quarter turn clockwise seen from above,
       * and its right-hand side is -x. */
      heading = forward ? -0.25 : 0.25;
      x = street_centre(c, street) + (forward ? -3.0 : 3.0);
      z = along;
    }
    int32_t mesh = -1, in = -1;
    if (zs_gen_model(&m, "car", err) >= 0) {
      if (car(&m, paint) == ZS_OK) mesh = zs_gen_add_mesh(s, &m, err);
      else ZS_GEN_NOMEM(err, a->spec);
    }
    zs_model_free(&m); /* empty unless car() failed */
    if (mesh >= 0) {
      double turn[16], move[16], place[16];
      zs_mat_rotate_turns(turn, heading, 0.0, 1.0, 0.0);
      zs_mat_translate(move, x, 0.0, z);
      zs_mat_mul(place, move, turn);
      in = zs_gen_add_instance(s, mesh, place, ZS_RGB_MESH, err, "car_%d", k);
    }
    if (in < 0) {
      free(seg);
      return err->code;
    }
    if (k < moving) zs_gen_move_along_x(s, in, speed);
  }
  free(seg);
  return ZS_OK;
}

/* The camera and the walk: from outside the city down a middle street
 * (mid) to the middle crossing, then round the outer streets and back
 * towards the start.  The walker keeps 2 m right of the centre line;
 * before each crossing it looks into the street it turns into. */
static zs_status city_walk(const zs_gen_args *a, const city *c, zs_scene *s, zs_error *err) {
  int n = c->n, mid = (n + 1) / 2;
  double w = street_centre(c, 0), e = street_centre(c, n), mm = street_centre(c, mid);
  const double route[][2] = {{w - 25.0, mm}, {mm, mm}, {mm, e}, {e, e},
                             {e, w},         {w, w},   {w, mm - 10.0}};
  enum { NROUTE = sizeof route / sizeof route[0] };
  /* With one block the middle street is an outer one: drop the corners
   * that coincide. */
  double corners[NROUTE][2];
  int ncorners = 0;
  for (int i = 0; i < NROUTE; i++)
    if (ncorners == 0 || route[i][0] != corners[ncorners - 1][0] ||
        route[i][1] != corners[ncorners - 1][1]) {
      corners[ncorners][0] = route[i][0];
      corners[ncorners][1] = route[i][1];
      ncorners++;
    }
  zs_gen_key keys[2 * NROUTE + 3];
  int nkeys = walk((const double(*)[2])corners, ncorners, keys);
  /* Then on up the street, slowly rising, and over the city. */
  const zs_gen_key over[3] = {
      {{w + 2.0, 4.0, mm + 8.0}, {w + 2.0, 4.0, mm + 8.0 + LOOK}},
      {{w - 10.0, 30.0, mm + 40.0}, {0.0, 0.0, 0.0}},
      {{0.5 * e, 40.0 + c->half, 1.5 * c->half + 30.0}, {0.0, 0.0, 0.0}}};
  for (int i = 0; i < 3; i++) keys[nkeys++] = over[i];

  const double eye[3] = {w - 25.0, 6.0, mm + 2.0};
  const double target[3] = {w + 15.0, 8.0, mm + 2.0};
  zs_gen_camera(s, eye, target, 0.1, 6.0 * c->half + 200.0);
  return zs_gen_path(s, keys, nkeys, zs_gen_int(a, "frames"), err);
}

static zs_status build_city(const zs_gen_args *a, zs_scene *s, zs_error *err) {
  int n = zs_gen_int(a, "blocks"), ncars = 2 * n * n;
  int moving = zs_gen_int(a, "moving");
  if (zs_gen_check_moving(a, moving, ncars, "the cars", err)) return err->code;
  city c = {n, 0.5 * (n * BLOCK + (n + 1) * STREET)};
  zs_rng rng;
  zs_rng_seed(&rng, a->seed);
  if (add_buildings(a, &c, &rng, s, err) || add_cars(a, &c, &rng, ncars, moving, s, err))
    return err->code;

  zs_model m;
  if (zs_gen_model(&m, "streets", err) < 0) return err->code;
  if (streets(&c, &m)) {
    zs_model_free(&m);
    return ZS_GEN_NOMEM(err, a->spec);
  }
  int32_t mesh = zs_gen_add_mesh(s, &m, err);
  if (mesh < 0 || zs_gen_add_instance(s, mesh, NULL, ZS_RGB_MESH, err, "streets") < 0)
    return err->code;
  return city_walk(a, &c, s, err);
}

static const zs_gen_param city_params[] = {
    {"blocks", ZS_GEN_INT, 1, 8, 2},
    {"moving", ZS_GEN_INT, 0, 128, 0},
    {"seed", ZS_GEN_SEED, 0, 0, 0},
    {"frames", ZS_GEN_INT, 16, 100000, 400}};

const zs_gen_def zs_gen_city_def = {"city", city_params, 4, build_city, NULL};
