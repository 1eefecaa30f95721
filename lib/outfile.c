/* The one output primitive (outfile.h). */
#include "lib/outfile.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

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

/* The directory part of path ("." when it has none). */
static char *dir_of(const char *path) {
  const char *slash = strrchr(path, '/');
  if (!slash) return dup_n(".", 1);
  return dup_n(path, slash == path ? 1 : (size_t)(slash - path));
}

/* A link's text, read relative to the directory of the link itself. */
static char *link_target(const char *link, zs_error *err) {
  struct stat st;
  if (lstat(link, &st) != 0) return NULL;
  size_t cap = st.st_size > 0 ? (size_t)st.st_size + 1 : 4096;
  char *text = malloc(cap);
  if (!text) return NULL;
  ssize_t n = readlink(link, text, cap);
  if (n < 0 || (size_t)n >= cap) {
    zs_error_set(err, ZS_ERR_IO, "%s: cannot read the link: %s", link,
                 n < 0 ? strerror(errno) : "it changed while read");
    free(text);
    return NULL;
  }
  text[n] = '\0';
  if (text[0] == '/' || !strchr(link, '/')) return text;
  char *dir = dir_of(link);
  char *joined = dir ? malloc(strlen(dir) + 1 + (size_t)n + 1) : NULL;
  if (joined) sprintf(joined, "%s/%s", dir, text);
  free(dir);
  free(text);
  return joined;
}

/* A Unix socket, connected to as a stream. */
static int open_socket(const char *path) {
  struct sockaddr_un addr;
  if (strlen(path) >= sizeof addr.sun_path) {
    errno = ENAMETOOLONG;
    return -1;
  }
  int fd = socket(AF_UNIX, SOCK_STREAM, 0);
  if (fd < 0) return -1;
  memset(&addr, 0, sizeof addr);
  addr.sun_family = AF_UNIX;
  strcpy(addr.sun_path, path);
  if (connect(fd, (const struct sockaddr *)&addr, sizeof addr) != 0) {
    int e = errno;
    close(fd);
    errno = e;
    return -1;
  }
  return fd;
}

/* Writes straight into a device, FIFO or socket. */
static zs_status open_direct(zs_out *o, const char *file, const struct stat *st, zs_error *err) {
  int fd = S_ISSOCK(st->st_mode) ? open_socket(file) : open(file, O_WRONLY | O_NOCTTY);
  if (fd >= 0 && !(o->fp = fdopen(fd, "wb"))) close(fd);
  if (!o->fp)
    return zs_error_set(err, ZS_ERR_IO, "%s: cannot open: %s", o->path, strerror(errno));
  return ZS_OK;
}

/* Creates the temporary beside file; mode: the permission bits it gets. */
static zs_status open_temporary(zs_out *o, const char *file, mode_t mode, zs_error *err) {
  static const char suffix[] = ".tmp.XXXXXX";
  size_t n = strlen(file);
  o->target = dup_n(file, n);
  o->tmp = malloc(n + sizeof suffix);
  if (!o->target || !o->tmp)
    return zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", o->path);
  memcpy(o->tmp, file, n);
  memcpy(o->tmp + n, suffix, sizeof suffix);
  int fd = mkstemp(o->tmp);
  if (fd < 0) {
    int e = errno;
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
  if (fchmod(fd, mode) != 0 || !(o->fp = fdopen(fd, "wb"))) {
    int e = errno;
    close(fd);
    remove(o->tmp);
    return zs_error_set(err, ZS_ERR_IO, "%s: cannot create: %s", o->path, strerror(e));
  }
  return ZS_OK;
}

static void release(zs_out *o) {
  free(o->path);
  free(o->target);
  free(o->tmp);
  memset(o, 0, sizeof *o);
}

/* Follows path's links to the file that is written: *file (malloc'd), with
 * *st its lstat and *exists whether it is there.  Directories and block
 * devices are refused here, so a check and an open say the same. */
static zs_status resolve(const char *path, char **file, struct stat *st, int *exists,
                         zs_error *err) {
  *file = NULL;
  *exists = 0;
  char *at = dup_n(path, strlen(path));
  if (!at) return zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", path);
  for (int links = 0;; links++) {
    if (lstat(at, st) != 0) {
      if (errno == ENOENT) break;
      zs_status code = zs_error_set(err, ZS_ERR_IO, "%s: %s", path, strerror(errno));
      free(at);
      return code;
    }
    if (!S_ISLNK(st->st_mode)) {
      *exists = 1;
      break;
    }
    char *next = links < MAX_LINKS ? link_target(at, err) : NULL;
    free(at);
    if (!next)
      return zs_error_set(err, ZS_ERR_IO, "%s: %s", path,
                          links < MAX_LINKS ? "cannot follow the link" : "too many links");
    at = next;
  }
  const char *refused = !*exists                  ? NULL
                        : S_ISDIR(st->st_mode)    ? "is a directory"
                        : S_ISBLK(st->st_mode)    ? "is a block device"
                        : S_ISREG(st->st_mode) || S_ISCHR(st->st_mode) ||
                                S_ISFIFO(st->st_mode) || S_ISSOCK(st->st_mode)
                            ? NULL
                            : "is not a file";
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
  struct stat st;
  int exists;
  zs_status code = resolve(path, &file, &st, &exists, err);
  if (code != ZS_OK) return code;
  if (!exists || S_ISREG(st.st_mode)) {
    /* the temporary is made beside the file: its folder must take it */
    char *dir = dir_of(file);
    struct stat ds;
    if (!dir)
      code = zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", path);
    else if (stat(dir, &ds) != 0 || !S_ISDIR(ds.st_mode))
      code = zs_error_set(err, ZS_ERR_IO, "%s: no such directory: %s", path, dir);
    else if (access(dir, W_OK) != 0)
      code = zs_error_set(err, ZS_ERR_IO, "%s: cannot write in %s: %s", path, dir,
                          strerror(errno));
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
    o->fp = stdout;
    return ZS_OK;
  }
  char *file;
  struct stat st;
  int exists;
  zs_status code = resolve(path, &file, &st, &exists, err);
  if (code == ZS_OK) {
    if (!exists) {
      mode_t mask = umask(0);
      umask(mask);
      code = open_temporary(o, file, 0666 & ~mask, err);
    } else if (S_ISREG(st.st_mode)) {
      code = open_temporary(o, file, st.st_mode & 07777, err);
    } else {
      code = open_direct(o, file, &st, err);
    }
    free(file);
  }
  if (code != ZS_OK) {
    if (o->fp) fclose(o->fp);
    release(o);
  }
  return code;
}

zs_status zs_out_commit(zs_out *o, zs_error *err) {
  if (!o->fp) {
    release(o);
    return zs_error_set(err, ZS_ERR_IO, "output already closed");
  }
  zs_status st = ZS_OK;
  const char *name = o->fp == stdout ? "standard output" : o->path;
  /* fflush first: a full disk shows only when the buffer goes out. */
  int bad = fflush(o->fp) != 0 || ferror(o->fp);
  int e = errno;
  if (o->fp != stdout && fclose(o->fp) != 0 && !bad) {
    bad = 1;
    e = errno;
  }
  o->fp = NULL;
  if (bad)
    st = zs_error_set(err, ZS_ERR_IO, "%s: cannot write: %s", name, strerror(e));
  else if (o->tmp && rename(o->tmp, o->target) != 0)
    st = zs_error_set(err, ZS_ERR_IO, "%s: cannot replace: %s", name, strerror(errno));
  else if (o->tmp) {
    free(o->tmp); /* renamed: nothing to remove */
    o->tmp = NULL;
  }
  if (o->tmp) remove(o->tmp);
  release(o);
  return st;
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
  /* mkdir -p: each parent, then the directory itself */
  zs_status st = ZS_OK;
  for (char *p = path + 1;; p++) {
    if (*p != '/' && *p != '\0') continue;
    char c = *p;
    *p = '\0';
    struct stat sb;
    if (mkdir(path, 0777) != 0 && errno != EEXIST)
      st = zs_error_set(err, ZS_ERR_IO, "%s %s: cannot create %s: %s", opt, dir, path,
                        strerror(errno));
    else if (stat(path, &sb) != 0 || !S_ISDIR(sb.st_mode))
      st = c == '\0' ? zs_error_set(err, ZS_ERR_IO, "%s %s: not a directory", opt, dir)
                     : zs_error_set(err, ZS_ERR_IO, "%s %s: %s is not a directory", opt, dir, path);
    *p = c;
    if (st != ZS_OK || c == '\0') break;
  }
  free(path);
  return st;
}

zs_status zs_append_file(FILE *f, const char *path, zs_error *err) {
  FILE *in = fopen(path, "r");
  if (!in) return zs_error_set(err, ZS_ERR_IO, "%s: cannot read: %s", path, strerror(errno));
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, in)) > 0) fwrite(buf, 1, n, f);
  fclose(in);
  return ZS_OK;
}
