/* The Teapot scene of the CHC paper (experiment 2): many teapots in random
 * poses, arranged mostly in columns.  What the paper asks of it: many small
 * faces that only together hide what is behind them, holes to see other
 * teapots through, and from the side more than half of the objects in view.
 *
 * LAYOUT (all units those of the teapot data: a teapot is 6.43 x 3.15 x 4)
 *   One teapot mesh at `level`, instanced `count` times.  A teapot turns
 *   about its pivot PIVOT, and every point of it is within RADIUS of the
 *   pivot, so two teapots whose pivots are 2 RADIUS apart never touch.
 *   - count - count / 8 teapots stand in columns on a g x g grid of cells
 *     CELL apart, g = ceil(sqrt(in_columns / 6)) so that about a quarter of
 *     the cells stay empty.  The cells are taken in a shuffled order; each
 *     column is 4 .. 12 teapots high (the last one what is left; if the
 *     cells run out, the rest go one by one on top of the columns in
 *     order).  In a column, teapot k has its pivot at height
 *     RADIUS + GAP + k PITCH, moved by up to JITTER in x and z, and a
 *     uniformly random rotation.
 *   - count / 8 teapots stand upright on the ground at random yaw, at the
 *     corners between cells (shuffled), moved by up to JITTER.
 *   - a ground slab, the last object, one cell wider than the grid all
 *     round, 0.5 thick, its top at y = 0.
 *   The random draws, in order: the cell order, the column heights, the
 *   corner order; per teapot the jitter in x and z, the rotation (three
 *   numbers; a scattered teapot draws one, its yaw) and the palette entry;
 *   last the speeds of the `moving` first teapots (0.05 .. 0.2 units per
 *   frame along their local x axis).
 */
#include <math.h>
#include <stdlib.h>

#include "util/matrix.h"
#include "scene/gen_internal.h"
#include "scene/teapot.h"

static const double PIVOT[3] = {0.2, 1.575, 0.0};
#define RADIUS 3.4  /* every teapot point lies within this of PIVOT */
#define GAP 0.2     /* above the ground, below the first of a column */
#define PITCH 7.2   /* 2 RADIUS + 0.4: pivots up a column */
#define CELL 10.0   /* between column centres: about 3 RADIUS */
#define JITTER 0.8  /* largest move off a cell centre or corner */

enum { MIN_HEIGHT = 4, MAX_HEIGHT = 12 };

typedef struct layout {
  int g;           /* grid side, in cells */
  int ncolumns;
  int *cell;       /* cell number (row g + col) of column c */
  int *height;     /* teapots in column c */
  int *corner;     /* shuffled corners, (g+1)^2 of them */
} layout;

static void layout_free(layout *l) {
  free(l->cell);
  free(l->height);
  free(l->corner);
}

static zs_status plan(zs_rng *rng, int in_columns, layout *l) {
  int g = (int)ceil(sqrt(in_columns / 6.0));
  if (g < 1) g = 1;
  int ncells = g * g, ncorners = (g + 1) * (g + 1);
  l->g = g;
  l->cell = malloc((size_t)ncells * sizeof *l->cell);
  l->height = calloc((size_t)ncells, sizeof *l->height);
  l->corner = malloc((size_t)ncorners * sizeof *l->corner);
  if (!l->cell || !l->height || !l->corner) return ZS_ERR_NOMEM;
  for (int i = 0; i < ncells; i++) l->cell[i] = i;
  zs_rng_shuffle(rng, l->cell, (size_t)ncells, sizeof *l->cell);

  int left = in_columns, c = 0;
  for (; c < ncells && left > 0; c++) {
    int h = MIN_HEIGHT + (int)zs_rng_below(rng, MAX_HEIGHT - MIN_HEIGHT + 1);
    l->height[c] = h < left ? h : left;
    left -= l->height[c];
  }
  l->ncolumns = c;
  for (int k = 0; left > 0; k = (k + 1) % c, left--) l->height[k]++;

  for (int i = 0; i < ncorners; i++) l->corner[i] = i;
  zs_rng_shuffle(rng, l->corner, (size_t)ncorners, sizeof *l->corner);
  return ZS_OK;
}

/* The centre of cell (or corner) number n of an s x s grid, spacing CELL,
 * centred on the origin. */
static void grid_point(int n, int s, double *x, double *z) {
  *x = CELL * ((n % s) - (s - 1) / 2.0);
  *z = CELL * ((n / s) - (s - 1) / 2.0);
}

static zs_status build_teapots(const zs_gen_args *a, zs_scene *s, zs_error *err) {
  int count = zs_gen_int(a, "count"), moving = zs_gen_int(a, "moving");
  if (zs_gen_check_moving(a, moving, count, "count", err)) return err->code;
  zs_rng rng;
  zs_rng_seed(&rng, a->seed);

  int32_t teapot_mesh = zs_gen_teapot_mesh(s, zs_gen_int(a, "level"), err);
  if (teapot_mesh < 0) return err->code;

  int scattered = count / 8, in_columns = count - scattered;
  layout l = {0};
  if (plan(&rng, in_columns, &l)) {
    layout_free(&l);
    return ZS_GEN_NOMEM(err, a->spec);
  }
  int g = l.g, tallest = 0;

  double to_pivot[16];
  zs_mat_translate(to_pivot, -PIVOT[0], -PIVOT[1], -PIVOT[2]);
  int t = 0;
  for (int c = 0; c < l.ncolumns; c++) {
    double cx, cz;
    grid_point(l.cell[c], g, &cx, &cz);
    if (l.height[c] > tallest) tallest = l.height[c];
    for (int k = 0; k < l.height[c]; k++, t++) {
      double jx = zs_rng_range(&rng, -JITTER, JITTER);
      double jz = zs_rng_range(&rng, -JITTER, JITTER);
      double turn[16], move[16], place[16];
      zs_gen_random_rotation(&rng, turn);
      zs_mat_translate(move, cx + jx, RADIUS + GAP + k * PITCH, cz + jz);
      zs_gen_mul3(place, move, turn, to_pivot);
      uint32_t rgb = zs_gen_palette((int)zs_rng_below(&rng, ZS_GEN_PALETTE_SIZE));
      if (zs_gen_add_instance(s, teapot_mesh, place, rgb, err, "teapot_%d", t) < 0) {
        layout_free(&l);
        return err->code;
      }
    }
  }
  for (int k = 0; k < scattered; k++, t++) {
    double px, pz;
    grid_point(l.corner[k], g + 1, &px, &pz);
    double jx = zs_rng_range(&rng, -JITTER, JITTER);
    double jz = zs_rng_range(&rng, -JITTER, JITTER);
    double turn[16], move[16], place[16];
    zs_mat_rotate_turns(turn, zs_rng_uniform(&rng), 0.0, 1.0, 0.0);
    zs_mat_translate(move, px + jx, 0.0, pz + jz);
    zs_mat_mul(place, move, turn);
    uint32_t rgb = zs_gen_palette((int)zs_rng_below(&rng, ZS_GEN_PALETTE_SIZE));
    if (zs_gen_add_instance(s, teapot_mesh, place, rgb, err, "teapot_%d", t) < 0) {
      layout_free(&l);
      return err->code;
    }
  }
  layout_free(&l);

  /* The first `moving` teapots move along their local x axis. */
  for (int i = 0; i < moving; i++) zs_gen_move_along_x(s, i, zs_rng_range(&rng, 0.05, 0.2));

  double half = CELL * (g + 1) / 2.0;
  const double lo[3] = {-half, -0.5, -half}, hi[3] = {half, 0.0, half};
  if (zs_gen_ground(s, lo, hi, a->spec, err) < 0) return err->code;

  /* W: half the field's width; H: the height of the tallest column.  The
   * gap between two rows of columns nearest the middle is at x = gx. */
  double w = CELL * g / 2.0, h = RADIUS + GAP + tallest * PITCH;
  double gx = (g % 2 == 0) ? 0.0 : CELL / 2.0;
  const double side_eye[3] = {-0.35 * w, 0.5 * h + 0.1 * w, -2.6 * w - 30.0};
  const double side_target[3] = {0.0, 0.3 * h, 0.0};
  zs_gen_camera(s, side_eye, side_target, 0.5, 8.0 * (w + h + 50.0));
  /* From the side (open), into the field between two rows of columns at
   * mid height (occluded), up above it, across and down outside again. */
  const zs_gen_key keys[] = {
      {{-0.35 * w, 0.5 * h + 0.1 * w, -2.6 * w - 30.0}, {0.0, 0.3 * h, 0.0}},
      {{0.3 * w, 0.45 * h, -1.8 * w - 10.0}, {0.0, 0.3 * h, 0.0}},
      {{gx, 0.35 * h, -w - 8.0}, {gx, 0.35 * h, 0.0}},
      {{gx, 0.3 * h, -0.3 * w}, {gx, 0.3 * h, w}},
      {{gx, 0.3 * h, 0.3 * w}, {w, 0.35 * h, 0.4 * w}},
      {{0.5 * w, 1.2 * h, 0.7 * w}, {0.0, 0.0, 0.0}},
      {{-0.3 * w, 1.6 * h + 0.5 * w, 0.0}, {0.0, 0.0, 0.0}},
      {{-1.3 * w, 0.7 * h, 0.6 * w}, {0.0, 0.3 * h, 0.0}},
      {{-1.6 * w - 10.0, 4.0, -0.4 * w}, {0.0, 0.4 * h, 0.0}}};
  return zs_gen_path(s, keys, (int)(sizeof keys / sizeof keys[0]), zs_gen_int(a, "frames"),
                     err);
}

static const zs_gen_param teapots_params[] = {
    {"count", ZS_GEN_INT, 1, ZS_GEN_TEAPOTS_MAX, 600},
    {"level", ZS_GEN_INT, 1, 16, 4},
    {"moving", ZS_GEN_INT, 0, ZS_GEN_TEAPOTS_MAX, 0},
    {"seed", ZS_GEN_SEED, 0, 0, 0},
    {"frames", ZS_GEN_INT, 16, 100000, 300}};

const zs_gen_def zs_gen_teapots_def = {"teapots", teapots_params, 5, build_teapots, NULL};
