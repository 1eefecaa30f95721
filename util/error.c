#include "zscan/error.h"

#include <stdarg.h>
#include <stdio.h>

void zs_error_clear(zs_error *err) {
  if (!err) return;
  err->code = ZS_OK;
  err->msg[0] = '\0';
}

zs_status zs_error_set(zs_error *err, zs_status code, const char *fmt, ...) {
  if (!err || err->code != ZS_OK) return code;
  err->code = code;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err->msg, sizeof err->msg, fmt, ap);
  va_end(ap);
  return code;
}
