#include "tools/input.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/builtin.h"
#include "scene/obj.h"
#include "scene/teapot.h"
#include "tools/cli.h"

static int has_suffix(const char *s, const char *suffix) {
  size_t n = strlen(s), k = strlen(suffix);
  if (n < k) return 0;
  for (size_t i = 0; i < k; i++) {
    char c = s[n - k + i];
    if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
    if (c != suffix[i]) return 0;
  }
  return 1;
}

/* builtin:NAME?key=value&key=value */
static zs_status load_builtin(const char *spec, zs_model *out, zs_error *err) {
  char buf[256];
  if (strlen(spec) >= sizeof buf)
    return zs_error_set(err, ZS_ERR_ARG, "%.40s...: input name too long", spec);
  snprintf(buf, sizeof buf, "%s", spec + strlen("builtin:"));
  char *query = strchr(buf, '?');
  if (query) *query++ = '\0';
  const char *name = buf;
  int n = 4, level = ZS_BUILTIN_TEAPOT_LEVEL;
  int is_cubes = strcmp(name, "cubes") == 0;
  if (!is_cubes && strcmp(name, "default") != 0)
    return zs_error_set(err, ZS_ERR_ARG, "%s: unknown generated scene '%s' (default, cubes)",
                        spec, name);
  for (char *kv = query; kv && *kv;) {
    char *amp = strchr(kv, '&');
    if (amp) *amp = '\0';
    char *eq = strchr(kv, '=');
    if (!eq) return zs_error_set(err, ZS_ERR_ARG, "%s: expected key=value, got '%s'", spec, kv);
    *eq = '\0';
    char opt[300];
    snprintf(opt, sizeof opt, "%s: %s", spec, kv);
    if (is_cubes && strcmp(kv, "n") == 0) {
      if (zs_cli_int(opt, eq + 1, 1, ZS_BUILTIN_CUBES_MAX, &n, err)) return err->code;
    } else if (!is_cubes && strcmp(kv, "level") == 0) {
      if (zs_cli_int(opt, eq + 1, 1, ZS_TEAPOT_MAX_LEVEL, &level, err)) return err->code;
    } else {
      return zs_error_set(err, ZS_ERR_ARG, "%s: unknown parameter '%s'", spec, kv);
    }
    kv = amp ? amp + 1 : NULL;
  }
  zs_model_init(out);
  zs_status st = is_cubes ? zs_builtin_cubes(out, n, err) : zs_builtin_teapot_field(out, level, err);
  if (st != ZS_OK) zs_model_free(out);
  return st;
}

zs_status zs_input_load(const char *spec, zs_model *out, zs_error *err) {
  if (!spec) return load_builtin("builtin:default", out, err);
  if (strncmp(spec, "builtin:", 8) == 0) return load_builtin(spec, out, err);
  if (has_suffix(spec, ".obj")) return zs_obj_load(spec, out, err);
  return zs_error_set(err, ZS_ERR_ARG,
                      "%s: unknown input format (expected .obj or builtin:NAME)", spec);
}
