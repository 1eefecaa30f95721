/* zscan scene — models through assimp (see load_assimp.h for what is read
 * and what is refused).
 *
 * assimp trusts the counts in a file's header: its OFF and ASCII PLY
 * readers allocate (and construct) the declared number of vertices and
 * faces before reading any, so a 300-byte file can make it touch tens of
 * gigabytes.  Those headers are read here first and refused when they
 * declare more than the file can hold.  Everything assimp returns is then
 * checked again before it enters a zs_model: finite coordinates, indices in
 * range, sizes within limits.
 */
#include "scene/load_assimp.h"
#include "scene/load_common.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#ifdef ZS_HAVE_ASSIMP
#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#endif

int zs_assimp_available(void) {
#ifdef ZS_HAVE_ASSIMP
  return 1;
#else
  return 0;
#endif
}

#ifndef ZS_HAVE_ASSIMP

zs_status zs_assimp_cameras(const char *path, zs_file_camera **out, int *n, zs_error *err) {
  *out = NULL;
  *n = 0;
  return zs_error_set(err, ZS_ERR_UNSUPPORTED,
                      "%s: cameras are read through assimp (built without it)", path);
}

zs_status zs_assimp_load(const char *path, zs_model *out, zs_error *err) {
  zs_model_init(out);
  return zs_error_set(err, ZS_ERR_UNSUPPORTED,
                      "%s: this build reads only .obj (built without assimp)", path);
}

#else

enum { HEADER_BYTES = 1 << 16 }; /* of a file read for the header checks */

/* Sets err to the message with every control character written as a
 * space: assimp's messages span lines, and names from the file may hold
 * anything. */
static zs_status
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    set_error(zs_error *err, zs_status code, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  zs_status st = zs_load_verror(err, code, 1, NULL, fmt, ap);
  va_end(ap);
  return st;
}

/* ---- header checks ---------------------------------------------------- */

/* The first bytes of a file, NUL-terminated, and its size. */
typedef struct file_head {
  char text[HEADER_BYTES + 1];
  size_t len;
  uint64_t size;
} file_head;

static int lower(int c) { return c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c; }

static int has_extension(const char *path, const char *ext) {
  size_t n = strlen(path), k = strlen(ext);
  if (n < k) return 0;
  for (size_t i = 0; i < k; i++)
    if (lower((unsigned char)path[n - k + i]) != ext[i]) return 0;
  return 1;
}

/* A decimal count at *s (saturating at UINT64_MAX); 0 when there is none. */
static int read_count(const char **s, uint64_t *out) {
  const char *p = *s;
  if (*p < '0' || *p > '9') return 0;
  uint64_t v = 0;
  for (; *p >= '0' && *p <= '9'; p++)
    v = v > (UINT64_MAX - 9) / 10 ? UINT64_MAX : v * 10 + (uint64_t)(*p - '0');
  *s = p;
  *out = v;
  return 1;
}

static uint64_t sat_add(uint64_t a, uint64_t b) { return a > UINT64_MAX - b ? UINT64_MAX : a + b; }
static uint64_t sat_mul(uint64_t a, uint64_t b) {
  return b != 0 && a > UINT64_MAX / b ? UINT64_MAX : a * b;
}

static int is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

/* Skips blanks and comment lines, as assimp's OFF reader does. */
static void off_next_token(const char **s) {
  for (;;) {
    while (is_blank(**s)) (*s)++;
    if (**s != '#') return;
    while (**s && **s != '\n') (*s)++;
  }
}

/* The vertex and face counts of an OFF header ([ST][C][N][4][n]OFF, an
 * optional dimension after nOFF, then the counts); 0 when the text does
 * not read as one.  Without the OFF keyword the file is OFF only by its
 * extension (is_off_name). */
static int off_counts(const char *t, int is_off_name, uint64_t *nv, uint64_t *nf) {
  const char *s = t;
  off_next_token(&s);
  int dim = 0;
  if (s[0] == 'S' && s[1] == 'T') s += 2;
  if (*s == 'C') s++;
  if (*s == 'N') s++;
  if (*s == '4') s++;
  if (*s == 'n') s++, dim = 1;
  if (strncmp(s, "OFF", 3) == 0) {
    s += 3;
  } else {
    if (!is_off_name) return 0;
    s = t;
    dim = 0;
  }
  off_next_token(&s);
  uint64_t d;
  if (dim && !read_count(&s, &d)) return 0;
  off_next_token(&s);
  if (!read_count(&s, nv)) return 0;
  off_next_token(&s);
  return read_count(&s, nf);
}

/* Bytes of one value of a PLY type name in a binary file (1 if unknown). */
static uint64_t ply_type_size(const char *type) {
  static const struct {
    const char *name;
    unsigned size;
  } types[] = {{"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},
               {"short", 2}, {"ushort", 2},  {"int16", 2},  {"uint16", 2},
               {"int", 4},   {"uint", 4},    {"int32", 4},  {"uint32", 4},
               {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
    if (strcmp(type, types[i].name) == 0) return types[i].size;
  return 1;
}

/* The fewest bytes the elements a PLY header declares can take: each
 * element at least one byte per property in ASCII, the sizes of its
 * scalars (and of its lists' counts) in binary, and one byte if it has no
 * property.  0 when the text is not a complete PLY header; *body is the
 * header's length. */
static int ply_min_bytes(const char *t, uint64_t *min_bytes, uint64_t *body) {
  if (strncmp(t, "ply", 3) != 0 || (t[3] != '\n' && t[3] != '\r')) return 0;
  int binary = 0;
  uint64_t total = 0, count = 0, per = 0;
  const char *line = t;
  while (*line) {
    const char *end = strchr(line, '\n');
    if (!end) return 0; /* header longer than what was read */
    char buf[256], w[4][64];
    size_t n = (size_t)(end - line) < sizeof buf - 1 ? (size_t)(end - line) : sizeof buf - 1;
    memcpy(buf, line, n);
    buf[n] = '\0';
    int nw = sscanf(buf, "%63s %63s %63s %63s", w[0], w[1], w[2], w[3]);
    line = end + 1;
    if (nw < 1) continue;
    if (strcmp(w[0], "end_header") == 0) {
      total = sat_add(total, sat_mul(count, per ? per : 1));
      *min_bytes = total;
      *body = (uint64_t)(line - t);
      return 1;
    }
    if (strcmp(w[0], "format") == 0 && nw >= 2) {
      binary = strncmp(w[1], "binary", 6) == 0;
    } else if (strcmp(w[0], "element") == 0 && nw >= 3) {
      total = sat_add(total, sat_mul(count, per ? per : 1));
      const char *c = w[2];
      if (!read_count(&c, &count)) count = 0;
      per = 0;
    } else if (strcmp(w[0], "property") == 0 && nw >= 3) {
      /* "property TYPE NAME" or "property list COUNT_TYPE INDEX_TYPE NAME" */
      int list = strcmp(w[1], "list") == 0;
      per = sat_add(per, binary ? ply_type_size(list ? w[2] : w[1]) : 1);
    }
  }
  return 0;
}

/* Refuses an OFF or PLY file whose header declares more than it holds. */
static zs_status check_header(const char *path, const file_head *h, zs_error *err) {
  uint64_t nv, nf, need, body;
  if (off_counts(h->text, has_extension(path, ".off"), &nv, &nf)) {
    /* every vertex and face line takes at least two bytes */
    if (sat_mul(sat_add(nv, nf), 2) > h->size)
      return set_error(err, ZS_ERR_PARSE,
                       "%s: OFF header declares %llu vertices and %llu faces, more than "
                       "the file's %llu bytes can hold",
                       path, (unsigned long long)nv, (unsigned long long)nf,
                       (unsigned long long)h->size);
  } else if (ply_min_bytes(h->text, &need, &body)) {
    if (need > h->size - body)
      return set_error(err, ZS_ERR_PARSE,
                       "%s: PLY header declares elements of at least %llu bytes, more than "
                       "the file's %llu bytes after the header",
                       path, (unsigned long long)need, (unsigned long long)(h->size - body));
  }
  return ZS_OK;
}

/* ---- the scene -------------------------------------------------------- */

typedef struct loader {
  const char *path;
  const struct aiScene *scene;
  zs_model *m;
  int64_t vertices, faces; /* added so far */
  zs_error *err;
} loader;

/* 4x4 row-major doubles from an aiMatrix4x4 (also row-major, column
 * vectors, so the same convention as raster.h). */
static void from_ai(const struct aiMatrix4x4 *a, double m[16]) {
  const ai_real v[16] = {a->a1, a->a2, a->a3, a->a4, a->b1, a->b2, a->b3, a->b4,
                         a->c1, a->c2, a->c3, a->c4, a->d1, a->d2, a->d3, a->d4};
  for (int i = 0; i < 16; i++) m[i] = (double)v[i];
}

static void mat_mul(double out[16], const double a[16], const double b[16]) {
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 4; c++) {
      double s = 0.0;
      for (int k = 0; k < 4; k++) s += a[4 * r + k] * b[4 * k + c];
      out[4 * r + c] = s;
    }
}

static uint32_t channel(float c) {
  double x = c > 0.0f ? (c < 1.0f ? c : 1.0f) : 0.0; /* NaN gives 0 */
  return (uint32_t)lround(x * 255.0);
}

static uint32_t mesh_colour(const struct aiScene *sc, const struct aiMesh *mesh) {
  if (mesh->mMaterialIndex >= sc->mNumMaterials || !sc->mMaterials) return ZS_GREY;
  struct aiColor4D c;
  if (aiGetMaterialColor(sc->mMaterials[mesh->mMaterialIndex], AI_MATKEY_COLOR_DIFFUSE, &c) !=
      aiReturn_SUCCESS)
    return ZS_GREY;
  return channel(c.r) << 16 | channel(c.g) << 8 | channel(c.b);
}

/* The object name of mesh mi placed by node nd. */
static void object_name(const struct aiNode *nd, unsigned mi, const struct aiMesh *mesh, char *buf,
                        size_t cap) {
  const char *node = nd->mName.length ? nd->mName.data : "";
  char mname[32];
  const char *mesh_name = mname;
  if (mesh->mName.length) mesh_name = mesh->mName.data;
  else snprintf(mname, sizeof mname, "mesh_%u", mi);
  if (!*node) snprintf(buf, cap, "%s", mesh_name);
  else if (nd->mNumMeshes > 1) snprintf(buf, cap, "%s/%s", node, mesh_name);
  else snprintf(buf, cap, "%s", node);
}

static zs_status add_mesh(loader *L, const struct aiNode *nd, unsigned j, const double xf[16]) {
  unsigned mi = nd->mMeshes[j];
  if (mi >= L->scene->mNumMeshes || !L->scene->mMeshes[mi])
    return set_error(L->err, ZS_ERR_PARSE, "%s: node %s: mesh %u does not exist", L->path,
                     nd->mName.data, mi);
  const struct aiMesh *mesh = L->scene->mMeshes[mi];
  if (L->vertices + mesh->mNumVertices > ZS_ASSIMP_MAX_VERTICES ||
      L->faces + mesh->mNumFaces > ZS_ASSIMP_MAX_VERTICES)
    return set_error(L->err, ZS_ERR_LIMIT, "%s: more than %d vertices or faces", L->path,
                     ZS_ASSIMP_MAX_VERTICES);
  if (mesh->mNumVertices > 0 && !mesh->mVertices)
    return set_error(L->err, ZS_ERR_PARSE, "%s: mesh %u has no vertex positions", L->path, mi);
  char name[2 * MAXLEN + 2];
  object_name(nd, mi, mesh, name, sizeof name);
  int32_t obj = zs_model_object(L->m, name);
  if (obj < 0) return set_error(L->err, ZS_ERR_NOMEM, "%s: out of memory", L->path);
  int32_t base = L->m->mesh.nverts;
  for (unsigned v = 0; v < mesh->mNumVertices; v++) {
    const struct aiVector3D *p = &mesh->mVertices[v];
    double q[4], w[3];
    double in[3] = {p->x, p->y, p->z};
    for (int r = 0; r < 4; r++)
      q[r] = xf[4 * r] * in[0] + xf[4 * r + 1] * in[1] + xf[4 * r + 2] * in[2] + xf[4 * r + 3];
    for (int k = 0; k < 3; k++) w[k] = q[3] == 1.0 ? q[k] : q[k] / q[3];
    if (!isfinite(in[0]) || !isfinite(in[1]) || !isfinite(in[2]) || !isfinite(w[0]) ||
        !isfinite(w[1]) || !isfinite(w[2]))
      return set_error(L->err, ZS_ERR_PARSE, "%s: mesh %u vertex %u: not a finite number", L->path,
                       mi, v);
    if (zs_model_add_vertex(L->m, w[0], w[1], w[2]) < 0)
      return set_error(L->err, ZS_ERR_NOMEM, "%s: out of memory", L->path);
  }
  L->vertices += mesh->mNumVertices;
  uint32_t rgb = mesh_colour(L->scene, mesh);
  for (unsigned f = 0; f < mesh->mNumFaces; f++) {
    const struct aiFace *face = &mesh->mFaces[f];
    if (face->mNumIndices < 3) continue; /* a point or a line */
    if (face->mNumIndices > INT32_MAX / sizeof(int32_t))
      return set_error(L->err, ZS_ERR_LIMIT, "%s: mesh %u face %u: %u vertices", L->path, mi, f,
                       face->mNumIndices);
    /* a face may have any number of corners: the model splits it */
    int32_t small[ZS_MAX_POLY_VERTS];
    int32_t *idx = face->mNumIndices <= ZS_MAX_POLY_VERTS
                       ? small
                       : malloc(face->mNumIndices * sizeof *idx);
    if (!idx) return set_error(L->err, ZS_ERR_NOMEM, "%s: out of memory", L->path);
    zs_status st = ZS_OK;
    for (unsigned k = 0; k < face->mNumIndices && st == ZS_OK; k++) {
      if (face->mIndices[k] >= mesh->mNumVertices)
        st = set_error(L->err, ZS_ERR_PARSE, "%s: mesh %u face %u: vertex index %u out of range",
                       L->path, mi, f, face->mIndices[k]);
      idx[k] = base + (int32_t)face->mIndices[k];
    }
    if (st == ZS_OK && zs_model_add_polygon(L->m, idx, (int)face->mNumIndices, rgb, obj) != ZS_OK)
      st = set_error(L->err, ZS_ERR_NOMEM, "%s: out of memory", L->path);
    if (idx != small) free(idx);
    if (st != ZS_OK) return st;
    L->faces++;
  }
  return ZS_OK;
}

static zs_status walk(loader *L, const struct aiNode *nd, const double parent[16], int depth) {
  if (depth > ZS_ASSIMP_MAX_DEPTH)
    return set_error(L->err, ZS_ERR_LIMIT, "%s: node tree deeper than %d", L->path,
                     ZS_ASSIMP_MAX_DEPTH);
  double local[16], xf[16];
  from_ai(&nd->mTransformation, local);
  mat_mul(xf, parent, local);
  for (unsigned j = 0; j < nd->mNumMeshes; j++) {
    zs_status st = add_mesh(L, nd, j, xf);
    if (st != ZS_OK) return st;
  }
  for (unsigned c = 0; c < nd->mNumChildren; c++) {
    if (!nd->mChildren || !nd->mChildren[c]) continue;
    zs_status st = walk(L, nd->mChildren[c], xf, depth + 1);
    if (st != ZS_OK) return st;
  }
  return ZS_OK;
}

/* The file at path through assimp with flags, once its header passed the
 * checks above; *sc is assimp's to release. */
static zs_status import_checked(const char *path, unsigned flags, const struct aiScene **sc,
                                zs_error *err) {
  *sc = NULL;
  file_head *h = malloc(sizeof *h);
  if (!h) return set_error(err, ZS_ERR_NOMEM, "%s: out of memory", path);
  zs_status st =
      zs_load_head(path, ZS_ASSIMP_MAX_BYTES, h->text, HEADER_BYTES, &h->len, &h->size, err);
  if (st == ZS_OK) st = check_header(path, h, err);
  free(h);
  if (st != ZS_OK) return st;
  *sc = aiImportFile(path, flags);
  if (!*sc) {
    const char *why = aiGetErrorString();
    return set_error(err, ZS_ERR_PARSE, "%s: %s", path,
                     why && *why ? why : "assimp could not read the file");
  }
  return ZS_OK;
}

zs_status zs_assimp_load(const char *path, zs_model *out, zs_error *err) {
  zs_model_init(out);
  const struct aiScene *sc;
  zs_status st = import_checked(path,
                                aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                    aiProcess_ValidateDataStructure,
                                &sc, err);
  if (st != ZS_OK) return st;
  if ((sc->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || sc->mNumMeshes == 0 || !sc->mRootNode) {
    unsigned cameras = sc->mNumCameras;
    aiReleaseImport(sc);
    if (cameras)
      return set_error(err, ZS_ERR_PARSE,
                       "%s: no meshes (%u camera%s and nothing to draw; render --list-cameras "
                       "lists them)",
                       path, cameras, cameras == 1 ? "" : "s");
    return set_error(err, ZS_ERR_PARSE, "%s: no meshes", path);
  }
  loader L = {path, sc, out, 0, 0, err};
  double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  st = walk(&L, sc->mRootNode, identity, 0);
  if (st == ZS_OK && out->nsource_faces == 0)
    st = set_error(err, ZS_ERR_PARSE, "%s: no polygons (only points or lines)", path);
  aiReleaseImport(sc);
  if (st != ZS_OK) zs_model_free(out);
  return st;
}

/* ---- cameras ---------------------------------------------------------- */

/* The world transform of the node named name, into xf, and its own, into
 * local; 0 when no node has that name. */
static int find_node(const struct aiNode *nd, const char *name, const double parent[16],
                     double xf[16], double local[16], int depth) {
  if (!nd || depth > ZS_ASSIMP_MAX_DEPTH) return 0;
  double own[16], here[16];
  from_ai(&nd->mTransformation, own);
  mat_mul(here, parent, own);
  if (strcmp(nd->mName.data, name) == 0) {
    memcpy(xf, here, sizeof here);
    memcpy(local, own, sizeof own);
    return 1;
  }
  for (unsigned c = 0; c < nd->mNumChildren; c++)
    if (nd->mChildren && find_node(nd->mChildren[c], name, here, xf, local, depth + 1)) return 1;
  return 0;
}

/* xf applied to (x, y, z, w): w = 1 a point, w = 0 a direction. */
static void place(const double xf[16], const struct aiVector3D *v, double w, double out[3]) {
  double p[3] = {v->x, v->y, v->z};
  for (int r = 0; r < 3; r++)
    out[r] = xf[4 * r] * p[0] + xf[4 * r + 1] * p[1] + xf[4 * r + 2] * p[2] + xf[4 * r + 3] * w;
}

zs_status zs_assimp_cameras(const char *path, zs_file_camera **out, int *n, zs_error *err) {
  *out = NULL;
  *n = 0;
  const struct aiScene *sc;
  zs_status st = import_checked(path, aiProcess_ValidateDataStructure, &sc, err);
  if (st != ZS_OK) return st;
  zs_file_camera *cams = sc->mNumCameras ? calloc(sc->mNumCameras, sizeof *cams) : NULL;
  if (sc->mNumCameras && !cams) {
    aiReleaseImport(sc);
    return set_error(err, ZS_ERR_NOMEM, "%s: out of memory", path);
  }
  const double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  for (unsigned i = 0; i < sc->mNumCameras && st == ZS_OK; i++) {
    const struct aiCamera *c = sc->mCameras[i];
    zs_file_camera *k = &cams[i];
    snprintf(k->name, sizeof k->name, "%.*s", (int)sizeof k->name - 1, c->mName.data);
    double xf[16], local[16];
    if (!find_node(sc->mRootNode, c->mName.data, identity, xf, local, 0)) {
      memcpy(xf, identity, sizeof xf);
      memcpy(local, identity, sizeof local);
    }
    /* A camera's position is relative to its node; but assimp's glTF 2
     * importer also copies the node's translation into it, which would
     * count it twice: a position equal to the node's own translation is
     * taken as that copy. */
    struct aiVector3D pos = c->mPosition;
    if ((pos.x != 0 || pos.y != 0 || pos.z != 0) && pos.x == local[3] && pos.y == local[7] &&
        pos.z == local[11])
      pos.x = pos.y = pos.z = 0;
    double dir[3];
    place(xf, &pos, 1.0, k->eye);
    place(xf, &c->mLookAt, 0.0, dir);
    place(xf, &c->mUp, 0.0, k->up);
    for (int a = 0; a < 3; a++) k->target[a] = k->eye[a] + dir[a];
    k->hfov_deg = c->mHorizontalFOV * (180.0 / 3.14159265358979323846);
    k->ortho_half_width = c->mOrthographicWidth;
    k->aspect = c->mAspect;
    k->znear = c->mClipPlaneNear;
    k->zfar = c->mClipPlaneFar;
    for (int a = 0; a < 3 && st == ZS_OK; a++)
      if (!isfinite(k->eye[a]) || !isfinite(k->target[a]) || !isfinite(k->up[a]))
        st = set_error(err, ZS_ERR_PARSE, "%s: camera %u (%s): not a finite number", path, i,
                       k->name);
  }
  int count = (int)sc->mNumCameras;
  aiReleaseImport(sc);
  if (st != ZS_OK) {
    free(cams);
    return st;
  }
  *out = cams;
  *n = count;
  return ZS_OK;
}

#endif
