/* What the file loaders share.  See load_common.h. */
#include "scene/load_common.h"

#include "util/os.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

zs_status zs_load_verror(zs_error *err, zs_status code, int trim, const char *prefix,
                         const char *fmt, va_list ap) {
  char msg[ZS_ERROR_MSG_MAX];
  int plen = snprintf(msg, sizeof msg, "%s", prefix ? prefix : "");
  if (plen >= 0 && (size_t)plen < sizeof msg)
    vsnprintf(msg + plen, sizeof msg - (size_t)plen, fmt, ap);
  size_t n = strlen(msg);
  for (size_t i = 0; i < n; i++)
    if ((unsigned char)msg[i] < 0x20 || msg[i] == 0x7f) msg[i] = ' ';
  while (trim && n > 0 && msg[n - 1] == ' ') msg[--n] = '\0';
  return zs_error_set(err, code, "%s", msg);
}

zs_status zs_load_error(zs_error *err, zs_status code, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  zs_status st = zs_load_verror(err, code, 0, NULL, fmt, ap);
  va_end(ap);
  return st;
}

/* Opens path and checks it against the flags (see zs_load_file); *st is
 * what the file is (kind NONE when a pipe's could not be had).  *f stays
 * NULL on failure, and for a missing file that may be missing. */
static zs_status open_checked(const char *path, const char *shown, long long max_bytes,
                              int flags, FILE **f, zs_path_info *st, zs_error *err) {
  int regular_only = (flags & ZS_LOAD_REGULAR_ONLY) != 0;
  *f = fopen(path, "rb");
  if (!*f && (flags & ZS_LOAD_MISSING_OK)) return ZS_OK;
  if (!*f) return zs_load_error(err, ZS_ERR_IO, "%s: cannot open: %s", shown, strerror(errno));
  zs_status res = ZS_OK;
  int e = zs_os_fstat(*f, st);
  if (e != 0) {
    if (regular_only) res = zs_load_error(err, ZS_ERR_IO, "%s: cannot open: %s", shown, strerror(e));
  } else if (regular_only && st->kind != ZS_PATH_FILE) {
    res = zs_load_error(err, ZS_ERR_IO, "%s: not a regular file", shown);
  }
  /* a regular file says its size: refuse it before allocating anything */
  if (res == ZS_OK && st->kind == ZS_PATH_FILE && st->size > max_bytes)
    res = zs_load_error(err, ZS_ERR_LIMIT, "%s: larger than %lld MiB", shown, max_bytes >> 20);
  if (res != ZS_OK) {
    fclose(*f);
    *f = NULL;
  }
  return res;
}

/* Reads f into *buf (capacity *cap, room for a NUL beyond it) to its end,
 * doubling *cap while there is more, up to max_bytes; without grow, once.
 * File bytes, not elements: the limit is max_bytes, not zs_grow's. */
static zs_status read_all(FILE *f, const char *shown, long long max_bytes, int grow, char **buf,
                          size_t *cap, size_t *n, zs_error *err) {
  for (;;) {
    *n += fread(*buf + *n, 1, *cap - *n, f);
    if (ferror(f))
      return zs_load_error(err, ZS_ERR_IO, "%s: read error: %s", shown, strerror(errno));
    if (feof(f) || !grow) return ZS_OK;
    if (*cap >= (size_t)max_bytes) /* a pipe that goes on and on */
      return zs_load_error(err, ZS_ERR_LIMIT, "%s: larger than %lld MiB", shown, max_bytes >> 20);
    char *bigger = realloc(*buf, 2 * *cap + 1);
    if (!bigger) return zs_load_error(err, ZS_ERR_NOMEM, "%s: out of memory", shown);
    *buf = bigger;
    *cap *= 2;
  }
}

zs_status zs_load_file(const char *path, const char *shown, long long max_bytes, int flags,
                       char **data, size_t *len, zs_error *err) {
  *data = NULL;
  *len = 0;
  int regular_only = (flags & ZS_LOAD_REGULAR_ONLY) != 0;
  FILE *f;
  zs_path_info st;
  zs_status res = open_checked(path, shown, max_bytes, flags, &f, &st, err);
  if (res != ZS_OK || !f) return res;
  /* A regular file: one byte more than its size, so that one that grew is
   * noticed; else chunks, doubling. */
  size_t cap = regular_only ? (size_t)st.size + 1 : (size_t)1 << 16, n = 0;
  char *buf = malloc(cap + 1);
  if (!buf) res = zs_load_error(err, ZS_ERR_NOMEM, "%s: out of memory", shown);
  else res = read_all(f, shown, max_bytes, !regular_only, &buf, &cap, &n, err);
  if (res == ZS_OK && regular_only && n > (size_t)st.size)
    res = zs_load_error(err, ZS_ERR_IO, "%s: changed while being read", shown);
  fclose(f);
  if (res != ZS_OK) {
    free(buf);
    return res;
  }
  buf[n] = '\0';
  *data = buf;
  *len = n;
  return ZS_OK;
}

zs_status zs_load_head(const char *path, long long max_bytes, char *buf, size_t cap,
                       size_t *len, uint64_t *size, zs_error *err) {
  FILE *f;
  zs_path_info st;
  zs_status res = open_checked(path, path, max_bytes, ZS_LOAD_REGULAR_ONLY, &f, &st, err);
  if (res != ZS_OK) return res;
  *size = (uint64_t)st.size;
  *len = fread(buf, 1, cap, f);
  buf[*len] = '\0';
  if (ferror(f)) res = zs_load_error(err, ZS_ERR_IO, "%s: read error: %s", path, strerror(errno));
  fclose(f);
  return res;
}

char *zs_load_dir(const char *path) {
  const char *slash = strrchr(path, '/');
  size_t dlen = slash ? (size_t)(slash - path) + (slash == path) : 0;
  char *dir = malloc(dlen + 1);
  if (!dir) return NULL;
  memcpy(dir, path, dlen);
  dir[dlen] = '\0';
  return dir;
}

zs_status zs_load_parsed(const char *path, long long max_bytes, int flags, zs_load_parser parse,
                         void *out, zs_error *err) {
  char *text;
  size_t len;
  zs_status st = zs_load_file(path, path, max_bytes, flags, &text, &len, err);
  if (st != ZS_OK) return st;
  char *dir = zs_load_dir(path);
  if (!dir) st = zs_load_error(err, ZS_ERR_NOMEM, "%s: out of memory", path);
  else st = parse(text, len, path, dir, out, err);
  free(dir);
  free(text);
  return st;
}
