#include "tools/costset.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "tools/cli.h"
#include "tools/clockfile.h"

typedef struct cost_field {
  const char *name;
  size_t offset;
  double lo, hi;
  int whole;              /* only whole numbers (measure: 0 or 1) */
  const char *what;
} cost_field;

#define FIELD(name, lo, hi, whole, what) {#name, offsetof(zs_cost_params, name), lo, hi, whole, what}
static const cost_field fields[] = {
    FIELD(w1, 0.0, 1.0, 0, "a probability from 0 to 1"),
    FIELD(w2, 0.0, 1.0, 0, "a probability from 0 to 1"),
    FIELD(ttri_ns, 0.0, 1e12, 0, "nanoseconds from 0 to 1e12"),
    FIELD(tcall_ns, 0.0, 1e12, 0, "nanoseconds from 0 to 1e12"),
    FIELD(t_ns, 0.0, 1e12, 0, "nanoseconds from 0 to 1e12"),
    FIELD(tq_ns, 0.0, 1e12, 0, "nanoseconds from 0 to 1e12"),
    FIELD(rho, 0.0, 1e6, 0, "pixels per unit of S from 0 to 1e6"),
    FIELD(learn, 0.0, 1e6, 0, "a number of outcomes from 0 to 1e6"),
    FIELD(measure, 0.0, 1.0, 1, "0 (off) or 1 (on)"),
};
#undef FIELD

zs_status zs_cost_set(const char *assignment, zs_cost_params *p, zs_error *err) {
  char name[64];
  double v;
  if (zs_cli_assignment("--cost-set", assignment, name, sizeof name, &v, err)) return err->code;
  for (size_t i = 0; i < sizeof fields / sizeof fields[0]; i++) {
    if (strcmp(fields[i].name, name) != 0) continue;
    if (v < fields[i].lo || v > fields[i].hi || (fields[i].whole && v != floor(v)))
      return zs_error_set(err, ZS_ERR_ARG, "--cost-set %s: expected %s, got %g", name,
                          fields[i].what, v);
    *(double *)((char *)p + fields[i].offset) = v;
    return ZS_OK;
  }
  return zs_error_set(err, ZS_ERR_ARG,
                      "--cost-set %s: unknown cost-model parameter (w1, w2, ttri_ns, tcall_ns, "
                      "t_ns, tq_ns, rho, learn, measure)",
                      name);
}

int zs_cull_option(int argc, char **argv, int *i, zs_clock_params *clock, zs_cost_params *cost,
                   zs_query_bounds *bounds, zs_error *err) {
  const char *a = argv[*i], *v = NULL;
  const int load = strcmp(a, "--clock") == 0, set = strcmp(a, "--clock-set") == 0;
  const int box = strcmp(a, "--bounds") == 0;
  if (!load && !set && !box && strcmp(a, "--cost-set") != 0) return 0;
  if (zs_cli_value(argc, argv, i, &v, err)) return -1;
  if (box) {
    int b = zs_query_bounds_parse(v);
    if (b < 0) {
      zs_error_set(err, ZS_ERR_ARG, "--bounds: expected parts or box, got '%s'", v);
      return -1;
    }
    *bounds = (zs_query_bounds)b;
    return 1;
  }
  zs_status st = load  ? zs_clockfile_load(v, clock, err)
                 : set ? zs_clockfile_set(v, clock, err)
                       : zs_cost_set(v, cost, err);
  return st ? -1 : 1;
}
