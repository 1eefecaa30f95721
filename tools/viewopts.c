#include "tools/viewopts.h"

#include "lib/frame.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "raster/raster.h"
#include "tools/cli.h"

const char zs_view_opts_usage[] =
    "  --size WxH          image size\n"
    "  --eye x,y,z         camera position (default: frame the input)\n"
    "  --target x,y,z      point looked at (default: centre of the input)\n"
    "  --up x,y,z          up direction (default 0,1,0)\n"
    "  --fovy DEG          vertical field of view (default 45)\n"
    "  --ortho L,R,B,T     orthographic camera showing that view rectangle\n"
    "  --near N --far F    clip planes (default: fit the input)\n"
    "  --cull-back         drop faces turned away from the camera\n";

void zs_view_opts_default(zs_view_opts *o, int width, int height) {
  o->width = width;
  o->height = height;
  o->cull_back = 0;
  zs_camera_default(&o->cam);
}

/* "l,r,b,t" */
static zs_status parse4(const char *opt, const char *s, double out[4], zs_error *err) {
  const char *p = s;
  for (int i = 0; i < 4; i++) {
    char *end;
    errno = 0;
    double v = strtod(p, &end);
    int sep_ok = i < 3 ? *end == ',' : *end == '\0';
    if (end == p || !sep_ok || !isfinite(v) || errno == ERANGE)
      return zs_error_set(err, ZS_ERR_ARG, "%s: expected four finite numbers L,R,B,T, got '%s'",
                          opt, s);
    out[i] = v;
    p = end + 1;
  }
  return ZS_OK;
}

int zs_view_opts_parse(zs_view_opts *o, int argc, char **argv, int *i, zs_error *err) {
  const char *a = argv[*i], *v = NULL;
  zs_camera *c = &o->cam;
  if (strcmp(a, "--cull-back") == 0) {
    o->cull_back = 1;
    return 1;
  }
  static const char *const with_value[] = {"--size", "--eye", "--target", "--up",
                                           "--fovy", "--ortho", "--near", "--far"};
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
  } else if (strcmp(a, "--fovy") == 0) {
    st = zs_cli_double(a, v, &c->fovy, err);
    o->fovy_given = 1;
  } else if (strcmp(a, "--ortho") == 0) {
    st = parse4(a, v, c->extent, err);
    c->ortho = 1;
  } else if (strcmp(a, "--near") == 0) {
    st = zs_cli_double(a, v, &c->znear, err);
    c->has_near = 1;
  } else {
    st = zs_cli_double(a, v, &c->zfar, err);
    c->has_far = 1;
  }
  return st == ZS_OK ? 1 : -1;
}

void zs_view_opts_for_scene(const zs_view_opts *o, const zs_scene *s, zs_camera *cam, int *width,
                            int *height) {
  zs_frame_view(s, &o->cam, o->fovy_given, cam);
  *width = o->size_given || !s->width ? o->width : s->width;
  *height = o->size_given || !s->height ? o->height : s->height;
}
