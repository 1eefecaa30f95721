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
 * ZS_GREY when the material has none.
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
 *   - no polygon at all (a point cloud, lines only).
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

#endif
