#include "tools/clockfile.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "tools/cli.h"
#include "lib/outfile.h"

#define FIELD(name) {#name, offsetof(zs_clock_params, name)}
const zs_clockfile_field zs_clockfile_fields[] = {
    FIELD(per_call_ns),      FIELD(per_vertex_ns),    FIELD(per_polygon_ns),
    FIELD(per_span_ns),      FIELD(per_pixel_ns),
    FIELD(per_write_ns),     FIELD(per_query_pixel_ns), FIELD(switch_ns),
    FIELD(query_latency_ns), FIELD(cpu_per_call_ns),  FIELD(cpu_per_query_ns),
    FIELD(cpu_per_node_ns),  FIELD(cpu_per_frustum_ns), FIELD(cpu_per_cost_eval_ns),
    FIELD(hzb_pass_ns),      FIELD(hzb_per_texel_ns),   FIELD(hzb_per_box_ns),
    FIELD(hzb_per_read_ns),
};
#undef FIELD
const int zs_clockfile_nfields = (int)(sizeof zs_clockfile_fields / sizeof zs_clockfile_fields[0]);

static double *field(zs_clock_params *p, const char *name) {
  for (int i = 0; i < zs_clockfile_nfields; i++)
    if (strcmp(zs_clockfile_fields[i].name, name) == 0)
      return (double *)((char *)p + zs_clockfile_fields[i].offset);
  return NULL;
}

static zs_status set_value(const char *where, const char *name, double v, zs_clock_params *p,
                           zs_error *err) {
  double *f = field(p, name);
  if (!f) return zs_error_set(err, ZS_ERR_ARG, "%s%s: unknown clock parameter", where, name);
  if (!isfinite(v) || v < 0.0 || v > 1e12)
    return zs_error_set(err, ZS_ERR_ARG, "%s%s: expected nanoseconds from 0 to 1e12, got %g",
                        where, name, v);
  *f = v;
  return ZS_OK;
}

zs_status zs_clockfile_set(const char *assignment, zs_clock_params *p, zs_error *err) {
  char name[64];
  double v;
  if (zs_cli_assignment("--clock-set", assignment, name, sizeof name, &v, err)) return err->code;
  return set_value("--clock-set ", name, v, p, err);
}

/* "source": {"KEY": "measured" | "default", ...}: where each constant came
 * from, as zscan calibrate says; read only to check it. */
static zs_status check_source(const char *path, const cJSON *src, zs_error *err) {
  if (!cJSON_IsObject(src))
    return zs_error_set(err, ZS_ERR_PARSE, "%s: source: expected an object", path);
  for (const cJSON *it = src->child; it; it = it->next) {
    zs_clock_params scratch;
    if (!field(&scratch, it->string))
      return zs_error_set(err, ZS_ERR_PARSE, "%s: source.%s: unknown clock parameter", path,
                          it->string);
    if (!cJSON_IsString(it) ||
        (strcmp(it->valuestring, "measured") != 0 && strcmp(it->valuestring, "default") != 0))
      return zs_error_set(err, ZS_ERR_PARSE, "%s: source.%s: expected \"measured\" or \"default\"",
                          path, it->string);
  }
  return ZS_OK;
}

zs_status zs_clockfile_load(const char *path, zs_clock_params *p, zs_error *err) {
  FILE *f = fopen(path, "rb");
  if (!f) return zs_error_set(err, ZS_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
  char buf[1 << 16];
  size_t n = fread(buf, 1, sizeof buf - 1, f);
  int too_long = !feof(f);
  fclose(f);
  if (too_long) return zs_error_set(err, ZS_ERR_LIMIT, "%s: larger than a clock file can be", path);
  buf[n] = '\0';
  cJSON *root = cJSON_ParseWithLength(buf, n);
  if (!root || !cJSON_IsObject(root)) {
    cJSON_Delete(root);
    return zs_error_set(err, ZS_ERR_PARSE, "%s: expected one JSON object of clock parameters", path);
  }
  char where[4200];
  snprintf(where, sizeof where, "%s: ", path);
  zs_status st = ZS_OK;
  for (cJSON *it = root->child; it && st == ZS_OK; it = it->next) {
    if (strcmp(it->string, "source") == 0) {
      st = check_source(path, it, err);
      continue;
    }
    if (!cJSON_IsNumber(it))
      st = zs_error_set(err, ZS_ERR_PARSE, "%s: %s: expected a number", path, it->string);
    else
      st = set_value(where, it->string, it->valuedouble, p, err);
  }
  cJSON_Delete(root);
  return st;
}

void zs_clockfile_print(FILE *f, const zs_clock_params *p, const unsigned char *measured) {
  fputs("{", f);
  for (int i = 0; i < zs_clockfile_nfields; i++)
    fprintf(f, "%s\"%s\":%.6g", i ? "," : "", zs_clockfile_fields[i].name,
            *(const double *)((const char *)p + zs_clockfile_fields[i].offset));
  if (measured) {
    fputs(",\"source\":{", f);
    for (int i = 0; i < zs_clockfile_nfields; i++)
      fprintf(f, "%s\"%s\":\"%s\"", i ? "," : "", zs_clockfile_fields[i].name,
              measured[i] ? "measured" : "default");
    fputs("}", f);
  }
  fputs("}\n", f);
}

zs_status zs_clockfile_write(const char *path, const zs_clock_params *p,
                             const unsigned char *measured, zs_error *err) {
  zs_out out;
  if (zs_out_open(&out, path, err)) return err->code;
  zs_clockfile_print(out.fp, p, measured);
  return zs_out_commit(&out, err);
}
