/* The one output primitive (outfile.h). */
#include "lib/outfile.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "util/os.h"

enum { MAX_LINKS = 40 }; /* as the kernel's own limit on a path's links */

int zs_out_is_stdout(const char *path) { return strcmp(path, "-") == 0; }

static char *dup_n(const char *s, size_t n) {
  char *d = malloc(n + 1);
  if (d) {
    memcpy(d, s, n);
    d[n] = '\0';
  }
  return d;
}

/* Where path's directory part ends (NULL when it has none). */
static const char *last_separator(const char *path) {
  const char *last = NULL;
  for (const char *p = path; *p; p++)
    if (zs_os_is_separator(*p)) last = p;
  return last;
}

/* The directory part of path ("." when it has none; a root keeps its
 * separator: "/", "C:\\"). */
static char *dir_of(const char *path) {
  const char *sep = last_separator(path);
  if (!sep) return dup_n(".", 1);
  const size_t n = (size_t)(sep - path), root = zs_os_root_length(path);
  return dup_n(path, n < root ? root : n);
}

/* A link's text, read relative to the directory of the link itself. */
static char *link_target(const char *link, zs_error *err) {
  int e = 0;
  char *text = zs_os_readlink(link, &e);
  if (!text) {
    if (e != ENOENT && e != ENOMEM)
      zs_error_set(err, ZS_ERR_IO, "%s: cannot read the link: %s", link,
                   e == EAGAIN ? "it changed while read" : strerror(e));
    return NULL;
  }
  if (zs_os_root_length(text) > 0 || !last_separator(link)) return text;
  char *dir = dir_of(link);
  char *joined = dir ? malloc(strlen(dir) + 1 + strlen(text) + 1) : NULL;
  if (joined) sprintf(joined, "%s/%s", dir, text);
  free(dir);
  free(text);
  return joined;
}

/* Writes straight into a device, FIFO or socket. */
static zs_status open_direct(zs_out *o, const char *file, zs_path_kind kind, zs_error *err) {
  int e = 0;
  if (!(o->fp = zs_os_open_direct(file, kind, &e)))
    return zs_error_set(err, ZS_ERR_IO, "%s: cannot open: %s", o->path, strerror(e));
  return ZS_OK;
}

/* Creates the temporary beside file; mode: the permission bits it gets. */
static zs_status open_temporary(zs_out *o, const char *file, unsigned mode, zs_error *err) {
  size_t n = strlen(file), cap = n + 64;
  o->target = dup_n(file, n);
  o->tmp = malloc(cap);
  if (!o->target || !o->tmp)
    return zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", o->path);
  int e = 0;
  if ((o->fp = zs_os_create_beside(file, mode, o->tmp, cap, &e))) return ZS_OK;
  free(o->tmp);
  o->tmp = NULL;
  if (e == ENOENT || e == ENOTDIR) {
    char *dir = dir_of(file);
    zs_error_set(err, ZS_ERR_IO, "%s: no such directory: %s", o->path, dir ? dir : file);
    free(dir);
    return ZS_ERR_IO;
  }
  return zs_error_set(err, ZS_ERR_IO, "%s: cannot create: %s", o->path, strerror(e));
}

static void release(zs_out *o) {
  free(o->path);
  free(o->target);
  free(o->tmp);
  memset(o, 0, sizeof *o);
}

/* Follows path's links to the file that is written: *file (malloc'd), with
 * *st what is there (kind NONE: nothing).  Directories and block devices
 * are refused here, so a check and an open say the same. */
static zs_status resolve(const char *path, char **file, zs_path_info *st, zs_error *err) {
  *file = NULL;
  char *at = dup_n(path, strlen(path));
  if (!at) return zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", path);
  for (int links = 0;; links++) {
    int e = zs_os_lstat(at, st);
    if (e != 0) {
      zs_status code = zs_error_set(err, ZS_ERR_IO, "%s: %s", path, strerror(e));
      free(at);
      return code;
    }
    if (st->kind != ZS_PATH_LINK) break;
    char *next = links < MAX_LINKS ? link_target(at, err) : NULL;
    free(at);
    if (!next)
      return zs_error_set(err, ZS_ERR_IO, "%s: %s", path,
                          links < MAX_LINKS ? "cannot follow the link" : "too many links");
    at = next;
  }
  const char *refused = st->kind == ZS_PATH_DIR     ? "is a directory"
                        : st->kind == ZS_PATH_BLOCK ? "is a block device"
                        : st->kind == ZS_PATH_OTHER ? "is not a file"
                                                    : NULL;
  if (refused) {
    free(at);
    return zs_error_set(err, ZS_ERR_IO, "%s: %s", path, refused);
  }
  *file = at;
  return ZS_OK;
}

zs_status zs_out_check(const char *path, zs_error *err) {
  if (path[0] == '\0') return zs_error_set(err, ZS_ERR_ARG, "empty path");
  if (zs_out_is_stdout(path)) return ZS_OK;
  char *file;
  zs_path_info st;
  zs_status code = resolve(path, &file, &st, err);
  if (code != ZS_OK) return code;
  if (st.kind == ZS_PATH_NONE || st.kind == ZS_PATH_FILE) {
    /* the temporary is made beside the file: its folder must take it */
    char *dir = dir_of(file);
    zs_path_info ds;
    int e;
    if (!dir)
      code = zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", path);
    else if (zs_os_stat(dir, &ds) != 0 || ds.kind != ZS_PATH_DIR)
      code = zs_error_set(err, ZS_ERR_IO, "%s: no such directory: %s", path, dir);
    else if ((e = zs_os_dir_writable(dir)) != 0)
      code = zs_error_set(err, ZS_ERR_IO, "%s: cannot write in %s: %s", path, dir, strerror(e));
    free(dir);
  }
  free(file);
  return code;
}

zs_status zs_out_open(zs_out *o, const char *path, zs_error *err) {
  memset(o, 0, sizeof *o);
  if (path[0] == '\0') return zs_error_set(err, ZS_ERR_ARG, "cannot write a file without a name");
  if (!(o->path = dup_n(path, strlen(path))))
    return zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", path);
  if (zs_out_is_stdout(path)) {
    zs_os_binary_stream(stdout);
    o->fp = stdout;
    return ZS_OK;
  }
  char *file;
  zs_path_info st;
  zs_status code = resolve(path, &file, &st, err);
  if (code == ZS_OK) {
    if (st.kind == ZS_PATH_NONE)
      code = open_temporary(o, file, zs_os_new_file_mode(), err);
    else if (st.kind == ZS_PATH_FILE)
      code = open_temporary(o, file, st.mode, err);
    else
      code = open_direct(o, file, st.kind, err);
    free(file);
  }
  if (code != ZS_OK) {
    if (o->fp) fclose(o->fp);
    release(o);
  }
  return code;
}

/* Flushes and closes o's stream (standard output stays open): a write
 * that failed, or a full disk, is an error. */
static zs_status close_checked(zs_out *o, zs_error *err) {
  const char *name = o->fp == stdout ? "standard output" : o->path;
  /* fflush first: a full disk shows only when the buffer goes out. */
  int bad = fflush(o->fp) != 0 || ferror(o->fp);
  int e = errno;
  if (o->fp != stdout && fclose(o->fp) != 0 && !bad) {
    bad = 1;
    e = errno;
  }
  o->fp = NULL;
  return bad ? zs_error_set(err, ZS_ERR_IO, "%s: cannot write: %s", name, strerror(e)) : ZS_OK;
}

/* Renames the closed o's temporary over its target (nothing for a direct
 * output), then empties o; on any failure the temporary is removed. */
static zs_status replace_and_release(zs_out *o, zs_status st, zs_error *err) {
  int e;
  if (st == ZS_OK && o->tmp && (e = zs_os_replace(o->tmp, o->target)) != 0)
    st = zs_error_set(err, ZS_ERR_IO, "%s: cannot replace: %s", o->path, strerror(e));
  else if (st == ZS_OK && o->tmp) {
    free(o->tmp); /* renamed: nothing to remove */
    o->tmp = NULL;
  }
  if (o->tmp) remove(o->tmp);
  release(o);
  return st;
}

zs_status zs_out_commit(zs_out *o, zs_error *err) {
  if (!o->fp) {
    release(o);
    return zs_error_set(err, ZS_ERR_IO, "output already closed");
  }
  return replace_and_release(o, close_checked(o, err), err);
}

zs_status zs_out_finish(zs_out *o, zs_out_set *set, zs_error *err) {
  if (!set || !o->fp || !o->tmp) return zs_out_commit(o, err);
  if (set->n == ZS_OUT_SET_MAX) {
    zs_out_discard(o);
    return zs_error_set(err, ZS_ERR_ARG, "more than %d outputs at once", ZS_OUT_SET_MAX);
  }
  zs_status st = close_checked(o, err);
  if (st != ZS_OK) return replace_and_release(o, st, err);
  set->held[set->n++] = *o;
  memset(o, 0, sizeof *o);
  return ZS_OK;
}

zs_status zs_out_set_land(zs_out_set *set, zs_error *err) {
  zs_status st = ZS_OK;
  for (int k = 0; k < set->n; k++) /* after a failure the rest are removed */
    st = replace_and_release(&set->held[k], st, err);
  set->n = 0;
  return st;
}

void zs_out_set_drop(zs_out_set *set) {
  for (int k = 0; k < set->n; k++) zs_out_discard(&set->held[k]);
  set->n = 0;
}

void zs_out_discard(zs_out *o) {
  if (o->fp && o->fp != stdout) fclose(o->fp);
  if (o->fp == stdout) fflush(stdout);
  if (o->tmp) remove(o->tmp);
  release(o);
}

zs_status zs_out_report(const char *const *outs, int n, const char *opts, FILE **report,
                        zs_error *err) {
  int to_stdout = 0;
  for (int k = 0; k < n; k++) to_stdout += outs[k] && zs_out_is_stdout(outs[k]);
  *report = to_stdout ? stderr : stdout;
  if (to_stdout > 1)
    return zs_error_set(err, ZS_ERR_ARG,
                        "standard output (-) takes one stream: only one of %s can be -", opts);
  return ZS_OK;
}

zs_status zs_out_error_option(zs_error *err, const char *opt) {
  size_t n = strlen(opt);
  if (!err || err->code == ZS_OK || strncmp(err->msg, opt, n) == 0) return err ? err->code : ZS_OK;
  /* shift the message right by the option and a space, cut at the end */
  size_t len = strlen(err->msg), room = sizeof err->msg - 1;
  if (n + 1 >= room) return err->code;
  if (len > room - n - 1) len = room - n - 1;
  memmove(err->msg + n + 1, err->msg, len);
  memcpy(err->msg, opt, n);
  err->msg[n] = ' ';
  err->msg[n + 1 + len] = '\0';
  return err->code;
}

zs_status zs_out_dir(const char *opt, const char *dir, zs_error *err) {
  if (dir[0] == '\0') return zs_error_set(err, ZS_ERR_ARG, "%s: needs a directory", opt);
  char *path = dup_n(dir, strlen(dir));
  if (!path) return zs_error_set(err, ZS_ERR_NOMEM, "%s %s: out of memory", opt, dir);
  /* mkdir -p: each parent after the root, then the directory itself */
  zs_status st = ZS_OK;
  const size_t root = zs_os_root_length(path);
  for (char *p = path + (root > 1 ? root : 1);; p++) {
    if (!zs_os_is_separator(*p) && *p != '\0') continue;
    char c = *p;
    *p = '\0';
    zs_path_info sb;
    int e = zs_os_stat(path, &sb) == 0 && sb.kind == ZS_PATH_DIR ? 0 : zs_os_mkdir(path);
    if (e != 0 && e != EEXIST)
      st = zs_error_set(err, ZS_ERR_IO, "%s %s: cannot create %s: %s", opt, dir, path, strerror(e));
    else if (zs_os_stat(path, &sb) != 0 || sb.kind != ZS_PATH_DIR)
      st = c == '\0' ? zs_error_set(err, ZS_ERR_IO, "%s %s: not a directory", opt, dir)
                     : zs_error_set(err, ZS_ERR_IO, "%s %s: %s is not a directory", opt, dir, path);
    *p = c;
    if (st != ZS_OK || c == '\0') break;
  }
  free(path);
  return st;
}

zs_status zs_append_file(FILE *f, const char *path, zs_error *err) {
  FILE *in = fopen(path, "rb");
  if (!in) return zs_error_set(err, ZS_ERR_IO, "%s: cannot read: %s", path, strerror(errno));
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, in)) > 0) fwrite(buf, 1, n, f);
  fclose(in);
  return ZS_OK;
}
