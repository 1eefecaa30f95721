/* One dispatcher for the command tables (tools/commands.h). */
#include "tools/commands.h"

#include <stdio.h>
#include <string.h>

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
