/* zscan tools — instruction counts under valgrind's callgrind.
 *
 * Wall time on a shared machine moves between runs by more than many a
 * change gains; the instructions a run executes do not (docs/RESULTS.md
 * tells how far each repeats).  zs_callgrind_count runs this very
 * zscan with the given arguments under `valgrind --tool=callgrind` and
 * returns the instructions it executed (callgrind's "Collected", Ir). */
#ifndef ZS_TOOLS_CALLGRIND_H
#define ZS_TOOLS_CALLGRIND_H

#include <stdint.h>

#include "zscan/error.h"

/* Whether instruction counts can be taken here: valgrind on the PATH and a
 * build without sanitizers (valgrind cannot run those).  When not, the
 * reason goes to err. */
int zs_callgrind_available(zs_error *err);

/* args: zscan's own arguments (NULL-terminated, without the program). */
zs_status zs_callgrind_count(const char *const *args, uint64_t *instructions, zs_error *err);

#endif
