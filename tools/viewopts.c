#include "tools/viewopts.h"

#include "lib/frame_camera.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "raster/raster.h"
#include "tools/cli.h"

const char zs_view_opts_usage[] =
    "  --size WxH          image size (default: the scene's, else 1024x768)\n"
    "  --eye x,y,z         camera position (default: frame the input)\n"
    "  --target x,y,z      point looked at (default: centre of the input)\n"
    "  --up x,y,z          up direction (default 0,1,0)\n"
    "  --fovy DEG          vertical field of view (default 45)\n"
    "  --ortho L,R,B,T     orthographic camera showing that view rectangle\n"
    "  --near N --far F    clip planes (default: fit the input)\n"
    "  --up-axis y|z       the model's up axis (default y; z for most STL and CAD\n"
    "                      exports): the automatic camera stands upright on it\n"
    "  --view NAME         the automatic camera's side: front, back, left, right,\n"
    "                      top, bottom or iso (default: front, right and above)\n"
    "  --fit F             the automatic camera F times closer (default 1: the\n"
    "                      bounding sphere with 5 % to spare)\n"
    "  --grid WxH          a WxH image where world (x, y) falls on the centre of\n"
    "                      pixel column x, row H-1-y: orthographic, looking down -z\n"
    "                      from z = 10, near 5, far 15 (depth (5 - z) / 10), as the\n"
    "                      lecture's examples are drawn\n"
    "  --cull-back         drop faces turned away from the camera (default: drawn)\n";

void zs_view_opts_default(zs_view_opts *o, int width, int height) {
  memset(o, 0, sizeof *o); /* nothing given yet */
  o->width = width;
  o->height = height;
  zs_camera_default(&o->cam);
}

int zs_view_opts_parse(zs_view_opts *o, int argc, char **argv, int *i, zs_error *err) {
  const char *a = argv[*i], *v = NULL;
  zs_camera *c = &o->cam;
  if (strcmp(a, "--cull-back") == 0) {
    o->cull_back = 1;
    return 1;
  }
  static const char *const with_value[] = {"--size", "--eye",  "--target",  "--up",
                                           "--fovy", "--ortho", "--near",    "--far",
                                           "--up-axis", "--view", "--fit", "--grid"};
  int known = 0;
  for (size_t k = 0; k < sizeof with_value / sizeof with_value[0]; k++)
    known |= strcmp(a, with_value[k]) == 0;
  if (!known) return 0;
  if (zs_cli_value(argc, argv, i, &v, err)) return -1;
  zs_status st = ZS_OK;
  if (strcmp(a, "--size") == 0) {
    st = zs_cli_size(a, v, ZS_MAX_IMAGE_SIDE, &o->width, &o->height, err);
    o->size_given = 1;
  } else if (strcmp(a, "--eye") == 0) {
    st = zs_cli_vec3(a, v, c->eye, err);
    c->has_eye = 1;
  } else if (strcmp(a, "--target") == 0) {
    st = zs_cli_vec3(a, v, c->target, err);
    c->has_target = 1;
  } else if (strcmp(a, "--up") == 0) {
    st = zs_cli_vec3(a, v, c->up, err);
    c->has_up = 1;
    if (st == ZS_OK && c->up[0] == 0.0 && c->up[1] == 0.0 && c->up[2] == 0.0)
      st = zs_error_set(err, ZS_ERR_ARG, "--up: expected a direction, got '%s'", v);
  } else if (strcmp(a, "--fovy") == 0) {
    st = zs_cli_double(a, v, &c->fovy, err);
    o->fovy_given = 1;
    if (st == ZS_OK && !(c->fovy > 0.0 && c->fovy < 180.0))
      st = zs_error_set(err, ZS_ERR_ARG, "--fovy: expected degrees above 0 and below 180, got '%s'",
                        v);
  } else if (strcmp(a, "--ortho") == 0) {
    st = zs_cli_numbers(a, v, 4, "four finite numbers L,R,B,T", c->extent, err);
    c->ortho = 1;
    if (st == ZS_OK && !(c->extent[0] < c->extent[1] && c->extent[2] < c->extent[3]))
      st = zs_error_set(err, ZS_ERR_ARG, "--ortho: expected L < R and B < T, got '%s'", v);
  } else if (strcmp(a, "--up-axis") == 0) {
    if (strcmp(v, "y") != 0 && strcmp(v, "z") != 0)
      st = zs_error_set(err, ZS_ERR_ARG, "--up-axis: expected y or z, got '%s'", v);
    o->up_z = strcmp(v, "z") == 0;
  } else if (strcmp(a, "--view") == 0) {
    o->view = 0;
    for (int k = 0; k < ZS_VIEWS; k++)
      if (strcmp(v, zs_view_names[k]) == 0) o->view = k + 1;
    if (!o->view)
      st = zs_error_set(err, ZS_ERR_ARG,
                        "--view: expected front, back, left, right, top, bottom or iso, got '%s'", v);
  } else if (strcmp(a, "--grid") == 0) {
    st = zs_cli_size(a, v, ZS_MAX_IMAGE_SIDE, &o->width, &o->height, err);
    o->size_given = 1;
    const double extent[4] = {-0.5, o->width - 0.5, -0.5, o->height - 0.5};
    const double eye[3] = {0, 0, 10}, target[3] = {0, 0, 0};
    memcpy(c->extent, extent, sizeof extent);
    memcpy(c->eye, eye, sizeof eye);
    memcpy(c->target, target, sizeof target);
    c->ortho = c->has_eye = c->has_target = 1;
    if (!c->has_near) c->znear = 5, c->has_near = 1;
    if (!c->has_far) c->zfar = 15, c->has_far = 1;
  } else if (strcmp(a, "--fit") == 0) {
    st = zs_cli_double(a, v, &o->fit, err);
    if (st == ZS_OK && !(o->fit > 0 && o->fit <= 1000))
      st = zs_error_set(err, ZS_ERR_ARG, "--fit: expected a number above 0 (at most 1000), got '%s'", v);
  } else if (strcmp(a, "--near") == 0) {
    st = zs_cli_double(a, v, &c->znear, err);
    c->has_near = 1;
  } else {
    st = zs_cli_double(a, v, &c->zfar, err);
    c->has_far = 1;
  }
  if (st == ZS_OK && c->has_near && c->has_far && !(c->znear < c->zfar) &&
      (strcmp(a, "--near") == 0 || strcmp(a, "--far") == 0))
    st = zs_error_set(err, ZS_ERR_ARG, "--near %g --far %g: near must be less than far", c->znear,
                      c->zfar);
  if (st == ZS_OK && c->ortho && o->fovy_given)
    st = zs_error_set(err, ZS_ERR_ARG,
                      "--fovy and --ortho: an orthographic camera has no field of view");
  return st == ZS_OK ? 1 : -1;
}

const char *const zs_view_names[ZS_VIEWS] = {"front", "back", "left", "right",
                                              "top", "bottom", "iso"};

/* The automatic camera's direction (from the target) and up of each view,
 * for a model whose up is +y; a +z model turns them: (x, y, z) -> (x, -z, y). */
static const double view_dir[ZS_VIEWS][3] = {{0, 0, 1}, {0, 0, -1}, {-1, 0, 0}, {1, 0, 0},
                                             {0, 1, 0}, {0, -1, 0}, {1, 1, 1}};
static const double view_up[ZS_VIEWS][3] = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0},
                                            {0, 0, -1}, {0, 0, 1}, {0, 1, 0}};

static void turned(const double in[3], int up_z, double out[3]) {
  out[0] = in[0];
  out[1] = up_z ? -in[2] : in[1];
  out[2] = up_z ? in[1] : in[2];
}

void zs_view_opts_for_scene(const zs_view_opts *o, const zs_scene *s, zs_camera *cam, int *width,
                            int *height) {
  zs_camera u = o->cam;
  if (o->view || o->up_z) { /* the automatic camera's side, upright on the model's axis */
    const double fallback[3] = ZS_CAMERA_DEFAULT_DIR, y_up[3] = {0, 1, 0};
    turned(o->view ? view_dir[o->view - 1] : fallback, o->up_z, u.dir);
    u.has_dir = 1;
    if (!u.has_up) {
      turned(o->view ? view_up[o->view - 1] : y_up, o->up_z, u.up);
      u.has_up = 1;
    }
  }
  if (o->fit > 0) u.fit = o->fit;
  zs_frame_view(s, &u, o->fovy_given, cam);
  *width = o->size_given || !s->width ? o->width : s->width;
  *height = o->size_given || !s->height ? o->height : s->height;
}
