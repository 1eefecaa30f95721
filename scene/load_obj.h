/* zscan scene — a Wavefront OBJ reader.
 *
 * What is read:
 *   v x y z [w]     a vertex (divided by w when w != 1); the common
 *                   extension `v x y z r g b` gives it a colour, 0 .. 1 a
 *                   channel as MeshLab and Open3D write them (values
 *                   beyond are clamped: 0 .. 255 colours come out white),
 *                   255 * x rounded, opaque
 *   vn x y z        a normal (any length; one beyond the range of a float
 *                   is scaled by a power of two; (0, 0, 0) is none)
 *   vt u [v [w]]    a texture coordinate, (0, 0) the bottom left of the
 *                   image as in OpenGL; v 0 when not given, w ignored; a
 *                   value beyond the range of a float is refused
 *   f a b c ...     a polygon of 3 or more vertices (any number), each
 *                   written v, v/vt, v//vn or v/vt/vn; a negative index
 *                   counts back from the last of its kind defined so far
 *                   (-1 is the last); only those defined earlier may be
 *                   used
 *   o NAME, g NAME  the object of the following faces (objects of the same
 *                   name are one; `g` with several names uses the first; no
 *                   name: no object, -1, as for faces before any o or g)
 *   mtllib FILE...  material libraries, relative to dir; a library that
 *                   cannot be opened is skipped (faces stay grey)
 *   usemtl NAME     the material of the following faces.  Each name is a
 *                   material of the model (numbered in the order of first
 *                   use; faces before the first usemtl get a grey one of
 *                   their own after them), and the face colour is its Kd as
 *                   0xRRGGBB, each channel round(clamp(kd, 0, 1) * 255); a
 *                   name no library defines, or a material without Kd,
 *                   gives ZS_GREY (zs_material_default).  Materials are
 *                   looked up once the whole file is read, so an mtllib may
 *                   come after its usemtl.
 * The corners get attribute vertices (zscan.h, zs_mesh) only when they
 * name a vt or a vn or a coloured vertex: one per distinct triple, numbered
 * in the order of first use.  A file with none of them has no attribute
 * arrays (and with no usemtl, no materials either): it draws as it always
 * did.  When there are attributes or a textured material, the corners
 * without a normal get one from zs_model_compute_normals at a crease of
 * 60 degrees.
 * l v1 v2 ... is a polyline and p v1 ... a list of points (zs_mesh's
 * lines and points; a vt after '/' read and dropped).
 * The other statements of the format (vp, s, curves and surfaces),
 * comments from a '#' starting a word, and unknown words made of
 * letters, digits and '_' (another program's extension) are ignored.  But
 * a file that is mostly lines of unknown words, or any line that holds a
 * control byte other than white space or starts with something that is no
 * word, is not an OBJ: "FILE:LINE: not an OBJ statement".
 *
 * In .mtl files (the MTL specification; spectral and xyz colours ignored):
 *   newmtl NAME     a material (a later definition of a name wins)
 *   Kd r [g b]      the base colour and face colour (one number: grey)
 *   Ks r [g b]      the highlight's colour, Ke r [g b] the emission
 *   Ns x            the shininess, rounded and clamped to 0 ..
 *                   ZS_MAX_SHININESS (none: 0, no highlight)
 *   d x, Tr x       the alpha: d (its -halo ignored), or 1 - Tr where no
 *                   d is given, whatever their order
 *   map_Kd [-options] FILE   the base colour's texture, FILE (the rest of
 *                   the line, a '\' taken for '/' as Windows exporters
 *                   mean it) relative to the .mtl file's folder; read
 *                   once per path, only for materials that faces use;
 *                   `-clamp on` clamps it at its edges (else it repeats),
 *                   the other options of the specification are read and
 *                   ignored, an unknown one is an error
 * Every material is double-sided (OBJ has no notion of sides) with the
 * material's own texture filter (ZS_FILTER_DEFAULT).  illum, Ka, Ni and
 * the other maps are ignored.
 *
 * Faces are numbered from 0 in file order (the model's nsource_faces); a
 * concave or non-planar face is split by zs_model_add_face, each piece
 * keeping the face's number and its corners' attributes.
 *
 * Errors are reported as "FILE:LINE: reason" (the .mtl file's path and
 * line for errors in a library) or "FILE: cannot open: reason".  A
 * texture that cannot be read is an error at its map_Kd line, the file
 * as written there, then the image reader's reason:
 * "DIR/m.mtl:12: map_Kd wood.png: cannot open: No such file or
 * directory" (with ZS_OBJ_SKIP_MISSING_TEXTURES, one that cannot be
 * opened or read is a note instead).  Lines longer than ZS_OBJ_LINE_MAX
 * bytes and NUL bytes are refused.
 */
#ifndef ZS_SCENE_LOAD_OBJ_H
#define ZS_SCENE_LOAD_OBJ_H

#include <stddef.h>

#include "zscan/error.h"
#include "scene/model.h"

enum { ZS_OBJ_LINE_MAX = 65536 }; /* bytes per line, without "\r\n" */
/* The largest OBJ file read (1 GiB): a larger one is refused before
 * anything is allocated for it ("FILE: larger than 1024 MiB"). */
#define ZS_OBJ_MAX_BYTES ((size_t)1 << 30)

/* Flags of zs_obj_load_flags and zs_obj_parse_flags (0: the defaults). */
enum {
  /* A texture that cannot be opened or read (ZS_ERR_IO) leaves its
   * materials untextured instead of failing the load, and the model's
   * notes say so, once per file: the message the load would have failed
   * with and ": drawn without it" ("m.mtl:12: map_Kd wood.png: cannot
   * open: No such file or directory: drawn without it").  An image that
   * is there but corrupt is still an error.  (zs_load_opts's
   * skip_missing_textures.) */
  ZS_OBJ_SKIP_MISSING_TEXTURES = 1
};

/* Reads the OBJ file at path into out, which is initialised here (any
 * previous content is not freed).  Material libraries are looked up in the
 * directory of path.  On failure out is left empty and err says why. */
zs_status zs_obj_load(const char *path, zs_model *out, zs_error *err);

/* Parses the len bytes of text (not necessarily NUL-terminated) as an OBJ
 * file.  name is used in messages; dir is the directory mtllib paths are
 * relative to ("" for the current directory, NULL to skip material
 * libraries).  out as for zs_obj_load. */
zs_status zs_obj_parse(const char *text, size_t len, const char *name,
                       const char *dir, zs_model *out, zs_error *err);

/* The same two with flags (ZS_OBJ_*); the plain ones pass 0. */
zs_status zs_obj_load_flags(const char *path, int flags, zs_model *out, zs_error *err);
zs_status zs_obj_parse_flags(const char *text, size_t len, const char *name, const char *dir,
                             int flags, zs_model *out, zs_error *err);

#endif
