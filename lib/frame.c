/* One frame of a scene into an image (lib/frame.h). */
#include "lib/frame.h"

#include <stdlib.h>
#include <string.h>

#include "lib/frame_camera.h"
#include "lib/samples.h"

typedef struct gather {
  zs_image *im;
  float *depth;
  float *normals; /* 3 a pixel */
  zs_layer *layer;
} gather;

static void gather_row(void *user, const zs_row *row) {
  gather *g = user;
  size_t off = (size_t)row->y * (size_t)row->width;
  if (g->layer) zs_layer_row_sink(g->layer, row);
  if (g->normals && row->normal)
    memcpy(g->normals + 3 * off, row->normal, 3 * (size_t)row->width * sizeof *row->normal);
  if (!g->im) return; /* the rows shaded and dropped: a frame timed */
  memcpy(g->im->rgb + off, row->rgb, (size_t)row->width * sizeof *row->rgb);
  if (g->depth)
    for (int x = 0; x < row->width; x++)
      g->depth[off + (size_t)x] =
          row->depth[x] == ZS_DEPTH_FAR ? 1.0f : (float)(row->depth[x] / 4294967296.0);
}

/* The frame's draws, every row then given to sink. */
static zs_status render_into(zs_device *dev, const zs_scene *scene, const double view[16],
                             const double proj[16], const zs_frame_look *look, zs_row_sink sink,
                             void *user, zs_error *err) {
  const zs_frame_look solid = {ZS_STYLE_SOLID, 1.0, 1.0, ZS_POINT_SQUARE};
  if (!look) look = &solid;
  const zs_frame_style style = look->style;
  if (zs_frame_draw_all(dev, scene, view, proj, err)) return err->code;
  const double line_width = look->line_width > 0.0 ? look->line_width : 1.0;
  /* hidden lines: the faces stay in the depth buffer; the picture is
   * their edges, and the model's own lines and points, drawn over the
   * paper (before it, the paper hid them while their depth hid edges) */
  if (style == ZS_STYLE_HIDDEN_LINE && zs_device_fill_color(dev, ZS_HIDDEN_LINE_PAPER, err))
    return err->code;
  if (zs_frame_draw_prims(dev, scene, line_width, look->point_size, look->point_shape, err))
    return err->code;
  if (style != ZS_STYLE_SOLID) {
    for (int32_t i = 0; i < scene->ninst; i++) {
      const zs_instance *in = &scene->inst[i];
      if (zs_device_draw_wide_edges(dev, &scene->meshes[in->mesh].mesh, in->model,
                                    ZS_HIDDEN_LINE_INK, line_width, err))
        return err->code;
    }
  }
  /* every row goes out, kept or not: the shadings that read attributes
   * colour a pixel only when its row does (raster/surface.h) */
  return zs_device_finish(dev, sink, user, err);
}

zs_status zs_frame_render_on(zs_device *dev, const zs_scene *scene,
                             const double view[16], const double proj[16],
                             const zs_frame_look *look, zs_image *out, float *depth,
                             zs_error *err) {
  gather g = {out, depth, NULL, NULL};
  return render_into(dev, scene, view, proj, look, gather_row, &g, err);
}

static void add_stats(zs_raster_stats *sum, const zs_raster_stats *s) {
  uint64_t *a = (uint64_t *)sum;
  const uint64_t *b = (const uint64_t *)s;
  for (size_t k = 0; k < sizeof *s / sizeof *a; k++) a[k] += b[k];
}

/* The samples' sums of each pixel, as two words: red and blue in the
 * lanes of 0xRR00BB (bits 16 and 0 on), green as 0xGG00 (bit 8 on).  A
 * lane's sum of 16 samples and the rounding's half take 12 bits, clear of
 * the lane above, so a sample adds two masked words a pixel, taken from
 * each row as it is shaded (still in cache). */
typedef struct sample_sums {
  uint32_t *rb, *g;
  int first; /* the first sample's rows set the sums: nothing to clear */
} sample_sums;

static void add_row(void *user, const zs_row *row) {
  const sample_sums *a = user;
  const size_t off = (size_t)row->y * (size_t)row->width;
  uint32_t *restrict rb = a->rb + off, *restrict g = a->g + off;
  const uint32_t *restrict c = row->rgb;
  const int n = row->width;
  if (a->first) {
    for (int x = 0; x < n; x++) rb[x] = c[x] & 0xFF00FFu, g[x] = c[x] & 0xFF00u;
  } else {
    for (int x = 0; x < n; x++) rb[x] += c[x] & 0xFF00FFu, g[x] += c[x] & 0xFF00u;
  }
}

zs_status zs_frame_render_samples(zs_device *dev, const zs_scene *scene, const double view[16],
                                  const double proj[16], const zs_frame_look *look, int samples,
                                  int per_sample, zs_image *out, zs_raster_stats *stats,
                                  zs_error *err) {
  if (samples <= 1) {
    zs_status st = zs_frame_render_on(dev, scene, view, proj, look, out, NULL, err);
    if (st == ZS_OK && stats) *stats = *zs_device_stats(dev);
    return st;
  }
  const zs_device_config *cfg = zs_device_config_of(dev);
  const int w = cfg->width, h = cfg->height;
  const size_t n = (size_t)w * (size_t)h;
  const int8_t *pos = zs_sample_positions(samples);
  sample_sums sums = {malloc(n * sizeof *sums.rb), malloc(n * sizeof *sums.g), 1};
  zs_raster_stats total;
  memset(&total, 0, sizeof total);
  zs_status st = sums.rb && sums.g ? ZS_OK : zs_error_set(err, ZS_ERR_NOMEM, "samples: out of memory");
  zs_device_set_shading_projection(dev, per_sample ? NULL : proj);
  for (int k = 0; k < samples && st == ZS_OK; k++) {
    double pk[16];
    zs_sample_projection(proj, w, h, pos[2 * k], pos[2 * k + 1], pk);
    st = render_into(dev, scene, view, pk, look, add_row, &sums, err);
    if (st != ZS_OK) break;
    add_stats(&total, zs_device_stats(dev));
    sums.first = 0;
  }
  zs_device_set_shading_projection(dev, NULL);
  if (st == ZS_OK && out) {
    /* (sum + samples / 2) / samples a channel: samples is a power of two;
     * the shift leaves each lane's quotient (at most 255) in its own 8
     * bits and brings its remainder into the zero bits below (4 at most),
     * which the masks drop */
    int shift = 0;
    while (1 << shift < samples) shift++;
    const uint32_t half = (uint32_t)samples / 2;
    const uint32_t half_rb = half << 16 | half, half_g = half << 8;
    for (size_t i = 0; i < n; i++)
      out->rgb[i] = ((sums.rb[i] + half_rb) >> shift & 0xFF00FFu) |
                    ((sums.g[i] + half_g) >> shift & 0xFF00u);
  }
  if (st == ZS_OK && stats) *stats = total;
  free(sums.rb);
  free(sums.g);
  return st;
}

zs_status zs_frame_finish(zs_device *dev, zs_image *out, float *depth, zs_error *err) {
  return zs_frame_finish_into(dev, out, depth, NULL, err);
}

zs_status zs_frame_finish_into(zs_device *dev, zs_image *out, float *depth, zs_layer *layer,
                               zs_error *err) {
  gather g = {out, depth, NULL, layer};
  return zs_device_finish(dev, gather_row, &g, err);
}

zs_status zs_frame_render_normals(const zs_device_config *cfg, const zs_scene *scene,
                                  const double view[16], const double proj[16], float *xyz,
                                  zs_error *err) {
  zs_device_config c = *cfg;
  c.shade = ZS_SHADE_NORMAL;
  zs_device *dev = NULL;
  gather g = {NULL, NULL, xyz, NULL}; /* the normals only: the colours are dropped */
  zs_status st = zs_device_create(&c, &dev, err);
  if (!st) st = zs_device_set_normals(dev, 1, err);
  if (!st) st = zs_frame_draw_all(dev, scene, view, proj, err);
  if (!st) st = zs_device_finish(dev, gather_row, &g, err);
  zs_device_destroy(dev);
  return st;
}

zs_status zs_frame_set_lights(zs_device *dev, const zs_scene *scene, const zs_light *lights,
                              int n, zs_error *err) {
  return zs_frame_lights_and_shadows(dev, scene, lights, n, NULL, NULL, 1, NULL, err);
}

int zs_frame_wireframe_fits(zs_algo algo, zs_shade shade) {
  return algo == ZS_ALGO_ZBUFFER && shade != ZS_SHADE_ID && shade != ZS_SHADE_DEPTH &&
         shade != ZS_SHADE_OVERDRAW;
}

zs_shade zs_frame_device_shade(zs_frame_style style, zs_shade shade) {
  return style == ZS_STYLE_HIDDEN_LINE ? ZS_SHADE_FLAT : shade;
}

int zs_frame_hidden_line_fits(zs_algo algo, zs_shade shade) {
  return algo == ZS_ALGO_ZBUFFER && (shade == ZS_SHADE_FLAT || shade == ZS_SHADE_AUTO);
}

zs_status zs_frame_render(const zs_scene *scene, const zs_camera *cam,
                          const zs_frame_opts *o, zs_image *out, float *depth,
                          zs_raster_stats *stats, zs_error *err) {
  double view[16], proj[16];
  if (zs_frame_camera(scene, cam, o->width, o->height, view, proj, err)) return err->code;
  if (o->style == ZS_STYLE_HIDDEN_LINE && !zs_frame_hidden_line_fits(o->algo, o->shade))
    return zs_error_set(err, ZS_ERR_ARG,
                        "hidden_line needs algo ZS_ALGO_ZBUFFER and shade ZS_SHADE_FLAT or ZS_SHADE_AUTO");
  if (o->style == ZS_STYLE_WIREFRAME && !zs_frame_wireframe_fits(o->algo, o->shade))
    return zs_error_set(err, ZS_ERR_ARG, "wireframe needs algo ZS_ALGO_ZBUFFER and a shading of "
                        "the surfaces (not ZS_SHADE_ID, _DEPTH or _OVERDRAW)");
  if (o->samples != 0 && !zs_samples_valid(o->samples))
    return zs_error_set(err, ZS_ERR_ARG, "samples: %d: expected 1, 2, 4, 8 or 16", o->samples);
  if (o->samples > 1 && o->shade == ZS_SHADE_ID)
    return zs_error_set(err, ZS_ERR_ARG, "samples: ids do not average: ZS_SHADE_ID draws one "
                        "sample a pixel");
  if (o->samples > 1 && depth)
    return zs_error_set(err, ZS_ERR_ARG, "samples: a depth map holds one sample a pixel");
  zs_device_config cfg = {o->width,     o->height,  o->algo,   zs_frame_device_shade(o->style, o->shade),
                          o->cull_back, o->threads, ZS_BACKGROUND_RGB, 0, (int)o->filter};
  zs_device *dev = NULL;
  if (zs_device_create(&cfg, &dev, err)) return err->code;
  zs_shadow_set maps = {0};
  if (zs_frame_lights_and_shadows(dev, scene, o->lights, o->nlights, o->shadows, view,
                                  o->threads, &maps, err)) {
    zs_device_destroy(dev);
    return err->code;
  }
  const zs_frame_look look = {o->style, o->line_width, o->point_size, o->point_shape};
  zs_status st = zs_image_alloc(out, o->width, o->height, err);
  if (st == ZS_OK && o->samples > 1) {
    st = zs_frame_render_samples(dev, scene, view, proj, &look, o->samples,
                                 o->per_sample, out, stats, err);
  } else if (st == ZS_OK) {
    st = zs_frame_render_on(dev, scene, view, proj, &look, out, depth, err);
    if (st == ZS_OK && stats) *stats = *zs_device_stats(dev);
  }
  if (st != ZS_OK) zs_image_free(out);
  zs_device_destroy(dev);
  zs_shadow_set_free(&maps);
  return st;
}
