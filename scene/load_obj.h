/* zscan scene — a Wavefront OBJ reader.
 *
 * What is read:
 *   v x y z [w]     a vertex (divided by w when w != 1); the common
 *                   extension `v x y z r g b` is accepted, colours ignored
 *   f a b c ...     a polygon of 3 or more vertices (any number), each
 *                   written v, v/vt, v//vn or v/vt/vn; a negative v counts
 *                   back from the last vertex defined so far (-1 is the
 *                   last); only vertices defined earlier may be used
 *   o NAME, g NAME  the object of the following faces (objects of the same
 *                   name are one; `g` with several names uses the first; no
 *                   name: no object, -1, as for faces before any o or g)
 *   mtllib FILE...  material libraries, relative to dir; a library that
 *                   cannot be opened is skipped (faces stay grey)
 *   usemtl NAME     the material of the following faces: its Kd as
 *                   0xRRGGBB, each channel round(clamp(kd, 0, 1) * 255);
 *                   a name no library defines, or a material without Kd,
 *                   gives ZS_GREY.  Materials are looked up once the whole
 *                   file is read, so an mtllib may come after its usemtl.
 * The other statements of the format (vt, vn, vp, s, l, p, curves and
 * surfaces), comments from a '#' starting a word, and unknown words made of
 * letters, digits and '_' (another program's extension) are ignored.  But
 * a file that is mostly lines of unknown words, or any line that holds a
 * control byte other than white space or starts with something that is no
 * word, is not an OBJ: "FILE:LINE: not an OBJ statement".  In .mtl files only newmtl and
 * Kd r [g b] are read (Kd spectral / Kd xyz are ignored).
 *
 * Faces are numbered from 0 in file order (the model's nsource_faces); a
 * concave or non-planar face is split by zs_model_add_polygon, each piece
 * keeping the face's number.
 *
 * Errors are reported as "FILE:LINE: reason" (the .mtl file's path and
 * line for errors in a library) or "FILE: cannot open: reason".  Lines
 * longer than ZS_OBJ_LINE_MAX bytes and NUL bytes are refused.
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

#endif
