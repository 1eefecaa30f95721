/* zscan scene — the Wavefront OBJ reader (see load_obj.h for what is read).
 *
 * The text is read line by line: each line is checked (length, NUL bytes),
 * copied into a NUL-terminated buffer with its comment cut off, and split
 * into words in place.  Numbers go through strtod, which follows the
 * LC_NUMERIC locale; zscan never calls setlocale, so that is "C" and the
 * decimal point is '.'.
 *
 * Materials are resolved at the end: while reading, a face's rgb holds
 * the number of its usemtl name (0: none) and its material is a grey
 * placeholder, one per name; once every library is loaded those numbers
 * become the materials' colours, the placeholders the materials, and
 * their textures are read.
 *
 * Attribute vertices are made as the faces name them: one for each
 * distinct (vt, vn, coloured vertex) that a corner uses, found again in a
 * hash table of those index triples (the numbering follows the order of
 * first use, whatever the table's layout).  A corner that names none of
 * them has none (-1), so a file without vt, vn or colours makes no
 * attribute arrays and draws as it always did.
 */
#include "scene/load_obj.h"
#include "util/compiler.h"
#include "util/grow.h"
#include "scene/load_common.h"
#include "scene/text.h"
#include "scene/texture_file.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


/* ---- lines and words -------------------------------------------------- */

typedef struct line_reader {
  const char *text; /* the whole file, len bytes, not NUL-terminated */
  size_t len, pos;
  const char *name; /* the file's name for messages */
  long line;        /* 1-based number of the line in buf */
  char *buf;        /* ZS_OBJ_LINE_MAX + 1 bytes: the line, NUL-terminated */
  char *cur;        /* where the next word starts */
  int control;      /* the line holds a control byte other than white space */
  zs_error *err;
} line_reader;

/* Sets err to "NAME:LINE: reason" and returns code. */
static zs_status ZS_PRINTF_LIKE(3, 4)
    line_error(const line_reader *r, zs_status code, const char *fmt, ...) {
  char why[ZS_ERROR_MSG_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(why, sizeof why, fmt, ap);
  va_end(ap);
  return zs_error_set(r->err, code, "%s:%ld: %s", r->name, r->line, why);
}

static zs_status reader_init(line_reader *r, const char *text, size_t len,
                             const char *name, zs_error *err) {
  *r = (line_reader){.text = text, .len = len, .name = name, .err = err};
  r->buf = malloc(ZS_OBJ_LINE_MAX + 1);
  if (!r->buf) return zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", name);
  return ZS_OK;
}

static int is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* Loads the next line into r->buf; *have is 0 at the end of the text. */
static zs_status next_line(line_reader *r, int *have) {
  *have = 0;
  if (r->pos >= r->len) return ZS_OK;
  const char *s = r->text + r->pos;
  size_t rest = r->len - r->pos;
  r->line++;
  /* Look for the newline no further than the longest line allowed (plus
   * "\r\n"), so that a huge text without newlines is refused at once. */
  size_t window = rest < ZS_OBJ_LINE_MAX + 2 ? rest : ZS_OBJ_LINE_MAX + 2;
  const char *nl = memchr(s, '\n', window);
  size_t n = nl ? (size_t)(nl - s) : window;
  r->pos += nl ? n + 1 : n;
  if (n > 0 && s[n - 1] == '\r') n--;
  if (n > ZS_OBJ_LINE_MAX)
    return line_error(r, ZS_ERR_LIMIT, "line longer than %d bytes",
                      ZS_OBJ_LINE_MAX);
  if (memchr(s, '\0', n)) return line_error(r, ZS_ERR_PARSE, "NUL byte");
  r->control = 0;
  for (size_t i = 0; i < n; i++) {
    unsigned char c = (unsigned char)s[i];
    r->control |= (c < 0x20 && !is_space((char)c)) || c == 0x7f;
  }
  memcpy(r->buf, s, n);
  r->buf[n] = '\0';
  /* A '#' that starts a word starts a comment. */
  for (size_t i = 0; i < n; i++) {
    if (r->buf[i] == '#' && (i == 0 || is_space(r->buf[i - 1]))) {
      r->buf[i] = '\0';
      break;
    }
  }
  r->cur = r->buf;
  *have = 1;
  return ZS_OK;
}

/* The next whitespace-separated word of the line, NUL-terminated in
 * place, or NULL at the end of the line. */
static char *next_word(line_reader *r) {
  char *s = r->cur;
  while (is_space(*s)) s++;
  if (*s == '\0') {
    r->cur = s;
    return NULL;
  }
  char *word = s;
  while (*s != '\0' && !is_space(*s)) s++;
  if (*s != '\0') *s++ = '\0';
  r->cur = s;
  return word;
}

/* Puts back the word w that next_word just returned, so that the next
 * call (or rest_of_line) reads it again. */
static void unread_word(line_reader *r, char *w) {
  size_t n = strlen(w);
  if (r->cur > w + n) w[n] = ' '; /* the separator next_word cut */
  r->cur = w;
}

/* The rest of the line without surrounding blanks, or NULL when empty. */
static char *rest_of_line(line_reader *r) {
  char *s = r->cur;
  while (is_space(*s)) s++;
  char *end = s + strlen(s);
  while (end > s && is_space(end[-1])) end--;
  *end = '\0';
  r->cur = end;
  return *s != '\0' ? s : NULL;
}

/* ---- numbers ---------------------------------------------------------- */

static int is_digit(char c) { return c >= '0' && c <= '9'; }

/* Parses the word w (NULL: the line ended) as a finite number. */
static zs_status parse_number(line_reader *r, const char *w, double *out) {
  if (!w) return line_error(r, ZS_ERR_PARSE, "expected a number");
  char *end;
  double x = strtod(w, &end);
  if (end == w || *end != '\0')
    return line_error(r, ZS_ERR_PARSE, "expected a number, got '%.40s'", w);
  if (!isfinite(x))
    return line_error(r, ZS_ERR_PARSE, "not a finite number: '%.40s'", w);
  if (!zs_text_is_decimal(w))
    return line_error(r, ZS_ERR_PARSE, "expected a number, got '%.40s'", w);
  *out = x;
  return ZS_OK;
}

/* Reads an integer [+-]digits at *s, advancing *s past it; returns 0 (and
 * leaves *s) when there is none.  The value saturates far beyond any index
 * an int32_t mesh can hold. */
static int scan_index(const char **s, long long *out) {
  const char *p = *s;
  int neg = *p == '-';
  if (*p == '+' || *p == '-') p++;
  if (!is_digit(*p)) return 0;
  long long v = 0;
  for (; is_digit(*p); p++)
    if (v < 1000000000000LL) v = v * 10 + (*p - '0');
  *out = neg ? -v : v;
  *s = p;
  return 1;
}

/* ---- names ------------------------------------------------------------ */

/* The names given to usemtl, in the order of their first use: name i is
 * material i of the model. */
typedef struct name_list {
  char **names;
  size_t n;
  int32_t cap;
} name_list;

static void names_free(name_list *l) {
  for (size_t i = 0; i < l->n; i++) free(l->names[i]);
  free(l->names);
  *l = (name_list){.n = 0};
}

static long names_find(const name_list *l, const char *name) {
  for (size_t i = 0; i < l->n; i++)
    if (strcmp(l->names[i], name) == 0) return (long)i;
  return -1;
}

/* Appends name; returns its index, -1 when out of memory. */
static long names_add(name_list *l, const char *name) {
  if (!zs_grow((void **)&l->names, &l->cap, (int64_t)l->n + 1, sizeof *l->names)) return -1;
  char *copy = strdup(name);
  if (!copy) return -1;
  l->names[l->n] = copy;
  return (long)l->n++;
}

/* "dir/file" (file alone when it is absolute or dir is empty), malloc'd. */
static char *join_path(const char *dir, const char *file) {
  size_t dlen = file[0] == '/' ? 0 : strlen(dir);
  int slash = dlen > 0 && dir[dlen - 1] != '/';
  size_t flen = strlen(file);
  char *path = malloc(dlen + (size_t)slash + flen + 1);
  if (!path) return NULL;
  memcpy(path, dir, dlen);
  if (slash) path[dlen] = '/';
  memcpy(path + dlen + slash, file, flen + 1);
  return path;
}

/* ---- material libraries ----------------------------------------------- */

/* A material of a library, as its newmtl block says it. */
typedef struct mtl_def {
  char *name;
  uint32_t rgb;      /* Kd as 0xRRGGBB: the face colour (ZS_GREY without Kd) */
  zs_material mat;   /* the rest (base[0..2] follow rgb at the end) */
  int has_d;         /* d given: Tr no longer counts */
  char *map;         /* map_Kd's file as written; NULL: none */
  char *map_path;    /* the same relative to the .mtl's folder */
  char *map_where;   /* "FILE.mtl:LINE" of the map_Kd, for messages */
} mtl_def;

typedef struct mtl_list {
  mtl_def *d;
  size_t n;
  int32_t cap;
} mtl_list;

static void mtl_def_free(mtl_def *d) {
  free(d->name);
  free(d->map);
  free(d->map_path);
  free(d->map_where);
}

static void mtl_free(mtl_list *l) {
  for (size_t i = 0; i < l->n; i++) mtl_def_free(&l->d[i]);
  free(l->d);
  *l = (mtl_list){.n = 0};
}

/* The last material named name (a later library overrides), or NULL. */
static const mtl_def *mtl_find(const mtl_list *l, const char *name) {
  for (size_t i = l->n; i > 0; i--)
    if (strcmp(l->d[i - 1].name, name) == 0) return &l->d[i - 1];
  return NULL;
}

/* A new material named name, grey until its statements say otherwise. */
static mtl_def *mtl_add(mtl_list *l, const char *name) {
  if (!zs_grow((void **)&l->d, &l->cap, (int64_t)l->n + 1, sizeof *l->d)) return NULL;
  mtl_def *d = &l->d[l->n];
  *d = (mtl_def){.rgb = ZS_GREY, .mat = zs_material_default()};
  if (!(d->name = strdup(name))) return NULL;
  l->n++;
  return d;
}

static uint8_t channel(double x) {
  if (x < 0.0) x = 0.0;
  if (x > 1.0) x = 1.0;
  return (uint8_t)lround(x * 255.0);
}

/* KW r [g b] (Kd, Ks, Ke): one number stands for all three; the spectral
 * and xyz forms leave the colour as it is (*set 0). */
static zs_status parse_rgb(line_reader *r, const char *kw, double c[3], int *set) {
  *set = 0;
  char *w = next_word(r);
  if (w && (strcmp(w, "spectral") == 0 || strcmp(w, "xyz") == 0)) return ZS_OK;
  zs_status st = parse_number(r, w, &c[0]);
  if (st != ZS_OK) return st;
  c[1] = c[2] = c[0];
  if ((w = next_word(r)) != NULL) {
    for (int i = 1; i < 3; i++) {
      if (i == 2 && !(w = next_word(r))) break;
      st = parse_number(r, w, &c[i]);
      if (st != ZS_OK) return st;
    }
    if (!w || next_word(r)) return line_error(r, ZS_ERR_PARSE, "%s takes 1 or 3 numbers", kw);
  }
  *set = 1;
  return ZS_OK;
}

/* KW x: exactly one number. */
static zs_status parse_single(line_reader *r, const char *kw, double *x) {
  zs_status st = parse_number(r, next_word(r), x);
  if (st == ZS_OK && next_word(r)) return line_error(r, ZS_ERR_PARSE, "%s takes 1 number", kw);
  return st;
}

static zs_status parse_colour_of(line_reader *r, const char *kw, mtl_def *d) {
  double c[3];
  int set;
  zs_status st = parse_rgb(r, kw, c, &set);
  if (st != ZS_OK || !set) return st;
  uint8_t *to = kw[1] == 's' ? d->mat.specular : d->mat.emissive;
  if (kw[1] == 'd')
    d->rgb = (uint32_t)channel(c[0]) << 16 | (uint32_t)channel(c[1]) << 8 | channel(c[2]);
  else
    for (int i = 0; i < 3; i++) to[i] = channel(c[i]);
  return ZS_OK;
}

/* The options of a texture map statement (the MTL specification's list)
 * and how many values each takes: the first `min` whatever they are, up
 * to `max` while they are numbers. */
static const struct map_option {
  const char *name;
  int min, max;
} map_options[] = {{"-blendu", 1, 1}, {"-blendv", 1, 1}, {"-boost", 1, 1}, {"-bm", 1, 1},
                   {"-cc", 1, 1},     {"-clamp", 1, 1},  {"-imfchan", 1, 1}, {"-mm", 1, 2},
                   {"-o", 1, 3},      {"-s", 1, 3},      {"-t", 1, 3},       {"-texres", 1, 1},
                   {"-type", 1, 1}};

static const struct map_option *find_map_option(const char *w) {
  for (size_t i = 0; i < sizeof map_options / sizeof map_options[0]; i++)
    if (strcmp(w, map_options[i].name) == 0) return &map_options[i];
  return NULL;
}

/* Reads option o's values; -clamp on clamps the texture at its edges,
 * every other option is read and ignored. */
static zs_status parse_map_option(line_reader *r, const struct map_option *o, mtl_def *d) {
  for (int i = 0; i < o->max; i++) {
    char *w = next_word(r);
    if (i >= o->min && (!w || !zs_text_is_decimal(w))) {
      if (w) unread_word(r, w); /* not a value: the next option or the file */
      break;
    }
    if (!w) return line_error(r, ZS_ERR_PARSE, "map_Kd: option %s needs a value", o->name);
    if (strcmp(o->name, "-clamp") == 0) {
      if (strcmp(w, "on") != 0 && strcmp(w, "off") != 0)
        return line_error(r, ZS_ERR_PARSE, "map_Kd: -clamp takes on or off, got '%.40s'", w);
      d->mat.wrap_s = d->mat.wrap_t = w[1] == 'n' ? ZS_WRAP_CLAMP : ZS_WRAP_REPEAT;
    }
  }
  return ZS_OK;
}

/* map_Kd [options] FILE: the file is the rest of the line (it may hold
 * spaces), relative to dir, the .mtl file's folder. */
static zs_status parse_map(line_reader *r, const char *dir, mtl_def *d) {
  for (;;) {
    char *w = next_word(r);
    if (!w || w[0] != '-') {
      if (w) unread_word(r, w);
      break;
    }
    const struct map_option *o = find_map_option(w);
    if (!o) return line_error(r, ZS_ERR_PARSE, "map_Kd: unknown option '%.40s'", w);
    zs_status st = parse_map_option(r, o, d);
    if (st != ZS_OK) return st;
  }
  char *file = rest_of_line(r);
  if (!file) return line_error(r, ZS_ERR_PARSE, "map_Kd: expected a file name");
  free(d->map);
  free(d->map_path);
  free(d->map_where);
  d->map = strdup(file);
  /* Windows exporters write "textures\wood.jpg"; a backslash in a file
   * name is rarer than that. */
  for (char *c = file; *c; c++)
    if (*c == '\\') *c = '/';
  d->map_path = join_path(dir, file);
  size_t wlen = strlen(r->name) + 24;
  if ((d->map_where = malloc(wlen)) != NULL)
    snprintf(d->map_where, wlen, "%s:%ld", r->name, r->line);
  if (!d->map || !d->map_path || !d->map_where)
    return line_error(r, ZS_ERR_NOMEM, "out of memory");
  return ZS_OK;
}

/* One statement of a library about material d (NULL before newmtl). */
static zs_status parse_mtl_statement(line_reader *r, const char *kw, const char *dir,
                                     mtl_def *d) {
  static const char *const known[] = {"Kd", "Ks", "Ke", "Ns", "d", "Tr", "map_Kd"};
  size_t i = 0;
  while (i < sizeof known / sizeof known[0] && strcmp(kw, known[i]) != 0) i++;
  if (i == sizeof known / sizeof known[0]) return ZS_OK; /* Ka, illum, Ni, other maps: unused */
  if (!d) return line_error(r, ZS_ERR_PARSE, "%s before newmtl", kw);
  if (i < 3) return parse_colour_of(r, kw, d);
  if (i == 6) return parse_map(r, dir, d);
  double x;
  char *w;
  /* d -halo x: the halo (alpha from the viewing angle) is not drawn */
  if (i == 4 && (w = next_word(r)) != NULL && strcmp(w, "-halo") != 0) unread_word(r, w);
  zs_status st = parse_single(r, kw, &x);
  if (st != ZS_OK) return st;
  if (i == 3) {
    double ns = x < 0.0 ? 0.0 : x > ZS_MAX_SHININESS ? ZS_MAX_SHININESS : x;
    d->mat.shininess = (uint16_t)lround(ns);
  } else if (i == 4) {
    d->mat.base[3] = channel(x);
    d->has_d = 1;
  } else if (!d->has_d) { /* Tr, transparency, where no d says the opacity */
    d->mat.base[3] = channel(1.0 - x);
  }
  return ZS_OK;
}

/* Adds the materials of the .mtl text (the file name, as read) to mtl. */
static zs_status parse_mtl(const char *text, size_t len, const char *name, mtl_list *mtl,
                           zs_error *err) {
  line_reader r;
  zs_status st = reader_init(&r, text, len, name, err);
  char *dir = st == ZS_OK ? zs_load_dir(name) : NULL;
  if (st == ZS_OK && !dir) st = line_error(&r, ZS_ERR_NOMEM, "out of memory");
  long current = -1; /* the material being defined */
  int have;
  while (st == ZS_OK && (st = next_line(&r, &have)) == ZS_OK && have) {
    char *kw = next_word(&r);
    if (!kw) continue;
    if (strcmp(kw, "newmtl") == 0) {
      char *mat = rest_of_line(&r);
      if (!mat) st = line_error(&r, ZS_ERR_PARSE, "expected a material name");
      else if (!mtl_add(mtl, mat)) st = line_error(&r, ZS_ERR_NOMEM, "out of memory");
      else current = (long)mtl->n - 1;
    } else {
      st = parse_mtl_statement(&r, kw, dir, current >= 0 ? &mtl->d[current] : NULL);
    }
  }
  free(dir);
  free(r.buf);
  return st;
}

/* ---- the OBJ file ----------------------------------------------------- */

/* A key of the attribute vertices: the vt, the vn and the coloured vertex
 * (each -1 for none) that a corner names; attr -1 marks an empty slot. */
typedef struct attr_slot {
  int32_t vt, vn, col, attr;
} attr_slot;

/* A texture read for a material, by its path (tex NULL: skipped). */
typedef struct loaded_texture {
  char *path;
  const zs_texture *tex;
} loaded_texture;

typedef struct obj_parser {
  line_reader r;
  long statements;  /* lines that are OBJ statements */
  long strangers;   /* lines that are not: the file may not be an OBJ */
  long first_stranger; /* the line of the first, for the message */
  zs_model *m;
  const char *dir; /* for mtllib; NULL: libraries are skipped */
  int flags;       /* ZS_OBJ_* */
  int32_t obj;     /* the object of the following faces, -1: none */
  uint32_t slot;   /* usemtl of the following faces: 0 none, else used[slot-1] */
  mtl_list mtl;    /* materials defined by the libraries */
  name_list used;  /* material names given to usemtl: the model's materials */
  int32_t *idx, *attr; /* the corners of the face being read */
  int32_t cap_idx, cap_attr;
  float *vn, *vt;  /* normals (3 floats) and texture coordinates (2) */
  int32_t nvn, nvt, cap_vn, cap_vt;
  uint32_t *vcol;  /* per vertex 0xFFRRGGBB, 0 for none; NULL: no colours yet */
  int32_t cap_vcol;
  attr_slot *slots; /* open addressing, cap_slots a power of two */
  int32_t nslots, cap_slots;
  loaded_texture *tex;
  int32_t ntex, cap_tex;
} obj_parser;

static zs_status out_of_memory(obj_parser *p) {
  return line_error(&p->r, ZS_ERR_NOMEM, "out of memory");
}

/* The colour of the vertex just added: vertex colours as MeshLab, Open3D
 * and others write them, 0 .. 1 a channel (values beyond clamped); the
 * array is made at the first coloured vertex, 0 (none) for the earlier. */
static int set_vertex_colour(obj_parser *p, const double *rgb) {
  int32_t v = p->m->mesh.nverts - 1;
  if (!rgb && !p->vcol) return 1;
  const int fresh = p->vcol == NULL;
  if (!zs_grow((void **)&p->vcol, &p->cap_vcol, (int64_t)v + 1, sizeof *p->vcol)) return 0;
  if (fresh) memset(p->vcol, 0, (size_t)v * sizeof *p->vcol);
  p->vcol[v] = rgb ? 0xFF000000u | (uint32_t)channel(rgb[0]) << 16 |
                         (uint32_t)channel(rgb[1]) << 8 | channel(rgb[2])
                   : 0;
  return 1;
}

static zs_status parse_vertex(obj_parser *p) {
  /* x y z, x y z w, or x y z r g b (vertex colours) */
  double c[7];
  int n = 0;
  for (char *w; (w = next_word(&p->r)) != NULL; n++) {
    if (n == 7) break;
    zs_status st = parse_number(&p->r, w, &c[n]);
    if (st != ZS_OK) return st;
  }
  if (n != 3 && n != 4 && n != 6)
    return line_error(&p->r, ZS_ERR_PARSE,
                      "expected x y z [w] (or x y z r g b), got %s%d numbers",
                      n == 7 ? "more than " : "", n == 7 ? 6 : n);
  if (n == 4 && c[3] != 1.0) {
    if (c[3] == 0.0)
      return line_error(&p->r, ZS_ERR_PARSE, "w is 0 (a point at infinity)");
    for (int i = 0; i < 3; i++) {
      c[i] /= c[3];
      if (!isfinite(c[i]))
        return line_error(&p->r, ZS_ERR_PARSE, "x/w, y/w or z/w overflows");
    }
  }
  if (zs_model_add_vertex(p->m, c[0], c[1], c[2]) < 0 ||
      !set_vertex_colour(p, n == 6 ? c + 3 : NULL))
    return out_of_memory(p);
  return ZS_OK;
}

/* vn x y z, as floats in the same direction: a normal beyond the range
 * of a float (either way) is scaled by a power of two first.  Its length
 * does not matter (the mesh's normals need not be unit); (0, 0, 0) is
 * "none", as in the mesh. */
static zs_status parse_normal(obj_parser *p) {
  double c[3];
  int n = 0, more = 0;
  for (char *w; (w = next_word(&p->r)) != NULL; n++) {
    if ((more = n == 3)) break;
    zs_status st = parse_number(&p->r, w, &c[n]);
    if (st != ZS_OK) return st;
  }
  if (n != 3 || more)
    return line_error(&p->r, ZS_ERR_PARSE, "expected x y z, got %s%d numbers",
                      more ? "more than " : "", n);
  double big = fmax(fabs(c[0]), fmax(fabs(c[1]), fabs(c[2])));
  if (big > 0.0 && (big > 0x1p100 || big < 0x1p-100)) {
    int e;
    frexp(big, &e);
    for (int i = 0; i < 3; i++) c[i] = ldexp(c[i], -e);
  }
  if (!zs_grow((void **)&p->vn, &p->cap_vn, 3 * ((int64_t)p->nvn + 1), sizeof *p->vn))
    return out_of_memory(p);
  for (int i = 0; i < 3; i++) p->vn[3 * (size_t)p->nvn + i] = (float)c[i];
  p->nvn++;
  return ZS_OK;
}

/* vt u [v [w]]: v 0 when not given, w ignored (no 3D textures). */
static zs_status parse_texcoord(obj_parser *p) {
  double c[3] = {0.0, 0.0, 0.0};
  int n = 0, more = 0;
  for (char *w; (w = next_word(&p->r)) != NULL; n++) {
    if ((more = n == 3)) break;
    zs_status st = parse_number(&p->r, w, &c[n]);
    if (st != ZS_OK) return st;
    if (fabs(c[n]) > FLT_MAX)
      return line_error(&p->r, ZS_ERR_PARSE, "texture coordinate out of range: '%.40s'", w);
  }
  if (n == 0 || more)
    return line_error(&p->r, ZS_ERR_PARSE, "expected u [v [w]], got %s%d numbers",
                      more ? "more than " : "", n);
  if (!zs_grow((void **)&p->vt, &p->cap_vt, 2 * ((int64_t)p->nvt + 1), sizeof *p->vt))
    return out_of_memory(p);
  p->vt[2 * (size_t)p->nvt] = (float)c[0];
  p->vt[2 * (size_t)p->nvt + 1] = (float)c[1];
  p->nvt++;
  return ZS_OK;
}

/* The 0-based index of an f line's index as written (w .. w + len - 1),
 * v, among count defined so far; what names the kind in messages. */
static zs_status resolve_index(obj_parser *p, long long v, const char *w, int len,
                               int32_t count, const char *what, const char *whats,
                               int32_t *out) {
  if (v == 0)
    return line_error(&p->r, ZS_ERR_PARSE, "%s index 0 (indices start at 1)", what);
  if (v > count || -v > count)
    return line_error(&p->r, ZS_ERR_PARSE, "%s index %.*s out of range (%ld %s so far)", what,
                      len > 40 ? 40 : len, w, (long)count, whats);
  *out = (int32_t)(v > 0 ? v - 1 : count + v);
  return ZS_OK;
}

/* One vertex of an f line, v, v/vt, v//vn or v/vt/vn, resolved to 0-based
 * indices of the vertex, texture coordinate and normal (-1: none). */
static zs_status parse_face_vertex(obj_parser *p, const char *w, int32_t out[3]) {
  line_reader *r = &p->r;
  const char *s = w, *at[3] = {w, NULL, NULL};
  long long v[3] = {0, 0, 0};
  int len[3] = {0, 0, 0};
  if (!scan_index(&s, &v[0]))
    return line_error(r, ZS_ERR_PARSE, "expected a vertex index, got '%.40s'", w);
  len[0] = (int)(s - w);
  for (int part = 1; *s == '/'; part++) {
    if (part == 3) return line_error(r, ZS_ERR_PARSE, "too many '/' in '%.40s'", w);
    s++;
    if (part == 1 && *s == '/') continue; /* v//vn */
    at[part] = s;
    if (!scan_index(&s, &v[part]))
      return line_error(r, ZS_ERR_PARSE, "%s face vertex '%.40s'",
                        *s == '\0' ? "truncated" : "bad", w);
    len[part] = (int)(s - at[part]);
  }
  if (*s != '\0') return line_error(r, ZS_ERR_PARSE, "bad face vertex '%.40s'", w);

  out[1] = out[2] = -1;
  zs_status st =
      resolve_index(p, v[0], w, len[0], p->m->mesh.nverts, "vertex", "vertices", &out[0]);
  if (st == ZS_OK && at[1])
    st = resolve_index(p, v[1], at[1], len[1], p->nvt, "texture coordinate",
                       "texture coordinates", &out[1]);
  if (st == ZS_OK && at[2])
    st = resolve_index(p, v[2], at[2], len[2], p->nvn, "normal", "normals", &out[2]);
  return st;
}

static uint32_t slot_hash(int32_t vt, int32_t vn, int32_t col) {
  uint64_t h = (uint64_t)(uint32_t)vt * 0x9E3779B97F4A7C15ull;
  h ^= (uint64_t)(uint32_t)vn * 0xC2B2AE3D27D4EB4Full;
  h ^= (uint64_t)(uint32_t)col * 0x165667B19E3779F9ull;
  return (uint32_t)(h ^ h >> 29);
}

/* The slot of the key (vt, vn, col): its own, or the empty one where it
 * goes. */
static attr_slot *find_slot(attr_slot *slots, int32_t cap, int32_t vt, int32_t vn, int32_t col) {
  uint32_t i = slot_hash(vt, vn, col) & (uint32_t)(cap - 1);
  while (slots[i].attr >= 0 &&
         !(slots[i].vt == vt && slots[i].vn == vn && slots[i].col == col))
    i = (i + 1) & (uint32_t)(cap - 1);
  return &slots[i];
}

/* Keeps the table at most half full. */
static int grow_slots(obj_parser *p) {
  if (2 * (int64_t)(p->nslots + 1) <= p->cap_slots) return 1;
  if (p->cap_slots > INT32_MAX / 4) return 0;
  int32_t cap = p->cap_slots > 0 ? 2 * p->cap_slots : 256;
  attr_slot *s = malloc((size_t)cap * sizeof *s);
  if (!s) return 0;
  for (int32_t i = 0; i < cap; i++) s[i].attr = -1;
  for (int32_t i = 0; i < p->cap_slots; i++)
    if (p->slots[i].attr >= 0)
      *find_slot(s, cap, p->slots[i].vt, p->slots[i].vn, p->slots[i].col) = p->slots[i];
  free(p->slots);
  p->slots = s;
  p->cap_slots = cap;
  return 1;
}

/* The attribute vertex of a corner naming vertex v, texture coordinate vt
 * and normal vn: one per distinct (vt, vn, coloured vertex), numbered in
 * the order of first use; -1 when the corner names none of them, -2 when
 * out of memory. */
static int32_t attr_of_corner(obj_parser *p, int32_t v, int32_t vt, int32_t vn) {
  int32_t col = p->vcol && p->vcol[v] ? v : -1;
  if (vt < 0 && vn < 0 && col < 0) return -1;
  if (!grow_slots(p)) return -2;
  attr_slot *s = find_slot(p->slots, p->cap_slots, vt, vn, col);
  if (s->attr >= 0) return s->attr;
  uint8_t rgba[4];
  if (col >= 0) {
    uint32_t c = p->vcol[col];
    rgba[0] = (uint8_t)(c >> 16);
    rgba[1] = (uint8_t)(c >> 8);
    rgba[2] = (uint8_t)c;
    rgba[3] = 255;
  }
  int32_t a = zs_model_add_attr(p->m, vn >= 0 ? p->vn + 3 * (size_t)vn : NULL,
                                col >= 0 ? rgba : NULL, vt >= 0 ? p->vt + 2 * (size_t)vt : NULL);
  if (a < 0) return -2;
  *s = (attr_slot){vt, vn, col, a};
  p->nslots++;
  return a;
}

static zs_status parse_face(obj_parser *p) {
  int n = 0, any_attr = 0;
  for (char *w; (w = next_word(&p->r)) != NULL; n++) {
    /* a face may have any number of corners */
    if (!zs_grow((void **)&p->idx, &p->cap_idx, (int64_t)n + 1, sizeof *p->idx) ||
        !zs_grow((void **)&p->attr, &p->cap_attr, (int64_t)n + 1, sizeof *p->attr))
      return out_of_memory(p);
    int32_t c[3] = {-1, -1, -1};
    zs_status st = parse_face_vertex(p, w, c);
    if (st != ZS_OK) return st;
    p->idx[n] = c[0];
    if ((p->attr[n] = attr_of_corner(p, c[0], c[1], c[2])) < -1) return out_of_memory(p);
    any_attr |= p->attr[n] >= 0;
  }
  if (n < 3)
    return line_error(&p->r, ZS_ERR_PARSE,
                      "face with %d vertices (at least 3 needed)", n);
  zs_status st = zs_model_add_face(p->m, p->idx, any_attr ? p->attr : NULL, n, p->slot,
                                   (int32_t)p->slot - 1, p->obj);
  if (st == ZS_ERR_NOMEM) return out_of_memory(p);
  if (st != ZS_OK)
    return line_error(&p->r, st, "face rejected by the model");
  return ZS_OK;
}

/* l v1 v2 ... (a polyline: a line between each two consecutive vertices,
 * texture coordinates after '/' read and dropped) and p v1 v2 ... (points),
 * in the colour of the current material, as faces take it. */
static zs_status parse_lines_or_points(obj_parser *p, int lines) {
  int n = 0;
  int32_t prev = -1;
  for (char *w; (w = next_word(&p->r)) != NULL; n++) {
    int32_t c[3] = {-1, -1, -1};
    zs_status st = parse_face_vertex(p, w, c);
    if (st != ZS_OK) return st;
    if (lines && n > 0) st = zs_model_add_line(p->m, prev, c[0], p->slot);
    if (!lines) st = zs_model_add_point(p->m, c[0], p->slot);
    if (st != ZS_OK) return st == ZS_ERR_NOMEM ? out_of_memory(p)
                                               : line_error(&p->r, st, "rejected by the model");
    prev = c[0];
  }
  if (lines && n < 2)
    return line_error(&p->r, ZS_ERR_PARSE, "line with %d vertices (at least 2 needed)", n);
  if (!lines && n < 1) return line_error(&p->r, ZS_ERR_PARSE, "point statement without a vertex");
  return ZS_OK;
}

/* o and g: name NULL returns to no object. */
static zs_status set_object(obj_parser *p, const char *name) {
  if (!name) {
    p->obj = -1;
    return ZS_OK;
  }
  p->obj = zs_model_object(p->m, name);
  return p->obj < 0 ? out_of_memory(p) : ZS_OK;
}

/* usemtl NAME: a name seen for the first time becomes the model's next
 * material, grey until the libraries are read at the end. */
static zs_status use_material(obj_parser *p, const char *name) {
  if (!name) return line_error(&p->r, ZS_ERR_PARSE, "expected a material name");
  long i = names_find(&p->used, name);
  if (i < 0) {
    zs_material grey = zs_material_default();
    if ((i = names_add(&p->used, name)) < 0 || zs_model_add_material(p->m, &grey) != i)
      return out_of_memory(p);
  }
  p->slot = (uint32_t)i + 1;
  return ZS_OK;
}

static zs_status load_mtl(obj_parser *p, const char *file) {
  char *path = join_path(p->dir, file);
  if (!path) return out_of_memory(p);
  /* A missing library is not an error: its faces stay grey, with a note
   * (exporters often leave the .mtl behind). */
  char *text;
  size_t len;
  zs_status st = zs_load_file(path, path, (long long)ZS_OBJ_MAX_BYTES, ZS_LOAD_MISSING_OK, &text,
                              &len, p->r.err);
  if (st == ZS_OK && text) st = parse_mtl(text, len, path, &p->mtl, p->r.err);
  if (st == ZS_OK && !text &&
      !zs_notes_add(&p->m->notes, "%s:%ld: mtllib %s: no such file: its materials drawn grey",
                    p->r.name, p->r.line, file))
    st = out_of_memory(p);
  free(text);
  free(path);
  return st;
}

/* Every keyword of the OBJ format (Wavefront's Appendix B1): a line that
 * starts with one is a statement, whether zscan draws it or not. */
static int is_obj_keyword(const char *kw) {
  static const char *const keywords[] = {
      "v",     "vt",     "vn",      "vp",       "f",        "l",      "p",     "o",
      "g",     "s",      "mg",      "usemtl",   "mtllib",   "cstype", "deg",   "bmat",
      "step",  "curv",   "curv2",   "surf",     "parm",     "trim",   "hole",  "scrv",
      "sp",    "end",    "con",     "lod",      "maplib",   "usemap", "shadow_obj",
      "trace_obj", "ctech", "stech", "bevel",   "c_interp", "d_interp", "call", "csh",
      "res"};
  for (size_t i = 0; i < sizeof keywords / sizeof keywords[0]; i++)
    if (strcmp(kw, keywords[i]) == 0) return 1;
  return 0;
}

/* A word that could be some program's own statement: letters, digits and
 * '_' only, starting with a letter. */
static int is_statement_like(const char *kw) {
  if (!((*kw >= 'a' && *kw <= 'z') || (*kw >= 'A' && *kw <= 'Z'))) return 0;
  for (; *kw; kw++)
    if (!((*kw >= 'a' && *kw <= 'z') || (*kw >= 'A' && *kw <= 'Z') || is_digit(*kw) ||
          *kw == '_'))
      return 0;
  return 1;
}

static zs_status parse_line(obj_parser *p) {
  if (p->r.control) return line_error(&p->r, ZS_ERR_PARSE, "not an OBJ statement");
  char *kw = next_word(&p->r);
  if (!kw) return ZS_OK;
  if (is_obj_keyword(kw)) {
    p->statements++;
  } else {
    if (!is_statement_like(kw)) return line_error(&p->r, ZS_ERR_PARSE, "not an OBJ statement");
    if (p->strangers++ == 0) p->first_stranger = p->r.line;
    return ZS_OK; /* another program's extension, perhaps: nothing to draw */
  }
  if (strcmp(kw, "v") == 0) return parse_vertex(p);
  if (strcmp(kw, "vn") == 0) return parse_normal(p);
  if (strcmp(kw, "vt") == 0) return parse_texcoord(p);
  if (strcmp(kw, "f") == 0) return parse_face(p);
  if (strcmp(kw, "l") == 0) return parse_lines_or_points(p, 1);
  if (strcmp(kw, "p") == 0) return parse_lines_or_points(p, 0);
  if (strcmp(kw, "o") == 0) return set_object(p, rest_of_line(&p->r));
  if (strcmp(kw, "g") == 0) return set_object(p, next_word(&p->r));
  if (strcmp(kw, "usemtl") == 0) return use_material(p, rest_of_line(&p->r));
  if (strcmp(kw, "mtllib") == 0) {
    char *file = next_word(&p->r);
    if (!file) return line_error(&p->r, ZS_ERR_PARSE, "expected a file name");
    for (; file; file = next_word(&p->r)) {
      zs_status st = p->dir ? load_mtl(p, file) : ZS_OK;
      if (st != ZS_OK) return st;
    }
    return ZS_OK;
  }
  /* vp, s, l, p, curves and surfaces: nothing to draw */
  return ZS_OK;
}

/* ---- the end: materials, textures, normals ---------------------------- */

static zs_status end_nomem(obj_parser *p) {
  return zs_error_set(p->r.err, ZS_ERR_NOMEM, "%s: out of memory", p->r.name);
}

/* The texture of d's map_Kd, read once per path; *out NULL when it is
 * skipped (ZS_OBJ_SKIP_MISSING_TEXTURES), with a note of the model's.  A
 * failure names the library's line and the file as written there, then
 * the reader's reason; the note is that message and ": drawn without
 * it". */
static zs_status texture_of(obj_parser *p, const mtl_def *d, const zs_texture **out) {
  for (int32_t i = 0; i < p->ntex; i++) {
    if (strcmp(p->tex[i].path, d->map_path) == 0) {
      *out = p->tex[i].tex;
      return ZS_OK;
    }
  }
  if (!zs_grow((void **)&p->tex, &p->cap_tex, (int64_t)p->ntex + 1, sizeof *p->tex))
    return end_nomem(p);
  zs_texture *tex = NULL;
  zs_error e;
  zs_error_clear(&e);
  zs_status st = zs_texture_load(d->map_path, &tex, &e);
  if (st != ZS_OK) {
    /* the reader's message begins with the path it was given: drop that */
    size_t plen = strlen(d->map_path);
    const char *why = strncmp(e.msg, d->map_path, plen) == 0 && strncmp(e.msg + plen, ": ", 2) == 0
                          ? e.msg + plen + 2 : e.msg;
    /* only a file that cannot be opened or read is skipped: a corrupt
     * image is there to be fixed */
    if (st != ZS_ERR_IO || !(p->flags & ZS_OBJ_SKIP_MISSING_TEXTURES))
      return zs_load_error(p->r.err, st, "%s: map_Kd %s: %s", d->map_where, d->map, why);
    if (!zs_notes_add(&p->m->notes, "%s: map_Kd %s: %s: drawn without it", d->map_where, d->map,
                      why))
      return end_nomem(p);
  }
  if (tex && !zs_model_own_texture(p->m, tex)) return end_nomem(p);
  if (!(p->tex[p->ntex].path = strdup(d->map_path))) return end_nomem(p);
  p->tex[p->ntex++].tex = tex;
  *out = tex;
  return ZS_OK;
}

/* Material i of the model from the library's definition of used name i
 * (grey when no library defines it). */
static zs_status resolve_material(obj_parser *p, size_t i, uint32_t *rgb) {
  const mtl_def *d = mtl_find(&p->mtl, p->used.names[i]);
  *rgb = d ? d->rgb : ZS_GREY;
  if (!d && p->dir && p->mtl.n > 0 &&
      !zs_notes_add(&p->m->notes, "%s: usemtl %s: no library defines it: drawn grey", p->r.name,
                    p->used.names[i]))
    return end_nomem(p);
  if (!d) return ZS_OK;
  zs_material *mat = &p->m->materials[i];
  *mat = d->mat;
  mat->base[0] = (uint8_t)(d->rgb >> 16);
  mat->base[1] = (uint8_t)(d->rgb >> 8);
  mat->base[2] = (uint8_t)d->rgb;
  return d->map ? texture_of(p, d, &mat->base_texture) : ZS_OK;
}

/* Faces before the first usemtl, in a file with materials: a grey
 * material of their own (-1 would mean material 0). */
static zs_status material_for_the_rest(obj_parser *p) {
  zs_mesh *mesh = &p->m->mesh;
  int32_t f = 0;
  while (f < mesh->nfaces && mesh->face_material && mesh->face_material[f] >= 0) f++;
  if (mesh->nmaterials == 0 || f == mesh->nfaces) return ZS_OK;
  zs_material grey = zs_material_default();
  int32_t k = zs_model_add_material(p->m, &grey);
  if (k < 0) return end_nomem(p);
  if (!mesh->face_material) {
    /* the capacity of the per-face arrays, as the model grows them together */
    if (!(mesh->face_material = malloc((size_t)p->m->cap_faces * sizeof *mesh->face_material)))
      return end_nomem(p);
    for (int32_t g = 0; g < mesh->nfaces; g++) mesh->face_material[g] = -1;
  }
  for (; f < mesh->nfaces; f++)
    if (mesh->face_material[f] < 0) mesh->face_material[f] = k;
  return ZS_OK;
}

/* Once every library is read: each face's usemtl number becomes the
 * material's colour, each used name a material (its texture read), the
 * faces without usemtl a grey material when there are others, and a mesh
 * with attributes or textures gets normals where the file gave none. */
static zs_status resolve_materials(obj_parser *p) {
  uint32_t *rgb = malloc((p->used.n + 1) * sizeof *rgb);
  if (!rgb) return end_nomem(p);
  rgb[0] = ZS_GREY;
  zs_status st = ZS_OK;
  for (size_t i = 0; st == ZS_OK && i < p->used.n; i++) st = resolve_material(p, i, &rgb[i + 1]);
  zs_mesh *mesh = &p->m->mesh;
  if (st == ZS_OK)
    for (int32_t f = 0; f < mesh->nfaces; f++) mesh->face_rgb[f] = rgb[mesh->face_rgb[f]];
  for (int32_t k = 0; st == ZS_OK && k < mesh->nlines; k++) mesh->line_rgb[k] = rgb[mesh->line_rgb[k]];
  for (int32_t k = 0; st == ZS_OK && k < mesh->npoints; k++)
    mesh->point_rgb[k] = rgb[mesh->point_rgb[k]];
  free(rgb);
  if (st == ZS_OK) st = material_for_the_rest(p);
  if (st == ZS_OK && !zs_model_complete_normals(p->m)) st = end_nomem(p);
  return st;
}

static void parser_free(obj_parser *p) {
  free(p->r.buf);
  free(p->idx);
  free(p->attr);
  free(p->vn);
  free(p->vt);
  free(p->vcol);
  free(p->slots);
  for (int32_t i = 0; i < p->ntex; i++) free(p->tex[i].path);
  free(p->tex);
  mtl_free(&p->mtl);
  names_free(&p->used);
}

zs_status zs_obj_parse_flags(const char *text, size_t len, const char *name, const char *dir,
                             int flags, zs_model *out, zs_error *err) {
  zs_model_init(out);
  if (!name) name = "(obj)";
  if (!text && len > 0)
    return zs_error_set(err, ZS_ERR_ARG, "%s: no text", name);
  obj_parser p = {.m = out, .dir = dir, .flags = flags, .obj = -1, .slot = 0};
  zs_status st = reader_init(&p.r, text, len, name, err);
  int have;
  while (st == ZS_OK && (st = next_line(&p.r, &have)) == ZS_OK && have)
    st = parse_line(&p);
  /* Mostly lines of unknown words: some other text, not an OBJ. */
  if (st == ZS_OK && p.strangers > p.statements)
    st = zs_error_set(err, ZS_ERR_PARSE, "%s:%ld: not an OBJ statement", name, p.first_stranger);
  if (st == ZS_OK) st = resolve_materials(&p);
  parser_free(&p);
  if (st != ZS_OK) zs_model_free(out);
  return st;
}

zs_status zs_obj_parse(const char *text, size_t len, const char *name,
                       const char *dir, zs_model *out, zs_error *err) {
  return zs_obj_parse_flags(text, len, name, dir, 0, out, err);
}

/* What zs_load_parsed hands to parse_obj. */
typedef struct obj_target {
  zs_model *m;
  int flags;
} obj_target;

static zs_status parse_obj(const char *text, size_t len, const char *name, const char *dir,
                           void *out, zs_error *err) {
  obj_target *t = out;
  return zs_obj_parse_flags(text, len, name, dir, t->flags, t->m, err);
}

zs_status zs_obj_load_flags(const char *path, int flags, zs_model *out, zs_error *err) {
  zs_model_init(out);
  obj_target t = {out, flags};
  /* Material libraries live next to the file. */
  return zs_load_parsed(path, (long long)ZS_OBJ_MAX_BYTES, 0, parse_obj, &t, err);
}

zs_status zs_obj_load(const char *path, zs_model *out, zs_error *err) {
  return zs_obj_load_flags(path, 0, out, err);
}
