/* zscan tests — shared helpers for the check suites. */
#ifndef ZS_TESTUTIL_H
#define ZS_TESTUTIL_H

#include <check.h>
#include <stddef.h>
#include <stdint.h>

/* Runs the suite and returns the process exit status (0 when all passed). */
int zs_test_run(Suite *s);

/* A path below the source tree (tests/data/...) or the build tree, in a
 * static buffer that the next call overwrites. */
const char *zs_test_src(const char *rel);
const char *zs_test_bin(const char *rel);

/* 64-bit FNV-1a of a byte buffer, for comparing images by hash. */
uint64_t zs_test_fnv1a(const void *data, size_t n);
/* FNV-1a of n named values, each as its 8 bytes, low byte first: a hash
 * of the fields a test names, which a field added to their struct leaves
 * alone (unlike the hash of the struct's bytes). */
uint64_t zs_test_hash_values(const uint64_t *v, size_t n);

/* Golden values: facts a test pins (hashes of images, scenes, trees,
 * counters) live in tests/golden/FILE, one "NAME HEX" line each, never in
 * the test's source.  zs_golden_check compares got with NAME's value: 1
 * when equal, 0 when not, -1 when the file has no NAME (*want: the value,
 * when there is one).  With ZS_GOLDEN_UPDATE set in the environment it
 * writes got as NAME's value instead (the line replaced in place, or
 * added) and returns 1: to accept new values, with a reason in the commit
 * message, run the suite once so. */
int zs_golden_check(const char *file, const char *name, uint64_t got, uint64_t *want);
/* zs_golden_check, failing the test with what differs. */
void zs_golden_assert(const char *file, const char *name, uint64_t got);


/* Runs build/zscan with args (NULL-terminated, without "zscan"); captures
 * stdout and stderr (each cut at cap - 1 bytes, NUL-terminated) and returns
 * the exit status, or -1 when it did not exit normally (a crash). */
int zs_test_run_zscan(const char *const *args, char *out, size_t out_cap, char *err,
                      size_t err_cap);

/* Reads the file at path into buf (at most cap - 1 bytes, NUL-terminated;
 * the test fails when it cannot be opened); returns the bytes read. */
size_t zs_test_read(const char *path, char *buf, size_t cap);

/* The whole file at path in a malloc'd buffer, its size in *n, a NUL
 * after its last byte (text can be read as a string); the test fails
 * when it cannot be read. */
unsigned char *zs_test_slurp(const char *path, size_t *n);
/* The two files hold the same bytes, and some. */
void zs_test_assert_same_file(const char *a, const char *b);

/* Whether a file exists. */
int zs_test_exists(const char *path);

/* Calls fn(path, user) for every file below dir (recursively, hidden
 * names skipped) whose name ends in one of the n suffixes, any case; a
 * folder that cannot be opened is skipped. */
void zs_test_each_file(const char *dir, const char *const *suffixes, int n,
                       void (*fn)(const char *path, void *user), void *user);

/* A mesh built by hand in a test: mb_vert / mb_face append, mb_free frees. */
#include "raster/raster.h"
typedef struct mesh_buf {
  zs_mesh m;
  int32_t cap_v, cap_f, cap_fv;
} mesh_buf;
int32_t mb_vert(mesh_buf *b, double x, double y, double z);
void mb_face(mesh_buf *b, const int32_t *v, int n, uint32_t rgb);
void mb_free(mesh_buf *b);
/* A fan of n triangles around (cx, cy) at depth 0: a regular n-gon of
 * radius r, white. */
void mb_fan(mesh_buf *b, double cx, double cy, double r, int n);
/* A closed UV sphere of radius r around (cx, cy, cz): triangles at the
 * poles, quads between; counter-clockwise seen from outside, or from
 * inside when inward. */
void mb_sphere(mesh_buf *b, double cx, double cy, double cz, double r, int slices, int stacks,
               int inward);

#endif
