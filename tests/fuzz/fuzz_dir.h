/* What the fuzz targets that read files share: a folder of the process's
 * own, made at the first need and emptied of the files named at exit,
 * and a file written into it whole. */
#ifndef ZS_FUZZ_DIR_H
#define ZS_FUZZ_DIR_H

#include <stdio.h>
#include <stdlib.h>

static char fuzz_dir_path[256];
static const char *const *fuzz_dir_files; /* the names removed at exit, NULL-ended */

static void fuzz_dir_remove(void) {
  for (const char *const *f = fuzz_dir_files; *f; f++) {
    char path[300];
    snprintf(path, sizeof path, "%s/%s", fuzz_dir_path, *f);
    remove(path);
  }
  remove(fuzz_dir_path);
}

/* The folder (zscan-fuzz-TAG-XXXXXX in TMPDIR or /tmp); files: the names
 * it may come to hold, NULL-ended, static. */
static const char *fuzz_dir(const char *tag, const char *const *files) {
  if (fuzz_dir_path[0]) return fuzz_dir_path;
  const char *tmp = getenv("TMPDIR");
  snprintf(fuzz_dir_path, sizeof fuzz_dir_path, "%s/zscan-fuzz-%s-XXXXXX",
           tmp && *tmp ? tmp : "/tmp", tag);
  if (!mkdtemp(fuzz_dir_path)) abort();
  fuzz_dir_files = files;
  atexit(fuzz_dir_remove);
  return fuzz_dir_path;
}

/* data[0 .. n - 1] as the file at path; 0 when it could not be. */
static int fuzz_write(const char *path, const void *data, size_t n) {
  FILE *f = fopen(path, "wb");
  if (!f) return 0;
  const int ok = fwrite(data, 1, n, f) == n;
  return fclose(f) == 0 && ok;
}

#endif
