/* zscan tools — the device clock's parameters on the command line and in
 * JSON files.
 *
 * A clock file is one JSON object whose keys are the fields of
 * zs_clock_params (raster/raster.h), in nanoseconds:
 *   {"per_call_ns": 2000, "per_polygon_ns": 20, ..., "query_latency_ns": 200000}
 * Keys left out keep their defaults; an unknown key, a value that is not a
 * number, or a negative one is an error naming the key.  `zscan calibrate`
 * writes such a file, with one more key saying where each value came from:
 *   "source": {"per_call_ns": "measured", ..., "query_latency_ns": "default"}  On the command line:
 *   --clock FILE.json        read a clock file
 *   --clock-set KEY=VALUE    set one parameter (after any --clock)
 */
#ifndef ZS_TOOLS_CLOCKFILE_H
#define ZS_TOOLS_CLOCKFILE_H

#include <stdio.h>

#include "raster/raster.h"

/* Names and addresses of the parameters, in the order of the struct. */
typedef struct zs_clockfile_field {
  const char *name;
  size_t offset;
} zs_clockfile_field;
extern const zs_clockfile_field zs_clockfile_fields[];
extern const int zs_clockfile_nfields;

zs_status zs_clockfile_load(const char *path, zs_clock_params *p, zs_error *err);
/* KEY=VALUE */
zs_status zs_clockfile_set(const char *assignment, zs_clock_params *p, zs_error *err);
/* Writes p as a clock file (through lib/outfile.h); measured: NULL, or
 * one flag per field of zs_clockfile_fields, written as the "source" key. */
zs_status zs_clockfile_write(const char *path, const zs_clock_params *p,
                             const unsigned char *measured, zs_error *err);
/* The same JSON to a stream (one object, keys in struct order). */
void zs_clockfile_print(FILE *f, const zs_clock_params *p, const unsigned char *measured);

#endif
