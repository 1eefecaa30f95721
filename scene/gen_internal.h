/* zscan scene — what the generators share (scene/gen_*.c), not a public
 * interface: the parameter tables the spec parser reads, and helpers for
 * matrices, meshes, instances and camera paths. */
#ifndef ZS_SCENE_GEN_INTERNAL_H
#define ZS_SCENE_GEN_INTERNAL_H

#include <stdarg.h>
#include <stdint.h>

#include "zscan/error.h"
#include "util/compiler.h"
#include "util/rng.h"
#include "scene/generate.h"
#include "scene/model.h"
#include "scene/scene.h"

enum { ZS_GEN_MAX_PARAMS = 12 };

/* ---- parameters -------------------------------------------------------- */

typedef enum zs_gen_kind {
  ZS_GEN_INT,   /* a whole number in lo .. hi */
  ZS_GEN_REAL,  /* a real number in lo .. hi */
  ZS_GEN_SEED   /* 0 .. 2^64 - 1, default ZS_GEN_DEFAULT_SEED */
} zs_gen_kind;

typedef struct zs_gen_param {
  const char *key;
  zs_gen_kind kind;
  double lo, hi, def; /* range and default (not for seeds) */
} zs_gen_param;

struct zs_gen_args;

/* A generated thing: its name, its parameters, and the function that
 * builds it from parsed arguments (a scene or a mesh, by the table). */
typedef struct zs_gen_def {
  const char *name;
  const zs_gen_param *params;
  int nparams;
  zs_status (*scene)(const struct zs_gen_args *a, zs_scene *s, zs_error *err);
  zs_status (*mesh)(const struct zs_gen_args *a, zs_model *m, zs_error *err);
} zs_gen_def;

/* The parsed values of a spec, defaults filled in. */
typedef struct zs_gen_args {
  const char *spec;             /* as given, for messages */
  const zs_gen_def *def;
  double value[ZS_GEN_MAX_PARAMS];
  int given[ZS_GEN_MAX_PARAMS];
  uint64_t seed;
} zs_gen_args;

/* The value of parameter key (which must be in the table). */
int zs_gen_int(const zs_gen_args *a, const char *key);
double zs_gen_real(const zs_gen_args *a, const char *key);
/* Whether key was given in the spec. */
int zs_gen_given(const zs_gen_args *a, const char *key);

extern const zs_gen_def zs_gen_teapots_def, zs_gen_spheres_def,
    zs_gen_city_def, zs_gen_plant_def, zs_gen_cubes_def, zs_gen_default_def;

/* Mesh specs (scene/gen_mesh.c). */
extern const zs_gen_def zs_gen_mesh_defs[];
extern const int zs_gen_mesh_ndefs;

/* ---- placing (gen_matrix.c; raster.h conventions, built on zs_mat_*) -- */

/* A uniformly random rotation (Shoemake's method: a uniform unit
 * quaternion from three uniform numbers). */
void zs_gen_random_rotation(zs_rng *rng, double m[16]);

/* out = a * b * c (apply c first). */
void zs_gen_mul3(double out[16], const double a[16], const double b[16],
                 const double c[16]);

/* The affine map taking the local axes x, y, z to the columns ax, ay, az
 * and the origin to o (no normalisation: lengths are scales). */
void zs_gen_frame(double m[16], const double ax[3], const double ay[3],
                  const double az[3], const double o[3]);

/* The unit box [-0.5, 0.5]^3 stretched onto lo .. hi. */
void zs_gen_box_matrix(double m[16], const double lo[3], const double hi[3]);

/* A part along local y placed from `from`, its y axis along the unit
 * direction d scaled by len, its x and z axes across d scaled by r. */
void zs_gen_along(double m[16], const double from[3], const double d[3], double len,
                  double r);

/* The same from a to b: local y from 0 to 1 runs from a to b. */
void zs_gen_between(double m[16], const double a[3], const double b[3], double r);

/* ---- the mesh kit (gen_mesh.c; the primitives are in generate.h) -------- */

/* A fresh model with one object named name; -1 (err set) when out of memory,
 * else the object index 0. */
int32_t zs_gen_model(zs_model *m, const char *name, zs_error *err);

/* The box x0 .. x1, y0 .. y1, z0 .. z1 placed by xf (NULL: none), object 0. */
zs_status zs_gen_box_at(zs_model *m, double x0, double y0, double z0, double x1, double y1,
                        double z1, const double *xf, uint32_t rgb);

/* A round rod from a to b (any direction), radius r, capped, object 0. */
zs_status zs_gen_rod(zs_model *m, const double a[3], const double b[3], double r,
                     int segments, uint32_t rgb);

/* A whole torus lying around the y axis, centred at height y, then placed
 * by xf (NULL: none), object 0. */
zs_status zs_gen_ring_y(zs_model *m, double major, double minor, double y, int around,
                        int sides, const double *xf, uint32_t rgb);

/* A lathe profile under construction: n points (r, y). */
typedef struct zs_gen_profile {
  double *pt;
  int32_t n, cap;
} zs_gen_profile;

/* Appends (r, y); 0 when out of memory. */
int zs_gen_pt(zs_gen_profile *pr, double r, double y);

/* From the last point to (r, y) in `steps` equal steps; 0 when out of
 * memory. */
int zs_gen_line_to(zs_gen_profile *pr, double r, double y, int steps);

/* Turns the profile into a lathe (zs_gen_lathe, object 0) when complete
 * (every point went in), else ZS_ERR_NOMEM; empties it either way, for the
 * next. */
zs_status zs_gen_profile_lathe(zs_model *m, zs_gen_profile *pr, int complete, int around,
                               int caps, const double *xf, uint32_t rgb);

/* ---- colours (gen_common.c) -------------------------------------------- */

#define ZS_GEN_GROUND_RGB 0x9C968Cu /* warm grey */

enum { ZS_GEN_PALETTE_SIZE = 12 };

/* Colour i (0 .. ZS_GEN_PALETTE_SIZE - 1) of a palette of soft, distinct
 * hues, 0xRRGGBB. */
uint32_t zs_gen_palette(int i);

/* ---- scene building (gen_common.c) ------------------------------------- */

/* Adds *m (consumed) to s; returns its index or -1 after setting err. */
int32_t zs_gen_add_mesh(zs_scene *s, zs_model *m, zs_error *err);

/* Adds an instance named printf(fmt, ...); -1 after setting err. */
int32_t zs_gen_add_instance(zs_scene *s, int32_t mesh, const double model[16],
                            uint32_t rgb, zs_error *err, const char *fmt, ...) ZS_PRINTF_LIKE(6, 7);

/* The same with the arguments of fmt in ap. */
int32_t zs_gen_add_instance_v(zs_scene *s, int32_t mesh, const double model[16],
                              uint32_t rgb, zs_error *err, const char *fmt, va_list ap);

/* Instance in moves along its local x axis at speed (world units a
 * frame). */
void zs_gen_move_along_x(zs_scene *s, int32_t in, double speed);

/* Adds one teapot mesh (object "teapot", grey, tessellated at level) to
 * s; returns its mesh index, or -1 with err set. */
int32_t zs_gen_teapot_mesh(zs_scene *s, int level, zs_error *err);

/* Refuses more moving objects than there are ("SPEC: moving: N is more
 * than WHAT (MAX)"). */
zs_status zs_gen_check_moving(const zs_gen_args *a, int moving, int max, const char *what,
                              zs_error *err);

/* Adds the ground: a slab from lo to hi (object "ground", ZS_GEN_GROUND_RGB)
 * as one mesh with one instance named "ground"; its instance index, or -1
 * with err set (spec names the scene in the message). */
int32_t zs_gen_ground(zs_scene *s, const double lo[3], const double hi[3], const char *spec,
                      zs_error *err);

/* Sets the scene's camera to look from eye at target (up +y), fovy 45,
 * near/far as given, image 1024 x 768. */
void zs_gen_camera(zs_scene *s, const double eye[3], const double target[3],
                   double znear, double zfar);

/* A path through the keys (eye and target each), frames frames long
 * (frames >= nkeys): key k is placed at a frame proportional to the
 * distance travelled so far (eye moves plus a quarter of target moves),
 * the first at 0 and the last at frames - 1, each at least one frame
 * after the one before.  up is +y. */
typedef struct zs_gen_key {
  double eye[3], target[3];
} zs_gen_key;

zs_status zs_gen_path(zs_scene *s, const zs_gen_key *keys, int nkeys,
                      int frames, zs_error *err);

/* Sets the scene's bounds. */
void zs_gen_bounds(zs_scene *s, const double lo[3], const double hi[3]);

/* The number of segments for a base count at a detail: round(base *
 * detail), at least min. */
int zs_gen_segments(double base, double detail, int min);

#define ZS_GEN_NOMEM(err, what) \
  zs_error_set((err), ZS_ERR_NOMEM, "%s: out of memory", (what))

#endif
