#include "tests/testutil.h"

#include <stdio.h>

int zs_test_run(Suite *s) {
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_ENV);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed == 0 ? 0 : 1;
}

const char *zs_test_src(const char *rel) {
  static char buf[4096];
  snprintf(buf, sizeof buf, "%s/%s", ZS_SOURCE_DIR, rel);
  return buf;
}

const char *zs_test_bin(const char *rel) {
  static char buf[4096];
  snprintf(buf, sizeof buf, "%s/%s", ZS_BINARY_DIR, rel);
  return buf;
}

uint64_t zs_test_fnv1a(const void *data, size_t n) {
  const unsigned char *p = data;
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < n; i++) {
    h ^= p[i];
    h *= 0x100000001b3ull;
  }
  return h;
}

#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

static void slurp(const char *path, char *buf, size_t cap) {
  buf[0] = '\0';
  FILE *f = fopen(path, "rb");
  if (!f) return;
  size_t n = fread(buf, 1, cap - 1, f);
  buf[n] = '\0';
  fclose(f);
}

int zs_test_run_zscan(const char *const *args, char *out, size_t out_cap, char *err,
                      size_t err_cap) {
  char exe[4096], out_path[4200], err_path[4200];
  snprintf(exe, sizeof exe, "%s/zscan", ZS_BINARY_DIR);
  snprintf(out_path, sizeof out_path, "%s/zscan-test-%d.out", ZS_BINARY_DIR, (int)getpid());
  snprintf(err_path, sizeof err_path, "%s/zscan-test-%d.err", ZS_BINARY_DIR, (int)getpid());
  const char *argv[64];
  int n = 0;
  argv[n++] = exe;
  for (int i = 0; args[i] && n < 63; i++) argv[n++] = args[i];
  argv[n] = NULL;
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, out_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, 2, err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid;
  int rc = posix_spawn(&pid, exe, &fa, NULL, (char *const *)argv, environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) return -2;
  int status;
  waitpid(pid, &status, 0);
  if (out) slurp(out_path, out, out_cap);
  if (err) slurp(err_path, err, err_cap);
  unlink(out_path);
  unlink(err_path);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int zs_test_exists(const char *path) {
  struct stat st;
  return stat(path, &st) == 0;
}
