/* zscan tools — output files that appear whole or not at all.
 *
 * A CSV, a table or a report is written to PATH.tmp.XXXXXX (mode 0666 less
 * the umask) and renamed over PATH when every byte went out; on any error
 * the temporary file is removed, so no half-written file is left. */
#ifndef ZS_TOOLS_OUTFILE_H
#define ZS_TOOLS_OUTFILE_H

#include <stdio.h>

#include "raster/error.h"

/* Creates PATH.tmp.XXXXXX; *tmp receives its name (malloc'd).  NULL, with
 * err set, on failure. */
FILE *zs_out_open(const char *path, char **tmp, zs_error *err);

/* Closes f and renames tmp over path (removing tmp on failure); frees tmp. */
zs_status zs_out_commit(FILE *f, char *tmp, const char *path, zs_error *err);

/* Closes f, removes tmp and frees it: nothing is written (after an error). */
void zs_out_discard(FILE *f, char *tmp);

/* Appends the file at path to f. */
zs_status zs_append_file(FILE *f, const char *path, zs_error *err);

/* The directory given to option opt, created when missing (one level). */
zs_status zs_out_dir(const char *opt, const char *dir, zs_error *err);

#endif
