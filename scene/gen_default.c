/* The default scene of `zscan render`: a 3 x 3 field of teapots (level 6,
 * native size) on a ground slab, from instances of one teapot mesh and one
 * ground box.
 *
 * LAYOUT
 *   Teapot t = 3 r + c stands at x = 8 (c - 1), z = 8 (r - 1), on the
 *   ground's top (y = 0), turned about +y by a whole number of degrees in
 *   [0, 360), with its own palette colour.  The rng, seeded with
 *   DEFAULT_SEED (not the spec's seed: the default scene is one picture),
 *   first shuffles the palette (Fisher-Yates; teapot t takes entry t), then
 *   draws the nine yaw angles in teapot order.  The ground is the slab x,
 *   z in [-12, 12], y in [-0.25, 0], the last object.  Ids: teapot t's
 *   faces start at t * 32 level^2, the ground's after the nine.  The camera
 *   is left to be completed from the bounds. */
#include "util/matrix.h"
#include "scene/gen_internal.h"
#include "scene/teapot.h"

#define DEFAULT_SEED 0x7EA907u

enum { SIDE = 3, FIELD = SIDE * SIDE, DEFAULT_LEVEL = 6 };

/* Every teapot has its own palette entry. */
_Static_assert((int)FIELD <= (int)ZS_GEN_PALETTE_SIZE, "more teapots than colours");

/* Teapot t's model matrix (the turn about +y, then the move) and colour. */
static void field_layout(double place[FIELD][16], uint32_t rgb[FIELD]) {
  const double spacing = 8.0;
  zs_rng rng;
  zs_rng_seed(&rng, DEFAULT_SEED);
  uint32_t colours[ZS_GEN_PALETTE_SIZE];
  for (int i = 0; i < ZS_GEN_PALETTE_SIZE; i++) colours[i] = zs_gen_palette(i);
  zs_rng_shuffle(&rng, colours, ZS_GEN_PALETTE_SIZE, sizeof colours[0]);
  for (int t = 0; t < FIELD; t++) {
    int row = t / SIDE, col = t % SIDE;
    /* Whole degrees: a short, exact record of the angle. */
    double yaw = (double)zs_rng_below(&rng, 360);
    double rot[16], move[16];
    zs_mat_rotate(rot, yaw, 0.0, 1.0, 0.0);
    zs_mat_translate(move, spacing * (col - (SIDE - 1) / 2.0), 0.0,
                     spacing * (row - (SIDE - 1) / 2.0));
    zs_mat_mul(place[t], move, rot); /* turn first, then move */
    rgb[t] = colours[t];
  }
}

static zs_status build_default(const zs_gen_args *a, zs_scene *s, zs_error *err) {
  int32_t teapot_mesh = zs_gen_teapot_mesh(s, zs_gen_int(a, "level"), err);
  if (teapot_mesh < 0) return err->code;

  double place[FIELD][16];
  uint32_t rgb[FIELD];
  field_layout(place, rgb);
  for (int t = 0; t < FIELD; t++)
    if (zs_gen_add_instance(s, teapot_mesh, place[t], rgb[t], err, "teapot_%d", t) < 0)
      return err->code;
  const double lo[3] = {-12.0, -0.25, -12.0}, hi[3] = {12.0, 0.0, 12.0};
  if (zs_gen_ground(s, lo, hi, a->spec, err) < 0) return err->code;

  /* The camera: completed later from the bounds. */
  zs_camera_default(&s->camera);
  s->width = 1024;
  s->height = 768;

  /* Around the field at a distance, down between the teapots (each hides
   * the ones behind it), and out and up again. */
  static const zs_gen_key keys[] = {
      {{24.0, 10.0, 24.0}, {0.0, 1.0, 0.0}}, {{0.0, 7.0, 30.0}, {0.0, 1.0, 0.0}},
      {{-22.0, 4.0, 18.0}, {0.0, 1.0, 0.0}}, {{-8.0, 1.6, 4.0}, {4.0, 1.2, -4.0}},
      {{4.0, 1.6, 4.0}, {8.0, 1.2, -12.0}},  {{12.0, 1.8, -8.0}, {0.0, 1.0, -8.0}},
      {{20.0, 5.0, -20.0}, {0.0, 1.0, 0.0}}, {{30.0, 14.0, 4.0}, {0.0, 1.0, 0.0}},
      {{24.0, 10.0, 24.0}, {0.0, 1.0, 0.0}}};
  return zs_gen_path(s, keys, (int)(sizeof keys / sizeof keys[0]), zs_gen_int(a, "frames"),
                     err);
}

static const zs_gen_param default_params[] = {
    {"level", ZS_GEN_INT, 1, ZS_TEAPOT_MAX_LEVEL, DEFAULT_LEVEL},
    {"frames", ZS_GEN_INT, 16, 100000, 200}};

const zs_gen_def zs_gen_default_def = {"default", default_params, 2, build_default, NULL};
