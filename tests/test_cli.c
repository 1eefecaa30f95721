/* The zscan command as a user meets it: error messages and exit status on
 * bad files and bad options, and outputs that are never half written. */
#include <cjson/cJSON.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <strings.h>
#include <unistd.h>

#include "tests/testutil.h"
#include "tools/cli.h"
#include "tools/clockfile.h"
#include "tools/commands.h"
#include "util/os.h"
#include "lib/image.h"

static char out[1 << 16], err[1 << 16];

/* Exactly one line on stderr. */
static int one_line(const char *s) {
  const char *nl = strchr(s, '\n');
  return nl && nl[1] == '\0';
}

START_TEST(bad_obj_files_refused_with_file_and_line) {
  /* Every file of tests/data/bad_obj: exit 1, one line
   * "zscan render: PATH:LINE: reason", no image written. */
  const char *dir = zs_test_src("tests/data/bad_obj");
  char dirbuf[4096];
  snprintf(dirbuf, sizeof dirbuf, "%s", dir);
  DIR *d = opendir(dirbuf);
  ck_assert_ptr_nonnull(d);
  int files = 0;
  struct dirent *e;
  char png[4096];
  snprintf(png, sizeof png, "%s/cli-bad.png", ZS_BINARY_DIR);
  while ((e = readdir(d))) {
    size_t n = strlen(e->d_name);
    if (n < 5 || strcmp(e->d_name + n - 4, ".obj") != 0) continue;
    char path[8192];
    snprintf(path, sizeof path, "%s/%s", dirbuf, e->d_name);
    unlink(png);
    const char *args[] = {"render", path, "-o", png, "--size", "32x32", NULL};
    int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
    ck_assert_msg(rc == 1, "%s: exit %d (stderr: %s)", e->d_name, rc, err);
    /* the file named is the OBJ, or the material library beside it */
    char prefix[8300];
    snprintf(prefix, sizeof prefix, "zscan render: %.*s.", (int)(strlen(path) - 4), path);
    ck_assert_msg(strncmp(err, prefix, strlen(prefix)) == 0, "%s: message '%s'", e->d_name, err);
    const char *p = strchr(err + strlen(prefix), ':');
    ck_assert_msg(p && (strncmp(p - 4, ".obj", 4) == 0 || strncmp(p - 4, ".mtl", 4) == 0),
                  "%s: message '%s'", e->d_name, err);
    p++;
    ck_assert_msg(*p >= '1' && *p <= '9', "%s: no line number in '%s'", e->d_name, err);
    while (*p >= '0' && *p <= '9') p++;
    ck_assert_msg(strncmp(p, ": ", 2) == 0 && p[2] != '\n', "%s: no reason in '%s'", e->d_name, err);
    ck_assert_msg(one_line(err), "%s: not one line: '%s'", e->d_name, err);
    ck_assert_msg(!zs_test_exists(png), "%s: an image was written", e->d_name);
    files++;
  }
  closedir(d);
  ck_assert_int_ge(files, 10);
}
END_TEST

/* Every file of a directory of broken inputs through `zscan render`: exit 1,
 * one line "zscan render: PATH...: reason", no image. */
static void refuse_every_file(const char *rel, const char *suffix) {
  char dirbuf[4096];
  snprintf(dirbuf, sizeof dirbuf, "%s", zs_test_src(rel));
  DIR *d = opendir(dirbuf);
  ck_assert_ptr_nonnull(d);
  char png[4096];
  snprintf(png, sizeof png, "%s/cli-bad-file.png", ZS_BINARY_DIR);
  int files = 0;
  struct dirent *e;
  while ((e = readdir(d))) {
    size_t n = strlen(e->d_name), k = strlen(suffix);
    if (e->d_name[0] == '.' || n < k || strcmp(e->d_name + n - k, suffix) != 0) continue;
    char path[8192], prefix[8300];
    snprintf(path, sizeof path, "%s/%s", dirbuf, e->d_name);
    unlink(png);
    const char *args[] = {"render", path, "-o", png, "--size", "32x24", NULL};
    int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
    ck_assert_msg(rc == 1, "%s: exit %d (stderr: %s)", e->d_name, rc, err);
    snprintf(prefix, sizeof prefix, "zscan render: %s", path);
    ck_assert_msg(strncmp(err, prefix, strlen(prefix)) == 0 && err[strlen(prefix)] == ':',
                  "%s: message '%s'", e->d_name, err);
    ck_assert_msg(one_line(err), "%s: not one line: '%s'", e->d_name, err);
    ck_assert_msg(!zs_test_exists(png), "%s: an image was written", e->d_name);
    files++;
  }
  closedir(d);
  ck_assert_int_ge(files, 10);
}

START_TEST(bad_scene_files_refused) { refuse_every_file("tests/data/bad_scene", ".json"); }
END_TEST

START_TEST(bad_model_files_refused) { refuse_every_file("tests/data/bad_models", ""); }
END_TEST

typedef struct bad_option {
  const char *args[12];
  const char *message; /* a part of the one-line message */
  int status;          /* the exit status: 2 for a usage error, 1 for the rest */
} bad_option;

static const bad_option bad_options[] = {
    {{"render", "--size", "0x0", NULL}, "--size: 0x0: each side must be 1 to 16384", 2},
    {{"render", "--size", "100000x100000", NULL}, "each side must be 1 to 16384", 2},
    {{"render", "--size", "12", NULL}, "--size: expected WxH, got '12'", 2},
    {{"render", "--eye", "1,nan,2", NULL}, "--eye: expected x,y,z", 2},
    {{"render", "--eye", "-1,-2", NULL}, "--eye: expected x,y,z", 2},
    {{"render", "--fovy", "0", NULL}, "--fovy: expected degrees above 0 and below 180, got '0'", 2},
    {{"render", "--fovy", "180", NULL}, "--fovy: expected degrees above 0 and below 180", 2},
    {{"render", "--fovy", "inf", NULL}, "--fovy: expected a finite number", 2},
    {{"render", "--near", "0", NULL}, "--near: 0: a perspective camera's near plane must be above 0", 2},
    {{"render", "--near", "-1", NULL}, "--near: -1: a perspective camera's near plane must be", 2},
    {{"render", "--near", "5", "--far", "5", NULL}, "--near 5 --far 5: near must be less than far", 2},
    {{"render", "--far", "1", "--near", "5", NULL}, "--near 5 --far 1: near must be less than far", 2},
    {{"render", "--up", "0,0,0", NULL}, "--up: expected a direction, got '0,0,0'", 2},
    {{"render", "--ortho", "1,-1,-1,1", NULL}, "--ortho: expected L < R and B < T", 2},
    {{"render", "--camera", "0", "--fovy", "30", NULL}, "--camera and --fovy: the file's camera", 2},
    {{"render", "--eye", "0,10,0", "--target", "0,0,0", "--up", "0,1,0", NULL},
     "up 0,1,0: zero or parallel to the view direction", 1},
    {{"render", "--eye", "1,1,1", "--target", "1,1,1", NULL}, "eye and target are the same point", 1},
    {{"render", "-o", "/nonexistent-dir/x.png", NULL},
     "-o /nonexistent-dir/x.png: no such directory: /nonexistent-dir", 1},
    {{"render", "--depth", "/nonexistent-dir/x.pfm", NULL},
     "--depth /nonexistent-dir/x.pfm: no such directory: /nonexistent-dir", 1},
    {{"render", "-o", "/", NULL}, "-o /: is a directory", 1},
    {{"render", "--frobnicate", NULL}, "unknown option '--frobnicate'", 2},
    {{"render", "--algo", "painter", NULL}, "--algo: expected zbuffer, scanline or depthsort", 2},
    {{"render", "--style", "sketch", NULL},
     "--style: expected solid, hidden-line or solid+wireframe, got 'sketch'", 2},
    {{"render", "--style", "solid+wireframe", "--algo", "scanline", NULL},
     "--style solid+wireframe needs --algo zbuffer and a shading of the surfaces (not id, depth "
     "or overdraw)", 2},
    {{"render", "--style", "solid+wireframe", "--shade", "depth", NULL},
     "--style solid+wireframe needs --algo zbuffer", 2},
    {{"render", "--overlay", "culling", NULL}, "--overlay culling needs --cull METHOD", 2},
    {{"render", "--shadows", "--shade", "gouraud", NULL},
     "--shadows needs --shade auto or phong (lit at each pixel), not gouraud", 2},
    {{"render", "--shadows", "--style", "hidden-line", NULL},
     "--shadows: the hidden-line style draws no light", 2},
    {{"render", "--shadow-size", "8", NULL}, "--shadow-size: 8 is outside 16 .. 8192", 2},
    {{"render", "--samples", "3", NULL}, "--samples: expected 1, 2, 4, 8 or 16, got 3", 2},
    {{"render", "--line-width", "0", NULL},
     "--line-width: expected a number above 0 and at most 64 (pixels), got 0", 2},
    {{"render", "--point-size", "65", NULL},
     "--point-size: expected a number above 0 and at most 64 (pixels), got 65", 2},
    {{"render", "--point-size", "nan", NULL}, "--point-size: expected a finite number, got 'nan'", 2},
    {{"render", "--point-shape", "star", NULL},
     "--point-shape: expected square or disc, got 'star'", 2},
    {{"render", "--supersample", NULL}, "--supersample needs --samples 2, 4, 8 or 16", 2},
    {{"render", "--samples", "4", "--shade", "id", NULL},
     "--samples: not with --shade id (ids do not average): one sample a pixel", 2},
    {{"render", "--samples", "4", "--cull", "chc", NULL},
     "--samples: not with --cull: one sample a pixel", 2},
    {{"render", "--shadow-bias", "1", NULL},
     "--shadow-bias: expected UNITS,SLOPE (two finite numbers), got '1'", 2},
    {{"render", "--shadow-bias", "-1,2", NULL},
     "--shadow-bias: -1,2: UNITS 0 to 4294967296 (2^32), SLOPE 0 to 1000000", 2},
    {{"render", "--cull", "magic", NULL}, "--cull: unknown method 'magic'", 2},
    {{"render", "--cull", "chc", "--algo", "scanline", NULL}, "--cull needs --algo zbuffer", 2},
    {{"render", "--style", "hidden-line", "--algo", "scanline", NULL},
     "--style hidden-line needs --algo zbuffer and --shade auto or flat", 2},
    {{"render", "--shade", "flat", "--light", "dir:0,-1,0", NULL},
     "--light: --shade flat draws no lights (auto, gouraud and phong do)", 2},
    {{"render", "--shade", "pink", NULL}, "--shade: expected auto, flat, unlit, gouraud, phong, normal, id, depth or overdraw", 2},
    {{"render", "-o", "lines.svg", NULL}, "-o: lines.svg: an SVG holds hidden lines (--style hidden-line)", 2},
    {{"render", "--threads", "0", NULL}, "--threads: 0 is outside 1 .. 64", 2},
    {{"render", "--repeat", NULL}, "--repeat: missing value", 2},
    {{"render", "a.obj", "b.obj", NULL}, "more than one INPUT", 2},
    {{"render", "/nonexistent-dir/model.stl", NULL}, "/nonexistent-dir/model.stl: ", 1},
    {{"render", "builtin:nothing", NULL}, "unknown generated scene 'nothing'", 1},
    {{"render", "builtin:cubes?n=0", NULL}, "0 is outside 1 .. 64", 1},
    {{"render", "/nonexistent-dir/m.obj", NULL}, "/nonexistent-dir/m.obj: cannot open", 1},
    {{"render", "--clock-set", "per_pixel_ns=-3", NULL},
     "--clock-set per_pixel_ns: expected nanoseconds from 0 to 1e12, got -3", 2},
    {{"render", "--clock-set", "bogus_ns=3", NULL}, "--clock-set bogus_ns: unknown clock parameter", 2},
    {{"render", "--clock-set", "per_pixel_ns", NULL}, "--clock-set: expected KEY=VALUE", 2},
    {{"render", "--cost-set", "w1", NULL}, "--cost-set: expected KEY=VALUE, got 'w1'", 2},
    {{"render", "--cost-set", "w1=1.5", NULL},
     "--cost-set w1: expected a probability from 0 to 1, got 1.5", 2},
    {{"render", "--cost-set", "tq_ns=x", NULL}, "--cost-set tq_ns: expected a finite number", 2},
    {{"render", "--cost-set", "beta=1", NULL}, "--cost-set beta: unknown cost-model parameter", 2},
    {{"render", "--cost-set", "learn=-1", NULL},
     "--cost-set learn: expected a number of outcomes from 0 to 1e6, got -1", 2},
    {{"render", "--cost-set", "measure=0.5", NULL},
     "--cost-set measure: expected 0 (off) or 1 (on), got 0.5", 2},
    {{"render", "--clock", "/nonexistent-dir/c.json", NULL}, "/nonexistent-dir/c.json: cannot open", 1},
    {{"render", "-o", "x.jpg", NULL}, "-o: x.jpg: zscan writes PNG (FILE.png)", 2},
    {{"render", "--depth", "d.png", NULL}, "--depth: d.png: zscan writes PFM (FILE.pfm)", 2},
    {{"render", "--normals", "n.png", NULL}, "--normals: n.png: zscan writes PFM (FILE.pfm)", 2},
    {{"render", "--layer", "l.png", NULL}, "--layer: l.png: zscan writes ZSL (FILE.zsl)", 2},
    {{"render", "-o", "x.png", "--depth", "same.pfm", "--normals", "same.pfm", NULL},
     "--depth and --normals: both write same.pfm: give each its own file", 2},
    {{"render", "--simd", "neon", NULL},
     "--simd: expected scalar, sse2, avx2, avx512 or best, got 'neon'", 2},
    {{"render", "--layer", "l.zsl", "--algo", "depthsort", NULL},
     "--layer: depthsort's depths are ranks, which do not composite", 2},
    {{"render", "--layer", "l.zsl", "--style", "hidden-line", NULL},
     "--layer: a layer holds faces, not hidden lines (--style solid)", 2},
    {{"render", "--objects", "3-1", NULL},
     "--objects: expected object numbers A or A-B (A <= B), comma-separated, got '3-1'", 2},
    {{"render", "--objects", "1,x", NULL},
     "--objects: expected object numbers A or A-B (A <= B), comma-separated, got '1,x'", 2},
    {{"render", "builtin:cubes,n=2", "--objects", "0-8", "-o", "/tmp/zscan-never.png", NULL},
     "--objects: object 8: the scene has 8 objects (0 to 7)", 1},
    {{"render", "--layer", "l.zsl", "--shade", "id", NULL},
     "--layer: id shading's PNG is marked as ids, which a composite does not keep", 2},
    {{"composite", NULL}, "no layers (see zscan composite --help)", 2},
    {{"composite", "a.zsl", NULL}, "-o OUT.png or --layer OUT.zsl: nothing to write", 2},
    {{"composite", "/nonexistent-dir/a.zsl", "-o", "c.png", NULL},
     "/nonexistent-dir/a.zsl: cannot open: No such file or directory", 1},
    {{"render", "--normals", "-", "-o", "-", NULL},
     "standard output (-) takes one stream: only one of -o -, --depth -, --normals -, --layer - "
     "and --stats",
     2},
    {{"render", "--background", "red", NULL}, "--background: expected RRGGBB (hex), got 'red'", 2},
    {{"render", "builtin:cubes", "--ortho", "-1,1,-1,1", "--fovy", "30", NULL},
     "--fovy and --ortho: an orthographic camera has no field", 2},
    {{"render", "builtin:cubes", "--view", "sideways", NULL},
     "--view: expected front, back, left, right, top, bottom or iso", 2},
    {{"walk", "builtin:cubes", "--cull", "vfc", "--named", "spin", NULL},
     "--named: expected static, translate, roll, yaw, fast, got 'spin'", 2},
    {{"walk", "builtin:cubes", "--cull", "chc", "--reference", "off", "--algos", "scanline", NULL},
     "--reference off: ", 2},
    {{"query", "builtin:cubes", "--format", "xml", NULL}, "--format: expected text or json, got 'xml'",
     2},
    {{"query", "builtin:cubes", "--samples", "3", NULL}, "--samples: expected 1, 2, 4, 8 or 16, got 3",
     2},
    {{"bench", "raster", "--simd", "neon", NULL}, "--simd: scalar, sse2, avx2 or avx512, not 'neon'", 2},
    {{"bench", "raster", "--speedup", NULL}, "--speedup: against --threads N, N of 2 or more", 2},
    {{"bench", "raster", "--case", "triangles 7x7", NULL}, "--case 'triangles 7x7': no such case", 1},
};

/* Help comes first, even beside an option the command does not know. */
static const char *const help_commands[][3] = {
    {"render", NULL}, {"walk", NULL}, {"trace", NULL}, {"query", NULL}, {"path", NULL},
    {"bench", "octree"}, {"bench", "depthsort"}, {"bench", "raster"}, {"bench", "tradeoff"},
    {"bench", "suite"}, {"calibrate", NULL}};

START_TEST(help_before_anything_else) {
  const char *const *c = help_commands[_i];
  const char *args[6];
  int n = 0;
  args[n++] = c[0];
  if (c[1]) args[n++] = c[1];
  args[n++] = "--frobnicate";
  args[n++] = "-h";
  args[n] = NULL;
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  ck_assert_msg(rc == 0, "%s: exit %d, stderr '%s'", c[0], rc, err);
  char want[64];
  snprintf(want, sizeof want, "usage: zscan %s%s%s", c[0], c[1] ? " " : "", c[1] ? c[1] : "");
  ck_assert_msg(strncmp(out, want, strlen(want)) == 0, "%s: '%.60s'", c[0], out);
  ck_assert_str_eq(err, "");
}
END_TEST

/* Every command of zscan's table answers --help, and `zscan help NAME`
 * says the same: a command added to the table is covered here. */
START_TEST(every_command_of_the_table_has_help) {
  const char *name = zs_commands[_i].name;
  static char help_out[sizeof out];
  const char *args[] = {name, "--help", NULL};
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  ck_assert_msg(rc == 0, "%s: exit %d, stderr '%s'", name, rc, err);
  char want[64];
  snprintf(want, sizeof want, "usage: zscan %s", name);
  ck_assert_msg(strncmp(out, want, strlen(want)) == 0, "%s: '%.60s'", name, out);
  const char *help[] = {"help", name, NULL};
  rc = zs_test_run_zscan(help, help_out, sizeof help_out, err, sizeof err);
  ck_assert_int_eq(rc, 0);
  ck_assert_str_eq(help_out, out);
}
END_TEST

START_TEST(bad_option_refused) {
  const bad_option *b = &bad_options[_i];
  char png[4096];
  snprintf(png, sizeof png, "%s/cli-opt-%d.png", ZS_BINARY_DIR, _i);
  unlink(png); /* an earlier run's image must not read as this run's */
  /* "render -o PNG" first, unless the case names its own output */
  const char *args[16];
  int n = 0, has_o = strcmp(b->args[0], "render") != 0;
  for (int i = 0; b->args[i]; i++) has_o |= strcmp(b->args[i], "-o") == 0;
  args[n++] = b->args[0];
  if (!has_o) {
    args[n++] = "-o";
    args[n++] = png;
  }
  for (int i = 1; b->args[i]; i++) args[n++] = b->args[i];
  args[n] = NULL;
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  ck_assert_msg(rc == b->status, "case %d: exit %d (not %d), stderr '%s'", _i, rc, b->status, err);
  char prefix[64]; /* "zscan render: ", "zscan bench raster: " */
  snprintf(prefix, sizeof prefix, "zscan %s%s%s: ", b->args[0], strcmp(b->args[0], "bench") ? "" : " ",
           strcmp(b->args[0], "bench") ? "" : b->args[1]);
  ck_assert_msg(strncmp(err, prefix, strlen(prefix)) == 0, "case %d: '%s'", _i, err);
  ck_assert_msg(strstr(err, b->message) != NULL, "case %d: '%s' lacks '%s'", _i, err, b->message);
  ck_assert_msg(one_line(err), "case %d: not one line: '%s'", _i, err);
  ck_assert_msg(!zs_test_exists(png), "case %d: an image was written", _i);
}
END_TEST

/* PATH in the build directory, with no file there yet. */
static void fresh_path(char *buf, size_t n, const char *name) {
  snprintf(buf, n, "%s/%s", ZS_BINARY_DIR, name);
  unlink(buf);
}

/* Runs zscan with args, which must succeed, and opens the CSV it wrote. */
static FILE *run_for_csv(const char *const *args, const char *csv) {
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  FILE *f = fopen(csv, "r");
  ck_assert_ptr_nonnull(f);
  return f;
}

#ifndef ZS_SANITIZED
/* The instructions per frame of the 500x500 triangles in zbuffer mode, from
 * the CSV of `bench raster --callgrind`. */
static double callgrind_instructions(const char *csv) {
  const char *args[] = {"bench", "raster", "--case", "triangles 500x500", "--algo", "zbuffer",
                        "--repeat", "1", "--size", "500x500", "--callgrind", "--csv", csv, NULL};
  FILE *f = run_for_csv(args, csv);
  char line[512];
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  ck_assert_ptr_null(fgets(line + 256, 256, f)); /* one case, one mode: one row */
  fclose(f);
  ck_assert_msg(strncmp(line, "triangles 500x500,zbuffer,1,", 28) == 0, "%s", line);
  const char *last = strrchr(line, ',');
  ck_assert_ptr_nonnull(last);
  return atof(last + 1);
}

#endif

START_TEST(bench_raster_counts_instructions) {
  char csv[4096];
  fresh_path(csv, sizeof csv, "cli-callgrind.csv");
#ifdef ZS_SANITIZED
  /* valgrind cannot run a sanitized build: refused up front, nothing written */
  const char *args[] = {"bench", "raster", "--callgrind", "--csv", csv, NULL};
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, err, sizeof err), 1);
  ck_assert_str_eq(err, "zscan bench raster: --callgrind: this zscan is built with sanitizers, "
                        "which valgrind cannot run\n");
  ck_assert(!zs_test_exists(csv));
#else
  /* 64 layers of 250,000 pixels: a few instructions a pixel, the same in
   * two runs but for the sort of the frame times (a handful) */
  double a = callgrind_instructions(csv), b = callgrind_instructions(csv);
  ck_assert_msg(a > 16e6 * 2 && a < 16e6 * 40, "%.0f instructions per frame", a);
  ck_assert_msg(fabs(a - b) < 1e-5 * a, "%.0f then %.0f", a, b);
  unlink(csv);
#endif
}
END_TEST

/* tradeoff.md of bench tradeoff in dir: each walk has all 15 rows (none,
 * 12 methods, 2 modes), and every exact method and the scanline mode get
 * no pixel wrong. */
static void check_tradeoff_md(const char *dir) {
  char path[4300];
  snprintf(path, sizeof path, "%s/tradeoff.md", dir);
  FILE *f = fopen(path, "r");
  ck_assert_ptr_nonnull(f);
  static const char *const exact[] = {"none", "vfc", "hsw", "chc", "chc-prob", "chcpp",
                                      "chcpp-prob", "nohc", "hzb", "ideal-box", "ideal",
                                      "auto", "scanline"};
  char line[1024];
  int heads = 0, rows = 0, exact_rows = 0, depthsort = 0;
  while (fgets(line, sizeof line, f)) {
    if (strncmp(line, "### ", 4) == 0) heads++;
    if (line[0] != '|' || strncmp(line, "|---", 4) == 0 || strncmp(line, "| method", 8) == 0)
      continue;
    rows++;
    char name[64];
    ck_assert_int_eq(sscanf(line, "| %63s |", name), 1);
    depthsort += strcmp(name, "depthsort") == 0;
    for (size_t m = 0; m < sizeof exact / sizeof exact[0]; m++)
      if (strcmp(name, exact[m]) == 0) {
        exact_rows++;
        ck_assert_msg(strstr(line, " | 0 |\n") != NULL, "not exact: %s", line);
      }
  }
  fclose(f);
  ck_assert_int_eq(heads, 3);
  ck_assert_int_eq(rows, 3 * 15);
  ck_assert_int_eq(exact_rows, 3 * 13);
  ck_assert_int_eq(depthsort, 3);
}

START_TEST(bench_suite_writes_every_file) {
  char dir[4096], path[4300];
  snprintf(dir, sizeof dir, "%s/cli-suite", ZS_BINARY_DIR);
  static const char *const files[] = {"raster.csv", "raster.md", "raster.png", "tradeoff.md",
                                      "tradeoff-plant.png", "depthsort.csv", "octree.csv",
                                      "octree.png", "shade-unlit.md", "shade-gouraud.md",
                                      "shade-phong.md", "arrays.md", "samples.md"};
  enum { NFILES = sizeof files / sizeof files[0] };
  for (int k = 0; k < NFILES; k++) {
    snprintf(path, sizeof path, "%s/%s", dir, files[k]);
    unlink(path);
  }
  /* everything small: every walk, method and mode, with its files; a
   * progress line after each benchmark, and the walks of tradeoff */
  const char *args[] = {"bench", "suite", "--quick", "--size", "500x500", "--out", dir, NULL};
  zs_os_setenv("ZSCAN_PROGRESS_MS", "0");
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  zs_os_setenv("ZSCAN_PROGRESS_MS", NULL);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  ck_assert_msg(strstr(err, "bench suite: benchmark 1/13 (7 %), ") != NULL, "%s", err);
  ck_assert_msg(strstr(err, "bench suite: benchmark 13/13 (100 %), ") != NULL, "%s", err);
  ck_assert_msg(strstr(err, "bench tradeoff: walk 3/3, plant\n") != NULL, "%s", err);
  ck_assert_msg(strstr(err, "walk: frame 5/5 (100 %), ") != NULL, "%s", err);
  for (int k = 0; k < NFILES; k++) {
    snprintf(path, sizeof path, "%s/%s", dir, files[k]);
    ck_assert_msg(zs_test_exists(path), "no %s", path);
  }
  /* each benchmark's command is echoed before its output */
  ck_assert_ptr_nonnull(strstr(out, "$ zscan bench raster --csv"));
  ck_assert_ptr_nonnull(strstr(out, "$ zscan bench tradeoff --out"));
  ck_assert_ptr_nonnull(strstr(out, "$ zscan bench raster --shade phong --no-tilings --md"));
  ck_assert_ptr_nonnull(strstr(out, "$ zscan bench depthsort --frames 4 --csv"));
  ck_assert_ptr_nonnull(strstr(out, "$ zscan bench octree --count 500"));
  check_tradeoff_md(dir);
  for (int k = 0; k < 3; k++) {
    static const char *const walks[] = {"teapots", "city", "plant"};
    snprintf(path, sizeof path, "%s/tradeoff-%s.csv", dir, walks[k]);
    ck_assert_msg(zs_test_exists(path), "no %s", path);
  }
}
END_TEST

START_TEST(bench_depthsort_coherence_pays_where_depths_are_kept) {
  /* The comparisons are exact: translation and roll keep the order and
   * insert a few faces (under 2 % of a full sort's comparisons; roll
   * none); slow yaw re-sorts (less than a full sort, more than a tenth);
   * fast motion replaces most faces (more than a tenth). */
  char csv[4096];
  fresh_path(csv, sizeof csv, "cli-depthsort.csv");
  const char *args[] = {"bench", "depthsort", "--frames", "6", "--size", "256x192", "--csv",
                        csv, NULL};
  FILE *f = run_for_csv(args, csv);
  char line[512];
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  ck_assert_str_eq(line, "motion,faces,reused_pct,full_sort_ms,coherent_sort_ms,"
                         "full_comparisons,coherent_comparisons,diff_pixels\n");
  static const char *const motions[4] = {"translate", "roll", "yaw", "fast"};
  double share[4]; /* coherent comparisons over a full sort's */
  for (int m = 0; m < 4; m++) {
    ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
    char name[32];
    double faces, reused, full_ms, coh_ms, full, coherent;
    ck_assert_int_eq(sscanf(line, "%31[^,],%lf,%lf,%lf,%lf,%lf,%lf", name, &faces, &reused,
                            &full_ms, &coh_ms, &full, &coherent), 7);
    ck_assert_str_eq(name, motions[m]);
    ck_assert_msg(full > faces, "%s: %s", motions[m], line);
    if (m < 2) ck_assert_msg(coherent < 0.02 * full, "%s: %s", motions[m], line);
    else ck_assert_msg(coherent > 0.1 * full && coherent < full, "%s: %s", motions[m], line);
    share[m] = coherent / full;
    /* the paper's roll: every face kept, nothing compared */
    if (m == 1) ck_assert_msg(reused == 100.0 && coherent == 0.0, "roll: %s", line);
  }
  /* the paper's order: roll cheapest, then translation, slow yaw, and
   * fast motion gaining least */
  ck_assert_msg(share[1] < share[0] && share[0] < share[2] && share[2] < share[3],
                "shares %g %g %g %g", share[0], share[1], share[2], share[3]);
  fclose(f);
}
END_TEST

START_TEST(bench_raster_writes_csv_and_table) {
  /* the triangle sizes at 500x500, one frame each: the counts are exact
   * (10x10: 2,500 squares of two triangles, 40 layers to reach 200,000
   * triangles; 500x500: one square, 64 layers, the most there are); and
   * the random triangles, both orders (200,000 of 10x10, 3,200 of
   * 100x100: 16 M pixels) */
  char csv[4096], md[4096];
  fresh_path(csv, sizeof csv, "cli-bench.csv");
  fresh_path(md, sizeof md, "cli-bench.md");
  const char *args[] = {"bench", "raster", "--no-scenes", "--no-simd", "--repeat", "1", "--size",
                        "500x500", "--csv", csv, "--md", md, NULL};
  FILE *f = run_for_csv(args, csv);
  ck_assert_str_eq(err, "");
  char line[512];
  int rows = 0;
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  ck_assert_str_eq(line, "case,algo,threads,spans,width,height,triangles,pixels_tested,ms,"
                         "mtri_per_s,mpix_per_s,table_bytes,instructions_per_frame\n");
  static const char *const want[] = {
      "triangles 10x10,zbuffer,1,scalar,500,500,200000,10000000,",
      "triangles 10x10,scanline,1,scalar,500,500,200000,10000000,",
      "triangles 500x500,zbuffer,1,scalar,500,500,128,16000000,",
      "triangles 500x500,scanline,1,scalar,500,500,128,16000000,",
      "random 10x10 back to front,zbuffer,1,scalar,500,500,200000,",
      "random 10x10 front to back,scanline,1,scalar,500,500,200000,",
      "random 100x100 back to front,zbuffer,1,scalar,500,500,3200,"};
  enum { NWANT = sizeof want / sizeof want[0] };
  int found[NWANT] = {0};
  while (fgets(line, sizeof line, f)) {
    rows++;
    for (int k = 0; k < NWANT; k++) found[k] += strncmp(line, want[k], strlen(want[k])) == 0;
  }
  fclose(f);
  ck_assert_int_eq(rows, 26);
  for (int k = 0; k < NWANT; k++) ck_assert_msg(found[k] == 1, "no row '%s'", want[k]);
  ck_assert(zs_test_exists(md));
  ck_assert_ptr_nonnull(strstr(out, "triangles 25x25"));
  /* too small for the largest triangles: refused, nothing written */
  unlink(csv);
  const char *small[] = {"bench", "raster", "--size", "100x100", "--csv", csv, NULL};
  ck_assert_int_eq(zs_test_run_zscan(small, out, sizeof out, err, sizeof err), 2);
  ck_assert_str_eq(err, "zscan bench raster: --size: at least 500x500 (the largest triangles)\n");
  ck_assert(!zs_test_exists(csv));
#if defined(__x86_64__)
  /* --simd sse2: every x86-64 CPU has it, and the CSV says it was used */
  const char *sse2[] = {"bench", "raster", "--no-scenes", "--simd", "sse2", "--case",
                        "triangles 500x500", "--algo", "zbuffer", "--repeat", "1", "--size",
                        "500x500", "--csv", csv, NULL};
  f = run_for_csv(sse2, csv);
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  const char *want_sse2 = "triangles 500x500,zbuffer,1,sse2,500,500,128,16000000,";
  ck_assert_msg(strncmp(line, want_sse2, strlen(want_sse2)) == 0, "%s", line);
  fclose(f);
  ck_assert_ptr_nonnull(strstr(out, "SSE2 spans"));
#endif
  /* --speedup: a scene on one thread and on two, frames in turn; the
   * images are the same (the times are not asserted); scanline mode walks
   * bands of rows on the threads */
  const char *speedup[] = {"bench", "raster", "--case", "builtin:city", "--algo", "scanline",
                           "--threads", "2", "--speedup", "--repeat", "3", "--size", "500x500",
                           NULL};
  ck_assert_int_eq(zs_test_run_zscan(speedup, out, sizeof out, err, sizeof err), 0);
  ck_assert_ptr_nonnull(strstr(out, "zscan on 1 thread and on 2, frames in turn, 3 pairs"));
  const char *row = strstr(out, "\nbuiltin:city ");
  row = row ? strstr(row + 1, "\nbuiltin:city ") : NULL; /* the speed-up table's row */
  ck_assert_ptr_nonnull(row);
  const char *eol = strchr(row + 1, '\n');
  ck_assert_ptr_nonnull(eol);
  ck_assert_msg(eol - row > 4 && strncmp(eol - 4, " yes", 4) == 0, "%.*s", (int)(eol - row), row);
  /* and the ceiling: one thread on each of the 2 CPUs at once (or "-"
   * where the CPUs cannot be pinned) */
  ck_assert_ptr_nonnull(strstr(out, "thread on each of 2 CPUs at once: the ceiling of the speed-up"));
  char fast[32], slow[32], ceiling[32], share[32];
  double one, many, ratio, q1, q3;
  ck_assert_int_eq(sscanf(row, " builtin:city scanline %lf %lf %lf %lf %lf %31s %31s %31s %31s", &one,
                          &many, &ratio, &q1, &q3, fast, slow, ceiling, share),
                   9);
  if (strcmp(ceiling, "-") != 0) {
    ck_assert_double_le(atof(fast), atof(slow));
    ck_assert_double_gt(atof(ceiling), 0.0);
    ck_assert_double_gt(atof(share), 0.0);
  } else {
    ck_assert_str_eq(fast, "-");
  }
}
END_TEST

START_TEST(walk_compares_hidden_surface_modes) {
  /* --algos: scanline mode draws none's image exactly in every frame;
   * depth sort does not on the city (its long street faces) and says by
   * how many pixels; the tradeoff plot is written */
  char csv[4096], png[4096];
  fresh_path(csv, sizeof csv, "cli-walk-algos.csv");
  fresh_path(png, sizeof png, "cli-walk-tradeoff.png");
  const char *args[] = {"walk", "builtin:city", "--cull", "vfc", "--algos", "scanline,depthsort",
                        "--frames", "3", "--size", "160x120", "--csv", csv, "--tradeoff", png,
                        "--quiet", NULL};
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  FILE *f = fopen(csv, "r");
  ck_assert_ptr_nonnull(f);
  char line[512];
  int scan = 0, sort = 0;
  uint64_t sort_wrong = 0;
  /* diff_pixels by its name in the header, and the GPU's split of every
   * frame adding up to its modelled time */
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  ck_assert_str_eq(line, "frame,method,chosen,modelled_ms,stall_ms,wall_ms,queries,queries_hidden,"
                         "faces_drawn,objects_drawn,nodes_visited,diff_pixels,gpu_draw_ms,"
                         "gpu_query_ms,gpu_switch_ms,gpu_idle_ms,hzb_phase1,hzb_phase2,"
                         "hzb_stale,hzb_boxes,hzb_texels,hzb_reads\n");
  while (fgets(line, sizeof line, f)) {
    double col[22];
    int ncol = 0;
    for (const char *p = line; p && ncol < 22; p = strchr(p, ','), p = p ? p + 1 : NULL)
      col[ncol++] = strtod(p, NULL);
    ck_assert_int_eq(ncol, 22);
    unsigned long long wrong = (unsigned long long)col[11];
    double sum = col[12] + col[13] + col[14] + col[15];
    ck_assert_msg(fabs(sum - col[3]) < 5e-6, "split %.6f, modelled %.6f: %s", sum, col[3], line);
    ck_assert_msg(col[12] > 0.0, "no drawing: %s", line);
    if (strstr(line, ",scanline,")) {
      scan++;
      ck_assert_msg(wrong == 0, "scanline differs: %s", line);
    }
    if (strstr(line, ",depthsort,")) sort++, sort_wrong += wrong;
  }
  fclose(f);
  ck_assert_int_eq(scan, 3);
  ck_assert_int_eq(sort, 3);
  ck_assert_uint_gt(sort_wrong, 0);
  ck_assert(zs_test_exists(png));
  const char *bad[] = {"walk", "builtin:city", "--cull", "vfc", "--algos", "raytrace", NULL};
  rc = zs_test_run_zscan(bad, out, sizeof out, err, sizeof err);
  ck_assert_int_eq(rc, 2); /* a usage error */
  ck_assert_str_eq(err, "zscan walk: --algos: expected scanline or depthsort, got 'raytrace'\n");
}
END_TEST

/* Line by line, the CSV's bytes without its wall_ms column (the 6th). */
static void strip_wall_column(char *line) {
  char *p = line;
  for (int c = 0; c < 5; c++) {
    p = strchr(p, ',');
    ck_assert_msg(p != NULL, "too few columns: %s", line);
    p++;
  }
  char *end = strchr(p, ',');
  ck_assert_msg(end != NULL, "too few columns: %s", line);
  memmove(p, end + 1, strlen(end + 1) + 1);
}

START_TEST(walk_csv_same_bytes_every_run_but_wall_time) {
  /* the walk's CSV is byte-identical from run to run apart from
   * its wall-time column, moving objects and every method that asks
   * included */
  char csv[2][4096];
  for (int run = 0; run < 2; run++) {
    char name[64];
    snprintf(name, sizeof name, "cli-walk-again-%d.csv", run);
    fresh_path(csv[run], sizeof csv[run], name);
    const char *args[] = {"walk", "builtin:teapots?count=60&moving=20", "--cull",
                          "vfc,hsw,chc,chc-prob,chcpp,chcpp-prob,nohc,ideal-box,ideal,auto",
                          "--frames", "6", "--step", "11", "--size", "160x120", "--csv", csv[run],
                          "--quiet", NULL};
    int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
    ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  }
  FILE *a = fopen(csv[0], "r"), *b = fopen(csv[1], "r");
  ck_assert_ptr_nonnull(a);
  ck_assert_ptr_nonnull(b);
  char la[512], lb[512];
  int lines = 0;
  while (fgets(la, sizeof la, a)) {
    ck_assert_ptr_nonnull(fgets(lb, sizeof lb, b));
    if (lines == 0) ck_assert_msg(strstr(la, ",modelled_ms,stall_ms,wall_ms,") != NULL, "%s", la);
    strip_wall_column(la);
    strip_wall_column(lb);
    ck_assert_str_eq(la, lb);
    lines++;
  }
  ck_assert_ptr_null(fgets(lb, sizeof lb, b));
  fclose(a);
  fclose(b);
  ck_assert_int_eq(lines, 1 + 6 * 11); /* the header, 6 frames of none and ten methods */
}
END_TEST

START_TEST(huge_obj_refused_before_reading) {
  /* a sparse file one byte over the limit: refused at once */
  char path[4096];
  snprintf(path, sizeof path, "%s/cli-huge.obj", ZS_BINARY_DIR);
  FILE *f = fopen(path, "w");
  ck_assert_ptr_nonnull(f);
  fclose(f);
  ck_assert_int_eq(truncate(path, ((off_t)1 << 30) + 1), 0);
  const char *args[] = {"render", path, "-o", "/tmp/zscan-huge.png", NULL};
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  char want[8300];
  snprintf(want, sizeof want, "zscan render: %s: larger than 1024 MiB\n", path);
  ck_assert_int_eq(rc, 1);
  ck_assert_str_eq(err, want);
  unlink(path);
}
END_TEST

/* Inputs with nothing to draw are refused, each with its file named;
 * --allow-empty renders the background alone. */
START_TEST(empty_inputs_refused_unless_allowed) {
  static const char junk[] = "\x7f" "ELF\x02\x01\x01\n\x03\x3e\x00\x01\x00\x00";
  static const struct {
    const char *name, *text, *why;
    size_t len; /* 0: strlen(text) */
  } cases[] = {
      {"cli-empty.obj", "", "no faces, lines or points", 0},
      {"cli-vertices.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "no faces, lines or points", 0},
      {"cli-junk.obj", junk, ":1: not an OBJ statement", sizeof junk - 1},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    char path[4096], png[4096];
    snprintf(path, sizeof path, "%s/%s", ZS_BINARY_DIR, cases[i].name);
    snprintf(png, sizeof png, "%s/cli-empty.png", ZS_BINARY_DIR);
    unlink(png);
    FILE *f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    fwrite(cases[i].text, 1, cases[i].len ? cases[i].len : strlen(cases[i].text), f);
    ck_assert_int_eq(fclose(f), 0);
#ifndef ZS_HAVE_ASSIMP
    if (strstr(cases[i].name, ".ply")) continue; /* no reader for it */
#endif
    const char *args[] = {"render", path, "--size", "32x24", "-o", png, NULL};
    int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
    char want[8300];
    snprintf(want, sizeof want, "zscan render: %s%s%s\n", path,
             cases[i].why[0] == ':' ? "" : ": ", cases[i].why);
    ck_assert_int_eq(rc, 1);
    ck_assert_str_eq(err, want);
    ck_assert(!zs_test_exists(png));
    if (strstr(cases[i].name, "junk")) continue; /* junk stays junk */
    if (strstr(cases[i].name, ".ply")) continue; /* assimp will not load it */
    const char *allowed[] = {"render", path, "--size", "32x24", "-o", png, "--allow-empty", NULL};
    rc = zs_test_run_zscan(allowed, out, sizeof out, err, sizeof err);
    ck_assert_msg(rc == 0, "%s: %s", cases[i].name, err);
    zs_image im;
    zs_error e;
    zs_error_clear(&e);
    ck_assert_int_eq(zs_png_read(png, &im, &e), ZS_OK);
    ck_assert_int_eq(im.width, 32);
    for (int k = 0; k < im.width * im.height; k++) ck_assert_uint_eq(im.rgb[k], im.rgb[0]);
    zs_image_free(&im);
    unlink(path);
  }
}
END_TEST

/* A material whose texture cannot be opened: exit 1 with the library's
 * line; with --skip-missing-textures exit 0, a warning naming it (none
 * with -q), and the image of the same model whose material has no
 * texture at all. */
START_TEST(render_skips_missing_textures) {
  char obj[4096], png[4200], plain_obj[4200], plain_mtl[4200], plain_png[4200], want[8400];
  snprintf(obj, sizeof obj, "%s", zs_test_src("tests/data/obj/missing_texture.obj"));
  snprintf(png, sizeof png, "%s/cli-notex.png", ZS_BINARY_DIR);
  unlink(png);
  const char *refused[] = {"render", obj, "--size", "32x24", "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(refused, out, sizeof out, err, sizeof err), 1);
  const char *why = "map_Kd nothing here.png: cannot open: No such file or directory";
  snprintf(want, sizeof want, "zscan render: %s: %s\n",
           zs_test_src("tests/data/obj/missing_texture.mtl:4"), why);
  ck_assert_str_eq(err, want);
  ck_assert(!zs_test_exists(png));

  const char *skipped[] = {"render", obj, "--size", "32x24", "-o", png, "--skip-missing-textures",
                           NULL};
  ck_assert_int_eq(zs_test_run_zscan(skipped, out, sizeof out, err, sizeof err), 0);
  snprintf(want, sizeof want,
           "zscan render: warning: %s: %s: drawn without it\n"
           "zscan render: wrote %s: 32x24, 1 faces, ",
           zs_test_src("tests/data/obj/missing_texture.mtl:4"), why, png);
  ck_assert_msg(strncmp(err, want, strlen(want)) == 0, "%s", err);
  ck_assert_str_eq(out, "");
  const char *quiet[] = {"render", obj, "--size", "32x24", "-o", png, "--skip-missing-textures",
                         "-q", NULL};
  ck_assert_int_eq(zs_test_run_zscan(quiet, out, sizeof out, err, sizeof err), 0);
  ck_assert_str_eq(err, "");

  /* the same model and material, without map_Kd */
  snprintf(plain_obj, sizeof plain_obj, "%s/cli-notex-plain.obj", ZS_BINARY_DIR);
  snprintf(plain_mtl, sizeof plain_mtl, "%s/cli-notex-plain.mtl", ZS_BINARY_DIR);
  snprintf(plain_png, sizeof plain_png, "%s/cli-notex-plain.png", ZS_BINARY_DIR);
  FILE *f = fopen(plain_obj, "w");
  ck_assert_ptr_nonnull(f);
  fputs("mtllib cli-notex-plain.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl gone\nf 1 2 3\n", f);
  ck_assert_int_eq(fclose(f), 0);
  ck_assert_ptr_nonnull(f = fopen(plain_mtl, "w"));
  fputs("newmtl gone\nKd 1 0 0\n", f);
  ck_assert_int_eq(fclose(f), 0);
  const char *plain[] = {"render", plain_obj, "--size", "32x24", "-o", plain_png, "-q", NULL};
  ck_assert_int_eq(zs_test_run_zscan(plain, out, sizeof out, err, sizeof err), 0);
  zs_test_assert_same_file(png, plain_png);
  unlink(plain_obj);
  unlink(plain_mtl);
  unlink(plain_png);
  unlink(png);
}
END_TEST

/* calibrate measures what this device shows and keeps the modelled
 * values of what it cannot (latency, switch, CPU side), saying which; the
 * file it writes reads back with its latency. */
START_TEST(calibrate_keeps_the_modelled_latency) {
  char clock[4096];
  snprintf(clock, sizeof clock, "%s/cli-clock.json", ZS_BINARY_DIR);
  unlink(clock);
  const char *args[] = {"calibrate", "-o", clock, "--repeat", "1", NULL};
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  ck_assert_msg(rc == 0, "%s", err);
  ck_assert_ptr_nonnull(strstr(out, "per_pixel_ns"));
  const char *lat = strstr(out, "query_latency_ns");
  ck_assert_ptr_nonnull(lat);
  const char *eol = strchr(lat, '\n');
  ck_assert_msg(eol && strstr(lat, "200000.0000 ns  default") != NULL &&
                    strstr(lat, "200000.0000 ns  default") < eol,
                "%s", lat);
  char text[4096];
  zs_test_read(clock, text, sizeof text);
  ck_assert_ptr_nonnull(strstr(text, "\"query_latency_ns\":200000,"));
  ck_assert_ptr_nonnull(strstr(text, "\"switch_ns\":1000,"));
  ck_assert_ptr_nonnull(strstr(text, "\"per_pixel_ns\":\"measured\""));
  ck_assert_ptr_nonnull(strstr(text, "\"query_latency_ns\":\"default\""));
  /* the depth pyramid's costs are this device's own, measured */
  ck_assert_ptr_nonnull(strstr(text, "\"hzb_per_texel_ns\":\"measured\""));
  ck_assert_ptr_nonnull(strstr(text, "\"hzb_per_box_ns\":\"measured\""));
  ck_assert_ptr_nonnull(strstr(text, "\"hzb_per_read_ns\":\"measured\""));
  ck_assert_ptr_nonnull(strstr(out, "boxes walled 8"));
  zs_clock_params p;
  zs_clock_params_default(&p);
  p.query_latency_ns = 0;
  zs_error e;
  zs_error_clear(&e);
  ck_assert_msg(zs_clockfile_load(clock, &p, &e) == ZS_OK, "%s", e.msg);
  ck_assert(p.query_latency_ns == 200000.0);
  unlink(clock);
}
END_TEST

/* A long command behind a pipe or in a log is never silent: plain
 * progress lines on stderr (every ZSCAN_PROGRESS_MS, 5 s by default; 0
 * here, a line every frame, as a walk this small can end within 1 ms);
 * --quiet leaves stderr empty. */
START_TEST(progress_in_logs_unless_quiet) {
  zs_os_setenv("ZSCAN_PROGRESS_MS", "0");
  const char *args[] = {"walk", "builtin:cubes,n=3", "--cull", "vfc", "--frames", "20", "--size",
                        "64x48", NULL};
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, err, sizeof err), 0);
  ck_assert_msg(strstr(err, "walk: frame ") && strstr(err, "/20 ("), "%s", err);
  ck_assert_ptr_nonnull(strstr(err, "walk: frame 20/20 (100 %)"));
  const char *quiet[] = {"walk", "builtin:cubes,n=3", "--cull", "vfc", "--frames", "20",
                         "--size", "64x48", "--quiet", NULL};
  ck_assert_int_eq(zs_test_run_zscan(quiet, out, sizeof out, err, sizeof err), 0);
  ck_assert_str_eq(err, "");
  zs_os_setenv("ZSCAN_PROGRESS_MS", NULL);
}
END_TEST

/* -o FILE.svg with --style hidden-line: the PNG's lines as vectors.  Every
 * run lies in the image and on the PNG's ink (its middle in a black pixel
 * or one beside it), the runs cover the PNG's ink, and the same options
 * give the same bytes. */
START_TEST(hidden_lines_as_svg) {
  char svg[4096], svg2[4096], png[4096];
  snprintf(svg, sizeof svg, "%s/cli-lines.svg", ZS_BINARY_DIR);
  snprintf(svg2, sizeof svg2, "%s/cli-lines-2.svg", ZS_BINARY_DIR);
  snprintf(png, sizeof png, "%s/cli-lines.png", ZS_BINARY_DIR);
  const char *as_svg[] = {"render", "builtin:cubes", "--style", "hidden-line", "--size", "320x240",
                          "-q", "-o", svg, NULL};
  ck_assert_int_eq(zs_test_run_zscan(as_svg, out, sizeof out, err, sizeof err), 0);
  as_svg[8] = svg2;
  ck_assert_int_eq(zs_test_run_zscan(as_svg, out, sizeof out, err, sizeof err), 0);
  as_svg[8] = png;
  ck_assert_int_eq(zs_test_run_zscan(as_svg, out, sizeof out, err, sizeof err), 0);

  static char text[1 << 20], text2[1 << 20];
  size_t n = zs_test_read(svg, text, sizeof text);
  ck_assert(n > 0 && n < sizeof text - 1);
  ck_assert_uint_eq(zs_test_read(svg2, text2, sizeof text2), n);
  ck_assert(memcmp(text, text2, n) == 0);
  ck_assert_ptr_nonnull(strstr(text, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"320\" "
                                     "height=\"240\" viewBox=\"0 0 320 240\">"));
  ck_assert_ptr_nonnull(strstr(text, "<rect width=\"320\" height=\"240\" fill=\"#ffffff\"/>"));
  ck_assert_ptr_nonnull(strstr(text, "stroke=\"#000000\" stroke-width=\"1\""));

  zs_image im;
  zs_error e;
  zs_error_clear(&e);
  ck_assert_int_eq(zs_png_read(png, &im, &e), ZS_OK);
  const int w = im.width, h = im.height;
  unsigned char *covered = calloc((size_t)w * (size_t)h, 1);
  ck_assert_ptr_nonnull(covered);
  int runs = 0;
  for (const char *p = strchr(text, 'M'); p; p = strchr(p + 1, 'M')) {
    double x0, y0, x1, y1;
    ck_assert_int_eq(sscanf(p, "M%lf %lfL%lf %lf", &x0, &y0, &x1, &y1), 4);
    ck_assert(x0 >= 0 && x0 <= w && x1 >= 0 && x1 <= w && y0 >= 0 && y0 <= h && y1 >= 0 && y1 <= h);
    int ink = 0;
    int mx = (int)((x0 + x1) / 2), my = (int)((y0 + y1) / 2);
    for (int dy = -1; dy <= 1; dy++)
      for (int dx = -1; dx <= 1; dx++) {
        int x = mx + dx, y = my + dy;
        if (x >= 0 && y >= 0 && x < w && y < h) ink |= (im.rgb[(size_t)y * w + x] & 0xFFFFFF) == 0;
      }
    ck_assert_msg(ink, "run %d (%g,%g)-(%g,%g) is not on the PNG's lines", runs, x0, y0, x1, y1);
    /* the pixels along the run, sampled every quarter pixel */
    double len = fabs(x1 - x0) > fabs(y1 - y0) ? fabs(x1 - x0) : fabs(y1 - y0);
    int steps = (int)(len * 4) + 1;
    for (int k = 0; k <= steps; k++) {
      double t = (double)k / steps;
      int x = (int)(x0 + t * (x1 - x0)), y = (int)(y0 + t * (y1 - y0));
      if (x >= 0 && y >= 0 && x < w && y < h) covered[(size_t)y * w + x] = 1;
    }
    runs++;
  }
  ck_assert_int_gt(runs, 100);
  /* every black pixel of the PNG is on a run */
  for (int y = 0; y < h; y++)
    for (int x = 0; x < w; x++)
      if ((im.rgb[(size_t)y * w + x] & 0xFFFFFF) == 0)
        ck_assert_msg(covered[(size_t)y * w + x], "ink at (%d,%d) is on no run", x, y);
  free(covered);
  zs_image_free(&im);

  /* --line-width: the stroke as wide as the PNG's edges, rounded as they are */
  const char *wide[] = {"render", "builtin:cubes", "--style", "hidden-line", "--size", "320x240",
                        "--line-width", "2.5", "-q", "-o", svg, NULL};
  ck_assert_int_eq(zs_test_run_zscan(wide, out, sizeof out, err, sizeof err), 0);
  n = zs_test_read(svg, text, sizeof text);
  ck_assert(n > 0 && n < sizeof text - 1);
  text[n] = '\0';
  ck_assert_ptr_nonnull(strstr(text, "stroke=\"#000000\" stroke-width=\"3\""));
}
END_TEST

/* The hidden-line picture is ink on paper whatever the model holds: a
 * transparent box is paper that hides, as in the SVG, not its colour
 * composited; a model's own lines and points are drawn over the paper
 * (the spiral round wire_cube.obj), not hidden under it. */
START_TEST(hidden_lines_of_glass_and_model_lines) {
  char png[4096];
  snprintf(png, sizeof png, "%s/cli-hidden-glass.png", ZS_BINARY_DIR);
  const char *glass[] = {"render", zs_test_src("tests/data/scenes/glass_box_beside_box.json"),
                         "--style", "hidden-line", "--size", "160x120", "-q", "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(glass, out, sizeof out, err, sizeof err), 0);
  zs_image im;
  zs_error e;
  zs_error_clear(&e);
  ck_assert_int_eq(zs_png_read(png, &im, &e), ZS_OK);
  int ink = 0;
  for (int i = 0; i < im.width * im.height; i++) {
    const uint32_t c = im.rgb[i] & 0xFFFFFFu;
    ck_assert_msg(c == 0xFFFFFFu || c == 0, "pixel %d: %06X, neither paper nor ink", i, (unsigned)c);
    ink += c == 0;
  }
  ck_assert_int_gt(ink, 200);
  zs_image_free(&im);
  const char *wire[] = {"render", zs_test_src("tests/data/scenes/wire_cube.obj"), "--style",
                        "hidden-line", "--eye", "4,3,6", "--target", "0,0,0", "--size", "240x180",
                        "-q", "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(wire, out, sizeof out, err, sizeof err), 0);
  ck_assert_int_eq(zs_png_read(png, &im, &e), ZS_OK);
  int coloured = 0;
  for (int i = 0; i < im.width * im.height; i++) {
    const uint32_t c = im.rgb[i] & 0xFFFFFFu;
    coloured += c != 0xFFFFFFu && c != 0;
  }
  ck_assert_int_gt(coloured, 100); /* the spiral, in its colour */
  zs_image_free(&im);
}
END_TEST

/* --background: flat shading's background, where no face is. */
START_TEST(render_background) {
  char png[4096];
  snprintf(png, sizeof png, "%s/cli-background.png", ZS_BINARY_DIR);
  const char *args[] = {"render", "builtin:cubes,n=1", "--size", "64x48", "--background", "10a0Ff",
                        "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, err, sizeof err), 0);
  zs_image im;
  zs_error e;
  zs_error_clear(&e);
  ck_assert_int_eq(zs_png_read(png, &im, &e), ZS_OK);
  ck_assert_uint_eq(im.rgb[0], 0x10A0FF); /* a corner: no cube there */
  int other = 0;
  for (int i = 0; i < im.width * im.height; i++) other += im.rgb[i] != 0x10A0FF;
  ck_assert_int_gt(other, 100); /* and the cube */
  zs_image_free(&im);
}
END_TEST

/* The image hash in a --stats line, into h[17]. */
static void stats_hash(const char *stats, char h[17]) {
  const char *at = strstr(stats, "\"image_hash\":\"");
  ck_assert_msg(at != NULL, "%s", stats);
  memcpy(h, at + 14, 16);
  h[16] = '\0';
}

typedef struct round_trip {
  int rendered, seen; /* files rendered twice, and model files met */
} round_trip;

/* render -v's camera, passed back as options, draws the same bytes. */
static void camera_round_trip(const char *path, void *user) {
  round_trip *r = user;
  r->seen++;
  char png[4096];
  snprintf(png, sizeof png, "%s/cli-camera.png", ZS_BINARY_DIR);
  const char *first[] = {"render", path, "--size", "96x72", "-v", "--stats", "-o", png, NULL};
  if (zs_test_run_zscan(first, out, sizeof out, err, sizeof err) != 0) return;
  char h1[17], h2[17];
  stats_hash(out, h1);
  const char *cam = strstr(err, "zscan render: camera: ");
  ck_assert_msg(cam != NULL, "%s: %s", path, err);
  static char line[4096];
  snprintf(line, sizeof line, "%s", cam + strlen("zscan render: camera: "));
  line[strcspn(line, "\n")] = '\0';
  const char *again[48] = {"render", path, "--size", "96x72", "--stats", "-o", png};
  int k = 7;
  for (char *w = strtok(line, " "); w && k < 46; w = strtok(NULL, " ")) again[k++] = w;
  again[k] = NULL;
  ck_assert_msg(zs_test_run_zscan(again, out, sizeof out, err, sizeof err) == 0, "%s: %s", path,
                err);
  stats_hash(out, h2);
  ck_assert_msg(strcmp(h1, h2) == 0, "%s: %s, again with its camera %s", path, h1, h2);
  r->rendered++;
}

static const char *const model_suffixes[] = {".obj", ".ply", ".stl", ".off", ".gltf", ".json"};
enum { NMODEL_SUFFIXES = sizeof model_suffixes / sizeof model_suffixes[0] };

START_TEST(printed_camera_reproduces_the_image) {
  round_trip r = {0, 0};
  zs_test_each_file(zs_test_src("tests/data"), model_suffixes, NMODEL_SUFFIXES, camera_round_trip, &r);
  zs_test_each_file(zs_test_src("scene/examples"), model_suffixes, NMODEL_SUFFIXES,
                    camera_round_trip, &r);
  int ours = r.rendered;
  ck_assert_int_ge(ours, 20);
  static const char *const assimp_dirs[] = {"OBJ", "PLY", "STL", "OFF", "glTF2"};
  for (size_t k = 0; k < sizeof assimp_dirs / sizeof assimp_dirs[0]; k++) {
    char dir[256];
    snprintf(dir, sizeof dir, "/usr/share/assimp/models/%s", assimp_dirs[k]);
    zs_test_each_file(dir, model_suffixes, NMODEL_SUFFIXES, camera_round_trip, &r);
  }
#ifdef ZS_HAVE_ASSIMP
  ck_assert_int_ge(r.rendered - ours, 30);
#endif
  printf("camera round trip: %d of %d files rendered twice, the same bytes\n", r.rendered, r.seen);
}
END_TEST

/* One convention for every command: an unknown option is a usage error
 * (exit 2), an input file that is not there is bad input (exit 1). */
START_TEST(every_command_exits_2_on_usage_and_1_on_a_missing_input) {
  static const char *const unknown[][6] = {
      {"render", NULL},          {"diff", "a.png", "b.png", NULL}, {"golden", "check", "m.json", NULL},
      {"trace", "x.obj", NULL},  {"walk", "x.json", "--cull", "vfc", NULL},
      {"path", "x.json", NULL},  {"query", "x.obj", NULL},       {"calibrate", NULL},
      {"bench", "octree", NULL}, {"bench", "depthsort", NULL},    {"bench", "raster", NULL},
      {"bench", "tradeoff", NULL}, {"bench", "suite", NULL}};
  for (size_t i = 0; i < sizeof unknown / sizeof unknown[0]; i++) {
    const char *args[8];
    int n = 0;
    for (; unknown[i][n]; n++) args[n] = unknown[i][n];
    args[n++] = "--frobnicate";
    args[n] = NULL;
    int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
    ck_assert_msg(rc == 2, "%s %s --frobnicate: exit %d (%s)", args[0], args[1] ? args[1] : "",
                  rc, err);
    ck_assert_msg(strstr(err, "--frobnicate") != NULL, "%s: %s", args[0], err);
  }
  static const char *const missing[][6] = {
      {"render", "/nonexistent/m.obj", NULL}, {"diff", "/nonexistent/a.png", "/nonexistent/b.png", NULL},
      {"golden", "check", "/nonexistent/m.json", NULL}, {"trace", "/nonexistent/m.obj", NULL},
      {"walk", "/nonexistent/s.json", "--cull", "vfc", NULL}, {"path", "/nonexistent/s.json", NULL},
      {"query", "/nonexistent/m.obj", NULL}, {"bench", "depthsort", "/nonexistent/m.obj", NULL}};
  for (size_t i = 0; i < sizeof missing / sizeof missing[0]; i++) {
    int rc = zs_test_run_zscan(missing[i], out, sizeof out, err, sizeof err);
    ck_assert_msg(rc == 1, "%s: exit %d (%s)", missing[i][0], rc, err);
    ck_assert_msg(strstr(err, "/nonexistent/") != NULL, "%s: %s", missing[i][0], err);
  }
  /* zscan help COMMAND is the command's --help */
  const char *help[] = {"help", "render", NULL};
  ck_assert_int_eq(zs_test_run_zscan(help, out, sizeof out, err, sizeof err), 0);
  ck_assert_ptr_nonnull(strstr(out, "usage: zscan render [INPUT] [options]"));
  ck_assert_ptr_nonnull(strstr(out, "--size WxH"));
}
END_TEST

/* --camera: a camera stored in a model file draws what the same view
 * given by options draws (the glTF camera: at 0.5,0.5,3 looking down -z,
 * yfov 0.7 radians, aspect 1, planes 0.01 and 100). */
START_TEST(camera_from_the_model_file) {
#ifdef ZS_HAVE_ASSIMP
  const char *gltf = "/usr/share/assimp/models/glTF2/cameras/Cameras.gltf";
  if (!zs_test_exists(gltf)) return; /* assimp-testmodels: tools/setup.sh installs it */
  const char *list[] = {"render", gltf, "--list-cameras", NULL};
  ck_assert_int_eq(zs_test_run_zscan(list, out, sizeof out, err, sizeof err), 0);
  ck_assert_msg(strncmp(out, "0 nodes[1]: eye 0.5,0.5,3 target 0.5,0.5,2 up 0,1,0 ", 52) == 0,
                "%s", out);
  ck_assert_ptr_nonnull(strstr(out, "\n1 nodes[2]: eye 0.5,0.5,3 target 0.5,0.5,2 up 0,1,0 ortho"));
  char a[4096], b[4096], h1[17], h2[17];
  snprintf(a, sizeof a, "%s/cli-cam-file.png", ZS_BINARY_DIR);
  snprintf(b, sizeof b, "%s/cli-cam-opts.png", ZS_BINARY_DIR);
  const char *file[] = {"render", gltf, "--camera", "0", "--size", "200x200", "--stats", "-o", a,
                        NULL};
  ck_assert_int_eq(zs_test_run_zscan(file, out, sizeof out, err, sizeof err), 0);
  stats_hash(out, h1);
  /* 0.7 radians is 40.107045659157625 degrees */
  const char *opts[] = {"render", gltf, "--eye", "0.5,0.5,3", "--target", "0.5,0.5,2", "--up",
                        "0,1,0", "--fovy", "40.107045659157625", "--near", "0.01", "--far",
                        "100", "--size", "200x200", "--stats", "-o", b, NULL};
  ck_assert_int_eq(zs_test_run_zscan(opts, out, sizeof out, err, sizeof err), 0);
  stats_hash(out, h2);
  ck_assert_str_eq(h1, h2);
  const char *name[] = {"render", gltf, "--camera", "nodes[1]", "--size", "200x200", "--stats",
                        "-o", a, NULL};
  ck_assert_int_eq(zs_test_run_zscan(name, out, sizeof out, err, sizeof err), 0);
  stats_hash(out, h2);
  ck_assert_str_eq(h1, h2);
  /* checked against the input, not the command line alone: exit 1 */
  const char *missing[] = {"render", gltf, "--camera", "7", "-o", a, NULL};
  ck_assert_int_eq(zs_test_run_zscan(missing, out, sizeof out, err, sizeof err), 1);
  ck_assert_ptr_nonnull(strstr(err, "--camera 7: "));
  ck_assert_ptr_nonnull(strstr(err, "has 2 cameras (see --list-cameras)"));
  const char *dae[] = {"render", "/usr/share/assimp/models/Collada/cameras.dae", "-o", a, NULL};
  ck_assert_int_eq(zs_test_run_zscan(dae, out, sizeof out, err, sizeof err), 1);
  ck_assert_ptr_nonnull(strstr(err, "no meshes (3 cameras and nothing to draw"));
#endif
  const char *gen[] = {"render", "builtin:cubes", "--camera", "0", NULL};
  ck_assert_int_eq(zs_test_run_zscan(gen, out, sizeof out, err, sizeof err), 1);
  ck_assert_ptr_nonnull(strstr(err, "--camera: a generated scene stores no cameras"));
}
END_TEST

/* The camera -v prints for args (render INPUT ...): eye, target, up. */
static void camera_of(const char *const *args, double eye[3], double target[3], double up[3]) {
  ck_assert_msg(zs_test_run_zscan(args, out, sizeof out, err, sizeof err) == 0, "%s", err);
  const char *c = strstr(err, "--eye ");
  ck_assert_ptr_nonnull(c);
  ck_assert_int_eq(sscanf(c, "--eye %lf,%lf,%lf --target %lf,%lf,%lf --up %lf,%lf,%lf", &eye[0],
                          &eye[1], &eye[2], &target[0], &target[1], &target[2], &up[0], &up[1],
                          &up[2]),
                   9);
}

/* --up-axis, --view and --fit steer the automatic camera; --fovy with
 * --ortho is refused. */
START_TEST(automatic_camera_options) {
  char png[4096];
  snprintf(png, sizeof png, "%s/cli-view.png", ZS_BINARY_DIR);
  double e[3], t[3], u[3], e2[3], t2[3], u2[3];
  const char *zup[] = {"render", "builtin:cubes,n=2", "--up-axis", "z", "-v", "-o", png, NULL};
  camera_of(zup, e, t, u);
  ck_assert(u[0] == 0 && u[1] == 0 && u[2] == 1);
  ck_assert(e[2] > t[2] && e[1] < t[1]); /* above (+z) and in front (-y) */
  const char *top[] = {"render", "builtin:cubes,n=2", "--view", "top", "-v", "-o", png, NULL};
  camera_of(top, e, t, u);
  ck_assert(e[0] == t[0] && e[2] == t[2] && e[1] > t[1]); /* straight above, y up */
  ck_assert(u[0] == 0 && u[1] == 0 && u[2] == -1);
  const char *near1[] = {"render", "builtin:cubes,n=2", "--view", "front", "-v", "-o", png, NULL};
  const char *near2[] = {"render", "builtin:cubes,n=2", "--view", "front", "--fit", "2", "-v",
                         "-o", png, NULL};
  camera_of(near1, e, t, u);
  camera_of(near2, e2, t2, u2);
  ck_assert(e[0] == t[0] && e[1] == t[1] && e[2] > t[2]); /* front: along +z */
  ck_assert_double_eq_tol(e2[2] - t2[2], 0.5 * (e[2] - t[2]), 1e-12);
}
END_TEST

/* Without --stats, render says in one line on stderr what it wrote; -q
 * silences it; --stats keeps wall-clock times in its last object. */
START_TEST(render_tells_a_person_what_it_wrote) {
  char png[4096];
  snprintf(png, sizeof png, "%s/cli-told.png", ZS_BINARY_DIR);
  const char *args[] = {"render", "builtin:cubes,n=2", "--size", "64x48", "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, err, sizeof err), 0);
  char want[4300];
  snprintf(want, sizeof want, "zscan render: wrote %s: 64x48, 48 faces, ", png);
  ck_assert_msg(strncmp(err, want, strlen(want)) == 0 && strstr(err, " ms\n"), "%s", err);
  ck_assert_str_eq(out, "");
  const char *quiet[] = {"render", "builtin:cubes,n=2", "--size", "64x48", "-o", png, "-q", NULL};
  ck_assert_int_eq(zs_test_run_zscan(quiet, out, sizeof out, err, sizeof err), 0);
  ck_assert_str_eq(err, "");
  const char *stats[] = {"render", "builtin:cubes,n=2", "--size", "64x48", "-o", png, "--stats",
                         NULL};
  ck_assert_int_eq(zs_test_run_zscan(stats, out, sizeof out, err, sizeof err), 0);
  ck_assert_str_eq(err, "");
  const char *timing = strstr(out, ",\"timing\":{\"ms_per_frame\":");
  ck_assert_ptr_nonnull(timing);
  ck_assert_ptr_nonnull(strstr(timing, ",\"ms_load\":"));
  ck_assert_ptr_null(strchr(strchr(timing, '}') + 1, ',')); /* nothing after it */
}
END_TEST

/* walk --named: any model walked along a camera path of zscan path's. */
START_TEST(walk_a_model_along_a_named_path) {
  const char *model = zs_test_src("tests/data/scenes/cyclic.obj");
  const char *args[] = {"walk", model, "--cull", "vfc,chc", "--named", "roll", "--frames", "20",
                        "--size", "160x120", "--csv", "-", "--quiet", NULL};
  ck_assert_msg(zs_test_run_zscan(args, out, sizeof out, err, sizeof err) == 0, "%s", err);
  int rows = 0;
  for (const char *l = strchr(out, '\n'); l && l[1]; l = strchr(l + 1, '\n')) rows++;
  ck_assert_int_eq(rows, 20 * 3); /* none, vfc, chc: every frame */
  ck_assert_ptr_nonnull(strstr(out, "\n19,chc,"));
  ck_assert_ptr_nonnull(strstr(err, "20 frames at 160x120, 3 objects"));
}
END_TEST

/* query --format json: the same figures as the text, as one object. */
START_TEST(query_as_json) {
  static char text[1 << 16];
  const char *t[] = {"query", "builtin:cubes,n=2", "--size", "64x48", NULL};
  ck_assert_int_eq(zs_test_run_zscan(t, text, sizeof text, err, sizeof err), 0);
  const char *j[] = {"query", "builtin:cubes,n=2", "--size", "64x48", "--format", "json", NULL};
  ck_assert_int_eq(zs_test_run_zscan(j, out, sizeof out, err, sizeof err), 0);
  cJSON *root = cJSON_Parse(out);
  ck_assert_msg(root != NULL, "%s", out);
  const cJSON *objects = cJSON_GetObjectItem(root, "objects");
  ck_assert_int_eq(cJSON_GetArraySize(objects), 8);
  for (const cJSON *o = objects->child; o; o = o->next) {
    char line[256];
    snprintf(line, sizeof line, "object %s visible=%.0f bbox=%.0f\n",
             cJSON_GetObjectItem(o, "name")->valuestring,
             cJSON_GetObjectItem(o, "visible")->valuedouble,
             cJSON_GetObjectItem(o, "bbox")->valuedouble);
    ck_assert_msg(strstr(text, line) != NULL, "%s not in %s", line, text);
  }
  ck_assert_int_eq(cJSON_GetObjectItem(cJSON_GetObjectItem(root, "total"), "pixels")->valueint,
                   64 * 48);
  cJSON_Delete(root);
}
END_TEST

/* query --samples N counts samples, as GL's sample-counting queries do:
 * a square whose edges lie on pixel edges owns every sample of its 16
 * pixels; polygons with sloped edges own a share of their edge pixels'
 * samples, so not 4 x their pixels; the total never exceeds the frame's
 * samples. */
START_TEST(query_counts_samples) {
  char square[4096], two[4096];
  snprintf(square, sizeof square, "%s", zs_test_src("tests/data/lecture/zbuffer_square.obj"));
  snprintf(two, sizeof two, "%s", zs_test_src("tests/data/lecture/two_polygons.obj"));
  const char *a[] = {"query", square, "--ortho", "-0.5,7.5,-0.5,5.5", "--eye", "0,0,0", "--target",
                     "0,0,-1", "--near", "-10", "--far", "5", "--size", "8x6", "--samples", "4", NULL};
  ck_assert_int_eq(zs_test_run_zscan(a, out, sizeof out, err, sizeof err), 0);
  ck_assert_str_eq(out, "object square visible=64 bbox=64\n"
                        "total objects=1 visible=64 bbox=64 pixels=48 samples=4\n");
  const char *one[] = {"query", two, "--grid", "12x10", "--format", "json", NULL};
  const char *four[] = {"query", two, "--grid", "12x10", "--format", "json", "--samples", "4", NULL};
  ck_assert_int_eq(zs_test_run_zscan(one, out, sizeof out, err, sizeof err), 0);
  cJSON *r1 = cJSON_Parse(out);
  ck_assert_int_eq(zs_test_run_zscan(four, out, sizeof out, err, sizeof err), 0);
  cJSON *r4 = cJSON_Parse(out);
  ck_assert(r1 && r4);
  const cJSON *t1 = cJSON_GetObjectItem(r1, "total"), *t4 = cJSON_GetObjectItem(r4, "total");
  const int v1 = cJSON_GetObjectItem(t1, "visible")->valueint;
  const int v4 = cJSON_GetObjectItem(t4, "visible")->valueint;
  ck_assert_int_eq(cJSON_GetObjectItem(t4, "samples_per_pixel")->valueint, 4);
  ck_assert_ptr_null(cJSON_GetObjectItem(t1, "samples_per_pixel"));
  ck_assert_int_le(v4, 4 * 120);
  ck_assert_int_ne(v4, 4 * v1);
  ck_assert_int_gt(v4, 3 * v1);
  cJSON_Delete(r1);
  cJSON_Delete(r4);
}
END_TEST

/* walk --frames-dir: every method's frame shaded as render shades it, or
 * with --shade id the face ids. */
START_TEST(walk_frames_shaded_or_ids) {
  char dir[4096], flat[4300], ids[4300], none[4300];
  snprintf(dir, sizeof dir, "%s/cli-frames", ZS_BINARY_DIR);
  const char *args[] = {"walk", "builtin:cubes,n=3", "--cull", "chc", "--frames", "2", "--size",
                        "96x72", "--frames-dir", dir, "--quiet", NULL};
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, err, sizeof err), 0);
  snprintf(flat, sizeof flat, "%s/chc-00001.png", dir);
  zs_image a, b;
  zs_error e;
  zs_error_clear(&e);
  ck_assert_int_eq(zs_png_read(flat, &a, &e), ZS_OK);
  ck_assert_uint_eq(a.rgb[0], 0x1E2228); /* render's background */
  int colours = 0;
  for (int i = 1; i < a.width * a.height; i++) colours += a.rgb[i] != a.rgb[i - 1];
  ck_assert_int_gt(colours, 20); /* shaded faces, not a flat silhouette */
  const char *id_args[] = {"walk", "builtin:cubes,n=3", "--cull", "chc", "--frames", "2",
                           "--size", "96x72", "--frames-dir", dir, "--shade", "id", "--quiet",
                           NULL};
  ck_assert_int_eq(zs_test_run_zscan(id_args, out, sizeof out, err, sizeof err), 0);
  snprintf(ids, sizeof ids, "%s/chc-00001.png", dir);
  ck_assert_int_eq(zs_png_read(ids, &b, &e), ZS_OK);
  ck_assert_uint_eq(b.rgb[0], 0); /* id images: background 0, faces id + 1 */
  for (int i = 0; i < b.width * b.height; i++) ck_assert_uint_le(b.rgb[i], 27 * 6);
  snprintf(none, sizeof none, "%s/none-00001.png", dir);
  ck_assert(zs_test_exists(none)); /* the reference's frames too */
  zs_image_free(&a);
  zs_image_free(&b);
}
END_TEST

/* walk --reference off: none is not run and no pixel compared. */
START_TEST(walk_without_reference) {
  const char *args[] = {"walk", "builtin:cubes,n=3", "--cull", "vfc,chc", "--frames", "3",
                        "--size", "96x72", "--reference", "off", "--csv", "-", "--quiet", NULL};
  ck_assert_msg(zs_test_run_zscan(args, out, sizeof out, err, sizeof err) == 0, "%s", err);
  ck_assert_ptr_null(strstr(out, ",none,"));
  ck_assert_ptr_nonnull(strstr(out, "\n2,chc,chc,"));
  ck_assert_ptr_nonnull(strstr(err, "\nvfc "));
  ck_assert_ptr_null(strstr(err, "\nnone "));
  const char *with_none[] = {"walk", "builtin:cubes,n=3", "--cull", "none,chc", "--frames", "2",
                             "--size", "96x72", "--reference", "off", "--quiet", NULL};
  ck_assert_int_eq(zs_test_run_zscan(with_none, out, sizeof out, err, sizeof err), 0);
  ck_assert_ptr_nonnull(strstr(out, "\nnone "));
}
END_TEST

START_TEST(render_writes_png_and_stats) {
  char png[4096], pfm[4096];
  snprintf(png, sizeof png, "%s/cli-ok.png", ZS_BINARY_DIR);
  snprintf(pfm, sizeof pfm, "%s/cli-ok.pfm", ZS_BINARY_DIR);
  unlink(png);
  unlink(pfm);
  const char *args[] = {"render", "--size", "64x48", "-o", png, "--depth", pfm, "--stats",
                        "--repeat", "3", NULL};
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  ck_assert(zs_test_exists(png));
  ck_assert(zs_test_exists(pfm));
  /* the statistics are the last line of stdout, one JSON object */
  ck_assert_msg(out[0] == '{' && one_line(out), "stdout: %s", out);
  const char *keys[] = {"\"faces\":10374", "\"objects\":10", "\"pixels_tested\":",
                        "\"pixels_written\":", "\"ms_per_frame\":", "\"repeat\":3",
                        "\"image_hash\":\""};
  for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
    ck_assert_msg(strstr(out, keys[i]) != NULL, "stdout lacks %s: %s", keys[i], out);
  ck_assert_str_eq(err, "");
  ck_assert_ptr_null(strstr(out, "\"cull\"")); /* no culling: no culling figures */
}
END_TEST

/* --normals: a three-channel PFM of the image's size, unit normals where
 * the spheres are and zeros at the background; the image is the one
 * rendered without it. */
START_TEST(render_writes_normals) {
  char png[4096], png2[4096], pfm[4096];
  snprintf(png, sizeof png, "%s/cli-normals.png", ZS_BINARY_DIR);
  snprintf(png2, sizeof png2, "%s/cli-normals-not.png", ZS_BINARY_DIR);
  snprintf(pfm, sizeof pfm, "%s/cli-normals.pfm", ZS_BINARY_DIR);
  unlink(pfm);
  const char *args[] = {"render", "builtin:teapots,count=4", "--size", "64x48", "-o", png,
                        "--normals", pfm, "--shade", "gouraud", NULL};
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  ck_assert_msg(strstr(err, ", normals to ") != NULL, "%s", err);
  const char *plain[] = {"render", "builtin:teapots,count=4", "--size", "64x48", "-o", png2,
                         "--shade", "gouraud", "-q", NULL};
  ck_assert_int_eq(zs_test_run_zscan(plain, out, sizeof out, err, sizeof err), 0);
  zs_test_assert_same_file(png, png2);
  size_t n = 0;
  unsigned char *f = zs_test_slurp(pfm, &n);
  ck_assert_ptr_nonnull(f);
  const char head[] = "PF\n64 48\n-1.0\n";
  ck_assert_uint_eq(n, strlen(head) + 64 * 48 * 12);
  ck_assert(memcmp(f, head, strlen(head)) == 0);
  int unit = 0, zero = 0;
  for (int i = 0; i < 64 * 48; i++) {
    float v[3];
    for (int k = 0; k < 3; k++) {
      const unsigned char *p = f + strlen(head) + 12 * i + 4 * k;
      const uint32_t bits = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
                            (uint32_t)p[3] << 24;
      memcpy(&v[k], &bits, sizeof bits);
    }
    const double len2 = (double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2];
    if (len2 == 0) zero++;
    else if (fabs(len2 - 1) < 1e-6) unit++;
  }
  free(f);
  ck_assert_int_eq(unit + zero, 64 * 48);
  ck_assert_int_gt(unit, 64 * 48 / 20);
  ck_assert_int_gt(zero, 64 * 48 / 20);
}
END_TEST

/* The value of "key":N in a JSON line of numbers. */
static long long json_int(const char *line, const char *key) {
  char pat[128];
  snprintf(pat, sizeof pat, "\"%s\":", key);
  const char *p = strstr(line, pat);
  ck_assert_msg(p != NULL, "no %s in %s", key, line);
  return atoll(p + strlen(pat));
}

/* --simd: every level draws the same image (the hash --stats prints), in
 * both modes, flat and textured Phong. */
START_TEST(render_same_at_every_simd_level) {
  static const char *const inputs[] = {"builtin:default", "builtin:plant,detail=0.2"};
  static const char *const levels[] = {"scalar", "sse2", "avx2", "avx512", "best"};
  static const char *const modes[][2] = {{"zbuffer", "flat"}, {"scanline", "phong"}};
  char png[4096], first[64];
  snprintf(png, sizeof png, "%s/cli-simd.png", ZS_BINARY_DIR);
  for (int i = 0; i < 2; i++)
    for (int m = 0; m < 2; m++)
      for (int k = 0; k < 5; k++) {
        const char *args[] = {"render", inputs[i], "--size", "160x120", "--algo", modes[m][0],
                              "--shade", modes[m][1], "--simd", levels[k], "-o", png, "--stats",
                              NULL};
        ck_assert_msg(zs_test_run_zscan(args, out, sizeof out, err, sizeof err) == 0, "%s", err);
        const char *h = strstr(out, "\"image_hash\":\"");
        ck_assert_ptr_nonnull(h);
        if (k == 0) snprintf(first, sizeof first, "%.40s", h);
        else ck_assert_msg(strncmp(h, first, strlen(first)) == 0, "%s %s %s: %.40s, scalar %s",
                           inputs[i], modes[m][0], levels[k], h, first);
      }
}
END_TEST

/* rgbα+z layers: a scene drawn in three parts, each into a layer from the
 * whole scene's camera, composites to the frame of the whole, byte for
 * byte, in both modes, flat and Phong-lit, with shadows, on 1 and 2
 * threads. */
START_TEST(composite_of_parts_is_the_whole) {
  static const char *const scenes[] = {"builtin:teapots,count=9", "builtin:city",
                                       "builtin:default", "builtin:spheres,count=40"};
  /* the shadow maps are drawn of the whole scene: a part shows the
   * shadows the others cast on it */
  static const char *const modes[][4] = {
      {"zbuffer", "flat", "1", "-q"}, {"scanline", "phong", "2", "-q"},
      {"zbuffer", "phong", "2", "-q"}, {"scanline", "flat", "1", "-q"},
      {"scanline", "auto", "2", "--shadows"}};
  char whole[4096], comp[4096], layer[3][4096];
  snprintf(whole, sizeof whole, "%s/cli-whole.png", ZS_BINARY_DIR);
  snprintf(comp, sizeof comp, "%s/cli-composite.png", ZS_BINARY_DIR);
  for (int k = 0; k < 3; k++) snprintf(layer[k], sizeof layer[k], "%s/cli-part%d.zsl", ZS_BINARY_DIR, k);
  for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++)
    for (size_t m = 0; m < sizeof modes / sizeof modes[0]; m++) {
      const char *w[] = {"render", scenes[i], "--size", "96x72", "--algo", modes[m][0], "--shade",
                         modes[m][1], "--threads", modes[m][2], modes[m][3], "-o", whole,
                         "--stats", NULL};
      ck_assert_msg(zs_test_run_zscan(w, out, sizeof out, err, sizeof err) == 0, "%s", err);
      const int n = (int)json_int(out, "objects");
      ck_assert_int_ge(n, 3);
      for (int k = 0; k < 3; k++) {
        char range[64];
        snprintf(range, sizeof range, "%d-%d", n * k / 3, n * (k + 1) / 3 - 1);
        const char *p[] = {"render", scenes[i], "--size", "96x72", "--algo", modes[m][0],
                           "--shade", modes[m][1], "--threads", modes[m][2], modes[m][3],
                           "--objects", range, "--layer", layer[k], "-o", comp, "-q", NULL};
        ck_assert_msg(zs_test_run_zscan(p, out, sizeof out, err, sizeof err) == 0, "%s", err);
      }
      unlink(comp);
      const char *c[] = {"composite", layer[2], layer[0], layer[1], "-o", comp, NULL};
      ck_assert_msg(zs_test_run_zscan(c, out, sizeof out, err, sizeof err) == 0, "%s", err);
      ck_assert_msg(strstr(err, "zscan composite: 3 layers, 96x72, ") != NULL, "%s", err);
      zs_test_assert_same_file(whole, comp);
    }
  /* layers of another size or camera are refused, and nothing is written */
  char other[4096];
  snprintf(other, sizeof other, "%s/cli-other.zsl", ZS_BINARY_DIR);
  const char *o1[] = {"render", "builtin:city", "--size", "48x36", "--layer", other, "-q", NULL};
  ck_assert_int_eq(zs_test_run_zscan(o1, out, sizeof out, err, sizeof err), 0);
  unlink(comp);
  const char *c1[] = {"composite", layer[0], other, "-o", comp, NULL};
  ck_assert_int_eq(zs_test_run_zscan(c1, out, sizeof out, err, sizeof err), 1);
  char want[9000];
  snprintf(want, sizeof want, "zscan composite: %s: 48x36, but %s is 96x72\n", other, layer[0]);
  ck_assert_str_eq(err, want);
  ck_assert(!zs_test_exists(comp));
  const char *o2[] = {"render", "builtin:spheres,count=40", "--size", "96x72", "--fovy", "20",
                      "--layer", other, "-q", NULL};
  ck_assert_int_eq(zs_test_run_zscan(o2, out, sizeof out, err, sizeof err), 0);
  ck_assert_int_eq(zs_test_run_zscan(c1, out, sizeof out, err, sizeof err), 1);
  snprintf(want, sizeof want, "zscan composite: %s: another camera than %s's\n", other, layer[0]);
  ck_assert_str_eq(err, want);
  /* a file that is no layer, and one cut short */
  FILE *f = fopen(other, "wb");
  fputs("P6\n1 1\n255\n...", f);
  fclose(f);
  ck_assert_int_eq(zs_test_run_zscan(c1, out, sizeof out, err, sizeof err), 1);
  snprintf(want, sizeof want, "zscan composite: %s:1: not a zscan layer (ZSLAYER 1)\n", other);
  ck_assert_str_eq(err, want);
  size_t len = 0;
  unsigned char *bytes = zs_test_slurp(layer[0], &len);
  ck_assert_ptr_nonnull(bytes);
  f = fopen(other, "wb");
  fwrite(bytes, 1, len - 12 * 96 * 10, f);
  fclose(f);
  free(bytes);
  ck_assert_int_eq(zs_test_run_zscan(c1, out, sizeof out, err, sizeof err), 1);
  snprintf(want, sizeof want, "zscan composite: %s: cut short: 62 of 72 rows of pixels\n", other);
  ck_assert_str_eq(err, want);
  ck_assert(!zs_test_exists(comp));
  /* a pixel that is neither a face nor the background, each way */
  static const struct {
    int alpha, face; /* alpha written; 1: at a face's pixel, 0: the background's */
    uint32_t id;     /* 5: written over the id; 1: the depth set to 1 */
    const char *why;
  } damage[] = {
      {128, 1, 0, "alpha 128: expected 255 (a face) or 0 (the background)"},
      {255, 0, 0, "alpha 255 (a face) without a face id"},
      {0, 1, 0, "alpha 0 (the background) with face id "},
      {0, 0, 5, "alpha 0 (the background) with face id 5"},
      {0, 0, 1, "the background at depth 1, not the far plane's 4294967295"},
  };
  for (size_t d = 0; d < sizeof damage / sizeof damage[0]; d++) {
    bytes = zs_test_slurp(layer[0], &len);
    ck_assert_ptr_nonnull(bytes);
    size_t at = 0;
    for (int line = 0; line < 6; line++) /* past the header's six lines */
      at = (size_t)((unsigned char *)memchr(bytes + at, '\n', len - at) - bytes) + 1;
    size_t i = 0;
    while (at + 12 * i < len && (bytes[at + 12 * i + 3] == 255) != damage[d].face) i++;
    ck_assert_uint_lt(at + 12 * i, len);
    bytes[at + 12 * i + 3] = (unsigned char)damage[d].alpha;
    if (damage[d].id == 5) memcpy(bytes + at + 12 * i + 8, "\x05\0\0\0", 4);
    if (damage[d].id == 1) memcpy(bytes + at + 12 * i + 4, "\x01\0\0\0", 4); /* depth 1 */
    f = fopen(other, "wb");
    fwrite(bytes, 1, len, f);
    fclose(f);
    free(bytes);
    ck_assert_int_eq(zs_test_run_zscan(c1, out, sizeof out, err, sizeof err), 1);
    snprintf(want, sizeof want, "zscan composite: %s: pixel (%d, %d): %s", other, (int)(i % 96),
             (int)(i / 96), damage[d].why);
    ck_assert_msg(strncmp(err, want, strlen(want)) == 0, "%s\nexpected %s", err, want);
    ck_assert(!zs_test_exists(comp));
  }
}
END_TEST

/* A light's direction is a direction at any length: one whose square
 * overflows or vanishes in a double lights (and casts shadows) as its
 * unit vector does, in the lit shading and the shadow map's camera. */
START_TEST(light_direction_at_any_length) {
  char png[4096], want[17] = "", got[17];
  snprintf(png, sizeof png, "%s/cli-light.png", ZS_BINARY_DIR);
  const char *lights[] = {"dir:-1,-2,-1", "dir:-1e200,-2e200,-1e200", "dir:-1e-200,-2e-200,-1e-200"};
  for (int k = 0; k < 3; k++) {
    const char *a[] = {"render", zs_test_src("scene/examples/table.json"), "--size", "96x72",
                       "--light", lights[k], "--shadows", "--stats", "-o", png, NULL};
    ck_assert_int_eq(zs_test_run_zscan(a, out, sizeof out, err, sizeof err), 0);
    ck_assert_msg(strstr(err, "warning") == NULL, "%s: %s", lights[k], err);
    stats_hash(out, k ? got : want);
    if (k) ck_assert_msg(strcmp(got, want) == 0, "%s: %s, not %s", lights[k], got, want);
  }
}
END_TEST

START_TEST(render_stats_show_the_culling_work) {
  /* vfc on the city: plane masking leaves far fewer box-plane tests than
   * six per element visited; chc-prob evaluates its cost model where it
   * decides and asks fewer queries than it evaluates */
  char png[4096];
  snprintf(png, sizeof png, "%s/cli-cull.png", ZS_BINARY_DIR);
  const char *vfc[] = {"render", "builtin:city", "--size", "256x192", "--cull", "vfc", "--stats",
                       "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(vfc, out, sizeof out, err, sizeof err), 0);
  ck_assert_ptr_nonnull(strstr(out, "\"cull\":\"vfc\""));
  long long visited = json_int(out, "nodes_visited"), tests = json_int(out, "frustum_tests");
  ck_assert_int_gt(visited, 0);
  ck_assert_int_lt(tests, 6 * visited / 2);
  ck_assert_int_eq(json_int(out, "cost_evals"), 0);
  ck_assert_int_gt(json_int(out, "octree_nodes"), 1);
  ck_assert_ptr_nonnull(strstr(out, "\"octree\":\"loose\""));
  /* a handful of objects (the default scene's 10): no octree, the root
   * lists them, so the elements visited are the root and the objects */
  const char *few[] = {"render", "--size", "256x192", "--cull", "hsw", "--stats", "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(few, out, sizeof out, err, sizeof err), 0);
  ck_assert_ptr_nonnull(strstr(out, "\"octree\":\"flat\""));
  ck_assert_int_eq(json_int(out, "octree_nodes"), 1);
  ck_assert_int_eq(json_int(out, "objects"), 10);
  ck_assert_int_eq(json_int(out, "nodes_visited"), 11);
  ck_assert_int_le(json_int(out, "queries"), 10);
  const char *prob[] = {"render", "builtin:city", "--size", "256x192", "--cull", "chc-prob",
                        "--stats", "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(prob, out, sizeof out, err, sizeof err), 0);
  /* the device's queries: those about boxes, and one around each draw */
  long long evals = json_int(out, "cost_evals"),
            queries = json_int(out, "queries") - json_int(out, "draws_measured");
  ck_assert_int_gt(evals, 0);
  ck_assert_int_lt(queries, evals);
  ck_assert_int_eq(json_int(out, "draws_measured"), json_int(out, "objects_drawn"));
  /* --cost-set: a query that costs a second never pays, so none is asked
   * about a box (the device's queries are only the draws chc-prob
   * measures, every one), and the picture is the same */
  char hash[32];
  const char *h = strstr(out, "\"image_hash\":\"");
  ck_assert_ptr_nonnull(h);
  snprintf(hash, sizeof hash, "%.16s", h + 14);
  const char *dear[] = {"render", "builtin:city", "--size", "256x192", "--cull", "chc-prob",
                        "--cost-set", "t_ns=1e9", "--stats", "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(dear, out, sizeof out, err, sizeof err), 0);
  ck_assert_int_gt(queries, 0);
  ck_assert_int_gt(json_int(out, "draws_measured"), 0);
  ck_assert_int_eq(json_int(out, "draws_measured"), json_int(out, "objects_drawn"));
  ck_assert_int_eq(json_int(out, "queries"), json_int(out, "draws_measured"));
  ck_assert_int_gt(json_int(out, "cost_evals"), 0); /* it still weighed each */
  ck_assert_msg(strstr(out, hash) != NULL, "image %s not in %s", hash, out);
}
END_TEST

START_TEST(query_counts_owned_pixels_and_box_samples) {
  char path[4096];
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/query/squares.obj"));
  const char *args[] = {"query", path, "--ortho", "0,200,0,200", "--eye", "0,0,0", "--target",
                        "0,0,-1", "--near", "0.5", "--far", "20", "--size", "200x200", NULL};
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  /* in order of first face; the group without faces is no object; the
   * wall owns what the squares leave, and its box samples are only those
   * pixels (the squares are nearer) */
  ck_assert_str_eq(out,
                   "object front visible=2500 bbox=2500\n"
                   "object back visible=7500 bbox=7500\n"
                   "object wall_behind visible=30000 bbox=30000\n"
                   "total objects=3 visible=40000 bbox=40000 pixels=40000\n");
}
END_TEST

/* Shadows asked for where nothing casts them: drawn, with a warning. */
START_TEST(shadow_options_that_cast_nothing_warn) {
  char png[4096];
  snprintf(png, sizeof png, "%s/cli-shadow-warn.png", ZS_BINARY_DIR);
  const char *a[] = {"render", zs_test_src("scene/examples/spotlight.json"), "--size", "64x48",
                     "--shade", "gouraud", "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(a, out, sizeof out, err, sizeof err), 0);
  ck_assert_msg(strncmp(err, "zscan render: warning: --shade gouraud shows no shadows (auto and "
                             "phong do): the lights marked \"shadow\" cast none\n", 114) == 0,
                "%s", err);
  const char *b[] = {"render", "builtin:default", "--size", "64x48", "--shadows", "--light",
                     "point:0,5,0", "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(b, out, sizeof out, err, sizeof err), 0);
  ck_assert_msg(strstr(err, "zscan render: warning: --shadows: no directional or spot light casts "
                            "shadows\n") == err, "%s", err);
}
END_TEST

/* Modelled milliseconds printed from integer picoseconds: to the nearest
 * nanosecond, halves away from zero, the same text on every target. */
START_TEST(milliseconds_of_picoseconds) {
  char b[32];
  ck_assert_str_eq(zs_cli_ms_of_ps(35495500, b), "0.035496");
  ck_assert_str_eq(zs_cli_ms_of_ps(35495499, b), "0.035495");
  ck_assert_str_eq(zs_cli_ms_of_ps(0, b), "0.000000");
  ck_assert_str_eq(zs_cli_ms_of_ps(499, b), "0.000000");
  ck_assert_str_eq(zs_cli_ms_of_ps(-1500, b), "-0.000002");
  ck_assert_str_eq(zs_cli_ms_of_ps(-400, b), "0.000000");
  ck_assert_str_eq(zs_cli_ms_of_ps(13086716000, b), "13.086716");
  ck_assert_str_eq(zs_cli_ms_of_ps(INT64_MAX, b), "9223372036.854776");
  ck_assert_str_eq(zs_cli_ms_of_ps(INT64_MIN, b), "-9223372036.854776");
}
END_TEST

START_TEST(unknown_command) {
  const char *args[] = {"paint", NULL};
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  ck_assert_int_eq(rc, 2);
  ck_assert(strstr(err, "zscan: unknown command 'paint'") == err);
}
END_TEST

int main(void) {
  Suite *s = suite_create("cli");
  TCase *tc = tcase_create("errors");
  tcase_set_timeout(tc, 300);
  tcase_add_test(tc, bad_obj_files_refused_with_file_and_line);
  tcase_add_test(tc, bad_scene_files_refused);
  tcase_add_test(tc, bad_model_files_refused);
  tcase_add_loop_test(tc, bad_option_refused, 0, sizeof bad_options / sizeof bad_options[0]);
  tcase_add_loop_test(tc, help_before_anything_else, 0,
                      sizeof help_commands / sizeof help_commands[0]);
  tcase_add_loop_test(tc, every_command_of_the_table_has_help, 0, zs_ncommands);
  tcase_add_test(tc, render_writes_png_and_stats);
  tcase_add_test(tc, render_writes_normals);
  tcase_add_test(tc, composite_of_parts_is_the_whole);
  tcase_add_test(tc, render_same_at_every_simd_level);
  tcase_add_test(tc, render_stats_show_the_culling_work);
  tcase_add_test(tc, light_direction_at_any_length);
  tcase_add_test(tc, hidden_lines_of_glass_and_model_lines);
  tcase_add_test(tc, huge_obj_refused_before_reading);
  tcase_add_test(tc, empty_inputs_refused_unless_allowed);
  tcase_add_test(tc, render_skips_missing_textures);
  tcase_add_test(tc, calibrate_keeps_the_modelled_latency);
  tcase_add_test(tc, progress_in_logs_unless_quiet);
  tcase_add_test(tc, render_background);
  tcase_add_test(tc, hidden_lines_as_svg);
  tcase_add_test(tc, printed_camera_reproduces_the_image);
  tcase_add_test(tc, camera_from_the_model_file);
  tcase_add_test(tc, automatic_camera_options);
  tcase_add_test(tc, render_tells_a_person_what_it_wrote);
  tcase_add_test(tc, walk_a_model_along_a_named_path);
  tcase_add_test(tc, query_as_json);
  tcase_add_test(tc, query_counts_samples);
  tcase_add_test(tc, walk_frames_shaded_or_ids);
  tcase_add_test(tc, walk_without_reference);
  tcase_add_test(tc, every_command_exits_2_on_usage_and_1_on_a_missing_input);
  tcase_add_test(tc, bench_raster_writes_csv_and_table);
  tcase_add_test(tc, bench_raster_counts_instructions);
  tcase_add_test(tc, bench_depthsort_coherence_pays_where_depths_are_kept);
  tcase_add_test(tc, walk_compares_hidden_surface_modes);
  tcase_add_test(tc, walk_csv_same_bytes_every_run_but_wall_time);
  tcase_add_test(tc, shadow_options_that_cast_nothing_warn);
  tcase_add_test(tc, milliseconds_of_picoseconds);
  tcase_add_test(tc, unknown_command);
  tcase_add_test(tc, query_counts_owned_pixels_and_box_samples);
  suite_add_tcase(s, tc);
  /* the whole quick suite, every benchmark in turn: under the sanitizers,
   * beside another test, it has run past 300 s */
  TCase *suite_tc = tcase_create("suite");
  tcase_set_timeout(suite_tc, 900);
  tcase_add_test(suite_tc, bench_suite_writes_every_file);
  suite_add_tcase(s, suite_tc);
  return zs_test_run(s);
}
