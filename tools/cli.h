/* zscan tools — strict parsing of command-line values.
 *
 * Every parser takes the option's name for its message and refuses
 * anything but the whole string as the value asked for: "1.5x" is not a
 * number, "nan" and "inf" are not numbers either.  Messages read
 * "--size: expected WxH, got '12'". */
#ifndef ZS_TOOLS_CLI_H
#define ZS_TOOLS_CLI_H

#include <stddef.h>
#include <stdint.h>

#include "zscan/zscan.h"

zs_status zs_cli_double(const char *opt, const char *s, double *out, zs_error *err);
zs_status zs_cli_int(const char *opt, const char *s, long lo, long hi, int *out,
                     zs_error *err);
/* "KEY=VALUE" with a number for VALUE: the key into key (cap bytes), the
 * number into *value; opt names the option in messages. */
zs_status zs_cli_assignment(const char *opt, const char *s, char *key, size_t cap,
                            double *value, zs_error *err);
/* n finite numbers separated by commas; what describes them in the
 * message ("x,y,z (three finite numbers)"). */
zs_status zs_cli_numbers(const char *opt, const char *s, int n, const char *what, double *out,
                         zs_error *err);
/* "x,y,z" */
zs_status zs_cli_vec3(const char *opt, const char *s, double out[3], zs_error *err);
/* A light: "dir:DX,DY,DZ", "point:X,Y,Z", "spot:X,Y,Z:DX,DY,DZ:INNER,OUTER"
 * (each optionally ":R,G,B", linear, default 1,1,1) or "ambient:R,G,B";
 * directions are the way the light travels, in world coordinates. */
zs_status zs_cli_light(const char *opt, const char *s, zs_light *out, zs_error *err);
/* "WxH", each side 1 .. max */
zs_status zs_cli_size(const char *opt, const char *s, int max, int *w, int *h,
                      zs_error *err);
/* The value of option argv[*i], advancing *i; an error when it is missing. */
zs_status zs_cli_value(int argc, char **argv, int *i, const char **out, zs_error *err);
/* Refuses an output path whose directory does not exist or cannot be
 * written, before any work is done. */
zs_status zs_cli_output_path(const char *opt, const char *path, zs_error *err);
/* The extension of path's file name (after its last '.', not the name's
 * first character), or NULL when it has none. */
const char *zs_cli_extension(const char *path);
/* Whether path's extension is ext (lower case), in any case. */
int zs_cli_extension_is(const char *path, const char *ext);
/* An output whose name says another format than the one written (-o x.jpg
 * for a PNG) is refused: "-o: x.jpg: zscan writes PNG".  ext is the
 * format's extension ("png"), any case; a name without an extension, "-",
 * or a device is taken as it is. */
zs_status zs_cli_output_format(const char *opt, const char *path, const char *ext,
                               zs_error *err);
/* Picoseconds as milliseconds with six decimals ("12.345679"), rounded to
 * the nearest nanosecond (halves away from zero), by integer arithmetic
 * alone, so the text is the same wherever doubles would round otherwise;
 * buf holds at least 32 bytes. */
const char *zs_cli_ms_of_ps(int64_t ps, char *buf);
/* zs_cli_value, then zs_cli_int or zs_cli_size on the value: an option
 * taking a whole number, or a size. */
zs_status zs_cli_int_value(int argc, char **argv, int *i, long lo, long hi, int *out,
                           zs_error *err);
zs_status zs_cli_size_value(int argc, char **argv, int *i, int max, int *w, int *h,
                            zs_error *err);
/* zs_cli_value, then zs_cli_output_path on the value: an output file's option. */
zs_status zs_cli_output_value(int argc, char **argv, int *i, const char **out, zs_error *err);

/* The exit status of a command that failed with err: 2 for a usage error
 * (an unknown option or a bad value, ZS_ERR_ARG or ZS_ERR_LIMIT, found while parsing the
 * command line), 1 for anything else (bad input, a failure while
 * working). */
int zs_cli_exit_status(const zs_error *err, int parsing);

/* 1 when any argument after the command is --help or -h: help is given
 * before anything else is parsed, so it works beside a bad option too. */
int zs_cli_help_asked(int argc, char **argv);
/* When help is asked: the usage, the NULL-terminated pieces in turn, on
 * stdout, and 1 (the command then exits 0); else 0. */
int zs_cli_help(int argc, char **argv, const char *usage, ...)
#if defined(__GNUC__)
    __attribute__((sentinel))
#endif
    ;

/* An argument that is no option the command knows: an unknown option
 * when it starts with '-' (not "-" alone: standard input), else the
 * command's operand (what: "INPUT", "SCENE") into *slot, which must not
 * have one yet. */
zs_status zs_cli_operand(const char *a, const char *cmd, const char *what, const char **slot,
                         zs_error *err);

/* A failed command's end: "CMD: message" on stderr; returns the exit
 * status (zs_cli_exit_status). */
int zs_cli_fail(const char *cmd, const zs_error *err, int parsing);

/* Progress of a long command on stderr: on a terminal, a bar with the
 * time so far and an estimate of the rest, redrawn in place; elsewhere (a
 * log, a pipe) a plain line every few seconds, such as
 *   walk: frame 120/400 (30 %), 14 s, about 33 s left
 * so that a long run is never silent (the environment's ZSCAN_PROGRESS_MS
 * sets the interval, in ms).  quiet: nothing at all. */
typedef struct zs_progress {
  const char *label, *unit; /* "walk", "frame" */
  int total, quiet, tty;
  double start_ms, last_ms, interval_ms;
} zs_progress;

void zs_progress_start(zs_progress *p, const char *label, const char *unit, int total, int quiet);
/* done of total finished (1 .. total). */
void zs_progress_step(zs_progress *p, int done);

/* The median of v[0..n-1], n > 0 (sorts v). */
double zs_median(double *v, int n);


#endif
