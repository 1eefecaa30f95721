/* `zscan bench suite [--out DIR] [--quick] [--size WxH] [--docs DIR]`:
 * the documented suite, one command, every file in DIR:
 *   raster.csv, .md, .png   bench raster: triangles of 4 to 500 pixels and
 *                           the whole scenes in both modes, one thread,
 *                           beside Mesa's llvmpipe on one thread when zscan
 *                           has it (--mesa), with the instructions per
 *                           frame when valgrind is there (--callgrind);
 *   raster-threads.csv, .md, .png, .txt   the same on every thread of the
 *                           machine (2 or more), zscan's speed-up over one
 *                           thread, frames in turn (--speedup), and
 *                           llvmpipe on as many threads (a child process,
 *                           as llvmpipe reads LP_NUM_THREADS when it starts);
 *   memory.md, memory.txt   what the device holds (render --stats) in
 *                           both modes at four image sizes;
 *   calibrate.txt, clock.json   zscan calibrate: the clock's constants;
 *   walk-plant.*, walk-teapots.*   zscan walk, every culling method over
 *                           every frame of the two large walks (.csv, .md,
 *                           .txt, and -every.png: a few methods' modelled
 *                           frame time along the walk);
 *   tradeoff*.csv, .md, .png  bench tradeoff: run time against error, every
 *                           method and mode on every walk (walk-plant.png
 *                           and walk-teapots.png: a few methods along two
 *                           of them);
 *   depthsort.csv           bench depthsort: the depth-sort paper's Table 1;
 *   octree.csv, .png        bench octree: loose against plain octree updates;
 *   RESULTS.md              all of the above as one page.
 * --docs DIR writes that page to DIR/RESULTS.md as well, its plots to
 * DIR/images/: `zscan bench suite --docs docs` refreshes the project's
 * docs/RESULTS.md.
 * --quick: one frame per raster case and no scenes or instruction counts,
 * the quick walks, fewer frames elsewhere: a check that it all runs. */
#include "tools/bench_suite.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <unistd.h>

#include "raster/raster.h"
#include "tools/bench_depthsort.h"
#include "tools/bench_octree.h"
#include "tools/bench_raster.h"
#include "tools/bench_tradeoff.h"
#include "tools/callgrind.h"
#include "tools/cli.h"
#include "tools/mesa.h"
#include "lib/outfile.h"
#include "tools/plot.h"
#include "tools/spawn.h"

static const char usage[] =
    "usage: zscan bench suite [--out DIR] [--quick] [--size WxH] [--docs DIR] [--quiet]\n"
    "  --out DIR   where every benchmark's files go (default bench-suite), with\n"
    "              RESULTS.md, the page of them all\n"
    "  --quick     a few frames of each: a check that it all runs\n"
    "  --size WxH  the image size of raster, tradeoff, depthsort and the walks (raster\n"
    "              needs 500x500 or more; default each one's own, 1024x768)\n"
    "  --docs DIR  also that page as DIR/RESULTS.md, its plots in DIR/images\n"
    "              (zscan bench suite --docs docs refreshes docs/RESULTS.md)\n"
    "  --quiet     no progress on stderr (else a line after each benchmark, and\n"
    "              the walks of tradeoff as bench tradeoff shows them)\n";

/* Every culling method, and the few whose lines a plot can tell apart
 * (hsw, which waits for every answer, would flatten them). */
static const char all_methods[] =
    "vfc,vfc-box,hsw,chc,chc-prob,chcpp,chcpp-nobatch,chcpp-nodefer,chcpp-nomulti,chcpp-prob,"
    "nohc,hzb,ideal-box,ideal,auto";
static const char *const plotted[] = {"vfc", "chc", "chc-prob", "chcpp", "nohc", "hzb", "ideal-box",
                                      "ideal"};
enum { NPLOTTED = sizeof plotted / sizeof plotted[0] };

/* The two large walks at every frame: name, scene, quick scene. */
static const char *const walks[2][3] = {
    {"plant", "builtin:plant,detail=1", "builtin:plant,detail=0.05"},
    {"teapots", "builtin:teapots,count=6000", "builtin:teapots,count=300"},
};
/* The walks of bench tradeoff, in its order, and their steps (full run). */
static const char *const tradeoff_walks[3] = {"teapots", "city", "plant"};

/* Memory: the default scene at four sizes, in both modes. */
static const char *const mem_sizes[2][4] = {
    {"1024x768", "4096x768", "1024x3072", "4096x3072"},
    {"256x192", "1024x192", "256x768", "1024x768"}, /* --quick */
};

/* Plots: the name in the output directory and in DIR/images of --docs. */
typedef struct plot_file {
  const char *out, *doc;
} plot_file;
static const plot_file plots[] = {
    {"raster.png", "bench-raster.png"},
    {"walk-plant-every.png", "walk-plant-every.png"},
    {"walk-teapots-every.png", "walk-teapots-every.png"},
    {"walk-teapots.png", "walk-teapots.png"},
    {"walk-plant.png", "walk-plant.png"},
    {"tradeoff-teapots.png", "tradeoff-teapots.png"},
    {"tradeoff-city.png", "tradeoff-city.png"},
    {"tradeoff-plant.png", "tradeoff-plant.png"},
    {"octree.png", "octree.png"},
};
enum { NPLOTS = sizeof plots / sizeof plots[0] };

enum { CMD = 2048, PATH = 4200 };

/* What one run of the suite did, for the page. */
typedef struct suite {
  const char *dir, *size;
  int quick, mesa, callgrind, threads; /* threads: of the second raster pass, 0: none */
  int quiet;                           /* --quiet */
  int have_mesa;                       /* built with OSMesa (mesa: and used) */
  int plots;                           /* gnuplot is there */
  char self[4096];
  char machine[512];
  char cmd_raster[CMD], cmd_threads[CMD], cmd_memory[CMD], cmd_calibrate[CMD];
  char cmd_walk[2][CMD], cmd_depthsort[CMD], cmd_octree[CMD];
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
  struct utsname u;
  const char *arch = uname(&u) == 0 ? u.machine : "unknown";
  long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
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
  snprintf(buf, cap, "%ld-core %s %s%s%s%s, %s, %s", ncpu, arch, vm ? "VM" : "machine",
           model[0] ? " (" : "", model, model[0] ? ")" : "", compiler, build);
}

/* Runs one benchmark's command with args (NULL-terminated, the command's
 * name first), its command line kept in cmd (when not NULL); returns its
 * exit status. */
static int run(int (*fn)(int, char **), char **args, char *cmd) {
  int n = 0;
  while (args[n]) n++;
  char line[CMD];
  join_cmd(line, "zscan bench", args);
  if (cmd) snprintf(cmd, CMD, "%s", line);
  printf("\n$ %s\n", line);
  fflush(stdout);
  return fn(n, args);
}

/* Runs this zscan again as a child with args (NULL-terminated, without
 * the program), its output into the file txt and then here too. */
static zs_status run_child(const suite *s, char **args, const char *txt, const char *env,
                           char *cmd, zs_error *err) {
  char *argv[48];
  int n = 0;
  argv[n++] = (char *)s->self;
  for (int i = 0; args[i] && n < 47; i++) argv[n++] = args[i];
  argv[n] = NULL;
  char prefix[96], line[CMD];
  snprintf(prefix, sizeof prefix, "%s%szscan", env ? env : "", env ? " " : "");
  join_cmd(line, prefix, args);
  if (cmd) snprintf(cmd, CMD, "%s", line);
  printf("\n$ %s\n", line);
  fflush(stdout);
  /* the child writes into a scratch file, which then reaches txt through
   * the output primitive like every other output */
  const char *tmpdir = getenv("TMPDIR");
  char scratch[PATH];
  snprintf(scratch, sizeof scratch, "%s/zscan-suite-XXXXXX", tmpdir && *tmpdir ? tmpdir : "/tmp");
  int fd = mkstemp(scratch);
  if (fd < 0) return zs_error_set(err, ZS_ERR_IO, "%s: cannot create: %s", scratch, strerror(errno));
  close(fd);
  int rc = zs_spawn_wait(argv, scratch, scratch);
  zs_out out;
  zs_status st = zs_out_open(&out, txt, err);
  if (!st && !(st = zs_append_file(out.fp, scratch, err))) st = zs_out_commit(&out, err);
  else if (!st) zs_out_discard(&out);
  if (!st) st = zs_append_file(stdout, scratch, err); /* what it printed, here too */
  unlink(scratch);
  if (rc != 0)
    return zs_error_set(err, ZS_ERR_IO, "'%s' failed (exit %d; its output: %s)", line, rc, txt);
  return st;
}

/* bench raster on n threads beside llvmpipe on n (when zscan has it), and
 * the speed-up over one thread. */
static zs_status run_threads(suite *s, zs_error *err) {
  char threads[16], csv[PATH], md[PATH], png[PATH], txt[PATH], env[64];
  snprintf(threads, sizeof threads, "%d", s->threads);
  in_dir(csv, s, "raster-threads.csv");
  in_dir(md, s, "raster-threads.md");
  in_dir(png, s, "raster-threads.png");
  in_dir(txt, s, "raster-threads.txt");
  char *args[24] = {"bench", "raster", "--threads", threads, "--speedup"};
  int k = 5;
  if (s->mesa) args[k++] = "--mesa";
  args[k++] = "--csv";
  args[k++] = csv;
  args[k++] = "--md";
  args[k++] = md;
  args[k++] = "--plot";
  args[k++] = png;
  if (s->size) {
    args[k++] = "--size";
    args[k++] = (char *)s->size;
  }
  args[k] = NULL;
  snprintf(env, sizeof env, "LP_NUM_THREADS=%s", threads);
  setenv("LP_NUM_THREADS", threads, 1);
  zs_status st = run_child(s, args, txt, s->mesa ? env : NULL, s->cmd_threads, err);
  setenv("LP_NUM_THREADS", "1", 1);
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
static zs_status run_memory(suite *s, zs_error *err) {
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
      zs_status st = run_child(s, args, txt, NULL, NULL, err);
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
  snprintf(s->cmd_memory, CMD, "zscan render --algo MODE --size SIZE --stats");
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
static zs_status run_walk(suite *s, int w, zs_error *err) {
  char csv[PATH], md[PATH], txt[PATH];
  in_dir_named(csv, s, "walk-%s.csv", walks[w][0]);
  in_dir_named(md, s, "walk-%s.md", walks[w][0]);
  in_dir_named(txt, s, "walk-%s.txt", walks[w][0]);
  char *args[24] = {"walk", (char *)walks[w][s->quick ? 2 : 1], "--cull", (char *)all_methods};
  int k = 4;
  if (s->quick) {
    args[k++] = "--frames";
    args[k++] = "4";
  }
  if (s->size) {
    args[k++] = "--size";
    args[k++] = (char *)s->size;
  }
  const int shown = k; /* the page shows the command without its files */
  args[k++] = "--csv";
  args[k++] = csv;
  args[k++] = "--md";
  args[k++] = md;
  args[k++] = "--quiet";
  args[k] = NULL;
  zs_status st = run_child(s, args, txt, NULL, NULL, err);
  args[shown] = NULL;
  join_cmd(s->cmd_walk[w], "zscan", args);
  return st;
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

/* ---- the page ------------------------------------------------------- */

/* Copies block k (0 from the top) of the Markdown tables in path: blocks
 * of consecutive lines that begin with '|'. */
static zs_status append_table(FILE *out, const char *path, int k, zs_error *err) {
  FILE *f = fopen(path, "r");
  if (!f) return zs_error_set(err, ZS_ERR_IO, "%s: cannot open", path);
  char line[8192];
  int block = -1, in = 0, copied = 0;
  while (fgets(line, sizeof line, f)) {
    const int row = line[0] == '|';
    if (row && !in) block++;
    in = row;
    if (row && block == k) {
      fputs(line, out);
      copied++;
    }
  }
  fclose(f);
  return copied ? ZS_OK : zs_error_set(err, ZS_ERR_IO, "%s: no table %d", path, k + 1);
}

/* The lines of the text file path from the first that begins with from,
 * up to the first blank line or "wrote " line after it. */
static zs_status append_lines(FILE *out, const char *path, const char *from, zs_error *err) {
  FILE *f = fopen(path, "r");
  if (!f) return zs_error_set(err, ZS_ERR_IO, "%s: cannot open", path);
  char line[8192];
  int on = 0, copied = 0;
  while (fgets(line, sizeof line, f)) {
    if (!on && strncmp(line, from, strlen(from)) == 0) on = 1;
    if (on && copied && (line[0] == '\n' || strncmp(line, "wrote ", 6) == 0)) break;
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

/* The image line of plot k, when the plot was made. */
static void image(FILE *f, const suite *s, int k, const char *alt, int docs) {
  char path[PATH];
  in_dir(path, s, plots[k].out);
  if (!s->plots || access(path, R_OK) != 0) return;
  fprintf(f, "\n![%s](%s%s)\n", alt, docs ? "images/" : "", docs ? plots[k].doc : plots[k].out);
}

static void command(FILE *f, const suite *s, const char *cmd) {
  fprintf(f, "\nOn the %s:\n\n```\n$ %s\n```\n\n", s->machine, cmd);
}

/* The command, then table k of the output directory's file name. */
static zs_status command_table(FILE *f, const suite *s, const char *cmd, const char *name, int k,
                               zs_error *err) {
  char path[PATH];
  in_dir(path, s, name);
  command(f, s, cmd);
  return append_table(f, path, k, err);
}

/* The page's title, how to read it, and its contents. */
static void page_head(FILE *f, const suite *s) {
  fprintf(f,
          "# Results\n\n"
          "Every table on this page names the command that produced it and the\n"
          "machine it ran on. `zscan bench suite --docs docs` runs them all again\n"
          "and rewrites this page and its plots (its other files go to\n"
          "`bench-suite/`); `zscan bench suite --quick` checks in seconds that\n"
          "everything runs, with figures not worth quoting.\n\n"
          "%s"
          "How to read the figures. Counts (triangles, pixels, queries, faces\n"
          "drawn, pixels wrong) and modelled times (the device clock,\n"
          "`raster/clock.c`) are exact: every run on every machine gives the same.\n"
          "Instruction counts (valgrind's callgrind) repeat to a few in a million.\n"
          "Wall times are the machine's and move between runs by 10 %% or more on\n"
          "a shared virtual machine: read them as faster or slower, compare the\n"
          "figures of one table (one run) rather than across tables, and prefer\n"
          "the instruction counts. The figures of each table come from one run.\n\n"
          "- [Raster throughput](#raster-throughput)\n"
          "- [Against Mesa's llvmpipe](#against-mesas-llvmpipe)\n"
          "- [Threads: the speed-up and its ceiling](#threads-the-speed-up-and-its-ceiling)\n"
          "- [Memory](#memory)\n"
          "- [The device clock, calibrated](#the-device-clock-calibrated)\n"
          "- [Culling walks, every frame](#culling-walks-every-frame)\n"
          "- [Run time against error](#run-time-against-error)\n"
          "- [Depth sort with frame coherence](#depth-sort-with-frame-coherence)\n"
          "- [Loose against plain octree](#loose-against-plain-octree)\n"
          "- [Things that did not pay](#things-that-did-not-pay)\n",
          s->quick ? "**These figures are from `--quick`: a check that the suite runs, "
                     "not figures to quote.**\n\n"
                   : "");
}

/* The prose of the page's sections: each begins with its heading. */
static const char prose_raster[] =
          "\n## Raster throughput\n\n"
          "Screens tiled with triangles (the two halves of S x S pixel squares) in\n"
          "layers drawn back to front, so that every pixel of every layer is tested\n"
          "and written, and four whole scenes from their own cameras; one thread,\n"
          "both hidden-surface modes, the median frame. The instructions per frame\n"
          "come from valgrind's callgrind: each case and mode runs alone for 1 and\n"
          "for 3 frames, and half the difference is one frame. Spans of 10 pixels\n"
          "or more are filled with AVX-512 (`--simd` caps the level; every level\n"
          "gives the same pixels).\n";
static const char prose_llvmpipe[] =
          "\n## Against Mesa's llvmpipe\n\n"
          "The same cases drawn through Mesa's llvmpipe (OSMesa) with the same\n"
          "matrices: vertex arrays, each face fanned into triangles, one colour per\n"
          "object, a \"less\" depth test; frames taken in turn with zscan's zbuffer\n"
          "mode, so that both see the same machine. A ratio under 1: zscan is faster.\n"
          "The last three columns compare the face each renderer shows at every\n"
          "pixel. A differing pixel is a depth tie when both renderers cover it with\n"
          "both faces and differ only in which is nearer, below the resolution of\n"
          "llvmpipe's 24-bit depth buffer (`tools/crosscheck.c`); everything else\n"
          "counts as coverage. `tests/test_mesa.c` bounds the coverage differences\n"
          "at 1 in 10,000 pixels.\n\n### One thread each\n";
static const char prose_speedup[] =
          "\n## Threads: the speed-up and its ceiling\n\n"
          "A whole scene on N threads is drawn deferred: set up in chunks, walked in\n"
          "bands of rows, with the same bytes and counters as on one thread.\n"
          "`--speedup` renders each scene on one thread and on N frame by frame in\n"
          "turn and reports the pairs' ratios; then one single-thread device per\n"
          "CPU, all at once, each pinned to its CPU (Linux): with t_one the\n"
          "one-thread frame and t_i each CPU's, the ceiling t_one x sum(1 / t_i) is\n"
          "what a perfect split would give in that round, the CPUs' interference\n"
          "with each other included (two virtual CPUs are not always equal).\n";
static const char prose_memory[] =
          "\n## Memory\n\n"
          "What the device holds, from `zscan render --stats`: `buffer_bytes`\n"
          "(the pixel buffers) and `table_bytes` (the polygon and edge tables and\n"
          "the walk's scratch), in bytes, for the default scene. Scanline mode\n"
          "keeps rows: its buffers grow with the width, not the area; its tables\n"
          "hold the whole frame's polygons, zbuffer mode's one draw's.\n";
static const char prose_calibrate[] =
          "\n## The device clock, calibrated\n\n"
          "The clock models each command's GPU time from counts (calls, vertices,\n"
          "polygons, spans, pixels tested and written, query pixels). `zscan\n"
          "calibrate` times synthetic workloads, each dominated by one count, and\n"
          "whole scenes on zscan's own raster code, fits the constants by least\n"
          "squares on relative error, and prints each workload's measured time\n"
          "against the model's. The culling walks below use the default clock,\n"
          "which describes a GPU, not these constants.\n";
static const char prose_walks[] =
          "\n## Culling walks, every frame\n\n"
          "`zscan walk` runs every method in lockstep over the scene's camera path,\n"
          "each on its own device with the default clock, and compares every frame\n"
          "with drawing everything (none). Figures are per frame on average; `x\n"
          "ideal` is the modelled time over the ideal's; pixels wrong are summed\n"
          "over all frames. The oracles' wall time includes the full render they\n"
          "make, which their modelled time does not see. Every column and method:\n"
          "[CULLING.md](CULLING.md#reading-a-walk). Below each table: how\n"
          "ideal-box's set changes from frame to frame, and the least that change\n"
          "costs a method that learns visibility from the last frame.\n";
static const char prose_walk_plots[] =
    "\nModelled frame time along the two walks, a few methods (hsw, which\n"
    "waits for every answer, left out: it would flatten the others):\n";
static const char prose_tradeoff[] =
          "\n## Run time against error\n\n"
          "`zscan bench tradeoff` walks the teapots, the city and the plant at every\n"
          "10th, 8th and 8th frame with every method and, beside the z-buffer, the\n"
          "scanline and depth-sort modes, which draw everything. Pixels wrong are\n"
          "counted against none in zbuffer mode: scanline mode draws its image\n"
          "exactly, depth sort and vfc-box do not. Each plot puts every method and\n"
          "mode at its pixels wrong per frame against its median wall time (left)\n"
          "and its modelled time (right).\n";
static const char prose_tradeoff_plots[] =
    "\nModelled frame time along the teapots and plant walks above, a few\n"
    "methods:\n";
static const char prose_depthsort[] =
          "\n## Depth sort with frame coherence\n\n"
          "The depth-sort paper's Table 1 on the city at street level. The sorter\n"
          "tells the camera's motion between two frames from the view matrices:\n"
          "`translate` moves sideways, `roll` turns about the view axis, `yaw` turns\n"
          "slowly, `fast` moves far enough that most faces are new. Reused: faces\n"
          "kept from the last frame's order. Times are medians of the frames after\n"
          "the first; comparisons are exact; diff pixels are the pixels a frame\n"
          "that differ from the z-buffer's image.\n";
static const char prose_octree[] =
          "\n## Loose against plain octree\n\n"
          "The cost-model paper's experiment 1: spheres of 576 faces moving in a\n"
          "1,000-unit cube, the time to update each tree per frame (median). The\n"
          "loose octree places an object in constant time, its level from its\n"
          "radius and its cell from its centre; the plain one deletes, descends\n"
          "from the root and inserts.\n";
static const char prose_not_paid[] =
          "\n## Things that did not pay\n\n"
          "Tried, measured, and not kept (the measurements are in the history of\n"
          "the code that was dropped):\n\n"
          "- Filling spans under 16 pixels with AVX2: masked stores for the last\n"
          "  pixels are slow on AMD CPUs, and full-width stores that write back what\n"
          "  lies past the span were no faster than the scalar loop.\n"
          "- SSE2 from 8 pixels instead of 16: more instructions a triangle.\n"
          "- AVX-512 for every span, or from 8 pixels: slower on meshes, as a\n"
          "  masked load of a row's next span cannot take its bytes from the masked\n"
          "  store of the span before it, which neighbouring faces of a mesh always\n"
          "  have (the plant 8 % slower from 1 pixel, the 10x10 tiling 3 % from\n"
          "  8); it takes spans from 10 pixels.\n"
          "- A branchless scalar span loop: where every pixel tested is written the\n"
          "  branch is always predicted, and the selects only add loads.\n"
          "- Unrolling the scalar span loop, indexing it from the span's end, writing\n"
          "  a polygon's edges through a local pointer: more instructions (the walk\n"
          "  has no register to spare).\n"
          "- Painting a polygon at a time in zbuffer mode: fewer instructions, but\n"
          "  slower, as a polygon's rows stride across pages where the walk's stream.\n"
          "- The edge step as a subtraction whose borrow is the carry (inline\n"
          "  assembly): fewer instructions, no faster.\n"
          "- A branch-free depth test: slower.\n"
          "- For the deferred walk on threads: more or fewer bands or chunks a\n"
          "  thread, more batches, balancing bands by polygons, the heaviest band\n"
          "  first, walking a task's bands in one pass, insertion sort for the\n"
          "  polygons begun above a band, per-worker vertex scratch, and the sorted\n"
          "  polygon table as an array sorted once a draw: none faster, several\n"
          "  slower.\n"
          "- The scanline mode on threads in rounds of bands, four a thread: each\n"
          "  band sorts the whole frame's batch into its rows' buckets, so on the\n"
          "  plant, two threads, eight bands in four rounds gave 1.41x one thread's\n"
          "  speed and four bands in two rounds 1.31x, where one band a thread gives\n"
          "  1.75x (`zscan bench raster --case builtin:plant --algo scanline\n"
          "  --threads 2 --speedup --repeat 21`).\n"
          "- hzb's box test at the classic level alone (the box's nearest corner\n"
          "  against the farthest texels over its rectangle, at most 3x3 texels):\n"
          "  on the first 40 frames of the plant at 512x384 it draws 541 objects a\n"
          "  frame, against 291 with the fine stage (each texel, up to 17x17,\n"
          "  against the faces that reach it) and 358 reading every pixel of the\n"
          "  rectangle with the classic test; the ideal draws 144 (`zscan walk\n"
          "  builtin:plant --cull hzb,ideal --frames 40 --size 512x384`).\n"
          "- Painting every batch of the z-buffer mode a polygon at a time: the\n"
          "  tilings slower (25x25 80.6 ms a frame against 60.3 walked, 4x4 116\n"
          "  against 104), as each polygon's rows are fetched a row apart where the\n"
          "  walk streams them; so a mesh laid out in order over a quarter of the\n"
          "  frame or more is still walked. Walking each bucket of the sorted table\n"
          "  with an active list of its own instead of painting: random 10x10\n"
          "  triangles 72 ms against 64 painted, the tilings as walked (`zscan\n"
          "  bench raster --algo zbuffer`, the variants in turn).\n"
          "- Inlining set-up's polygon emit into each face shape (triangle, quad)\n"
          "  by force: more instructions, not fewer (the 4x4 tiling, 1,639.4 M a\n"
          "  frame against 1,613.5 M where gcc chooses: `zscan bench raster --case\n"
          "  \"triangles 4x4\" --algo zbuffer --callgrind`).\n"
          "  A triangle's two chains written with no branch on its shape (each of\n"
          "  its three edges stored where it goes either way, an edge between two\n"
          "  rows of centres overwritten or left past the polygon's): slower, the\n"
          "  4x4 tiling 106.5 -> 116.3 ms a frame, random 10x10 back to front 56.8\n"
          "  -> 59.3, the teapots 45.0 -> 47.2 (medians of 6 rounds in turn,\n"
          "  `zscan bench raster --algo zbuffer --case C --repeat 9`).\n"
          "- Balancing the scanline mode's two bands by the last frame's modelled\n"
          "  work: on the plant the two bands already took the same time (5.2 and\n"
          "  5.1 ms a frame, measured inside the walk), where their counters, priced\n"
          "  by the device clock, differ (0.54 and 0.92 ms), so that split would\n"
          "  have unbalanced them. What the bands lost was clearing a band's buffers\n"
          "  at once before walking them, now done a row at a time as the walk\n"
          "  reaches it (1.70x -> 1.75x).\n"
          "- Leaving out of the tables, at set-up, a polygon whose box holds at most\n"
          "  four pixel centres and that covers none of them (an exact half-plane\n"
          "  test of each): the teapot field as fast (31.6 against 31.6 ms a frame)\n"
          "  and the teapots 5 % slower (48.9 against 46.7): the test cost what the\n"
          "  painter saved.\n"
          "- The depth planes of a run of 64 faces at once, eight in the lanes of\n"
          "  a vector with AVX-512 (as the flat levels are), each polygon given\n"
          "  its plane in a second pass: slower, the 4x4 tiling 97.3 -> 100.0 ms a\n"
          "  frame, the teapots 41.8 -> 42.8, the plant 18.0 -> 18.6 (medians of\n"
          "  12, 10 and 8 rounds in turn, `zscan bench raster --algo zbuffer --case\n"
          "  C --repeat 9`): the run's stores and the second pass over the\n"
          "  polygons cost more than the chain of divisions they hid.\n"
          "  Measured again with all of set-up's work before a polygon's records\n"
          "  in the lanes (eight triangles or quads at once: their corners\n"
          "  gathered, the area, the box, the tests for faces turned away, off the\n"
          "  window or between pixel centres, the fan triangle, the plane and the\n"
          "  convexity), each face then written in order: slower, the 4x4 tiling\n"
          "  94.4 -> 105.1 ms a frame, random 10x10 back to front 52.0 -> 55.1,\n"
          "  the teapots 44.7 -> 47.0 (medians of 4, 4 and 6 rounds in turn).\n"
          "  Under perf the lanes took 15 % of the 4x4 tiling's frame, about what\n"
          "  the same work had taken a face at a time (set-up was 42 %, of which\n"
          "  18 % writes the polygon and its edges and 10 % is the flat normal),\n"
          "  most of it waiting on the gathers; the corners read a face at a time\n"
          "  instead, and the records' writer inlined, the 4x4 tiling still took\n"
          "  1.10 and 1.15 of the time.\n"
          "- A branch-free floor division in the edge DDA (truncate, then correct\n"
          "  where the quotient was rounded up): slower, the teapots 42.4 -> 43.9 ms\n"
          "  and the plant 17.7 -> 18.3 (`zscan bench raster --case C`, the two in\n"
          "  turn). The form now in the code, one division and the quotient less\n"
          "  one where the remainder is negative, measured faster: the teapots 41.7\n"
          "  -> 40.2 ms and the plant 19.3 -> 18.7 (medians of 16 and 12 rounds in\n"
          "  turn, `zscan bench raster --algo zbuffer --case C --repeat 9`).\n"
          "  Two ways round the DDA's division, both slower (medians of 6 rounds\n"
          "  in turn, the same command): its quotient from a division in double\n"
          "  precision, truncated and corrected the same way (exact, as the\n"
          "  numerator has under 53 bits): the teapots 41.5 -> 42.5 ms, random\n"
          "  10x10 back to front 52.4 -> 55.8; and, for an edge whose ends span at\n"
          "  most four pixel centres, its first column as the first of those\n"
          "  centres plus the number of them left of the edge: the teapots 43.9 ->\n"
          "  44.4, random 10x10 back to front 65.5 -> 79.7.\n"
          "- Painting every small polygon of a soup by its edge functions, with no\n"
          "  limit on its rows: the random 10x10 triangles a tenth slower (55.3\n"
          "  against 61.0 ms a frame), where 8 rows at most leaves them as fast and\n"
          "  takes the 4x4 ones a sixth faster; measured again with the edges'\n"
          "  lanes in registers, 12 rows at most 56.9 -> 58.9 ms and 16 rows 61.1;\n"
          "  and again with its rows' pointers stepped, not read through the\n"
          "  target after each store, and an inner polygon's depths not clamped:\n"
          "  at 8 rows as fast (random 4x4 back to front 0.99 of the time, random\n"
          "  10x10 1.01, 10 rounds in turn), at 16 rows random 10x10 1.02 (6).\n"
          "  And a mesh's small polygons so (the span from the mask of centres\n"
          "  inside, filled by the span kernel): the teapots 43.9 -> 47.2 ms, the\n"
          "  teapot field 27.7 -> 29.7 (`zscan bench raster --algo zbuffer --case C\n"
          "  --repeat 15`, the builds in turn); measured again with a face's whole\n"
          "  box of up to sixteen centres (4x4, 8x2, 2x8 or 16x1) in one vector,\n"
          "  its rows' spans read from the mask, no division: the teapots 1.04 to\n"
          "  1.08 of the time (8 and 10 rounds in turn).\n"
          "- A soup's polygons past the small painter filled without a call a row\n"
          "  (the DDA's spans in AVX-512 steps inline, the lanes' depth offsets,\n"
          "  colour and id set once a polygon): random 10x10 back to front 55.2 ->\n"
          "  53.4 ms a frame, but random 25x25 29.7 -> 30.9 and random 4x4 33.0 ->\n"
          "  34.7 (medians of 6 to 8 rounds in turn, `zscan bench raster --algo\n"
          "  zbuffer --case C --repeat 9`).\n"
          "- Beginning the next polygon's edges (their DDA's divisions) before\n"
          "  painting the rows of the one before, so that the divisions run beside\n"
          "  those rows: slower, the teapots 41.2 -> 44.5 ms a frame and random\n"
          "  10x10 back to front 55.4 -> 56.4 (medians of 8 rounds in turn, `zscan\n"
          "  bench raster --algo zbuffer --case C --repeat 9`): the polygon begun\n"
          "  ahead is copied through memory, where begun in place its edges stay\n"
          "  in registers.\n"
          "- Painting a soup in bands of rows, each band's polygons in the\n"
          "  table's order (those begun above it first), each polygon's rows\n"
          "  painted in every band they reach: no faster, as the table's order\n"
          "  already keeps the pixels a soup touches within a polygon's height of\n"
          "  the row it has reached: random 10x10 back to front 1.10 of the time\n"
          "  in bands of 32 rows, 0.99 in bands of 128 (medians of 4 rounds in\n"
          "  turn, `zscan bench raster --algo zbuffer --case C --repeat 9`).\n"
          "- Fetching ahead the pixels a polygon will test (its column's depth, id\n"
          "  and colour on each row), 4, 8 or 16 polygons ahead: none faster, some\n"
          "  runs far slower (random 10x10 back to front 62 ms against 64 to 90).\n"
          "- The frame buffers in huge pages (madvise): as fast (random 10x10 back\n"
          "  to front 61.4, 60.7, 61.5 against 62.1, 61.4, 61.0 ms); and every\n"
          "  block malloc gives, the tables' too\n"
          "  (`GLIBC_TUNABLES=glibc.malloc.hugetlb=1`, 45 MB of huge pages in\n"
          "  use): random 4x4 back to front as fast (31.8 to 33.4 ms against 31.5\n"
          "  to 32.2, 3 rounds in turn). Nor do the\n"
          "  pixels' loads hold that case up: a build that neither loads nor stores\n"
          "  a pixel (for timing only) takes 43 ms against 56, so three quarters of\n"
          "  its frame is set-up and each polygon's own work; 10 M triangles a second\n"
          "  would need set-up and painting across polygons in vectors.\n"
          "- Flat shading before set-up, so that set-up's work hides its root and\n"
          "  division: slower (the teapots 43.4 -> 44.2 ms, the plant 17.6 -> 19.0).\n"
          "- The three frame buffers in one block, each a third of a page further\n"
          "  into its page than the one before, so that a pixel's depth, id and\n"
          "  colour no longer share a set of the L1 cache (apart, each buffer\n"
          "  starts at the same place in its page, and at 1024 pixels a row is a\n"
          "  page): random 10x10 back to front 0.96 of the time, but random 4x4\n"
          "  1.09 back to front and 1.07 front to back (8 rounds in turn each).\n"
          "  Rows padded so that a row is not a whole page, tried as a wider image\n"
          "  (1040 against 1024 pixels, the same binary, 6 rounds in turn): random\n"
          "  10x10 back to front 0.97, random 4x4 1.05, random 25x25 within noise;\n"
          "  not made.\n"
          "- Fetching the table's records ahead for a soup only, leaving a mesh's\n"
          "  to the caches' own prefetch: the teapots 0.98 of the time, but the\n"
          "  teapot field 1.06 (`builtin:default?level=42`, 29.9 -> 31.6 ms, the\n"
          "  medians of 10 rounds in turn, `zscan bench raster --algo zbuffer\n"
          "  --case C --repeat 9`): its draws are a thousand specks each, whose\n"
          "  records the fetch ahead still finds.\n"
          "- The AVX-512 span kernel forced inline into the painter's copy under gcc\n"
          "  (paint.c built for AVX-512 throughout): the random 4x4 triangles 0.98\n"
          "  of the time before, whole process, within the noise.\n"
          "- Split sort and natural merge sort for depth sort under slow yaw on the\n"
          "  large city: more comparisons than the insertion sort.\n"
          "- Learning w1 and w2 of the cost model from a walk's own queries\n"
          "  (`--cost-set learn=K`) as the default: slower on both large walks.\n";

/* Raster throughput: the table. */
static zs_status page_raster(FILE *f, const suite *s, int docs, zs_error *err) {
  (void)docs;
  return command_table(f, s, s->cmd_raster, "raster.md", 0, err);
}

/* zscan against llvmpipe, on one thread and on all. */
static zs_status page_llvmpipe(FILE *f, const suite *s, int docs, zs_error *err) {
  (void)docs;
  if (s->mesa) {
    if (command_table(f, s, s->cmd_raster, "raster.md", 1, err)) return err->code;
  } else {
    fprintf(f, "\nNot measured: %s.\n",
            s->have_mesa ? "--quick" : "this zscan was built without OSMesa");
  }
  fprintf(f, "\n### Every thread of the machine, each\n");
  if (s->mesa && s->threads)
    return command_table(f, s, s->cmd_threads, "raster-threads.md", 1, err);
  fprintf(f, "\nNot measured: %s.\n",
          !s->have_mesa ? "this zscan was built without OSMesa"
          : s->quick    ? "--quick"
                        : "the machine has one thread");
  return ZS_OK;
}

/* zscan on every thread against one. */
static zs_status page_speedup(FILE *f, const suite *s, int docs, zs_error *err) {
  (void)docs;
  if (s->threads)
    return command_table(f, s, s->cmd_threads, "raster-threads.md", s->mesa ? 2 : 1, err);
  fprintf(f, "\nNot measured: %s.\n", s->quick ? "--quick" : "the machine has one thread");
  return ZS_OK;
}

/* What the device holds. */
static zs_status page_memory(FILE *f, const suite *s, int docs, zs_error *err) {
  (void)docs;
  return command_table(f, s, s->cmd_memory, "memory.md", 0, err);
}

/* The clock's constants, as zscan calibrate fitted them. */
static zs_status page_calibrate(FILE *f, const suite *s, int docs, zs_error *err) {
  (void)docs;
  char p[PATH];
  in_dir(p, s, "calibrate.txt");
  command(f, s, s->cmd_calibrate);
  fputs("```\n", f);
  zs_status st = append_lines(f, p, "workload", err);
  fputs("```\n", f);
  return st;
}

/* The two large walks at every frame. */
static zs_status page_walks(FILE *f, const suite *s, int docs, zs_error *err) {
  (void)docs;
  for (int w = 0; w < 2; w++) {
    char p[PATH], q[PATH], extent[256];
    in_dir_named(p, s, "walk-%s.txt", walks[w][0]);
    in_dir_named(q, s, "walk-%s.md", walks[w][0]);
    walk_extent(p, extent, sizeof extent);
    fprintf(f, "\n### `%s`, every frame (%s)\n", walks[w][s->quick ? 2 : 1], extent);
    command(f, s, s->cmd_walk[w]);
    if (append_table(f, q, 0, err)) return err->code;
    fputs("\n```\n", f);
    zs_status st = append_lines(f, p, "ideal-box's set", err);
    fputs("```\n", f);
    if (st) return st;
  }
  return ZS_OK;
}

/* bench tradeoff's walks: a table and a plot each. */
static zs_status page_tradeoff(FILE *f, const suite *s, int docs, zs_error *err) {
  for (int w = 0; w < 3; w++) {
    char cmd[CMD], name[64];
    tradeoff_cmd(s, w, cmd);
    snprintf(name, sizeof name, "tradeoff-%s.md", tradeoff_walks[w]);
    char scene[256], every[64];
    walk_of(cmd, scene, sizeof scene, every, sizeof every);
    fprintf(f, "\n### `%s`, %s\n", scene, every);
    if (command_table(f, s, cmd, name, 0, err)) return err->code;
    char alt[96];
    snprintf(alt, sizeof alt, "run time against error: %s", tradeoff_walks[w]);
    image(f, s, 5 + w, alt, docs);
  }
  return ZS_OK;
}

/* bench depthsort's table: the depth-sort paper's Table 1. */
static zs_status page_depthsort(FILE *f, const suite *s, int docs, zs_error *err) {
  (void)docs;
  char p[PATH];
  in_dir(p, s, "depthsort.csv");
  command(f, s, s->cmd_depthsort);
  static const int col[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  static const char *const head[8] = {"motion",
                                      "faces",
                                      "reused %",
                                      "full sort ms",
                                      "coherent sort ms",
                                      "full comparisons",
                                      "coherent comparisons",
                                      "diff pixels"};
  static const char *const fmt[8] = {NULL, "%.0f", "%.2f", "%.3f", "%.3f", "%.0f", "%.0f", "%.1f"};
  return csv_table(f, p, 8, col, head, fmt, err);
}

/* bench octree's table. */
static zs_status page_octree(FILE *f, const suite *s, int docs, zs_error *err) {
  char p[PATH];
  in_dir(p, s, "octree.csv");
  command(f, s, s->cmd_octree);
  static const int col[5] = {0, 1, 2, 3, 4};
  static const char *const head[5] = {"moving", "loose ms/frame", "plain ms/frame",
                                      "loose us/object", "plain us/object"};
  static const char *const fmt[5] = {"%.0f", "%.3f", "%.3f", "%.3f", "%.3f"};
  (void)docs;
  return csv_table(f, p, 5, col, head, fmt, err);
}

/* The page's sections in turn: the prose, then what the benchmark wrote
 * (none: the prose alone), then up to two plots (none: NULL). */
typedef zs_status (*section_body)(FILE *f, const suite *s, int docs, zs_error *err);
static const struct {
  const char *prose;
  section_body body;
  int plot[2];
  const char *alt[2];
} sections[] = {
    {prose_raster, page_raster, {0, 0}, {"raster throughput against triangle size", NULL}},
    {prose_llvmpipe, page_llvmpipe, {0, 0}, {NULL, NULL}},
    {prose_speedup, page_speedup, {0, 0}, {NULL, NULL}},
    {prose_memory, page_memory, {0, 0}, {NULL, NULL}},
    {prose_calibrate, page_calibrate, {0, 0}, {NULL, NULL}},
    {prose_walks, page_walks, {0, 0}, {NULL, NULL}},
    {prose_walk_plots, NULL, {2, 1}, {"the teapots walk, every frame", "the plant walk, every frame"}},
    {prose_tradeoff, page_tradeoff, {0, 0}, {NULL, NULL}},
    {prose_tradeoff_plots, NULL, {3, 4},
     {"the teapots walk, every 10th frame", "the plant walk, every 8th frame"}},
    {prose_depthsort, page_depthsort, {0, 0}, {NULL, NULL}},
    {prose_octree, page_octree, {8, 0}, {"loose against plain octree updates", NULL}},
    {prose_not_paid, NULL, {0, 0}, {NULL, NULL}},
};

static zs_status write_page(const suite *s, const char *path, int docs, zs_error *err) {
  zs_out out;
  if (zs_out_open(&out, path, err)) return err->code;
  FILE *f = out.fp;
  page_head(f, s);
  for (size_t k = 0; k < sizeof sections / sizeof sections[0]; k++) {
    fputs(sections[k].prose, f);
    if (sections[k].body && sections[k].body(f, s, docs, err)) {
      zs_out_discard(&out);
      return err->code;
    }
    for (int i = 0; i < 2 && sections[k].alt[i]; i++)
      image(f, s, sections[k].plot[i], sections[k].alt[i], docs);
  }
  return zs_out_commit(&out, err);
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

static zs_status write_docs(const suite *s, const char *docs, zs_error *err) {
  char page[PATH], images[PATH], from[PATH], to[PATH + 64];
  snprintf(images, sizeof images, "%s/images", docs);
  if (zs_out_dir("--docs", images, err)) return err->code;
  for (int k = 0; k < NPLOTS && s->plots; k++) {
    in_dir(from, s, plots[k].out);
    if (access(from, R_OK) != 0) continue;
    snprintf(to, sizeof to, "%s/%s", images, plots[k].doc);
    if (copy_file(from, to, err)) return err->code;
  }
  snprintf(page, sizeof page, "%s/RESULTS.md", docs);
  if (write_page(s, page, 1, err)) return err->code;
  printf("wrote %s and its plots in %s\n", page, images);
  return ZS_OK;
}

/* The options; a usage error is ZS_ERR_ARG (exit 2). */
static zs_status parse(int argc, char **argv, suite *s, const char **docs, zs_error *err) {
  int w, h;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--quick") == 0) {
      s->quick = 1;
    } else if (strcmp(argv[i], "--quiet") == 0) {
      s->quiet = 1;
    } else if (strcmp(argv[i], "--out") == 0) {
      if (zs_cli_value(argc, argv, &i, &s->dir, err)) return err->code;
    } else if (strcmp(argv[i], "--docs") == 0) {
      if (zs_cli_value(argc, argv, &i, docs, err)) return err->code;
    } else if (strcmp(argv[i], "--size") == 0) {
      if (zs_cli_value(argc, argv, &i, &s->size, err) ||
          zs_cli_size(argv[i - 1], s->size, ZS_MAX_IMAGE_SIDE, &w, &h, err))
        return err->code;
    } else {
      return zs_error_set(err, ZS_ERR_ARG, "unknown option '%s' (see zscan bench suite --help)",
                          argv[i]);
    }
  }
  return ZS_OK;
}

/* The folders, this program's path, and what the machine offers: the
 * machine's description, llvmpipe, valgrind, gnuplot, its threads. */
static zs_status probe(suite *s, const char *docs, zs_error *err) {
  if (zs_out_dir("--out", s->dir, err)) return err->code;
  if (docs && zs_out_dir("--docs", docs, err)) return err->code;
  if (!zs_self_path(s->self, sizeof s->self))
    return zs_error_set(err, ZS_ERR_IO, "cannot find this program's path");
  describe_machine(s->machine, sizeof s->machine);
  zs_error probe;
  zs_error_clear(&probe);
  s->have_mesa = zs_mesa_available();
  s->mesa = s->have_mesa && !s->quick;
  s->callgrind = !s->quick && zs_callgrind_available(&probe);
  s->plots = zs_plot_available();
  long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
  s->threads = !s->quick && ncpu >= 2 ? (int)(ncpu > 64 ? 64 : ncpu) : 0;
  return ZS_OK;
}

/* The files of the benchmarks run in this process, and their arguments. */
enum { F_RASTER_CSV, F_RASTER_MD, F_RASTER_PNG, F_DEPTHSORT, F_OCTREE_CSV, F_OCTREE_PNG,
       F_CALIBRATE, F_CLOCK, NFILES };
typedef struct bench_args {
  char path[NFILES][PATH];
  char *raster[20], *tradeoff[8], *depthsort[8], *octree[10], *calibrate[6];
} bench_args;

static void bench_arguments(const suite *s, bench_args *b) {
  static const char *const names[NFILES] = {"raster.csv",    "raster.md",  "raster.png",
                                            "depthsort.csv", "octree.csv", "octree.png",
                                            "calibrate.txt", "clock.json"};
  for (int k = 0; k < NFILES; k++) in_dir(b->path[k], s, names[k]);
  char **raster = b->raster;
  int n = 0;
  raster[n++] = "raster";
  raster[n++] = "--csv";
  raster[n++] = b->path[F_RASTER_CSV];
  raster[n++] = "--md";
  raster[n++] = b->path[F_RASTER_MD];
  raster[n++] = "--plot";
  raster[n++] = b->path[F_RASTER_PNG];
  if (s->mesa) raster[n++] = "--mesa";
  if (s->callgrind) raster[n++] = "--callgrind";
  if (s->quick) {
    raster[n++] = "--repeat";
    raster[n++] = "1";
    raster[n++] = "--no-scenes";
  }
  if (s->size) {
    raster[n++] = "--size";
    raster[n++] = (char *)s->size;
  }
  raster[n] = NULL;
  char **tradeoff = b->tradeoff, **depthsort = b->depthsort;
  int nt = 0, nd = 0;
  tradeoff[nt++] = "tradeoff";
  tradeoff[nt++] = "--out";
  tradeoff[nt++] = (char *)s->dir;
  if (s->quick) tradeoff[nt++] = "--quick";
  if (s->quiet) tradeoff[nt++] = "--quiet";
  depthsort[nd++] = "depthsort";
  depthsort[nd++] = "--frames";
  depthsort[nd++] = s->quick ? "4" : "40";
  depthsort[nd++] = "--csv";
  depthsort[nd++] = b->path[F_DEPTHSORT];
  if (s->size) {
    tradeoff[nt++] = "--size";
    tradeoff[nt++] = (char *)s->size;
    depthsort[nd++] = "--size";
    depthsort[nd++] = (char *)s->size;
  }
  tradeoff[nt] = depthsort[nd] = NULL;
  char *octree[] = {"octree", "--count", s->quick ? "500" : "5000", "--frames", s->quick ? "3" : "50",
                    "--csv", b->path[F_OCTREE_CSV], "--plot", b->path[F_OCTREE_PNG], NULL};
  char *calibrate[] = {"calibrate", "--repeat", s->quick ? "1" : "9", "-o", b->path[F_CLOCK], NULL};
  memcpy(b->octree, octree, sizeof octree);
  memcpy(b->calibrate, calibrate, sizeof calibrate);
}

/* The two large walks' modelled time along every frame, and along
 * bench tradeoff's steps. */
static zs_status plot_walks(const suite *s, zs_error *err) {
  static const char *const walk_name[2][2] = {{"walk-plant", "tradeoff-plant"},
                                              {"walk-teapots", "tradeoff-teapots"}};
  for (int k = 0; k < 2; k++) {
    char csv[PATH], png[PATH], title[400];
    in_dir_named(csv, s, "%s.csv", walk_name[k][0]);
    in_dir_named(png, s, "%s-every.png", walk_name[k][0]);
    snprintf(title, sizeof title, "%s, every frame", walks[k][s->quick ? 2 : 1]);
    if (plot_walk(csv, png, title, err)) return err->code;
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

/* The benchmarks in turn: raster, on all threads, memory, calibrate, two
 * walks, tradeoff, depthsort, octree.  1: a benchmark run here failed
 * (it said why); -1: an error in err. */
static int run_all(suite *s, bench_args *b, zs_error *err) {
  zs_progress progress;
  int done = 0;
  zs_progress_start(&progress, "bench suite", "benchmark", 8 + (s->threads > 0), s->quiet);
  /* llvmpipe on one thread beside zscan's one */
  if (s->mesa) setenv("LP_NUM_THREADS", "1", 1);
  if (run(zs_cmd_bench_raster, b->raster, NULL)) return 1;
  zs_progress_step(&progress, ++done);
  join_cmd(s->cmd_raster, s->mesa ? "LP_NUM_THREADS=1 zscan bench" : "zscan bench", b->raster);
  if (s->threads) {
    if (run_threads(s, err)) return -1;
    zs_progress_step(&progress, ++done);
  }
  if (run_memory(s, err)) return -1;
  zs_progress_step(&progress, ++done);
  if (run_child(s, b->calibrate, b->path[F_CALIBRATE], NULL, s->cmd_calibrate, err)) return -1;
  zs_progress_step(&progress, ++done);
  for (int k = 0; k < 2; k++) {
    if (run_walk(s, k, err)) return -1;
    zs_progress_step(&progress, ++done);
  }
  if (run(zs_cmd_bench_tradeoff, b->tradeoff, NULL)) return 1;
  zs_progress_step(&progress, ++done);
  if (run(zs_cmd_bench_depthsort, b->depthsort, s->cmd_depthsort)) return 1;
  zs_progress_step(&progress, ++done);
  if (run(zs_cmd_bench_octree, b->octree, s->cmd_octree)) return 1;
  zs_progress_step(&progress, ++done);
  return 0;
}

int zs_cmd_bench_suite(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, NULL)) return 0;
  static suite s; /* large: its command lines */
  static bench_args b;
  memset(&s, 0, sizeof s);
  s.dir = "bench-suite";
  const char *docs = NULL;
  zs_error err;
  zs_error_clear(&err);
  if (parse(argc, argv, &s, &docs, &err)) {
    return zs_cli_fail("zscan bench suite", &err, 1); /* a usage error exits 2 (tools/cli.h) */
  }
  if (probe(&s, docs, &err)) goto fail;
  bench_arguments(&s, &b);
  int rc = run_all(&s, &b, &err);
  if (rc > 0) return 1; /* the benchmark said why */
  if (rc < 0) goto fail;
  if (s.plots && plot_walks(&s, &err)) goto fail;
  char page[PATH];
  in_dir(page, &s, "RESULTS.md");
  if (write_page(&s, page, 0, &err)) goto fail;
  if (docs && write_docs(&s, docs, &err)) goto fail;
  printf("\nwrote %s: raster, memory, calibrate, walks, tradeoff (per walk), depthsort and "
         "octree files, and RESULTS.md%s%s%s\n",
         s.dir, s.mesa ? "; llvmpipe beside zscan" : "",
         s.threads ? ", on one thread and on all" : "",
         s.callgrind ? "; instructions per frame under callgrind" : "");
  return 0;
fail:
  return zs_cli_fail("zscan bench suite", &err, 0);
}
