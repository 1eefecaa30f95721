/* zscan — the command: `zscan COMMAND [options]`. */
#include <stdio.h>
#include <string.h>

#include "raster/raster.h"
#include "tools/commands.h"

static const zs_command commands[] = {
    {"render", "[INPUT]", "render one frame to a PNG, with its counters", zs_cmd_render},
    {"diff", "A.png B.png", "compare two images: pixels differing, faces involved", zs_cmd_diff},
    {"golden", "update|check M", "golden-image tests over a manifest, with reports",
     zs_cmd_golden},
    {"trace", "INPUT", "the scanline z-buffer's tables, scanline by scanline", zs_cmd_trace},
    {"walk", "SCENE", "culling methods over the scene's camera path", zs_cmd_walk},
    {"path", "SCENE", "the cameras of the scene's walk, one line per frame", zs_cmd_path},
    {"query", "INPUT", "per object: pixels owned and bounding-box samples", zs_cmd_query},
    {"calibrate", "", "measure the device clock's constants on this machine", zs_cmd_calibrate},
    {"bench", "WHAT", "benchmarks: octree, depthsort, raster, tradeoff, suite", zs_cmd_bench},
};

/* The version, and what this build holds: the span fill in use and the
 * optional parts compiled in. */
static int version(void) {
  printf("zscan %s (library %s)\n", ZSCAN_VERSION_STRING, zs_version());
  printf("span fill: %s\n", zs_simd_name(zs_span_simd_level(ZS_SIMD_AVX512)));
  printf("features:%s%s\n", ZS_FEATURES[0] ? " " : " none", ZS_FEATURES);
  return 0;
}

int main(int argc, char **argv) {
  if (argc == 2 && (strcmp(argv[1], "--version") == 0 || strcmp(argv[1], "-V") == 0))
    return version();
  return zs_command_dispatch("zscan", commands, (int)(sizeof commands / sizeof commands[0]), argc,
                             argv);
}
