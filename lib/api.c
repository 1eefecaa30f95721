/* The public API's own functions (zscan/zscan.h): the version, scenes
 * behind an opaque handle, and one call that renders as `zscan render`
 * does.  Everything else public is the device's and the images'. */
#include <stdlib.h>
#include <string.h>

#include "lib/frame.h"
#include "lib/frame_camera.h"
#include "lib/input.h"
#include "lib/object_visibility.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "zscan/zscan.h"

const char *zs_version(void) { return ZSCAN_VERSION_STRING; }

int zs_pixel_version(void) { return ZSCAN_PIXEL_VERSION; }

/* docs/CHANGES.md, a line a version, from 1 */
static const char *const pixel_changes[] = {
    "the first numbered: every output as zscan 0.9.0 draws it",
    "zscan render --stats prints its modelled milliseconds from the integer picoseconds, "
    "rounded to the nearest nanosecond, halves up: a time ending in exactly half a "
    "nanosecond may print one more in its last digit",
    "transparent faces (material, texture or vertex-colour alpha below 255) are composited "
    "in depth order over the opaque surface, where they were drawn opaque before: models "
    "with such alpha change, opaque ones do not",
    "a model's lines and points (OBJ l and p, glTF LINES and POINTS, PLY edges and point "
    "clouds) are drawn, by GL's rules for aliased lines and points, where they were dropped "
    "before: models with them change, models without them do not",
    "zscan query and zs_query_objects: an object with transparent faces hides nothing (the "
    "others own the pixels, and the boxes pass the samples, seen through it): counts of "
    "scenes with transparency change, images do not; models through assimp with a normal "
    "or colour that is not a finite number, an empty face or a malformed PLY header are "
    "refused",
    "the edges of the hidden-line and wireframe styles take the line width (zscan render "
    "--line-width, zs_render_opts.line_width), as a model's lines do, and the SVG's stroke "
    "with them: images with a width other than 1 change, images at width 1 do not; a nan or "
    "inf in a text PLY, OFF or STL file is refused with its line",
    "a text OFF file's face of no or more than 9 corners, with fewer corners than it counts, "
    "or with a corner that is no vertex index below the header's count is refused with its "
    "line, where assimp dropped the face or took another vertex; a layer file with a pixel "
    "that is neither a face nor the background is refused; a vertex not a finite number in "
    "a binary model is refused where assimp's joining of vertices hid it; a light's "
    "direction whose square overflows or vanishes lights as its unit vector; zscan render's "
    "camera options out of range exit 2 naming the option, and --camera refuses the options "
    "that place a view; a text PLY file with lines unlike its header is refused; "
    "hidden-line faces are all opaque paper, and a model's lines and "
    "points are drawn over it",
};

_Static_assert(sizeof pixel_changes / sizeof *pixel_changes == ZSCAN_PIXEL_VERSION,
               "a line in pixel_changes (and docs/CHANGES.md) for each pixel version");

const char *zs_pixel_changes(int v) {
  return v >= 1 && v <= ZSCAN_PIXEL_VERSION ? pixel_changes[v - 1] : NULL;
}

zs_status zs_scene_load(const char *input, const zs_load_opts *opts, zs_scene **out,
                        zs_error *err) {
  *out = NULL;
  zs_scene *s = malloc(sizeof *s);
  if (!s) return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  int flags = 0;
  if (opts && opts->allow_empty) flags |= ZS_INPUT_ALLOW_EMPTY;
  if (opts && opts->skip_missing_textures) flags |= ZS_INPUT_SKIP_MISSING_TEXTURES;
  zs_status st = zs_input_load(input, flags, s, err);
  if (st != ZS_OK) {
    free(s);
    return st;
  }
  *out = s;
  return ZS_OK;
}

void zs_scene_destroy(zs_scene *scene) {
  if (!scene) return;
  zs_scene_free(scene);
  free(scene);
}

int32_t zs_scene_objects(const zs_scene *scene) { return scene->ninst; }

const char *zs_scene_notes(const zs_scene *scene) {
  return scene->notes.text ? scene->notes.text : "";
}

/* The camera and the frame's options that opts ask for, on scene: the
 * user's camera over the scene's, as the command's options are. */
static zs_status settle(const zs_scene *scene, const zs_render_opts *opts, zs_camera *cam,
                        zs_frame_opts *fo, zs_shadow_opts *so, zs_error *err) {
  static const zs_render_opts none;
  const zs_render_opts *o = opts ? opts : &none;
  if (o->width < 0 || o->height < 0 || o->threads < 0)
    return zs_error_set(err, ZS_ERR_ARG, "zs_render_opts: negative size or thread count");
  zs_camera user;
  zs_camera_default(&user);
  memcpy(user.eye, o->eye, sizeof user.eye);
  memcpy(user.target, o->target, sizeof user.target);
  memcpy(user.up, o->up, sizeof user.up);
  user.has_eye = o->has_eye;
  user.has_target = o->has_target;
  user.has_up = o->has_up;
  user.fovy = o->fovy;
  user.znear = o->znear;
  user.has_near = o->znear != 0.0;
  user.zfar = o->zfar;
  user.has_far = o->zfar != 0.0;
  zs_frame_view(scene, &user, o->fovy != 0.0, cam);
  int width, height;
  zs_frame_size(scene, o->width, o->height, &width, &height);
  if ((unsigned)o->filter > ZS_FILTER_TRILINEAR)
    return zs_error_set(err, ZS_ERR_ARG, "zs_render_opts.filter: unknown filter %d", (int)o->filter);
  if (o->nlights < 0 || o->nlights > ZS_MAX_LIGHTS || (o->nlights > 0 && !o->lights))
    return zs_error_set(err, ZS_ERR_ARG, "zs_render_opts.lights: %d lights at %s", o->nlights,
                        o->lights ? "an array" : "NULL");
  if (o->hidden_line && o->wireframe)
    return zs_error_set(err, ZS_ERR_ARG, "zs_render_opts: hidden_line and wireframe: one style");
  const zs_frame_style style = zs_frame_style_of(o->hidden_line, o->wireframe);
  if (o->shadow_size != 0 &&
      (o->shadow_size < ZS_SHADOW_MIN_SIZE || o->shadow_size > ZS_SHADOW_MAX_SIZE))
    return zs_error_set(err, ZS_ERR_ARG, "zs_render_opts.shadow_size: %d: %d to %d (0: %d)",
                        o->shadow_size, ZS_SHADOW_MIN_SIZE, ZS_SHADOW_MAX_SIZE,
                        ZS_SHADOW_DEFAULT_SIZE);
  *so = (zs_shadow_opts){o->shadows != 0, o->shadow_size, ZS_SHADOW_BIAS_UNITS,
                         ZS_SHADOW_BIAS_SLOPE};
  if (o->has_shadow_bias) {
    so->units = o->shadow_bias[0];
    so->slope = o->shadow_bias[1];
    if (!(so->units >= 0.0 && so->units <= 4294967296.0 && so->slope >= 0.0 && so->slope <= 1e6))
      return zs_error_set(err, ZS_ERR_ARG, "zs_render_opts.shadow_bias: %g, %g: units 0 to 2^32, "
                          "slope 0 to 1e6", so->units, so->slope);
  }
  if (o->line_width != 0.0 && !(o->line_width > 0.0 && o->line_width <= ZS_MAX_LINE_WIDTH))
    return zs_error_set(err, ZS_ERR_ARG, "zs_render_opts.line_width: %g: above 0 and at most %d "
                        "(0: 1)", o->line_width, ZS_MAX_LINE_WIDTH);
  if (o->point_size != 0.0 && !(o->point_size > 0.0 && o->point_size <= ZS_MAX_POINT_SIZE))
    return zs_error_set(err, ZS_ERR_ARG, "zs_render_opts.point_size: %g: above 0 and at most %d "
                        "(0: 1)", o->point_size, ZS_MAX_POINT_SIZE);
  if ((unsigned)o->point_shape > ZS_POINT_DISC)
    return zs_error_set(err, ZS_ERR_ARG, "zs_render_opts.point_shape: unknown shape %d",
                        (int)o->point_shape);
  *fo = (zs_frame_opts){width,    height,   o->algo, o->shade, o->cull_back, o->threads ? o->threads : 1,
                        style, o->filter, o->lights, o->nlights, so,
                        o->samples, o->supersample, o->line_width, o->point_size, o->point_shape};
  return ZS_OK;
}

zs_status zs_render(const zs_scene *scene, const zs_render_opts *opts, zs_image *out,
                    float **depth, zs_raster_stats *stats, zs_error *err) {
  out->width = out->height = 0;
  out->rgb = NULL;
  if (depth) *depth = NULL;
  zs_camera cam;
  zs_frame_opts fo = {0};
  zs_shadow_opts so;
  zs_status st = settle(scene, opts, &cam, &fo, &so, err);
  if (st != ZS_OK) return st;
  float *d = NULL;
  if (depth && !(d = malloc((size_t)fo.width * (size_t)fo.height * sizeof *d)))
    return zs_error_set(err, ZS_ERR_NOMEM, "zs_render: out of memory");
  if (fo.algo == ZS_ALGO_DEPTHSORT && zs_scene_has_prims(scene))
    st = zs_error_set(err, ZS_ERR_ARG, "zs_render_opts.algo: the scene's lines and points need "
                      "ZS_ALGO_ZBUFFER or ZS_ALGO_SCANLINE");
  else st = zs_frame_render(scene, &cam, &fo, out, d, stats, err);
  if (st != ZS_OK || !depth) free(d);
  else *depth = d;
  return st;
}

zs_status zs_render_normals(const zs_scene *scene, const zs_render_opts *opts, float **xyz,
                            zs_error *err) {
  *xyz = NULL;
  zs_camera cam;
  zs_frame_opts fo = {0};
  zs_shadow_opts so;
  zs_status st = settle(scene, opts, &cam, &fo, &so, err);
  if (st != ZS_OK) return st;
  double view[16], proj[16];
  if ((st = zs_frame_camera(scene, &cam, fo.width, fo.height, view, proj, err))) return st;
  float *n = calloc(3 * (size_t)fo.width * (size_t)fo.height, sizeof *n);
  if (!n) return zs_error_set(err, ZS_ERR_NOMEM, "zs_render_normals: out of memory");
  const zs_device_config cfg = {fo.width,     fo.height,  fo.algo,           ZS_SHADE_NORMAL,
                                fo.cull_back, fo.threads, ZS_BACKGROUND_RGB, 0, (int)fo.filter};
  if ((st = zs_frame_render_normals(&cfg, scene, view, proj, n, err))) {
    free(n);
    return st;
  }
  *xyz = n;
  return ZS_OK;
}

zs_status zs_query_objects(const zs_scene *scene, const zs_render_opts *opts,
                           zs_object_visibility **out, int32_t *n, zs_error *err) {
  *out = NULL;
  *n = 0;
  zs_camera cam;
  zs_frame_opts fo = {0};
  zs_shadow_opts so;
  zs_status st = settle(scene, opts, &cam, &fo, &so, err);
  if (st != ZS_OK) return st;
  return zs_query_objects_at(scene, &cam, fo.width, fo.height, fo.cull_back,
                             opts ? opts->samples : 0, fo.shade, out, n, err);
}
