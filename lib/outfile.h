/* zscan lib — the one way every output is written.
 *
 * What happens at PATH depends on what is there:
 *   - nothing, or a regular file: the bytes go to PATH.tmp.XXXXXX beside it,
 *     which is renamed over PATH once every byte went out and the file is
 *     closed; on any error the temporary is removed.  A crash leaves the old
 *     file or the new one, never half of one.  A file that is replaced keeps
 *     its permission bits; a new one gets 0666 less the umask, as fopen()
 *     would give it.  (No fsync: this guards against errors and interrupted
 *     runs, not against power loss.)
 *   - a symbolic link: it is followed (up to 40 links) and its final target
 *     is written as above; the link stays a link.
 *   - a character device, a FIFO or a Unix socket: opened and written
 *     directly, with no temporary and no rename (a FIFO's open waits for its
 *     reader, as for any program).
 *   - "-": standard output, written directly and flushed, never closed.
 *   - a directory, a block device, or a path whose directory does not exist:
 *     refused, with a one-line reason.
 * A write that fails (a full disk, /dev/full) is an error at the commit,
 * never a success.
 *
 * Errors read "PATH: reason"; a command prefixes the option that named the
 * path with zs_out_error_option, so the user reads "-o out/x.png: ...". */
#ifndef ZS_LIB_OUTFILE_H
#define ZS_LIB_OUTFILE_H

#include <stdio.h>

#include "zscan/error.h"

typedef struct zs_out {
  FILE *fp;     /* where the bytes go; NULL when closed */
  char *path;   /* the path as given, for messages */
  char *target; /* the file renamed over (a link's target); NULL: direct */
  char *tmp;    /* the temporary beside target; NULL: direct */
} zs_out;

/* Opens PATH for writing as described above.  On failure *o is empty and
 * err is set. */
zs_status zs_out_open(zs_out *o, const char *path, zs_error *err);

/* What zs_out_open would refuse, found before any work is done: a
 * directory, a block device, a missing folder, a folder that cannot be
 * written in.  It opens nothing (a FIFO's open would wait). */
zs_status zs_out_check(const char *path, zs_error *err);

/* Flushes and closes the output and, for a file, renames the temporary over
 * the target.  Any failure (a write error, a full disk) removes the
 * temporary and is returned.  *o is empty afterwards. */
zs_status zs_out_commit(zs_out *o, zs_error *err);

/* Closes the output and removes the temporary: nothing is written (after an
 * error).  Safe on an empty or already closed zs_out. */
void zs_out_discard(zs_out *o);

/* Outputs that replace their files together, so that a command whose
 * later output fails leaves the files of the earlier ones as they were: a
 * writer given a set finishes its output into it (zs_out_finish: flushed,
 * closed, checked, but not renamed); zs_out_set_land then renames every
 * temporary over its file, zs_out_set_drop removes them.  Standard
 * output, a FIFO and a device cannot wait: they are done when finished
 * (a command writes such an output last).  Start a set as
 * ZS_OUT_SET_EMPTY. */
enum { ZS_OUT_SET_MAX = 8 };
typedef struct zs_out_set {
  zs_out held[ZS_OUT_SET_MAX];
  int n;
} zs_out_set;
#define ZS_OUT_SET_EMPTY {{{0}}, 0}

/* zs_out_commit when set is NULL; else o, flushed and closed, is held in
 * set, or its temporary removed and the error returned.  *o is empty
 * afterwards. */
zs_status zs_out_finish(zs_out *o, zs_out_set *set, zs_error *err);

/* Renames the set's temporaries over their files, in the order finished;
 * where one cannot be, the error is returned and the rest are removed
 * (the files before it are replaced).  The set is empty afterwards. */
zs_status zs_out_set_land(zs_out_set *set, zs_error *err);

/* Removes the set's temporaries: none of its files is replaced. */
void zs_out_set_drop(zs_out_set *set);

/* Whether PATH means standard output ("-"). */
int zs_out_is_stdout(const char *path);

/* Standard output carries one stream: a command's printed report, or the
 * one output of outs[0..n-1] (NULL entries skipped) named "-".  *report
 * receives stdout, or stderr when an output takes stdout; more than one
 * "-" is an error naming opts (the options, for the message). */
zs_status zs_out_report(const char *const *outs, int n, const char *opts, FILE **report,
                        zs_error *err);

/* Prefixes err's message with the option that named the path ("-o"), once;
 * returns err's code. */
zs_status zs_out_error_option(zs_error *err, const char *opt);

/* Appends the file at path to f. */
zs_status zs_append_file(FILE *f, const char *path, zs_error *err);

/* The directory given to option opt, created with its parents when
 * missing; an error names the option when it cannot be, or when something
 * other than a directory stands there. */
zs_status zs_out_dir(const char *opt, const char *dir, zs_error *err);

#endif
