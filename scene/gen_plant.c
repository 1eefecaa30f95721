/* A stand-in for UNC's Powerplant model (the CHC paper's second scene:
 * 1,185 objects, 12.7 M triangles, high and very uneven depth complexity):
 * a power station generated from a seed.
 *
 * LAYOUT (metres, y up; the hall spans x 0 .. 150, z 0 .. 60, 40 high)
 *   Hall: four outer walls with doors and high window openings, a roof, two
 *   inner walls with doorways at x = 50 and x = 100 cutting it into bays,
 *   steel columns along the long walls.
 *   - Bay A (x 0 .. 50), boiler house: four boilers (vertical vessels 11 m
 *     wide, 33 m tall, stiffening rings, manways) with two railed
 *     platforms each; flue ducts to the stack outside.
 *   - Bay B (x 50 .. 100), turbine hall: two turbine-generator sets (47 m
 *     long, on concrete tables) either side of a walkway, an overhead
 *     crane on its rails.
 *   - Bay C (x 100 .. 150), auxiliary bay: two decks (10.4 and 20.4 m) on
 *     columns and beams, with a stair well and railings; pumps, tanks and
 *     heat exchangers on the floor and on both decks.
 *   Outside: the stack, two cooling towers, a tank farm reached over a pipe
 *   rack, transformers, the ground.
 *   Pipe runs join the equipment: main steam (boilers to turbines), feed
 *   water, cooling water (towers to turbines), runs within each bay and out
 *   to the tank farm.  A run rises from its start, crosses at a random
 *   height and lane, and comes down to its end; every straight piece,
 *   elbow, flange (with its eight bolts and nuts) and valve is an object.
 *
 * SIZE
 *   The same objects at every detail: 1,223 at the default seed, 1,109 ..
 *   1,223 over seeds 1 .. 50 (mean 1,174; runs differ in their legs, and a
 *   run that finds no room is left out).  `detail` scales the
 *   tessellation: segments around a round part and rings along it are
 *   their full-size counts times detail (at least a small minimum).
 *   detail = 1 is the full size: 4,072,508 triangles at the default seed
 *   (3.9 .. 4.1 M for others); the default 0.25 has 425,668.
 *
 * MESHES
 *   Every kind of part is one mesh, shared by its instances (a boiler mesh
 *   for the four boilers, one elbow for every elbow, scaled by the pipe's
 *   radius), so memory and load time follow the number of kinds, not the
 *   number of triangles drawn.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/exactmath.h"
#include "util/compiler.h"
#include "util/matrix.h"
#include "scene/gen_internal.h"

/* ---- colours ----------------------------------------------------------- */

#define WALL_RGB 0xB9B2A6u
#define INNER_WALL_RGB 0xA8A196u
#define ROOF_RGB 0x7D7A74u
#define GROUND_RGB 0x6E6A60u
#define DECK_RGB 0x8F8A80u
#define STEEL_RGB 0x5E6B78u
#define PLATFORM_RGB 0x707880u
#define RAILING_RGB 0xE0B020u
#define BOILER_RGB 0xC9CED3u
#define CASING_RGB 0x3D6E8Fu
#define GENERATOR_RGB 0x2F5D3Au
#define SHAFT_RGB 0x555555u
#define CONCRETE_RGB 0x9E978Bu
#define TANK_RGB 0xD4D0C8u
#define HX_RGB 0x7A8B99u
#define MOTOR_RGB 0x2E5C8Au
#define PUMP_RGB 0x6F7479u
#define VALVE_RGB 0x4A4F55u
#define WHEEL_RGB 0xB3261Eu
#define DUCT_RGB 0x8C8782u
#define STACK_RGB 0xB0A89Cu
#define BAND_RGB 0xB3261Eu
#define TOWER_RGB 0xC4BFB5u
#define CRANE_RGB 0xE3A72Fu
#define TRANSFORMER_RGB 0x5D6D5Fu
#define INSULATOR_RGB 0x8A5A3Cu
#define BOLT_RGB 0x3A3A3Au

/* Pipe services. */
#define STEAM_RGB 0xC8CCD0u
#define FEED_RGB 0x4E8F5Au
#define COOLING_RGB 0x3A6EA5u
#define OIL_RGB 0x8B5A2Bu
#define GAS_RGB 0xD9B038u
#define FIRE_RGB 0xB33A3Au
#define AIR_RGB 0x7FB3D5u

static const uint32_t SERVICES[] = {FEED_RGB, OIL_RGB, GAS_RGB, FIRE_RGB, AIR_RGB, STEAM_RGB};
enum { NSERVICES = sizeof SERVICES / sizeof SERVICES[0] };

/* ---- dimensions -------------------------------------------------------- */

#define HALL_X 150.0
#define HALL_Z 60.0
#define HALL_H 40.0
#define DECK1 10.0 /* deck bottoms; 0.4 thick */
#define DECK2 20.0
#define DECK_T 0.4
#define ELBOW 3.0  /* an elbow's bend radius, in pipe radii */

static const double BOILERS[4][2] = {{14, 16}, {36, 16}, {14, 44}, {36, 44}};
#define BOILER_R 5.5
static const double TURBINES[2] = {62.0, 88.0}; /* x of the axes */
#define TURBINE_Z 8.0
#define TABLE_H 8.0

/* ---- the generator's state --------------------------------------------- */

enum mesh_kind {
  M_BOX, M_BEAM, M_PIPE, M_ELBOW, M_FLANGE, M_VALVE, M_BOILER, M_PLATFORM,
  M_TURBINE, M_TANK, M_HX, M_PUMP, M_RAILING, M_STAIR, M_STACK, M_TOWER,
  M_CRANE, M_TRANSFORMER, NMESH_KINDS
};

enum pool { BOILER_TOP, BOILER_SIDE, TURBINE_IN, TURBINE_SIDE, BAY_C_FLOOR, BAY_C, OUTSIDE,
            TOWER, NPOOLS };

enum { MAX_NOZZLES = 64 };

typedef struct plant {
  zs_scene *s;
  zs_rng rng;
  double detail;
  zs_error *err;
  int32_t mesh[NMESH_KINDS];
  double nozzle[NPOOLS][MAX_NOZZLES][3];  /* pipe ends, pipes leave upwards */
  int nnozzles[NPOOLS];
  int nruns;
} plant;

static zs_status nomem(plant *p) { return ZS_GEN_NOMEM(p->err, "plant"); }

static zs_status add(plant *p, int32_t mesh, const double m[16], uint32_t rgb,
                     const char *fmt, ...) ZS_PRINTF_LIKE(5, 6);

static zs_status add(plant *p, int32_t mesh, const double m[16], uint32_t rgb,
                     const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int32_t i = zs_gen_add_instance_v(p->s, mesh, m, rgb, p->err, fmt, ap);
  va_end(ap);
  return i < 0 ? p->err->code : ZS_OK;
}

static void add_nozzle(plant *p, enum pool pool, const double at[3]) {
  if (p->nnozzles[pool] < MAX_NOZZLES)
    memcpy(p->nozzle[pool][p->nnozzles[pool]++], at, 3 * sizeof(double));
}

static int seg(const plant *p, double full, int min) {
  return zs_gen_segments(full, p->detail, min);
}

#define TRY(expr)                      \
  do {                                 \
    zs_status try_st_ = (expr);        \
    if (try_st_ != ZS_OK) return try_st_; \
  } while (0)

/* ---- placing ------------------------------------------------------------ */

static zs_status add_box(plant *p, double x0, double y0, double z0, double x1, double y1,
                         double z1, uint32_t rgb, const char *name) {
  const double lo[3] = {x0, y0, z0}, hi[3] = {x1, y1, z1};
  double m[16];
  zs_gen_box_matrix(m, lo, hi);
  return add(p, p->mesh[M_BOX], m, rgb, "%s", name);
}

/* The I-beam mesh (local y from 0 to 1, flanges across x) between two
 * points, its section w x w. */
static zs_status add_beam(plant *p, const double from[3], const double to[3], double w,
                          const char *fmt, int i) {
  double m[16];
  zs_gen_between(m, from, to, w);
  return add(p, p->mesh[M_BEAM], m, STEEL_RGB, fmt, i);
}

/* ---- meshes --------------------------------------------------------------
 * Each builds into a fresh model; colours are the mesh's own where its
 * instances keep them (ZS_RGB_MESH), grey where instances give one. */

/* The upper dished head of a vessel of radius 1: a quarter ellipse in head
 * steps from the shell's top at y to the axis at y + 0.5. */
static int upper_head(zs_gen_profile *pr, int head, double y) {
  for (int i = 1; i <= head; i++) {
    double s, c;
    zs_sincos_turns(0.25 * (1.0 - (double)i / head), &s, &c);
    if (!zs_gen_pt(pr, i == head ? 0.0 : s, y + 0.5 * c)) return 0;
  }
  return 1;
}

/* The boiler: radius 1, 6 high (scaled by BOILER_R): a skirt, a 2:1
 * elliptical bottom head, the shell from y = 1 to 5.5 with stiffening
 * rings, the top head, manways, a steam nozzle on top (to y = 6.25). */
static zs_status mesh_boiler(const plant *p, zs_model *m) {
  int around = seg(p, 384, 12), head = seg(p, 48, 3), shell = seg(p, 160, 2);
  double s0, c0;
  zs_sincos_turns(0.15, &s0, &c0);
  zs_gen_profile pr = {0};
  int ok = zs_gen_pt(&pr, 0.0, 0.0) && zs_gen_pt(&pr, s0, 0.0);
  for (int i = 0; i <= head && ok; i++) {
    double s, c;
    zs_sincos_turns(0.15 + 0.1 * i / head, &s, &c);
    ok = zs_gen_pt(&pr, s, 1.0 - 0.5 * c);
  }
  ok = ok && zs_gen_line_to(&pr, 1.0, 5.5, shell);
  ok = ok && upper_head(&pr, head, 5.5);
  TRY(zs_gen_profile_lathe(m, &pr, ok, around, 0, NULL, BOILER_RGB));
  for (int k = 0; k < 5; k++)
    TRY(zs_gen_ring_y(m, 1.02, 0.035, 1.8 + 0.8 * k, around, seg(p, 16, 4), NULL, BOILER_RGB));
  /* Manways: short nozzles out of the shell at two heights, four sides. */
  for (int k = 0; k < 8; k++) {
    double sa, ca;
    zs_sincos_turns(0.125 * k + (k >= 4 ? 0.0625 : 0.0), &sa, &ca);
    double y = k < 4 ? 1.6 : 4.4;
    const double a[3] = {0.95 * ca, y, -0.95 * sa}, b[3] = {1.2 * ca, y, -1.2 * sa};
    TRY(zs_gen_rod(m, a, b, 0.12, seg(p, 48, 6), BOILER_RGB));
  }
  const double a[3] = {0.0, 5.9, 0.0}, b[3] = {0.0, 6.25, 0.0};
  return zs_gen_rod(m, a, b, 0.09, seg(p, 48, 6), BOILER_RGB);
}

/* A square platform 16 x 16 around a hole of 12 x 12, 0.3 thick, top at
 * y = 0, railed along its outer edge (posts every 2 m, two rails). */
static zs_status mesh_platform(const plant *p, zs_model *m) {
  TRY(zs_gen_box_at(m, -8, -0.3, -8, 8, 0, -6, NULL, PLATFORM_RGB));
  TRY(zs_gen_box_at(m, -8, -0.3, 6, 8, 0, 8, NULL, PLATFORM_RGB));
  TRY(zs_gen_box_at(m, -8, -0.3, -6, -6, 0, 6, NULL, PLATFORM_RGB));
  TRY(zs_gen_box_at(m, 6, -0.3, -6, 8, 0, 6, NULL, PLATFORM_RGB));
  for (int side = 0; side < 4; side++) {
    for (int k = 0; k < 8; k++) {
      double u = -7.8 + 2.0 * k, x = side < 2 ? u : (side == 2 ? -7.85 : 7.85);
      double z = side < 2 ? (side == 0 ? -7.85 : 7.85) : -u;
      const double a[3] = {x, 0.0, z}, b[3] = {x, 1.1, z};
      TRY(zs_gen_rod(m, a, b, 0.03, seg(p, 12, 4), RAILING_RGB));
    }
    for (int r = 0; r < 2; r++) {
      double y = r ? 1.1 : 0.55;
      if (side < 2) {
        double z = side == 0 ? -7.85 : 7.85;
        TRY(zs_gen_box_at(m, -7.9, y - 0.03, z - 0.03, 7.9, y + 0.03, z + 0.03, NULL, RAILING_RGB));
      } else {
        double x = side == 2 ? -7.85 : 7.85;
        TRY(zs_gen_box_at(m, x - 0.03, y - 0.03, -7.9, x + 0.03, y + 0.03, 7.9, NULL, RAILING_RGB));
      }
    }
  }
  return ZS_OK;
}

/* A turbine-generator set along +z from z = 0 to 47, its axis 2.5 above
 * the table (y = 0): HP, IP and two LP casings, the ribbed generator,
 * bearing pedestals, steam inlets on top of HP and IP (to y = 5.5). */
static zs_status mesh_turbine(const plant *p, zs_model *m) {
  int around = seg(p, 256, 12);
  double up[16], turn[16], xf[16];
  zs_mat_translate(up, 0.0, 2.5, 0.0);
  zs_mat_rotate_turns(turn, 0.25, 1.0, 0.0, 0.0); /* +y onto +z */
  zs_mat_mul(xf, up, turn);
#define RINGS(len) seg(p, 4.0 * (len), 1)
  zs_gen_profile pr = {0};
  int ok = zs_gen_pt(&pr, 0.0, 0.0) && zs_gen_pt(&pr, 0.35, 0.0) && zs_gen_pt(&pr, 0.35, 2.0) &&
           zs_gen_pt(&pr, 1.3, 2.0) && zs_gen_line_to(&pr, 1.7, 2.8, 1) &&
           zs_gen_line_to(&pr, 1.7, 9.2, RINGS(6.4)) && zs_gen_line_to(&pr, 1.3, 10.0, 1) &&
           zs_gen_pt(&pr, 0.35, 10.0) && zs_gen_pt(&pr, 0.35, 11.0) && zs_gen_pt(&pr, 2.1, 11.0) &&
           zs_gen_line_to(&pr, 2.1, 18.0, RINGS(7)) && zs_gen_pt(&pr, 0.35, 18.0);
  for (int lp = 0; lp < 2 && ok; lp++) {
    double y = 19.0 + 10.0 * lp;
    ok = zs_gen_pt(&pr, 0.35, y) && zs_gen_pt(&pr, 2.6, y) &&
         zs_gen_line_to(&pr, 3.3, y + 2.0, RINGS(2)) &&
         zs_gen_line_to(&pr, 3.3, y + 7.0, RINGS(5)) &&
         zs_gen_line_to(&pr, 2.6, y + 9.0, RINGS(2)) && zs_gen_pt(&pr, 0.35, y + 9.0);
  }
  ok = ok && zs_gen_pt(&pr, 0.0, 38.0);
  TRY(zs_gen_profile_lathe(m, &pr, ok, around, 0, xf, CASING_RGB));
  /* The generator: ribs every so often along its barrel. */
  int ribs = seg(p, 24, 3);
  ok = zs_gen_pt(&pr, 0.0, 38.5) && zs_gen_pt(&pr, 0.35, 38.5) && zs_gen_pt(&pr, 0.35, 39.0) &&
       zs_gen_pt(&pr, 2.3, 39.0);
  for (int k = 0; k < ribs && ok; k++) {
    double y = 39.0 + 7.0 * (k + 0.5) / ribs;
    ok = zs_gen_line_to(&pr, 2.3, y - 0.1, 1) && zs_gen_pt(&pr, 2.45, y - 0.1) &&
         zs_gen_pt(&pr, 2.45, y + 0.1) && zs_gen_pt(&pr, 2.3, y + 0.1);
  }
  ok = ok && zs_gen_line_to(&pr, 2.3, 46.0, 1) && zs_gen_pt(&pr, 0.35, 46.0) &&
       zs_gen_pt(&pr, 0.35, 47.0) && zs_gen_pt(&pr, 0.0, 47.0);
  TRY(zs_gen_profile_lathe(m, &pr, ok, around, 0, xf, GENERATOR_RGB));
#undef RINGS
  static const double bearings[] = {0.9, 10.5, 18.5, 28.5, 38.2, 46.5};
  for (int k = 0; k < 6; k++)
    TRY(zs_gen_box_at(m, -1.0, 0.0, bearings[k] - 0.4, 1.0, 2.5, bearings[k] + 0.4, NULL,
                      SHAFT_RGB));
  static const double inlets[2][2] = {{6.0, 1.6}, {14.5, 2.0}};
  for (int k = 0; k < 2; k++) {
    const double a[3] = {0.0, 2.5 + inlets[k][1] - 0.2, inlets[k][0]};
    const double b[3] = {0.0, 5.5, inlets[k][0]};
    TRY(zs_gen_rod(m, a, b, 0.45, seg(p, 48, 8), CASING_RGB));
  }
  return ZS_OK;
}

/* A vertical tank: radius 1, shell to y = 1, a conical roof to 1.15 and a
 * nozzle to 1.22 (instances scale x and z by the radius, y by the
 * height). */
static zs_status mesh_tank(const plant *p, zs_model *m) {
  zs_gen_profile pr = {0};
  int ok = zs_gen_pt(&pr, 0.0, 0.0) && zs_gen_pt(&pr, 1.0, 0.0) &&
           zs_gen_line_to(&pr, 1.0, 1.0, seg(p, 40, 1)) &&
           zs_gen_line_to(&pr, 0.12, 1.15, seg(p, 8, 1)) && zs_gen_pt(&pr, 0.12, 1.22) &&
           zs_gen_pt(&pr, 0.0, 1.22);
  TRY(zs_gen_profile_lathe(m, &pr, ok, seg(p, 192, 12), 0, NULL, TANK_RGB));
  /* A ring stiffener under the roof and one at mid height. */
  TRY(zs_gen_ring_y(m, 1.01, 0.012, 0.5, seg(p, 192, 12), seg(p, 8, 3), NULL, TANK_RGB));
  return zs_gen_ring_y(m, 1.01, 0.012, 0.98, seg(p, 192, 12), seg(p, 8, 3), NULL, TANK_RGB);
}

/* A horizontal heat exchanger, radius 1, along z from -3 to 3, its axis 1.6
 * above the floor: elliptical heads, channel flanges, two saddles, two
 * nozzles on top (to y = 2.9 at z = -2 and 2). */
static zs_status mesh_hx(const plant *p, zs_model *m) {
  int around = seg(p, 256, 12), head = seg(p, 24, 2), shell = seg(p, 80, 1);
  double up[16], turn[16], xf[16];
  zs_mat_translate(up, 0.0, 1.6, -3.0);
  zs_mat_rotate_turns(turn, 0.25, 1.0, 0.0, 0.0);
  zs_mat_mul(xf, up, turn);
  zs_gen_profile pr = {0};
  int ok = zs_gen_pt(&pr, 0.0, 0.0);
  for (int i = 1; i <= head && ok; i++) {
    double s, c;
    zs_sincos_turns(0.25 * i / head, &s, &c);
    ok = zs_gen_pt(&pr, s, 0.5 - 0.5 * c);
  }
  ok = ok && zs_gen_line_to(&pr, 1.0, 0.9, 1) && zs_gen_pt(&pr, 1.12, 0.9) &&
       zs_gen_pt(&pr, 1.12, 1.05) && zs_gen_pt(&pr, 1.0, 1.05) &&
       zs_gen_line_to(&pr, 1.0, 4.95, shell) && zs_gen_pt(&pr, 1.12, 4.95) &&
       zs_gen_pt(&pr, 1.12, 5.1) && zs_gen_pt(&pr, 1.0, 5.1) && zs_gen_line_to(&pr, 1.0, 5.5, 1);
  ok = ok && upper_head(&pr, head, 5.5);
  TRY(zs_gen_profile_lathe(m, &pr, ok, around, 0, xf, HX_RGB));
  for (int k = -1; k <= 1; k += 2) {
    TRY(zs_gen_box_at(m, -0.9, 0.0, 1.8 * k - 0.2, 0.9, 1.0, 1.8 * k + 0.2, NULL, STEEL_RGB));
    const double a[3] = {0.0, 2.4, 2.0 * k}, b[3] = {0.0, 2.9, 2.0 * k};
    TRY(zs_gen_rod(m, a, b, 0.15, seg(p, 32, 6), HX_RGB));
  }
  return ZS_OK;
}

/* A pump set along z: base plate, finned motor, coupling, volute casing,
 * suction and discharge (to (0.5, 1.8, 0.55)). */
static zs_status mesh_pump(const plant *p, zs_model *m) {
  TRY(zs_gen_box_at(m, -0.6, 0.0, -1.6, 0.6, 0.25, 1.6, NULL, PUMP_RGB));
  double up[16], turn[16], xf[16];
  zs_mat_translate(up, 0.0, 0.75, -1.5);
  zs_mat_rotate_turns(turn, 0.25, 1.0, 0.0, 0.0);
  zs_mat_mul(xf, up, turn);
  int fins = seg(p, 20, 3);
  zs_gen_profile pr = {0};
  int ok = zs_gen_pt(&pr, 0.0, 0.0) && zs_gen_pt(&pr, 0.45, 0.0);
  for (int k = 0; k < fins && ok; k++) {
    double y = 0.1 + 1.2 * k / fins, w = 0.6 / fins;
    ok = zs_gen_line_to(&pr, 0.45, y, 1) && zs_gen_pt(&pr, 0.55, y) &&
         zs_gen_pt(&pr, 0.55, y + w) && zs_gen_pt(&pr, 0.45, y + w);
  }
  ok = ok && zs_gen_line_to(&pr, 0.45, 1.4, 1) && zs_gen_pt(&pr, 0.0, 1.4);
  TRY(zs_gen_profile_lathe(m, &pr, ok, seg(p, 64, 8), 0, xf, MOTOR_RGB));
  TRY(zs_gen_box_at(m, -0.5, 0.25, -1.45, 0.5, 0.35, -0.15, NULL, MOTOR_RGB));
  const double c0[3] = {0.0, 0.75, -0.15}, c1[3] = {0.0, 0.75, 0.3};
  TRY(zs_gen_rod(m, c0, c1, 0.15, seg(p, 32, 6), SHAFT_RGB));
  /* The volute: a torus around the shaft (its axis z). */
  double move[16], at[16];
  zs_mat_translate(move, -0.35, 0.0, 0.0);
  zs_mat_translate(at, 0.0, 0.75, 0.55);
  zs_mat_mul(xf, at, move);
  TRY(zs_gen_torus(m, 0.35, 0.22, 1.0, seg(p, 48, 8), seg(p, 24, 6), 0, xf, PUMP_RGB, 0));
  TRY(zs_gen_box_at(m, -0.3, 0.25, 0.35, 0.3, 0.5, 0.75, NULL, PUMP_RGB));
  const double s0[3] = {0.0, 0.75, 0.55}, s1[3] = {0.0, 0.75, 1.3};
  TRY(zs_gen_rod(m, s0, s1, 0.14, seg(p, 32, 6), PUMP_RGB));
  const double d0[3] = {0.5, 0.75, 0.55}, d1[3] = {0.5, 1.8, 0.55};
  return zs_gen_rod(m, d0, d1, 0.12, seg(p, 32, 6), PUMP_RGB);
}

/* A flange with its bolts, for a pipe of radius 1 along y: a disc to
 * radius 1.8, hubs, and 8 studs with a hexagonal nut on either face. */
static zs_status mesh_flange(const plant *p, zs_model *m) {
  zs_gen_profile pr = {0};
  int ok = zs_gen_pt(&pr, 0.0, -0.35) && zs_gen_pt(&pr, 1.15, -0.35) &&
           zs_gen_pt(&pr, 1.15, -0.2) && zs_gen_pt(&pr, 1.8, -0.2) && zs_gen_pt(&pr, 1.8, 0.2) &&
           zs_gen_pt(&pr, 1.15, 0.2) && zs_gen_pt(&pr, 1.15, 0.35) && zs_gen_pt(&pr, 0.0, 0.35);
  TRY(zs_gen_profile_lathe(m, &pr, ok, seg(p, 48, 8), 0, NULL, 0x808080u));
  for (int k = 0; k < 8; k++) {
    double s, c;
    zs_sincos_turns((k + 0.5) / 8.0, &s, &c);
    double x = 1.5 * c, z = -1.5 * s;
    const double a[3] = {x, -0.5, z}, b[3] = {x, 0.5, z};
    TRY(zs_gen_rod(m, a, b, 0.09, 6, BOLT_RGB));
    for (int side = -1; side <= 1; side += 2) {
      const double n0[3] = {x, side * 0.2, z}, n1[3] = {x, side * 0.38, z};
      TRY(zs_gen_rod(m, side < 0 ? n1 : n0, side < 0 ? n0 : n1, 0.17, 6, BOLT_RGB));
    }
  }
  return ZS_OK;
}

/* A gate valve for a pipe of radius 1 along y, centred on the origin: the
 * body with flanged ends, a bonnet along +x, the stem, the handwheel. */
static zs_status mesh_valve(const plant *p, zs_model *m) {
  zs_gen_profile pr = {0};
  int ok = zs_gen_pt(&pr, 0.0, -2.2) && zs_gen_pt(&pr, 1.6, -2.2) && zs_gen_pt(&pr, 1.6, -1.9) &&
           zs_gen_pt(&pr, 1.05, -1.9) && zs_gen_line_to(&pr, 1.3, -1.2, 1) &&
           zs_gen_line_to(&pr, 1.7, -0.5, 1) && zs_gen_line_to(&pr, 1.7, 0.5, seg(p, 4, 1)) &&
           zs_gen_line_to(&pr, 1.3, 1.2, 1) && zs_gen_line_to(&pr, 1.05, 1.9, 1) &&
           zs_gen_pt(&pr, 1.6, 1.9) && zs_gen_pt(&pr, 1.6, 2.2) && zs_gen_pt(&pr, 0.0, 2.2);
  TRY(zs_gen_profile_lathe(m, &pr, ok, seg(p, 48, 8), 0, NULL, VALVE_RGB));
  const double b0[3] = {1.2, 0.0, 0.0}, b1[3] = {3.5, 0.0, 0.0};
  TRY(zs_gen_rod(m, b0, b1, 0.9, seg(p, 48, 8), VALVE_RGB));
  const double f0[3] = {3.3, 0.0, 0.0}, f1[3] = {3.6, 0.0, 0.0};
  TRY(zs_gen_rod(m, f0, f1, 1.2, seg(p, 48, 8), VALVE_RGB));
  const double s1[3] = {5.6, 0.0, 0.0};
  TRY(zs_gen_rod(m, f1, s1, 0.15, seg(p, 16, 4), SHAFT_RGB));
  double move[16], turn[16], at[16], xf[16];
  zs_mat_translate(move, -1.6, 0.0, 0.0);
  zs_mat_rotate_turns(turn, 0.25, 0.0, 1.0, 0.0); /* the ring's axis +z onto +x */
  zs_mat_translate(at, 5.2, 0.0, 0.0);
  zs_gen_mul3(xf, at, turn, move);
  TRY(zs_gen_torus(m, 1.6, 0.12, 1.0, seg(p, 48, 8), seg(p, 12, 4), 0, xf, WHEEL_RGB, 0));
  TRY(zs_gen_box_at(m, 5.12, -1.6, -0.08, 5.28, 1.6, 0.08, NULL, WHEEL_RGB));
  return zs_gen_box_at(m, 5.12, -0.08, -1.6, 5.28, 0.08, 1.6, NULL, WHEEL_RGB);
}

/* A railing section 4 m long along +x: posts at 0.5, 2 and 3.5, top and
 * middle rails, a toe board. */
static zs_status mesh_railing(const plant *p, zs_model *m) {
  for (int k = 0; k < 3; k++) {
    const double a[3] = {0.5 + 1.5 * k, 0.0, 0.0}, b[3] = {0.5 + 1.5 * k, 1.1, 0.0};
    TRY(zs_gen_rod(m, a, b, 0.025, seg(p, 12, 4), 0x808080u));
  }
  for (int r = 0; r < 2; r++) {
    const double a[3] = {0.0, r ? 1.1 : 0.55, 0.0}, b[3] = {4.0, r ? 1.1 : 0.55, 0.0};
    TRY(zs_gen_rod(m, a, b, 0.03, seg(p, 12, 4), 0x808080u));
  }
  return zs_gen_box_at(m, 0.0, 0.0, -0.01, 4.0, 0.12, 0.01, NULL, 0x808080u);
}

/* A stair flight along +x from (0, 0) to (14, 10.4), 1.2 wide (z 0 ..
 * 1.2): treads and two stringers. */
static zs_status mesh_stair(zs_model *m) {
  const int steps = 40;
  const double run = 14.0, rise = 10.4, t = run / steps, h = rise / steps;
  for (int k = 0; k < steps; k++)
    TRY(zs_gen_box_at(m, k * t, (k + 1) * h - 0.05, 0.05, (k + 1) * t + 0.05, (k + 1) * h, 1.15,
                 NULL, 0x808080u));
  /* Stringers: boxes sheared so their top follows the slope. */
  double shear[16];
  zs_mat_identity(shear);
  shear[4] = rise / run;
  TRY(zs_gen_box_at(m, 0.0, -0.35, 0.0, run, 0.05, 0.05, shear, 0x808080u));
  return zs_gen_box_at(m, 0.0, -0.35, 1.15, run, 0.05, 1.2, shear, 0x808080u);
}

/* The stack: 120 m, radius 6 tapering to 3.5, red bands near the top, a
 * lip, and a bore 13 m deep. */
static zs_status mesh_stack(const plant *p, zs_model *m) {
  int around = seg(p, 256, 12), rings = seg(p, 64, 2);
  zs_gen_profile pr = {0};
  int ok = zs_gen_pt(&pr, 0.0, 0.0) && zs_gen_pt(&pr, 6.0, 0.0) &&
           zs_gen_line_to(&pr, 3.8, 105.0, rings) && zs_gen_pt(&pr, 0.0, 105.0);
  TRY(zs_gen_profile_lathe(m, &pr, ok, around, 0, NULL, STACK_RGB));
  /* 105 .. 120 in three bands, red, white, red; the bore from the top. */
  static const uint32_t bands[3] = {BAND_RGB, STACK_RGB, BAND_RGB};
  for (int b = 0; b < 3; b++) {
    double y0 = 105.0 + 5.0 * b, y1 = y0 + 5.0;
    double r0 = 3.8 - 0.3 * (y0 - 105.0) / 15.0, r1 = 3.8 - 0.3 * (y1 - 105.0) / 15.0;
    ok = zs_gen_pt(&pr, 0.0, y0) && zs_gen_pt(&pr, r0, y0) &&
         zs_gen_line_to(&pr, r1, y1, seg(p, 4, 1));
    if (b < 2)
      ok = ok && zs_gen_pt(&pr, 0.0, y1);
    else
      ok = ok && zs_gen_pt(&pr, r1 + 0.4, y1) && zs_gen_pt(&pr, r1 + 0.4, y1 + 2.0) &&
           zs_gen_pt(&pr, r1 - 0.6, y1 + 2.0) && zs_gen_pt(&pr, r1 - 0.6, y1 - 10.0) &&
           zs_gen_pt(&pr, 0.0, y1 - 10.0);
    TRY(zs_gen_profile_lathe(m, &pr, ok, around, 0, NULL, bands[b]));
  }
  return ZS_OK;
}

/* A cooling tower: a hyperboloid shell 0.6 m thick from y = 10 to 100
 * (radius 40 at the bottom, 24 at the throat at y = 75, 27 at the top) on
 * 36 pairs of slanted legs. */
static zs_status mesh_tower(const plant *p, zs_model *m) {
  int around = seg(p, 512, 16), rings = seg(p, 96, 6);
  const double a = 24.0, b = 48.75, throat = 75.0;
  zs_gen_profile pr = {0};
  int ok = 1;
  for (int i = 0; i <= rings && ok; i++) {
    double y = 10.0 + 90.0 * i / rings, q = (y - throat) / b;
    ok = zs_gen_pt(&pr, a * sqrt(1.0 + q * q), y);
  }
  for (int i = rings; i >= 0 && ok; i--) {
    double y = 10.0 + 90.0 * i / rings, q = (y - throat) / b;
    ok = zs_gen_pt(&pr, a * sqrt(1.0 + q * q) - 0.6, y);
  }
  ok = ok && zs_gen_pt(&pr, pr.pt[0], pr.pt[1]); /* close the loop */
  TRY(zs_gen_profile_lathe(m, &pr, ok, around, 0, NULL, TOWER_RGB));
  for (int k = 0; k < 72; k++) {
    double s0, c0, s1, c1;
    zs_sincos_turns(k / 72.0, &s0, &c0);
    zs_sincos_turns((k + (k % 2 ? -1.0 : 1.0)) / 72.0, &s1, &c1);
    const double foot[3] = {40.0 * c0, 0.0, -40.0 * s0}, top[3] = {39.7 * c1, 10.0, -39.7 * s1};
    TRY(zs_gen_rod(m, foot, top, 0.35, seg(p, 12, 4), TOWER_RGB));
  }
  return ZS_OK;
}

/* The overhead crane: a bridge spanning x 0.5 .. 49.5 (two box girders,
 * end trucks), a trolley, the rope and hook block. */
static zs_status mesh_crane(const plant *p, zs_model *m) {
  TRY(zs_gen_box_at(m, 0.5, 0.0, -1.8, 49.5, 2.2, -1.2, NULL, CRANE_RGB));
  TRY(zs_gen_box_at(m, 0.5, 0.0, 1.2, 49.5, 2.2, 1.8, NULL, CRANE_RGB));
  TRY(zs_gen_box_at(m, 0.5, 0.0, -3.0, 2.0, 1.2, 3.0, NULL, CRANE_RGB));
  TRY(zs_gen_box_at(m, 48.0, 0.0, -3.0, 49.5, 1.2, 3.0, NULL, CRANE_RGB));
  TRY(zs_gen_box_at(m, 20.0, 2.2, -2.0, 24.0, 3.4, 2.0, NULL, CRANE_RGB));
  const double r0[3] = {22.0, -12.0, 0.0}, r1[3] = {22.0, 2.2, 0.0};
  TRY(zs_gen_rod(m, r0, r1, 0.05, seg(p, 8, 4), SHAFT_RGB));
  TRY(zs_gen_box_at(m, 21.5, -13.2, -0.4, 22.5, -12.0, 0.4, NULL, CRANE_RGB));
  /* The hook: three quarters of a ring under the block. */
  double xf[16];
  zs_mat_translate(xf, 22.0 - 0.3, -13.6, 0.0);
  return zs_gen_torus(m, 0.3, 0.08, 0.75, seg(p, 24, 4), seg(p, 8, 4), 1, xf, SHAFT_RGB, 0);
}

/* A transformer: tank, cooling fins either side, three bushings with
 * sheds. */
static zs_status mesh_transformer(const plant *p, zs_model *m) {
  TRY(zs_gen_box_at(m, -2.0, 0.0, -1.5, 2.0, 3.2, 1.5, NULL, TRANSFORMER_RGB));
  for (int k = 0; k < 12; k++) {
    double x = -1.8 + 0.33 * k;
    TRY(zs_gen_box_at(m, x, 0.4, -2.4, x + 0.08, 2.8, -1.5, NULL, TRANSFORMER_RGB));
    TRY(zs_gen_box_at(m, x, 0.4, 1.5, x + 0.08, 2.8, 2.4, NULL, TRANSFORMER_RGB));
  }
  int sheds = seg(p, 10, 3);
  for (int k = 0; k < 3; k++) {
    double up[16];
    zs_mat_translate(up, -1.2 + 1.2 * k, 3.2, 0.0);
    zs_gen_profile pr = {0};
    int ok = zs_gen_pt(&pr, 0.0, 0.0) && zs_gen_pt(&pr, 0.18, 0.0);
    for (int s = 0; s < sheds && ok; s++) {
      double y = 0.2 + 1.4 * s / sheds;
      ok = zs_gen_line_to(&pr, 0.18, y, 1) && zs_gen_pt(&pr, 0.32, y + 0.03) &&
           zs_gen_pt(&pr, 0.18, y + 0.08);
    }
    ok = ok && zs_gen_line_to(&pr, 0.18, 1.8, 1) && zs_gen_pt(&pr, 0.0, 1.8);
    TRY(zs_gen_profile_lathe(m, &pr, ok, seg(p, 32, 6), 0, up, INSULATOR_RGB));
  }
  return ZS_OK;
}

/* The I-beam along y, 0 .. 1, in a section 1 x 1: two flanges and a web. */
static zs_status mesh_beam(zs_model *m) {
  TRY(zs_gen_box_at(m, -0.5, 0.0, -0.5, 0.5, 1.0, -0.38, NULL, STEEL_RGB));
  TRY(zs_gen_box_at(m, -0.5, 0.0, 0.38, 0.5, 1.0, 0.5, NULL, STEEL_RGB));
  return zs_gen_box_at(m, -0.05, 0.0, -0.38, 0.05, 1.0, 0.38, NULL, STEEL_RGB);
}

static zs_status build_meshes(plant *p) {
  static const char *names[NMESH_KINDS] = {
      "box",   "beam", "pipe",     "elbow",   "flange", "valve",   "boiler",
      "platform", "turbine", "tank", "exchanger", "pump", "railing", "stair",
      "stack", "cooling_tower", "crane", "transformer"};
  for (int k = 0; k < NMESH_KINDS; k++) {
    zs_model m;
    if (zs_gen_model(&m, names[k], p->err) < 0) return p->err->code;
    zs_status st = ZS_OK;
    const double lo[3] = {-0.5, -0.5, -0.5}, hi[3] = {0.5, 0.5, 0.5};
    int pipe = seg(p, 48, 8);
    switch ((enum mesh_kind)k) {
      case M_BOX: st = zs_gen_box(&m, lo, hi, NULL, 0x808080u, 0); break;
      case M_BEAM: st = mesh_beam(&m); break;
      case M_PIPE: st = zs_gen_cylinder(&m, 1.0, 1.0, pipe, 1, NULL, 0x808080u, 0); break;
      case M_ELBOW:
        st = zs_gen_torus(&m, ELBOW, 1.0, 0.25, seg(p, 24, 3), pipe, 1, NULL, 0x808080u, 0);
        break;
      case M_FLANGE: st = mesh_flange(p, &m); break;
      case M_VALVE: st = mesh_valve(p, &m); break;
      case M_BOILER: st = mesh_boiler(p, &m); break;
      case M_PLATFORM: st = mesh_platform(p, &m); break;
      case M_TURBINE: st = mesh_turbine(p, &m); break;
      case M_TANK: st = mesh_tank(p, &m); break;
      case M_HX: st = mesh_hx(p, &m); break;
      case M_PUMP: st = mesh_pump(p, &m); break;
      case M_RAILING: st = mesh_railing(p, &m); break;
      case M_STAIR: st = mesh_stair(&m); break;
      case M_STACK: st = mesh_stack(p, &m); break;
      case M_TOWER: st = mesh_tower(p, &m); break;
      case M_CRANE: st = mesh_crane(p, &m); break;
      case M_TRANSFORMER: st = mesh_transformer(p, &m); break;
      case NMESH_KINDS: break;
    }
    if (st != ZS_OK) {
      zs_model_free(&m);
      return nomem(p);
    }
    p->mesh[k] = zs_gen_add_mesh(p->s, &m, p->err);
    if (p->mesh[k] < 0) return p->err->code;
  }
  return ZS_OK;
}

/* ---- the building ------------------------------------------------------ */

/* A wall or slab with rectangular openings, as boxes: the rectangle u0 ..
 * u1 by v0 .. v1 (u along axis ua, v along axis va), w0 .. w1 thick along
 * the third axis, less the openings (u0, u1, v0, v1 each, inside it and
 * not overlapping).  Cut into strips at every opening's u edges; in each
 * strip, a box for every stretch of v not in an opening. */
static zs_status panel(zs_model *m, int ua, int va, double u0, double u1, double v0, double v1,
                       double w0, double w1, const double (*hole)[4], int nholes, uint32_t rgb) {
  double cut[2 + 2 * 16];
  int ncut = 0;
  cut[ncut++] = u0;
  cut[ncut++] = u1;
  for (int h = 0; h < nholes && h < 16; h++) {
    cut[ncut++] = hole[h][0];
    cut[ncut++] = hole[h][1];
  }
  /* Sort the cuts (insertion sort: a handful). */
  for (int i = 1; i < ncut; i++)
    for (int j = i; j > 0 && cut[j] < cut[j - 1]; j--) {
      double t = cut[j];
      cut[j] = cut[j - 1];
      cut[j - 1] = t;
    }
  int wa = 3 - ua - va;
  for (int i = 0; i + 1 < ncut; i++) {
    double a = cut[i], b = cut[i + 1];
    if (!(b > a)) continue;
    /* The openings across this strip, in order of v. */
    double v = v0;
    for (;;) {
      double next = v1, after = v1;
      for (int h = 0; h < nholes; h++)
        if (hole[h][0] <= a && hole[h][1] >= b && hole[h][3] > v && hole[h][2] < next) {
          next = hole[h][2] > v ? hole[h][2] : v;
          after = hole[h][3];
        }
      if (next > v) {
        double lo[3], hi[3];
        lo[ua] = a;
        hi[ua] = b;
        lo[va] = v;
        hi[va] = next;
        lo[wa] = w0;
        hi[wa] = w1;
        TRY(zs_gen_box(m, lo, hi, NULL, rgb, 0));
      }
      if (next >= v1) break;
      v = after;
    }
  }
  return ZS_OK;
}

static zs_status add_panel(plant *p, const char *name, int ua, int va, double u0, double u1,
                           double v0, double v1, double w0, double w1, const double (*hole)[4],
                           int nholes, uint32_t rgb) {
  zs_model m;
  if (zs_gen_model(&m, name, p->err) < 0) return p->err->code;
  if (panel(&m, ua, va, u0, u1, v0, v1, w0, w1, hole, nholes, rgb)) {
    zs_model_free(&m);
    return nomem(p);
  }
  int32_t mesh = zs_gen_add_mesh(p->s, &m, p->err);
  if (mesh < 0) return p->err->code;
  return add(p, mesh, NULL, ZS_RGB_MESH, "%s", name);
}

/* Sets opening h to u0 .. u1 by v0 .. v1. */
static void opening(double h[4], double u0, double u1, double v0, double v1) {
  h[0] = u0;
  h[1] = u1;
  h[2] = v0;
  h[3] = v1;
}

static zs_status building(plant *p) {
  TRY(add_box(p, -130, -0.5, -130, 300, 0, 230, GROUND_RGB, "ground"));
  /* High window openings, three a bay along the long walls; the south
   * door into bay B, the north door into bay C. */
  double holes[16][4];
  int n = 0;
  for (int k = 0; k < 9; k++) {
    double c = 10.0 + 15.0 * (k % 3) + 50.0 * (k / 3);
    opening(holes[n++], c - 3, c + 3, 28, 34);
  }
  opening(holes[n++], 70, 80, 0, 16);
  TRY(add_panel(p, "wall_south", 0, 1, -0.5, HALL_X + 0.5, 0, HALL_H, -0.5, 0, holes, n,
                WALL_RGB));
  opening(holes[n - 1], 120, 126, 0, 5);
  TRY(add_panel(p, "wall_north", 0, 1, -0.5, HALL_X + 0.5, 0, HALL_H, HALL_Z, HALL_Z + 0.5,
                holes, n, WALL_RGB));
  /* The end walls: windows, and the east door out to the pipe rack. */
  n = 0;
  for (int k = 0; k < 3; k++) {
    double c = 15.0 + 15.0 * k;
    opening(holes[n++], c - 3, c + 3, 28, 34);
  }
  TRY(add_panel(p, "wall_west", 2, 1, 0, HALL_Z, 0, HALL_H, -0.5, 0, holes, n, WALL_RGB));
  opening(holes[n++], 25, 35, 0, 10);
  TRY(add_panel(p, "wall_east", 2, 1, 0, HALL_Z, 0, HALL_H, HALL_X, HALL_X + 0.5, holes, n,
                WALL_RGB));
  /* The inner walls' doorways, near the south wall, clear of the turbine
   * tables. */
  const double door_a[1][4] = {{1, 8, 0, 10}}, door_c[1][4] = {{9, 17, 0, 9.5}};
  TRY(add_panel(p, "wall_bay_ab", 2, 1, 0, HALL_Z, 0, HALL_H, 49.8, 50.2, door_a, 1,
                INNER_WALL_RGB));
  TRY(add_panel(p, "wall_bay_bc", 2, 1, 0, HALL_Z, 0, HALL_H, 99.8, 100.2, door_c, 1,
                INNER_WALL_RGB));
  TRY(add_box(p, -0.5, HALL_H, -0.5, HALL_X + 0.5, HALL_H + 0.8, HALL_Z + 0.5, ROOF_RGB, "roof"));

  /* Columns along the long walls, every 10 m. */
  for (int k = 0; k < 15; k++) {
    double x = 5.0 + 10.0 * k;
    for (int side = 0; side < 2; side++) {
      double z = side ? HALL_Z - 0.5 : 0.5;
      const double a[3] = {x, 0.0, z}, b[3] = {x, HALL_H, z};
      TRY(add_beam(p, a, b, 0.6, side ? "column_n_%d" : "column_s_%d", k));
    }
  }
  return ZS_OK;
}

/* ---- bays ---------------------------------------------------------------- */

static zs_status bay_a(plant *p) {
  for (int b = 0; b < 4; b++) {
    double x = BOILERS[b][0], z = BOILERS[b][1], m[16];
    zs_mat_identity(m);
    m[0] = m[5] = m[10] = BOILER_R;
    m[3] = x;
    m[11] = z;
    TRY(add(p, p->mesh[M_BOILER], m, ZS_RGB_MESH, "boiler_%d", b));
    const double top[3] = {x, 6.25 * BOILER_R, z};
    add_nozzle(p, BOILER_TOP, top);
    for (int k = 0; k < 2; k++) {
      double y = 12.0 * (k + 1);
      zs_mat_translate(m, x, y, z);
      TRY(add(p, p->mesh[M_PLATFORM], m, ZS_RGB_MESH, "platform_%d_%d", b, k));
    }
    /* Side nozzles, just off the shell, for feed water and services. */
    for (int k = 0; k < 4; k++) {
      double dx = (k & 1) ? 6.3 : -6.3, y = (k & 2) ? 18.0 : 2.0;
      const double at[3] = {x + dx, y, z + ((k & 2) ? 1.0 : -1.0)};
      add_nozzle(p, BOILER_SIDE, at);
    }
  }
  /* Flue ducts: across the boiler tops, and out to the stack. */
  TRY(add_box(p, 12, 31, 16, 16, 35, 44, DUCT_RGB, "duct_0"));
  TRY(add_box(p, 34, 31, 16, 38, 35, 44, DUCT_RGB, "duct_1"));
  TRY(add_box(p, -27, 30, 27.5, 38, 35, 32.5, DUCT_RGB, "duct_stack"));
  return ZS_OK;
}

static zs_status bay_b(plant *p) {
  for (int t = 0; t < 2; t++) {
    double x = TURBINES[t];
    TRY(add_box(p, x - 4, 0, TURBINE_Z - 2, x + 4, TABLE_H, TURBINE_Z + 48, CONCRETE_RGB,
                t ? "table_1" : "table_0"));
    double m[16];
    zs_mat_translate(m, x, TABLE_H, TURBINE_Z);
    TRY(add(p, p->mesh[M_TURBINE], m, ZS_RGB_MESH, "turbine_%d", t));
    for (int k = 0; k < 2; k++) {
      const double in[3] = {x, TABLE_H + 5.5, TURBINE_Z + (k ? 14.5 : 6.0)};
      add_nozzle(p, TURBINE_IN, in);
    }
    for (int k = 0; k < 3; k++) {
      const double side[3] = {x + (t ? -4.6 : 4.6), 1.0, 14.0 + 14.0 * k};
      add_nozzle(p, TURBINE_SIDE, side);
    }
  }
  const double r0[3] = {50.8, 33.0, 0.6}, r1[3] = {50.8, 33.0, HALL_Z - 0.6};
  TRY(add_beam(p, r0, r1, 0.6, "crane_rail_%d", 0));
  const double r2[3] = {99.2, 33.0, 0.6}, r3[3] = {99.2, 33.0, HALL_Z - 0.6};
  TRY(add_beam(p, r2, r3, 0.6, "crane_rail_%d", 1));
  double m[16];
  zs_mat_translate(m, 50.0, 33.6, 36.0);
  return add(p, p->mesh[M_CRANE], m, ZS_RGB_MESH, "crane");
}

/* A pump turned by a quarter turns about +y, scaled by s, at (x, y, z). */
static zs_status pump(plant *p, double x, double y, double z, int quarter, double s,
                      enum pool pool, int i) {
  double turn[16], size[16], move[16], m[16];
  zs_mat_rotate_turns(turn, 0.25 * quarter, 0.0, 1.0, 0.0);
  zs_mat_scale(size, s, s, s);
  zs_mat_translate(move, x, y, z);
  zs_gen_mul3(m, move, turn, size);
  TRY(add(p, p->mesh[M_PUMP], m, ZS_RGB_MESH, "pump_%d", i));
  const double out[3] = {0.5, 1.8, 0.55};
  double at[4];
  zs_mat_apply(m, out, at);
  add_nozzle(p, pool, at);
  return ZS_OK;
}

static zs_status tank(plant *p, double x, double y, double z, double r, double h,
                      enum pool pool, uint32_t rgb, const char *name, int i) {
  double m[16];
  zs_mat_identity(m);
  m[0] = m[10] = r;
  m[5] = h;
  m[3] = x;
  m[7] = y;
  m[11] = z;
  TRY(add(p, p->mesh[M_TANK], m, rgb, name, i));
  const double top[3] = {x, y + 1.22 * h, z};
  add_nozzle(p, pool, top);
  return ZS_OK;
}

static zs_status exchanger(plant *p, double x, double y, double z, double s, int i) {
  double m[16];
  zs_mat_identity(m);
  m[0] = m[5] = m[10] = s;
  m[3] = x;
  m[7] = y;
  m[11] = z;
  TRY(add(p, p->mesh[M_HX], m, ZS_RGB_MESH, "exchanger_%d", i));
  for (int k = -1; k <= 1; k += 2) {
    const double at[3] = {x, y + 2.9 * s, z + 2.0 * k * s};
    add_nozzle(p, BAY_C, at);
  }
  return ZS_OK;
}

static zs_status railing_run(plant *p, double x, double y, double z, int quarter, int sections,
                             int *count) {
  for (int k = 0; k < sections; k++) {
    double turn[16], move[16], m[16], d[2];
    zs_mat_rotate_turns(turn, 0.25 * quarter, 0.0, 1.0, 0.0);
    d[0] = turn[0]; /* where the section's +x goes: (x, z) */
    d[1] = turn[8];
    zs_mat_translate(move, x + 4.0 * k * d[0], y, z + 4.0 * k * d[1]);
    zs_mat_mul(m, move, turn);
    TRY(add(p, p->mesh[M_RAILING], m, RAILING_RGB, "railing_%d", (*count)++));
  }
  return ZS_OK;
}

static zs_status bay_c(plant *p) {
  /* Decks: x 100.2 .. 146, the stair well x 128 .. 142, z 40 .. 46. */
  const double well[1][4] = {{128, 142, 40, 46}};
  for (int d = 0; d < 2; d++) {
    double y = d ? DECK2 : DECK1;
    TRY(add_panel(p, d ? "deck_2" : "deck_1", 0, 2, 100.2, 146.0, 0.0, HALL_Z, y, y + DECK_T,
                  well, 1, DECK_RGB));
  }
  /* Columns on a grid, beams under both decks. */
  int c = 0;
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 3; j++) {
      const double a[3] = {110.0 + 10.0 * i, 0.0, 15.0 + 15.0 * j};
      const double b[3] = {a[0], DECK2, a[2]};
      TRY(add_beam(p, a, b, 0.5, "deck_column_%d", c++));
    }
  c = 0;
  for (int d = 0; d < 2; d++) {
    double y = (d ? DECK2 : DECK1) - 0.25;
    for (int j = 0; j < 3; j++) {
      const double a[3] = {100.2, y, 15.0 + 15.0 * j}, b[3] = {146.0, y, 15.0 + 15.0 * j};
      TRY(add_beam(p, a, b, 0.5, "deck_beam_%d", c++));
    }
    for (int i = 0; i < 4; i++) {
      const double a[3] = {110.0 + 10.0 * i, y, 0.2}, b[3] = {110.0 + 10.0 * i, y, HALL_Z - 0.2};
      TRY(add_beam(p, a, b, 0.5, "deck_beam_%d", c++));
    }
  }
  /* Railings: along the open east edge and the long sides of the stair
   * well (its ends are where the flights arrive). */
  int r = 0;
  for (int d = 0; d < 2; d++) {
    double y = (d ? DECK2 : DECK1) + DECK_T;
    TRY(railing_run(p, 145.9, y, 60.0, 1, 15, &r));
    TRY(railing_run(p, 128.0, y, 39.9, 0, 3, &r));
    TRY(railing_run(p, 128.0, y, 46.1, 0, 3, &r));
  }
  /* Stairs: up to deck 1 along +x, on to deck 2 along -x. */
  double m[16], turn[16], move[16];
  zs_mat_translate(m, 128.0, 0.0, 40.3);
  TRY(add(p, p->mesh[M_STAIR], m, STEEL_RGB, "stair_%d", 0));
  zs_mat_rotate_turns(turn, 0.5, 0.0, 1.0, 0.0);
  zs_mat_translate(move, 142.0, DECK1 + DECK_T, 45.7);
  zs_mat_mul(m, move, turn);
  TRY(add(p, p->mesh[M_STAIR], m, STEEL_RGB, "stair_%d", 1));

  /* Equipment.  Floor: pumps in two rows, four exchangers. */
  int np = 0;
  static const double rows_x[4] = {104.5, 114.5, 124.5, 134.5};
  for (int row = 0; row < 2; row++)
    for (int i = 0; i < 4; i++)
      TRY(pump(p, rows_x[i], 0.0, row ? 22.0 : 6.0, row * 2, zs_rng_range(&p->rng, 1.0, 1.4),
               BAY_C_FLOOR, np++));
  int nx = 0;
  TRY(exchanger(p, 106.0, 0.0, 52.0, 1.0, nx++));
  TRY(exchanger(p, 118.0, 0.0, 52.0, 1.1, nx++));
  TRY(exchanger(p, 104.5, 0.0, 36.0, 0.9, nx++));
  TRY(exchanger(p, 116.0, 0.0, 36.5, 0.9, nx++));
  /* Deck 1: tanks and pumps; deck 2: exchangers, pumps, a tank. */
  int nt = 0;
  double y1 = DECK1 + DECK_T, y2 = DECK2 + DECK_T;
  static const double tanks1[4][2] = {{114, 22}, {126, 22}, {114, 37}, {125, 36}};
  for (int i = 0; i < 4; i++) {
    /* Two draws: in two statements, as the order of evaluation of a call's
     * arguments is unspecified (gcc and clang differ). */
    double r = zs_rng_range(&p->rng, 2.0, 2.6);
    double h = zs_rng_range(&p->rng, 5.0, 7.0);
    TRY(tank(p, tanks1[i][0], y1, tanks1[i][1], r, h, BAY_C, TANK_RGB, "tank_%d", nt++));
  }
  for (int i = 0; i < 4; i++) TRY(pump(p, rows_x[i], y1, 6.0, 0, 1.0, BAY_C, np++));
  TRY(exchanger(p, 105.0, y2, 30.0, 1.0, nx++));
  TRY(exchanger(p, 136.0, y2, 22.0, 1.0, nx++));
  for (int i = 0; i < 4; i++)
    TRY(pump(p, rows_x[i] + (i == 3 ? 2.0 : 0.0), y2, 53.0, 2, 1.0, BAY_C, np++));
  TRY(tank(p, 118.0, y2, 22.0, 1.8, 6.0, BAY_C, TANK_RGB, "tank_%d", nt++));
  TRY(tank(p, 143.0, y2, 8.0, 1.5, 5.0, BAY_C, TANK_RGB, "tank_%d", nt++));
  return ZS_OK;
}

static zs_status outside(plant *p) {
  double m[16];
  zs_mat_translate(m, -33.0, 0.0, 30.0);
  TRY(add(p, p->mesh[M_STACK], m, ZS_RGB_MESH, "stack"));
  for (int t = 0; t < 2; t++) {
    double x = t ? 110.0 : 20.0;
    zs_mat_translate(m, x, 0.0, 150.0);
    TRY(add(p, p->mesh[M_TOWER], m, ZS_RGB_MESH, "cooling_tower_%d", t));
    const double at[3] = {x, 1.0, 108.0};
    add_nozzle(p, TOWER, at);
  }
  /* Tank farm east of the hall, over a pipe rack. */
  int nt = 100;
  static const double big[3][2] = {{205, 10}, {205, 44}, {238, 27}};
  for (int i = 0; i < 3; i++)
    TRY(tank(p, big[i][0], 0.0, big[i][1], 12.0, 14.0, OUTSIDE, 0xE8E4DAu, "tank_%d", nt++));
  static const double small[4][2] = {{176, 6}, {183, 6}, {176, 54}, {183, 54}};
  for (int i = 0; i < 4; i++)
    TRY(tank(p, small[i][0], 0.0, small[i][1], 2.5, 7.0, OUTSIDE, 0xE8E4DAu, "tank_%d", nt++));
  int nb = 0;
  for (int k = 0; k < 6; k++) {
    double x = 154.0 + 7.0 * k;
    for (int side = 0; side < 2; side++) {
      const double a[3] = {x, 0.0, side ? 33.0 : 27.0}, b[3] = {x, 16.0, side ? 33.0 : 27.0};
      TRY(add_beam(p, a, b, 0.4, "rack_column_%d", nb++));
    }
    const double a[3] = {x, 16.0, 26.5}, b[3] = {x, 16.0, 33.5};
    TRY(add_beam(p, a, b, 0.4, "rack_beam_%d", k));
  }
  static const double xs[4] = {58.0, 66.0, 84.0, 92.0};
  for (int k = 0; k < 4; k++) {
    zs_mat_translate(m, xs[k], 0.0, -14.0);
    TRY(add(p, p->mesh[M_TRANSFORMER], m, ZS_RGB_MESH, "transformer_%d", k));
  }
  return ZS_OK;
}

/* ---- pipe runs ----------------------------------------------------------- */

/* The unit direction from a to b along the one axis they differ in. */
static void axis_dir(const double a[3], const double b[3], double d[3]) {
  for (int k = 0; k < 3; k++) d[k] = (double)((b[k] > a[k]) - (b[k] < a[k]));
}

/* The length of an axis-parallel leg from a to b (any other distance
 * would need a square root; this one is exact). */
static double dist(const double a[3], const double b[3]) {
  return fabs(b[0] - a[0]) + fabs(b[1] - a[1]) + fabs(b[2] - a[2]);
}

/* A run of radius r from a to b (both ends leave upwards): up from a to a
 * crossing height y in ylo .. yhi, along z to a lane z in zlo .. zhi,
 * along x, along z, down to b.  Legs of zero length are dropped; each leg
 * must leave room for its elbows.  Up to 16 tries of (y, lane); a run that
 * fits none is left out. */
static zs_status run(plant *p, const double a[3], const double b[3], double r, uint32_t rgb,
                     double ylo, double yhi, double zlo, double zhi, int with_valve) {
  double e = ELBOW * r, pts[6][3];
  int n = 0;
  for (int attempt = 0; attempt < 16 && n == 0; attempt++) {
    double low = (a[1] > b[1] ? a[1] : b[1]) + 2.0 * e + 0.3;
    double y = zs_rng_range(&p->rng, ylo, yhi);
    if (y < low) y = low;
    double lane = floor(zs_rng_range(&p->rng, zlo, zhi) * 4.0) / 4.0;
    const double raw[6][3] = {{a[0], a[1], a[2]}, {a[0], y, a[2]}, {a[0], y, lane},
                              {b[0], y, lane},    {b[0], y, b[2]}, {b[0], b[1], b[2]}};
    /* Drop repeated points, then points in the middle of a straight. */
    double q[6][3];
    int m = 0;
    for (int i = 0; i < 6; i++)
      if (m == 0 || dist(q[m - 1], raw[i]) > 0.0) memcpy(q[m++], raw[i], sizeof q[0]);
    int k = 0;
    for (int i = 0; i < m; i++) {
      if (k >= 2) {
        double d0[3], d1[3];
        axis_dir(q[k - 2], q[k - 1], d0);
        axis_dir(q[k - 1], q[i], d1);
        if (d0[0] == d1[0] && d0[1] == d1[1] && d0[2] == d1[2]) k--;
      }
      memcpy(q[k++], q[i], sizeof q[0]);
    }
    int ok = k >= 2;
    for (int i = 0; i + 1 < k && ok; i++) {
      double need = (i > 0 ? e : 0.5) + (i + 2 < k ? e : 0.5) + 0.2;
      double d0[3], d1[3];
      ok = dist(q[i], q[i + 1]) >= need;
      if (i + 2 < k) {
        axis_dir(q[i], q[i + 1], d0);
        axis_dir(q[i + 1], q[i + 2], d1);
        ok = ok && d0[0] * d1[0] + d0[1] * d1[1] + d0[2] * d1[2] == 0.0;
      }
    }
    if (ok) {
      memcpy(pts, q, sizeof q[0] * (size_t)k);
      n = k;
    }
  }
  if (n == 0) return ZS_OK;

  int id = p->nruns++, longest = -1;
  double best = 0.0;
  for (int i = 0; i + 1 < n; i++) {
    double d[3], from[3], m[16];
    axis_dir(pts[i], pts[i + 1], d);
    double len = dist(pts[i], pts[i + 1]) - (i > 0 ? e : 0.0) - (i + 2 < n ? e : 0.0);
    for (int k = 0; k < 3; k++) from[k] = pts[i][k] + (i > 0 ? e : 0.0) * d[k];
    zs_gen_along(m, from, d, len, r);
    TRY(add(p, p->mesh[M_PIPE], m, rgb, "pipe_%d_%d", id, i));
    if (d[1] != 0.0 && len > best) {
      best = len;
      longest = i;
    }
    if (i + 2 < n) {
      /* The elbow at pts[i+1]: local +y along d, +x along the next leg. */
      double d2[3], z[3], o[3], ax[3], ay[3], az[3];
      axis_dir(pts[i + 1], pts[i + 2], d2);
      z[0] = d2[1] * d[2] - d2[2] * d[1];
      z[1] = d2[2] * d[0] - d2[0] * d[2];
      z[2] = d2[0] * d[1] - d2[1] * d[0];
      for (int k = 0; k < 3; k++) {
        o[k] = pts[i + 1][k] - e * d[k];
        ax[k] = r * d2[k];
        ay[k] = r * d[k];
        az[k] = r * z[k];
      }
      zs_gen_frame(m, ax, ay, az, o);
      TRY(add(p, p->mesh[M_ELBOW], m, rgb, "elbow_%d_%d", id, i));
    }
  }
  /* Flanges where the run meets its equipment, 0.4 m along. */
  for (int end = 0; end < 2; end++) {
    const double *at = end ? pts[n - 1] : pts[0];
    const double *next = end ? pts[n - 2] : pts[1];
    double d[3], c[3], m[16];
    axis_dir(at, next, d);
    for (int k = 0; k < 3; k++) c[k] = at[k] + 0.4 * d[k];
    zs_gen_along(m, c, d, r, r);
    TRY(add(p, p->mesh[M_FLANGE], m, 0x9A9A9Au, "flange_%d_%d", id, end));
  }
  if (with_valve && longest >= 0 && best > 5.0 * r + 2.0 * e) {
    double d[3], c[3], m[16];
    axis_dir(pts[longest], pts[longest + 1], d);
    for (int k = 0; k < 3; k++) c[k] = 0.5 * (pts[longest][k] + pts[longest + 1][k]);
    zs_gen_along(m, c, d, r, r);
    TRY(add(p, p->mesh[M_VALVE], m, ZS_RGB_MESH, "valve_%d", id));
  }
  return ZS_OK;
}

static const double *pick(plant *p, enum pool pool) {
  return p->nozzle[pool][zs_rng_below(&p->rng, (uint64_t)p->nnozzles[pool])];
}

/* A service run with a valve from a to b (none when they are the same
 * nozzle): a colour from the first ncolours SERVICES, a radius in rlo ..
 * rhi, drawn in that order. */
static zs_status service(plant *p, const double *a, const double *b, int ncolours, double rlo,
                         double rhi, double ylo, double yhi, double zlo, double zhi) {
  if (a == b) return ZS_OK;
  uint32_t rgb = SERVICES[zs_rng_below(&p->rng, (uint64_t)ncolours)];
  return run(p, a, b, zs_rng_range(&p->rng, rlo, rhi), rgb, ylo, yhi, zlo, zhi, 1);
}

static zs_status runs(plant *p) {
  /* Main steam: each boiler to one turbine inlet. */
  for (int b = 0; b < 4; b++)
    TRY(run(p, p->nozzle[BOILER_TOP][b], p->nozzle[TURBINE_IN][b], 0.45, STEAM_RGB, 37.4, 39.0,
            22.0, 38.0, 1));
  /* Feed water: floor pumps in bay C to the boilers. */
  for (int b = 0; b < 4; b++)
    TRY(run(p, p->nozzle[BAY_C_FLOOR][b], p->nozzle[BOILER_SIDE][4 * b], 0.3, FEED_RGB, 26.0,
            30.0, 2.0, 58.0, 1));
  /* Cooling water: the towers to the turbines' condensers, there and back. */
  for (int k = 0; k < 4; k++)
    TRY(run(p, p->nozzle[TOWER][k / 2], p->nozzle[TURBINE_SIDE][k < 2 ? k : k + 1], 0.7,
            COOLING_RGB, 5.0, 7.0, 64.0, 100.0, 0));
  /* Services within bay A, bay B to bay C, within bay C, out to the tanks
   * (a and b picked in two statements: a call's arguments are evaluated in
   * no fixed order). */
  for (int k = 0; k < 12; k++) {
    const double *a = pick(p, BOILER_SIDE);
    const double *b = pick(p, BOILER_SIDE);
    TRY(service(p, a, b, NSERVICES, 0.08, 0.2, 20.0, 29.0, 2.0, 58.0));
  }
  for (int k = 0; k < 10; k++) {
    const double *a = pick(p, TURBINE_SIDE);
    const double *b = pick(p, k % 2 ? BAY_C : BAY_C_FLOOR);
    TRY(service(p, a, b, NSERVICES, 0.1, 0.3, 24.0, 32.0, 2.0, 58.0));
  }
  for (int k = 0; k < 48; k++) {
    const double *a = pick(p, k % 3 ? BAY_C : BAY_C_FLOOR);
    const double *b = pick(p, BAY_C);
    TRY(service(p, a, b, NSERVICES, 0.06, 0.25, 8.0, 38.0, 1.0, 59.0));
  }
  for (int k = 0; k < 8; k++) {
    const double *a = pick(p, BAY_C_FLOOR);
    const double *b = pick(p, OUTSIDE);
    TRY(service(p, a, b, 2, 0.15, 0.35, 16.6, 19.5, 27.5, 32.5));
  }
  return ZS_OK;
}

/* ---- the scene ----------------------------------------------------------- */

static zs_status build_plant(const zs_gen_args *a, zs_scene *s, zs_error *err) {
  plant *p = calloc(1, sizeof *p);
  if (!p) return ZS_GEN_NOMEM(err, a->spec);
  p->s = s;
  p->err = err;
  p->detail = zs_gen_real(a, "detail");
  zs_rng_seed(&p->rng, a->seed);
  zs_status st = build_meshes(p);
  if (st == ZS_OK) st = building(p);
  if (st == ZS_OK) st = bay_a(p);
  if (st == ZS_OK) st = bay_b(p);
  if (st == ZS_OK) st = bay_c(p);
  if (st == ZS_OK) st = outside(p);
  if (st == ZS_OK) st = runs(p);
  free(p);
  if (st != ZS_OK) return st;

  const double eye[3] = {250.0, 80.0, -160.0}, target[3] = {70.0, 15.0, 40.0};
  zs_gen_camera(s, eye, target, 0.2, 2000.0);
  /* From far outside (open), down to the south door, into bay B between
   * the turbines, west along the south wall into the boiler house (doorway
   * z 1 .. 8), back east and through the doorway to bay C (z 9 .. 17),
   * under deck 1, up both stair flights to deck 2, over its east edge and
   * down by the east wall, out of the east door along the pipe rack to the
   * tanks, and up to look back over the whole plant. */
  static const zs_gen_key keys[] = {
      {{250, 80, -160}, {70, 15, 40}},       {{130, 25, -80}, {75, 10, 0}},
      {{75, 4, -28}, {75, 6, 10}},           {{75, 4.5, 2.5}, {75, 6, 40}},
      {{72, 4.5, 3.5}, {40, 5, 4}},          {{54, 4.5, 4}, {30, 6, 10}},
      {{45, 4.5, 5}, {25, 8, 30}},           {{25, 5, 30}, {25, 25, 50}},
      {{30, 6, 24}, {48, 5, 6}},             {{46, 4.5, 4.5}, {60, 5, 4}},
      {{60, 4.5, 3.5}, {95, 5, 4}},          {{94, 4.5, 4}, {96, 5, 13}},
      {{97, 4.5, 13}, {130, 4.5, 13}},       {{118, 4, 13}, {122, 4, 38}},
      {{122, 4, 34}, {128, 4, 41}},          {{129, 2.5, 40.9}, {142, 11.5, 40.9}},
      {{140.5, 12.6, 42.5}, {140.5, 13, 46}}, {{140.5, 13.2, 45.1}, {128, 21.5, 45.1}},
      {{126, 22.6, 45}, {110, 22, 25}},      {{124, 22.6, 30}, {146, 21, 30}},
      {{148, 18, 30}, {148, 3, 30}},         {{148, 4, 30}, {170, 5, 30}},
      {{172, 6, 30}, {210, 10, 30}},         {{220, 60, 110}, {80, 15, 30}},
      {{120, 120, 230}, {70, 20, 30}}};
  return zs_gen_path(s, keys, (int)(sizeof keys / sizeof keys[0]), zs_gen_int(a, "frames"),
                     err);
}

static const zs_gen_param plant_params[] = {
    {"detail", ZS_GEN_REAL, 0.05, 1.0, 0.25},
    {"seed", ZS_GEN_SEED, 0, 0, 0},
    {"frames", ZS_GEN_INT, 32, 100000, 400}};

const zs_gen_def zs_gen_plant_def = {"plant", plant_params, 3, build_plant, NULL};
