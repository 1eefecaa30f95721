/* zscan — the command: `zscan COMMAND [options]`, through the table of
 * tools/commands.c, and `zscan --version`. */
#include <stdio.h>
#include <string.h>

#include "raster/raster.h"
#include "tools/commands.h"
#include "util/os.h"

/* The version, and what this build holds: the span fill in use and the
 * optional parts compiled in. */
static int version(void) {
  printf("zscan %s (library %s)\n", ZSCAN_VERSION_STRING, zs_version());
  printf("pixel version: %d\n", zs_pixel_version());
  printf("span fill: %s\n", zs_simd_name(zs_span_simd_level(ZS_SIMD_AVX512)));
  printf("features:%s%s\n", ZS_FEATURES[0] ? " " : " none", ZS_FEATURES);
  return 0;
}

int main(int argc, char **argv) {
  /* what zscan prints: the same bytes on every system */
  zs_os_binary_stream(stdout);
  zs_os_binary_stream(stderr);
  if (argc == 2 && (strcmp(argv[1], "--version") == 0 || strcmp(argv[1], "-V") == 0))
    return version();
  return zs_command_dispatch("zscan", zs_commands, zs_ncommands, argc, argv);
}
