/* `zscan bench suite [--out DIR] [--quick] [--size WxH] [--threads N]
 * [--docs DIR] [--quiet]`: the documented suite, one command, every file
 * in the --out directory:
 *   raster.csv, .md, .png   bench raster: triangles of 4 to 500 pixels and
 *                           the whole scenes in both modes, one thread,
 *                           beside Mesa's llvmpipe on one thread (--mesa),
 *                           with the instructions per frame (--callgrind);
 *   shade-unlit.md, shade-gouraud.md, shade-phong.md   bench raster's
 *                           scenes in each shading that reads attributes,
 *                           beside llvmpipe's equivalent state;
 *   colours.md              bench colours: the unlit colours against
 *                           llvmpipe's, pixel by pixel;
 *   lines.md                bench lines: wide lines and points against
 *                           llvmpipe's, pixel by pixel;
 *   arrays.md               bench arrays: a mesh built from arrays beside
 *                           the same mesh loaded from its OBJ file;
 *   samples.md              bench samples: one sample a pixel and four, and
 *                           each sample's faces beside llvmpipe's;
 *   raster-threads.csv, .md, .png, .txt   the same on N threads (every CPU
 *                           by default), zscan's speed-up over one thread
 *                           (--speedup), and llvmpipe on as many threads (a
 *                           child process, as llvmpipe reads LP_NUM_THREADS
 *                           when it starts);
 *   memory.md, memory.txt   what the device holds (render --stats) in
 *                           both modes at four image sizes;
 *   calibrate.txt, clock.json   zscan calibrate: the clock's constants;
 *   walk-plant.*, walk-teapots.*   zscan walk, every culling method over
 *                           every frame of the two large walks (.csv, .md,
 *                           .txt, and -every.png: a few methods' modelled
 *                           frame time along the walk);
 *   tradeoff*.csv, .md, .png  bench tradeoff: run time against error
 *                           (walk-plant.png and walk-teapots.png: a few
 *                           methods along two of its walks);
 *   depthsort.csv           bench depthsort: the depth-sort paper's Table 1;
 *   octree.csv, .png        bench octree: loose against plain octree updates.
 *
 * --docs DIR writes the results page, DIR/RESULTS.md, its plots in
 * DIR/images/: `zscan bench suite --docs docs` rewrites docs/RESULTS.md.
 * The page holds no word of this file: its templates, the .md files of
 * DIR/results/ in the order of their names, are Markdown in which {NAME}
 * stands for what the suite measured (placeholders[] below: a table, a
 * command, a figure); a brace opens nothing else.  The templates are
 * read and checked before anything runs: an unknown or malformed
 * placeholder, an image the suite does not draw, or a measurement no
 * template shows is a one-line error naming the file (and line), exit 1.
 * The page shows each benchmark's command as the full run runs it,
 * without the files it writes, so that a --quick page shows the same
 * headings and commands as the full one (tests/test_results.c).  A full
 * run for --docs needs OSMesa, valgrind, gnuplot and two CPUs, so that
 * the page is never written with a table missing.
 *
 * --quick: one frame per raster case at 500x500 and no scenes or
 * instruction counts, two frames of small walks at 160x120, fewer frames
 * elsewhere, neither llvmpipe nor the threads: a check that it all runs
 * and renders, in seconds (minutes under the sanitizers at -O0). */
#include "tools/bench_suite.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "raster/raster.h"
#include "tools/bench_depthsort.h"
#include "tools/bench_octree.h"
#include "tools/bench_colours.h"
#include "tools/bench_arrays.h"
#include "tools/bench_samples.h"
#include "tools/bench_lines.h"
#include "tools/bench_raster.h"
#include "tools/bench_tradeoff.h"
#include "tools/callgrind.h"
#include "tools/cli.h"
#include "tools/mesa.h"
#include "lib/outfile.h"
#include "tools/plot.h"
#include "util/os.h"

static const char usage[] =
    "usage: zscan bench suite [--out DIR] [--quick] [--size WxH] [--threads N] [--docs DIR]\n"
    "                         [--quiet] [--no-run]\n"
    "  --out DIR    where every benchmark's files go (default bench-suite)\n"
    "  --quick      a few frames of each, small scenes: a check that it all runs\n"
    "  --size WxH   the image size of raster, tradeoff, depthsort and the walks (raster\n"
    "               needs 500x500 or more; default each one's own, 1024x768)\n"
    "  --threads N  the second raster pass and llvmpipe's on N threads (default: every\n"
    "               CPU, 2 or more)\n"
    "  --docs DIR   also the results page, DIR/RESULTS.md, from the templates\n"
    "               DIR/results/*.md, its plots in DIR/images (zscan bench suite\n"
    "               --docs docs rewrites docs/RESULTS.md)\n"
    "  --quiet      no progress on stderr (else a line after each benchmark, and\n"
    "               the walks of tradeoff as bench tradeoff shows them)\n"
    "  --no-run     measure nothing: the page (--docs) from the files an earlier run\n"
    "               with the same options left in --out, after a template's edit\n";

/* Every culling method; the few whose lines a plot can tell apart (hsw,
 * which waits for every answer, would flatten them); the rows of the
 * depth pyramid's comparison. */
static const char all_methods[] =
    "vfc,vfc-box,hsw,chc,chc-prob,chcpp,chcpp-nobatch,chcpp-nodefer,chcpp-nomulti,chcpp-prob,"
    "nohc,hzb,ideal-box,ideal,auto";
static const char *const plotted[] = {"vfc", "chc", "chc-prob", "chcpp", "nohc", "hzb", "ideal-box",
                                      "ideal"};
enum { NPLOTTED = sizeof plotted / sizeof plotted[0] };
static const char *const hzb_rows[] = {"none", "hzb", "chcpp-prob", "ideal-box", "ideal"};

/* The two large walks at every frame: name, scene, quick scene. */
static const char *const walks[2][3] = {
    {"plant", "builtin:plant,detail=1", "builtin:plant,detail=0.05"},
    {"teapots", "builtin:teapots,count=6000", "builtin:teapots,count=60"},
};
/* The walks of bench tradeoff, in its order. */
static const char *const tradeoff_walks[3] = {"teapots", "city", "plant"};
/* The shadings of bench raster's scenes beside llvmpipe's equivalent
 * state. */
static const char *const shadings[3] = {"unlit", "gouraud", "phong"};

/* Memory: the default scene at four sizes, in both modes. */
static const char *const mem_sizes[2][4] = {
    {"1024x768", "4096x768", "1024x3072", "4096x3072"},
    {"256x192", "1024x192", "256x768", "1024x768"}, /* --quick */
};
/* The sizes under --quick without --size: the walks', tradeoff's and
 * depthsort's, and raster's (the least its tilings take). */
static const char quick_size[] = "160x120", quick_raster_size[] = "500x500";

/* The plots the page may show: the name in the output directory and in
 * DIR/images of --docs. */
typedef struct plot_file {
  const char *out, *doc;
} plot_file;
static const plot_file plots[] = {
    {"raster.png", "bench-raster.png"},
    {"walk-plant-every.png", "walk-plant-every.png"},
    {"walk-teapots-every.png", "walk-teapots-every.png"},
    {"tradeoff-teapots.png", "tradeoff-teapots.png"},
    {"tradeoff-city.png", "tradeoff-city.png"},
    {"tradeoff-plant.png", "tradeoff-plant.png"},
    {"octree.png", "octree.png"},
};
enum { NPLOTS = sizeof plots / sizeof plots[0] };

/* What the templates may name.  shown: some template must show it (the
 * measurements and their commands), so that a template gone missing is
 * an error, not a section quietly dropped. */
static const struct placeholder {
  const char *name;
  int shown;
} placeholders[] = {
    {"machine", 0},
    {"suite.command", 0},
    {"raster.command", 1},
    {"raster.table", 1},
    {"llvmpipe.table", 1},
    {"threads.command", 1},
    {"threads.llvmpipe.table", 1},
    {"threads.speedup.table", 1},
    {"memory.command", 1},
    {"memory.table", 1},
    {"calibrate.command", 1},
    {"calibrate.output", 1},
    {"walk.plant.scene", 0},
    {"walk.plant.command", 1},
    {"walk.plant.extent", 0},
    {"walk.plant.table", 1},
    {"walk.plant.churn", 1},
    {"walk.plant.hzb", 1},
    {"walk.teapots.scene", 0},
    {"walk.teapots.command", 1},
    {"walk.teapots.extent", 0},
    {"walk.teapots.table", 1},
    {"walk.teapots.churn", 1},
    {"walk.teapots.hzb", 1},
    {"tradeoff.command", 1},
    {"tradeoff.teapots.walk", 0},
    {"tradeoff.teapots.table", 1},
    {"tradeoff.city.walk", 0},
    {"tradeoff.city.table", 1},
    {"tradeoff.plant.walk", 0},
    {"tradeoff.plant.table", 1},
    {"depthsort.command", 1},
    {"depthsort.table", 1},
    {"octree.command", 1},
    {"octree.table", 1},
    {"shade.unlit.command", 1},
    {"shade.unlit.llvmpipe", 1},
    {"shade.gouraud.command", 1},
    {"shade.gouraud.llvmpipe", 1},
    {"shade.phong.command", 1},
    {"shade.phong.llvmpipe", 1},
    {"colours.command", 1},
    {"colours.table", 1},
    {"lines.command", 1},
    {"lines.table", 1},
    {"arrays.command", 1},
    {"arrays.table", 1},
    {"samples.command", 1},
    {"samples.table", 1},
};
enum { NPLACEHOLDERS = sizeof placeholders / sizeof placeholders[0] };

enum { CMD = 2048, PATH = 4200, MAX_TEMPLATES = 64 };

/* One template: its path (as the user named the folder) and its text. */
typedef struct template_file {
  char path[PATH + 256];
  char *text;
} template_file;

/* What one run of the suite does, and what it measured, for the page. */
typedef struct suite {
  const char *dir, *size, *docs;
  int quick, quiet, no_run;
  int threads;                     /* N of the second raster pass, as its command shows */
  char threads_arg[16], lp_env[48]; /* "N", "LP_NUM_THREADS=N" */
  int mesa, callgrind, run_threads; /* what this run does */
  int have_mesa, plots, ncpu;
  char self[4096];
  char machine[512];
  char command[CMD]; /* this run's own command line */
  template_file tmpl[MAX_TEMPLATES];
  int ntmpl;
  char *value[NPLACEHOLDERS]; /* each placeholder's text, once measured */
} suite;

static void in_dir(char *buf, const suite *s, const char *name) {
  snprintf(buf, PATH, "%s/%s", s->dir, name);
}

/* in_dir of the name pattern with its %s replaced by word: "walk-%s.csv". */
static void in_dir_named(char *buf, const suite *s, const char *pattern, const char *word) {
  char name[256];
  snprintf(name, sizeof name, pattern, word);
  in_dir(buf, s, name);
}

/* args joined by spaces after prefix, a word with a shell's special
 * characters in double quotes. */
static void join_cmd(char *buf, const char *prefix, char *const *args) {
  size_t len = (size_t)snprintf(buf, CMD, "%s", prefix);
  for (int i = 0; args[i] && len < CMD; i++) {
    const int quote = strpbrk(args[i], "?&* ;") != NULL;
    len += (size_t)snprintf(buf + len, CMD - len, "%s%s%s%s", len ? " " : "", quote ? "\"" : "",
                            args[i], quote ? "\"" : "");
  }
}

/* "2-core x86_64 VM (AMD EPYC), gcc 12.2.0, Release build" */
static void describe_machine(char *buf, size_t cap) {
  char model[256] = "";
  int vm = 0;
  FILE *f = fopen("/proc/cpuinfo", "r");
  if (f) {
    char line[4096];
    while (fgets(line, sizeof line, f)) {
      char *c = strchr(line, ':');
      if (!model[0] && c && strncmp(line, "model name", 10) == 0) {
        for (c++; *c == ' ' || *c == '\t'; c++) {}
        c[strcspn(c, "\n")] = '\0';
        snprintf(model, sizeof model, "%s", c);
      }
      if (strncmp(line, "flags", 5) == 0 && strstr(line, " hypervisor")) vm = 1;
    }
    fclose(f);
  }
  char arch[64];
  zs_os_machine(arch, sizeof arch);
  const int ncpu = zs_os_cpu_count();
  char compiler[128];
#if defined(__clang__)
  snprintf(compiler, sizeof compiler, "clang %d.%d.%d", __clang_major__, __clang_minor__,
           __clang_patchlevel__);
#elif defined(__GNUC__)
  snprintf(compiler, sizeof compiler, "gcc %d.%d.%d", __GNUC__, __GNUC_MINOR__,
           __GNUC_PATCHLEVEL__);
#else
  snprintf(compiler, sizeof compiler, "an unknown compiler");
#endif
#if defined(NDEBUG) && defined(__OPTIMIZE__)
  const char *build = "Release build";
#elif defined(__OPTIMIZE__)
  const char *build = "optimised build";
#else
  const char *build = "unoptimised build";
#endif
  snprintf(buf, cap, "%d-core %s %s%s%s%s, %s, %s", ncpu, arch, vm ? "VM" : "machine",
           model[0] ? " (" : "", model, model[0] ? ")" : "", compiler, build);
}

/* ---- the benchmarks' arguments ----------------------------------------- */

/* A NULL-terminated argument list. */
typedef struct arglist {
  char *v[40];
  int n;
} arglist;

static void arg(arglist *a, const char *word) {
  if (a->n < 39) a->v[a->n++] = (char *)word;
  a->v[a->n] = NULL;
}

static void arg2(arglist *a, const char *opt, const char *value) {
  arg(a, opt);
  arg(a, value);
}

/* How a benchmark's arguments are built: as this run runs it, or as the
 * page shows it (the full run's, without the files it writes). */
typedef struct how {
  int quick, mesa, callgrind, files;
} how;

static how as_run(const suite *s) { return (how){s->quick, s->mesa, s->callgrind, 1}; }
static const how as_shown = {0, 1, 1, 0};

/* --size: the user's, else under --quick the small one, when given. */
static void size_arg(const suite *s, how h, const char *small, arglist *a) {
  if (s->size) arg2(a, "--size", s->size);
  else if (h.quick && small) arg2(a, "--size", small);
}

/* The output files of the benchmarks run in this process. */
enum { F_RASTER_CSV, F_RASTER_MD, F_RASTER_PNG, F_DEPTHSORT, F_OCTREE_CSV, F_OCTREE_PNG,
       F_CLOCK, F_THREADS_CSV, F_THREADS_MD, F_THREADS_PNG, NFILES };
static const char *const file_names[NFILES] = {
    "raster.csv", "raster.md",          "raster.png",         "depthsort.csv",
    "octree.csv", "octree.png",         "clock.json",         "raster-threads.csv",
    "raster-threads.md", "raster-threads.png"};

typedef struct files {
  char path[NFILES][PATH];
  char walk[2][3][PATH]; /* each large walk's csv, md, txt */
  char shade[3][PATH];   /* each shading's md */
  char colours[PATH];    /* bench colours' md */
  char lines[PATH];      /* bench lines' md */
  char arrays[PATH];     /* bench arrays' md */
  char samples[PATH];    /* bench samples' md */
} files;

static void raster_args(const suite *s, const files *fs, how h, arglist *a) {
  arg(a, "raster");
  if (h.files) {
    arg2(a, "--csv", fs->path[F_RASTER_CSV]);
    arg2(a, "--md", fs->path[F_RASTER_MD]);
    arg2(a, "--plot", fs->path[F_RASTER_PNG]);
  }
  if (h.mesa) arg(a, "--mesa");
  if (h.callgrind) arg(a, "--callgrind");
  if (h.quick) {
    arg2(a, "--repeat", "1");
    arg(a, "--no-scenes");
  }
  size_arg(s, h, quick_raster_size, a);
}

static void threads_args(const suite *s, const files *fs, how h, arglist *a) {
  arg(a, "bench");
  arg(a, "raster");
  arg2(a, "--threads", s->threads_arg);
  arg(a, "--speedup");
  if (h.mesa) arg(a, "--mesa");
  if (h.files) {
    arg2(a, "--csv", fs->path[F_THREADS_CSV]);
    arg2(a, "--md", fs->path[F_THREADS_MD]);
    arg2(a, "--plot", fs->path[F_THREADS_PNG]);
  }
  size_arg(s, h, NULL, a);
}

/* bench raster's scenes in shading k, beside llvmpipe's equivalent. */
static void shade_args(const suite *s, const files *fs, int k, how h, arglist *a) {
  arg(a, "raster");
  arg2(a, "--shade", shadings[k]);
  arg(a, "--no-tilings");
  if (h.files) arg2(a, "--md", fs->shade[k]);
  if (h.mesa) arg(a, "--mesa");
  if (h.quick) { /* one small scene, a frame: a check that it runs */
    arg2(a, "--repeat", "1");
    arg2(a, "--case", "builtin:teapots,count=4");
  }
  size_arg(s, h, quick_raster_size, a);
}

static void colours_args(const files *fs, how h, arglist *a) {
  arg(a, "colours");
  if (h.files) arg2(a, "--md", fs->colours);
}

static void lines_args(const files *fs, how h, arglist *a) {
  arg(a, "lines");
  if (h.files) arg2(a, "--md", fs->lines);
}

static void arrays_args(const files *fs, how h, arglist *a) {
  arg(a, "arrays");
  if (h.quick) arg(a, "--quick");
  if (h.files) arg2(a, "--md", fs->arrays);
}

static void samples_args(const files *fs, how h, arglist *a) {
  arg(a, "samples");
  if (h.quick) arg(a, "--quick");
  if (h.files) arg2(a, "--md", fs->samples);
}

static void calibrate_args(const suite *s, const files *fs, how h, arglist *a) {
  (void)s;
  arg(a, "calibrate");
  arg2(a, "--repeat", h.quick ? "1" : "9");
  if (h.files) arg2(a, "-o", fs->path[F_CLOCK]);
}

static void walk_args(const suite *s, const files *fs, int w, how h, arglist *a) {
  arg(a, "walk");
  arg(a, walks[w][h.quick ? 2 : 1]);
  arg2(a, "--cull", all_methods);
  if (h.quick) arg2(a, "--frames", "2"); /* the least that shows ideal-box's set change */
  size_arg(s, h, quick_size, a);
  if (h.files) {
    arg2(a, "--csv", fs->walk[w][0]);
    arg2(a, "--md", fs->walk[w][1]);
    arg(a, "--quiet");
  }
}

static void tradeoff_args(const suite *s, how h, arglist *a) {
  arg(a, "tradeoff");
  if (h.files) arg2(a, "--out", s->dir);
  if (h.quick) arg(a, "--quick");
  if (h.files && s->quiet) arg(a, "--quiet");
  size_arg(s, h, quick_size, a);
}

static void depthsort_args(const suite *s, const files *fs, how h, arglist *a) {
  arg(a, "depthsort");
  arg2(a, "--frames", h.quick ? "4" : "40");
  if (h.files) arg2(a, "--csv", fs->path[F_DEPTHSORT]);
  size_arg(s, h, quick_size, a);
}

static void octree_args(const suite *s, const files *fs, how h, arglist *a) {
  (void)s;
  arg(a, "octree");
  arg2(a, "--count", h.quick ? "500" : "5000");
  arg2(a, "--frames", h.quick ? "3" : "50");
  if (h.files) {
    arg2(a, "--csv", fs->path[F_OCTREE_CSV]);
    arg2(a, "--plot", fs->path[F_OCTREE_PNG]);
  }
}

/* ---- running them ------------------------------------------------------ */

/* Runs one benchmark's command with args (NULL-terminated, the command's
 * name first); returns its exit status. */
static int run(int (*fn)(int, char **), char **args) {
  int n = 0;
  while (args[n]) n++;
  char line[CMD];
  join_cmd(line, "zscan bench", args);
  printf("\n$ %s\n", line);
  fflush(stdout);
  return fn(n, args);
}

/* Runs this zscan again as a child with args (NULL-terminated, without
 * the program), its output into the file txt and then here too. */
static zs_status run_child(const suite *s, char **args, const char *txt, const char *env,
                           zs_error *err) {
  char *argv[48];
  int n = 0;
  argv[n++] = (char *)s->self;
  for (int i = 0; args[i] && n < 47; i++) argv[n++] = args[i];
  argv[n] = NULL;
  char prefix[96], line[CMD];
  snprintf(prefix, sizeof prefix, "%s%szscan", env ? env : "", env ? " " : "");
  join_cmd(line, prefix, args);
  printf("\n$ %s\n", line);
  fflush(stdout);
  /* the child writes into a scratch file, which then reaches txt through
   * the output primitive like every other output */
  char dir[PATH], scratch[PATH + 16];
  int e = zs_os_scratch_dir("zscan-suite", dir, sizeof dir);
  if (e != 0) return zs_error_set(err, ZS_ERR_IO, "cannot create a scratch folder: %s", strerror(e));
  snprintf(scratch, sizeof scratch, "%s/output.txt", dir);
  FILE *made = fopen(scratch, "wb"); /* (there even when the child never starts) */
  if (!made || fclose(made) != 0) {
    zs_os_rmdir(dir);
    return zs_error_set(err, ZS_ERR_IO, "%s: cannot create: %s", scratch, strerror(errno));
  }
  int rc = zs_os_spawn_wait(argv, scratch, scratch);
  zs_out out;
  zs_status st = zs_out_open(&out, txt, err);
  if (!st && !(st = zs_append_file(out.fp, scratch, err))) st = zs_out_commit(&out, err);
  else if (!st) zs_out_discard(&out);
  if (!st) st = zs_append_file(stdout, scratch, err); /* what it printed, here too */
  remove(scratch);
  zs_os_rmdir(dir);
  if (rc != 0)
    return zs_error_set(err, ZS_ERR_IO, "'%s' failed (exit %d; its output: %s)", line, rc, txt);
  return st;
}

/* bench raster on N threads beside llvmpipe on N, and the speed-up over
 * one thread. */
static zs_status run_threads(suite *s, const files *fs, zs_error *err) {
  char txt[PATH];
  in_dir(txt, s, "raster-threads.txt");
  arglist a = {0};
  threads_args(s, fs, as_run(s), &a);
  zs_os_setenv("LP_NUM_THREADS", s->threads_arg);
  zs_status st = run_child(s, a.v, txt, s->mesa ? s->lp_env : NULL, err);
  zs_os_setenv("LP_NUM_THREADS", "1");
  return st;
}

/* The value of "key":NUMBER in a JSON line; -1 when absent. */
static long long json_int(const char *line, const char *key) {
  char pat[64];
  snprintf(pat, sizeof pat, "\"%s\":", key);
  const char *p = strstr(line, pat);
  return p ? strtoll(p + strlen(pat), NULL, 10) : -1;
}

/* 1234567 as "1,234,567" */
static void grouped(char *buf, size_t cap, long long v) {
  char digits[32];
  int n = snprintf(digits, sizeof digits, "%lld", v < 0 ? -v : v), len = 0;
  if (v < 0 && (size_t)len + 1 < cap) buf[len++] = '-';
  for (int i = 0; i < n && (size_t)len + 2 < cap; i++) {
    if (i && (n - i) % 3 == 0) buf[len++] = ',';
    buf[len++] = digits[i];
  }
  buf[len] = '\0';
}

/* render --stats in both modes at four sizes: the buffers and tables the
 * device holds, into memory.md. */
static zs_status run_memory(const suite *s, zs_error *err) {
  char txt[PATH], png[PATH], md[PATH];
  in_dir(txt, s, "memory.txt");
  in_dir(png, s, "memory.png");
  in_dir(md, s, "memory.md");
  static const char *const algos[2] = {"zbuffer", "scanline"};
  long long bytes[4][2][2]; /* size, mode, buffers / tables */
  for (int i = 0; i < 4; i++)
    for (int a = 0; a < 2; a++) {
      char *args[] = {"render", "--algo", (char *)algos[a], "--size",
                      (char *)mem_sizes[s->quick][i], "--stats", "-o", png, NULL};
      zs_status st = run_child(s, args, txt, NULL, err);
      if (st) return st;
      FILE *f = fopen(txt, "r");
      char line[8192] = "";
      if (!f || !fgets(line, sizeof line, f)) {
        if (f) fclose(f);
        return zs_error_set(err, ZS_ERR_IO, "%s: no statistics", txt);
      }
      fclose(f);
      bytes[i][a][0] = json_int(line, "buffer_bytes");
      bytes[i][a][1] = json_int(line, "table_bytes");
    }
  remove(png);
  zs_out out;
  if (zs_out_open(&out, md, err)) return err->code;
  fprintf(out.fp, "| size | zbuffer: buffers | zbuffer: tables | scanline: buffers | scanline: "
                  "tables |\n|---|---|---|---|---|\n");
  for (int i = 0; i < 4; i++) {
    char v[4][32];
    for (int k = 0; k < 4; k++) grouped(v[k], sizeof v[k], bytes[i][k / 2][k % 2]);
    fprintf(out.fp, "| %s | %s | %s | %s | %s |\n", mem_sizes[s->quick][i], v[0], v[1], v[2],
            v[3]);
  }
  return zs_out_commit(&out, err);
}

/* One of the large walks at every frame, every method. */
static zs_status run_walk(const suite *s, const files *fs, int w, zs_error *err) {
  arglist a = {0};
  walk_args(s, fs, w, as_run(s), &a);
  return run_child(s, a.v, fs->walk[w][2], NULL, err);
}

/* Modelled ms along a walk from its CSV (frame,method,chosen,modelled_ms,
 * ...), the plotted methods only, into png. */
static zs_status plot_walk(const char *csv, const char *png, const char *title, zs_error *err) {
  FILE *f = fopen(csv, "r");
  if (!f) return zs_error_set(err, ZS_ERR_IO, "%s: cannot open", csv);
  char line[1024];
  int cap = 0, n = 0, step = 0, first = -1;
  double *y = NULL;
  zs_status st = ZS_OK;
  if (!fgets(line, sizeof line, f)) st = zs_error_set(err, ZS_ERR_IO, "%s: empty", csv);
  while (st == ZS_OK && fgets(line, sizeof line, f)) {
    char method[64];
    int frame;
    double ms;
    if (sscanf(line, "%d,%63[^,],%*[^,],%lf", &frame, method, &ms) != 3) continue;
    int j = -1;
    for (int m = 0; m < NPLOTTED; m++)
      if (strcmp(method, plotted[m]) == 0) j = m;
    if (j < 0) continue;
    if (first < 0) first = frame;
    if (!step && frame != first) step = frame - first;
    const int i = step ? (frame - first) / step : 0;
    if (i >= cap) {
      int ncap = cap ? 2 * cap : 256;
      while (ncap <= i) ncap *= 2;
      double *ny = realloc(y, (size_t)ncap * NPLOTTED * sizeof *y);
      if (!ny) {
        st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
        break;
      }
      for (size_t q = (size_t)cap * NPLOTTED; q < (size_t)ncap * NPLOTTED; q++) ny[q] = 0.0;
      y = ny;
      cap = ncap;
    }
    y[(size_t)i * NPLOTTED + (size_t)j] = ms;
    if (i + 1 > n) n = i + 1;
  }
  fclose(f);
  if (st == ZS_OK && n == 0) st = zs_error_set(err, ZS_ERR_IO, "%s: no frames to plot", csv);
  if (st == ZS_OK)
    st = zs_plot_series(png, title, "frame", "modelled ms per frame", y, n, NPLOTTED, plotted,
                        first < 0 ? 0 : first, step ? step : 1, 0, err);
  free(y);
  return st;
}

/* The i-th "$ zscan walk ..." line of tradeoff.md, without the "$ ". */
static void tradeoff_cmd(const suite *s, int i, char *buf) {
  char path[PATH], line[CMD];
  in_dir(path, s, "tradeoff.md");
  buf[0] = '\0';
  FILE *f = fopen(path, "r");
  if (!f) return;
  for (int k = 0; fgets(line, sizeof line, f);)
    if (strncmp(line, "$ zscan walk", 12) == 0 && k++ == i) {
      line[strcspn(line, "\n")] = '\0';
      snprintf(buf, CMD, "%s", line + 2);
      break;
    }
  fclose(f);
}

/* From "zscan walk \"SCENE\" ... --step K ...": the scene, and "every
 * Kth frame" ("every frame" without a step). */
static void walk_of(const char *cmd, char *scene, size_t cap, char *every, size_t ecap) {
  const char *a = strstr(cmd, "walk "), *st = strstr(cmd, "--step ");
  scene[0] = '\0';
  if (a) {
    a += 5;
    const int quoted = *a == '"';
    a += quoted;
    size_t len = strcspn(a, quoted ? "\"" : " ");
    if (len >= cap) len = cap - 1;
    memcpy(scene, a, len);
    scene[len] = '\0';
  }
  const int k = st ? atoi(st + 7) : 1;
  const char *suffix = k % 10 == 1 && k % 100 != 11   ? "st"
                       : k % 10 == 2 && k % 100 != 12 ? "nd"
                       : k % 10 == 3 && k % 100 != 13 ? "rd"
                                                      : "th";
  if (k <= 1) snprintf(every, ecap, "every frame");
  else snprintf(every, ecap, "every %d%s frame", k, suffix);
}

/* The two large walks' modelled time along every frame, and along
 * bench tradeoff's steps. */
static zs_status plot_walks(const suite *s, const files *fs, zs_error *err) {
  static const char *const walk_name[2][2] = {{"walk-plant", "tradeoff-plant"},
                                              {"walk-teapots", "tradeoff-teapots"}};
  for (int k = 0; k < 2; k++) {
    char csv[PATH], png[PATH], title[400];
    in_dir_named(png, s, "%s-every.png", walk_name[k][0]);
    snprintf(title, sizeof title, "%s, every frame", walks[k][s->quick ? 2 : 1]);
    if (plot_walk(fs->walk[k][0], png, title, err)) return err->code;
    in_dir_named(csv, s, "%s.csv", walk_name[k][1]);
    in_dir_named(png, s, "%s.png", walk_name[k][0]);
    char cmd[CMD], scene[256], every[64];
    tradeoff_cmd(s, k ? 0 : 2, cmd); /* its walks: teapots, city, plant */
    walk_of(cmd, scene, sizeof scene, every, sizeof every);
    snprintf(title, sizeof title, "%s, %s", scene, every);
    if (plot_walk(csv, png, title, err)) return err->code;
  }
  return ZS_OK;
}

/* The benchmarks in turn: raster, on N threads, the three shadings, the
 * colours and the lines (with llvmpipe), arrays, memory, calibrate, two walks, tradeoff,
 * depthsort, octree.  1: a benchmark run here failed
 * (it said why); -1: an error in err. */
static int run_all(suite *s, const files *fs, zs_error *err) {
  zs_progress progress;
  int done = 0;
  zs_progress_start(&progress, "bench suite", "benchmark", 13 + s->run_threads + 2 * s->mesa,
                    s->quiet);
  const how h = as_run(s);
  arglist a = {0};
  /* llvmpipe on one thread beside zscan's one */
  if (s->mesa) zs_os_setenv("LP_NUM_THREADS", "1");
  raster_args(s, fs, h, &a);
  if (run(zs_cmd_bench_raster, a.v)) return 1;
  zs_progress_step(&progress, ++done);
  if (s->run_threads) {
    if (run_threads(s, fs, err)) return -1;
    zs_progress_step(&progress, ++done);
  }
  for (int k = 0; k < 3; k++) {
    a = (arglist){0};
    shade_args(s, fs, k, h, &a);
    if (run(zs_cmd_bench_raster, a.v)) return 1;
    zs_progress_step(&progress, ++done);
  }
  if (s->mesa) {
    a = (arglist){0};
    colours_args(fs, h, &a);
    if (run(zs_cmd_bench_colours, a.v)) return 1;
    zs_progress_step(&progress, ++done);
    a = (arglist){0};
    lines_args(fs, h, &a);
    if (run(zs_cmd_bench_lines, a.v)) return 1;
    zs_progress_step(&progress, ++done);
  }
  a = (arglist){0};
  arrays_args(fs, h, &a);
  if (run(zs_cmd_bench_arrays, a.v)) return 1;
  zs_progress_step(&progress, ++done);
  a = (arglist){0};
  samples_args(fs, h, &a);
  if (run(zs_cmd_bench_samples, a.v)) return 1;
  zs_progress_step(&progress, ++done);
  if (run_memory(s, err)) return -1;
  zs_progress_step(&progress, ++done);
  char calibrate_txt[PATH];
  in_dir(calibrate_txt, s, "calibrate.txt");
  a = (arglist){0};
  calibrate_args(s, fs, h, &a);
  if (run_child(s, a.v, calibrate_txt, NULL, err)) return -1;
  zs_progress_step(&progress, ++done);
  for (int k = 0; k < 2; k++) {
    if (run_walk(s, fs, k, err)) return -1;
    zs_progress_step(&progress, ++done);
  }
  a = (arglist){0};
  tradeoff_args(s, h, &a);
  if (run(zs_cmd_bench_tradeoff, a.v)) return 1;
  zs_progress_step(&progress, ++done);
  a = (arglist){0};
  depthsort_args(s, fs, h, &a);
  if (run(zs_cmd_bench_depthsort, a.v)) return 1;
  zs_progress_step(&progress, ++done);
  a = (arglist){0};
  octree_args(s, fs, h, &a);
  if (run(zs_cmd_bench_octree, a.v)) return 1;
  zs_progress_step(&progress, ++done);
  return 0;
}

/* ---- what the page shows ------------------------------------------------ */

/* Copies block k (0 from the top) of the Markdown tables in path: blocks
 * of consecutive lines that begin with '|'.  With rows, only the header,
 * its rule and the rows whose first cell is one of rows[0..nrows-1]. */
static zs_status append_table(FILE *out, const char *path, int k, const char *const *rows,
                              int nrows, zs_error *err) {
  FILE *f = fopen(path, "r");
  if (!f) return zs_error_set(err, ZS_ERR_IO, "%s: cannot open", path);
  char line[8192];
  int block = -1, in = 0, copied = 0, row = 0;
  while (fgets(line, sizeof line, f)) {
    const int is_row = line[0] == '|';
    if (is_row && !in) {
      block++;
      row = 0;
    }
    in = is_row;
    if (!is_row || block != k) continue;
    int keep = row++ < 2 || !rows;
    for (int r = 0; r < nrows && !keep; r++) {
      const size_t len = strlen(rows[r]);
      keep = strncmp(line, "| ", 2) == 0 && strncmp(line + 2, rows[r], len) == 0 &&
             line[2 + len] == ' ';
    }
    if (keep) {
      fputs(line, out);
      copied++;
    }
  }
  fclose(f);
  return copied ? ZS_OK : zs_error_set(err, ZS_ERR_IO, "%s: no table %d", path, k + 1);
}

/* The first n paragraphs (runs of lines up to a blank line) of the text
 * file path from the first line that begins with from, and not past a
 * "wrote " line. */
static zs_status append_lines(FILE *out, const char *path, const char *from, int n,
                              zs_error *err) {
  FILE *f = fopen(path, "r");
  if (!f) return zs_error_set(err, ZS_ERR_IO, "%s: cannot open", path);
  char line[8192];
  int on = 0, copied = 0;
  while (fgets(line, sizeof line, f)) {
    if (!on && strncmp(line, from, strlen(from)) == 0) on = 1;
    if (on && copied && ((line[0] == '\n' && --n == 0) || strncmp(line, "wrote ", 6) == 0))
      break;
    if (on) {
      fputs(line, out);
      copied++;
    }
  }
  fclose(f);
  return copied ? ZS_OK : zs_error_set(err, ZS_ERR_IO, "%s: no '%s'", path, from);
}

/* The first line of a walk's output, "SCENE: 400 frames at ...", without
 * the scene: "400 frames at 1024x768, 1223 objects, 1998586 faces". */
static void walk_extent(const char *txt, char *buf, size_t cap) {
  buf[0] = '\0';
  FILE *f = fopen(txt, "r");
  char line[1024];
  if (f && fgets(line, sizeof line, f)) {
    char *p = strstr(line, ": ");
    line[strcspn(line, "\n")] = '\0';
    const char *from = p ? p + 2 : line;
    size_t len = strlen(from);
    if (len >= cap) len = cap - 1;
    memcpy(buf, from, len);
    buf[len] = '\0';
  }
  if (f) fclose(f);
}

/* The CSV at path (a header, then rows) as a Markdown table: the columns
 * col[0..n-1] (0-based) under the headers head, each number printed with
 * fmt[j] ("%.3f"; "%.0f" for counts). */
static zs_status csv_table(FILE *out, const char *path, int n, const int *col,
                           const char *const *head, const char *const *fmt, zs_error *err) {
  FILE *f = fopen(path, "r");
  if (!f) return zs_error_set(err, ZS_ERR_IO, "%s: cannot open", path);
  char line[4096];
  if (!fgets(line, sizeof line, f)) {
    fclose(f);
    return zs_error_set(err, ZS_ERR_IO, "%s: empty", path);
  }
  fputs("|", out);
  for (int j = 0; j < n; j++) fprintf(out, " %s |", head[j]);
  fputs("\n|", out);
  for (int j = 0; j < n; j++) fputs("---|", out);
  fputs("\n", out);
  while (fgets(line, sizeof line, f)) {
    line[strcspn(line, "\r\n")] = '\0';
    char *field[64];
    int nf = 0;
    for (char *p = line; nf < 64;) {
      field[nf++] = p;
      char *c = strchr(p, ',');
      if (!c) break;
      *c = '\0';
      p = c + 1;
    }
    fputs("|", out);
    for (int j = 0; j < n; j++) {
      const char *v = col[j] < nf ? field[col[j]] : "";
      char *end;
      double d = strtod(v, &end);
      char cell[64];
      if (fmt[j] && *v && !*end) snprintf(cell, sizeof cell, fmt[j], d);
      else snprintf(cell, sizeof cell, "%s", v);
      fprintf(out, " %s |", cell);
    }
    fputs("\n", out);
  }
  fclose(f);
  return ZS_OK;
}

static int placeholder_index(const char *name, size_t len) {
  for (int i = 0; i < NPLACEHOLDERS; i++)
    if (strlen(placeholders[i].name) == len && memcmp(placeholders[i].name, name, len) == 0)
      return i;
  return -1;
}

/* A text written through a stream, to become a placeholder's value. */
typedef zs_memfile capture;

static zs_status capture_open(capture *c, zs_error *err) {
  int e = zs_memfile_open(c);
  return e ? zs_error_set(err, ZS_ERR_NOMEM, "cannot keep a text: %s", strerror(e)) : ZS_OK;
}

/* Closes the capture; on st == ZS_OK its text, without its last line
 * breaks, becomes the value of name (one of placeholders[]). */
static zs_status capture_keep(suite *s, const char *name, capture *c, zs_status st,
                              zs_error *err) {
  if (zs_memfile_close(c) != 0 && st == ZS_OK) st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  const int i = placeholder_index(name, strlen(name));
  if (st == ZS_OK && i < 0) st = zs_error_set(err, ZS_ERR_ARG, "no placeholder {%s}", name);
  if (st != ZS_OK) {
    free(c->data);
    return st;
  }
  while (c->size && c->data[c->size - 1] == '\n') c->data[--c->size] = '\0';
  free(s->value[i]);
  s->value[i] = c->data;
  return ZS_OK;
}

/* name's value: the text text. */
static zs_status set_text(suite *s, const char *name, const char *text, zs_error *err) {
  capture c;
  if (capture_open(&c, err)) return err->code;
  fputs(text, c.f);
  return capture_keep(s, name, &c, ZS_OK, err);
}

/* name's value: a command line, args joined after prefix. */
static zs_status set_command(suite *s, const char *name, const char *prefix, char *const *args,
                             zs_error *err) {
  char line[CMD];
  join_cmd(line, prefix, args);
  return set_text(s, name, line, err);
}

/* name's value: table k of the output directory's file md (rows: only
 * those of hzb_rows). */
static zs_status set_table(suite *s, const char *name, const char *md, int k, int rows,
                           zs_error *err) {
  char path[PATH];
  in_dir(path, s, md);
  capture c;
  if (capture_open(&c, err)) return err->code;
  zs_status st = append_table(c.f, path, k, rows ? hzb_rows : NULL,
                              rows ? (int)(sizeof hzb_rows / sizeof hzb_rows[0]) : 0, err);
  return capture_keep(s, name, &c, st, err);
}

/* name's value: the first n paragraphs of the text file path from the
 * line that begins with from (append_lines). */
static zs_status set_lines(suite *s, const char *name, const char *path, const char *from, int n,
                           zs_error *err) {
  capture c;
  if (capture_open(&c, err)) return err->code;
  return capture_keep(s, name, &c, append_lines(c.f, path, from, n, err), err);
}

/* name's value: the CSV at path as a Markdown table (csv_table). */
static zs_status set_csv(suite *s, const char *name, const char *path, int n, const int *col,
                         const char *const *head, const char *const *fmt, zs_error *err) {
  capture c;
  if (capture_open(&c, err)) return err->code;
  return capture_keep(s, name, &c, csv_table(c.f, path, n, col, head, fmt, err), err);
}

/* The value of a table this run did not measure. */
static const char not_measured[] = "Not measured with `--quick`.";

/* The raster tables on one thread and on N, beside llvmpipe; memory; the
 * clock. */
static zs_status fill_device(suite *s, const files *fs, zs_error *err) {
  arglist a = {0};
  char lpn[96], path[PATH];
  snprintf(lpn, sizeof lpn, "%s zscan", s->lp_env);
  raster_args(s, fs, as_shown, &a);
  if (set_command(s, "raster.command", "LP_NUM_THREADS=1 zscan bench", a.v, err) ||
      set_table(s, "raster.table", "raster.md", 0, 0, err))
    return err->code;
  zs_status st = s->mesa ? set_table(s, "llvmpipe.table", "raster.md", 1, 0, err)
                         : set_text(s, "llvmpipe.table", not_measured, err);
  if (st) return st;
  a = (arglist){0};
  threads_args(s, fs, as_shown, &a);
  if (set_command(s, "threads.command", lpn, a.v, err)) return err->code;
  st = s->run_threads && s->mesa
           ? set_table(s, "threads.llvmpipe.table", "raster-threads.md", 1, 0, err)
           : set_text(s, "threads.llvmpipe.table", not_measured, err);
  if (!st)
    st = s->run_threads
             ? set_table(s, "threads.speedup.table", "raster-threads.md", s->mesa ? 2 : 1, 0, err)
             : set_text(s, "threads.speedup.table", not_measured, err);
  if (st) return st;
  if (set_text(s, "memory.command", "zscan render --algo MODE --size SIZE --stats", err) ||
      set_table(s, "memory.table", "memory.md", 0, 0, err))
    return err->code;
  a = (arglist){0};
  calibrate_args(s, fs, as_shown, &a);
  in_dir(path, s, "calibrate.txt");
  if (set_command(s, "calibrate.command", "zscan", a.v, err) ||
      set_lines(s, "calibrate.output", path, "workload", 2, err))
    return err->code;
  return ZS_OK;
}

/* bench raster's scenes in each shading beside llvmpipe's, and bench
 * colours' and bench lines' cross-checks. */
static zs_status fill_shading(suite *s, const files *fs, zs_error *err) {
  for (int k = 0; k < 3; k++) {
    char name[64], md[64];
    arglist a = {0};
    shade_args(s, fs, k, as_shown, &a);
    snprintf(md, sizeof md, "shade-%s.md", shadings[k]);
#define NAME(field) (snprintf(name, sizeof name, "shade.%s." field, shadings[k]), name)
    if (set_command(s, NAME("command"), "LP_NUM_THREADS=1 zscan bench", a.v, err) ||
        (s->mesa ? set_table(s, NAME("llvmpipe"), md, 1, 0, err)
                 : set_text(s, NAME("llvmpipe"), not_measured, err)))
      return err->code;
#undef NAME
  }
  arglist a = {0};
  colours_args(fs, as_shown, &a);
  if (set_command(s, "colours.command", "zscan bench", a.v, err) ||
      (s->mesa ? set_table(s, "colours.table", "colours.md", 0, 0, err)
               : set_text(s, "colours.table", not_measured, err)))
    return err->code;
  a = (arglist){0};
  lines_args(fs, as_shown, &a);
  if (set_command(s, "lines.command", "zscan bench", a.v, err) ||
      (s->mesa ? set_table(s, "lines.table", "lines.md", 0, 0, err)
               : set_text(s, "lines.table", not_measured, err)))
    return err->code;
  a = (arglist){0};
  arrays_args(fs, as_shown, &a);
  if (set_command(s, "arrays.command", "zscan bench", a.v, err) ||
      set_table(s, "arrays.table", "arrays.md", 0, 0, err))
    return err->code;
  a = (arglist){0};
  samples_args(fs, as_shown, &a);
  if (set_command(s, "samples.command", "zscan bench", a.v, err) ||
      set_table(s, "samples.table", "samples.md", 0, 0, err))
    return err->code;
  return ZS_OK;
}

/* The two large walks, and bench tradeoff's. */
static zs_status fill_walks(suite *s, const files *fs, zs_error *err) {
  for (int w = 0; w < 2; w++) {
    char name[64], extent[256], md[64];
    const char *key = walks[w][0];
    arglist a = {0};
    walk_args(s, fs, w, as_shown, &a);
    walk_extent(fs->walk[w][2], extent, sizeof extent);
    snprintf(md, sizeof md, "walk-%s.md", key);
#define NAME(field) (snprintf(name, sizeof name, "walk.%s." field, key), name)
    if (set_command(s, NAME("command"), "zscan", a.v, err) ||
        set_text(s, NAME("scene"), walks[w][1], err) ||
        set_text(s, NAME("extent"), extent, err) || set_table(s, NAME("table"), md, 0, 0, err) ||
        set_table(s, NAME("hzb"), md, 0, 1, err) ||
        set_lines(s, NAME("churn"), fs->walk[w][2], "ideal-box's set", 1, err))
      return err->code;
#undef NAME
  }
  arglist a = {0};
  tradeoff_args(s, as_shown, &a);
  if (set_command(s, "tradeoff.command", "zscan bench", a.v, err)) return err->code;
  for (int w = 0; w < 3; w++) {
    char name[64], md[64], cmd[CMD], scene[256], every[64], walk[400];
    tradeoff_cmd(s, w, cmd);
    walk_of(cmd, scene, sizeof scene, every, sizeof every);
    snprintf(walk, sizeof walk, "`%s`, %s", scene, every);
    snprintf(name, sizeof name, "tradeoff.%s.walk", tradeoff_walks[w]);
    if (set_text(s, name, walk, err)) return err->code;
    snprintf(name, sizeof name, "tradeoff.%s.table", tradeoff_walks[w]);
    snprintf(md, sizeof md, "tradeoff-%s.md", tradeoff_walks[w]);
    if (set_table(s, name, md, 0, 0, err)) return err->code;
  }
  return ZS_OK;
}

/* bench depthsort's and bench octree's tables, from their CSVs. */
static zs_status fill_sorts(suite *s, const files *fs, zs_error *err) {
  static const int ds_col[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  static const char *const ds_head[8] = {"motion",
                                         "faces",
                                         "reused %",
                                         "full sort ms",
                                         "coherent sort ms",
                                         "full comparisons",
                                         "coherent comparisons",
                                         "diff pixels"};
  static const char *const ds_fmt[8] = {NULL,   "%.0f", "%.2f", "%.3f",
                                        "%.3f", "%.0f", "%.0f", "%.1f"};
  static const int oc_col[5] = {0, 1, 2, 3, 4};
  static const char *const oc_head[5] = {"moving", "loose ms/frame", "plain ms/frame",
                                         "loose us/object", "plain us/object"};
  static const char *const oc_fmt[5] = {"%.0f", "%.3f", "%.3f", "%.3f", "%.3f"};
  arglist a = {0}, b = {0};
  depthsort_args(s, fs, as_shown, &a);
  octree_args(s, fs, as_shown, &b);
  if (set_command(s, "depthsort.command", "zscan bench", a.v, err) ||
      set_csv(s, "depthsort.table", fs->path[F_DEPTHSORT], 8, ds_col, ds_head, ds_fmt, err) ||
      set_command(s, "octree.command", "zscan bench", b.v, err) ||
      set_csv(s, "octree.table", fs->path[F_OCTREE_CSV], 5, oc_col, oc_head, oc_fmt, err))
    return err->code;
  return ZS_OK;
}

/* Every placeholder's value, from the files the benchmarks wrote. */
static zs_status fill_values(suite *s, const files *fs, zs_error *err) {
  if (set_text(s, "machine", s->machine, err) || set_text(s, "suite.command", s->command, err) ||
      fill_device(s, fs, err) || fill_shading(s, fs, err) || fill_walks(s, fs, err) ||
      fill_sorts(s, fs, err))
    return err->code;
  return ZS_OK;
}

/* ---- the templates and the page --------------------------------------- */

static int by_name(const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The names of the templates (*.md) found so far. */
typedef struct template_names {
  char *names[MAX_TEMPLATES];
  int n;
} template_names;

static int add_template_name(const char *name, void *ctx) {
  template_names *t = ctx;
  const size_t len = strlen(name);
  if (name[0] == '.' || len < 4 || strcmp(name + len - 3, ".md") != 0) return 0;
  if (t->n == MAX_TEMPLATES) return ZS_ERR_LIMIT;
  return (t->names[t->n++] = strdup(name)) ? 0 : ZS_ERR_NOMEM;
}

/* Reads the .md files of DIR/results/, in the order of their names. */
static zs_status read_templates(suite *s, zs_error *err) {
  char dir[PATH];
  snprintf(dir, sizeof dir, "%s/results", s->docs);
  template_names found = {{NULL}, 0};
  const int rc = zs_os_each_name(dir, add_template_name, &found);
  zs_status st = ZS_OK;
  if (rc < 0) st = zs_error_set(err, ZS_ERR_IO, "%s: cannot open: %s", dir, strerror(-rc));
  else if (rc == ZS_ERR_LIMIT)
    st = zs_error_set(err, ZS_ERR_LIMIT, "%s: more than %d templates", dir, MAX_TEMPLATES);
  else if (rc) st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  if (!st && found.n == 0) st = zs_error_set(err, ZS_ERR_IO, "%s: no templates (*.md)", dir);
  if (!st) qsort(found.names, (size_t)found.n, sizeof found.names[0], by_name);
  for (int i = 0; i < found.n; i++) {
    if (!st && found.names[i]) {
      template_file *t = &s->tmpl[s->ntmpl];
      snprintf(t->path, sizeof t->path, "%s/%s", dir, found.names[i]);
      capture c;
      if (!(st = capture_open(&c, err))) {
        st = zs_append_file(c.f, t->path, err);
        if (zs_memfile_close(&c) != 0 && !st) st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
        if (st) free(c.data);
        else t->text = c.data, s->ntmpl++;
      }
    }
    free(found.names[i]);
  }
  return st;
}

static int is_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' || c == '-' || c == '_';
}

/* Whether the suite draws the plot DIR/images/NAME (name: up to ')'). */
static int is_plot(const char *name) {
  const size_t len = strcspn(name, ")");
  for (int k = 0; k < NPLOTS; k++)
    if (strlen(plots[k].doc) == len && strncmp(plots[k].doc, name, len) == 0) return 1;
  return 0;
}

/* Whether the link whose "](" is at p, in text, is an image's: "![". */
static int is_image(const char *text, const char *p) {
  while (p > text && *p != '[' && *p != '\n') p--;
  return *p == '[' && p > text && p[-1] == '!';
}

/* Writes template t to out with each placeholder replaced by its value;
 * with out NULL, only checks it, marking in used the placeholders it
 * names. */
static zs_status expand(FILE *out, const suite *s, const template_file *t, int *used,
                        zs_error *err) {
  const char *text = t->text;
  int line = 1;
  for (const char *p = text; *p; p++) {
    if (*p == '\n') line++;
    if (!out && strncmp(p, "](images/", 9) == 0 && is_image(text, p) && !is_plot(p + 9))
      return zs_error_set(err, ZS_ERR_PARSE, "%s:%d: images/%.*s: the suite draws no such plot",
                          t->path, line, (int)strcspn(p + 9, ")\n"), p + 9);
    if (*p != '{') {
      if (out) fputc(*p, out);
      continue;
    }
    size_t len = 0;
    while (is_name_char(p[1 + len])) len++;
    if (p[1 + len] != '}' || len == 0) {
      const size_t shown = strcspn(p, "}\n");
      return zs_error_set(err, ZS_ERR_PARSE,
                          "%s:%d: malformed placeholder '%.*s' (a brace opens {name})", t->path,
                          line, (int)(shown > 40 ? 40 : shown + (p[shown] == '}')), p);
    }
    const int i = placeholder_index(p + 1, len);
    if (i < 0)
      return zs_error_set(err, ZS_ERR_PARSE, "%s:%d: unknown placeholder {%.*s}", t->path, line,
                          (int)len, p + 1);
    if (used) used[i] = 1;
    if (out && s->value[i]) fputs(s->value[i], out);
    p += len + 1;
  }
  return ZS_OK;
}

/* Checks every template before anything runs: each placeholder known,
 * each image drawn, each measurement shown. */
static zs_status check_templates(const suite *s, zs_error *err) {
  int used[NPLACEHOLDERS] = {0};
  for (int k = 0; k < s->ntmpl; k++)
    if (expand(NULL, s, &s->tmpl[k], used, err)) return err->code;
  for (int i = 0; i < NPLACEHOLDERS; i++)
    if (placeholders[i].shown && !used[i])
      return zs_error_set(err, ZS_ERR_PARSE, "%s/results: no template shows {%s}", s->docs,
                          placeholders[i].name);
  return ZS_OK;
}

/* Copies the file from into to, through the output primitive. */
static zs_status copy_file(const char *from, const char *to, zs_error *err) {
  zs_out out;
  if (zs_out_open(&out, to, err)) return err->code;
  if (zs_append_file(out.fp, from, err)) {
    zs_out_discard(&out);
    return err->code;
  }
  return zs_out_commit(&out, err);
}

/* DIR/RESULTS.md from the templates, a blank line between two; the plots
 * into DIR/images. */
static zs_status write_docs(suite *s, zs_error *err) {
  char page[PATH], images[PATH], from[PATH], to[PATH + 64];
  snprintf(images, sizeof images, "%s/images", s->docs);
  if (zs_out_dir("--docs", images, err)) return err->code;
  for (int k = 0; k < NPLOTS && s->plots; k++) {
    in_dir(from, s, plots[k].out);
    if (!zs_os_readable(from)) continue;
    snprintf(to, sizeof to, "%s/%s", images, plots[k].doc);
    if (copy_file(from, to, err)) return err->code;
  }
  snprintf(page, sizeof page, "%s/RESULTS.md", s->docs);
  zs_out out;
  if (zs_out_open(&out, page, err)) return err->code;
  for (int k = 0; k < s->ntmpl; k++) {
    if (k) fputc('\n', out.fp);
    if (expand(out.fp, s, &s->tmpl[k], NULL, err)) {
      zs_out_discard(&out);
      return err->code;
    }
  }
  if (zs_out_commit(&out, err)) return err->code;
  printf("wrote %s and its plots in %s\n", page, images);
  return ZS_OK;
}

/* ---- the command ------------------------------------------------------- */

/* The options; a usage error is ZS_ERR_ARG (exit 2). */
static zs_status parse(int argc, char **argv, suite *s, zs_error *err) {
  int w, h;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--quick") == 0) {
      s->quick = 1;
    } else if (strcmp(argv[i], "--quiet") == 0) {
      s->quiet = 1;
    } else if (strcmp(argv[i], "--no-run") == 0) {
      s->no_run = 1;
    } else if (strcmp(argv[i], "--out") == 0) {
      if (zs_cli_value(argc, argv, &i, &s->dir, err)) return err->code;
    } else if (strcmp(argv[i], "--docs") == 0) {
      if (zs_cli_value(argc, argv, &i, &s->docs, err)) return err->code;
    } else if (strcmp(argv[i], "--threads") == 0) {
      if (zs_cli_int_value(argc, argv, &i, 2, 64, &s->threads, err)) return err->code;
    } else if (strcmp(argv[i], "--size") == 0) {
      if (zs_cli_value(argc, argv, &i, &s->size, err) ||
          zs_cli_size(argv[i - 1], s->size, ZS_MAX_IMAGE_SIDE, &w, &h, err))
        return err->code;
    } else {
      return zs_error_set(err, ZS_ERR_ARG, "unknown option '%s' (see zscan bench suite --help)",
                          argv[i]);
    }
  }
  if (s->no_run && !s->docs)
    return zs_error_set(err, ZS_ERR_ARG, "--no-run: writes the page only: give --docs DIR");
  /* the page names the run that measured: without --no-run */
  char *kept[64];
  int n = 0;
  for (int i = 0; i < argc && n < 63; i++)
    if (strcmp(argv[i], "--no-run") != 0) kept[n++] = argv[i];
  kept[n] = NULL;
  join_cmd(s->command, "zscan bench", kept);
  return ZS_OK;
}

/* The folders, this program's path, and what the machine offers: the
 * machine's description, llvmpipe, valgrind, gnuplot, its CPUs.  A full
 * run for --docs needs them all. */
static zs_status probe(suite *s, zs_error *err) {
  zs_error quiet;
  zs_error_clear(&quiet);
  s->have_mesa = zs_mesa_available();
  const int valgrind = zs_callgrind_available(&quiet);
  s->plots = zs_plot_available();
  const int ncpu = zs_os_cpu_count();
  s->ncpu = ncpu > 64 ? 64 : ncpu;
  if (!s->threads) s->threads = s->ncpu < 2 ? 2 : s->ncpu;
  snprintf(s->threads_arg, sizeof s->threads_arg, "%d", s->threads);
  snprintf(s->lp_env, sizeof s->lp_env, "LP_NUM_THREADS=%d", s->threads);
  s->mesa = s->have_mesa && !s->quick;
  s->callgrind = valgrind && !s->quick;
  s->run_threads = !s->quick && s->ncpu >= 2;
  if (s->docs && !s->quick) {
    const char *lack = !s->have_mesa ? "OSMesa (the llvmpipe tables): this zscan was built without it"
                       : !valgrind   ? "valgrind (the instructions per frame)"
                       : !s->plots   ? "gnuplot (the plots)"
                       : s->ncpu < 2 ? "two CPUs (the threads' tables)"
                                     : NULL;
    if (lack) return zs_error_set(err, ZS_ERR_UNSUPPORTED, "--docs: the page needs %s", lack);
  }
  if (zs_out_dir("--out", s->dir, err)) return err->code;
  if (!zs_os_self_path(s->self, sizeof s->self))
    return zs_error_set(err, ZS_ERR_IO, "cannot find this program's path");
  describe_machine(s->machine, sizeof s->machine);
  return ZS_OK;
}

static void free_suite(suite *s) {
  for (int k = 0; k < s->ntmpl; k++) free(s->tmpl[k].text);
  for (int i = 0; i < NPLACEHOLDERS; i++) free(s->value[i]);
}

int zs_cmd_bench_suite(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, NULL)) return 0;
  static suite s; /* large: its templates' paths and command lines */
  static files fs;
  memset(&s, 0, sizeof s);
  s.dir = "bench-suite";
  zs_error err;
  zs_error_clear(&err);
  if (parse(argc, argv, &s, &err)) {
    return zs_cli_fail("zscan bench suite", &err, 1); /* a usage error exits 2 (tools/cli.h) */
  }
  int rc = 1;
  /* the templates first: a fault in one is found before the measuring,
   * not after it */
  if (s.docs && (read_templates(&s, &err) || check_templates(&s, &err))) goto fail;
  if (probe(&s, &err)) goto fail;
  for (int k = 0; k < NFILES; k++) in_dir(fs.path[k], &s, file_names[k]);
  for (int k = 0; k < 3; k++) in_dir_named(fs.shade[k], &s, "shade-%s.md", shadings[k]);
  in_dir(fs.colours, &s, "colours.md");
  in_dir(fs.lines, &s, "lines.md");
  in_dir(fs.arrays, &s, "arrays.md");
  in_dir(fs.samples, &s, "samples.md");
  for (int w = 0; w < 2; w++) {
    in_dir_named(fs.walk[w][0], &s, "walk-%s.csv", walks[w][0]);
    in_dir_named(fs.walk[w][1], &s, "walk-%s.md", walks[w][0]);
    in_dir_named(fs.walk[w][2], &s, "walk-%s.txt", walks[w][0]);
  }
  const int ran = s.no_run ? 0 : run_all(&s, &fs, &err);
  if (ran > 0) goto done; /* the benchmark said why */
  if (ran < 0) goto fail;
  if (s.plots && plot_walks(&s, &fs, &err)) goto fail;
  if (s.docs && (fill_values(&s, &fs, &err) || write_docs(&s, &err))) goto fail;
  if (!s.no_run)
    printf("\nwrote %s: raster, shading, arrays, samples, memory, calibrate, walks, tradeoff (per walk), depthsort and "
         "octree files%s%s%s\n",
         s.dir, s.mesa ? "; llvmpipe beside zscan, colours too" : "",
         s.run_threads ? ", on one thread and on N" : "",
         s.callgrind ? "; instructions per frame under callgrind" : "");
  rc = 0;
  goto done;
fail:
  rc = zs_cli_fail("zscan bench suite", &err, 0);
done:
  free_suite(&s);
  return rc;
}
