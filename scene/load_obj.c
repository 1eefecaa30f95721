/* zscan scene — the Wavefront OBJ reader (see load_obj.h for what is read).
 *
 * The text is read line by line: each line is checked (length, NUL bytes),
 * copied into a NUL-terminated buffer with its comment cut off, and split
 * into words in place.  Numbers go through strtod, which follows the
 * LC_NUMERIC locale; zscan never calls setlocale, so that is "C" and the
 * decimal point is '.'.
 *
 * Colours are resolved at the end: while reading, a face's rgb holds the
 * number of its usemtl name (0: none), and once every library is loaded
 * those numbers are replaced by the materials' colours.
 */
#include "scene/load_obj.h"
#include "util/grow.h"
#include "scene/load_common.h"
#include "scene/text.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <sys/stat.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__GNUC__)
#define PRINTF_LIKE(f, a) __attribute__((format(printf, f, a)))
#else
#define PRINTF_LIKE(f, a)
#endif

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
static zs_status PRINTF_LIKE(3, 4)
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

/* ---- materials -------------------------------------------------------- */

/* A list of names with a colour each: the materials of the libraries, in
 * the order defined, and the names used by usemtl. */
typedef struct name_list {
  char **names;
  uint32_t *rgb;
  size_t n;
  int32_t cap;
} name_list;

static void names_free(name_list *l) {
  for (size_t i = 0; i < l->n; i++) free(l->names[i]);
  free(l->names);
  free(l->rgb);
  *l = (name_list){.n = 0};
}

/* The index of the last entry named name, or -1. */
static long names_find(const name_list *l, const char *name) {
  for (size_t i = l->n; i > 0; i--)
    if (strcmp(l->names[i - 1], name) == 0) return (long)(i - 1);
  return -1;
}

/* Appends name with colour rgb; returns its index, -1 when out of memory. */
static long names_add(name_list *l, const char *name, uint32_t rgb) {
  /* names and rgb grow alike from cap; cap is raised with the last. */
  int32_t names_cap = l->cap;
  if (!zs_grow((void **)&l->names, &names_cap, (int64_t)l->n + 1, sizeof *l->names) ||
      !zs_grow((void **)&l->rgb, &l->cap, (int64_t)l->n + 1, sizeof *l->rgb))
    return -1;
  char *copy = strdup(name);
  if (!copy) return -1;
  l->names[l->n] = copy;
  l->rgb[l->n] = rgb;
  return (long)l->n++;
}

static uint32_t channel(double kd) {
  if (kd < 0.0) kd = 0.0;
  if (kd > 1.0) kd = 1.0;
  return (uint32_t)lround(kd * 255.0);
}

/* Kd r [g b] of the current material: one number stands for all three. */
static zs_status parse_kd(line_reader *r, uint32_t *rgb) {
  char *w = next_word(r);
  if (w && (strcmp(w, "spectral") == 0 || strcmp(w, "xyz") == 0))
    return ZS_OK; /* other colour spaces: keep the colour as it is */
  double kd[3];
  zs_status st = parse_number(r, w, &kd[0]);
  if (st != ZS_OK) return st;
  kd[1] = kd[2] = kd[0];
  if ((w = next_word(r)) != NULL) {
    for (int i = 1; i < 3; i++) {
      st = parse_number(r, i == 1 ? w : next_word(r), &kd[i]);
      if (st != ZS_OK) return st;
    }
    if (next_word(r))
      return line_error(r, ZS_ERR_PARSE, "Kd takes 1 or 3 numbers");
  }
  *rgb = channel(kd[0]) << 16 | channel(kd[1]) << 8 | channel(kd[2]);
  return ZS_OK;
}

/* Adds the materials of the .mtl text to mtl. */
static zs_status parse_mtl(const char *text, size_t len, const char *name,
                           name_list *mtl, zs_error *err) {
  line_reader r;
  zs_status st = reader_init(&r, text, len, name, err);
  long current = -1; /* the material being defined */
  int have;
  while (st == ZS_OK && (st = next_line(&r, &have)) == ZS_OK && have) {
    char *kw = next_word(&r);
    if (!kw) continue;
    if (strcmp(kw, "newmtl") == 0) {
      char *mat = rest_of_line(&r);
      if (!mat) st = line_error(&r, ZS_ERR_PARSE, "expected a material name");
      else if ((current = names_add(mtl, mat, ZS_GREY)) < 0)
        st = line_error(&r, ZS_ERR_NOMEM, "out of memory");
    } else if (strcmp(kw, "Kd") == 0) {
      if (current < 0) st = line_error(&r, ZS_ERR_PARSE, "Kd before newmtl");
      else st = parse_kd(&r, &mtl->rgb[current]);
    }
    /* Ka, Ks, Ns, d, illum, maps...: not used by flat shading. */
  }
  free(r.buf);
  return st;
}

/* ---- the OBJ file ----------------------------------------------------- */

typedef struct obj_parser {
  line_reader r;
  long statements;  /* lines that are OBJ statements */
  long strangers;   /* lines that are not: the file may not be an OBJ */
  long first_stranger; /* the line of the first, for the message */
  zs_model *m;
  const char *dir; /* for mtllib; NULL: libraries are skipped */
  int32_t obj;     /* the object of the following faces, -1: none */
  uint32_t slot;   /* usemtl of the following faces: 0 none, else used[slot-1] */
  name_list mtl;   /* materials defined by the libraries */
  name_list used;  /* material names given to usemtl */
  int32_t *idx;    /* the corners of the face being read */
  int32_t cap_idx;
} obj_parser;

static zs_status out_of_memory(obj_parser *p) {
  return line_error(&p->r, ZS_ERR_NOMEM, "out of memory");
}

static zs_status parse_vertex(obj_parser *p) {
  /* x y z, x y z w, or x y z r g b (vertex colours, ignored) */
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
  if (zs_model_add_vertex(p->m, c[0], c[1], c[2]) < 0) return out_of_memory(p);
  return ZS_OK;
}

/* One vertex of an f line, v, v/vt, v//vn or v/vt/vn, resolved to a
 * 0-based vertex index.  vt and vn are checked for form only. */
static zs_status parse_face_vertex(obj_parser *p, const char *w,
                                   int32_t *out) {
  line_reader *r = &p->r;
  const char *s = w;
  long long v;
  if (!scan_index(&s, &v))
    return line_error(r, ZS_ERR_PARSE, "expected a vertex index, got '%.40s'",
                      w);
  int vlen = (int)(s - w); /* the index as written, for messages */
  for (int part = 1; *s == '/'; part++) {
    if (part == 3)
      return line_error(r, ZS_ERR_PARSE, "too many '/' in '%.40s'", w);
    s++;
    if (part == 1 && *s == '/') continue; /* v//vn */
    long long ignored;
    if (!scan_index(&s, &ignored))
      return line_error(r, ZS_ERR_PARSE, "%s face vertex '%.40s'",
                        *s == '\0' ? "truncated" : "bad", w);
  }
  if (*s != '\0')
    return line_error(r, ZS_ERR_PARSE, "bad face vertex '%.40s'", w);

  int32_t nverts = p->m->mesh.nverts;
  if (v == 0)
    return line_error(r, ZS_ERR_PARSE, "vertex index 0 (indices start at 1)");
  if (v > nverts || -v > nverts)
    return line_error(r, ZS_ERR_PARSE,
                      "vertex index %.*s out of range (%ld vertices so far)",
                      vlen > 40 ? 40 : vlen, w, (long)nverts);
  *out = (int32_t)(v > 0 ? v - 1 : nverts + v);
  return ZS_OK;
}

static zs_status parse_face(obj_parser *p) {
  int n = 0;
  for (char *w; (w = next_word(&p->r)) != NULL; n++) {
    /* a face may have any number of corners */
    if (!zs_grow((void **)&p->idx, &p->cap_idx, (int64_t)n + 1, sizeof *p->idx))
      return out_of_memory(p);
    zs_status st = parse_face_vertex(p, w, &p->idx[n]);
    if (st != ZS_OK) return st;
  }
  int32_t *idx = p->idx;
  if (n < 3)
    return line_error(&p->r, ZS_ERR_PARSE,
                      "face with %d vertices (at least 3 needed)", n);
  zs_status st = zs_model_add_polygon(p->m, idx, n, p->slot, p->obj);
  if (st == ZS_ERR_NOMEM) return out_of_memory(p);
  if (st != ZS_OK)
    return line_error(&p->r, st, "face rejected by the model");
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

static zs_status load_mtl(obj_parser *p, const char *file) {
  /* file relative to dir, unless absolute */
  size_t dlen = file[0] == '/' ? 0 : strlen(p->dir);
  int slash = dlen > 0 && p->dir[dlen - 1] != '/';
  size_t flen = strlen(file);
  char *path = malloc(dlen + (size_t)slash + flen + 1);
  if (!path) return out_of_memory(p);
  memcpy(path, p->dir, dlen);
  if (slash) path[dlen] = '/';
  memcpy(path + dlen + slash, file, flen + 1);

  /* A missing library is not an error: its faces stay grey. */
  char *text;
  size_t len;
  zs_status st = zs_load_file(path, path, (long long)ZS_OBJ_MAX_BYTES, ZS_LOAD_MISSING_OK, &text,
                              &len, p->r.err);
  if (st == ZS_OK && text) st = parse_mtl(text, len, path, &p->mtl, p->r.err);
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
  if (strcmp(kw, "f") == 0) return parse_face(p);
  if (strcmp(kw, "o") == 0) return set_object(p, rest_of_line(&p->r));
  if (strcmp(kw, "g") == 0) return set_object(p, next_word(&p->r));
  if (strcmp(kw, "usemtl") == 0) {
    char *name = rest_of_line(&p->r);
    if (!name)
      return line_error(&p->r, ZS_ERR_PARSE, "expected a material name");
    long i = names_find(&p->used, name);
    if (i < 0 && (i = names_add(&p->used, name, 0)) < 0)
      return out_of_memory(p);
    p->slot = (uint32_t)i + 1;
    return ZS_OK;
  }
  if (strcmp(kw, "mtllib") == 0) {
    char *file = next_word(&p->r);
    if (!file) return line_error(&p->r, ZS_ERR_PARSE, "expected a file name");
    for (; file; file = next_word(&p->r)) {
      zs_status st = p->dir ? load_mtl(p, file) : ZS_OK;
      if (st != ZS_OK) return st;
    }
    return ZS_OK;
  }
  /* vt, vn, s, l, p, curves and surfaces: nothing to draw */
  return ZS_OK;
}

/* Replaces each face's usemtl number by the material's colour. */
static zs_status resolve_colours(obj_parser *p) {
  uint32_t *rgb = malloc((p->used.n + 1) * sizeof *rgb);
  if (!rgb)
    return zs_error_set(p->r.err, ZS_ERR_NOMEM, "%s: out of memory",
                        p->r.name);
  rgb[0] = ZS_GREY;
  for (size_t i = 0; i < p->used.n; i++) {
    long k = names_find(&p->mtl, p->used.names[i]);
    rgb[i + 1] = k >= 0 ? p->mtl.rgb[k] : ZS_GREY;
  }
  zs_mesh *mesh = &p->m->mesh;
  for (int32_t f = 0; f < mesh->nfaces; f++)
    mesh->face_rgb[f] = rgb[mesh->face_rgb[f]];
  free(rgb);
  return ZS_OK;
}

zs_status zs_obj_parse(const char *text, size_t len, const char *name,
                       const char *dir, zs_model *out, zs_error *err) {
  zs_model_init(out);
  if (!name) name = "(obj)";
  if (!text && len > 0)
    return zs_error_set(err, ZS_ERR_ARG, "%s: no text", name);
  obj_parser p = {.m = out, .dir = dir, .obj = -1, .slot = 0};
  zs_status st = reader_init(&p.r, text, len, name, err);
  int have;
  while (st == ZS_OK && (st = next_line(&p.r, &have)) == ZS_OK && have)
    st = parse_line(&p);
  /* Mostly lines of unknown words: some other text, not an OBJ. */
  if (st == ZS_OK && p.strangers > p.statements)
    st = zs_error_set(err, ZS_ERR_PARSE, "%s:%ld: not an OBJ statement", name, p.first_stranger);
  if (st == ZS_OK) st = resolve_colours(&p);
  free(p.r.buf);
  free(p.idx);
  names_free(&p.mtl);
  names_free(&p.used);
  if (st != ZS_OK) zs_model_free(out);
  return st;
}

static zs_status parse_obj(const char *text, size_t len, const char *name, const char *dir,
                           void *out, zs_error *err) {
  return zs_obj_parse(text, len, name, dir, out, err);
}

zs_status zs_obj_load(const char *path, zs_model *out, zs_error *err) {
  zs_model_init(out);
  /* Material libraries live next to the file. */
  return zs_load_parsed(path, (long long)ZS_OBJ_MAX_BYTES, 0, parse_obj, out, err);
}
