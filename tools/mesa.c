/* The same scene through Mesa's llvmpipe (mesa.h). */
#include "tools/mesa.h"

#ifdef ZS_HAVE_OSMESA

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/osmesa.h>
#include <stdlib.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <string.h>

#include "raster/raster.h"

/* A mesh's faces fanned into triangles: its index array. */
typedef struct fan {
  GLuint *index;
  GLsizei count;
} fan;

struct zs_mesa {
  OSMesaContext ctx;
  int w, h;
  unsigned char *rgba;
  fan *fans;
  int32_t nfans;
};

int zs_mesa_available(void) { return 1; }

zs_status zs_mesa_create(int w, int h, zs_mesa **out, zs_error *err) {
  *out = NULL;
#ifdef __GLIBC__
  /* llvmpipe allocates its bins and frees them every frame, and glibc
   * gives the freed top of the heap back to the kernel (it trims), so the
   * same pages would be faulted in again every frame and llvmpipe's times
   * would measure the kernel's page faults more than its rendering.
   * (glibc's thresholds adapt once a large block has been freed, so
   * without this a second context would often, not always, be faster than
   * the first.)  zscan allocates nothing per frame, so its times do not
   * depend on it (zscan bench raster --mesa --case builtin:teapots
   * measures both). */
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
  zs_mesa *m = calloc(1, sizeof *m);
  if (!m || !(m->rgba = malloc((size_t)w * (size_t)h * 4))) {
    free(m);
    return zs_error_set(err, ZS_ERR_NOMEM, "mesa: out of memory");
  }
  m->w = w, m->h = h;
  m->ctx = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, NULL);
  if (!m->ctx || !OSMesaMakeCurrent(m->ctx, m->rgba, GL_UNSIGNED_BYTE, w, h)) {
    zs_mesa_destroy(m);
    return zs_error_set(err, ZS_ERR_UNSUPPORTED, "mesa: cannot make an OSMesa context");
  }
  *out = m;
  return ZS_OK;
}

void zs_mesa_destroy(zs_mesa *m) {
  if (!m) return;
  if (m->ctx) OSMesaDestroyContext(m->ctx);
  for (int32_t i = 0; i < m->nfans; i++) free(m->fans[i].index);
  free(m->fans);
  free(m->rgba);
  free(m);
}

/* The state both paths share: viewport, clear, "less" depth, flat colour,
 * zscan's projection (GL is column-major). */
static void begin_frame(zs_mesa *m, const double proj[16]) {
  OSMesaMakeCurrent(m->ctx, m->rgba, GL_UNSIGNED_BYTE, m->w, m->h);
  glViewport(0, 0, m->w, m->h);
  glClearColor(0, 0, 0, 0);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DITHER);
  glShadeModel(GL_FLAT);
  double p[16];
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 4; c++) p[4 * c + r] = proj[4 * r + c];
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixd(p);
  glMatrixMode(GL_MODELVIEW);
}

static void load_modelview(const double view[16], const double model[16]) {
  double mv[16], g[16];
  zs_mat_mul(mv, view, model);
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 4; c++) g[4 * c + r] = mv[4 * r + c];
  glLoadMatrixd(g);
}

zs_status zs_mesa_ids(zs_mesa *m, const zs_scene *s, const double view[16], const double proj[16],
                      uint32_t *ids, zs_error *err) {
  (void)err;
  begin_frame(m, proj);
  for (int32_t i = 0; i < s->ninst; i++) { /* all faces, in id order */
    const zs_instance *in = &s->inst[i];
    load_modelview(view, in->model);
    const zs_mesh *mesh = &s->meshes[in->mesh].mesh;
    for (int32_t f = 0; f < mesh->nfaces; f++) {
      uint32_t id = in->id_base + (uint32_t)(mesh->face_id ? mesh->face_id[f] : f) + 1;
      glColor3ub((GLubyte)(id >> 16), (GLubyte)(id >> 8), (GLubyte)id);
      glBegin(GL_POLYGON);
      for (int32_t k = mesh->face_start[f]; k < mesh->face_start[f + 1]; k++)
        glVertex3dv(&mesh->pos[3 * mesh->face_vert[k]]);
      glEnd();
    }
  }
  glFinish();
  for (int y = 0; y < m->h; y++) /* GL's row 0 is the bottom */
    for (int x = 0; x < m->w; x++) {
      const unsigned char *q = &m->rgba[4 * ((size_t)(m->h - 1 - y) * m->w + x)];
      ids[(size_t)y * m->w + x] = (uint32_t)q[0] << 16 | (uint32_t)q[1] << 8 | q[2];
    }
  return ZS_OK;
}

/* The texture object of tex with filter and the wraps (made for each
 * draw that uses it: the cross-check's scenes are small), its levels
 * uploaded bottom row first, so that GL's t = 0 is the image's last row
 * and its t the v zscan reads. */
static GLuint texture_of(const zs_texture *tex, const zs_material *mat, zs_filter filter) {
  static const GLint wraps[] = {GL_REPEAT, GL_CLAMP_TO_EDGE, GL_MIRRORED_REPEAT};
  GLuint name = 0;
  glGenTextures(1, &name);
  glBindTexture(GL_TEXTURE_2D, name);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  const int levels = filter == ZS_FILTER_NEAREST ? 1 : zs_texture_levels(tex);
  for (int k = 0; k < levels; k++) {
    int w, h;
    const uint8_t *t = zs_texture_level(tex, k, &w, &h);
    uint8_t *flip = malloc(4 * (size_t)w * (size_t)h);
    if (!flip) break;
    for (int y = 0; y < h; y++) memcpy(flip + 4 * (size_t)y * w, t + 4 * (size_t)(h - 1 - y) * w, 4 * (size_t)w);
    glTexImage2D(GL_TEXTURE_2D, k, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, flip);
    free(flip);
  }
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, levels - 1);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
                  filter == ZS_FILTER_NEAREST    ? GL_NEAREST
                  : filter == ZS_FILTER_BILINEAR ? GL_LINEAR_MIPMAP_NEAREST
                                                 : GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER,
                  filter == ZS_FILTER_NEAREST ? GL_NEAREST : GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wraps[mat->wrap_s]);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wraps[mat->wrap_t]);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  return name;
}

zs_status zs_mesa_unlit(zs_mesa *m, const zs_scene *s, const double view[16],
                        const double proj[16], zs_filter filter, uint32_t *rgb, zs_error *err) {
  (void)err;
  begin_frame(m, proj);
  glShadeModel(GL_SMOOTH);
  for (int32_t i = 0; i < s->ninst; i++) {
    const zs_instance *in = &s->inst[i];
    load_modelview(view, in->model);
    const zs_mesh *mesh = &s->meshes[in->mesh].mesh;
    for (int32_t f = 0; f < mesh->nfaces; f++) {
      const zs_material *mat = NULL;
      if (mesh->materials && mesh->nmaterials > 0) {
        int32_t k = mesh->face_material ? mesh->face_material[f] : 0;
        mat = &mesh->materials[k >= 0 && k < mesh->nmaterials ? k : 0];
      }
      /* the base colour as zscan's surface shading takes it (zscan.h) */
      const uint32_t base = in->rgb != ZS_RGB_MESH ? in->rgb
                            : mat ? (uint32_t)mat->base[0] << 16 | (uint32_t)mat->base[1] << 8 | mat->base[2]
                            : mesh->color ? 0xFFFFFFu
                            : mesh->face_rgb ? mesh->face_rgb[f] : 0xB4B4B4u;
      const zs_filter fl = filter != ZS_FILTER_DEFAULT ? filter
                           : mat && mat->filter != ZS_FILTER_DEFAULT ? mat->filter
                                                                     : ZS_FILTER_TRILINEAR;
      GLuint tex = 0;
      if (mat && mat->base_texture) {
        tex = texture_of(mat->base_texture, mat, fl);
        glEnable(GL_TEXTURE_2D);
      }
      glBegin(GL_POLYGON);
      for (int32_t k = mesh->face_start[f]; k < mesh->face_start[f + 1]; k++) {
        int32_t a = mesh->corner_attr ? mesh->corner_attr[k] : mesh->face_vert[k];
        if (a >= mesh->nattrs) a = -1;
        GLubyte c[3];
        for (int ch = 0; ch < 3; ch++) {
          const uint32_t v = a >= 0 && mesh->color ? mesh->color[4 * (size_t)a + ch] : 255;
          c[ch] = (GLubyte)(((base >> (16 - 8 * ch) & 255) * v + 127) / 255);
        }
        glColor3ubv(c);
        if (a >= 0 && mesh->uv) glTexCoord2fv(&mesh->uv[2 * (size_t)a]);
        glVertex3dv(&mesh->pos[3 * mesh->face_vert[k]]);
      }
      glEnd();
      if (tex) {
        glDisable(GL_TEXTURE_2D);
        glDeleteTextures(1, &tex);
      }
    }
  }
  glFinish();
  for (int y = 0; y < m->h; y++)
    for (int x = 0; x < m->w; x++) {
      const unsigned char *q = &m->rgba[4 * ((size_t)(m->h - 1 - y) * m->w + x)];
      rgb[(size_t)y * m->w + x] = (uint32_t)q[0] << 16 | (uint32_t)q[1] << 8 | q[2];
    }
  return ZS_OK;
}

static zs_status make_fans(zs_mesa *m, const zs_scene *s, zs_error *err) {
  if (m->nfans == s->nmeshes) return ZS_OK;
  for (int32_t i = 0; i < m->nfans; i++) free(m->fans[i].index);
  free(m->fans);
  m->nfans = 0;
  if (!(m->fans = calloc((size_t)(s->nmeshes > 0 ? s->nmeshes : 1), sizeof *m->fans)))
    return zs_error_set(err, ZS_ERR_NOMEM, "mesa: out of memory");
  m->nfans = s->nmeshes;
  for (int32_t i = 0; i < s->nmeshes; i++) {
    const zs_mesh *mesh = &s->meshes[i].mesh;
    size_t n = 0;
    for (int32_t f = 0; f < mesh->nfaces; f++) {
      int32_t k = mesh->face_start[f + 1] - mesh->face_start[f];
      if (k >= 3) n += 3 * (size_t)(k - 2);
    }
    if (!(m->fans[i].index = malloc((n ? n : 1) * sizeof *m->fans[i].index)))
      return zs_error_set(err, ZS_ERR_NOMEM, "mesa: out of memory");
    GLuint *o = m->fans[i].index;
    for (int32_t f = 0; f < mesh->nfaces; f++) {
      const int32_t *v = &mesh->face_vert[mesh->face_start[f]];
      for (int32_t k = 1; k + 1 < mesh->face_start[f + 1] - mesh->face_start[f]; k++)
        *o++ = (GLuint)v[0], *o++ = (GLuint)v[k], *o++ = (GLuint)v[k + 1];
    }
    m->fans[i].count = (GLsizei)n;
  }
  return ZS_OK;
}

zs_status zs_mesa_frame(zs_mesa *m, const zs_scene *s, const double view[16],
                        const double proj[16], zs_error *err) {
  zs_status st = make_fans(m, s, err);
  if (st) return st;
  begin_frame(m, proj);
  glEnableClientState(GL_VERTEX_ARRAY);
  for (int32_t i = 0; i < s->ninst; i++) {
    const zs_instance *in = &s->inst[i];
    const zs_mesh *mesh = &s->meshes[in->mesh].mesh;
    load_modelview(view, in->model);
    glColor3ub((GLubyte)(in->rgb >> 16), (GLubyte)(in->rgb >> 8), (GLubyte)in->rgb);
    glVertexPointer(3, GL_DOUBLE, 0, mesh->pos);
    glDrawElements(GL_TRIANGLES, m->fans[in->mesh].count, GL_UNSIGNED_INT, m->fans[in->mesh].index);
  }
  glDisableClientState(GL_VERTEX_ARRAY);
  glFinish();
  return ZS_OK;
}

#else /* no OSMesa */

int zs_mesa_available(void) { return 0; }

zs_status zs_mesa_create(int w, int h, zs_mesa **out, zs_error *err) {
  (void)w, (void)h;
  *out = NULL;
  return zs_error_set(err, ZS_ERR_UNSUPPORTED,
                      "mesa: zscan was built without OSMesa (install libosmesa6-dev, rebuild)");
}

void zs_mesa_destroy(zs_mesa *m) { (void)m; }

zs_status zs_mesa_ids(zs_mesa *m, const zs_scene *s, const double view[16], const double proj[16],
                      uint32_t *ids, zs_error *err) {
  (void)m, (void)s, (void)view, (void)proj, (void)ids;
  return zs_error_set(err, ZS_ERR_UNSUPPORTED, "mesa: zscan was built without OSMesa");
}

zs_status zs_mesa_unlit(zs_mesa *m, const zs_scene *s, const double view[16],
                        const double proj[16], zs_filter filter, uint32_t *rgb, zs_error *err) {
  (void)m, (void)s, (void)view, (void)proj, (void)filter, (void)rgb;
  return zs_error_set(err, ZS_ERR_UNSUPPORTED, "mesa: zscan was built without OSMesa");
}

zs_status zs_mesa_frame(zs_mesa *m, const zs_scene *s, const double view[16],
                        const double proj[16], zs_error *err) {
  (void)m, (void)s, (void)view, (void)proj;
  return zs_error_set(err, ZS_ERR_UNSUPPORTED, "mesa: zscan was built without OSMesa");
}

#endif
