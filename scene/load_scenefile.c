/* zscan scene — scene files (see load_scenefile.h for the format).
 *
 * The text is parsed whole by cJSON, then walked with a "reader" that
 * knows the JSON path of the value in hand (instances[3].transform.scale)
 * and the name of the file, so every message can say where it points.
 * Every object's keys are checked against what it may hold before its
 * values are read, so a misspelt key is reported as such rather than as
 * a missing one.
 */
#include "scene/load_scenefile.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/matrix.h"
#include "scene/load_assimp.h"
#include "scene/generate.h"
#include "scene/load_common.h"
#include "scene/load_obj.h"
#include "scene/paths.h"
#include "scene/texture_file.h"
#include "util/lights.h"
#include "util/os.h"

enum {
  PATH_MAX_CHARS = 256, /* of a JSON path in messages */
  MAX_FREE_KEYS = 64    /* of a generator mesh's object */
};

/* ---- the reader: file name, JSON path, errors ------------------------- */

/* Messages go through zs_load_error and zs_load_verror: a newline inside
 * a JSON string or key, echoed back, cannot break one into two lines. */

typedef struct reader {
  const char *name; /* the scene file, for messages */
  const char *dir;  /* mesh files are relative to it */
  int flags;        /* ZS_SCENEFILE_* */
  char path[PATH_MAX_CHARS];
  size_t plen;
  zs_error *err;
} reader;

/* "NAME: PATH: " ("NAME: " at the top level): what every message of the
 * value at the path starts with. */
static void where(const reader *r, char *buf, size_t cap) {
  if (r->plen == 0) snprintf(buf, cap, "%s: ", r->name);
  else snprintf(buf, cap, "%s: %s: ", r->name, r->path);
}

/* Sets err to "NAME: PATH: reason" ("NAME: reason" at the top level). */
static zs_status ZS_PRINTF_LIKE(3, 4) fail(reader *r, zs_status code, const char *fmt, ...) {
  char prefix[ZS_ERROR_MSG_MAX];
  where(r, prefix, sizeof prefix);
  va_list ap;
  va_start(ap, fmt);
  zs_status st = zs_load_verror(r->err, code, 0, prefix, fmt, ap);
  va_end(ap);
  return st;
}

/* Appends ".key" (or "key" at the top) to the path; returns the length to
 * go back to with pop(). */
static size_t push_key(reader *r, const char *key) {
  size_t mark = r->plen;
  int n = snprintf(r->path + r->plen, sizeof r->path - r->plen, "%s%s", r->plen ? "." : "", key);
  if (n > 0)
    r->plen += (size_t)n < sizeof r->path - r->plen ? (size_t)n : sizeof r->path - r->plen - 1;
  return mark;
}

static size_t push_index(reader *r, int i) {
  size_t mark = r->plen;
  int n = snprintf(r->path + r->plen, sizeof r->path - r->plen, "[%d]", i);
  if (n > 0)
    r->plen += (size_t)n < sizeof r->path - r->plen ? (size_t)n : sizeof r->path - r->plen - 1;
  return mark;
}

static void pop(reader *r, size_t mark) {
  r->plen = mark;
  r->path[mark] = '\0';
}

/* ---- values ----------------------------------------------------------- */

/* Checks that obj is an object whose keys are all in allowed (NULL-ended;
 * allowed NULL: any key) and none repeated. */
static zs_status check_object(reader *r, const cJSON *obj, const char *const *allowed) {
  if (!cJSON_IsObject(obj)) return fail(r, ZS_ERR_PARSE, "expected object");
  /* With a list, every earlier key is a distinct allowed one, so the
   * search for repeats is short; without one, the count is bounded. */
  if (!allowed && cJSON_GetArraySize(obj) > MAX_FREE_KEYS)
    return fail(r, ZS_ERR_LIMIT, "more than %d keys", MAX_FREE_KEYS);
  for (const cJSON *c = obj->child; c; c = c->next) {
    size_t mark = push_key(r, c->string);
    int known = allowed == NULL;
    for (const char *const *a = allowed; a && *a && !known; a++) known = strcmp(*a, c->string) == 0;
    if (!known) return fail(r, ZS_ERR_PARSE, "unknown key");
    for (const cJSON *d = obj->child; d != c; d = d->next)
      if (strcmp(d->string, c->string) == 0) return fail(r, ZS_ERR_PARSE, "duplicate key");
    pop(r, mark);
  }
  return ZS_OK;
}

static const cJSON *member(const cJSON *obj, const char *key) {
  return cJSON_GetObjectItemCaseSensitive(obj, key);
}

static zs_status read_number(reader *r, const cJSON *v, double *out) {
  if (!cJSON_IsNumber(v)) return fail(r, ZS_ERR_PARSE, "expected number");
  if (!isfinite(v->valuedouble)) return fail(r, ZS_ERR_PARSE, "not a finite number");
  *out = v->valuedouble;
  return ZS_OK;
}

/* A whole number in lo .. hi. */
static zs_status read_int(reader *r, const cJSON *v, double lo, double hi, int32_t *out) {
  double x = 0.0;
  zs_status st = read_number(r, v, &x);
  if (st != ZS_OK) return st;
  if (x != floor(x)) return fail(r, ZS_ERR_PARSE, "expected a whole number, got %g", x);
  if (x < lo || x > hi) return fail(r, ZS_ERR_PARSE, "%.0f is outside %.0f .. %.0f", x, lo, hi);
  *out = (int32_t)x;
  return ZS_OK;
}

/* An array of exactly n finite numbers. */
static zs_status read_numbers(reader *r, const cJSON *v, int n, double *out) {
  if (!cJSON_IsArray(v)) return fail(r, ZS_ERR_PARSE, "expected array of %d numbers", n);
  int size = cJSON_GetArraySize(v);
  if (size != n) return fail(r, ZS_ERR_PARSE, "expected %d numbers, got %d", n, size);
  int i = 0;
  for (const cJSON *c = v->child; c; c = c->next, i++) {
    size_t mark = push_index(r, i);
    zs_status st = read_number(r, c, &out[i]);
    if (st != ZS_OK) return st;
    pop(r, mark);
  }
  return ZS_OK;
}

/* A non-empty string. */
static zs_status read_string(reader *r, const cJSON *v, const char **out) {
  if (!cJSON_IsString(v) || !v->valuestring) return fail(r, ZS_ERR_PARSE, "expected string");
  if (!*v->valuestring) return fail(r, ZS_ERR_PARSE, "expected a non-empty string");
  *out = v->valuestring;
  return ZS_OK;
}

static int is_zero3(const double v[3]) { return v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0; }

/* The member key of obj, NULL when absent (an error, "missing \"key\"",
 * when required). */
static zs_status get_member(reader *r, const cJSON *obj, const char *key, int required,
                            const cJSON **v) {
  *v = member(obj, key);
  if (!*v && required) return fail(r, ZS_ERR_PARSE, "missing \"%s\"", key);
  return ZS_OK;
}

/* The get_ functions read the member key of obj with the path set to it;
 * *given (when not NULL) says whether it was there. */
/* n = 0: one number; else an array of n numbers. */
static zs_status get_numbers(reader *r, const cJSON *obj, const char *key, int required, int n,
                             double *out, int *given) {
  const cJSON *v;
  zs_status st = get_member(r, obj, key, required, &v);
  if (given) *given = v != NULL;
  if (st != ZS_OK || !v) return st;
  size_t mark = push_key(r, key);
  st = n == 0 ? read_number(r, v, out) : read_numbers(r, v, n, out);
  if (st == ZS_OK) pop(r, mark);
  return st;
}

static zs_status get_number(reader *r, const cJSON *obj, const char *key, int required, double *out,
                            int *given) {
  return get_numbers(r, obj, key, required, 0, out, given);
}

static zs_status get_vec3(reader *r, const cJSON *obj, const char *key, int required, double out[3],
                          int *given) {
  return get_numbers(r, obj, key, required, 3, out, given);
}

static zs_status get_int(reader *r, const cJSON *obj, const char *key, int required, double lo,
                         double hi, int32_t *out, int *given) {
  const cJSON *v;
  zs_status st = get_member(r, obj, key, required, &v);
  if (given) *given = v != NULL;
  if (st != ZS_OK || !v) return st;
  size_t mark = push_key(r, key);
  st = read_int(r, v, lo, hi, out);
  if (st == ZS_OK) pop(r, mark);
  return st;
}

static zs_status get_string(reader *r, const cJSON *obj, const char *key, int required,
                            const char **out) {
  const cJSON *v;
  zs_status st = get_member(r, obj, key, required, &v);
  if (st != ZS_OK || !v) return st;
  size_t mark = push_key(r, key);
  st = read_string(r, v, out);
  if (st == ZS_OK) pop(r, mark);
  return st;
}

/* Fails with the path set to member key of the object at the path. */
static zs_status ZS_PRINTF_LIKE(4, 5)
    fail_at(reader *r, const char *key, zs_status code, const char *fmt, ...) {
  char why[ZS_ERROR_MSG_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(why, sizeof why, fmt, ap);
  va_end(ap);
  push_key(r, key);
  return fail(r, code, "%s", why);
}

/* ---- names ------------------------------------------------------------ */

/* A set of names with an index each (open addressing, FNV-1a). */
typedef struct name_table {
  const char **names;
  int32_t *index;
  size_t cap, count;
} name_table;

static uint64_t hash_name(const char *s) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (; *s; s++) h = (h ^ (unsigned char)*s) * 0x100000001b3ull;
  return h;
}

static int table_init(name_table *t, size_t n) {
  t->cap = 16;
  while (t->cap < 2 * n + 2) t->cap *= 2;
  t->count = 0;
  t->names = calloc(t->cap, sizeof *t->names);
  t->index = calloc(t->cap, sizeof *t->index);
  return t->names && t->index;
}

static void table_free(name_table *t) {
  free(t->names);
  free(t->index);
}

/* The slot of name: where it is, or the empty slot where it would go. */
static size_t table_slot(const name_table *t, const char *name) {
  size_t i = (size_t)hash_name(name) & (t->cap - 1);
  while (t->names[i] && strcmp(t->names[i], name) != 0) i = (i + 1) & (t->cap - 1);
  return i;
}

static int32_t table_find(const name_table *t, const char *name) {
  size_t i = table_slot(t, name);
  return t->names[i] ? t->index[i] : -1;
}

/* Adds name (not copied; it must outlive the table) unless present; returns
 * 0 when it was there already.  The table never fills: it was made for at
 * most n names. */
static int table_add(name_table *t, const char *name, int32_t index) {
  size_t i = table_slot(t, name);
  if (t->names[i]) return 0;
  t->names[i] = name;
  t->index[i] = index;
  t->count++;
  return 1;
}

/* ---- files ------------------------------------------------------------ */

/* The size of the file at path, or -1 when it cannot be found out (the
 * loader then says why it cannot open it). */
static long long file_size(const char *path) {
  zs_path_info st;
  return zs_os_stat(path, &st) == 0 && st.kind != ZS_PATH_NONE ? st.size : -1;
}

static int has_obj_extension(const char *path) {
  size_t n = strlen(path);
  if (n < 4) return 0;
  const char *e = path + n - 4;
  return e[0] == '.' && (e[1] | 32) == 'o' && (e[2] | 32) == 'b' && (e[3] | 32) == 'j';
}

/* ---- meshes ----------------------------------------------------------- */

static zs_status load_mesh_file(reader *r, const char *file, zs_model *m) {
  char full[4096];
  const char *dir = r->dir ? r->dir : "";
  int n = file[0] == '/' || !*dir ? snprintf(full, sizeof full, "%s", file)
                                  : snprintf(full, sizeof full, "%s/%s", dir, file);
  if (n < 0 || (size_t)n >= sizeof full) return fail(r, ZS_ERR_LIMIT, "path too long");
  long long size = file_size(full);
  if (size > ZS_SCENEFILE_MAX_BYTES)
    return fail(r, ZS_ERR_LIMIT, "%s: larger than %lld MiB", full, ZS_SCENEFILE_MAX_BYTES >> 20);
  zs_error inner;
  zs_error_clear(&inner);
  const int skip = (r->flags & ZS_SCENEFILE_SKIP_MISSING_TEXTURES) != 0;
  zs_status st =
      has_obj_extension(full)
          ? zs_obj_load_flags(full, skip ? ZS_OBJ_SKIP_MISSING_TEXTURES : 0, m, &inner)
          : zs_assimp_load_flags(full, skip ? ZS_ASSIMP_SKIP_MISSING_TEXTURES : 0, m, &inner);
  if (st != ZS_OK) return fail(r, st, "%s", inner.msg);
  if (!zs_model_drawable(m)) return fail(r, ZS_ERR_PARSE, "%s: no faces, lines or points", full);
  /* the file's notes follow the path, as its errors do */
  char prefix[PATH_MAX_CHARS + 4096];
  where(r, prefix, sizeof prefix);
  zs_notes notes = {NULL, 0, 0};
  if (!zs_notes_move(&notes, &m->notes, prefix)) return fail(r, ZS_ERR_NOMEM, "out of memory");
  m->notes = notes;
  return ZS_OK;
}

/* The shortest decimal text of x that reads back as x, without exponent
 * when one of at most 30 decimals does (generator specs take plain
 * decimals). */
static void format_number(double x, char *buf, size_t cap) {
  if (x == floor(x) && fabs(x) < 9007199254740992.0) {
    snprintf(buf, cap, "%.0f", x);
    return;
  }
  for (int p = 1; p <= 30; p++) {
    snprintf(buf, cap, "%.*f", p, x);
    if (strtod(buf, NULL) == x) return;
  }
  snprintf(buf, cap, "%.17g", x);
}

/* The spec "GENERATOR?key=value&..." of a generator mesh object. */
static zs_status generator_spec(reader *r, const cJSON *obj, const char *gen, char *spec,
                                size_t cap) {
  size_t n = strlen(gen);
  if (n >= cap) return fail_at(r, "generator", ZS_ERR_LIMIT, "generator spec too long");
  memcpy(spec, gen, n + 1);
  char sep = '?';
  for (const cJSON *c = obj->child; c; c = c->next) {
    if (strcmp(c->string, "name") == 0 || strcmp(c->string, "generator") == 0 ||
        strcmp(c->string, "material") == 0)
      continue;
    size_t mark = push_key(r, c->string);
    char value[64];
    if (cJSON_IsNumber(c)) {
      double x = 0.0;
      zs_status st = read_number(r, c, &x);
      if (st != ZS_OK) return st;
      format_number(x, value, sizeof value);
    } else if (cJSON_IsString(c) && c->valuestring) {
      if (strpbrk(c->valuestring, "&=?# \t\r\n") || !*c->valuestring)
        return fail(r, ZS_ERR_PARSE, "expected a word without '&', '=', '?', '#' or blanks");
      if (strlen(c->valuestring) >= sizeof value) return fail(r, ZS_ERR_LIMIT, "value too long");
      snprintf(value, sizeof value, "%s", c->valuestring);
    } else {
      return fail(r, ZS_ERR_PARSE, "expected number or string");
    }
    if (strpbrk(c->string, "&=?# \t\r\n") || !*c->string)
      return fail(r, ZS_ERR_PARSE, "not a generator parameter name");
    int k = snprintf(spec + n, cap - n, "%c%s=%s", sep, c->string, value);
    if (k < 0 || (size_t)k >= cap - n) return fail(r, ZS_ERR_LIMIT, "generator spec too long");
    n += (size_t)k;
    sep = '&';
    pop(r, mark);
  }
  return ZS_OK;
}

static zs_status load_generated_mesh(reader *r, const cJSON *obj, const char *gen, zs_model *m) {
  char spec[ZS_GEN_SPEC_MAX + 1];
  zs_status st = generator_spec(r, obj, gen, spec, sizeof spec);
  if (st != ZS_OK) return st;
  size_t mark = push_key(r, "generator");
  zs_error inner;
  zs_error_clear(&inner);
  st = zs_gen_mesh(spec, m, &inner);
  if (st != ZS_OK) return fail(r, st, "%s", inner.msg);
  pop(r, mark);
  return ZS_OK;
}

/* A boolean member key of obj into *out (left as it is when absent). */
static zs_status get_bool(reader *r, const cJSON *obj, const char *key, int *out) {
  const cJSON *v = member(obj, key);
  if (!v) return ZS_OK;
  if (!cJSON_IsBool(v)) return fail_at(r, key, ZS_ERR_PARSE, "expected true or false");
  *out = cJSON_IsTrue(v);
  return ZS_OK;
}

static zs_status read_color(reader *r, const cJSON *v, uint32_t *rgb);

/* A colour member key of obj into rgb (8-bit sRGB), when given. */
static zs_status get_color(reader *r, const cJSON *obj, const char *key, uint8_t rgb[3]) {
  const cJSON *v = member(obj, key);
  if (!v) return ZS_OK;
  uint32_t x = 0;
  size_t mark = push_key(r, key);
  zs_status st = read_color(r, v, &x);
  if (st != ZS_OK) return st;
  pop(r, mark);
  rgb[0] = (uint8_t)(x >> 16), rgb[1] = (uint8_t)(x >> 8), rgb[2] = (uint8_t)x;
  return ZS_OK;
}

/* The name of a word member key of obj among names (its index in *out,
 * left as it is when absent). */
static zs_status get_word(reader *r, const cJSON *obj, const char *key,
                          const char *const *names, int n, int *out) {
  const char *w = NULL;
  if (!member(obj, key)) return ZS_OK;
  zs_status st = get_string(r, obj, key, 1, &w);
  if (st != ZS_OK) return st;
  for (int i = 0; i < n; i++)
    if (strcmp(w, names[i]) == 0) return *out = i, ZS_OK;
  char list[128] = "";
  for (int i = 0; i < n; i++)
    snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "", names[i]);
  return fail_at(r, key, ZS_ERR_PARSE, "expected one of %s, got \"%.40s\"", list, w);
}

/* A mesh's "material": it replaces the mesh's own on every face.  Colours
 * as instances' (sRGB); its texture is a file beside the scene file, or
 * a note of the model's when it cannot be opened or read and
 * ZS_SCENEFILE_SKIP_MISSING_TEXTURES says to draw without it. */
static zs_status read_material(reader *r, const cJSON *obj, zs_model *m) {
  static const char *const keys[] = {"color",   "alpha",  "specular", "shininess", "emissive",
                                     "texture", "wrap",   "filter",   "double_sided", NULL};
  static const char *const wraps[] = {"repeat", "clamp", "mirror"};
  static const char *const filters[] = {"nearest", "bilinear", "trilinear"};
  if (!cJSON_IsObject(obj)) return fail(r, ZS_ERR_PARSE, "expected object");
  zs_status st = check_object(r, obj, keys);
  zs_material mat = zs_material_default();
  double alpha = 1.0;
  int32_t shininess = 0;
  int wrap = ZS_WRAP_REPEAT, filter = -1, two = 1, given = 0;
  const char *texture = NULL;
  if (st == ZS_OK) st = get_color(r, obj, "color", mat.base);
  if (st == ZS_OK) st = get_color(r, obj, "specular", mat.specular);
  if (st == ZS_OK) st = get_color(r, obj, "emissive", mat.emissive);
  if (st == ZS_OK) st = get_number(r, obj, "alpha", 0, &alpha, &given);
  if (st == ZS_OK && given && !(alpha >= 0.0 && alpha <= 1.0))
    st = fail_at(r, "alpha", ZS_ERR_PARSE, "%g is outside 0 .. 1", alpha);
  if (st == ZS_OK) st = get_int(r, obj, "shininess", 0, 0, ZS_MAX_SHININESS, &shininess, NULL);
  if (st == ZS_OK) st = get_word(r, obj, "wrap", wraps, 3, &wrap);
  if (st == ZS_OK) st = get_word(r, obj, "filter", filters, 3, &filter);
  if (st == ZS_OK) st = get_bool(r, obj, "double_sided", &two);
  if (st == ZS_OK) st = get_string(r, obj, "texture", 0, &texture);
  if (st != ZS_OK) return st;
  mat.base[3] = (uint8_t)lround(alpha * 255.0);
  mat.shininess = (uint16_t)shininess;
  mat.wrap_s = mat.wrap_t = (zs_wrap)wrap;
  mat.filter = filter < 0 ? ZS_FILTER_DEFAULT : (zs_filter)(filter + ZS_FILTER_NEAREST);
  mat.double_sided = (uint8_t)two;
  if (texture) {
    char path[4096];
    const char *dir = r->dir ? r->dir : "";
    int n = texture[0] == '/' || !*dir ? snprintf(path, sizeof path, "%s", texture)
                                       : snprintf(path, sizeof path, "%s/%s", dir, texture);
    if (n < 0 || (size_t)n >= sizeof path)
      return fail_at(r, "texture", ZS_ERR_LIMIT, "path too long");
    zs_texture *tex = NULL;
    zs_error inner;
    zs_error_clear(&inner);
    zs_status tst = zs_texture_load(path, &tex, &inner);
    /* only a file that cannot be opened or read is skipped: a corrupt
     * image is there to be fixed */
    if (tst == ZS_ERR_IO && (r->flags & ZS_SCENEFILE_SKIP_MISSING_TEXTURES)) {
      char prefix[PATH_MAX_CHARS + 4096];
      size_t mark = push_key(r, "texture");
      where(r, prefix, sizeof prefix);
      pop(r, mark);
      if (!zs_notes_add(&m->notes, "%s%s: drawn without it", prefix, inner.msg))
        return fail(r, ZS_ERR_NOMEM, "out of memory");
    } else if (tst != ZS_OK) {
      return fail_at(r, "texture", inner.code, "%s", inner.msg);
    } else if (!zs_model_own_texture(m, tex)) {
      return fail(r, ZS_ERR_NOMEM, "out of memory");
    }
    mat.base_texture = tex;
  }
  /* one material for every face */
  free(m->materials);
  m->materials = NULL;
  m->mesh.nmaterials = m->cap_materials = 0;
  if (zs_model_add_material(m, &mat) < 0) return fail(r, ZS_ERR_NOMEM, "out of memory");
  for (int32_t f = 0; f < m->mesh.nfaces && m->mesh.face_material; f++) m->mesh.face_material[f] = 0;
  /* and its colour the faces' own, which flat shading draws */
  const uint32_t rgb = (uint32_t)mat.base[0] << 16 | (uint32_t)mat.base[1] << 8 | mat.base[2];
  for (int32_t f = 0; f < m->mesh.nfaces && m->mesh.face_rgb; f++) m->mesh.face_rgb[f] = rgb;
  return ZS_OK;
}

static zs_status read_mesh(reader *r, const cJSON *obj, zs_scene *s, name_table *names) {
  if (!cJSON_IsObject(obj)) return fail(r, ZS_ERR_PARSE, "expected object");
  const cJSON *fv = member(obj, "file"), *gv = member(obj, "generator");
  if (fv && gv) return fail_at(r, "generator", ZS_ERR_PARSE, "cannot be combined with \"file\"");
  if (!fv && !gv) return fail(r, ZS_ERR_PARSE, "expected \"file\" or \"generator\"");
  /* a generator's object holds its parameters: any key */
  static const char *const file_keys[] = {"name", "file", "material", NULL};
  zs_status st = check_object(r, obj, gv ? NULL : file_keys);
  const char *name = NULL, *what = NULL;
  if (st == ZS_OK) st = get_string(r, obj, "name", 1, &name);
  if (st == ZS_OK) st = get_string(r, obj, fv ? "file" : "generator", 1, &what);
  if (st != ZS_OK) return st;
  if (table_find(names, name) >= 0)
    return fail_at(r, "name", ZS_ERR_PARSE, "duplicate mesh name '%s'", name);
  zs_model m;
  zs_model_init(&m);
  if (fv) {
    size_t mark = push_key(r, "file");
    st = load_mesh_file(r, what, &m);
    if (st == ZS_OK) pop(r, mark);
  } else {
    st = load_generated_mesh(r, obj, what, &m);
  }
  const cJSON *mv = member(obj, "material");
  if (st == ZS_OK && mv) {
    size_t mark = push_key(r, "material");
    st = read_material(r, mv, &m);
    if (st == ZS_OK) pop(r, mark);
  }
  int32_t index = st == ZS_OK ? zs_scene_add_mesh(s, &m) : -1;
  zs_model_free(&m);
  if (st != ZS_OK) return st;
  if (index < 0) return fail(r, ZS_ERR_NOMEM, "out of memory");
  table_add(names, name, index);
  return ZS_OK;
}

static zs_status read_meshes(reader *r, const cJSON *arr, zs_scene *s, name_table *names) {
  if (!cJSON_IsArray(arr)) return fail(r, ZS_ERR_PARSE, "expected array");
  int n = cJSON_GetArraySize(arr);
  if (n > ZS_SCENEFILE_MAX_MESHES)
    return fail(r, ZS_ERR_LIMIT, "%d meshes, more than %d", n, ZS_SCENEFILE_MAX_MESHES);
  if (!table_init(names, (size_t)n)) return fail(r, ZS_ERR_NOMEM, "out of memory");
  int i = 0;
  for (const cJSON *c = arr->child; c; c = c->next, i++) {
    size_t mark = push_index(r, i);
    zs_status st = read_mesh(r, c, s, names);
    if (st != ZS_OK) return st;
    pop(r, mark);
  }
  return ZS_OK;
}

/* ---- instances -------------------------------------------------------- */

/* One rotation [deg, ax, ay, az], multiplied onto the left of m. */
static zs_status read_rotation(reader *r, const cJSON *v, double m[16]) {
  double q[4];
  zs_status st = read_numbers(r, v, 4, q);
  if (st != ZS_OK) return st;
  if (q[1] == 0.0 && q[2] == 0.0 && q[3] == 0.0)
    return fail(r, ZS_ERR_PARSE, "rotation axis must not be zero");
  double rot[16], t[16];
  zs_mat_rotate(rot, q[0], q[1], q[2], q[3]);
  zs_mat_mul(t, rot, m);
  memcpy(m, t, sizeof t);
  return ZS_OK;
}

/* [deg, ax, ay, az] or a list of them, the first applied first. */
static zs_status read_rotate(reader *r, const cJSON *v, double m[16]) {
  zs_mat_identity(m);
  if (!cJSON_IsArray(v) || !v->child || !cJSON_IsArray(v->child)) return read_rotation(r, v, m);
  int i = 0;
  for (const cJSON *c = v->child; c; c = c->next, i++) {
    size_t mark = push_index(r, i);
    zs_status st = read_rotation(r, c, m);
    if (st != ZS_OK) return st;
    pop(r, mark);
  }
  return ZS_OK;
}

static zs_status read_scale(reader *r, const cJSON *v, double sc[3]) {
  zs_status st;
  if (cJSON_IsNumber(v)) {
    st = read_number(r, v, &sc[0]);
    sc[1] = sc[2] = sc[0];
  } else if (cJSON_IsArray(v)) {
    st = read_numbers(r, v, 3, sc);
  } else {
    return fail(r, ZS_ERR_PARSE, "expected number or array of 3 numbers");
  }
  if (st != ZS_OK) return st;
  if (sc[0] == 0.0 || sc[1] == 0.0 || sc[2] == 0.0)
    return fail(r, ZS_ERR_PARSE, "scale must not be zero");
  return ZS_OK;
}

/* {"translate", "rotate", "scale"} as T * R * S. */
static zs_status read_transform(reader *r, const cJSON *obj, double model[16]) {
  static const char *const keys[] = {"translate", "rotate", "scale", NULL};
  zs_status st = check_object(r, obj, keys);
  double t[3] = {0, 0, 0}, sc[3] = {1, 1, 1}, rot[16];
  zs_mat_identity(rot);
  if (st == ZS_OK) st = get_vec3(r, obj, "translate", 0, t, NULL);
  const cJSON *v;
  if (st == ZS_OK && (v = member(obj, "rotate"))) {
    size_t mark = push_key(r, "rotate");
    st = read_rotate(r, v, rot);
    if (st == ZS_OK) pop(r, mark);
  }
  if (st == ZS_OK && (v = member(obj, "scale"))) {
    size_t mark = push_key(r, "scale");
    st = read_scale(r, v, sc);
    if (st == ZS_OK) pop(r, mark);
  }
  if (st != ZS_OK) return st;
  double tm[16], sm[16], rs[16];
  zs_mat_translate(tm, t[0], t[1], t[2]);
  zs_mat_scale(sm, sc[0], sc[1], sc[2]);
  zs_mat_mul(rs, rot, sm);
  zs_mat_mul(model, tm, rs);
  return ZS_OK;
}

/* 16 numbers, row-major, affine and not singular. */
static zs_status read_matrix(reader *r, const cJSON *v, double m[16]) {
  zs_status st = read_numbers(r, v, 16, m);
  if (st != ZS_OK) return st;
  if (m[12] != 0.0 || m[13] != 0.0 || m[14] != 0.0 || m[15] != 1.0)
    return fail(r, ZS_ERR_PARSE, "the last row must be 0 0 0 1");
  double det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
               m[2] * (m[4] * m[9] - m[5] * m[8]);
  if (det == 0.0 || !isfinite(det)) return fail(r, ZS_ERR_PARSE, "singular matrix");
  return ZS_OK;
}

static int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

/* [r, g, b] each 0 .. 1, or "#rrggbb". */
static zs_status read_color(reader *r, const cJSON *v, uint32_t *rgb) {
  if (cJSON_IsString(v) && v->valuestring) {
    const char *s = v->valuestring;
    uint32_t x = 0;
    int ok = strlen(s) == 7 && s[0] == '#';
    for (int i = 1; ok && i < 7; i++) {
      ok = hex_digit(s[i]) >= 0;
      x = x << 4 | (uint32_t)(ok ? hex_digit(s[i]) : 0);
    }
    if (!ok) return fail(r, ZS_ERR_PARSE, "expected \"#rrggbb\", got \"%.20s\"", s);
    *rgb = x;
    return ZS_OK;
  }
  if (!cJSON_IsArray(v)) return fail(r, ZS_ERR_PARSE, "expected [r, g, b] or \"#rrggbb\"");
  double c[3];
  zs_status st = read_numbers(r, v, 3, c);
  if (st != ZS_OK) return st;
  *rgb = 0;
  for (int i = 0; i < 3; i++) {
    if (c[i] < 0.0 || c[i] > 1.0) {
      push_index(r, i);
      return fail(r, ZS_ERR_PARSE, "%g is outside 0 .. 1", c[i]);
    }
    *rgb = *rgb << 8 | (uint32_t)lround(c[i] * 255.0);
  }
  return ZS_OK;
}

static zs_status read_motion(reader *r, const cJSON *obj, zs_motion *m) {
  static const char *const keys[] = {"axis", "speed", NULL};
  zs_status st = check_object(r, obj, keys);
  if (st == ZS_OK) st = get_vec3(r, obj, "axis", 1, m->axis, NULL);
  if (st == ZS_OK && is_zero3(m->axis)) return fail_at(r, "axis", ZS_ERR_PARSE, "must not be zero");
  if (st == ZS_OK) st = get_number(r, obj, "speed", 1, &m->speed, NULL);
  m->moving = st == ZS_OK && m->speed != 0.0;
  return st;
}

static zs_status read_instance(reader *r, const cJSON *obj, int index, zs_scene *s,
                               const name_table *meshes, name_table *names) {
  static const char *const keys[] = {"mesh",  "name",   "transform", "matrix",
                                     "color", "motion", NULL};
  zs_status st = check_object(r, obj, keys);
  const char *mesh = NULL, *name = NULL;
  if (st == ZS_OK) st = get_string(r, obj, "mesh", 1, &mesh);
  if (st != ZS_OK) return st;
  int32_t mi = table_find(meshes, mesh);
  if (mi < 0) return fail_at(r, "mesh", ZS_ERR_PARSE, "unknown mesh '%s'", mesh);
  st = get_string(r, obj, "name", 0, &name);
  if (st != ZS_OK) return st;

  double model[16];
  zs_mat_identity(model);
  const cJSON *tv = member(obj, "transform"), *mv = member(obj, "matrix"), *v;
  if (tv && mv) return fail_at(r, "matrix", ZS_ERR_PARSE, "cannot be combined with \"transform\"");
  size_t mark = push_key(r, tv ? "transform" : "matrix");
  if (tv) st = read_transform(r, tv, model);
  else if (mv) st = read_matrix(r, mv, model);
  if (st != ZS_OK) return st;
  pop(r, mark);

  uint32_t rgb = ZS_RGB_MESH;
  if ((v = member(obj, "color"))) {
    mark = push_key(r, "color");
    if ((st = read_color(r, v, &rgb)) != ZS_OK) return st;
    pop(r, mark);
  }
  zs_motion motion = {0, {0, 0, 0}, 0.0};
  if ((v = member(obj, "motion"))) {
    mark = push_key(r, "motion");
    if ((st = read_motion(r, v, &motion)) != ZS_OK) return st;
    pop(r, mark);
  }

  char fallback[PATH_MAX_CHARS + 16];
  if (!name) snprintf(fallback, sizeof fallback, "%.*s_%d", PATH_MAX_CHARS, mesh, index);
  int32_t ii = zs_scene_add_instance(s, mi, model, rgb, name ? name : fallback);
  if (ii < 0) return fail(r, ZS_ERR_NOMEM, "out of memory");
  s->inst[ii].motion = motion;
  /* the scene's copy of the name outlives the table */
  if (!table_add(names, s->inst[ii].name, ii)) {
    if (name) return fail_at(r, "name", ZS_ERR_PARSE, "duplicate instance name '%s'", name);
    return fail(r, ZS_ERR_PARSE, "default name '%s' is taken by another instance", fallback);
  }
  return ZS_OK;
}

static zs_status read_instances(reader *r, const cJSON *arr, zs_scene *s,
                                const name_table *meshes) {
  if (!cJSON_IsArray(arr)) return fail(r, ZS_ERR_PARSE, "expected array");
  int n = cJSON_GetArraySize(arr);
  if (n == 0) return fail(r, ZS_ERR_PARSE, "expected at least one instance");
  if (n > ZS_SCENEFILE_MAX_INSTANCES)
    return fail(r, ZS_ERR_LIMIT, "%d instances, more than %d", n, ZS_SCENEFILE_MAX_INSTANCES);
  name_table names;
  zs_status st = table_init(&names, (size_t)n) ? ZS_OK : fail(r, ZS_ERR_NOMEM, "out of memory");
  int i = 0;
  for (const cJSON *c = arr->child; c && st == ZS_OK; c = c->next, i++) {
    size_t mark = push_index(r, i);
    st = read_instance(r, c, i, s, meshes, &names);
    if (st == ZS_OK) pop(r, mark);
  }
  table_free(&names);
  return st;
}

/* ---- camera, bounds, path --------------------------------------------- */

/* Whether up is zero or (nearly) along the view from eye to target, the
 * cases gluLookAt cannot handle. */
static int up_along_view(const double eye[3], const double target[3], const double up[3]) {
  double d[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
  double c[3] = {d[1] * up[2] - d[2] * up[1], d[2] * up[0] - d[0] * up[2],
                 d[0] * up[1] - d[1] * up[0]};
  double cl = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  double ul = sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]);
  return !(cl > 1e-12 * dl * ul);
}

static zs_status read_size(reader *r, const cJSON *v, zs_scene *s) {
  if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != 2)
    return fail(r, ZS_ERR_PARSE, "expected [width, height]");
  int32_t wh[2];
  int i = 0;
  for (const cJSON *c = v->child; c; c = c->next, i++) {
    size_t mark = push_index(r, i);
    zs_status st = read_int(r, c, 1, ZS_MAX_IMAGE_SIDE, &wh[i]);
    if (st != ZS_OK) return st;
    pop(r, mark);
  }
  s->width = wh[0];
  s->height = wh[1];
  return ZS_OK;
}

/* The keys given replace those of s->camera one by one. */
static zs_status read_camera(reader *r, const cJSON *obj, zs_scene *s) {
  static const char *const keys[] = {"eye", "target", "up", "fovy", "near", "far", "size", NULL};
  zs_status st = check_object(r, obj, keys);
  if (st != ZS_OK) return st;
  zs_camera *c = &s->camera;
  int given;
  if ((st = get_vec3(r, obj, "eye", 0, c->eye, &given)) != ZS_OK) return st;
  c->has_eye |= given;
  if ((st = get_vec3(r, obj, "target", 0, c->target, &given)) != ZS_OK) return st;
  c->has_target |= given;
  if ((st = get_vec3(r, obj, "up", 0, c->up, &given)) != ZS_OK) return st;
  c->has_up |= given;
  if (given && is_zero3(c->up)) return fail_at(r, "up", ZS_ERR_PARSE, "must not be zero");
  if ((st = get_number(r, obj, "fovy", 0, &c->fovy, &given)) != ZS_OK) return st;
  if (given && !(c->fovy > 0.0 && c->fovy < 180.0))
    return fail_at(r, "fovy", ZS_ERR_PARSE, "%g: must be between 0 and 180 degrees", c->fovy);
  if ((st = get_number(r, obj, "near", 0, &c->znear, &given)) != ZS_OK) return st;
  c->has_near |= given;
  if (given && !(c->znear > 0.0))
    return fail_at(r, "near", ZS_ERR_PARSE, "%g: must be greater than 0", c->znear);
  if ((st = get_number(r, obj, "far", 0, &c->zfar, &given)) != ZS_OK) return st;
  c->has_far |= given;
  if (given && !(c->zfar > 0.0))
    return fail_at(r, "far", ZS_ERR_PARSE, "%g: must be greater than 0", c->zfar);
  if (c->has_near && c->has_far && !(c->znear < c->zfar))
    return fail_at(r, "far", ZS_ERR_PARSE, "%g: must be greater than near (%g)", c->zfar, c->znear);
  if (c->has_eye && c->has_target && memcmp(c->eye, c->target, sizeof c->eye) == 0)
    return fail_at(r, "target", ZS_ERR_PARSE, "the same point as the eye");
  if (c->has_eye && c->has_target && up_along_view(c->eye, c->target, c->up))
    return fail_at(r, "up", ZS_ERR_PARSE, "parallel to the view direction");
  const cJSON *v = member(obj, "size");
  if (v) {
    size_t mark = push_key(r, "size");
    if ((st = read_size(r, v, s)) != ZS_OK) return st;
    pop(r, mark);
  }
  return ZS_OK;
}

/* One light of "lights" (zscan.h, zs_light): colours linear, times
 * "intensity". */
static zs_status read_light(reader *r, const cJSON *obj, zs_light *l) {
  static const char *const keys[] = {"type",  "color", "intensity", "position", "direction",
                                     "inner", "outer", "eye_space", "shadow", NULL};
  static const char *const kinds[] = {"directional", "point", "spot", "ambient"};
  if (!cJSON_IsObject(obj)) return fail(r, ZS_ERR_PARSE, "expected object");
  zs_status st = check_object(r, obj, keys);
  memset(l, 0, sizeof *l);
  int kind = -1, eye = 0, given = 0;
  double intensity = 1.0;
  l->color[0] = l->color[1] = l->color[2] = 1.0;
  if (st == ZS_OK && !member(obj, "type")) st = fail(r, ZS_ERR_PARSE, "missing \"type\"");
  if (st == ZS_OK) st = get_word(r, obj, "type", kinds, 4, &kind);
  if (st == ZS_OK) st = get_vec3(r, obj, "color", 0, l->color, NULL);
  if (st == ZS_OK) st = get_number(r, obj, "intensity", 0, &intensity, &given);
  if (st == ZS_OK && given && !(intensity >= 0.0))
    st = fail_at(r, "intensity", ZS_ERR_PARSE, "%g: must not be negative", intensity);
  const int placed = kind == ZS_LIGHT_POINT || kind == ZS_LIGHT_SPOT;
  const int aimed = kind == ZS_LIGHT_DIRECTIONAL || kind == ZS_LIGHT_SPOT;
  if (st == ZS_OK) st = get_vec3(r, obj, "position", placed, l->position, NULL);
  if (st == ZS_OK) st = get_vec3(r, obj, "direction", aimed, l->direction, NULL);
  if (st == ZS_OK) st = get_number(r, obj, "inner", kind == ZS_LIGHT_SPOT, &l->inner_deg, NULL);
  if (st == ZS_OK) st = get_number(r, obj, "outer", kind == ZS_LIGHT_SPOT, &l->outer_deg, NULL);
  if (st == ZS_OK) st = get_bool(r, obj, "eye_space", &eye);
  if (st == ZS_OK) st = get_bool(r, obj, "shadow", &l->shadow);
  if (st != ZS_OK) return st;
  l->kind = (zs_light_kind)kind;
  l->eye_space = eye;
  for (int k = 0; k < 3; k++) l->color[k] = l->color[k] * intensity;
  zs_error why;
  zs_error_clear(&why);
  if (zs_lights_check(l, 1, &why) != ZS_OK) {
    /* "lights[0].FIELD: reason", or "lights[0]: reason" for a spot's
     * angles: the message at the key at fault */
    const char *field = strchr(why.msg, '.'), *colon = strchr(why.msg, ':');
    char key[32] = "inner";
    if (field && colon && field < colon && (size_t)(colon - field - 1) < sizeof key) {
      memcpy(key, field + 1, (size_t)(colon - field - 1));
      key[colon - field - 1] = '\0';
    }
    return fail_at(r, key, ZS_ERR_PARSE, "%s", colon + 2);
  }
  return ZS_OK;
}

static zs_status read_lights(reader *r, const cJSON *arr, zs_scene *s) {
  if (!cJSON_IsArray(arr)) return fail(r, ZS_ERR_PARSE, "expected array");
  const int n = cJSON_GetArraySize(arr);
  if (n > ZS_MAX_LIGHTS) return fail(r, ZS_ERR_LIMIT, "%d lights: at most %d", n, ZS_MAX_LIGHTS);
  int i = 0;
  for (const cJSON *c = arr->child; c; c = c->next, i++) {
    size_t mark = push_index(r, i);
    zs_status st = read_light(r, c, &s->lights[i]);
    if (st != ZS_OK) return st;
    pop(r, mark);
  }
  s->nlights = n;
  return ZS_OK;
}

static zs_status read_bounds(reader *r, const cJSON *obj, zs_scene *s) {
  static const char *const keys[] = {"min", "max", NULL};
  double lo[3], hi[3];
  zs_status st = check_object(r, obj, keys);
  if (st == ZS_OK) st = get_vec3(r, obj, "min", 1, lo, NULL);
  if (st == ZS_OK) st = get_vec3(r, obj, "max", 1, hi, NULL);
  if (st != ZS_OK) return st;
  for (int k = 0; k < 3; k++)
    if (lo[k] > hi[k]) return fail_at(r, "max", ZS_ERR_PARSE, "below min on the %c axis", "xyz"[k]);
  memcpy(s->lo, lo, sizeof lo);
  memcpy(s->hi, hi, sizeof hi);
  s->has_bounds = 1;
  return ZS_OK;
}

static zs_status read_key(reader *r, const cJSON *obj, int32_t frames, int32_t prev,
                          const double up[3], zs_keyframe *k) {
  static const char *const keys[] = {"frame", "eye", "target", "up", NULL};
  zs_status st = check_object(r, obj, keys);
  if (st == ZS_OK) st = get_int(r, obj, "frame", 1, 0, frames - 1, &k->frame, NULL);
  if (st != ZS_OK) return st;
  if (k->frame <= prev)
    return fail_at(r, "frame", ZS_ERR_PARSE, "%d is not after the previous key's frame %d",
                   (int)k->frame, (int)prev);
  memcpy(k->up, up, sizeof k->up);
  int given;
  if ((st = get_vec3(r, obj, "eye", 1, k->eye, NULL)) != ZS_OK) return st;
  if ((st = get_vec3(r, obj, "target", 1, k->target, NULL)) != ZS_OK) return st;
  if ((st = get_vec3(r, obj, "up", 0, k->up, &given)) != ZS_OK) return st;
  if (memcmp(k->eye, k->target, sizeof k->eye) == 0)
    return fail_at(r, "target", ZS_ERR_PARSE, "the same point as the eye");
  if (up_along_view(k->eye, k->target, k->up))
    return given ? fail_at(r, "up", ZS_ERR_PARSE, "zero or parallel to the view direction")
                 : fail(r, ZS_ERR_PARSE, "the camera's up is parallel to this key's view");
  return ZS_OK;
}

static zs_status read_keys(reader *r, const cJSON *arr, int32_t frames, zs_scene *s) {
  if (!cJSON_IsArray(arr)) return fail(r, ZS_ERR_PARSE, "expected array");
  int n = cJSON_GetArraySize(arr);
  if (n == 0) return fail(r, ZS_ERR_PARSE, "expected at least one key");
  if (n > frames) return fail(r, ZS_ERR_PARSE, "%d keys for %d frames", n, (int)frames);
  zs_keyframe *keys = malloc((size_t)n * sizeof *keys);
  if (!keys) return fail(r, ZS_ERR_NOMEM, "out of memory");
  zs_status st = ZS_OK;
  int i = 0;
  for (const cJSON *c = arr->child; c && st == ZS_OK; c = c->next, i++) {
    size_t mark = push_index(r, i);
    st = read_key(r, c, frames, i > 0 ? keys[i - 1].frame : -1, s->camera.up, &keys[i]);
    if (st == ZS_OK) pop(r, mark);
  }
  if (st != ZS_OK) {
    free(keys);
    return st;
  }
  zs_path_free(&s->path);
  s->path.keys = keys;
  s->path.nkeys = n;
  s->path.frames = frames;
  return ZS_OK;
}

/* A named path waits for the scene's bounds (see read_scene). */
typedef struct named_path {
  const char *name;
  int32_t frames;
} named_path;

static zs_status read_path(reader *r, const cJSON *obj, zs_scene *s, named_path *named) {
  static const char *const keys[] = {"frames", "keys", "named", NULL};
  int32_t frames;
  zs_status st = check_object(r, obj, keys);
  if (st == ZS_OK) st = get_int(r, obj, "frames", 1, 1, ZS_PATH_MAX_FRAMES, &frames, NULL);
  if (st != ZS_OK) return st;
  const cJSON *kv = member(obj, "keys"), *nv = member(obj, "named");
  if (kv && nv) return fail_at(r, "named", ZS_ERR_PARSE, "cannot be combined with \"keys\"");
  if (!kv && !nv) return fail(r, ZS_ERR_PARSE, "expected \"keys\" or \"named\"");
  if (nv) {
    named->frames = frames;
    return get_string(r, obj, "named", 1, &named->name);
  }
  size_t mark = push_key(r, "keys");
  st = read_keys(r, kv, frames, s);
  if (st == ZS_OK) pop(r, mark);
  return st;
}

/* The named path from the camera completed from the scene's bounds. */
static zs_status make_named_path(reader *r, const named_path *named, zs_scene *s) {
  zs_camera base = s->camera;
  double aspect = s->width > 0 && s->height > 0 ? (double)s->width / s->height : 1.0;
  zs_camera_complete(&base, s->lo, s->hi, aspect);
  zs_path p;
  zs_error inner;
  zs_error_clear(&inner);
  if (zs_path_named(named->name, &base, named->frames, &p, &inner) != ZS_OK) {
    push_key(r, "path");
    return fail_at(r, "named", inner.code, "%s", inner.msg);
  }
  zs_path_free(&s->path);
  s->path = p;
  return ZS_OK;
}

/* ---- the scene -------------------------------------------------------- */

static zs_status read_generated_scene(reader *r, const cJSON *root, zs_scene *s) {
  if (member(root, "meshes") || member(root, "instances"))
    return fail_at(r, "generator", ZS_ERR_PARSE,
                   "cannot be combined with \"meshes\" or \"instances\"");
  const char *spec;
  zs_status st = get_string(r, root, "generator", 1, &spec);
  if (st != ZS_OK) return st;
  zs_error inner;
  zs_error_clear(&inner);
  zs_scene_free(s);
  if (zs_gen_scene(spec, s, &inner) != ZS_OK)
    return fail_at(r, "generator", inner.code, "%s", inner.msg);
  return ZS_OK;
}

static zs_status read_objects(reader *r, const cJSON *root, zs_scene *s) {
  const cJSON *mv = member(root, "meshes"), *iv = member(root, "instances");
  if (!iv) return fail(r, ZS_ERR_PARSE, "missing \"instances\" (or a \"generator\")");
  name_table meshes = {NULL, NULL, 0, 0};
  zs_status st = ZS_OK;
  if (mv) {
    size_t mark = push_key(r, "meshes");
    st = read_meshes(r, mv, s, &meshes);
    if (st == ZS_OK) pop(r, mark);
  } else if (!table_init(&meshes, 0)) {
    st = fail(r, ZS_ERR_NOMEM, "out of memory");
  }
  if (st == ZS_OK) {
    size_t mark = push_key(r, "instances");
    st = read_instances(r, iv, s, &meshes);
    if (st == ZS_OK) pop(r, mark);
  }
  table_free(&meshes);
  return st;
}

/* Reads a member object with fn, the path set to it. */
static zs_status read_part(reader *r, const cJSON *root, const char *key, zs_scene *s,
                           zs_status (*fn)(reader *, const cJSON *, zs_scene *)) {
  const cJSON *v = member(root, key);
  if (!v) return ZS_OK;
  size_t mark = push_key(r, key);
  zs_status st = fn(r, v, s);
  if (st == ZS_OK) pop(r, mark);
  return st;
}

static zs_status read_scene(reader *r, const cJSON *root, zs_scene *s) {
  static const char *const keys[] = {"description", "meshes", "instances", "generator",
                                     "camera",      "path",   "bounds",    "lights", NULL};
  zs_status st = check_object(r, root, keys);
  if (st != ZS_OK) return st;
  const cJSON *dv = member(root, "description");
  if (dv && !cJSON_IsString(dv)) return fail_at(r, "description", ZS_ERR_PARSE, "expected string");
  st = member(root, "generator") ? read_generated_scene(r, root, s) : read_objects(r, root, s);
  if (st == ZS_OK) st = read_part(r, root, "camera", s, read_camera);
  if (st == ZS_OK) st = read_part(r, root, "bounds", s, read_bounds);
  const cJSON *lv = member(root, "lights");
  if (st == ZS_OK && lv) {
    size_t mark = push_key(r, "lights");
    st = read_lights(r, lv, s);
    if (st == ZS_OK) pop(r, mark);
  }
  named_path named = {NULL, 0};
  const cJSON *pv = member(root, "path");
  if (st == ZS_OK && pv) {
    size_t mark = push_key(r, "path");
    st = read_path(r, pv, s, &named);
    if (st == ZS_OK) pop(r, mark);
  }
  if (st != ZS_OK) return st;
  zs_error inner;
  zs_error_clear(&inner);
  if (zs_scene_finish(s, &inner) != ZS_OK) return fail(r, inner.code, "%s", inner.msg);
  return named.name ? make_named_path(r, &named, s) : ZS_OK;
}

/* Line and column (from 1, in bytes) of offset pos in text. */
static void line_col(const char *text, size_t pos, long *line, long *col) {
  *line = 1;
  size_t start = 0;
  for (size_t i = 0; i < pos; i++)
    if (text[i] == '\n') {
      (*line)++;
      start = i + 1;
    }
  *col = (long)(pos - start) + 1;
}

/* What zs_load_parsed hands to parse_scene. */
typedef struct scene_target {
  zs_scene *s;
  int flags;
} scene_target;

/* zs_scenefile_parse, in the form of zs_load_parser. */
static zs_status parse_scene(const char *text, size_t len, const char *name, const char *dir,
                             void *target, zs_error *err) {
  const scene_target *t = target;
  zs_scene *out = t->s;
  zs_scene_init(out);
  if ((unsigned long long)len > (unsigned long long)ZS_SCENEFILE_MAX_BYTES)
    return zs_load_error(err, ZS_ERR_LIMIT, "%s: larger than %lld MiB", name,
                         ZS_SCENEFILE_MAX_BYTES >> 20);
  long line, col;
  const char *nul = memchr(text, '\0', len);
  if (nul) {
    line_col(text, (size_t)(nul - text), &line, &col);
    return zs_load_error(err, ZS_ERR_PARSE, "%s:%ld:%ld: NUL byte", name, line, col);
  }
  char *buf = malloc(len + 1);
  if (!buf) return zs_load_error(err, ZS_ERR_NOMEM, "%s: out of memory", name);
  memcpy(buf, text, len);
  buf[len] = '\0';
  const char *end = NULL;
  cJSON *root = cJSON_ParseWithOpts(buf, &end, 1);
  zs_status st;
  if (!root) {
    size_t pos = end && end >= buf && end <= buf + len ? (size_t)(end - buf) : len;
    line_col(buf, pos, &line, &col);
    st = zs_load_error(err, ZS_ERR_PARSE, "%s:%ld:%ld: invalid JSON", name, line, col);
  } else {
    reader r = {name, dir, t->flags, "", 0, err};
    st = read_scene(&r, root, out);
  }
  cJSON_Delete(root);
  free(buf);
  if (st != ZS_OK) zs_scene_free(out);
  return st;
}

zs_status zs_scenefile_parse(const char *text, size_t len, const char *name, const char *dir,
                             zs_scene *out, zs_error *err) {
  scene_target t = {out, 0};
  return parse_scene(text, len, name, dir, &t, err);
}

zs_status zs_scenefile_load_flags(const char *path, int flags, zs_scene *out, zs_error *err) {
  zs_scene_init(out);
  scene_target t = {out, flags};
  /* mesh files live next to the scene file */
  return zs_load_parsed(path, ZS_SCENEFILE_MAX_BYTES, ZS_LOAD_REGULAR_ONLY, parse_scene, &t, err);
}

zs_status zs_scenefile_load(const char *path, zs_scene *out, zs_error *err) {
  return zs_scenefile_load_flags(path, 0, out, err);
}
