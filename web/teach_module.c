/* zscan web — the engine of the teaching page (web/teach.html), compiled
 * to WebAssembly by emscripten from the same sources as the native build:
 * the page hands over a lesson (polygons on a grid) as JSON, and gets back
 * the trace `zscan trace --format json` prints for the same polygons
 * (tools/trace_walk.c does both), or the lesson's errors, each with the
 * place it belongs to.  Built natively too, for its tests.
 *
 * The lesson:
 *
 *   {"width": 12, "height": 10, "algo": "scanline" | "zbuffer",
 *    "polygons": [{"vertices": [[x, y, z], ...]}, ...]}
 *
 * in the lecture's coordinates: x to the right, y up, (x, y) the centre of
 * pixel column x, row height - 1 - y; z larger is nearer, the background
 * at z = -5.  A vertex may add a fourth number, its intensity I (0 .. 255,
 * the Gouraud shading's); a polygon may give "plane": [a, b, c] and
 * vertices [x, y], for z = a x + b y + c.  The camera is the command's
 *
 *   --ortho -0.5,W-0.5,-0.5,H-0.5 --eye 0,0,0 --target 0,0,-1
 *   --near -10 --far 5 --size WxH
 *
 * so view z is the lecture's z.  The answer:
 *
 *   {"trace": [line, ...], "obj": "the lesson as an OBJ file",
 *    "args": ["--ortho", ...]}
 *   {"errors": [{"path": "polygons[1].vertices[2]", "message": "..."}]}
 */
#include "web/teach_module.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"
#include "tools/trace_walk.h"
#include "tools/viewopts.h"
#include "util/os.h"

#ifdef __EMSCRIPTEN__
#include <emscripten.h>
#define ZS_TEACH_EXPORT EMSCRIPTEN_KEEPALIVE
#else
#define ZS_TEACH_EXPORT
#endif

/* What one lesson may hold: a grid that fits the page beside its tables
 * at 1280 x 800, and polygons a learner can follow by hand. */
enum { MIN_SIDE = 2, MAX_WIDTH = 32, MAX_HEIGHT = 24, MAX_POLYGONS = 8, MAX_CORNERS = 8 };
#define Z_FAR (-5.0) /* the far plane: the background */
#define Z_NEAR 10.0  /* the near plane */

typedef struct corner {
  double x, y, z;
  int I; /* -1: none */
} corner;

typedef struct lesson {
  int width, height, zbuffer;
  int npolys, ncorners[MAX_POLYGONS];
  corner c[MAX_POLYGONS][MAX_CORNERS];
  cJSON *errors; /* [{path, message}] */
} lesson;

static void fail_msg(lesson *l, const char *path, const char *msg) {
  cJSON *e = cJSON_CreateObject();
  cJSON_AddStringToObject(e, "path", path);
  cJSON_AddStringToObject(e, "message", msg);
  cJSON_AddItemToArray(l->errors, e);
}

/* The error at path: fmt with the numbers a and b. */
static void fail(lesson *l, const char *path, const char *fmt, double a, double b) {
  char msg[200];
  snprintf(msg, sizeof msg, fmt, a, b);
  fail_msg(l, path, msg);
}

/* A whole number lo .. hi at key of o, else an error at path. */
static int whole(lesson *l, const cJSON *o, const char *key, int lo, int hi, int *out) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
  if (!cJSON_IsNumber(v) || v->valuedouble != floor(v->valuedouble) || v->valuedouble < lo ||
      v->valuedouble > hi) {
    fail(l, key, "expected a whole number %g to %g", lo, hi);
    return 0;
  }
  *out = (int)v->valuedouble;
  return 1;
}

/* Twice the signed area of the polygon's (x, y). */
static double area2(const corner *c, int n) {
  double a = 0;
  for (int i = 0; i < n; i++) {
    const corner *p = &c[i], *q = &c[(i + 1) % n];
    a += p->x * q->y - q->x * p->y;
  }
  return a;
}

/* Reads and checks vertex j of polygon i (its plane, when given). */
static void read_corner(lesson *l, int i, int j, const cJSON *v, const double *plane) {
  char path[64];
  snprintf(path, sizeof path, "polygons[%d].vertices[%d]", i, j);
  const int n = cJSON_GetArraySize(v), want = plane ? 2 : 3;
  if (!cJSON_IsArray(v) || n < want || n > want + 1) {
    fail(l, path, plane ? "expected [x, y] or [x, y, I] (the plane gives z)"
                        : "expected [x, y, z] or [x, y, z, I]", 0, 0);
    return;
  }
  double a[4];
  for (int k = 0; k < n; k++) {
    const cJSON *e = cJSON_GetArrayItem(v, k);
    if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble)) {
      fail(l, path, "expected numbers", 0, 0);
      return;
    }
    a[k] = e->valuedouble;
  }
  corner *c = &l->c[i][j];
  c->x = a[0];
  c->y = a[1];
  c->z = plane ? plane[0] * a[0] + plane[1] * a[1] + plane[2] : a[2];
  /* (checked below; a double out of int's range must not be converted) */
  c->I = n > want && a[want] >= 0 && a[want] <= 255 ? (int)a[want] : -1;
  if (c->x < 0 || c->x > l->width - 1)
    fail(l, path, "x = %g is off the grid: 0 to %g", c->x, l->width - 1);
  else if (c->y < 0 || c->y > l->height - 1)
    fail(l, path, "y = %g is off the grid: 0 to %g", c->y, l->height - 1);
  else if (!(c->z > Z_FAR && c->z < Z_NEAR))
    fail(l, path, "z = %g: expected above %g (the background) and below 10", c->z, Z_FAR);
  else if (n > want && (a[want] != floor(a[want]) || a[want] < 0 || a[want] > 255))
    fail(l, path, "I = %g: expected a whole number 0 to %g", a[want], 255);
}

static void read_polygon(lesson *l, int i, const cJSON *p) {
  char path[64];
  snprintf(path, sizeof path, "polygons[%d]", i);
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(p, "vertices");
  const cJSON *pl = cJSON_GetObjectItemCaseSensitive(p, "plane");
  double plane[3];
  if (pl) {
    int ok = cJSON_IsArray(pl) && cJSON_GetArraySize(pl) == 3;
    for (int k = 0; ok && k < 3; k++) {
      const cJSON *e = cJSON_GetArrayItem(pl, k);
      ok = cJSON_IsNumber(e) && isfinite(e->valuedouble);
      if (ok) plane[k] = e->valuedouble;
    }
    if (!ok) {
      fail(l, path, "plane: expected [a, b, c], for z = a x + b y + c", 0, 0);
      return;
    }
  }
  const int n = cJSON_GetArraySize(v);
  if (!cJSON_IsArray(v) || n < 3) {
    fail(l, path, "a polygon needs at least 3 vertices", 0, 0);
    return;
  }
  if (n > MAX_CORNERS) {
    fail(l, path, "%g vertices: at most %g", n, MAX_CORNERS);
    return;
  }
  const int before = cJSON_GetArraySize(l->errors);
  for (int j = 0; j < n; j++) read_corner(l, i, j, cJSON_GetArrayItem(v, j), pl ? plane : NULL);
  if (cJSON_GetArraySize(l->errors) > before) return;
  l->ncorners[i] = n;
  for (int j = 0; j < n; j++) {
    const corner *a = &l->c[i][j], *b = &l->c[i][(j + 1) % n];
    if (a->x == b->x && a->y == b->y) {
      snprintf(path, sizeof path, "polygons[%d].vertices[%d]", i, (j + 1) % n);
      fail(l, path, "the same point as vertex %g: a polygon's corners must differ", j, 0);
      return;
    }
  }
  if (area2(l->c[i], n) == 0)
    fail(l, path, "degenerate: its corners are on one line (no area)", 0, 0);
}

static void read_lesson(lesson *l, const char *text) {
  cJSON *root = cJSON_Parse(text);
  if (!cJSON_IsObject(root)) {
    fail(l, "", "the lesson is not a JSON object", 0, 0);
    cJSON_Delete(root);
    return;
  }
  int ok = whole(l, root, "width", MIN_SIDE, MAX_WIDTH, &l->width);
  ok &= whole(l, root, "height", MIN_SIDE, MAX_HEIGHT, &l->height);
  const cJSON *algo = cJSON_GetObjectItemCaseSensitive(root, "algo");
  if (algo && !(cJSON_IsString(algo) && (strcmp(algo->valuestring, "scanline") == 0 ||
                                         strcmp(algo->valuestring, "zbuffer") == 0)))
    fail(l, "algo", "expected \"scanline\" or \"zbuffer\"", 0, 0);
  l->zbuffer = cJSON_IsString(algo) && strcmp(algo->valuestring, "zbuffer") == 0;
  const cJSON *polys = cJSON_GetObjectItemCaseSensitive(root, "polygons");
  const int n = cJSON_GetArraySize(polys);
  if (!cJSON_IsArray(polys) || n < 1)
    fail(l, "polygons", "expected at least one polygon", 0, 0);
  else if (n > MAX_POLYGONS)
    fail(l, "polygons", "%g polygons: at most %g", n, MAX_POLYGONS);
  else if (ok)
    for (int i = 0; i < n; i++) read_polygon(l, i, cJSON_GetArrayItem(polys, i));
  l->npolys = n;
  cJSON_Delete(root);
}

/* The lesson as the OBJ file the command reads: one object a polygon,
 * the intensities as vertex colours (v x y z r g b). */
static char *lesson_obj(const lesson *l) {
  zs_memfile m;
  if (zs_memfile_open(&m) != 0) return NULL;
  FILE *f = m.f;
  fprintf(f, "# a zscan lesson: zscan trace lesson.obj --ortho -0.5,%d.5,-0.5,%d.5 "
             "--eye 0,0,0 --target 0,0,-1 --near -10 --far 5 --size %dx%d%s\n",
          l->width - 1, l->height - 1, l->width, l->height, l->zbuffer ? " --algo zbuffer" : "");
  int first = 1;
  for (int i = 0; i < l->npolys; i++) {
    fprintf(f, "o polygon_%d\n", i);
    for (int j = 0; j < l->ncorners[i]; j++) {
      const corner *c = &l->c[i][j];
      fprintf(f, "v %.17g %.17g %.17g", c->x, c->y, c->z);
      if (c->I >= 0) fprintf(f, " %.17g %.17g %.17g", c->I / 255.0, c->I / 255.0, c->I / 255.0);
      fputc('\n', f);
    }
    fprintf(f, "f");
    for (int j = 0; j < l->ncorners[i]; j++) fprintf(f, " %d", first + j);
    fputc('\n', f);
    first += l->ncorners[i];
  }
  return zs_memfile_close(&m) == 0 ? m.data : NULL;
}

/* The command's view options for the lesson, and the view they give. */
static int lesson_view(const lesson *l, const zs_scene *s, zs_view_opts *view, cJSON *args,
                       zs_error *err) {
  char ortho[64], size[16];
  snprintf(ortho, sizeof ortho, "-0.5,%d.5,-0.5,%d.5", l->width - 1, l->height - 1);
  snprintf(size, sizeof size, "%dx%d", l->width, l->height);
  char *argv[] = {"teach", "--ortho", ortho, "--eye", "0,0,0", "--target", "0,0,-1",
                  "--near", "-10", "--far", "5", "--size", size};
  const int argc = (int)(sizeof argv / sizeof *argv);
  zs_view_opts asked;
  zs_view_opts_default(&asked, 32, 24);
  for (int i = 1; i < argc; i++) {
    const int at = i;
    if (zs_view_opts_parse(&asked, argc, argv, &i, err) != 1) return 0;
    for (int k = at; k <= i; k++) cJSON_AddItemToArray(args, cJSON_CreateString(argv[k]));
  }
  if (l->zbuffer) {
    cJSON_AddItemToArray(args, cJSON_CreateString("--algo"));
    cJSON_AddItemToArray(args, cJSON_CreateString("zbuffer"));
  }
  *view = asked;
  zs_view_opts_for_scene(&asked, s, &view->cam, &view->width, &view->height);
  return 1;
}

/* The lesson's scene: polygon i is object i, with face id 0. */
static zs_status lesson_scene(const lesson *l, zs_scene **out, zs_error *err) {
  if (zs_scene_create(out, err)) return err->code;
  for (int i = 0; i < l->npolys; i++) {
    const int n = l->ncorners[i];
    double pos[3 * MAX_CORNERS];
    int32_t start[2] = {0, n}, vert[MAX_CORNERS];
    uint8_t rgba[4 * MAX_CORNERS];
    int shaded = 0;
    for (int j = 0; j < n; j++) {
      pos[3 * j] = l->c[i][j].x;
      pos[3 * j + 1] = l->c[i][j].y;
      pos[3 * j + 2] = l->c[i][j].z;
      vert[j] = j;
      const int I = l->c[i][j].I;
      shaded |= I >= 0;
      rgba[4 * j] = rgba[4 * j + 1] = rgba[4 * j + 2] = (uint8_t)(I >= 0 ? I : 255);
      rgba[4 * j + 3] = 255;
    }
    zs_mesh m;
    memset(&m, 0, sizeof m);
    m.pos = pos;
    m.nverts = n;
    m.face_start = start;
    m.face_vert = vert;
    m.nfaces = 1;
    if (shaded) {
      m.nattrs = n;
      m.color = rgba;
    }
    char name[32];
    snprintf(name, sizeof name, "polygon_%d", i);
    if (zs_scene_add_object(*out, &m, NULL, name, err)) return err->code;
  }
  return ZS_OK;
}

/* The trace of the lesson, as the JSON array the page reads. */
static char *lesson_trace(const lesson *l, cJSON *args, zs_error *err) {
  zs_scene *s = NULL;
  zs_memfile m = {NULL, NULL, 0};
  zs_trace_opts o;
  memset(&o, 0, sizeof o);
  o.row1 = ZS_MAX_IMAGE_SIDE;
  o.json = 1;
  o.as_array = 1;
  o.zbuffer = l->zbuffer;
  zs_tracer t;
  memset(&t, 0, sizeof t);
  if (lesson_scene(l, &s, err) || !lesson_view(l, s, &o.view, args, err)) goto done;
  if (zs_memfile_open(&m) != 0) {
    zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
    goto done;
  }
  fputc('[', m.f);
  if (zs_trace_walk(&t, &o, s, m.f, err)) goto done;
  fputc(']', m.f);
  if (zs_memfile_close(&m) != 0) zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
done:
  if (m.f) fclose(m.f);
  zs_tracer_free(&t);
  zs_scene_destroy(s);
  if (err->code) {
    free(m.data);
    return NULL;
  }
  return m.data;
}

ZS_TEACH_EXPORT char *zs_teach_run(const char *lesson_json) {
  lesson l;
  memset(&l, 0, sizeof l);
  l.errors = cJSON_CreateArray();
  cJSON *answer = cJSON_CreateObject();
  read_lesson(&l, lesson_json ? lesson_json : "");
  if (cJSON_GetArraySize(l.errors) == 0) {
    zs_error err;
    zs_error_clear(&err);
    cJSON *args = cJSON_CreateArray();
    char *trace = lesson_trace(&l, args, &err), *obj = lesson_obj(&l);
    if (trace && obj) {
      cJSON_AddItemToObject(answer, "trace", cJSON_CreateRaw(trace));
      cJSON_AddStringToObject(answer, "obj", obj);
      cJSON_AddItemToObject(answer, "args", args);
      args = NULL;
    } else {
      fail_msg(&l, "", err.code ? err.msg : "out of memory");
    }
    cJSON_Delete(args);
    free(trace);
    free(obj);
  }
  if (cJSON_GetArraySize(l.errors)) cJSON_AddItemToObject(answer, "errors", l.errors);
  else cJSON_Delete(l.errors);
  char *s = cJSON_PrintUnformatted(answer);
  cJSON_Delete(answer);
  return s;
}

ZS_TEACH_EXPORT void zs_teach_free(char *answer) { free(answer); }
