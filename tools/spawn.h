/* zscan tools — running another program (gnuplot, valgrind) without a
 * shell: the arguments go as they are, whatever characters a scene spec or
 * a path holds. */
#ifndef ZS_TOOLS_SPAWN_H
#define ZS_TOOLS_SPAWN_H

#include <stddef.h>

/* Whether an executable of that name is on the PATH. */
int zs_program_available(const char *name);

/* Runs argv[0] (looked up on the PATH) with argv, its standard output and
 * error to the files named (or /dev/null when NULL), and waits.  Returns
 * its exit status, or -1 when it could not be started or did not exit. */
int zs_spawn_wait(char *const argv[], const char *out_path, const char *err_path);

/* The path of this very program (to run it again as a child), into
 * buf[cap]; 0 when it cannot be found. */
int zs_self_path(char *buf, size_t cap);

#endif
