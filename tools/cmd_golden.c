/* `zscan golden update|check MANIFEST`: golden-image tests over a manifest
 * of render cases, with reports a reviewer and a CI system can read.
 *
 * The manifest is JSON:
 *   {"cases": [{"name": "teapots", "input": "builtin:teapots",
 *               "size": "320x240", "eye": "9,7,14", "shade": "id"}, ...]}
 * Each case's keys besides name and input are zscan render's long options
 * without the dashes, with the values as on the command line (a number
 * may be a JSON number, a point a JSON array of three, a size an array of
 * two, a flag true);
 * input is relative to the manifest unless it is absolute or builtin:.
 * Two keys are the case's tolerances: max_channel_diff (a pixel differs
 * only when a channel differs by more; default 0) and max_diff_pixels
 * (how many may differ; default 0).  A case's golden is DIR/NAME.png.
 *
 * Because zscan gives the same bytes on every machine, one golden serves
 * every platform, and the tolerances default to none. */
#include <cjson/cJSON.h>
#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/image.h"
#include "lib/outfile.h"
#include "util/os.h"
#include "tools/cli.h"
#include "tools/commands.h"
#include "tools/cmd_render.h"

static const char usage[] =
    "usage: zscan golden update MANIFEST [--dir DIR]\n"
    "       zscan golden check MANIFEST [--dir DIR] [--report OUT] [--shard K/N] [--jobs J]\n"
    "  update              render every case and write DIR/NAME.png, and zscan's\n"
    "                      pixel version to DIR/PIXEL-VERSION\n"
    "  check               render every case and compare it with DIR/NAME.png: exit 0\n"
    "                      when all pass, 1 when any differs or lacks its golden (and\n"
    "                      then, if DIR/PIXEL-VERSION is another, what changed since)\n"
    "  MANIFEST            JSON: {\"cases\": [{\"name\": ..., \"input\": ..., OPTION: VALUE,\n"
    "                      ...}]}, OPTION any long option of zscan render without\n"
    "                      its dashes; max_channel_diff and max_diff_pixels: the\n"
    "                      case's tolerances (default 0)\n"
    "  --dir DIR           the goldens (default: golden/ beside the manifest)\n"
    "  --report OUT        OUT/index.html (the failing cases' golden, actual and diff\n"
    "                      side by side), OUT/NAME.actual.png, OUT/NAME.diff.png and\n"
    "                      OUT/junit.xml for CI\n"
    "  --shard K/N         only the K-th of N disjoint parts of the cases\n"
    "  --jobs J            render J cases at once (default 1)\n"
    "  --quiet             no progress on stderr\n";

enum { MAX_ARGS = 128 };

typedef struct golden_case {
  char *name;
  zs_cmd_render_opts opts;
  char *argv_text;      /* the render options' strings, owned */
  char *argv[MAX_ARGS]; /* render's argv, pointing into argv_text */
  int argc;
  int max_channel_diff;
  long long max_diff_pixels;
  /* the result */
  zs_image actual, golden, heat;
  zs_diff_result diff;
  int missing, size_differs, failed, rendered;
  double ms;
  zs_error err;
} golden_case;

typedef struct golden_run {
  const char *manifest, *dir, *report;
  int update, shard_k, shard_n, jobs, quiet;
  golden_case *cases;
  int ncases;
  int next; /* the next case a worker takes, under lock */
  int done; /* cases finished, under lock */
  zs_progress progress;
  pthread_mutex_t lock;
} golden_run;

/* ---- the manifest ---------------------------------------------------- */

/* Appends s to the case's argv (copied into its text). */
static zs_status push_arg(golden_case *c, size_t *used, size_t cap, const char *s,
                          const char *where, zs_error *err) {
  size_t n = strlen(s) + 1;
  if (c->argc + 1 >= MAX_ARGS || *used + n > cap)
    return zs_error_set(err, ZS_ERR_LIMIT, "%s: too many options", where);
  memcpy(c->argv_text + *used, s, n);
  c->argv[c->argc++] = c->argv_text + *used;
  *used += n;
  return ZS_OK;
}

/* A JSON value as the command line writes it: a string as it is, a number
 * in full, an array of numbers joined by commas. */
static int value_text(const cJSON *v, const char *key, char *buf, size_t cap) {
  const char *join = strcmp(key, "size") == 0 ? "x" : ","; /* [320, 240] is 320x240 */
  if (cJSON_IsString(v)) return snprintf(buf, cap, "%s", v->valuestring) < (int)cap;
  if (cJSON_IsNumber(v)) return snprintf(buf, cap, "%.17g", v->valuedouble) < (int)cap;
  if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) == 0) return 0;
  size_t len = 0;
  for (const cJSON *e = v->child; e; e = e->next) {
    if (!cJSON_IsNumber(e)) return 0;
    int k = snprintf(buf + len, cap - len, "%s%.17g", e == v->child ? "" : join, e->valuedouble);
    if (k < 0 || (size_t)k >= cap - len) return 0;
    len += (size_t)k;
  }
  return 1;
}

static int safe_name(const char *s) {
  if (!*s || strcmp(s, ".") == 0 || strcmp(s, "..") == 0) return 0;
  for (; *s; s++)
    if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9') ||
          *s == '-' || *s == '_' || *s == '.'))
      return 0;
  return 1;
}

static zs_status parse_case(const char *manifest, const char *mdir, const cJSON *jc, int i,
                            golden_case *c, zs_error *err) {
  char where[4400];
  snprintf(where, sizeof where, "%s: cases[%d]", manifest, i);
  if (!cJSON_IsObject(jc)) return zs_error_set(err, ZS_ERR_PARSE, "%s: expected an object", where);
  const cJSON *name = cJSON_GetObjectItemCaseSensitive(jc, "name");
  const cJSON *input = cJSON_GetObjectItemCaseSensitive(jc, "input");
  if (!cJSON_IsString(name) || !safe_name(name->valuestring))
    return zs_error_set(err, ZS_ERR_PARSE,
                        "%s.name: expected a name of letters, digits, '-', '_' and '.'", where);
  if (!cJSON_IsString(input) || !*input->valuestring)
    return zs_error_set(err, ZS_ERR_PARSE, "%s.input: expected a file or builtin:NAME", where);
  c->name = strdup(name->valuestring);
  size_t cap = 16384, used = 0;
  c->argv_text = malloc(cap);
  if (!c->name || !c->argv_text) return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  zs_status st = push_arg(c, &used, cap, "render", where, err);
  /* the input, relative to the manifest's folder */
  char path[8192];
  const char *in = input->valuestring;
  if (in[0] == '/' || strncmp(in, "builtin:", 8) == 0 || !*mdir)
    snprintf(path, sizeof path, "%s", in);
  else
    snprintf(path, sizeof path, "%s/%s", mdir, in);
  if (!st) st = push_arg(c, &used, cap, path, where, err);
  for (const cJSON *o = jc->child; o && !st; o = o->next) {
    const char *key = o->string;
    if (strcmp(key, "name") == 0 || strcmp(key, "input") == 0) continue;
    if (strcmp(key, "max_channel_diff") == 0 || strcmp(key, "max_diff_pixels") == 0) {
      int pixels = key[4] == 'd';
      double lim = pixels ? 1e15 : 255;
      if (!cJSON_IsNumber(o) || o->valuedouble < 0 || o->valuedouble > lim ||
          o->valuedouble != (double)(long long)o->valuedouble)
        return zs_error_set(err, ZS_ERR_PARSE, "%s.%s: expected a whole number from 0 to %.0f",
                            where, key, lim);
      if (pixels) c->max_diff_pixels = (long long)o->valuedouble;
      else c->max_channel_diff = (int)o->valuedouble;
      continue;
    }
    char opt[300], value[4096];
    snprintf(opt, sizeof opt, "--%s", key);
    if (cJSON_IsBool(o)) { /* a flag */
      if (cJSON_IsTrue(o)) st = push_arg(c, &used, cap, opt, where, err);
      continue;
    }
    if (cJSON_IsArray(o) && o->child && cJSON_IsString(o->child)) {
      /* an array of strings: the option once for each ("light": ["dir:..",
       * "ambient:.."] is --light dir:.. --light ambient:..) */
      for (const cJSON *e = o->child; e && !st; e = e->next) {
        if (!cJSON_IsString(e))
          return zs_error_set(err, ZS_ERR_PARSE, "%s.%s: expected an array of strings", where,
                              key);
        if (!(st = push_arg(c, &used, cap, opt, where, err)))
          st = push_arg(c, &used, cap, e->valuestring, where, err);
      }
      continue;
    }
    if (!value_text(o, key, value, sizeof value))
      return zs_error_set(err, ZS_ERR_PARSE,
                          "%s.%s: expected a string, a number, an array of numbers or an array "
                          "of strings", where, key);
    if (!(st = push_arg(c, &used, cap, opt, where, err)))
      st = push_arg(c, &used, cap, value, where, err);
  }
  if (st) return st;
  c->argv[c->argc] = NULL;
  /* render's own parser, so every option means what it means there */
  zs_error perr;
  zs_error_clear(&perr);
  if (zs_cmd_render_parse(c->argc, c->argv, 1, &c->opts, &perr))
    return zs_error_set(err, perr.code, "%s (%s): %s", where, c->name, perr.msg);
  return ZS_OK;
}

static void free_case(golden_case *c) {
  free(c->name);
  free(c->argv_text);
  zs_image_free(&c->actual);
  zs_image_free(&c->golden);
  zs_image_free(&c->heat);
}

/* The folder of path ("" for a bare file name). */
static void folder_of(const char *path, char *out, size_t cap) {
  const char *slash = strrchr(path, '/');
  if (!slash) snprintf(out, cap, "%s", "");
  else if (slash == path) snprintf(out, cap, "/");
  else snprintf(out, cap, "%.*s", (int)(slash - path), path);
}

static zs_status load_manifest(golden_run *r, zs_error *err) {
  FILE *f = fopen(r->manifest, "rb");
  if (!f) return zs_error_set(err, ZS_ERR_IO, "%s: cannot open: %s", r->manifest, strerror(errno));
  size_t cap = 1 << 16, n = 0;
  char *text = malloc(cap);
  for (size_t got; text && (got = fread(text + n, 1, cap - n, f)) > 0;) {
    n += got;
    if (n == cap && cap < ((size_t)64 << 20)) text = realloc(text, cap *= 2);
    else if (n == cap) break;
  }
  fclose(f);
  if (!text) return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  cJSON *root = cJSON_ParseWithLength(text, n);
  const char *bad = root ? NULL : cJSON_GetErrorPtr();
  long line = 1;
  for (const char *p = text; bad && p < bad && p < text + n; p++) line += *p == '\n';
  free(text);
  zs_status st = ZS_OK;
  const cJSON *cases = root ? cJSON_GetObjectItemCaseSensitive(root, "cases") : NULL;
  if (!root)
    st = zs_error_set(err, ZS_ERR_PARSE, "%s:%ld: not JSON", r->manifest, line);
  else if (!cJSON_IsArray(cases) || cJSON_GetArraySize(cases) == 0)
    st = zs_error_set(err, ZS_ERR_PARSE, "%s: cases: expected an array of at least one case",
                      r->manifest);
  char mdir[4200];
  folder_of(r->manifest, mdir, sizeof mdir);
  if (!st) {
    r->ncases = cJSON_GetArraySize(cases);
    r->cases = calloc((size_t)r->ncases, sizeof *r->cases);
    if (!r->cases) st = zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  }
  int i = 0;
  for (const cJSON *c = cases ? cases->child : NULL; c && !st; c = c->next, i++) {
    st = parse_case(r->manifest, mdir, c, i, &r->cases[i], err);
    for (int k = 0; k < i && !st; k++)
      if (strcmp(r->cases[k].name, r->cases[i].name) == 0)
        st = zs_error_set(err, ZS_ERR_PARSE, "%s: cases[%d].name: '%s' is cases[%d]'s name too",
                          r->manifest, i, r->cases[i].name, k);
  }
  cJSON_Delete(root);
  return st;
}

/* ---- rendering and comparing ----------------------------------------- */

static int in_shard(const golden_run *r, int i) { return i % r->shard_n == r->shard_k - 1; }

static void golden_path(const golden_run *r, const golden_case *c, char *buf, size_t cap) {
  snprintf(buf, cap, "%s/%s.png", r->dir, c->name);
}

static void run_case(golden_run *r, golden_case *c) {
  zs_error_clear(&c->err);
  double t0 = zs_os_monotonic_ms();
  if (zs_cmd_render_image(&c->opts, &c->actual, &c->err)) {
    c->failed = 1;
    c->ms = zs_os_monotonic_ms() - t0;
    return;
  }
  c->ms = zs_os_monotonic_ms() - t0;
  c->rendered = 1;
  if (r->update) return;
  char path[8400];
  golden_path(r, c, path, sizeof path);
  zs_path_info st;
  if (zs_os_stat(path, &st) != 0 || st.kind == ZS_PATH_NONE) {
    c->missing = 1;
    c->failed = 1;
    return;
  }
  zs_error e;
  zs_error_clear(&e);
  if (zs_png_read(path, &c->golden, &e)) {
    c->err = e;
    c->failed = 1;
    return;
  }
  if (c->golden.width != c->actual.width || c->golden.height != c->actual.height) {
    c->size_differs = 1;
    c->failed = 1;
    return;
  }
  if (zs_image_compare(&c->golden, &c->actual, c->max_channel_diff, &c->heat, &c->diff, &e)) {
    c->err = e;
    c->failed = 1;
    return;
  }
  c->failed = (long long)c->diff.differing > c->max_diff_pixels;
}

static void *worker(void *arg) {
  golden_run *r = arg;
  for (;;) {
    pthread_mutex_lock(&r->lock);
    int i = r->next++;
    pthread_mutex_unlock(&r->lock);
    if (i >= r->ncases) return NULL;
    if (!in_shard(r, i)) continue;
    run_case(r, &r->cases[i]);
    pthread_mutex_lock(&r->lock);
    zs_progress_step(&r->progress, ++r->done);
    pthread_mutex_unlock(&r->lock);
  }
}

/* ---- reports ---------------------------------------------------------- */

static const char b64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/* The file at path as a data: URL, written into f. */
static void data_url(FILE *f, const char *path) {
  FILE *in = fopen(path, "rb");
  fputs("data:image/png;base64,", f);
  if (!in) return;
  unsigned char b[3];
  size_t n;
  while ((n = fread(b, 1, 3, in)) > 0) {
    if (n < 3) memset(b + n, 0, 3 - n);
    char q[4] = {b64[b[0] >> 2], b64[(b[0] & 3) << 4 | b[1] >> 4],
                 n > 1 ? b64[(b[1] & 15) << 2 | b[2] >> 6] : '=', n > 2 ? b64[b[2] & 63] : '='};
    fwrite(q, 1, 4, f);
  }
  fclose(in);
}

/* s with &, <, >, " escaped, for HTML and XML. */
static void escaped(FILE *f, const char *s) {
  for (; *s; s++) {
    switch (*s) {
      case '&': fputs("&amp;", f); break;
      case '<': fputs("&lt;", f); break;
      case '>': fputs("&gt;", f); break;
      case '"': fputs("&quot;", f); break;
      default: fputc(*s, f);
    }
  }
}

/* What went wrong with c, in one line. */
static void reason(const golden_case *c, char *buf, size_t cap) {
  if (c->err.code) snprintf(buf, cap, "%s", c->err.msg);
  else if (c->missing) snprintf(buf, cap, "no golden (zscan golden update writes it)");
  else if (c->size_differs)
    snprintf(buf, cap, "size %dx%d, golden %dx%d", c->actual.width, c->actual.height,
             c->golden.width, c->golden.height);
  else
    snprintf(buf, cap, "%llu of %llu pixels differ (at most %lld allowed), largest channel "
                       "difference %d (tolerance %d)",
             (unsigned long long)c->diff.differing, (unsigned long long)c->diff.total,
             c->max_diff_pixels, c->diff.max_channel_diff, c->max_channel_diff);
}

static zs_status write_junit(const golden_run *r, const char *path, int tests, int failures,
                             double total_ms, zs_error *err) {
  zs_out out;
  if (zs_out_open(&out, path, err)) return err->code;
  FILE *f = out.fp;
  fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
             "<testsuites>\n<testsuite name=\"zscan golden\" tests=\"%d\" failures=\"%d\" "
             "errors=\"0\" time=\"%.3f\">\n",
          tests, failures, total_ms / 1000.0);
  for (int i = 0; i < r->ncases; i++) {
    const golden_case *c = &r->cases[i];
    if (!in_shard(r, i)) continue;
    fprintf(f, "  <testcase classname=\"golden\" name=\"");
    escaped(f, c->name);
    fprintf(f, "\" time=\"%.3f\"", c->ms / 1000.0);
    if (!c->failed) {
      fputs("/>\n", f);
      continue;
    }
    char why[1024];
    reason(c, why, sizeof why);
    fputs(">\n    <failure message=\"", f);
    escaped(f, why);
    fputs("\"/>\n  </testcase>\n", f);
  }
  fputs("</testsuite>\n</testsuites>\n", f);
  return zs_out_commit(&out, err);
}

static zs_status write_html(const golden_run *r, const char *path, int tests, int failures,
                            zs_error *err) {
  zs_out out;
  if (zs_out_open(&out, path, err)) return err->code;
  FILE *f = out.fp;
  fprintf(f,
          "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
          "<title>zscan golden: %d of %d failed</title>\n<style>\n"
          "body{font:15px/1.4 sans-serif;margin:24px;color:#222}\n"
          "h1{font-size:22px} h2{font-size:18px;margin-top:28px}\n"
          ".fail{color:#b00020} .pass{color:#1b7f3b}\n"
          ".row{display:flex;gap:16px;flex-wrap:wrap;align-items:flex-start}\n"
          "figure{margin:0} figcaption{font-size:13px;color:#555}\n"
          "img{image-rendering:pixelated;border:1px solid #ccc}\n"
          "code{background:#f3f3f3;padding:1px 4px}\n</style></head><body>\n"
          "<h1>zscan golden: <span class=\"%s\">%d of %d failed</span></h1>\n",
          failures, tests, failures ? "fail" : "pass", failures, tests);
  fputs("<p>Manifest <code>", f);
  escaped(f, r->manifest);
  fputs("</code>, goldens in <code>", f);
  escaped(f, r->dir);
  fputs("</code>. The diff is a heat map: pixels that do not differ are faded grey, those "
        "that do run from yellow (a difference of 1) to red (255).</p>\n",
        f);
  for (int i = 0; i < r->ncases; i++) {
    const golden_case *c = &r->cases[i];
    if (!in_shard(r, i) || !c->failed) continue;
    char why[1024], p[8400];
    reason(c, why, sizeof why);
    fputs("<section class=\"case\" id=\"", f);
    escaped(f, c->name);
    fputs("\"><h2 class=\"fail\">FAIL ", f);
    escaped(f, c->name);
    fputs("</h2>\n<p class=\"why\">", f);
    escaped(f, why);
    fputs("</p>\n<div class=\"row\">\n", f);
    const char *labels[3] = {"golden", "actual", "diff"};
    for (int k = 0; k < 3; k++) {
      if (k == 0) golden_path(r, c, p, sizeof p);
      else snprintf(p, sizeof p, "%s/%s.%s.png", r->report, c->name, labels[k]);
      zs_path_info st;
      if (zs_os_stat(p, &st) != 0 || st.kind == ZS_PATH_NONE) continue;
      /* small pictures at twice their size, pixels kept sharp */
      const zs_image *im = k == 0 ? &c->golden : k == 1 ? &c->actual : &c->heat;
      int shown = im->width && im->width <= 240 ? 2 * im->width : im->width ? im->width : 320;
      fprintf(f, "<figure><img alt=\"%s\" width=\"%d\" src=\"", labels[k], shown);
      data_url(f, p);
      fprintf(f, "\"><figcaption>%s</figcaption></figure>\n", labels[k]);
    }
    fputs("</div></section>\n", f);
  }
  fputs("<h2>Passed</h2>\n<ul class=\"passed\">\n", f);
  for (int i = 0; i < r->ncases; i++) {
    const golden_case *c = &r->cases[i];
    if (!in_shard(r, i) || c->failed) continue;
    fputs("<li class=\"pass\">", f);
    escaped(f, c->name);
    fprintf(f, " (%.1f ms)</li>\n", c->ms);
  }
  fputs("</ul>\n</body></html>\n", f);
  return zs_out_commit(&out, err);
}

static zs_status write_report(const golden_run *r, int tests, int failures, double total_ms,
                              zs_error *err) {
  if (zs_out_dir("--report", r->report, err)) return err->code;
  char p[8400];
  for (int i = 0; i < r->ncases; i++) {
    const golden_case *c = &r->cases[i];
    if (!in_shard(r, i) || !c->failed) continue;
    snprintf(p, sizeof p, "%s/%s.actual.png", r->report, c->name);
    if (c->rendered && zs_png_write_shaded(p, &c->actual, c->opts.shade, err)) return err->code;
    snprintf(p, sizeof p, "%s/%s.diff.png", r->report, c->name);
    if (c->heat.rgb && zs_png_write(p, &c->heat, err)) return err->code;
  }
  snprintf(p, sizeof p, "%s/junit.xml", r->report);
  if (write_junit(r, p, tests, failures, total_ms, err)) return err->code;
  snprintf(p, sizeof p, "%s/index.html", r->report);
  return write_html(r, p, tests, failures, err);
}

/* ---- the pixel version the goldens were made with ---------------------- */

/* DIR/PIXEL-VERSION, written by update beside the goldens. */
static void version_path(const golden_run *r, char *buf, size_t cap) {
  snprintf(buf, cap, "%s/PIXEL-VERSION", r->dir);
}

static zs_status write_version(const golden_run *r, zs_error *err) {
  char p[8400];
  version_path(r, p, sizeof p);
  zs_out o;
  if (zs_out_open(&o, p, err)) return err->code;
  fprintf(o.fp, "%d\n", zs_pixel_version());
  return zs_out_commit(&o, err);
}

/* The goldens' pixel version: 0 when the file is missing, -1 unreadable. */
static int read_version(const golden_run *r) {
  char p[8400];
  version_path(r, p, sizeof p);
  FILE *f = fopen(p, "r");
  if (!f) return 0;
  int v = -1;
  if (fscanf(f, "%d", &v) != 1 || v < 1) v = -1;
  fclose(f);
  return v;
}

/* After a failed check: whether the goldens are of another pixel version,
 * and then what changed since theirs, a line a version. */
static void explain_version(const golden_run *r) {
  const int theirs = read_version(r), ours = zs_pixel_version();
  if (theirs == ours) return;
  if (theirs <= 0) {
    printf("golden check: %s/PIXEL-VERSION %s: the goldens' pixel version is unknown; this "
           "zscan draws pixel version %d\n", r->dir, theirs ? "is unreadable" : "is missing",
           ours);
    return;
  }
  printf("golden check: the goldens were made with pixel version %d; this zscan draws pixel "
         "version %d%s\n", theirs, ours, theirs < ours ? ", which changed:" : " (an older zscan)");
  for (int v = theirs + 1; v <= ours; v++) printf("  pixel version %d: %s\n", v, zs_pixel_changes(v));
}

/* ---- the command ------------------------------------------------------ */

static int usage_error(const char *fmt, const char *arg) {
  fputs("zscan golden: ", stderr);
  fprintf(stderr, fmt, arg);
  fputs(" (see zscan golden --help)\n", stderr);
  return 2;
}

int zs_cmd_golden(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, NULL)) return 0;
  golden_run r = {0};
  r.shard_k = r.shard_n = r.jobs = 1;
  if (argc < 2) return usage_error("%s", "expected update or check");
  if (strcmp(argv[1], "update") == 0) r.update = 1;
  else if (strcmp(argv[1], "check") != 0)
    return usage_error("'%s': expected update or check", argv[1]);
  zs_error err;
  zs_error_clear(&err);
  for (int i = 2; i < argc; i++) {
    const char *a = argv[i], *v = NULL;
    if (strcmp(a, "--dir") == 0 || strcmp(a, "--report") == 0 || strcmp(a, "--shard") == 0 ||
        strcmp(a, "--jobs") == 0) {
      if (zs_cli_value(argc, argv, &i, &v, &err)) return usage_error("%s", err.msg);
      if ((a[2] == 'r' || a[2] == 's') && r.update)
        return usage_error("%s: for check only", a);
      if (a[2] == 'd') r.dir = v;
      else if (a[2] == 'r') r.report = v;
      else if (a[2] == 'j') {
        if (zs_cli_int(a, v, 1, 64, &r.jobs, &err)) return usage_error("%s", err.msg);
      } else {
        char tail;
        if (sscanf(v, "%d/%d%c", &r.shard_k, &r.shard_n, &tail) != 2 || r.shard_n < 1 ||
            r.shard_k < 1 || r.shard_k > r.shard_n)
          return usage_error("--shard: expected K/N with 1 <= K <= N, got '%s'", v);
      }
    } else if (strcmp(a, "--quiet") == 0) {
      r.quiet = 1;
    } else if (a[0] == '-' && a[1]) {
      return usage_error("unknown option '%s'", a);
    } else if (!r.manifest) {
      r.manifest = a;
    } else {
      return usage_error("more than one MANIFEST: '%s'", a);
    }
  }
  if (!r.manifest) return usage_error("%s", "missing MANIFEST");
  char default_dir[4300];
  if (!r.dir) {
    char mdir[4200];
    folder_of(r.manifest, mdir, sizeof mdir);
    snprintf(default_dir, sizeof default_dir, "%s%sgolden", mdir, *mdir ? "/" : "");
    r.dir = default_dir;
  }
  int status = 1;
  pthread_mutex_init(&r.lock, NULL);
  if (load_manifest(&r, &err)) goto done;
  if (r.update && zs_out_dir("--dir", r.dir, &err)) goto done;
  double t0 = zs_os_monotonic_ms();
  int in_this_shard = 0;
  for (int i = 0; i < r.ncases; i++) in_this_shard += in_shard(&r, i);
  zs_progress_start(&r.progress, "golden", "case", in_this_shard, r.quiet);
  pthread_t threads[64];
  int started = 0;
  for (int j = 1; j < r.jobs; j++)
    if (pthread_create(&threads[started], NULL, worker, &r) == 0) started++;
  worker(&r);
  for (int j = 0; j < started; j++) pthread_join(threads[j], NULL);
  double total_ms = zs_os_monotonic_ms() - t0;
  int tests = 0, failures = 0;
  for (int i = 0; i < r.ncases; i++) {
    golden_case *c = &r.cases[i];
    if (!in_shard(&r, i)) continue;
    tests++;
    if (r.update && c->rendered) {
      char p[8400];
      golden_path(&r, c, p, sizeof p);
      zs_error e;
      zs_error_clear(&e);
      if (zs_png_write_shaded(p, &c->actual, c->opts.shade, &e)) {
        c->err = e;
        c->failed = 1;
      }
    }
    failures += c->failed;
    char why[1024] = "";
    if (c->failed) reason(c, why, sizeof why);
    if (r.update)
      printf("%-24s %s %8.1f ms%s%s\n", c->name, c->failed ? "FAIL" : "wrote", c->ms,
             c->failed ? "  " : "", why);
    else if (c->failed)
      printf("%-24s FAIL %8.1f ms  %s\n", c->name, c->ms, why);
    else
      printf("%-24s pass %8.1f ms  %llu pixels differ\n", c->name, c->ms,
             (unsigned long long)c->diff.differing);
  }
  if (!r.update && r.report && write_report(&r, tests, failures, total_ms, &err)) goto done;
  /* the version stamps goldens all made by this zscan */
  if (r.update && failures == 0 && write_version(&r, &err)) goto done;
  if (!r.update && failures) explain_version(&r);
  printf("golden %s: %d passed, %d failed%s\n", r.update ? "update" : "check", tests - failures,
         failures, r.shard_n > 1 ? " (this shard)" : "");
  status = failures ? 1 : 0;
done:
  if (err.code) fprintf(stderr, "zscan golden: %s\n", err.msg);
  for (int i = 0; i < r.ncases; i++) free_case(&r.cases[i]);
  free(r.cases);
  pthread_mutex_destroy(&r.lock);
  return status;
}
