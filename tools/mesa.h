/* zscan tools — the same scene through Mesa's llvmpipe (OSMesa), for the
 * cross-check test and `zscan bench raster --mesa`.
 *
 * Built with OSMesa when CMake finds it (libosmesa6-dev; ZS_HAVE_OSMESA),
 * else every call reports that Mesa is not there.  llvmpipe's thread
 * count is its own: it reads LP_NUM_THREADS when the first context is
 * made (the default: one per core). */
#ifndef ZS_TOOLS_MESA_H
#define ZS_TOOLS_MESA_H

#include <stdint.h>

#include "zscan/error.h"
#include "scene/scene.h"

typedef struct zs_mesa zs_mesa;

/* Whether zscan was built with OSMesa. */
int zs_mesa_available(void);

/* A w x h RGBA context with a 24-bit depth buffer; ZS_ERR_UNSUPPORTED
 * without OSMesa. */
zs_status zs_mesa_create(int w, int h, zs_mesa **out, zs_error *err);
void zs_mesa_destroy(zs_mesa *m);

/* The ids (id + 1, 0 where nothing) of the lines and points of scene s
 * alone, as zs_mesa_ids draws faces: GL_LINES at glLineWidth(width) and
 * GL_POINTS at glPointSize(size), aliased, in id order. */
zs_status zs_mesa_prim_ids(zs_mesa *m, const zs_scene *s, const double view[16],
                           const double proj[16], double width, double size, uint32_t *ids,
                           zs_error *err);

/* The face ids (id + 1, 0 where nothing) of scene s drawn with view and
 * proj (zscan's row-major matrices): one flat colour per face, a "less"
 * depth test, faces in id order, immediate mode.  ids: w * h, row 0 at
 * the top. */
zs_status zs_mesa_ids(zs_mesa *m, const zs_scene *s, const double view[16], const double proj[16],
                      uint32_t *ids, zs_error *err);

/* The colours (0xRRGGBB, row 0 at the top) of scene s drawn as zscan's
 * unlit shading draws it (zscan.h, ZS_SHADE_UNLIT): lighting off, smooth
 * shading, each corner's colour the face's base colour times its vertex
 * colour (8 bits, rounded as zscan rounds), each material's base texture
 * modulating it (GL_MODULATE) through filter (ZS_FILTER_NEAREST:
 * GL_NEAREST; else GL_LINEAR magnified and GL_LINEAR_MIPMAP_NEAREST or
 * _LINEAR minified, over zscan's own mip chain) and its wraps; faces as
 * polygons (GL fans them from their first corner, as zscan does) in id
 * order, a "less" depth test. */
zs_status zs_mesa_unlit(zs_mesa *m, const zs_scene *s, const double view[16],
                        const double proj[16], zs_filter filter, uint32_t *rgb, zs_error *err);

/* One frame of s as zscan's shading `shade` draws it, as fast as this GL
 * offers it (the equivalent state for `zscan bench raster --mesa
 * --shade`): each mesh's faces fanned into triangles whose corners carry
 * their normals, colours (the base colour times the vertex colour) and
 * texture coordinates, drawn from vertex arrays built on the first call,
 * a group a material, its texture bound (zscan's mip chain, GL_MODULATE)
 * when it has one; unlit: lighting off; gouraud: OpenGL's fixed-function
 * lighting with the device's lights (or the headlight) and a separate
 * specular colour; phong: the same lights per fragment, in a GLSL
 * program of Blinn-Phong.  Cleared first, finished (glFinish) at the end.
 * ZS_ERR_UNSUPPORTED for another shading, or phong where this GL has no
 * GLSL. */
zs_status zs_mesa_frame_shaded(zs_mesa *m, const zs_scene *s, const double view[16],
                               const double proj[16], zs_shade shade, zs_filter filter,
                               const zs_light *lights, int nlights, zs_error *err);

/* One frame of s as fast as this GL offers it: each mesh's faces, fanned
 * into triangles, drawn from vertex arrays (built on the first call), one
 * colour per instance; cleared first, finished (glFinish) at the end. */
zs_status zs_mesa_frame(zs_mesa *m, const zs_scene *s, const double view[16],
                        const double proj[16], zs_error *err);

#endif
