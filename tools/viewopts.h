/* zscan tools — the options that say what a frame sees, shared by every
 * command that renders: --size, --eye, --target, --up, --fovy, --ortho,
 * --near, --far, --cull-back, --up-axis, --view, --fit. */
#ifndef ZS_TOOLS_VIEWOPTS_H
#define ZS_TOOLS_VIEWOPTS_H

#include "zscan/error.h"
#include "scene/camera.h"
#include "scene/scene.h"

typedef struct zs_view_opts {
  int width, height;
  zs_camera cam;
  int cull_back;
  int size_given, fovy_given; /* what the user said; the rest may come
                                 from the scene */
  int up_z;                   /* --up-axis z: the model's up is +z */
  int view;                   /* --view: 0 none, else 1 + the index of the name */
  double fit;                 /* --fit: 0 none */
} zs_view_opts;

/* width x height, a default camera (framed later from the input). */
void zs_view_opts_default(zs_view_opts *o, int width, int height);

/* When argv[*i] is a view option, takes it (and its value, advancing *i)
 * and returns 1; returns 0 when it is not one, -1 on a bad value. */
int zs_view_opts_parse(zs_view_opts *o, int argc, char **argv, int *i, zs_error *err);

/* The frame the user asked for of scene s: the scene's camera and size
 * where the options say nothing, each option given overriding it.  cam,
 * width and height must not point into *o. */
void zs_view_opts_for_scene(const zs_view_opts *o, const zs_scene *s, zs_camera *cam, int *width,
                            int *height);

enum { ZS_VIEWS = 7 };
/* --view's names: front, back, left, right, top, bottom, iso. */
extern const char *const zs_view_names[ZS_VIEWS];

/* The usage lines of these options. */
extern const char zs_view_opts_usage[];

#endif
