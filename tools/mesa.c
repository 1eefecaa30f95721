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

#include "lib/frame.h"
#include "raster/raster.h"
#include "raster/surface.h"
#include "util/lights.h"
#include "util/matrix.h"

/* A mesh's faces fanned into triangles: its index array. */
typedef struct fan {
  GLuint *index;
  GLsizei count;
} fan;

/* A mesh's fanned triangles with their corners' attributes, grouped by
 * material (group k: corners first[k] .. first[k + 1] - 1). */
typedef struct shaded {
  GLdouble *pos;
  GLfloat *nrm, *uv;
  GLubyte *col;
  int32_t *first; /* ngroups + 1 */
  int32_t ngroups;
  GLuint *tex;    /* per group, 0: none */
} shaded;

struct zs_mesa {
  OSMesaContext ctx;
  int w, h;
  unsigned char *rgba;
  fan *fans;
  int32_t nfans;
  shaded *shaded;   /* per mesh, for zs_mesa_frame_shaded */
  int32_t nshaded;
  zs_filter shaded_filter;
  GLuint phong;     /* the Blinn-Phong program, 0 until made */
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

static void free_shaded(zs_mesa *m) {
  for (int32_t i = 0; i < m->nshaded; i++) {
    shaded *sh = &m->shaded[i];
    if (sh->tex) glDeleteTextures(sh->ngroups, sh->tex);
    free(sh->pos), free(sh->nrm), free(sh->uv), free(sh->col), free(sh->first), free(sh->tex);
  }
  free(m->shaded);
  m->shaded = NULL;
  m->nshaded = 0;
}

void zs_mesa_destroy(zs_mesa *m) {
  if (!m) return;
  if (m->ctx) {
    OSMesaMakeCurrent(m->ctx, m->rgba, GL_UNSIGNED_BYTE, m->w, m->h);
    free_shaded(m);
  }
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

/* The frame's ids out of GL's colour buffer (its row 0 is the bottom). */
static void read_ids(const zs_mesa *m, uint32_t *ids) {
  glFinish();
  for (int y = 0; y < m->h; y++)
    for (int x = 0; x < m->w; x++) {
      const unsigned char *q = &m->rgba[4 * ((size_t)(m->h - 1 - y) * m->w + x)];
      ids[(size_t)y * m->w + x] = (uint32_t)q[0] << 16 | (uint32_t)q[1] << 8 | q[2];
    }
}

static void colour_id(uint32_t id) { glColor3ub((GLubyte)(id >> 16), (GLubyte)(id >> 8), (GLubyte)id); }

zs_status zs_mesa_prim_ids(zs_mesa *m, const zs_scene *s, const double view[16],
                           const double proj[16], double width, double size, uint32_t *ids,
                           zs_error *err) {
  (void)err;
  begin_frame(m, proj);
  glDisable(GL_LINE_SMOOTH);
  glDisable(GL_POINT_SMOOTH);
  glLineWidth((GLfloat)width);
  glPointSize((GLfloat)size);
  for (int32_t i = 0; i < s->ninst; i++) {
    const zs_instance *in = &s->inst[i];
    load_modelview(view, in->model);
    const zs_mesh *mesh = &s->meshes[in->mesh].mesh;
    const uint32_t first = in->id_base + (uint32_t)mesh->prim_id + 1;
    glBegin(GL_LINES);
    for (int32_t k = 0; k < mesh->nlines; k++) {
      colour_id(first + (uint32_t)k);
      glVertex3dv(&mesh->pos[3 * mesh->line_vert[2 * k]]);
      glVertex3dv(&mesh->pos[3 * mesh->line_vert[2 * k + 1]]);
    }
    glEnd();
    glBegin(GL_POINTS);
    for (int32_t k = 0; k < mesh->npoints; k++) {
      colour_id(first + (uint32_t)(mesh->nlines + k));
      glVertex3dv(&mesh->pos[3 * mesh->point_vert[k]]);
    }
    glEnd();
  }
  read_ids(m, ids);
  return ZS_OK;
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
      colour_id(in->id_base + (uint32_t)(mesh->face_id ? mesh->face_id[f] : f) + 1);
      glBegin(GL_POLYGON);
      for (int32_t k = mesh->face_start[f]; k < mesh->face_start[f + 1]; k++)
        glVertex3dv(&mesh->pos[3 * mesh->face_vert[k]]);
      glEnd();
    }
  }
  read_ids(m, ids);
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
  /* zscan's background, which transparent faces are blended over */
  glClearColor((ZS_BACKGROUND_RGB >> 16 & 255) / 255.0f, (ZS_BACKGROUND_RGB >> 8 & 255) / 255.0f,
               (ZS_BACKGROUND_RGB & 255) / 255.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glShadeModel(GL_SMOOTH);
  /* the opaque faces, then the transparent ones blended over them
   * (SRC_ALPHA, ONE_MINUS_SRC_ALPHA, no depth writes) in the scene's
   * order: zscan's A-buffer is the same where they do not overlap, as in
   * the cross-check's scenes */
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  for (int pass = 0; pass < 2; pass++) {
    if (pass) {
      glEnable(GL_BLEND);
      glDepthMask(GL_FALSE);
    }
    for (int32_t i = 0; i < s->ninst; i++) {
      const zs_instance *in = &s->inst[i];
      load_modelview(view, in->model);
      const zs_mesh *mesh = &s->meshes[in->mesh].mesh;
      for (int32_t f = 0; f < mesh->nfaces; f++) {
        if (zs_face_transparent(mesh, f) != pass) continue;
        const zs_material *mat = zs_face_material(mesh, f);
        const uint32_t base = zs_face_base_rgb(mesh, mat, f, in->rgb);
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
          const int32_t a = zs_corner_attr(mesh, k);
          GLubyte c[4];
          for (int ch = 0; ch < 3; ch++) {
            const uint32_t v = a >= 0 && mesh->color ? mesh->color[4 * (size_t)a + ch] : 255;
            c[ch] = (GLubyte)(((base >> (16 - 8 * ch) & 255) * v + 127) / 255);
          }
          const uint32_t va = a >= 0 && mesh->color ? mesh->color[4 * (size_t)a + 3] : 255;
          c[3] = (GLubyte)(((mat ? mat->base[3] : 255u) * va + 127) / 255);
          glColor4ubv(c);
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
  }
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glFinish();
  for (int y = 0; y < m->h; y++)
    for (int x = 0; x < m->w; x++) {
      const unsigned char *q = &m->rgba[4 * ((size_t)(m->h - 1 - y) * m->w + x)];
      rgb[(size_t)y * m->w + x] = (uint32_t)q[0] << 16 | (uint32_t)q[1] << 8 | q[2];
    }
  return ZS_OK;
}

/* Mesh i's shaded arrays (struct shaded): its faces by material, each
 * fanned from its first corner as zscan shades it. */
static int make_shaded_mesh(const zs_mesh *mesh, zs_filter filter, shaded *sh) {
  const int32_t groups = mesh->nmaterials > 0 ? mesh->nmaterials : 1;
  size_t n = 0;
  for (int32_t f = 0; f < mesh->nfaces; f++) {
    const int32_t k = mesh->face_start[f + 1] - mesh->face_start[f];
    if (k >= 3) n += 3 * (size_t)(k - 2);
  }
  sh->ngroups = groups;
  sh->first = calloc((size_t)groups + 1, sizeof *sh->first);
  sh->tex = calloc((size_t)groups, sizeof *sh->tex);
  sh->pos = malloc((n ? n : 1) * 3 * sizeof *sh->pos);
  sh->nrm = malloc((n ? n : 1) * 3 * sizeof *sh->nrm);
  sh->uv = malloc((n ? n : 1) * 2 * sizeof *sh->uv);
  sh->col = malloc((n ? n : 1) * 4 * sizeof *sh->col);
  if (!sh->first || !sh->tex || !sh->pos || !sh->nrm || !sh->uv || !sh->col) return 0;
  size_t o = 0;
  for (int32_t g = 0; g < groups; g++) {
    sh->first[g] = (int32_t)o;
    for (int32_t f = 0; f < mesh->nfaces; f++) {
      const zs_material *mat = zs_face_material(mesh, f);
      if (mat && mat - mesh->materials != g) continue;
      if (!mat && g != 0) continue;
      /* the mesh's own colours: an instance's colour is not applied here */
      const uint32_t base = zs_face_base_rgb(mesh, mat, f, ZS_RGB_MESH);
      const int32_t s0 = mesh->face_start[f], nv = mesh->face_start[f + 1] - s0;
      /* the face's plane normal, for corners without one */
      double fn[3] = {0, 0, 0};
      for (int i = 0; i < nv; i++)
        zs_newell_add(fn, &mesh->pos[3 * (size_t)mesh->face_vert[s0 + i]],
                      &mesh->pos[3 * (size_t)mesh->face_vert[s0 + (i + 1) % nv]]);
      for (int k = 1; k + 1 < nv; k++) {
        const int32_t corner[3] = {s0, s0 + k, s0 + k + 1};
        for (int c = 0; c < 3; c++, o++) {
          const int32_t v = mesh->face_vert[corner[c]];
          int32_t a = mesh->corner_attr ? mesh->corner_attr[corner[c]] : v;
          if (a >= mesh->nattrs) a = -1;
          memcpy(&sh->pos[3 * o], &mesh->pos[3 * (size_t)v], 3 * sizeof *sh->pos);
          const float *nv3 = a >= 0 && mesh->normal ? &mesh->normal[3 * (size_t)a] : NULL;
          const int has = nv3 && (nv3[0] != 0 || nv3[1] != 0 || nv3[2] != 0);
          for (int q = 0; q < 3; q++) sh->nrm[3 * o + q] = has ? nv3[q] : (GLfloat)fn[q];
          sh->uv[2 * o] = a >= 0 && mesh->uv ? mesh->uv[2 * (size_t)a] : 0.0f;
          sh->uv[2 * o + 1] = a >= 0 && mesh->uv ? mesh->uv[2 * (size_t)a + 1] : 0.0f;
          for (int q = 0; q < 3; q++) {
            const uint32_t vc = a >= 0 && mesh->color ? mesh->color[4 * (size_t)a + q] : 255;
            sh->col[4 * o + q] = (GLubyte)(((base >> (16 - 8 * q) & 255) * vc + 127) / 255);
          }
          sh->col[4 * o + 3] = 255;
        }
      }
    }
    const zs_material *mat = mesh->nmaterials > 0 ? &mesh->materials[g] : NULL;
    if (mat && mat->base_texture && mesh->uv) {
      const zs_filter fl = filter != ZS_FILTER_DEFAULT ? filter
                           : mat->filter != ZS_FILTER_DEFAULT ? mat->filter : ZS_FILTER_TRILINEAR;
      sh->tex[g] = texture_of(mat->base_texture, mat, fl);
    }
  }
  sh->first[groups] = (int32_t)o;
  return 1;
}

static zs_status make_shaded(zs_mesa *m, const zs_scene *s, zs_filter filter, zs_error *err) {
  if (m->nshaded == s->nmeshes && m->shaded_filter == filter) return ZS_OK;
  free_shaded(m);
  if (!(m->shaded = calloc((size_t)(s->nmeshes > 0 ? s->nmeshes : 1), sizeof *m->shaded)))
    return zs_error_set(err, ZS_ERR_NOMEM, "mesa: out of memory");
  m->nshaded = s->nmeshes;
  m->shaded_filter = filter;
  for (int32_t i = 0; i < s->nmeshes; i++)
    if (!make_shaded_mesh(&s->meshes[i].mesh, filter, &m->shaded[i]))
      return zs_error_set(err, ZS_ERR_NOMEM, "mesa: out of memory");
  return ZS_OK;
}

/* Blinn-Phong per fragment over the enabled fixed-function lights (their
 * eye-space positions, colours, attenuation and cones), the colour array
 * as the base, a texture modulating it when bound. */
static const char phong_vs[] =
    "varying vec3 p, n;\n"
    "void main() {\n"
    "  p = vec3(gl_ModelViewMatrix * gl_Vertex);\n"
    "  n = gl_NormalMatrix * gl_Normal;\n"
    "  gl_FrontColor = gl_Color;\n"
    "  gl_TexCoord[0] = gl_MultiTexCoord0;\n"
    "  gl_Position = ftransform();\n"
    "}\n";
static const char phong_fs[] =
    "uniform int lights, textured;\n"
    "uniform sampler2D tex;\n"
    "varying vec3 p, n;\n"
    "void main() {\n"
    "  vec3 v = normalize(-p), nn = normalize(n);\n"
    "  if (dot(nn, v) < 0.0) nn = -nn;\n"
    "  vec3 base = gl_Color.rgb;\n"
    "  if (textured != 0) base *= texture2D(tex, gl_TexCoord[0].st).rgb;\n"
    "  vec3 d = gl_LightModel.ambient.rgb, s = vec3(0.0);\n"
    "  for (int i = 0; i < 8; i++) {\n"
    "    if (i >= lights) break;\n"
    "    vec4 lp = gl_LightSource[i].position;\n"
    "    vec3 l = lp.w == 0.0 ? normalize(lp.xyz) : normalize(lp.xyz - p);\n"
    "    float f = 1.0;\n"
    "    if (lp.w != 0.0) { vec3 t = lp.xyz - p; f = 1.0 / dot(t, t); }\n"
    "    float ndl = dot(nn, l);\n"
    "    if (ndl <= 0.0) continue;\n"
    "    d += gl_LightSource[i].diffuse.rgb * f * ndl;\n"
    "    float ndh = max(dot(nn, normalize(l + v)), 0.0);\n"
    "    s += gl_LightSource[i].specular.rgb * f * pow(ndh, gl_FrontMaterial.shininess);\n"
    "  }\n"
    "  gl_FragColor = vec4(base * d + gl_FrontMaterial.specular.rgb * s, 1.0);\n"
    "}\n";

static GLuint phong_program(void) {
  GLuint prog = glCreateProgram(), vs = glCreateShader(GL_VERTEX_SHADER),
         fs = glCreateShader(GL_FRAGMENT_SHADER);
  const char *v = phong_vs, *f = phong_fs;
  glShaderSource(vs, 1, &v, NULL);
  glShaderSource(fs, 1, &f, NULL);
  glCompileShader(vs);
  glCompileShader(fs);
  glAttachShader(prog, vs);
  glAttachShader(prog, fs);
  glLinkProgram(prog);
  GLint ok = 0;
  glGetProgramiv(prog, GL_LINK_STATUS, &ok);
  return ok ? prog : 0;
}

/* The lights as OpenGL's fixed-function lights: positions in eye space
 * (view, or as given for eye-space lights), point and spot falling off as
 * 1 / d^2, a spot cut off at its outer angle; the ambient lights summed
 * into the light model's ambient.  The number of lights set. */
static int set_gl_lights(const double view[16], const zs_light *lights, int n) {
  GLfloat ambient[4] = {0, 0, 0, 1};
  int k = 0;
  for (int i = 0; i < n && k < 8; i++) {
    const zs_light *l = &lights[i];
    if (l->kind == ZS_LIGHT_AMBIENT) {
      for (int c = 0; c < 3; c++) ambient[c] += (GLfloat)l->color[c];
      continue;
    }
    const GLenum id = GL_LIGHT0 + (GLenum)k++;
    double g[16], ident[16];
    zs_mat_identity(ident);
    const double *mv = l->eye_space ? ident : view;
    for (int r = 0; r < 4; r++)
      for (int c = 0; c < 4; c++) g[4 * c + r] = mv[4 * r + c];
    glLoadMatrixd(g);
    const GLfloat col[4] = {(GLfloat)l->color[0], (GLfloat)l->color[1], (GLfloat)l->color[2], 1};
    const GLfloat none[4] = {0, 0, 0, 1};
    glLightfv(id, GL_DIFFUSE, col);
    glLightfv(id, GL_SPECULAR, col);
    glLightfv(id, GL_AMBIENT, none);
    if (l->kind == ZS_LIGHT_DIRECTIONAL) {
      const GLfloat pos[4] = {(GLfloat)-l->direction[0], (GLfloat)-l->direction[1],
                              (GLfloat)-l->direction[2], 0};
      glLightfv(id, GL_POSITION, pos);
    } else {
      const GLfloat pos[4] = {(GLfloat)l->position[0], (GLfloat)l->position[1],
                              (GLfloat)l->position[2], 1};
      glLightfv(id, GL_POSITION, pos);
      glLightf(id, GL_CONSTANT_ATTENUATION, 0);
      glLightf(id, GL_QUADRATIC_ATTENUATION, 1);
      if (l->kind == ZS_LIGHT_SPOT) {
        const GLfloat dir[3] = {(GLfloat)l->direction[0], (GLfloat)l->direction[1],
                                (GLfloat)l->direction[2]};
        glLightfv(id, GL_SPOT_DIRECTION, dir);
        glLightf(id, GL_SPOT_CUTOFF, (GLfloat)l->outer_deg);
      }
    }
    glEnable(id);
  }
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
  return k;
}

zs_status zs_mesa_frame_shaded(zs_mesa *m, const zs_scene *s, const double view[16],
                               const double proj[16], zs_shade shade, zs_filter filter,
                               const zs_light *lights, int nlights, zs_error *err) {
  if (shade != ZS_SHADE_UNLIT && shade != ZS_SHADE_GOURAUD && shade != ZS_SHADE_PHONG)
    return zs_error_set(err, ZS_ERR_UNSUPPORTED, "mesa: --shade %s has no llvmpipe state here",
                        zs_shade_name(shade));
  begin_frame(m, proj);
  zs_status st = make_shaded(m, s, filter, err);
  if (st) return st;
  glShadeModel(GL_SMOOTH);
  zs_light head[ZS_MAX_LIGHTS];
  if (nlights == 0) nlights = zs_lights_default(head), lights = head;
  const int lit = shade != ZS_SHADE_UNLIT;
  int ngl = 0;
  if (lit) {
    glMatrixMode(GL_MODELVIEW);
    ngl = set_gl_lights(view, lights, nlights);
    glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
    glLightModeli(GL_LIGHT_MODEL_COLOR_CONTROL, GL_SEPARATE_SPECULAR_COLOR);
    glEnable(GL_COLOR_MATERIAL);
    glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
    glEnable(GL_NORMALIZE);
  }
  if (shade == ZS_SHADE_PHONG) {
    if (!m->phong && !(m->phong = phong_program()))
      return zs_error_set(err, ZS_ERR_UNSUPPORTED, "mesa: this OSMesa has no GLSL program");
    glUseProgram(m->phong);
    glUniform1i(glGetUniformLocation(m->phong, "lights"), ngl);
    glUniform1i(glGetUniformLocation(m->phong, "tex"), 0);
  } else if (lit) {
    glEnable(GL_LIGHTING);
  }
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  for (int32_t i = 0; i < s->ninst; i++) {
    const zs_instance *in = &s->inst[i];
    const zs_mesh *mesh = &s->meshes[in->mesh].mesh;
    const shaded *sh = &m->shaded[in->mesh];
    load_modelview(view, in->model);
    glVertexPointer(3, GL_DOUBLE, 0, sh->pos);
    glNormalPointer(GL_FLOAT, 0, sh->nrm);
    glColorPointer(4, GL_UNSIGNED_BYTE, 0, sh->col);
    glTexCoordPointer(2, GL_FLOAT, 0, sh->uv);
    for (int32_t g = 0; g < sh->ngroups; g++) {
      const GLsizei count = sh->first[g + 1] - sh->first[g];
      if (count == 0) continue;
      const zs_material *mat = mesh->nmaterials > 0 ? &mesh->materials[g] : NULL;
      const GLfloat spec[4] = {mat ? mat->specular[0] / 255.0f : 0, mat ? mat->specular[1] / 255.0f : 0,
                               mat ? mat->specular[2] / 255.0f : 0, 1};
      glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, spec);
      glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS,
                  mat ? (mat->shininess > 128 ? 128.0f : (GLfloat)mat->shininess) : 0.0f);
      if (sh->tex[g]) {
        glBindTexture(GL_TEXTURE_2D, sh->tex[g]);
        glEnable(GL_TEXTURE_2D);
      }
      if (m->phong && shade == ZS_SHADE_PHONG)
        glUniform1i(glGetUniformLocation(m->phong, "textured"), sh->tex[g] != 0);
      glDrawArrays(GL_TRIANGLES, sh->first[g], count);
      if (sh->tex[g]) glDisable(GL_TEXTURE_2D);
    }
  }
  glDisableClientState(GL_TEXTURE_COORD_ARRAY);
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
  if (shade == ZS_SHADE_PHONG) glUseProgram(0);
  glDisable(GL_LIGHTING);
  glDisable(GL_COLOR_MATERIAL);
  for (int k = 0; k < 8; k++) glDisable(GL_LIGHT0 + (GLenum)k);
  glFinish();
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

zs_status zs_mesa_prim_ids(zs_mesa *m, const zs_scene *s, const double view[16],
                           const double proj[16], double width, double size, uint32_t *ids,
                           zs_error *err) {
  (void)m, (void)s, (void)view, (void)proj, (void)width, (void)size, (void)ids;
  return zs_error_set(err, ZS_ERR_UNSUPPORTED, "mesa: zscan was built without OSMesa");
}

zs_status zs_mesa_unlit(zs_mesa *m, const zs_scene *s, const double view[16],
                        const double proj[16], zs_filter filter, uint32_t *rgb, zs_error *err) {
  (void)m, (void)s, (void)view, (void)proj, (void)filter, (void)rgb;
  return zs_error_set(err, ZS_ERR_UNSUPPORTED, "mesa: zscan was built without OSMesa");
}

zs_status zs_mesa_frame_shaded(zs_mesa *m, const zs_scene *s, const double view[16],
                               const double proj[16], zs_shade shade, zs_filter filter,
                               const zs_light *lights, int nlights, zs_error *err) {
  (void)m, (void)s, (void)view, (void)proj, (void)shade, (void)filter, (void)lights, (void)nlights;
  return zs_error_set(err, ZS_ERR_UNSUPPORTED, "mesa: zscan was built without OSMesa");
}

zs_status zs_mesa_frame(zs_mesa *m, const zs_scene *s, const double view[16],
                        const double proj[16], zs_error *err) {
  (void)m, (void)s, (void)view, (void)proj;
  return zs_error_set(err, ZS_ERR_UNSUPPORTED, "mesa: zscan was built without OSMesa");
}

#endif
