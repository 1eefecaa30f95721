#include "tools/bench_load.h"

#include "lib/input.h"
#include "tools/cli.h"
#include "util/os.h"

zs_status zs_bench_load_report(FILE *f, const char *const *specs, int n, zs_error *err) {
  fprintf(f, "scene loading (wall time)\n");
  for (int i = 0; i < n; i++) {
    zs_scene s;
    double t0 = zs_os_monotonic_ms();
    if (zs_input_load_scene(specs[i], &s, err)) return err->code;
    double ms = zs_os_monotonic_ms() - t0;
    fprintf(f, "  %-30s %9.1f ms  (%d objects, %llu triangles)\n", specs[i], ms, (int)s.ninst,
            (unsigned long long)zs_scene_triangles(&s));
    zs_scene_free(&s);
  }
  return ZS_OK;
}
