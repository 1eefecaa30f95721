/* zscan — the command: `zscan COMMAND [args]`. */
#include <stdio.h>
#include <string.h>

#include "tools/bench.h"
#include "tools/calibrate.h"
#include "tools/diff.h"
#include "tools/path.h"
#include "tools/query.h"
#include "tools/render.h"
#include "tools/trace.h"
#include "tools/walk.h"

static const char usage[] =
    "usage: zscan COMMAND [options]\n"
    "commands:\n"
    "  render [INPUT]   render one frame to a PNG (zscan render --help)\n"
    "  diff A.png B.png compare two images (pixels differing, faces involved)\n"
    "  trace INPUT      the scanline z-buffer's tables, scanline by scanline\n"
    "  walk SCENE       culling methods over the scene's camera path\n"
    "  path SCENE       the cameras of the scene's walk, one line per frame\n"
    "  query INPUT      per object: pixels owned and bounding-box samples\n"
    "  calibrate        measure the device clock's constants on this machine\n"
    "  bench WHAT       benchmarks: octree, depthsort, raster\n";

int main(int argc, char **argv) {
  if (argc < 2) {
    fputs(usage, stderr);
    return 2;
  }
  const char *cmd = argv[1];
  if (strcmp(cmd, "render") == 0) return zs_cmd_render(argc - 1, argv + 1);
  if (strcmp(cmd, "diff") == 0) return zs_cmd_diff(argc - 1, argv + 1);
  if (strcmp(cmd, "query") == 0) return zs_cmd_query(argc - 1, argv + 1);
  if (strcmp(cmd, "path") == 0) return zs_cmd_path(argc - 1, argv + 1);
  if (strcmp(cmd, "walk") == 0) return zs_cmd_walk(argc - 1, argv + 1);
  if (strcmp(cmd, "trace") == 0) return zs_cmd_trace(argc - 1, argv + 1);
  if (strcmp(cmd, "bench") == 0) return zs_cmd_bench(argc - 1, argv + 1);
  if (strcmp(cmd, "calibrate") == 0) return zs_cmd_calibrate(argc - 1, argv + 1);
  if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
    fputs(usage, stdout);
    return 0;
  }
  fprintf(stderr, "zscan: unknown command '%s'\n%s", cmd, usage);
  return 2;
}
