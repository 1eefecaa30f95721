/* zscan's table of commands, and the one dispatcher of it and of `zscan
 * bench`'s table (tools/commands.h). */
#include "tools/commands.h"

#include <stdio.h>
#include <string.h>

const zs_command zs_commands[] = {
    {"render", "[INPUT]", "render one frame to a PNG, with its counters", zs_cmd_render},
    {"composite", "L1 L2 ...", "merge layers of a scene's parts by depth, as one frame",
     zs_cmd_composite},
    {"diff", "A.png B.png", "compare two images: pixels differing, faces involved", zs_cmd_diff},
    {"golden", "update|check M", "golden-image tests over a manifest, with reports",
     zs_cmd_golden},
    {"trace", "INPUT", "the scanline z-buffer's tables, scanline by scanline", zs_cmd_trace},
    {"teach", "-o FILE.html", "the live teaching page: draw polygons, step the real walk",
     zs_cmd_teach},
    {"walk", "SCENE", "culling methods over the scene's camera path", zs_cmd_walk},
    {"path", "SCENE", "the cameras of the scene's walk, one line per frame", zs_cmd_path},
    {"query", "INPUT", "per object: pixels owned and bounding-box samples", zs_cmd_query},
    {"calibrate", "", "measure the device clock's constants on this machine", zs_cmd_calibrate},
    {"bench", "WHAT", "benchmarks: octree, depthsort, colours, raster, tradeoff, suite", zs_cmd_bench},
};
const int zs_ncommands = (int)(sizeof zs_commands / sizeof zs_commands[0]);

static void usage(FILE *f, const char *prog, const zs_command *table, int n) {
  fprintf(f, "usage: %s COMMAND [options]   (%s help COMMAND, or %s COMMAND --help)\ncommands:\n",
          prog, prog, prog);
  for (int i = 0; i < n; i++) {
    char head[64];
    snprintf(head, sizeof head, "%s %s", table[i].name, table[i].args);
    fprintf(f, "  %-22s %s\n", head, table[i].summary);
  }
}

int zs_command_dispatch(const char *prog, const zs_command *table, int n, int argc, char **argv) {
  if (argc < 2) {
    usage(stderr, prog, table, n);
    return 2;
  }
  const char *name = argv[1];
  if (strcmp(name, "help") == 0 && argc >= 3) { /* zscan help COMMAND: its --help */
    for (int i = 0; i < n; i++)
      if (strcmp(argv[2], table[i].name) == 0) {
        char *help[] = {argv[2], "--help", NULL};
        return table[i].run(2, help);
      }
    fprintf(stderr, "%s: unknown command '%s'\n", prog, argv[2]);
    usage(stderr, prog, table, n);
    return 2;
  }
  for (int i = 0; i < n; i++)
    if (strcmp(name, table[i].name) == 0) return table[i].run(argc - 1, argv + 1);
  if (strcmp(name, "--help") == 0 || strcmp(name, "-h") == 0 || strcmp(name, "help") == 0) {
    usage(stdout, prog, table, n);
    return 0;
  }
  fprintf(stderr, "%s: unknown command '%s'\n", prog, name);
  usage(stderr, prog, table, n);
  return 2;
}
