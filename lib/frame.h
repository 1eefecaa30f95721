/* zscan lib — one frame of a scene, into an image: the path shared by
 * `zscan render`, the golden tests and the benchmarks. */
#ifndef ZS_LIB_FRAME_H
#define ZS_LIB_FRAME_H

#include "raster/raster.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "lib/image.h"
#include "lib/scene_draw.h"
#include "lib/shadow.h"
#include "zscan/layer.h"

#define ZS_BACKGROUND_RGB 0x1E2228u /* flat shading's background */

#define ZS_HIDDEN_LINE_PAPER 0xFFFFFFu /* hidden-line style: background */
#define ZS_HIDDEN_LINE_INK 0x000000u   /* and the lines */

/* What a frame draws: the faces; their visible edges alone, ink on
 * paper (hidden lines); or the faces with their visible edges over them
 * in ink (a wireframe over the solid, its edges offset towards the eye as
 * the hidden lines' are, so that no face stitches through them). */
typedef enum zs_frame_style {
  ZS_STYLE_SOLID,
  ZS_STYLE_HIDDEN_LINE,
  ZS_STYLE_WIREFRAME
} zs_frame_style;

/* The style the options' two flags ask for (both: hidden lines; callers
 * refuse that first). */
static inline zs_frame_style zs_frame_style_of(int hidden_line, int wireframe) {
  return hidden_line ? ZS_STYLE_HIDDEN_LINE : wireframe ? ZS_STYLE_WIREFRAME : ZS_STYLE_SOLID;
}

/* How a frame draws: its style, and the width of its lines and the size
 * and shape of its points (zs_device_draw_lines, _points); NULL where
 * one is taken: solid, 1, 1, squares. */
typedef struct zs_frame_look {
  zs_frame_style style;
  double line_width, point_size; /* pixels; 0: 1 */
  zs_point_shape point_shape;
} zs_frame_look;

typedef struct zs_frame_opts {
  int width, height;
  zs_algo algo;
  zs_shade shade;
  int cull_back, threads;
  zs_frame_style style;
  zs_filter filter; /* every texture's filter; 0: each material's */
  const zs_light *lights; /* NULL: the scene's, else the device's headlight */
  int nlights;
  const zs_shadow_opts *shadows; /* NULL: no shadows (lib/shadow.h) */
  int samples;      /* 0 or 1: one sample a pixel; 2, 4, 8, 16 */
  int per_sample;   /* supersampled: shaded at each sample */
  double line_width, point_size; /* zs_frame_look's */
  zs_point_shape point_shape;
} zs_frame_opts;

/* The lights of a frame: lights[0 .. n) when n > 0, else the scene's
 * when it has any, else the device's default (zs_device_set_lights). */
zs_status zs_frame_set_lights(zs_device *dev, const zs_scene *scene, const zs_light *lights,
                              int n, zs_error *err);

/* Whether the hidden-line style can draw with algo and shade: its edges
 * are tested against the faces' full-frame depth buffer, which zbuffer
 * mode alone keeps, and its picture is ink on paper, not a shading.  The
 * rule lives here once; the library and the command each word a refusal
 * in their own terms (fields here, flags there). */
int zs_frame_hidden_line_fits(zs_algo algo, zs_shade shade);
/* The same for the wireframe over the solid: zbuffer mode, and a shading
 * of the surfaces (the id, depth and overdraw shadings colour a pixel
 * from the buffers, over any ink). */
int zs_frame_wireframe_fits(zs_algo algo, zs_shade shade);
/* The device's shading for a frame of style drawn with shade: flat for
 * hidden lines, whose faces are paper that hides (a transparent face
 * too, as in the SVG of the same lines), else shade. */
zs_shade zs_frame_device_shade(zs_frame_style style, zs_shade shade);

/* Renders scene seen by cam (completed from the scene's bounds where it is
 * partial) into out (allocated here), and the window depth (1 = far) into
 * depth when it is not NULL (width * height floats, row 0 at the top).
 * stats, when not NULL, gets the frame's counters. */
zs_status zs_frame_render(const zs_scene *scene, const zs_camera *cam,
                          const zs_frame_opts *o, zs_image *out, float *depth,
                          zs_raster_stats *stats, zs_error *err);

/* The same with a device made by the caller and kept across frames
 * (`--repeat`): the device's size and modes are used.  out may be NULL
 * (and then depth too): the frame is rendered, its rows shaded and
 * dropped, and its buffers stay in the device. */
zs_status zs_frame_render_on(zs_device *dev, const zs_scene *scene,
                             const double view[16], const double proj[16],
                             const zs_frame_look *look, zs_image *out, float *depth,
                             zs_error *err);

/* The same, anti-aliased: samples (1, 2, 4, 8 or 16) frames, each with
 * proj moved so that the pixels' centres fall on one of the standard
 * sample positions (lib/samples.h), and out (allocated by the caller; NULL:
 * drawn and dropped) each channel's mean over them, (sum + samples / 2) /
 * samples.  Multisampled (per_sample 0): every sample shaded at the
 * pixel's centre, from the face that covers the sample (flat shading is
 * the same either way); supersampled (1): at the sample.  stats, when not
 * NULL, gets the counters summed over the samples' frames.  samples 1:
 * zs_frame_render_on's frame. */
zs_status zs_frame_render_samples(zs_device *dev, const zs_scene *scene, const double view[16],
                                  const double proj[16], const zs_frame_look *look, int samples,
                                  int per_sample, zs_image *out, zs_raster_stats *stats,
                                  zs_error *err);

/* The eye-space unit normals of what scene shows from (view, proj), into
 * xyz (3 floats a pixel, row 0 at the top; 0, 0, 0 where no face is): one
 * frame of every instance on a device configured as cfg but shaded
 * ZS_SHADE_NORMAL, handing out normals (zs_device_set_normals), so that every face has them
 * (its corners', else its plane's).  The `--normals` of zscan render. */
zs_status zs_frame_render_normals(const zs_device_config *cfg, const zs_scene *scene,
                                  const double view[16], const double proj[16], float *xyz,
                                  zs_error *err);

/* Ends the device's frame into out (and depth, when not NULL). */
zs_status zs_frame_finish(zs_device *dev, zs_image *out, float *depth, zs_error *err);
/* The same, and into layer too when it is not NULL (of the device's size:
 * zs_layer_alloc). */
zs_status zs_frame_finish_into(zs_device *dev, zs_image *out, float *depth, zs_layer *layer,
                               zs_error *err);

#endif
