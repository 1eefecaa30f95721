/* zscan — a software scanline z-buffer renderer with exact occlusion
 * queries: the same bytes on every machine.
 *
 * One object (zs_device: an emulated GPU), a few calls, and above it what
 * most programs want: load a model or scene, render it into an image in
 * memory, write or read PNG, hash and compare images.
 *
 *   #include <zscan/zscan.h>
 *   #include <stdio.h>
 *
 *   int main(int argc, char **argv) {
 *     zs_error err = {0};
 *     zs_scene *scene;
 *     zs_image im = {0};
 *     zs_render_opts opts = {0};          // 1024x768, zbuffer, flat, auto camera
 *     if (argc < 2 || zs_scene_load(argv[1], NULL, &scene, &err) ||
 *         zs_render(scene, &opts, &im, NULL, NULL, &err) ||
 *         zs_png_write("out.png", &im, &err))
 *       return fprintf(stderr, "%s\n", err.msg), 1;
 *     printf("%016llx\n", (unsigned long long)zs_image_hash(&im));
 *     zs_image_free(&im);
 *     zs_scene_destroy(scene);
 *   }
 *
 * Build: cc prog.c $(pkg-config --cflags --libs zscan), or in CMake
 * find_package(zscan) and target_link_libraries(prog zscan::zscan).
 *
 * KNOBS, every one with its default; in every options struct 0 (or NULL)
 * means the default, so a zero-initialised struct is always valid:
 *   zs_device_config.width, .height   0: 1024 x 768; else 1 .. 16384
 *   zs_device_config.algo             0: ZS_ALGO_ZBUFFER
 *   zs_device_config.shade            0: ZS_SHADE_AUTO (flat, or Phong for a
 *                                     mesh with normals, colours or textures)
 *   zs_device_config.cull_back        0: back faces drawn
 *   zs_device_config.threads          0: 1; else 1 .. 64 (depthsort: its walk only)
 *   zs_device_config.background       0: black (0xRRGGBB)
 *   zs_device_config.spans            0: the widest span fill the CPU has
 *   zs_render_opts.width, .height     0: the scene's own size, else 1024 x 768
 *   zs_render_opts.algo, .shade, .cull_back, .threads   as the device's
 *   zs_render_opts.hidden_line        0: faces; 1: the visible edges
 *   zs_render_opts.wireframe          0: faces; 1: their visible edges over them
 *   zs_render_opts.has_eye/.eye ...   0: the scene's camera, completed
 *                                     from its bounds (the automatic camera)
 *   zs_render_opts.fovy               0: the scene's, else 45 degrees
 *   zs_render_opts.znear, .zfar       0: from the scene's bounds
 *   zs_render_opts.filter             0: each material's own texture filter
 *   zs_render_opts.lights, .nlights   NULL: the scene's lights, else the headlight
 *   zs_render_opts.shadows            0: only lights marked shadow cast them
 *   zs_render_opts.shadow_size        0: maps of 1024 x 1024 texels
 *   zs_render_opts.has_shadow_bias    0: ZS_SHADOW_BIAS_UNITS, _SLOPE
 *   zs_render_opts.samples            0: one sample a pixel (no anti-aliasing)
 *   zs_render_opts.supersample        0: multisampled, shaded once a pixel
 *   zs_load_opts.allow_empty          0: a model without faces is an error
 *   zs_load_opts.skip_missing_textures  0: a texture that cannot be opened
 *                                     is an error; else the material is drawn
 *                                     without it, noted (zs_scene_notes)
 *   the device clock (zscan/clock.h)  zs_clock_params_default
 *
 * STABILITY: before 1.0 the names and structs here may still change
 * between minor versions (0.x); the ABI is tied to the major version
 * (SONAME libzscan.so.0).  Images and hashes change only with a reason in
 * the release notes and a new pixel version (ZSCAN_PIXEL_VERSION below,
 * docs/CHANGES.md).  The extras (zscan/walk.h, zscan/clock.h,
 * zscan/trace.h, zscan/depthsort.h) may change more often.
 *
 * CONVENTIONS
 *   Matrices are double[16], row-major, acting on column vectors:
 *   p' = M p, element (row r, column c) at m[4*r + c].  The camera follows
 *   gluLookAt / gluPerspective: the eye looks down -z, clip space is
 *   OpenGL's (-w <= x,y,z <= w).  Window coordinates follow glViewport with
 *   pixel centres at (x + 0.5, y + 0.5).  Images have row 0 at the top.
 *   Vertices are snapped to 1/256 pixel.  A pixel belongs to a polygon
 *   when its centre lies inside; a centre exactly on an edge belongs to the
 *   polygon for which that edge is a left or a bottom edge in the written
 *   image (OpenGL's top-left rule, as Mesa's llvmpipe applies it), so a
 *   centre on an edge shared by two faces goes to exactly one of them.
 *   Depth is window z in [0,1] as a 32-bit integer (0xFFFFFFFF farthest);
 *   a fragment (z, id) replaces the pixel's (zb, idb) when z < zb, or
 *   z == zb and id < idb: the image never depends on the order of draws.
 *   Faces are convex (loaders split concave ones), counter-clockwise in
 *   front.  docs/ALGORITHMS.md explains the scanline walk behind it.
 */
#ifndef ZSCAN_H
#define ZSCAN_H

#include <stddef.h>
#include <stdint.h>

#include "zscan/error.h"

#define ZSCAN_VERSION_MAJOR 0
#define ZSCAN_VERSION_MINOR 12
#define ZSCAN_VERSION_PATCH 3
#define ZSCAN_VERSION_STRING "0.12.3"

#ifdef __cplusplus
extern "C" {
#endif

/* The library's version, "MAJOR.MINOR.PATCH": compare it with
 * ZSCAN_VERSION_STRING to tell the library from the header. */
const char *zs_version(void);

/* The pixel version: a number raised whenever any output of an unchanged
 * input and options changes (an image's bytes, a counter, a modelled
 * time, a printed camera), and only then, so that a golden made with
 * another number is known to differ on purpose.  docs/CHANGES.md lists
 * each version's changes; zs_pixel_changes gives them. */
#define ZSCAN_PIXEL_VERSION 7
int zs_pixel_version(void);
/* What changed in the outputs of pixel version v against v - 1, one
 * line; NULL for a version this library does not know (v < 1 or later
 * than its own). */
const char *zs_pixel_changes(int v);

enum {
  ZS_MAX_IMAGE_SIDE = 16384, /* width and height, each */
  ZS_MAX_POLY_VERTS = 64,    /* per face of a zs_mesh (loaders split more) */
  ZS_DEVICE_DEFAULT_WIDTH = 1024,
  ZS_DEVICE_DEFAULT_HEIGHT = 768
};

#define ZS_DEPTH_FAR 0xFFFFFFFFu
#define ZS_ID_NONE 0xFFFFFFFFu
#define ZS_RGB_MESH 0xFF000000u /* draw with the mesh's own colours */

/* ==== The device ==== */

/* Geometry the device draws: owned by the caller, read only.
 * Faces are index lists into pos: face f uses face_vert[face_start[f] ..
 * face_start[f+1]-1], 3 .. ZS_MAX_POLY_VERTS of them.  face_id gives each
 * face the id used for the depth tie-break and ZS_SHADE_ID (NULL: the face
 * index); several mesh faces may share an id when a loader split one face.
 * face_rgb is 0xRRGGBB per face (NULL: grey). */
typedef struct zs_material zs_material;

typedef struct zs_mesh {
  double *pos;          /* x, y, z per vertex */
  int32_t nverts;
  int32_t *face_start;  /* nfaces + 1 entries */
  int32_t *face_vert;
  int32_t nfaces;
  uint32_t *face_rgb;
  int32_t *face_id;
  /* Shading attributes, every one optional (NULL: none); only the lit and
   * unlit shadings read them (ZS_SHADE_AUTO, _UNLIT, _GOURAUD, _PHONG,
   * _NORMAL).  They belong to attribute vertices, so that a position may
   * carry a different normal or texture coordinate in each face that
   * meets there: corner k of the faces (face_vert[k]) takes attribute
   * vertex corner_attr[k], -1 for none (a normal from the face's plane,
   * white, (0, 0)); corner_attr NULL: the corner's position index, with
   * nattrs == nverts. */
  int32_t nattrs;
  int32_t *corner_attr;
  float *normal;        /* x, y, z per attribute vertex, any length; (0, 0, 0):
                         * none, the face's plane normal instead */
  uint8_t *color;       /* R, G, B, A per attribute vertex (0 .. 255) */
  float *uv;            /* u, v per attribute vertex: (0, 0) the bottom left
                         * of a texture, (1, 1) its top right, as in OpenGL */
  int32_t *face_material; /* per face, into materials; -1 or NULL: material 0,
                         * or none when nmaterials is 0 */
  const zs_material *materials;
  int32_t nmaterials;
  /* Lines and points (zs_device_draw_lines, _points), both optional:
   * line k joins positions line_vert[2k] and line_vert[2k + 1], point k
   * is position point_vert[k]; line_rgb and point_rgb give each its
   * 0xRRGGBB (NULL: the grey of a face without
   * a colour, 0xB4B4B4).  Line k takes the id prim_id + k
   * and point k the id prim_id + nlines + k (after the faces' ids, when
   * the caller sets prim_id past them), for the depth tie-break. */
  int32_t *line_vert;
  int32_t nlines;
  uint32_t *line_rgb;
  int32_t *point_vert;
  int32_t npoints;
  uint32_t *point_rgb;
  int32_t prim_id;
} zs_mesh;


typedef enum zs_algo {
  ZS_ALGO_ZBUFFER,  /* immediate mode: each draw into full-frame buffers */
  ZS_ALGO_SCANLINE, /* the whole frame at once, one row of buffers */
  ZS_ALGO_DEPTHSORT /* painter's algorithm with frame coherence */
} zs_algo;

/* "zbuffer", "scanline", "depthsort"; and back (-1 for another name). */
const char *zs_algo_name(zs_algo a);
int zs_algo_parse(const char *name);

typedef enum zs_shade {
  ZS_SHADE_AUTO,     /* as the mesh says: flat for a mesh without normals,
                      * colours or textures, Phong for one with them and
                      * for every mesh once lights are given */
  ZS_SHADE_FLAT,     /* face colour times a Lambert term, attributes unread */
  ZS_SHADE_ID,       /* RGB = id + 1 as 24 bits, background 0 */
  ZS_SHADE_DEPTH,    /* grey from the linear eye distance, near white */
  ZS_SHADE_OVERDRAW, /* fragments per pixel as a heat map, no depth test */
  ZS_SHADE_UNLIT,    /* base colour x vertex colour x texel, unlit, in the
                      * values the file gives (no sRGB conversion) */
  ZS_SHADE_GOURAUD,  /* lit at the corners, colours interpolated */
  ZS_SHADE_PHONG,    /* normals interpolated, Blinn-Phong at each pixel */
  ZS_SHADE_NORMAL    /* the eye-space unit normal n as (n + 1) / 2 * 255 */
} zs_shade;

/* "auto", "flat", "id", "depth", "overdraw", "unlit", "gouraud", "phong",
 * "normal"; and back (-1 for another name). */
const char *zs_shade_name(zs_shade s);
int zs_shade_parse(const char *name);

/* How wide the span fill goes: spans of 10 pixels or more sixteen at a
 * time with AVX-512, of 16 or more eight at a time with AVX2 or four with
 * SSE2, or one at a time; at AVX-512 the vertices are transformed eight
 * at a time too.  Every level gives the same bytes; the choice is made
 * once, when the device is created. */
typedef enum zs_span_fill {
  ZS_SPANS_BEST = 0,  /* the widest this CPU has */
  ZS_SPANS_SCALAR,
  ZS_SPANS_SSE2,      /* at most SSE2 */
  ZS_SPANS_AVX2,      /* at most AVX2 */
  ZS_SPANS_AVX512     /* at most AVX-512 (the same as best on x86-64); on
                       * aarch64 every level but scalar is NEON's */
} zs_span_fill;

/* ---- Textures and materials ----
 *
 * A texture is an immutable grid of RGBA texels, 8 bits a channel (colour
 * in sRGB, alpha linear), row 0 at the top, with its mip chain made when
 * it is created, in integers: level k + 1 is max(1, w_k / 2) x max(1,
 * h_k / 2), each texel the mean of the 2 x 2 texels of level k above it
 * (the last row or column of an odd side folded into its neighbour's),
 * rounded to nearest.  Sampling is in integers too (docs/API.md): the
 * level of detail comes from the exact derivatives of the texture
 * mapping at the pixel, so a pixel's texel never depends on its
 * neighbours or the order of drawing. */
typedef struct zs_texture zs_texture;

enum { ZS_MAX_TEXTURE_SIDE = 8192 }; /* width and height, each */

/* A texture of width x height texels rgba (4 bytes a texel, copied). */
zs_status zs_texture_create(int width, int height, const uint8_t *rgba, zs_texture **out,
                            zs_error *err);
void zs_texture_destroy(zs_texture *tex);
int zs_texture_width(const zs_texture *tex);
int zs_texture_height(const zs_texture *tex);
int zs_texture_levels(const zs_texture *tex);
/* Level k's texels (RGBA, row 0 at the top) and size. */
const uint8_t *zs_texture_level(const zs_texture *tex, int k, int *width, int *height);

typedef enum zs_wrap {
  ZS_WRAP_REPEAT,    /* GL_REPEAT */
  ZS_WRAP_CLAMP,     /* GL_CLAMP_TO_EDGE */
  ZS_WRAP_MIRROR     /* GL_MIRRORED_REPEAT */
} zs_wrap;

typedef enum zs_filter {
  ZS_FILTER_DEFAULT,   /* the material's own (zs_material.filter) */
  ZS_FILTER_NEAREST,   /* the nearest texel of level 0 (GL_NEAREST) */
  ZS_FILTER_BILINEAR,  /* 2 x 2 texels of the nearest level
                        * (GL_LINEAR_MIPMAP_NEAREST; GL_LINEAR magnified) */
  ZS_FILTER_TRILINEAR  /* 2 x 2 texels of the two nearest levels, blended
                        * (GL_LINEAR_MIPMAP_LINEAR) */
} zs_filter;

/* "default", "nearest", "bilinear", "trilinear"; and back (-1 otherwise). */
const char *zs_filter_name(zs_filter f);
int zs_filter_parse(const char *name);

/* A surface's material, as glTF's metallic-free core and OBJ's MTL say
 * it.  Colours are 8-bit sRGB; zs_material_default gives the grey of a
 * face without one.  Nothing here has a zero default: fill every field. */
struct zs_material {
  uint8_t base[4];          /* base colour and alpha (glTF baseColorFactor, MTL Kd, d) */
  uint8_t specular[3];      /* the highlight's colour (MTL Ks); 0: none */
  uint8_t emissive[3];      /* light of its own (MTL Ke, glTF emissiveFactor) */
  uint16_t shininess;       /* Blinn-Phong exponent 0 .. ZS_MAX_SHININESS (MTL Ns) */
  uint8_t double_sided;     /* lit on both sides (glTF doubleSided) */
  const zs_texture *base_texture; /* multiplies the base colour; NULL: none */
  zs_wrap wrap_s, wrap_t;   /* across and up the texture */
  zs_filter filter;         /* ZS_FILTER_DEFAULT: trilinear */
  uint8_t ignore_alpha;     /* every alpha ignored, the faces opaque (glTF's
                             * OPAQUE mode); 0: alpha below 255 is transparent */
  uint8_t alpha_cutoff;     /* 1 .. 255: a pixel's alpha at or above it is
                             * opaque, below it clear (glTF's MASK mode, its
                             * alphaCutoff c as ceil(255 c)); 0: alpha blends */
};

enum { ZS_MAX_SHININESS = 4096 };

/* A mid-grey (0xB4B4B4), opaque, no highlight, double-sided, untextured. */
zs_material zs_material_default(void);

/* Transparency.  A face is transparent where its material's alpha
 * (base[3]), its base texture's alpha or its vertex colours' alpha is
 * below 255 (unless its material ignores alpha), under the shadings that read attributes (AUTO, UNLIT,
 * GOURAUD, PHONG; NORMAL draws every face opaque).  Its pixels are kept
 * in an A-buffer and composited over the opaque surface in depth order,
 * in integers, when the frame's rows go out, so the image depends on the
 * surfaces drawn, never on the order of drawing (docs/ALGORITHMS.md
 * gives the arithmetic).  A transparent face writes no depth: occlusion
 * queries count its pixels, and it occludes nothing.  zbuffer and
 * scanline modes; depthsort refuses it.  Each row of the image keeps at
 * most ZS_FRAGMENTS_PER_PIXEL x width transparent fragments lying in
 * front of the opaque surface drawn before them; the draw that passes
 * that fails with ZS_ERR_LIMIT. */
enum { ZS_FRAGMENTS_PER_PIXEL = 16 };

/* Whether every texel of tex has alpha 255. */
int zs_texture_opaque(const zs_texture *tex);

/* ---- Lights (the lit shadings: AUTO, GOURAUD, PHONG) ----
 *
 * A light's colour is linear RGB radiance (intensity folded in; 1 is a
 * white light as bright as the headlight).  Every light and every product
 * is evaluated in double, with +, -, *, / and sqrt only, in a fixed order
 * (docs/ALGORITHMS.md gives the formula), so the bytes are the same on
 * every machine. */
typedef enum zs_light_kind {
  ZS_LIGHT_DIRECTIONAL, /* parallel rays along direction */
  ZS_LIGHT_POINT,       /* from position, falling off as 1 / d^2 */
  ZS_LIGHT_SPOT,        /* a point light within a cone about direction */
  ZS_LIGHT_AMBIENT      /* the same from every side, on every surface */
} zs_light_kind;

typedef struct zs_light {
  zs_light_kind kind;
  double color[3];        /* linear RGB, >= 0 */
  double position[3];     /* point and spot */
  double direction[3];    /* directional and spot: the way the light travels */
  double inner_deg, outer_deg; /* spot: full light within inner, none past
                           * outer (half angles, 0 < inner <= outer < 90) */
  int eye_space;          /* position and direction in eye coordinates: the
                           * light moves with the camera (a headlight) */
  int shadow;             /* directional and spot: casts shadows, where the
                           * device has its map (zs_device_set_shadow_maps;
                           * zs_render draws them) */
} zs_light;

enum { ZS_MAX_LIGHTS = 16 };

typedef struct zs_device_config {
  int width, height;       /* 0: 1024 x 768 */
  zs_algo algo;            /* 0: zbuffer */
  zs_shade shade;          /* 0: flat */
  int cull_back;           /* drop faces clockwise in window coordinates */
  int threads;             /* 0: 1; up to 64 (depthsort: its walk only) */
  uint32_t background;     /* 0xRRGGBB for flat shading; 0: black */
  zs_span_fill spans;      /* 0: the widest the CPU has */
  int filter;              /* a zs_filter for every texture; 0: each material's */
} zs_device_config;

/* Counters of one frame (since the last zs_device_clear). */
typedef struct zs_raster_stats {
  uint64_t draws;
  uint64_t vertices;             /* vertices transformed */
  uint64_t polygons_in;          /* faces submitted */
  uint64_t polygons_outside;     /* dropped whole: outside a clip plane */
  uint64_t polygons_clipped;     /* crossed near, far or the guard band */
  uint64_t polygons_culled_back; /* back faces, when culling is on */
  uint64_t polygons_degenerate;  /* zero area after snapping */
  uint64_t polygons_offscreen;   /* in the guard band, but their window box holds
                                  * no pixel centre: dropped by set-up */
  uint64_t polygons_rasterized;  /* set up and walked by the scanline code */
  uint64_t spans;                /* non-empty spans filled */
  uint64_t pixels_tested;        /* fragments depth-tested */
  uint64_t pixels_written;       /* fragments that passed and were written */
} zs_raster_stats;

/* One finished row of the image, handed to a zs_row_sink in order y = 0,
 * 1, ..., height-1.  rgb is 0xRRGGBB per pixel as shaded; depth and id are
 * the raw buffers (id ZS_ID_NONE for background); count is the fragment
 * count per pixel in ZS_SHADE_OVERDRAW, else NULL.  normal, when
 * zs_device_set_normals has asked for them, is x, y, z per pixel: the unit
 * eye-space normal a pixel's face has there, as ZS_SHADE_NORMAL colours
 * it (the corners' normals interpolated, else the face's plane), and
 * 0, 0, 0 where no face shaded from attributes is; else NULL.  The
 * pointers are valid only during the call. */
typedef struct zs_row {
  int y, width;
  const uint32_t *rgb;
  const uint32_t *depth;
  const uint32_t *id;
  const uint32_t *count;
  const float *normal;
} zs_row;

typedef void (*zs_row_sink)(void *user, const zs_row *row);

typedef struct zs_device zs_device;

/* cfg may be NULL (every default). */
zs_status zs_device_create(const zs_device_config *cfg, zs_device **out, zs_error *err);
void zs_device_destroy(zs_device *dev);
/* The configuration in force, defaults filled in. */
const zs_device_config *zs_device_config_of(const zs_device *dev);

/* The camera for the following draws: view (world to eye) and projection
 * (eye to clip), e.g. from zs_mat_look_at and zs_mat_perspective. */
void zs_device_set_camera(zs_device *dev, const double view[16], const double proj[16]);

/* The lights of the lit shadings from the next draw on: n of them (1 ..
 * ZS_MAX_LIGHTS, copied); under ZS_SHADE_AUTO they light every mesh, those
 * without attributes too (Phong, with their faces' plane normals).  n = 0,
 * and a new device: the headlight, a white directional light of 0.9 along
 * the view, (0, 0, -1) in eye space, and an ambient light of 0.1.  Directions need not be unit; a zero
 * direction, a negative colour, a spot's angles out of range or a value
 * not finite is refused (ZS_ERR_ARG, naming the light and its field). */
zs_status zs_device_set_lights(zs_device *dev, const zs_light *lights, int n, zs_error *err);

/* The projection at which the shadings that read attributes evaluate a
 * triangle's attributes, from the next draw on, in place of the camera's
 * (which still decides coverage and depth); NULL: the camera's.  A
 * multisampled frame (zs_render_opts.samples) draws each sample with the
 * camera's projection moved by the sample's offset and shades every
 * sample at the pixel's centre with this. */
void zs_device_set_shading_projection(zs_device *dev, const double proj[16]);

/* ---- Shadows (the Phong shading) ----
 * A shadow map is a z-buffer drawn from a light: the depth buffer
 * (zs_device_depth_buffer) of a zbuffer-mode device that drew the scene
 * through the light's camera (zs_shadow_camera).  Where a light has one,
 * Phong shading (ZS_SHADE_PHONG, and AUTO's Phong) weights its diffuse and
 * specular light at a pixel by the fraction of a 3 x 3 block of map texels
 * that do not hide the pixel (percentage-closer filtering in integers):
 * the pixel's light-space position, interpolated exactly as every
 * attribute is, is projected into the map (texel tx, ty = floor of its
 * window x, y there; depth r = floor(z 2^32), window z as the device
 * stores it), and texel (tx + i, ty + j), i, j in -1 .. 1, lights it when
 * r - bias <= its depth, or when it lies off the map.  bias = units +
 * slope m, rounded down, at most 2^32, m = |dz/dx| + |dz/dy|, the
 * receiving triangle's depth change per texel in the map along x and y
 * (in depth units): slope 1.5 covers the depth change from the receiver
 * to the farthest of the nine texels' centres on its own plane, so a
 * plane does not shadow itself ("shadow acne"); the default 2 leaves a
 * margin for snapping and curvature.  A pixel behind the light's eye
 * (w <= 0) is lit.  docs/ALGORITHMS.md shows the bias's
 * work (shadow acne without it). */
enum { ZS_MAX_SHADOW_MAPS = 4 };
#define ZS_SHADOW_BIAS_UNITS 4096.0 /* the defaults zs_render and `zscan render` use */
#define ZS_SHADOW_BIAS_SLOPE 2.0

typedef struct zs_shadow_map {
  int light;                 /* the light it belongs to: its index in the list
                              * given to zs_device_set_lights (directional or spot) */
  int width, height;         /* 1 .. ZS_MAX_IMAGE_SIDE */
  const uint32_t *depth;     /* width * height depths, row 0 at the top, as
                              * zs_device_depth_buffer gives them: the caller's,
                              * valid while the device holds the map (until
                              * maps or lights are set again, or it is
                              * destroyed) */
  double view[16], proj[16]; /* the camera it was drawn with */
  double bias_units;         /* 0 .. 2^32: bias = units + slope m (above) */
  double bias_slope;         /* 0 .. 1e6 */
} zs_shadow_map;

/* The shadow maps of the frames from the next on (copied; the depths are
 * not), set before a frame's first draw (after zs_device_clear): n of
 * them, 0 .. ZS_MAX_SHADOW_MAPS, each for a different directional or spot
 * light of those set; n = 0: none.  Setting lights drops them.  The
 * device's shading must be ZS_SHADE_AUTO or ZS_SHADE_PHONG (Gouraud lights
 * only the corners, flat not by the lights): else ZS_ERR_ARG, as for a map
 * out of range, naming maps[i] and its field. */
zs_status zs_device_set_shadow_maps(zs_device *dev, const zs_shadow_map *maps, int n,
                                    zs_error *err);

/* The camera of light's shadow map over the world box lo..hi, which the
 * map then holds whole: a directional light looks along its direction
 * through an orthographic box about the box's bounding sphere, a spot
 * from its position along its axis with a square frustum of twice its
 * outer angle, near and far where the sphere begins and ends.  An
 * eye-space light is placed by view (the camera's, world to eye).
 * Returns 0 for a point or ambient light (no map: they cast none here). */
int zs_shadow_camera(const zs_light *light, const double view[16], const double lo[3],
                     const double hi[3], double light_view[16], double light_proj[16]);

/* The key light of a shadowed scene that has no lights of its own, into
 * out[0 .. 2): a white directional light of 0.8 from above, to the left
 * and behind the viewer, travelling (1, -2, -1) in eye space, so that
 * the shadows fall behind and to the right of what casts them, in view;
 * it casts shadows; and an ambient light of 0.2.  Returns 2. */
int zs_lights_key(zs_light out[2]);

/* Starts a frame: clears colour, depth and id, and the counters. */
void zs_device_clear(zs_device *dev);

/* Draws every face of mesh, placed by model (NULL: identity); face f gets
 * id id_base + face_id[f] and the colour rgb, or its mesh colour when rgb
 * is ZS_RGB_MESH.  In zbuffer mode the faces are rasterized now; in scanline
 * mode they are set up and kept for zs_device_finish.  Under the shadings
 * that read attributes, a pixel is shaded once, from the face that owns it
 * when the frame is finished: the mesh's arrays, its materials and
 * textures must stay valid until zs_device_finish (the zs_mesh struct
 * itself is copied).  A face's base colour there is rgb when it is not
 * ZS_RGB_MESH, else its material's, else white when the mesh has vertex
 * colours (they are the colour), else face_rgb's. */
zs_status zs_device_draw(zs_device *dev, const zs_mesh *mesh, const double model[16],
                         uint32_t id_base, uint32_t rgb, zs_error *err);

/* Ends the frame (scanline mode rasterizes it now) and hands every row to
 * sink, top to bottom.  sink may be NULL. */
zs_status zs_device_finish(zs_device *dev, zs_row_sink sink, void *user, zs_error *err);

/* Whether the rows zs_device_finish hands out carry their eye-space
 * normals (zs_row.normal), from the next finish on; off on a new device.
 * Needs a shading that reads attributes (ZS_SHADE_NORMAL gives every face
 * one): ZS_ERR_ARG under another. */
zs_status zs_device_set_normals(zs_device *dev, int on, zs_error *err);

const zs_raster_stats *zs_device_stats(const zs_device *dev);

/* The full-frame buffers of zbuffer mode (NULL in scanline mode), row 0 at
 * the top, width * height entries, current whenever read.  (A device
 * clears the rows no draw reaches lazily until these are first asked for,
 * and eagerly from then on.) */
const uint32_t *zs_device_depth_buffer(const zs_device *dev);
const uint32_t *zs_device_id_buffer(const zs_device *dev);

/* ---- Occlusion queries (zbuffer mode) ----
 * Between zs_device_query_begin and zs_device_query_end, every pixel that
 * passes the depth test adds one sample to the query: pixels written by
 * draws, and pixels of query boxes.  A query box draws the faces of an
 * axis-aligned world box that face the eye (all six when the eye is
 * inside) with the test "less or equal" and no writes, brought towards the
 * eye by a small bias and grown by zs_device_query_margin, so that it is
 * never hidden when what lies in it is visible.  A box cut by the near
 * plane counts only what lies beyond it: treat such boxes as visible.
 * Results arrive after the modelled latency (zscan/clock.h); asking early
 * stalls the modelled CPU.  Several queries may be in flight. */
typedef uint32_t zs_query;

zs_status zs_device_query_begin(zs_device *dev, zs_query *q, zs_error *err);
zs_status zs_device_query_end(zs_device *dev, zs_error *err);
zs_status zs_device_query_box(zs_device *dev, const double lo[3], const double hi[3],
                              zs_error *err);
/* n boxes (lo[i], hi[i]) as one draw call, as a multiquery draws them. */
zs_status zs_device_query_boxes(zs_device *dev, const double (*lo)[3], const double (*hi)[3],
                                int n, zs_error *err);
/* How far a query box lo..hi grows on every side, in world units. */
double zs_device_query_margin(const zs_device *dev, const double lo[3], const double hi[3]);
/* Whether the result of q is available at the modelled CPU time now. */
int zs_device_query_ready(const zs_device *dev, zs_query q);
/* The samples of q (waiting for it, in modelled time, when not ready);
 * 0 for a q not issued since the frame's clear. */
uint64_t zs_device_query_result(zs_device *dev, zs_query q);
/* The queries begun since the frame's clear: q is one when q < this. */
uint32_t zs_device_queries(const zs_device *dev);

/* ---- Hidden lines (zbuffer mode) ----
 * After the faces are drawn, zs_device_fill_color paints the colour buffer
 * one colour (keeping depth and ids), and zs_device_draw_edges draws the
 * edges of the front faces wherever they are not behind the depth buffer. */
zs_status zs_device_fill_color(zs_device *dev, uint32_t rgb, zs_error *err);
zs_status zs_device_draw_edges(zs_device *dev, const zs_mesh *mesh, const double model[16],
                               uint32_t rgb, zs_error *err);
/* The twelve edges of the world box lo..hi, over everything. */
zs_status zs_device_draw_box_lines(zs_device *dev, const double lo[3], const double hi[3],
                                   uint32_t rgb, zs_error *err);

/* ---- Lines and points (zbuffer and scanline modes) ----
 * The mesh's lines and points (zs_mesh.line_vert, .point_vert) by GL's
 * rules for aliased wide lines and points, each pixel tested against the
 * depth buffer as a face's is (less, then the lower id) and written with
 * its depth and id, so that faces drawn later hide them too; drawn after
 * the faces queued before them (the call flushes; in scanline mode each
 * row gets them at finish, after its faces: the same pixels).  rgb is ZS_RGB_MESH
 * (each line's or point's own colour) or one colour for all.  A width or
 * size is rounded to the nearest integer (halves up), as GL rounds an
 * aliased one, and must lie in (0, ZS_MAX_LINE_WIDTH] or (0,
 * ZS_MAX_POINT_SIZE].
 *   A line covers, along its major axis (x when |dx| >= |dy|), the pixels
 *   whose centres lie from its start (included) to its end (excluded), and
 *   at each of them the w pixels across it whose centres lie within w / 2
 *   of the exact line, by the top-left rule: GL's wide line, its ends cut
 *   square to the major axis (butt caps).  Its depth at each pixel is the
 *   line's at the major-axis centre.
 *   A point covers the pixels whose centres lie in the square of side s
 *   centred on it (GL's aliased point), or, a disc, strictly within s / 2
 *   of it; its depth is the point's.  GL clips a point by its centre: one
 *   whose centre is outside the view is not drawn.
 * Every position is snapped to 1/256 pixel and every test is in integers,
 * so the pixels are the same on every machine; docs/ALGORITHMS.md draws
 * them.  Occlusion queries do not count them. */
enum { ZS_MAX_LINE_WIDTH = 64, ZS_MAX_POINT_SIZE = 64 };

typedef enum zs_point_shape {
  ZS_POINT_SQUARE, /* GL's aliased point */
  ZS_POINT_DISC    /* the pixels within size / 2 of it */
} zs_point_shape;

zs_status zs_device_draw_lines(zs_device *dev, const zs_mesh *mesh, const double model[16],
                               uint32_t id_base, uint32_t rgb, double width, zs_error *err);
zs_status zs_device_draw_points(zs_device *dev, const zs_mesh *mesh, const double model[16],
                                uint32_t id_base, uint32_t rgb, double size,
                                zs_point_shape shape, zs_error *err);

/* ---- Matrices (OpenGL conventions, exact trigonometry) ---- */
void zs_mat_identity(double m[16]);
void zs_mat_mul(double out[16], const double a[16], const double b[16]);
void zs_mat_translate(double m[16], double x, double y, double z);
void zs_mat_scale(double m[16], double x, double y, double z);
/* Rotation by deg degrees about the axis (x,y,z), right-handed. */
void zs_mat_rotate(double m[16], double deg, double x, double y, double z);
/* gluLookAt; returns 0 when eye == target or up is parallel to the view. */
int zs_mat_look_at(double m[16], const double eye[3], const double target[3],
                   const double up[3]);
/* gluPerspective: fovy in degrees, aspect = width / height. */
void zs_mat_perspective(double m[16], double fovy_deg, double aspect, double znear,
                        double zfar);
/* glOrtho. */
void zs_mat_ortho(double m[16], double left, double right, double bottom, double top,
                  double znear, double zfar);

/* ==== Images ==== */

/* width * height pixels 0xRRGGBB, row 0 at the top (the top byte is
 * ignored when writing and zero when reading). */
typedef struct zs_image {
  int width, height;
  uint32_t *rgb;
} zs_image;

/* A width x height image, all black.  On failure *im is left empty. */
zs_status zs_image_alloc(zs_image *im, int width, int height, zs_error *err);
/* Frees the pixels and empties *im (im may be NULL). */
void zs_image_free(zs_image *im);

/* The image hash that golden tests and `zscan render --stats` print:
 * 64-bit FNV-1a (offset basis 0xcbf29ce484222325, prime 0x100000001b3)
 * over width and height, each as a 32-bit little-endian number, then R,
 * G, B of every pixel, row 0 first, left to right. */
uint64_t zs_image_hash(const zs_image *im);

typedef struct zs_diff_result {
  uint64_t differing; /* pixels whose 0xRRGGBB differ */
  uint64_t total;     /* width * height */
  int max_channel_diff; /* the largest |a - b| over R, G and B */
} zs_diff_result;

/* Compares a and b, which must have the same size (else ZS_ERR_ARG).  When
 * diff_out is not NULL it receives a new image of the same size: a pixel
 * equal in a and b is the grey of a darkened to a quarter (luma / 4, Rec.
 * 601 weights), a differing pixel red, 0xFF0000. */
zs_status zs_image_diff(const zs_image *a, const zs_image *b, zs_image *diff_out,
                        zs_diff_result *res, zs_error *err);

/* The comparison of a golden test: a pixel differs when its largest
 * channel difference exceeds max_channel_diff (0 .. 255); res counts
 * those.  heat_out, when not NULL, receives a heat map: the pixels that
 * do not differ a faded grey of a, those that do coloured by how much,
 * from yellow (a difference of 1) to red (255). */
zs_status zs_image_compare(const zs_image *a, const zs_image *b, int max_channel_diff,
                           zs_image *heat_out, zs_diff_result *res, zs_error *err);

/* Writes im as an 8-bit RGB PNG, the same bytes for the same pixels (with
 * one zlib).  path "-" is standard output; a regular file is replaced
 * whole or not at all, a symbolic link is followed, a device or FIFO is
 * written directly. */
zs_status zs_png_write(const char *path, const zs_image *im, zs_error *err);
/* Reads a PNG of any colour type and bit depth into *out (allocated here;
 * free it with zs_image_free); alpha is dropped, no gamma applied. */
zs_status zs_png_read(const char *path, zs_image *out, zs_error *err);
/* A single-channel PFM of width * height floats, row 0 at the top (written
 * bottom row first, as the format wants). */
zs_status zs_pfm_write(const char *path, int width, int height, const float *values,
                       zs_error *err);
/* A three-channel PFM of width * height x, y, z triples (as zs_row.normal
 * holds them), row 0 at the top. */
zs_status zs_pfm_write_rgb(const char *path, int width, int height, const float *xyz,
                           zs_error *err);

/* ==== Scenes: load, render ==== */

typedef struct zs_scene zs_scene;

typedef struct zs_load_opts {
  int allow_empty; /* 0: a model without faces is refused ("FILE: no faces") */
  int skip_missing_textures; /* 0: a texture that cannot be opened is an error; else the
                              * material is drawn without it, and the scene says which
                              * (zs_scene_notes) */
} zs_load_opts;

/* Loads input (opts may be NULL):
 *   FILE.obj                 Wavefront OBJ, one object per o/g
 *   FILE.json                a zscan scene file (docs/SCENES.md)
 *   FILE.ply, .stl, .gltf .. through assimp, when built with it
 *   builtin:NAME[,k=v,..]    a generated scene: default, teapots, spheres,
 *                            city, plant, cubes
 *   NULL                     builtin:default
 * Errors name the file and line (or the JSON path). */
zs_status zs_scene_load(const char *input, const zs_load_opts *opts, zs_scene **out,
                        zs_error *err);
void zs_scene_destroy(zs_scene *scene);
/* Instances (objects) and source faces, over the instances. */
int32_t zs_scene_objects(const zs_scene *scene);
uint64_t zs_scene_faces(const zs_scene *scene);
/* The notes of the load, each a line ending in '\n' ("" when none): what
 * is drawn otherwise than the input asks, as the message the load would
 * have failed with and ": drawn without it", e.g. "model.mtl:12: map_Kd
 * wood.png: cannot open: No such file or directory: drawn without it"
 * (zs_load_opts.skip_missing_textures).  Valid while the scene is. */
const char *zs_scene_notes(const zs_scene *scene);

/* Scenes built in code.  zs_scene_create makes an empty scene (no
 * objects, the default camera, no lights); zs_scene_add_object copies
 * mesh into it as one object (instance) placed by model (local to world,
 * row-major as zs_device_draw takes it; NULL: identity), named name
 * (NULL: "object N").  The copy goes through what the OBJ reader does
 * with a file of the same data, so the two draw the same bytes: face f
 * of mesh is the object's face f, whatever face_id says (a concave or
 * non-planar face is split, each piece keeping its number); face_rgb
 * NULL is grey; attributes given for some corners and none for normals
 * get normals computed (a crease of 60 degrees, as for files), and so do
 * textured faces.  Its face ids follow those of the objects before it.
 * materials are copied, but not their textures: each base_texture must
 * outlive the scene.  Bad input (a count below 0, a NULL array, a
 * position, normal or uv not finite, an index out of range, a face of
 * fewer than 3 corners, a mesh with nothing to draw) is ZS_ERR_ARG with a
 * message naming the array and its element, e.g.
 * "zs_mesh.face_vert[7]: vertex 12 out of range (8 vertices)"; the scene
 * is then as it was. */
zs_status zs_scene_create(zs_scene **out, zs_error *err);
zs_status zs_scene_add_object(zs_scene *scene, const zs_mesh *mesh, const double model[16],
                              const char *name, zs_error *err);

typedef struct zs_render_opts {
  int width, height;       /* 0: the scene's size, else 1024 x 768 */
  zs_algo algo;
  zs_shade shade;
  int cull_back;
  int threads;             /* 0: 1 */
  int hidden_line;         /* the visible edges of front faces, on white */
  int has_eye, has_target, has_up;  /* 0: the scene's camera, completed */
  double eye[3], target[3], up[3];
  double fovy;             /* degrees; 0: the scene's (45 unless it says) */
  double znear, zfar;      /* the clip planes' distances; 0: from the bounds */
  zs_filter filter;        /* every texture's filter; 0: each material's */
  const zs_light *lights;  /* NULL: the scene's lights, or the headlight */
  int nlights;
  int shadows;             /* 1: every directional and spot light casts
                            * shadows (with no light given or in the scene:
                            * the key light, zs_lights_key); 0: those marked;
                            * at most ZS_MAX_SHADOW_MAPS lights cast them */
  int shadow_size;         /* each map's side in texels; 0: 1024 */
  int has_shadow_bias;     /* 0: ZS_SHADOW_BIAS_UNITS and _SLOPE */
  double shadow_bias[2];   /* units, slope (zs_shadow_map) */
  int samples;             /* anti-aliasing: 0 or 1 one sample a pixel, else 2,
                            * 4, 8 or 16 at the standard positions (D3D's and
                            * Vulkan's), the pixel the mean of its samples,
                            * (sum + samples / 2) / samples a channel; not
                            * with ZS_SHADE_ID or a depth map */
  int supersample;         /* with samples: shade each sample where it lies;
                            * 0: at the pixel's centre (multisampling) */
  int wireframe;           /* the visible edges of front faces in black over
                            * the faces (zbuffer mode; not with hidden_line) */
  double line_width;       /* the scene's lines and the edges of the hidden-line and
                            * wireframe styles, pixels (0: 1; zs_device_draw_lines) */
  double point_size;       /* its points, pixels (0: 1) */
  zs_point_shape point_shape; /* squares (0) or discs */
} zs_render_opts;

/* Renders scene into out (allocated here; free it with zs_image_free):
 * the image `zscan render` makes with the same options, byte for byte.
 * opts may be NULL.  depth, when not NULL, receives a malloc'd array of
 * width * height window depths, row 0 at the top (1 = far; free() it);
 * stats, when not NULL, the frame's counters. */
zs_status zs_render(const zs_scene *scene, const zs_render_opts *opts, zs_image *out,
                    float **depth, zs_raster_stats *stats, zs_error *err);

/* The eye-space unit normal at each pixel of the frame zs_render draws
 * with the same options (its camera, size, algo, cull_back), as
 * `zscan render --normals` writes them: *xyz receives a malloc'd array of
 * 3 * width * height floats, x, y, z a pixel, row 0 at the top, 0, 0, 0
 * where no face is (free() it). */
zs_status zs_render_normals(const zs_scene *scene, const zs_render_opts *opts, float **xyz,
                            zs_error *err);

/* The object (instance) each id of the scene's renders belongs to, to turn
 * a pixel's id (ZS_SHADE_ID's RGB - 1, or zs_row.id) into its object:
 * *owner receives a malloc'd array of *n entries, entry i the object whose
 * face, line or point draws id i, -1 where none does (free() it). */
zs_status zs_scene_id_objects(const zs_scene *scene, int32_t **owner, uint32_t *n,
                              zs_error *err);

/* Per object (instance) of the scene, as `zscan query` prints it: the
 * pixels of the rendered frame (zbuffer mode, opts as for zs_render) that
 * show one of its faces, and the samples of an occlusion query on its
 * axis-aligned world box against the finished depth buffer.  An object
 * with faces the render draws transparent (opts->shade) hides nothing,
 * its opaque faces neither (as the culling methods' oracles take it):
 * the other objects own the pixels where they are the nearest surface
 * but for such objects, every box is queried against their depth alone,
 * and a transparent object owns the pixels where it is the nearest
 * surface of all.  With opts->samples N (2, 4, 8, 16) both count
 * samples, as GL's sample-counting queries do: the frame drawn at each
 * of the N standard positions, the counts summed. */
typedef struct zs_object_visibility {
  const char *name;        /* the object's name; valid while the scene is */
  int32_t object;          /* its number in the scene, from 0 */
  uint32_t first_face;     /* its lowest face id: the order of the list */
  uint64_t visible;        /* pixels (samples) it owns */
  uint64_t box_samples;    /* samples of its box's query */
} zs_object_visibility;

/* *out receives a malloc'd array of *n entries, in order of first face,
 * then of number (free() it). */
zs_status zs_query_objects(const zs_scene *scene, const zs_render_opts *opts,
                           zs_object_visibility **out, int32_t *n, zs_error *err);

#ifdef __cplusplus
}
#endif

#endif
