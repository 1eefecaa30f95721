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
#include "util/compiler.h"
#include "scene/load_common.h"
#include "scene/texture_file.h"
#include "util/grow.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef ZS_HAVE_ASSIMP
#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
/* glTF's sampler filters: assimp 5.1 and later */
#if defined(__has_include)
#if __has_include(<assimp/GltfMaterial.h>)
#include <assimp/GltfMaterial.h>
#endif
#endif
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

zs_status zs_assimp_load_flags(const char *path, int flags, zs_model *out, zs_error *err) {
  (void)flags;
  zs_model_init(out);
  return zs_error_set(err, ZS_ERR_UNSUPPORTED,
                      "%s: this build reads only .obj (built without assimp)", path);
}

zs_status zs_assimp_load(const char *path, zs_model *out, zs_error *err) {
  return zs_assimp_load_flags(path, 0, out, err);
}

#else

enum { HEADER_BYTES = 1 << 16 }; /* of a file read for the header checks */

/* Sets err to the message with every control character written as a
 * space: assimp's messages span lines, and names from the file may hold
 * anything. */
static zs_status ZS_PRINTF_LIKE(3, 4)
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
 * optional dimension after nOFF, then the counts) and where its body
 * begins, as assimp's reader finds it (after the edge count, if any, and
 * the blanks and comments after that); 0 when the text does not read as
 * one.  Without the OFF keyword the file is OFF only by its extension
 * (is_off_name). */
static int off_counts(const char *t, int is_off_name, uint64_t *nv, uint64_t *nf,
                      uint64_t *body) {
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
  if (!read_count(&s, nf)) return 0;
  off_next_token(&s);
  uint64_t edges;
  read_count(&s, &edges);
  off_next_token(&s);
  *body = (uint64_t)(s - t);
  return 1;
}

/* Bytes of one value of a PLY type name in a binary file (0 if unknown). */
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
  return 0;
}

/* The fewest bytes the elements a PLY header declares can take: each
 * element at least one byte per property in ASCII, the sizes of its
 * scalars (and of its lists' counts) in binary, and one byte if it has no
 * property.  0 when the text (len bytes read) is not a PLY header;
 * *body is the header's length.  A header cut short (*cut: longer than
 * what was read, or ended by a NUL byte, *nul) gives the bytes of what it
 * declares up to the cut, and the cut as its length: still a bound from
 * below on what the file must hold after its header, so a count far
 * beyond the file is refused before assimp allocates for it.  A line
 * the header's grammar does not allow sets *bad_line (from 1). */
/* A PLY header's elements, as a text body is checked against them: each
 * element's count, its properties and which of them are lists (n -1: too
 * many to follow, and the body is not checked). */
enum { PLY_ELEMENTS = 16, PLY_PROPS = 32 };
typedef struct ply_layout {
  int n;
  struct {
    char name[64];
    uint64_t count;
    int props;
    uint32_t lists; /* bit p: property p is a list */
  } e[PLY_ELEMENTS];
} ply_layout;

static void layout_element(ply_layout *lay, const char *name, uint64_t count) {
  if (lay->n < 0 || lay->n == PLY_ELEMENTS) {
    lay->n = -1;
    return;
  }
  snprintf(lay->e[lay->n].name, sizeof lay->e[0].name, "%s", name);
  lay->e[lay->n].count = count;
  lay->e[lay->n].props = 0;
  lay->e[lay->n].lists = 0;
  lay->n++;
}

static void layout_property(ply_layout *lay, int list) {
  if (lay->n <= 0) return;
  int *p = &lay->e[lay->n - 1].props;
  if (*p == PLY_PROPS) {
    lay->n = -1;
    return;
  }
  if (list) lay->e[lay->n - 1].lists |= 1u << *p;
  (*p)++;
}

static int ply_min_bytes(const char *t, size_t len, int ply_name, uint64_t *min_bytes,
                         uint64_t *body, int *cut, int *nul, int *bad_line, ply_layout *lay) {
  /* what assimp reads as a PLY: a name ending .ply, or text starting
   * "ply"; its first line must be that word alone */
  if (!ply_name && strncmp(t, "ply", 3) != 0) return 0;
  if (strncmp(t, "ply", 3) != 0 || (t[3] != '\n' && t[3] != '\r')) {
    *bad_line = 1;
    return 1;
  }
  int binary = 0, formats = 0, elements = 0, number = 0;
  uint64_t total = 0, count = 0, per = 0;
  const char *line = t;
  for (;; number++) {
    const char *end = *line ? strchr(line, '\n') : NULL;
    if (!end) { /* cut short */
      *min_bytes = sat_add(total, sat_mul(count, per ? per : 1));
      *body = (uint64_t)(line - t);
      *nul = (size_t)(line - t) + strlen(line) < len;
      *cut = 1;
      return 1;
    }
    char buf[256], w[5][64];
    size_t n = (size_t)(end - line) < sizeof buf - 1 ? (size_t)(end - line) : sizeof buf - 1;
    memcpy(buf, line, n);
    buf[n] = '\0';
    int nw = sscanf(buf, "%63s %63s %63s %63s %63s", w[0], w[1], w[2], w[3], w[4]);
    line = end + 1;
    /* a header is text: printable ASCII and tabs (before the NUL check
     * below, which a line cut by one reaches) */
    for (size_t i = 0; i < n; i++)
      if ((buf[i] < ' ' || buf[i] > '~') && buf[i] != '\t' && buf[i] != '\r') {
        *bad_line = number + 1;
        return 1;
      }
    if (nw < 1 || number == 0) continue; /* (line 0: "ply") */
    /* The header's grammar: a format line before the elements, once; an
     * element's properties after it; any other line a comment (Blender
     * once wrote its name on a line of its own, and assimp reads past
     * it).  assimp 5.2's reader takes some other headers into states its
     * post-processing asserts on (abort()), so they are refused here,
     * with the line. */
    const int is_comment = strcmp(w[0], "format") != 0 && strcmp(w[0], "element") != 0 &&
                           strcmp(w[0], "property") != 0;
    const int good =
        is_comment ||
        (strcmp(w[0], "format") == 0 && nw == 3 && formats++ == 0 && !elements) ||
        (strcmp(w[0], "element") == 0 && nw == 3 && formats) ||
        (strcmp(w[0], "property") == 0 && elements &&
         ((nw == 3 && ply_type_size(w[1])) ||
          (nw == 5 && strcmp(w[1], "list") == 0 && ply_type_size(w[2]) && ply_type_size(w[3]))));
    if (!good) {
      *bad_line = number + 1;
      return 1;
    }
    if (strcmp(w[0], "end_header") == 0) {
      total = sat_add(total, sat_mul(count, per ? per : 1));
      *min_bytes = total;
      *body = (uint64_t)(line - t);
      return 1;
    }
    if (strcmp(w[0], "format") == 0 && nw >= 2) {
      binary = strncmp(w[1], "binary", 6) == 0;
    } else if (strcmp(w[0], "element") == 0) {
      total = sat_add(total, sat_mul(count, per ? per : 1));
      const char *c = w[2];
      if (!read_count(&c, &count) || *c) {
        *bad_line = number + 1;
        return 1;
      }
      elements++;
      per = 0;
      layout_element(lay, w[1], count);
    } else if (strcmp(w[0], "property") == 0 && nw >= 3) {
      /* "property TYPE NAME" or "property list COUNT_TYPE INDEX_TYPE NAME" */
      int list = strcmp(w[1], "list") == 0;
      layout_property(lay, list);
      per = sat_add(per, binary ? ply_type_size(list ? w[2] : w[1]) : 1);
    }
  }
}

/* Whether a word of a text model spells a number that is not finite:
 * nan or inf (infinity), any case, signed or not, as strtod reads them.
 * assimp 5.2's number parser reads such a word as 0 (or a part of it),
 * so a vertex at NaN in an ASCII PLY, OFF or STL file came through as a
 * finite one, and is looked for in the text instead. */
static int spells_non_finite(const char *w) {
  if (*w == '+' || *w == '-') w++;
  return (lower((unsigned char)w[0]) == 'n' && lower((unsigned char)w[1]) == 'a' &&
          lower((unsigned char)w[2]) == 'n') ||
         (lower((unsigned char)w[0]) == 'i' && lower((unsigned char)w[1]) == 'n' &&
          lower((unsigned char)w[2]) == 'f');
}

/* Hands the file's bytes from byte `from` on to take, a buffer at a
 * time, while it returns ZS_OK and wants more (*more, set to 1 first);
 * the scans of a text model below read through it. */
typedef zs_status (*take_bytes)(void *user, const char *b, size_t n, int *more, zs_error *err);

static zs_status read_from(const char *path, uint64_t from, take_bytes take, void *user,
                           zs_error *err) {
  FILE *f = fopen(path, "rb");
  if (!f) return set_error(err, ZS_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
  static char buf[1 << 16];
  zs_status st = ZS_OK;
  int more = 1;
  if (fseek(f, (long)from, SEEK_SET) != 0)
    st = set_error(err, ZS_ERR_IO, "%s: cannot read: %s", path, strerror(errno));
  for (size_t n; st == ZS_OK && more && (n = fread(buf, 1, sizeof buf, f)) > 0;)
    st = take(user, buf, n, &more, err);
  fclose(f);
  return st;
}

/* The text model's words from byte `from` on: a word that spells a number that is not finite is refused with its
 * line.  OFF's comments (# to the end of the line) are skipped; in STL the
 * name after solid and endsolid is not a number. */
typedef struct word_scan {
  const char *path;
  char word[32];
  size_t n;                     /* the word's bytes so far (0: between words) */
  int line, comment, named, at; /* at: the line's words before this one */
  int off, stl;
} word_scan;

/* The word just ended: refused, or noted. */
static zs_status end_word(word_scan *w, zs_error *err) {
  if (w->n == 0 || w->comment || w->named) return w->n = 0, ZS_OK;
  w->word[w->n < sizeof w->word ? w->n : sizeof w->word - 1] = '\0';
  w->n = 0;
  if (spells_non_finite(w->word))
    return set_error(err, ZS_ERR_PARSE, "%s:%d: '%s': not a finite number", w->path, w->line,
                     w->word);
  if (w->stl && w->at == 0 && (strcmp(w->word, "solid") == 0 || strcmp(w->word, "endsolid") == 0))
    w->named = 1;
  w->at++;
  return ZS_OK;
}

static zs_status take_words(void *user, const char *b, size_t n, int *more, zs_error *err) {
  word_scan *w = user;
  (void)more;
  zs_status st = ZS_OK;
  for (size_t i = 0; i < n && st == ZS_OK; i++) {
    const char c = b[i];
    if (is_blank(c) || c == '\0') {
      st = end_word(w, err);
      if (c == '\n') w->line++, w->comment = w->named = w->at = 0;
      continue;
    }
    if (w->off && c == '#' && w->n == 0) w->comment = 1;
    if (w->n < sizeof w->word - 1) w->word[w->n] = c;
    w->n++;
  }
  return st;
}

static zs_status check_text_numbers(const char *path, uint64_t from, int off, int stl,
                                    int first_line, zs_error *err) {
  word_scan w = {path, {0}, 0, first_line, 0, 0, 0, off, stl};
  zs_status st = read_from(path, from, take_words, &w, err);
  return st == ZS_OK ? end_word(&w, err) : st; /* the file's last word */
}

/* The faces of a text OFF file, read as assimp 5.2's reader reads them:
 * from the body on, a line is a run of bytes without a line end (\n, \r,
 * \f: empty lines are skipped); the first nv lines are vertices, the next
 * nf faces "K I1 .. IK", words parted by spaces and tabs.  That reader
 * drops a face of no or more than 9 corners, takes an index at or past nv
 * as the last vertex and a word that is not digits as 0, all without an
 * error; each is refused here with its line instead. */
typedef struct off_faces {
  const char *path;
  uint64_t nv, nf, lines; /* lines: the body's so far */
  int line;               /* the file's, for the message */
  char word[24];
  size_t n;        /* the word's bytes so far */
  int words;       /* this line's words before the word */
  uint64_t k;      /* this face's corners, from its first word */
  int in_line;     /* a byte of this line seen */
} off_faces;

/* The word's value (read_count), or UINT64_MAX when it is not all digits;
 * the word is then NUL-terminated. */
static uint64_t off_word_value(off_faces *f) {
  const int whole = f->n < sizeof f->word;
  f->word[whole ? f->n : sizeof f->word - 1] = '\0';
  const char *c = f->word;
  uint64_t v;
  return whole && read_count(&c, &v) && *c == '\0' ? v : UINT64_MAX;
}

static int off_in_faces(const off_faces *f) {
  return f->lines >= f->nv && f->lines - f->nv < f->nf;
}

static zs_status off_end_word(off_faces *f, zs_error *err) {
  if (f->n == 0) return ZS_OK;
  const uint64_t v = off_word_value(f);
  f->n = 0;
  if (!off_in_faces(f)) return ZS_OK;
  const int w = f->words++;
  if (w == 0) {
    f->k = v;
    if (v == UINT64_MAX || v == 0)
      return set_error(err, ZS_ERR_PARSE, "%s:%d: '%s': expected a face's corner count, 1 to 9",
                       f->path, f->line, f->word);
    if (v > 9)
      return set_error(err, ZS_ERR_PARSE,
                       "%s:%d: a face of %s corners: assimp's OFF reader takes 1 to 9 (and "
                       "drops the face)",
                       f->path, f->line, f->word);
  } else if ((uint64_t)w <= f->k && v >= f->nv) {
    return set_error(err, ZS_ERR_PARSE,
                     "%s:%d: face corner '%s': expected a vertex index below %llu, the "
                     "header's vertex count",
                     f->path, f->line, f->word, (unsigned long long)f->nv);
  }
  return ZS_OK;
}

static zs_status off_end_line(off_faces *f, zs_error *err) {
  zs_status st = off_end_word(f, err);
  if (st != ZS_OK || !f->in_line) return st;
  if (off_in_faces(f)) {
    if (f->words == 0)
      return set_error(err, ZS_ERR_PARSE, "%s:%d: a blank line where a face was expected",
                       f->path, f->line);
    if ((uint64_t)f->words - 1 < f->k)
      return set_error(err, ZS_ERR_PARSE, "%s:%d: a face of %llu corners lists %d", f->path,
                       f->line, (unsigned long long)f->k, f->words - 1);
  }
  f->lines++;
  f->words = f->in_line = 0;
  return ZS_OK;
}

static zs_status take_face_lines(void *user, const char *b, size_t n, int *more, zs_error *err) {
  off_faces *f = user;
  zs_status st = ZS_OK;
  for (size_t i = 0; i < n && st == ZS_OK && f->lines < f->nv + f->nf; i++) {
    const char c = b[i];
    if (c == '\n' || c == '\r' || c == '\f' || c == '\0') {
      st = off_end_line(f, err);
      f->line += c == '\n';
    } else if (c == ' ' || c == '\t') {
      f->in_line = 1;
      st = off_end_word(f, err);
    } else {
      f->in_line = 1;
      if (f->n < sizeof f->word) f->word[f->n] = c;
      f->n++;
    }
  }
  *more = f->lines < f->nv + f->nf;
  return st;
}

static zs_status check_off_faces(const char *path, uint64_t body, int first_line, uint64_t nv,
                                 uint64_t nf, zs_error *err) {
  off_faces f = {path, nv, nf, 0, first_line, {0}, 0, 0, 0, 0};
  zs_status st = read_from(path, body, take_face_lines, &f, err);
  return st == ZS_OK ? off_end_line(&f, err) : st; /* the file's last line */
}

/* The lines of a text PLY body against its header: an element instance a
 * line (blank lines skipped), each with as many values as its properties
 * take (a list: its count, then that many).  assimp's reader takes a
 * missing value as 0 and stops quietly where the file does, so a file cut
 * short, or a face "3 0 1", rendered another mesh. */
typedef struct ply_lines {
  const char *path;
  const ply_layout *lay;
  int el;          /* the element of this line; lay->n: past the last */
  uint64_t done;   /* instances of it read */
  uint64_t seen, total; /* instances of all elements */
  int line;
  char word[24];
  size_t n;
  int prop;        /* the property the next value is for */
  uint64_t items;  /* list items still due */
  int in_line;     /* a value seen on this line */
} ply_lines;

static zs_status ply_end_word(ply_lines *p, zs_error *err) {
  if (p->n == 0 || p->el >= p->lay->n) return p->n = 0, ZS_OK;
  const size_t len = p->n;
  p->word[len < sizeof p->word ? len : sizeof p->word - 1] = '\0';
  p->n = 0;
  p->in_line = 1;
  const int props = p->lay->e[p->el].props;
  if (p->items > 0) return p->items--, ZS_OK;
  if (p->prop == props)
    return set_error(err, ZS_ERR_PARSE, "%s:%d: %s %llu: more values than its %d properties take",
                     p->path, p->line, p->lay->e[p->el].name, (unsigned long long)p->done, props);
  if (p->lay->e[p->el].lists >> p->prop & 1u) {
    const char *c = p->word;
    if (!read_count(&c, &p->items) || *c || len >= sizeof p->word)
      return set_error(err, ZS_ERR_PARSE, "%s:%d: %s %llu: '%s': expected a list's count",
                       p->path, p->line, p->lay->e[p->el].name, (unsigned long long)p->done,
                       p->word);
  }
  p->prop++;
  return ZS_OK;
}

static zs_status ply_end_line(ply_lines *p, zs_error *err) {
  zs_status st = ply_end_word(p, err);
  if (st != ZS_OK || !p->in_line) return st;
  const int props = p->lay->e[p->el].props;
  if (p->prop < props || p->items > 0)
    return set_error(err, ZS_ERR_PARSE, "%s:%d: %s %llu: fewer values than its %d properties take",
                     p->path, p->line, p->lay->e[p->el].name, (unsigned long long)p->done, props);
  p->prop = 0;
  p->in_line = 0;
  p->seen++;
  if (++p->done == p->lay->e[p->el].count)
    for (p->done = 0, p->el++; p->el < p->lay->n && p->lay->e[p->el].count == 0;) p->el++;
  return ZS_OK;
}

static zs_status take_ply_lines(void *user, const char *b, size_t n, int *more, zs_error *err) {
  ply_lines *p = user;
  zs_status st = ZS_OK;
  for (size_t i = 0; i < n && st == ZS_OK && p->el < p->lay->n; i++) {
    const char c = b[i];
    if (c == '\n' || c == '\r') {
      st = ply_end_line(p, err);
      p->line += c == '\n';
    } else if (is_blank(c)) {
      st = ply_end_word(p, err);
    } else {
      if (p->n < sizeof p->word) p->word[p->n] = c;
      p->n++;
    }
  }
  *more = p->el < p->lay->n;
  return st;
}

static zs_status check_ply_lines(const char *path, uint64_t body, int first_line,
                                 const ply_layout *lay, zs_error *err) {
  ply_lines p = {path, lay, 0, 0, 0, 0, first_line, {0}, 0, 0, 0, 0};
  for (int k = 0; k < lay->n; k++) p.total = sat_add(p.total, lay->e[k].count);
  while (p.el < lay->n && lay->e[p.el].count == 0) p.el++;
  zs_status st = read_from(path, body, take_ply_lines, &p, err);
  if (st == ZS_OK && p.el < lay->n) st = ply_end_line(&p, err); /* the last line */
  if (st == ZS_OK && p.el < lay->n)
    st = set_error(err, ZS_ERR_PARSE,
                   "%s: cut short: %llu of the %llu element lines the header declares (%s %llu "
                   "of %llu)",
                   path, (unsigned long long)p.seen, (unsigned long long)p.total,
                   lay->e[p.el].name, (unsigned long long)p.done,
                   (unsigned long long)lay->e[p.el].count);
  return st;
}

/* The lines of the first n bytes of t. */
static int header_lines(const char *t, uint64_t n) {
  int lines = 0;
  for (uint64_t i = 0; i < n && t[i]; i++) lines += t[i] == '\n';
  return lines;
}

/* An STL file in text: "solid" first and no NUL byte in what was read
 * (a binary STL's 80-byte header may begin "solid" too, its counts and
 * floats hold zero bytes). */
static int is_ascii_stl(const file_head *h) {
  const char *t = h->text;
  while (is_blank(*t)) t++;
  return strncmp(t, "solid", 5) == 0 && strlen(h->text) == h->len;
}

/* Refuses an OFF or PLY file whose header declares more than it holds,
 * and a text PLY, OFF or STL file with a number that is not finite. */
static zs_status check_header(const char *path, const file_head *h, zs_error *err) {
  uint64_t nv, nf, need, body;
  ply_layout lay = {0};
  int cut = 0, nul = 0, bad_line = 0;
  if (off_counts(h->text, has_extension(path, ".off"), &nv, &nf, &body)) {
    /* every vertex and face line takes at least two bytes */
    if (sat_mul(sat_add(nv, nf), 2) > h->size)
      return set_error(err, ZS_ERR_PARSE,
                       "%s: OFF header declares %llu vertices and %llu faces, more than "
                       "the file's %llu bytes can hold",
                       path, (unsigned long long)nv, (unsigned long long)nf,
                       (unsigned long long)h->size);
    zs_status st = check_text_numbers(path, 0, 1, 0, 1, err);
    return st == ZS_OK ? check_off_faces(path, body, header_lines(h->text, body) + 1, nv, nf, err)
                       : st;
  } else if (ply_min_bytes(h->text, h->len, has_extension(path, ".ply"), &need, &body, &cut, &nul,
                           &bad_line, &lay)) {
    if (bad_line == 1)
      return set_error(err, ZS_ERR_PARSE, "%s: not a PLY file (its first line is not \"ply\")",
                       path);
    if (bad_line)
      return set_error(err, ZS_ERR_PARSE, "%s:%d: not a line of a PLY header", path, bad_line);
    /* (assimp 5.2's reader can loop without end on one) */
    if (nul) return set_error(err, ZS_ERR_PARSE, "%s: PLY header holds a NUL byte", path);
    if (cut && h->len == h->size)
      return set_error(err, ZS_ERR_PARSE, "%s: PLY header without an end_header line", path);
    if (need > h->size - body)
      return set_error(err, ZS_ERR_PARSE,
                       "%s: PLY header declares elements of at least %llu bytes, more than "
                       "the file's %llu bytes after the header",
                       path, (unsigned long long)need, (unsigned long long)(h->size - body));
    if (strstr(h->text, "\nformat ascii")) {
      const int first = header_lines(h->text, body) + 1;
      zs_status st = check_text_numbers(path, body, 0, 0, first, err);
      return st == ZS_OK && lay.n > 0 ? check_ply_lines(path, body, first, &lay, err) : st;
    }
  } else if (has_extension(path, ".stl") && is_ascii_stl(h)) {
    return check_text_numbers(path, 0, 0, 1, 1, err);
  }
  return ZS_OK;
}

/* ---- the scene -------------------------------------------------------- */

/* A texture made once for every material that names it: key is the
 * file's path as opened, or "*N" for embedded texture N. */
typedef struct tex_entry {
  char *key;
  const zs_texture *tex; /* owned by the model; NULL: skipped */
} tex_entry;

typedef struct loader {
  const char *path;
  const struct aiScene *scene;
  zs_model *m;
  int64_t vertices, faces; /* added so far */
  zs_error *err;
  char *dir;               /* the model's folder, for texture files */
  int32_t *material;       /* per assimp material: its model material, -1 until used */
  tex_entry *tex;
  int32_t ntex, cap_tex;
  int need_normals;        /* a mesh has colours or uvs but no normals */
  int flags;               /* ZS_ASSIMP_* */
  int point_cloud;         /* read without assimp's validation (a mesh without faces) */
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

/* ---- materials and textures ------------------------------------------ */

static zs_wrap wrap_mode(enum aiTextureMapMode m) {
  switch (m) {
  case aiTextureMapMode_Clamp:
  case aiTextureMapMode_Decal: return ZS_WRAP_CLAMP; /* (a border zscan does not have) */
  case aiTextureMapMode_Mirror: return ZS_WRAP_MIRROR;
  default: return ZS_WRAP_REPEAT;
  }
}

/* glTF's sampler filters (the GL enums), as assimp passes them on: the
 * minification filter decides, as that is where the three differ; a
 * magnification filter alone only when it asks for nearest texels. */
enum {
  GLTF_NEAREST = 9728,
  GLTF_LINEAR = 9729,
  GLTF_NEAREST_MIPMAP_NEAREST = 9984,
  GLTF_LINEAR_MIPMAP_NEAREST = 9985,
  GLTF_NEAREST_MIPMAP_LINEAR = 9986,
  GLTF_LINEAR_MIPMAP_LINEAR = 9987
};

static zs_filter texture_filter(const struct aiMaterial *mat, enum aiTextureType type) {
#ifndef AI_MATKEY_GLTF_MAPPINGFILTER_MIN
  (void)mat;
  (void)type;
  return ZS_FILTER_DEFAULT;
#else
  int min = 0, mag = 0;
  if (aiGetMaterialIntegerArray(mat, AI_MATKEY_GLTF_MAPPINGFILTER_MIN(type, 0), &min, NULL) ==
      aiReturn_SUCCESS) {
    switch (min) {
    case GLTF_NEAREST:
    case GLTF_NEAREST_MIPMAP_NEAREST: return ZS_FILTER_NEAREST;
    case GLTF_LINEAR:
    case GLTF_LINEAR_MIPMAP_NEAREST: return ZS_FILTER_BILINEAR;
    case GLTF_NEAREST_MIPMAP_LINEAR:
    case GLTF_LINEAR_MIPMAP_LINEAR: return ZS_FILTER_TRILINEAR;
    default: break;
    }
  }
  if (aiGetMaterialIntegerArray(mat, AI_MATKEY_GLTF_MAPPINGFILTER_MAG(type, 0), &mag, NULL) ==
          aiReturn_SUCCESS &&
      mag == GLTF_NEAREST)
    return ZS_FILTER_NEAREST;
  return ZS_FILTER_DEFAULT;
#endif
}

/* What follows the last '/' or '\' of a name, as assimp matches embedded
 * textures by their file names. */
static const char *short_name(const char *s) {
  const char *p = s;
  for (const char *q = s; *q; q++)
    if (*q == '/' || *q == '\\') p = q + 1;
  return p;
}

/* The embedded texture that name means ("*N", or the file name of one of
 * the scene's textures); -1 for none, -2 for "*N" out of range. */
static int embedded_index(const struct aiScene *sc, const char *name) {
  if (name[0] == '*') {
    char *end;
    errno = 0;
    unsigned long i = strtoul(name + 1, &end, 10);
    if (name[1] < '0' || name[1] > '9' || *end || errno || i >= sc->mNumTextures ||
        !sc->mTextures || !sc->mTextures[i])
      return -2;
    return (int)i;
  }
  for (unsigned i = 0; i < sc->mNumTextures; i++)
    if (sc->mTextures && sc->mTextures[i] && sc->mTextures[i]->mFilename.length &&
        strcmp(short_name(sc->mTextures[i]->mFilename.data), short_name(name)) == 0)
      return (int)i;
  return -1;
}

/* Embedded texture i: compressed bytes (PNG, JPEG) to decode, or
 * mWidth x mHeight texels of B, G, R, A. */
static zs_status embedded_texture(loader *L, int i, const char *key, zs_texture **out,
                                  zs_error *e) {
  const struct aiTexture *t = L->scene->mTextures[i];
  if (!t->pcData) return zs_error_set(e, ZS_ERR_PARSE, "%s: no texels", key);
  if (t->mHeight == 0) return zs_texture_decode(t->pcData, t->mWidth, key, out, e);
  if (t->mWidth > ZS_MAX_TEXTURE_SIDE || t->mHeight > ZS_MAX_TEXTURE_SIDE)
    return zs_error_set(e, ZS_ERR_LIMIT, "%s: %ux%u texture: each side must be 1 to %d", key,
                        t->mWidth, t->mHeight, ZS_MAX_TEXTURE_SIDE);
  size_t n = (size_t)t->mWidth * t->mHeight;
  uint8_t *rgba = malloc(4 * n);
  if (!rgba) return zs_error_set(e, ZS_ERR_NOMEM, "%s: out of memory", key);
  for (size_t k = 0; k < n; k++) {
    const struct aiTexel *p = &t->pcData[k];
    rgba[4 * k] = p->r;
    rgba[4 * k + 1] = p->g;
    rgba[4 * k + 2] = p->b;
    rgba[4 * k + 3] = p->a;
  }
  zs_status st = zs_texture_create((int)t->mWidth, (int)t->mHeight, rgba, out, e);
  free(rgba);
  return st;
}

/* The texture that a material names (a file relative to the model's
 * folder, or embedded), made on its first use and owned by the model;
 * errors read "MODEL: texture NAME: reason".  *out NULL when it is
 * skipped (ZS_ASSIMP_SKIP_MISSING_TEXTURES), with a note of the model's:
 * that message and ": drawn without it". */
static zs_status find_texture(loader *L, const char *name, const zs_texture **out) {
  *out = NULL;
  int emb = embedded_index(L->scene, name);
  if (emb == -2)
    return set_error(L->err, ZS_ERR_PARSE, "%s: texture %s: no such embedded texture", L->path,
                     name);
  char *key;
  if (emb >= 0) {
    key = malloc(24);
    if (key) snprintf(key, 24, "*%d", emb);
  } else {
    /* relative to the model's folder unless absolute (a drive letter
     * too, as written on Windows, where '\' is '/') */
    const int absolute = name[0] == '/' || name[0] == '\\' ||
                         (((name[0] | 0x20) >= 'a' && (name[0] | 0x20) <= 'z') && name[1] == ':');
    size_t dlen = absolute ? 0 : strlen(L->dir);
    int slash = dlen > 0 && L->dir[dlen - 1] != '/';
    size_t nlen = strlen(name);
    key = malloc(dlen + (size_t)slash + nlen + 1);
    if (key) {
      memcpy(key, L->dir, dlen);
      if (slash) key[dlen] = '/';
      for (size_t k = 0; k <= nlen; k++) key[dlen + slash + k] = name[k] == '\\' ? '/' : name[k];
    }
  }
  if (!key) return set_error(L->err, ZS_ERR_NOMEM, "%s: out of memory", L->path);
  for (int32_t k = 0; k < L->ntex; k++)
    if (strcmp(L->tex[k].key, key) == 0) {
      free(key);
      *out = L->tex[k].tex;
      return ZS_OK;
    }
  zs_error e;
  zs_error_clear(&e);
  zs_texture *t = NULL;
  zs_status st = emb >= 0 ? embedded_texture(L, emb, key, &t, &e) : zs_texture_load(key, &t, &e);
  /* only a file that cannot be opened or read is skipped: a corrupt
   * image is there to be fixed */
  if (st == ZS_ERR_IO && (L->flags & ZS_ASSIMP_SKIP_MISSING_TEXTURES)) {
    if (!zs_notes_add(&L->m->notes, "%s: texture %s: drawn without it", L->path, e.msg)) {
      free(key);
      return set_error(L->err, ZS_ERR_NOMEM, "%s: out of memory", L->path);
    }
    st = ZS_OK; /* t stays NULL: the entry below remembers the skip */
  }
  if (st != ZS_OK) {
    free(key);
    return set_error(L->err, st, "%s: texture %s", L->path, e.msg);
  }
  if (!zs_grow((void **)&L->tex, &L->cap_tex, (int64_t)L->ntex + 1, sizeof *L->tex)) {
    zs_texture_destroy(t);
    free(key);
    return set_error(L->err, ZS_ERR_NOMEM, "%s: out of memory", L->path);
  }
  if (t && !zs_model_own_texture(L->m, t)) { /* (which destroyed t) */
    free(key);
    return set_error(L->err, ZS_ERR_NOMEM, "%s: out of memory", L->path);
  }
  L->tex[L->ntex].key = key;
  L->tex[L->ntex].tex = t;
  L->ntex++;
  *out = t;
  return ZS_OK;
}

static uint16_t shininess(float s) {
  if (!(s > 0.0f)) return 0; /* NaN too */
  return s >= (float)ZS_MAX_SHININESS ? ZS_MAX_SHININESS : (uint16_t)lround(s);
}

/* The model material of assimp material mi, made on its first use; -1
 * for a mesh without one. */
static zs_status find_material(loader *L, unsigned mi, int32_t *out) {
  *out = -1;
  const struct aiScene *sc = L->scene;
  if (mi >= sc->mNumMaterials || !sc->mMaterials || !sc->mMaterials[mi]) return ZS_OK;
  if (L->material[mi] >= 0) {
    *out = L->material[mi];
    return ZS_OK;
  }
  const struct aiMaterial *mat = sc->mMaterials[mi];
  zs_material zm = zs_material_default();
  struct aiColor4D c;
  /* the base colour: glTF's, else the diffuse one; its alpha, unless
   * the material gives an opacity; glTF's OPAQUE mode ignores alpha */
  if (aiGetMaterialColor(mat, AI_MATKEY_BASE_COLOR, &c) == aiReturn_SUCCESS ||
      aiGetMaterialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &c) == aiReturn_SUCCESS) {
    zm.base[0] = (uint8_t)channel(c.r);
    zm.base[1] = (uint8_t)channel(c.g);
    zm.base[2] = (uint8_t)channel(c.b);
    zm.base[3] = (uint8_t)channel(c.a);
  }
  ai_real f;
  if (aiGetMaterialFloatArray(mat, AI_MATKEY_OPACITY, &f, NULL) == aiReturn_SUCCESS)
    zm.base[3] = (uint8_t)channel(f);
#ifdef AI_MATKEY_GLTF_ALPHAMODE
  struct aiString mode;
  if (aiGetMaterialString(mat, AI_MATKEY_GLTF_ALPHAMODE, &mode) == aiReturn_SUCCESS &&
      strcmp(mode.data, "OPAQUE") == 0) {
    zm.base[3] = 255;
    zm.ignore_alpha = 1; /* the texture's and the vertex colours' too */
  } else if (strcmp(mode.data, "MASK") == 0) {
    /* the least 8-bit alpha a that passes a / 255 >= c in float, as a GPU
     * compares it; a cut-off that 0 passes keeps every pixel (opaque) */
    ai_real cut = 0.5;
    aiGetMaterialFloatArray(mat, AI_MATKEY_GLTF_ALPHACUTOFF, &cut, NULL);
    int a = 0;
    for (; a < 255; a++) {
      const float alpha = (float)a / 255.0f; /* rounded to float here, on every target */
      if (alpha >= (float)cut) break;
    }
    if (a == 0) zm.ignore_alpha = 1;
    else zm.alpha_cutoff = (uint8_t)a;
  }
#endif
  /* a highlight: its colour (times its strength) and exponent; none at
   * shininess 0, which assimp defines as Gouraud shading, or when the
   * shading model says so */
  int model = 0;
  ai_real shine = 0.0f, strength = 1.0f;
  int shaded =
      aiGetMaterialIntegerArray(mat, AI_MATKEY_SHADING_MODEL, &model, NULL) != aiReturn_SUCCESS ||
      !(model == aiShadingMode_Flat || model == aiShadingMode_Gouraud ||
        model == aiShadingMode_NoShading);
  if (aiGetMaterialFloatArray(mat, AI_MATKEY_SHININESS, &shine, NULL) == aiReturn_SUCCESS &&
      shaded && shininess(shine) > 0 &&
      aiGetMaterialColor(mat, AI_MATKEY_COLOR_SPECULAR, &c) == aiReturn_SUCCESS) {
    if (aiGetMaterialFloatArray(mat, AI_MATKEY_SHININESS_STRENGTH, &strength, NULL) !=
        aiReturn_SUCCESS)
      strength = 1.0f;
    zm.specular[0] = (uint8_t)channel(c.r * strength);
    zm.specular[1] = (uint8_t)channel(c.g * strength);
    zm.specular[2] = (uint8_t)channel(c.b * strength);
    zm.shininess = shininess(shine);
  }
  if (aiGetMaterialColor(mat, AI_MATKEY_COLOR_EMISSIVE, &c) == aiReturn_SUCCESS) {
    zm.emissive[0] = (uint8_t)channel(c.r);
    zm.emissive[1] = (uint8_t)channel(c.g);
    zm.emissive[2] = (uint8_t)channel(c.b);
  }
  int two = 0;
  if (aiGetMaterialIntegerArray(mat, AI_MATKEY_TWOSIDED, &two, NULL) == aiReturn_SUCCESS)
    zm.double_sided = two != 0;
  /* the base colour's texture: glTF's, else the diffuse one */
  static const enum aiTextureType types[] = {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE};
  for (int k = 0; k < 2; k++) {
    struct aiString file;
    enum aiTextureMapMode wrap[2] = {aiTextureMapMode_Wrap, aiTextureMapMode_Wrap};
    if (aiGetMaterialTextureCount(mat, types[k]) == 0 ||
        aiGetMaterialTexture(mat, types[k], 0, &file, NULL, NULL, NULL, NULL, wrap, NULL) !=
            aiReturn_SUCCESS ||
        file.length == 0)
      continue;
    /* the name assimp's MD2 reader gives a model without a skin */
    if (strcmp(file.data, "$texture_dummy.bmp") == 0) break;
    zs_status st = find_texture(L, file.data, &zm.base_texture);
    if (st != ZS_OK) return st;
    zm.wrap_s = wrap_mode(wrap[0]);
    zm.wrap_t = wrap_mode(wrap[1]);
    zm.filter = texture_filter(mat, types[k]);
    break;
  }
  int32_t idx = zs_model_add_material(L->m, &zm);
  if (idx < 0) return set_error(L->err, ZS_ERR_NOMEM, "%s: out of memory", L->path);
  L->material[mi] = idx;
  *out = idx;
  return ZS_OK;
}

/* ---- meshes ----------------------------------------------------------- */

/* The normal matrix of the transform xf: its 3 x 3 cofactors, signed by
 * its determinant (the inverse transpose up to a positive factor); 0
 * when xf's 3 x 3 is the identity, whose normals are copied as they are. */
static int normal_matrix(const double xf[16], double n[9]) {
  const double a = xf[0], b = xf[1], c = xf[2], d = xf[4], e = xf[5], f = xf[6], g = xf[8],
               h = xf[9], i = xf[10];
  if (a == 1 && b == 0 && c == 0 && d == 0 && e == 1 && f == 0 && g == 0 && h == 0 && i == 1)
    return 0;
  const double co[9] = {e * i - f * h, f * g - d * i, d * h - e * g,
                        c * h - b * i, a * i - c * g, b * g - a * h,
                        b * f - c * e, c * d - a * f, a * e - b * d};
  const double det = a * co[0] + b * co[1] + c * co[2];
  for (int k = 0; k < 9; k++) n[k] = det < 0 ? -co[k] : co[k];
  return 1;
}

/* Vertex v's normal (finite) placed by the normal matrix nm (NULL: as it
 * is), of unit length; (0, 0, 0), none, when it has no length (or its
 * length overflows). */
static void place_normal(const struct aiVector3D *in, const double *nm, float out[3]) {
  double p[3] = {in->x, in->y, in->z}, q[3];
  for (int r = 0; r < 3; r++)
    q[r] = nm ? nm[3 * r] * p[0] + nm[3 * r + 1] * p[1] + nm[3 * r + 2] * p[2] : p[r];
  const double len2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
  if (!isfinite(len2) || !(len2 > 0.0)) {
    out[0] = out[1] = out[2] = 0.0f;
    return;
  }
  const double len = nm ? sqrt(len2) : 1.0;
  for (int r = 0; r < 3; r++) out[r] = (float)(q[r] / len);
}

/* One attribute vertex per vertex of the mesh, from its normals, first
 * colours and first texture coordinates (those it has). */
static zs_status add_attrs(loader *L, const struct aiMesh *mesh, unsigned mi, const double xf[16]) {
  const struct aiVector3D *nrm = mesh->mNormals, *uvs = mesh->mTextureCoords[0];
  const struct aiColor4D *col = mesh->mColors[0];
  double nm[9];
  const int turn = normal_matrix(xf, nm);
  if (!nrm) L->need_normals = 1;
  for (unsigned v = 0; v < mesh->mNumVertices; v++) {
    float n[3], uv[2];
    uint8_t rgba[4];
    if (nrm) {
      if (!isfinite(nrm[v].x) || !isfinite(nrm[v].y) || !isfinite(nrm[v].z))
        return set_error(L->err, ZS_ERR_PARSE, "%s: mesh %u vertex %u: normal not a finite number",
                         L->path, mi, v);
      place_normal(&nrm[v], turn ? nm : NULL, n);
      if (n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f) L->need_normals = 1;
    }
    if (col) {
      if (!isfinite(col[v].r) || !isfinite(col[v].g) || !isfinite(col[v].b) ||
          !isfinite(col[v].a))
        return set_error(L->err, ZS_ERR_PARSE, "%s: mesh %u vertex %u: colour not a finite number",
                         L->path, mi, v);
      rgba[0] = (uint8_t)channel(col[v].r);
      rgba[1] = (uint8_t)channel(col[v].g);
      rgba[2] = (uint8_t)channel(col[v].b);
      rgba[3] = (uint8_t)channel(col[v].a);
    }
    if (uvs) {
      /* assimp's convention is OpenGL's, v up, as zs_mesh's */
      if (!isfinite(uvs[v].x) || !isfinite(uvs[v].y))
        return set_error(L->err, ZS_ERR_PARSE,
                         "%s: mesh %u vertex %u: texture coordinate not a finite number",
                         L->path, mi, v);
      uv[0] = (float)uvs[v].x;
      uv[1] = (float)uvs[v].y;
    }
    if (zs_model_add_attr(L->m, nrm ? n : NULL, col ? rgba : NULL, uvs ? uv : NULL) < 0)
      return set_error(L->err, ZS_ERR_NOMEM, "%s: out of memory", L->path);
  }
  return ZS_OK;
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

/* The colour of a line or point from vertex v: its first colour when the
 * mesh has colours, else the mesh's material colour rgb. */
static uint32_t vertex_colour(const struct aiMesh *mesh, unsigned v, uint32_t rgb) {
  const struct aiColor4D *c = mesh->mColors[0];
  return c ? channel(c[v].r) << 16 | channel(c[v].g) << 8 | channel(c[v].b) : rgb;
}

/* The mesh's faces of one and two vertices as points and lines (glTF's
 * POINTS and LINES, a PLY's edges), each in the colour of its first
 * vertex; a mesh without faces (a point cloud, L->point_cloud) as a
 * point at each vertex. */
static zs_status add_lines_and_points(loader *L, const struct aiMesh *mesh, unsigned mi,
                                      int32_t base) {
  const uint32_t rgb = mesh_colour(L->scene, mesh);
  zs_status st = ZS_OK;
  if (mesh->mNumFaces == 0 && L->point_cloud)
    for (unsigned v = 0; v < mesh->mNumVertices && st == ZS_OK; v++)
      st = zs_model_add_point(L->m, base + (int32_t)v, vertex_colour(mesh, v, rgb));
  for (unsigned f = 0; f < mesh->mNumFaces && st == ZS_OK; f++) {
    const struct aiFace *face = &mesh->mFaces[f];
    const unsigned n = face->mNumIndices;
    if (n == 0 || n > 2) continue;
    for (unsigned k = 0; k < n; k++)
      if (face->mIndices[k] >= mesh->mNumVertices)
        return set_error(L->err, ZS_ERR_PARSE, "%s: mesh %u face %u: vertex index %u out of range",
                         L->path, mi, f, face->mIndices[k]);
    const int32_t a = base + (int32_t)face->mIndices[0];
    const uint32_t c = vertex_colour(mesh, face->mIndices[0], rgb);
    st = n == 1 ? zs_model_add_point(L->m, a, c)
                : zs_model_add_line(L->m, a, base + (int32_t)face->mIndices[1], c);
  }
  return st == ZS_OK ? ZS_OK : set_error(L->err, ZS_ERR_NOMEM, "%s: out of memory", L->path);
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
  zs_status pst = add_lines_and_points(L, mesh, mi, base);
  if (pst != ZS_OK) return pst;
  /* attributes and a material only for a mesh with polygons; attribute
   * vertices only for a mesh that has attributes, so that a file without
   * any keeps a mesh without attribute arrays */
  int polygons = 0;
  for (unsigned f = 0; f < mesh->mNumFaces && !polygons; f++)
    polygons = mesh->mFaces[f].mNumIndices >= 3;
  if (!polygons) return ZS_OK;
  int32_t abase = -1;
  if (mesh->mNormals || mesh->mColors[0] || mesh->mTextureCoords[0]) {
    abase = L->m->mesh.nattrs;
    zs_status st = add_attrs(L, mesh, mi, xf);
    if (st != ZS_OK) return st;
  }
  int32_t material;
  zs_status mst = find_material(L, mesh->mMaterialIndex, &material);
  if (mst != ZS_OK) return mst;
  uint32_t rgb = mesh_colour(L->scene, mesh);
  for (unsigned f = 0; f < mesh->mNumFaces; f++) {
    const struct aiFace *face = &mesh->mFaces[f];
    if (face->mNumIndices < 3) continue; /* a point or a line */
    if (face->mNumIndices > INT32_MAX / sizeof(int32_t))
      return set_error(L->err, ZS_ERR_LIMIT, "%s: mesh %u face %u: %u vertices", L->path, mi, f,
                       face->mNumIndices);
    /* a face may have any number of corners: the model splits it */
    /* (positions and attributes in one array: idx, then attr) */
    int32_t small[2 * ZS_MAX_POLY_VERTS];
    const unsigned n = face->mNumIndices;
    int32_t *idx = n <= ZS_MAX_POLY_VERTS ? small : malloc(2 * (size_t)n * sizeof *idx);
    if (!idx) return set_error(L->err, ZS_ERR_NOMEM, "%s: out of memory", L->path);
    int32_t *attr = abase >= 0 ? idx + n : NULL;
    zs_status st = ZS_OK;
    for (unsigned k = 0; k < n && st == ZS_OK; k++) {
      if (face->mIndices[k] >= mesh->mNumVertices)
        st = set_error(L->err, ZS_ERR_PARSE, "%s: mesh %u face %u: vertex index %u out of range",
                       L->path, mi, f, face->mIndices[k]);
      idx[k] = base + (int32_t)face->mIndices[k];
      if (attr) attr[k] = abase + (int32_t)face->mIndices[k];
    }
    if (st == ZS_OK &&
        zs_model_add_face(L->m, idx, attr, (int)n, rgb, material, obj) != ZS_OK)
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
  return zs_assimp_load_flags(path, 0, out, err);
}

/* Each mesh's primitive types as its faces have them, or an error for a
 * face without a vertex.  A reader can set a type no face has (assimp
 * 5.2's PLY reader on a malformed face line sets "polygon" and leaves
 * the face empty), and aiProcess_Triangulate asserts (abort()) on a mesh
 * that claims polygons and has none. */
static zs_status settle_primitive_types(const char *path, const struct aiScene *sc,
                                        zs_error *err) {
  for (unsigned i = 0; i < sc->mNumMeshes; i++) {
    struct aiMesh *m = sc->mMeshes[i];
    unsigned types = 0;
    for (unsigned f = 0; f < m->mNumFaces; f++) {
      const unsigned n = m->mFaces[f].mNumIndices;
      if (n == 0)
        return set_error(err, ZS_ERR_PARSE, "%s: mesh %u face %u: no vertices", path, i, f);
      types |= n == 1   ? aiPrimitiveType_POINT
               : n == 2 ? aiPrimitiveType_LINE
               : n == 3 ? aiPrimitiveType_TRIANGLE
                        : aiPrimitiveType_POLYGON;
    }
    m->mPrimitiveTypes = types;
  }
  return ZS_OK;
}

static int finite3(float x, float y, float z) { return isfinite(x) && isfinite(y) && isfinite(z); }

/* Refuses a vertex whose position, normal, first colour or first texture
 * coordinate is not a finite number, before the vertices are joined:
 * joining takes a NaN for the same as its neighbour (NaN compares as
 * no difference there), and a bad vertex merged away went unseen. */
static zs_status check_finite(const char *path, const struct aiScene *sc, zs_error *err) {
  for (unsigned i = 0; i < sc->mNumMeshes; i++) {
    const struct aiMesh *m = sc->mMeshes[i];
    const struct aiVector3D *p = m->mVertices, *n = m->mNormals, *uv = m->mTextureCoords[0];
    const struct aiColor4D *c = m->mColors[0];
    for (unsigned v = 0; v < m->mNumVertices; v++) {
      const char *what = !finite3(p[v].x, p[v].y, p[v].z)               ? ""
                         : n && !finite3(n[v].x, n[v].y, n[v].z)        ? "normal "
                         : c && !(finite3(c[v].r, c[v].g, c[v].b) && isfinite(c[v].a)) ? "colour "
                         : uv && !(isfinite(uv[v].x) && isfinite(uv[v].y))
                             ? "texture coordinate "
                             : NULL;
      if (what)
        return set_error(err, ZS_ERR_PARSE, "%s: mesh %u vertex %u: %snot a finite number", path,
                         i, v, what);
    }
  }
  return ZS_OK;
}

/* The file read and validated, then triangulated and its identical
 * vertices joined, as aiImportFile with all three flags does (the same
 * steps in the same order), with the primitive types settled between. */
static zs_status import_triangulated(const char *path, const struct aiScene **sc,
                                     zs_error *err) {
  zs_status st = import_checked(path, aiProcess_ValidateDataStructure, sc, err);
  if (st != ZS_OK) return st;
  if ((st = settle_primitive_types(path, *sc, err)) != ZS_OK ||
      (st = check_finite(path, *sc, err)) != ZS_OK) {
    aiReleaseImport(*sc);
    *sc = NULL;
    return st;
  }
  const struct aiScene *done =
      aiApplyPostProcessing(*sc, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
  if (!done) { /* (post-processing failed: the scene is gone) */
    *sc = NULL;
    const char *why = aiGetErrorString();
    return set_error(err, ZS_ERR_PARSE, "%s: %s", path,
                     why && *why ? why : "assimp could not process the file");
  }
  *sc = done;
  return ZS_OK;
}

zs_status zs_assimp_load_flags(const char *path, int flags, zs_model *out, zs_error *err) {
  zs_model_init(out);
  const struct aiScene *sc;
  zs_status st = import_triangulated(path, &sc, err);
  /* A point cloud (a PLY of vertices alone) is a mesh without faces,
   * which assimp's validation refuses: read it again without, and take
   * each vertex as a point (add_mesh checks what it reads itself). */
  int point_cloud = 0;
  if (st != ZS_OK && strstr(err->msg, "contains no faces")) {
    zs_error_clear(err);
    st = import_checked(path, 0, &sc, err);
    point_cloud = st == ZS_OK;
  }
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
  loader L = {path, sc, out, 0, 0, err, zs_load_dir(path), NULL, NULL, 0, 0, 0, flags, point_cloud};
  if (sc->mNumMaterials) L.material = malloc(sc->mNumMaterials * sizeof *L.material);
  if (!L.dir || (sc->mNumMaterials && !L.material)) {
    st = set_error(err, ZS_ERR_NOMEM, "%s: out of memory", path);
  } else {
    for (unsigned i = 0; i < sc->mNumMaterials; i++) L.material[i] = -1;
    double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    st = walk(&L, sc->mRootNode, identity, 0);
  }
  if (st == ZS_OK && !zs_model_drawable(out))
    st = set_error(err, ZS_ERR_PARSE, "%s: no faces, lines or points", path);
  /* zscan's own normals, the same bytes everywhere, where the file has
   * none (never assimp's aiProcess_GenNormals) */
  if (st == ZS_OK && L.need_normals && !zs_model_compute_normals(out, 60.0))
    st = set_error(err, ZS_ERR_NOMEM, "%s: out of memory", path);
  aiReleaseImport(sc);
  for (int32_t k = 0; k < L.ntex; k++) free(L.tex[k].key);
  free(L.tex);
  free(L.material);
  free(L.dir);
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
