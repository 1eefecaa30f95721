/* zscan scene — model formats beyond OBJ through assimp's C API (PLY, STL,
 * OFF, glTF 1 and 2, 3DS, Collada, ...).
 *
 * What is read.  The file is imported with aiProcess_Triangulate,
 * aiProcess_JoinIdenticalVertices and aiProcess_ValidateDataStructure;
 * then the node tree is walked depth first (a node's meshes in order, then
 * its children in order), each node's transform composed with its
 * parents'.  Every (node, mesh) pair becomes one object of the model: the
 * mesh's vertices placed by the node's world transform, and its faces.
 * The object is named after the node ("mesh_M" when the node has no name
 * but the mesh has none either; the mesh's name when only it has one); a
 * node with several meshes names them "NODE/MESH".  Objects of the same
 * name are one (as in OBJ).  Faces are the triangles (and polygons) of the
 * meshes; points and lines are skipped.  Faces are numbered from 0 in the
 * order of the walk.  A face's colour is its material's diffuse colour
 * (AI_MATKEY_COLOR_DIFFUSE, each channel round(clamp(c, 0, 1) * 255)),
 * ZS_GREY when the material has none: what the flat shading draws.
 *
 * Shading attributes (zscan.h, zs_mesh).  A mesh with normals, first
 * colours (COLOR_0, as round(clamp(c, 0, 1) * 255)) or first texture
 * coordinates (TEXCOORD_0, OpenGL's v up as assimp gives them: no
 * aiProcess_FlipUVs) gets one attribute vertex per vertex, its normal
 * turned by the node's transform (the cofactors of its 3 x 3, unit
 * length); a mesh without them gets none, so a file without any has no
 * attribute arrays and draws as before.  Where a mesh has colours or
 * coordinates but no normals (or a normal of zero length),
 * zs_model_compute_normals (crease 60 degrees) makes them, never
 * assimp's aiProcess_GenNormals.  A normal, colour or texture
 * coordinate that is not a finite number is refused: "FILE: mesh M
 * vertex V: normal not a finite number" (ZS_ERR_PARSE).  JoinIdenticalVertices joins only
 * vertices whose every attribute is equal, so nothing read is lost.
 *
 * Materials, one per assimp material that a mesh with polygons uses, in
 * the order of first use: the base colour AI_MATKEY_BASE_COLOR, else
 * the diffuse one, its alpha replaced by AI_MATKEY_OPACITY when there is
 * one, and 255 under glTF's alphaMode OPAQUE; the specular colour (times
 * AI_MATKEY_SHININESS_STRENGTH) and AI_MATKEY_SHININESS (rounded, at most
 * ZS_MAX_SHININESS), none when the shininess is 0 or the shading model
 * is flat, Gouraud or none, as assimp defines them; the emissive colour;
 * AI_MATKEY_TWOSIDED (double-sided when absent).  The base colour's
 * texture is the first of aiTextureType_BASE_COLOR, else _DIFFUSE: a
 * file relative to the model's folder ('\' read as '/'), or embedded
 * ("*N", or a file name of aiScene.mTextures): compressed PNG or JPEG
 * bytes, or B, G, R, A texels.  Each texture is read once however many
 * materials name it, and owned by the model.  Its wrap modes are
 * AI_MATKEY_MAPPINGMODE_U/V (wrap, clamp and decal as clamp, mirror);
 * its filter glTF's sampler's (GltfMaterial.h): the minification filter
 * NEAREST and NEAREST_MIPMAP_NEAREST nearest, LINEAR and
 * LINEAR_MIPMAP_NEAREST bilinear, *_MIPMAP_LINEAR trilinear; else a
 * magnification filter NEAREST nearest; else the default.
 *
 * What is refused, each as one line "FILE: reason":
 *   - a file that cannot be opened, is not a regular file, or is larger
 *     than ZS_ASSIMP_MAX_BYTES;
 *   - an OFF or PLY file whose header declares more vertices, faces or
 *     elements than the file has bytes for (assimp would reserve memory for
 *     the declared counts first: invalid/OutOfMemory.off of assimp's test
 *     models asks for about 1.3 billion vertices);
 *   - whatever assimp refuses (its message, newlines replaced by spaces);
 *   - a scene without meshes or marked incomplete; a node tree deeper than
 *     ZS_ASSIMP_MAX_DEPTH;
 *   - a vertex that is not finite, before or after its node's transform
 *     ("mesh M vertex V: not a finite number"); a face index out of range;
 *   - more than ZS_ASSIMP_MAX_VERTICES vertices or faces in all (meshes
 *     instanced by many nodes are counted each time);
 *   - no polygon at all (a point cloud, lines only);
 *   - a texture coordinate that is not finite ("mesh M vertex V: texture
 *     coordinate not a finite number");
 *   - a texture that cannot be read ("FILE: texture PATH: REASON", REASON
 *     as scene/texture_file.h words it, e.g. "cannot open: No such file
 *     or directory"), or an embedded one that does not exist; with
 *     ZS_ASSIMP_SKIP_MISSING_TEXTURES, one that cannot be opened or read
 *     is a note instead (below).
 * A build without assimp (ZS_HAVE_ASSIMP undefined) refuses every file
 * with "FILE: this build reads only .obj (built without assimp)".
 */
#ifndef ZS_SCENE_LOAD_ASSIMP_H
#define ZS_SCENE_LOAD_ASSIMP_H

#include "zscan/error.h"
#include "scene/model.h"

#define ZS_ASSIMP_MAX_BYTES (256ll << 20) /* 256 MiB */

enum {
  ZS_ASSIMP_MAX_VERTICES = 1 << 26, /* vertices, and faces, in all */
  ZS_ASSIMP_MAX_DEPTH = 256         /* nodes from the root */
};

/* Whether this build reads files through assimp. */
int zs_assimp_available(void);

/* A camera stored in a model file (glTF, Collada, FBX, 3DS, ...), placed
 * in the world by its node.  The field of view is the file's horizontal
 * angle (assimp's importers give the whole angle); an orthographic camera
 * has ortho_half_width > 0 instead. */
typedef struct zs_file_camera {
  char name[96];
  double eye[3], target[3], up[3];
  double hfov_deg;          /* the whole horizontal angle, degrees */
  double ortho_half_width;  /* > 0: orthographic, half the view's width */
  double aspect;            /* width / height the file gives, 0 when none */
  double znear, zfar;
} zs_file_camera;

/* The cameras of the model file at path, in the file's order: *out
 * (malloc'd, free() it) and *n, which may be 0. */
zs_status zs_assimp_cameras(const char *path, zs_file_camera **out, int *n, zs_error *err);

/* Reads the model file at path into out, which is initialised here (any
 * previous content is not freed).  On failure out is left empty and err
 * says why. */
zs_status zs_assimp_load(const char *path, zs_model *out, zs_error *err);

/* Flags of zs_assimp_load_flags (0: the defaults). */
enum {
  /* A texture file that cannot be opened or read (ZS_ERR_IO) leaves its
   * materials untextured instead of failing the load, and the model's
   * notes say so, once per file: the message the load would have failed
   * with and ": drawn without it" ("FILE: texture DIR/wood.png: cannot
   * open: No such file or directory: drawn without it").  A corrupt
   * image, or an embedded one that is not there, is still an error. */
  ZS_ASSIMP_SKIP_MISSING_TEXTURES = 1
};

/* zs_assimp_load with flags (ZS_ASSIMP_*); the plain one passes 0. */
zs_status zs_assimp_load_flags(const char *path, int flags, zs_model *out, zs_error *err);

#endif
