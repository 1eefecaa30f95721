/* zscan scene — what the file loaders share (load_obj.c, load_scenefile.c,
 * load_assimp.c; the generators read no files): reading a file within a
 * size limit, the head of one, the directory of a path, and messages with
 * the control characters of names from a file blanked out. */
#ifndef ZS_SCENE_LOAD_COMMON_H
#define ZS_SCENE_LOAD_COMMON_H

#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include "zscan/error.h"
#include "util/compiler.h"

/* Sets err to prefix (NULL: none) followed by the message, cut to
 * ZS_ERROR_MSG_MAX, with every control character written as a space (a
 * newline in a name from a file cannot break the message in two); trim:
 * trailing spaces go too.  Returns code. */
zs_status zs_load_verror(zs_error *err, zs_status code, int trim, const char *prefix,
                         const char *fmt, va_list ap);

/* The same without prefix or trimming. */
zs_status zs_load_error(zs_error *err, zs_status code, const char *fmt, ...) ZS_PRINTF_LIKE(3, 4);

enum {
  ZS_LOAD_REGULAR_ONLY = 1, /* refuse all but a regular file; notice one that grew */
  ZS_LOAD_MISSING_OK = 2    /* a file that cannot be opened: ZS_OK, *data NULL */
};

/* Reads the whole file at path, at most max_bytes, into a malloc'd buffer
 * (NUL-terminated; *len excludes the NUL).  Without ZS_LOAD_REGULAR_ONLY
 * in flags a pipe is read too, up to max_bytes.  Messages name the file
 * as shown: "SHOWN: cannot open: why", ": not a regular file", ": larger
 * than N MiB", ": read error: why", ": changed while being read", ": out
 * of memory". */
zs_status zs_load_file(const char *path, const char *shown, long long max_bytes, int flags,
                       char **data, size_t *len, zs_error *err);

/* The first cap bytes (at most) of the regular file at path, at most
 * max_bytes long, into buf (NUL-terminated, cap + 1 bytes), with *len read
 * and *size the file's size.  Messages as zs_load_file's. */
zs_status zs_load_head(const char *path, long long max_bytes, char *buf, size_t cap,
                       size_t *len, uint64_t *size, zs_error *err);

/* Parses text (len bytes, NUL-terminated) of the file name, whose
 * directory is dir, into out. */
typedef zs_status (*zs_load_parser)(const char *text, size_t len, const char *name,
                                    const char *dir, void *out, zs_error *err);

/* Reads the file at path (zs_load_file: max_bytes, flags) and parses it
 * into out, telling parse the file's directory (zs_load_dir). */
zs_status zs_load_parsed(const char *path, long long max_bytes, int flags, zs_load_parser parse,
                         void *out, zs_error *err);

/* The directory of path, malloc'd: path up to its last '/' ("/" for a file
 * in the root, "" for a bare file name); NULL when out of memory. */
char *zs_load_dir(const char *path);

#endif
