/* Output files written under a temporary name (outfile.h). */
#include "tools/outfile.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Creates PATH.tmp.XXXXXX; *tmp receives its name (malloc'd). */
FILE *zs_out_open(const char *path, char **tmp, zs_error *err) {
  static const char suffix[] = ".tmp.XXXXXX";
  *tmp = NULL;
  if (path[0] == '\0') {
    zs_error_set(err, ZS_ERR_ARG, "cannot create a file without a name");
    return NULL;
  }
  size_t n = strlen(path);
  *tmp = malloc(n + sizeof suffix);
  if (!*tmp) {
    zs_error_set(err, ZS_ERR_NOMEM, "%s: out of memory", path);
    return NULL;
  }
  memcpy(*tmp, path, n);
  memcpy(*tmp + n, suffix, sizeof suffix);
  int fd = mkstemp(*tmp);
  FILE *f = NULL;
  if (fd >= 0) {
    mode_t mask = umask(0);
    umask(mask);
    if (fchmod(fd, 0666 & ~mask) == 0) f = fdopen(fd, "wb");
    if (!f) {
      close(fd);
      remove(*tmp);
    }
  }
  if (!f) {
    zs_error_set(err, ZS_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
    free(*tmp);
    *tmp = NULL;
  }
  return f;
}

/* Closes f and renames tmp over path (removing tmp on failure). */
zs_status zs_out_commit(FILE *f, char *tmp, const char *path, zs_error *err) {
  zs_status st = ZS_OK;
  int bad = ferror(f);
  if (fclose(f) != 0 || bad)
    st = zs_error_set(err, ZS_ERR_IO, "%s: cannot write: %s", path, strerror(errno));
  else if (rename(tmp, path) != 0)
    st = zs_error_set(err, ZS_ERR_IO, "%s: cannot replace: %s", path, strerror(errno));
  if (st) remove(tmp);
  free(tmp);
  return st;
}

void zs_out_discard(FILE *f, char *tmp) {
  fclose(f);
  remove(tmp);
  free(tmp);
}

zs_status zs_out_dir(const char *opt, const char *dir, zs_error *err) {
  if (mkdir(dir, 0777) != 0 && errno != EEXIST)
    return zs_error_set(err, ZS_ERR_IO, "%s %s: cannot create: %s", opt, dir, strerror(errno));
  return ZS_OK;
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
