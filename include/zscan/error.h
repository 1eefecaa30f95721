/* zscan — errors, shared by every layer and by the public API.
 *
 * Functions that can fail return a zs_status and fill a zs_error with a
 * one-line message of the form "file:line: reason" (or "json.path: reason",
 * or "OPTION PATH: reason").  The first error wins: a later zs_error_set on
 * an error already set keeps the first message, so the root cause is what
 * the user reads.  The library never prints and never exits.
 */
#ifndef ZSCAN_ERROR_H
#define ZSCAN_ERROR_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum zs_status {
  ZS_OK = 0,
  ZS_ERR_ARG,         /* a bad argument or option value */
  ZS_ERR_IO,          /* a file could not be opened, read or written */
  ZS_ERR_PARSE,       /* malformed input */
  ZS_ERR_LIMIT,       /* beyond a documented size limit */
  ZS_ERR_NOMEM,       /* an allocation failed */
  ZS_ERR_UNSUPPORTED  /* valid, but not what this mode can do */
} zs_status;

enum { ZS_ERROR_MSG_MAX = 512 };

typedef struct zs_error {
  zs_status code;
  char msg[ZS_ERROR_MSG_MAX];
} zs_error;

/* Clears err (err may be NULL). */
void zs_error_clear(zs_error *err);

/* Sets err unless it is already set (first error wins); returns code, so a
 * caller can write `return zs_error_set(err, ZS_ERR_PARSE, "%s:%d: ...")`.
 * err may be NULL. */
zs_status zs_error_set(zs_error *err, zs_status code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#ifdef __cplusplus
}
#endif

#endif
