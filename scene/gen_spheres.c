/* Experiment 1 of the CHC paper: spheres of 576 faces filling a cube of
 * 1,000 units a side, each moving along the x axis of its own coordinates;
 * the experiment varies how many of the 5,000 move (500 .. 5000).
 *
 * LAYOUT
 *   One sphere mesh (slices x stacks, radius 1) instanced count times.  The
 *   random draws, sphere by sphere: the radius (RMIN .. RMAX), the centre
 *   (each coordinate in [r, SIDE - r], so the sphere lies inside the cube
 *   [0, SIDE]^3, which is the scene's bounds), a uniformly random rotation
 *   (three numbers), the palette entry, and the speed (SPEED_MIN ..
 *   SPEED_MAX units per frame).  Every sphere draws its speed, so `moving`
 *   changes which spheres move and nothing else: the first `moving` ones
 *   move along their local x axis and bounce off the cube's walls.
 */
#include "util/matrix.h"
#include "scene/gen_internal.h"

#define SIDE 1000.0
#define RMIN 8.0
#define RMAX 16.0
#define SPEED_MIN 0.5
#define SPEED_MAX 2.5

static zs_status build_spheres(const zs_gen_args *a, zs_scene *s, zs_error *err) {
  int count = zs_gen_int(a, "count");
  int moving = zs_gen_given(a, "moving") ? zs_gen_int(a, "moving") : count;
  if (zs_gen_check_moving(a, moving, count, "count", err)) return err->code;
  zs_rng rng;
  zs_rng_seed(&rng, a->seed);

  zs_model sphere;
  int32_t obj = zs_gen_model(&sphere, "sphere", err);
  if (obj < 0) return err->code;
  if (zs_gen_sphere(&sphere, zs_gen_int(a, "slices"), zs_gen_int(a, "stacks"), NULL,
                    ZS_GREY, obj)) {
    zs_model_free(&sphere);
    return ZS_GEN_NOMEM(err, a->spec);
  }
  int32_t mesh = zs_gen_add_mesh(s, &sphere, err);
  if (mesh < 0) return err->code;

  for (int i = 0; i < count; i++) {
    double r = zs_rng_range(&rng, RMIN, RMAX);
    double c[3];
    for (int k = 0; k < 3; k++) c[k] = zs_rng_range(&rng, r, SIDE - r);
    double move[16], turn[16], size[16], place[16];
    zs_mat_translate(move, c[0], c[1], c[2]);
    zs_gen_random_rotation(&rng, turn);
    zs_mat_scale(size, r, r, r);
    zs_gen_mul3(place, move, turn, size);
    uint32_t rgb = zs_gen_palette((int)zs_rng_below(&rng, ZS_GEN_PALETTE_SIZE));
    double speed = zs_rng_range(&rng, SPEED_MIN, SPEED_MAX);
    int32_t in = zs_gen_add_instance(s, mesh, place, rgb, err, "sphere_%d", i);
    if (in < 0) return err->code;
    if (i < moving) zs_gen_move_along_x(s, in, speed);
  }

  const double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {SIDE, SIDE, SIDE};
  zs_gen_bounds(s, lo, hi);
  /* The target a little below the middle, so the nearest corner of the
   * cube stays in the picture. */
  const double eye[3] = {1.5 * SIDE, 1.05 * SIDE, 2.0 * SIDE};
  const double target[3] = {0.5 * SIDE, 0.42 * SIDE, 0.5 * SIDE};
  zs_gen_camera(s, eye, target, 1.0, 5.0 * SIDE);
  /* Around the cube (everything in view), into it from the -x side through
   * the cloud (nearby spheres hide most of the others), out and around. */
  const zs_gen_key keys[] = {
      {{1.5 * SIDE, 1.05 * SIDE, 2.0 * SIDE}, {0.5 * SIDE, 0.42 * SIDE, 0.5 * SIDE}},
      {{0.5 * SIDE, 0.9 * SIDE, 2.3 * SIDE}, {0.5 * SIDE, 0.5 * SIDE, 0.5 * SIDE}},
      {{-0.7 * SIDE, 0.7 * SIDE, 1.6 * SIDE}, {0.5 * SIDE, 0.5 * SIDE, 0.5 * SIDE}},
      {{-0.3 * SIDE, 0.5 * SIDE, 0.5 * SIDE}, {0.5 * SIDE, 0.5 * SIDE, 0.5 * SIDE}},
      {{0.25 * SIDE, 0.48 * SIDE, 0.52 * SIDE}, {SIDE, 0.5 * SIDE, 0.56 * SIDE}},
      {{0.75 * SIDE, 0.52 * SIDE, 0.48 * SIDE}, {SIDE, 0.6 * SIDE, 0.0}},
      {{1.3 * SIDE, 0.6 * SIDE, -0.2 * SIDE}, {0.5 * SIDE, 0.5 * SIDE, 0.5 * SIDE}},
      {{2.0 * SIDE, 1.0 * SIDE, 1.0 * SIDE}, {0.5 * SIDE, 0.5 * SIDE, 0.5 * SIDE}},
      {{1.5 * SIDE, 1.05 * SIDE, 2.0 * SIDE}, {0.5 * SIDE, 0.42 * SIDE, 0.5 * SIDE}}};
  return zs_gen_path(s, keys, (int)(sizeof keys / sizeof keys[0]), zs_gen_int(a, "frames"),
                     err);
}

static const zs_gen_param spheres_params[] = {
    {"count", ZS_GEN_INT, 1, ZS_GEN_SPHERES_MAX, ZS_GEN_SPHERES_MAX},
    {"moving", ZS_GEN_INT, 0, ZS_GEN_SPHERES_MAX, 0}, /* default: count */
    {"slices", ZS_GEN_INT, 3, 256, 24},
    {"stacks", ZS_GEN_INT, 2, 256, 24},
    {"seed", ZS_GEN_SEED, 0, 0, 0},
    {"frames", ZS_GEN_INT, 16, 100000, 300}};

const zs_gen_def zs_gen_spheres_def = {"spheres", spheres_params, 6, build_spheres, NULL};
