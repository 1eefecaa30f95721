#include "tools/callgrind.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/os.h"

int zs_callgrind_available(zs_error *err) {
#ifdef ZS_SANITIZED
  zs_error_set(err, ZS_ERR_UNSUPPORTED,
               "--callgrind: this zscan is built with sanitizers, which valgrind cannot run");
  return 0;
#else
  if (zs_os_program_available("valgrind")) return 1;
  zs_error_set(err, ZS_ERR_UNSUPPORTED, "--callgrind: valgrind is not installed (apt-get install valgrind)");
  return 0;
#endif
}

zs_status zs_callgrind_count(const char *const *args, uint64_t *instructions, zs_error *err) {
  *instructions = 0;
  if (!zs_callgrind_available(err)) return err->code;
  char self[4096];
  if (!zs_os_self_path(self, sizeof self))
    return zs_error_set(err, ZS_ERR_IO, "--callgrind: cannot find this program's path");
  char dir[4096], log[4200];
  int e = zs_os_scratch_dir("zscan-callgrind", dir, sizeof dir);
  if (e != 0)
    return zs_error_set(err, ZS_ERR_IO, "--callgrind: cannot create a scratch folder: %s", strerror(e));
  snprintf(log, sizeof log, "%s/callgrind.log", dir);
  char log_opt[4300];
  snprintf(log_opt, sizeof log_opt, "--log-file=%s", log);
  const char *argv[64];
  int k = 0;
  argv[k++] = "valgrind";
  argv[k++] = "--tool=callgrind";
  argv[k++] = "--callgrind-out-file=/dev/null";
  argv[k++] = log_opt;
  argv[k++] = self;
  for (int i = 0; args[i]; i++) {
    if (k == 63) {
      zs_os_rmdir(dir);
      return zs_error_set(err, ZS_ERR_ARG, "--callgrind: too many arguments");
    }
    argv[k++] = args[i];
  }
  argv[k] = NULL;
  int rc = zs_os_spawn_wait((char *const *)argv, NULL, NULL);
  /* callgrind's summary: "==PID== Collected : N" */
  FILE *f = fopen(log, "r");
  char line[512];
  int found = 0;
  while (f && fgets(line, sizeof line, f)) {
    const char *c = strstr(line, "Collected :");
    if (c) found = sscanf(c + strlen("Collected :"), "%" SCNu64, instructions) == 1;
  }
  if (f) fclose(f);
  remove(log);
  zs_os_rmdir(dir);
  if (rc != 0 || !found)
    return zs_error_set(err, ZS_ERR_IO, "--callgrind: the run under valgrind failed (exit %d)", rc);
  return ZS_OK;
}
