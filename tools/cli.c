#include "tools/cli.h"
#include "util/lights.h"

#include <stdarg.h>

#include "lib/outfile.h"

#include "scene/text.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/os.h"

zs_status zs_cli_double(const char *opt, const char *s, double *out, zs_error *err) {
  char *end;
  errno = 0;
  double v = zs_text_is_decimal(s) ? strtod(s, &end) : NAN;
  if (!isfinite(v) || errno == ERANGE)
    return zs_error_set(err, ZS_ERR_ARG, "%s: expected a finite number, got '%s'", opt, s);
  *out = v;
  return ZS_OK;
}

zs_status zs_cli_assignment(const char *opt, const char *s, char *key, size_t cap,
                            double *value, zs_error *err) {
  const char *eq = strchr(s, '=');
  if (!eq || eq == s || (size_t)(eq - s) >= cap)
    return zs_error_set(err, ZS_ERR_ARG, "%s: expected KEY=VALUE, got '%s'", opt, s);
  snprintf(key, cap, "%.*s", (int)(eq - s), s);
  char where[160];
  snprintf(where, sizeof where, "%s %s", opt, key);
  return zs_cli_double(where, eq + 1, value, err);
}

zs_status zs_cli_int(const char *opt, const char *s, long lo, long hi, int *out,
                     zs_error *err) {
  char *end;
  errno = 0;
  long v = strtol(s, &end, 10);
  if (end == s || *end != '\0' || errno == ERANGE)
    return zs_error_set(err, ZS_ERR_ARG, "%s: expected a whole number, got '%s'", opt, s);
  if (v < lo || v > hi)
    return zs_error_set(err, ZS_ERR_ARG, "%s: %ld is outside %ld .. %ld", opt, v, lo, hi);
  *out = (int)v;
  return ZS_OK;
}

zs_status zs_cli_numbers(const char *opt, const char *s, int n, const char *what, double *out,
                         zs_error *err) {
  const char *p = s;
  for (int i = 0; i < n; i++) {
    char *end;
    errno = 0;
    double v = strtod(p, &end);
    int sep_ok = i < n - 1 ? *end == ',' : *end == '\0';
    if (end == p || !sep_ok || !isfinite(v) || errno == ERANGE)
      return zs_error_set(err, ZS_ERR_ARG, "%s: expected %s, got '%s'", opt, what, s);
    out[i] = v;
    p = end + 1;
  }
  return ZS_OK;
}

zs_status zs_cli_vec3(const char *opt, const char *s, double out[3], zs_error *err) {
  return zs_cli_numbers(opt, s, 3, "x,y,z (three finite numbers)", out, err);
}

/* The ':'-separated fields of a light's text, in place in buf: at most
 * max of them; their count. */
static int light_fields(char *buf, char **field, int max) {
  int n = 0;
  for (char *p = buf; n < max; n++) {
    field[n] = p;
    char *colon = strchr(p, ':');
    if (!colon) return n + 1;
    *colon = '\0';
    p = colon + 1;
  }
  return max + 1; /* too many */
}

zs_status zs_cli_light(const char *opt, const char *s, zs_light *out, zs_error *err) {
  static const char usage[] = "dir:DX,DY,DZ, point:X,Y,Z, spot:X,Y,Z:DX,DY,DZ:INNER,OUTER "
                              "(each with :R,G,B or not) or ambient:R,G,B";
  char buf[256], *f[6];
  if (strlen(s) >= sizeof buf)
    return zs_error_set(err, ZS_ERR_ARG, "%s: expected %s, got '%.40s...'", opt, usage, s);
  strcpy(buf, s);
  const int n = light_fields(buf, f, 5);
  memset(out, 0, sizeof *out);
  out->color[0] = out->color[1] = out->color[2] = 1.0;
  int places = 0; /* fields before the colour */
  if (strcmp(f[0], "dir") == 0) out->kind = ZS_LIGHT_DIRECTIONAL, places = 2;
  else if (strcmp(f[0], "point") == 0) out->kind = ZS_LIGHT_POINT, places = 2;
  else if (strcmp(f[0], "spot") == 0) out->kind = ZS_LIGHT_SPOT, places = 4;
  else if (strcmp(f[0], "ambient") == 0) out->kind = ZS_LIGHT_AMBIENT, places = 1;
  if (places == 0 || n < places || n > places + 1 ||
      (out->kind == ZS_LIGHT_AMBIENT && n != 2))
    return zs_error_set(err, ZS_ERR_ARG, "%s: expected %s, got '%s'", opt, usage, s);
  zs_status st = ZS_OK;
  const char *three = "x,y,z (three finite numbers)";
  if (out->kind == ZS_LIGHT_DIRECTIONAL) st = zs_cli_numbers(opt, f[1], 3, three, out->direction, err);
  if (out->kind == ZS_LIGHT_POINT || out->kind == ZS_LIGHT_SPOT)
    st = zs_cli_numbers(opt, f[1], 3, three, out->position, err);
  if (st == ZS_OK && out->kind == ZS_LIGHT_SPOT) {
    double cone[2] = {0.0, 0.0};
    st = zs_cli_numbers(opt, f[2], 3, three, out->direction, err);
    if (st == ZS_OK)
      st = zs_cli_numbers(opt, f[3], 2, "INNER,OUTER (two angles in degrees)", cone, err);
    out->inner_deg = cone[0];
    out->outer_deg = cone[1];
  }
  if (st == ZS_OK && n == places + 1)
    st = zs_cli_numbers(opt, f[places], 3, "R,G,B (three finite numbers)", out->color, err);
  if (st != ZS_OK) return st;
  zs_error why = {0};
  if (zs_lights_check(out, 1, &why) != ZS_OK) /* "lights[0].FIELD: reason" */
    return zs_error_set(err, ZS_ERR_ARG, "%s: %s: %s", opt, s, strchr(why.msg, ' ') + 1);
  return ZS_OK;
}

zs_status zs_cli_size(const char *opt, const char *s, int max, int *w, int *h,
                      zs_error *err) {
  char *end;
  errno = 0;
  long a = strtol(s, &end, 10);
  if (end == s || (*end != 'x' && *end != 'X') || errno == ERANGE)
    return zs_error_set(err, ZS_ERR_ARG, "%s: expected WxH, got '%s'", opt, s);
  const char *p = end + 1;
  long b = strtol(p, &end, 10);
  if (end == p || *end != '\0' || errno == ERANGE)
    return zs_error_set(err, ZS_ERR_ARG, "%s: expected WxH, got '%s'", opt, s);
  if (a < 1 || b < 1 || a > max || b > max)
    return zs_error_set(err, ZS_ERR_LIMIT, "%s: %s: each side must be 1 to %d", opt, s, max);
  *w = (int)a;
  *h = (int)b;
  return ZS_OK;
}

zs_status zs_cli_value(int argc, char **argv, int *i, const char **out, zs_error *err) {
  if (*i + 1 >= argc)
    return zs_error_set(err, ZS_ERR_ARG, "%s: missing value", argv[*i]);
  *out = argv[++*i];
  return ZS_OK;
}

zs_status zs_cli_output_path(const char *opt, const char *path, zs_error *err) {
  if (zs_out_check(path, err)) return zs_out_error_option(err, opt);
  return ZS_OK;
}

const char *zs_cli_extension(const char *path) {
  const char *base = path; /* (after the last separator: '\\' too on Windows) */
  for (const char *p = path; *p; p++)
    if (zs_os_is_separator(*p)) base = p + 1;
  const char *dot = strrchr(base, '.');
  return dot && dot != base ? dot + 1 : NULL;
}

int zs_cli_extension_is(const char *path, const char *ext) {
  const char *given = zs_cli_extension(path);
  if (!given) return 0;
  for (; *given && *ext; given++, ext++)
    if ((*given >= 'A' && *given <= 'Z' ? *given - 'A' + 'a' : *given) != *ext) return 0;
  return *given == *ext;
}

zs_status zs_cli_output_format(const char *opt, const char *path, const char *ext,
                               zs_error *err) {
  const char *given = zs_cli_extension(path);
  if (!given) return ZS_OK; /* no extension: a device, a pipe, a plain name */
  if (zs_cli_extension_is(path, ext)) return ZS_OK;
  char upper[16];
  size_t n = 0;
  for (; ext[n] && n + 1 < sizeof upper; n++)
    upper[n] = (char)(ext[n] >= 'a' && ext[n] <= 'z' ? ext[n] - 'a' + 'A' : ext[n]);
  upper[n] = '\0';
  return zs_error_set(err, ZS_ERR_ARG, "%s: %s: zscan writes %s (FILE.%s)", opt, path, upper, ext);
}

zs_status zs_cli_output_value(int argc, char **argv, int *i, const char **out, zs_error *err) {
  const char *opt = argv[*i];
  if (zs_cli_value(argc, argv, i, out, err)) return err->code;
  return zs_cli_output_path(opt, *out, err);
}

zs_status zs_cli_int_value(int argc, char **argv, int *i, long lo, long hi, int *out,
                           zs_error *err) {
  const char *opt = argv[*i], *v = NULL;
  if (zs_cli_value(argc, argv, i, &v, err)) return err->code;
  return zs_cli_int(opt, v, lo, hi, out, err);
}

zs_status zs_cli_size_value(int argc, char **argv, int *i, int max, int *w, int *h,
                            zs_error *err) {
  const char *opt = argv[*i], *v = NULL;
  if (zs_cli_value(argc, argv, i, &v, err)) return err->code;
  return zs_cli_size(opt, v, max, w, h, err);
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

int zs_cli_exit_status(const zs_error *err, int parsing) {
  return parsing && (err->code == ZS_ERR_ARG || err->code == ZS_ERR_LIMIT) ? 2 : 1;
}

int zs_cli_help_asked(int argc, char **argv) {
  for (int i = 1; i < argc; i++)
    if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) return 1;
  return 0;
}

int zs_cli_help(int argc, char **argv, const char *usage, ...) {
  if (!zs_cli_help_asked(argc, argv)) return 0;
  va_list ap;
  va_start(ap, usage);
  for (const char *piece = usage; piece; piece = va_arg(ap, const char *)) fputs(piece, stdout);
  va_end(ap);
  return 1;
}

zs_status zs_cli_operand(const char *a, const char *cmd, const char *what, const char **slot,
                         zs_error *err) {
  if (a[0] == '-' && a[1])
    return zs_error_set(err, ZS_ERR_ARG, "unknown option '%s' (see %s --help)", a, cmd);
  if (*slot) return zs_error_set(err, ZS_ERR_ARG, "more than one %s: '%s' and '%s'", what, *slot, a);
  *slot = a;
  return ZS_OK;
}

int zs_cli_fail(const char *cmd, const zs_error *err, int parsing) {
  fprintf(stderr, "%s: %s\n", cmd, err->msg);
  return zs_cli_exit_status(err, parsing);
}

/* A line in a log every five seconds; ZSCAN_PROGRESS_MS sets another
 * interval (the tests use a short one). */
static double log_interval_ms(void) {
  const char *e = getenv("ZSCAN_PROGRESS_MS");
  double ms = e && *e ? atof(e) : 5000.0;
  return ms >= 0 ? ms : 5000.0;
}

void zs_progress_start(zs_progress *p, const char *label, const char *unit, int total, int quiet) {
  *p = (zs_progress){label, unit, total, quiet, zs_os_stderr_is_terminal(), zs_os_monotonic_ms(), 0.0, log_interval_ms()};
  p->last_ms = p->start_ms;
}

void zs_progress_step(zs_progress *p, int done) {
  if (p->quiet || p->total <= 0) return;
  double now = zs_os_monotonic_ms(), spent = (now - p->start_ms) / 1000.0;
  double left = done > 0 ? spent * (p->total - done) / done : 0.0;
  if (p->tty) {
    enum { WIDTH = 30 };
    int bar = (int)((int64_t)done * WIDTH / p->total);
    fprintf(stderr, "\r%s [%.*s%*s] %s %d/%d, %.0f s, about %.0f s left ", p->label, bar,
            "##############################", WIDTH - bar, "", p->unit, done, p->total, spent,
            left);
    if (done == p->total) fputc('\n', stderr);
  } else if (now - p->last_ms >= p->interval_ms ||
             (done == p->total && now - p->start_ms >= p->interval_ms)) {
    fprintf(stderr, "%s: %s %d/%d (%d %%), %.0f s, about %.0f s left\n", p->label, p->unit, done,
            p->total, (int)((int64_t)done * 100 / p->total), spent, left);
    p->last_ms = now;
  }
}

double zs_median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

const char *zs_cli_ms_of_ps(int64_t ps, char *buf) {
  /* |ps| as unsigned, so that INT64_MIN negates */
  const uint64_t mag = ps < 0 ? 0 - (uint64_t)ps : (uint64_t)ps;
  const uint64_t ns = mag / 1000 + (mag % 1000 >= 500);
  snprintf(buf, 32, "%s%llu.%06llu", ps < 0 && ns ? "-" : "", (unsigned long long)(ns / 1000000),
           (unsigned long long)(ns % 1000000));
  return buf;
}
