/* docs/RESULTS.md is generated: `zscan bench suite --docs docs` writes it
 * from the templates of docs/results/ and what it measured
 * (tools/bench_suite.c).
 *
 * The page renders with --quick into a scratch folder of the build tree
 * (its templates: a link to the source's docs/results/), and the
 * committed page is that page with other figures: the same headings in
 * the same order, and every command it shows (each "$ " line of its code
 * blocks) shown by the render too.  The render is asked for the
 * committed page's thread count (its commands name it), so that the two
 * compare on a machine of any size.  The committed page has at most 600
 * lines.
 *
 * A bad template is refused before any benchmark runs (no output folder
 * is made), with one line naming the file and line, exit 1: an unknown
 * placeholder, a malformed one, an image the suite does not draw, a
 * measurement no template shows, no templates at all. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tests/testutil.h"
#include "util/os.h"

static char out[1 << 20], err[1 << 16];

enum { MAX_LINES = 256 };

/* What a page shows: its headings (lines that begin with '#', outside
 * code blocks) and its commands (the "$ " lines inside them, without the
 * "$ "), pointers into the page's text, which this cuts into lines. */
typedef struct shown {
  const char *heading[MAX_LINES], *command[MAX_LINES];
  int nheadings, ncommands, lines;
} shown;

static void read_page(char *text, shown *p) {
  memset(p, 0, sizeof *p);
  int fenced = 0;
  for (char *line = text; *line;) {
    char *nl = strchr(line, '\n');
    if (nl) *nl = '\0';
    p->lines++;
    if (strncmp(line, "```", 3) == 0) {
      fenced = !fenced;
    } else if (!fenced && line[0] == '#') {
      ck_assert_int_lt(p->nheadings, MAX_LINES);
      p->heading[p->nheadings++] = line;
    } else if (fenced && strncmp(line, "$ ", 2) == 0) {
      ck_assert_int_lt(p->ncommands, MAX_LINES);
      p->command[p->ncommands++] = line + 2;
    }
    line = nl ? nl + 1 : line + strlen(line);
  }
}

/* The folder name below the build tree, emptied of the files a run
 * leaves (RESULTS.md, images/, out/) and holding results/, a link to
 * the source's templates or, with copy, a copy of them. */
static const char *scratch(const char *name, int copy) {
  static char dir[4096];
  char cmd[9000];
  snprintf(dir, sizeof dir, "%s/%s", ZS_BINARY_DIR, name);
  snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s'", dir, dir);
  ck_assert_int_eq(system(cmd), 0);
  char link[4200];
  snprintf(link, sizeof link, "%s/results", dir);
  if (copy) {
    snprintf(cmd, sizeof cmd, "cp -R '%s' '%s'", zs_test_src("docs/results"), link);
    ck_assert_int_eq(system(cmd), 0);
  } else {
    ck_assert_msg(symlink(zs_test_src("docs/results"), link) == 0, "%s: %s", link,
                  strerror(errno));
  }
  return dir;
}

/* N of the committed page's "--threads N", or NULL. */
static const char *threads_of(const shown *p, char *buf, size_t cap) {
  for (int i = 0; i < p->ncommands; i++) {
    const char *t = strstr(p->command[i], "--threads ");
    if (t) {
      snprintf(buf, cap, "%.*s", (int)strcspn(t + 10, " "), t + 10);
      return buf;
    }
  }
  return NULL;
}

START_TEST(the_quick_page_has_the_committed_sections_and_commands) {
  size_t n;
  char *committed = (char *)zs_test_slurp(zs_test_src("docs/RESULTS.md"), &n);
  static shown want, got;
  read_page(committed, &want);
  ck_assert_msg(want.lines <= 700, "docs/RESULTS.md has %d lines; at most 700", want.lines);
  ck_assert_msg(want.nheadings >= 5 && want.ncommands >= 5,
                "docs/RESULTS.md: %d headings, %d commands", want.nheadings, want.ncommands);

  char dir[4096], outdir[4200], threads[16];
  snprintf(dir, sizeof dir, "%s", scratch("results-quick", 0));
  snprintf(outdir, sizeof outdir, "%s/out", dir);
  const char *args[16] = {"bench", "suite", "--quick", "--quiet", "--out", outdir, "--docs", dir};
  int k = 8;
  if (threads_of(&want, threads, sizeof threads)) {
    args[k++] = "--threads";
    args[k++] = threads;
  }
  args[k] = NULL;
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  ck_assert_msg(rc == 0, "bench suite --quick exited %d: %s", rc, err);

  char page[4300];
  snprintf(page, sizeof page, "%s/RESULTS.md", dir);
  char *rendered = (char *)zs_test_slurp(page, &n);
  read_page(rendered, &got);
  for (int i = 0; i < want.nheadings || i < got.nheadings; i++)
    ck_assert_msg(i < want.nheadings && i < got.nheadings && strcmp(want.heading[i], got.heading[i]) == 0,
                  "heading %d: docs/RESULTS.md has '%s', the templates give '%s' (%s)", i + 1,
                  i < want.nheadings ? want.heading[i] : "(none)",
                  i < got.nheadings ? got.heading[i] : "(none)", page);
  for (int i = 0; i < want.ncommands; i++) {
    int found = 0;
    for (int j = 0; j < got.ncommands && !found; j++) found = strcmp(want.command[i], got.command[j]) == 0;
    ck_assert_msg(found, "docs/RESULTS.md shows '$ %s', which the suite no longer runs (%s)",
                  want.command[i], page);
  }
  free(rendered);
  free(committed);
}
END_TEST

/* A bad template, and the line the suite refuses it with. */
typedef struct bad_case {
  const char *file, *text; /* written into the copy of the templates (text NULL: removed) */
  const char *message;      /* after "zscan bench suite: DIR/" */
} bad_case;

static const bad_case bad[] = {
    {"11-x.md", "## X\n\nA {foo} here.\n", "results/11-x.md:3: unknown placeholder {foo}"},
    {"11-x.md", "## X\n\n{raster table}\n",
     "results/11-x.md:3: malformed placeholder '{raster table}' (a brace opens {name})"},
    {"11-x.md", "## X\n{raster.table\n",
     "results/11-x.md:2: malformed placeholder '{raster.table' (a brace opens {name})"},
    {"11-x.md", "![a plot](images/nope.png)\n",
     "results/11-x.md:1: images/nope.png: the suite draws no such plot"},
    {"04-memory.md", NULL, "results: no template shows {memory.command}"},
};
enum { NBAD = sizeof bad / sizeof bad[0] };

START_TEST(a_bad_template_is_one_line_before_anything_runs) {
  const bad_case *b = &bad[_i];
  char dir[4096], path[4300], outdir[4200];
  snprintf(dir, sizeof dir, "%s", scratch("results-bad", 1));
  snprintf(path, sizeof path, "%s/results/%s", dir, b->file);
  if (b->text) {
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fputs(b->text, f);
    ck_assert_int_eq(fclose(f), 0);
  } else {
    ck_assert_int_eq(unlink(path), 0);
  }
  snprintf(outdir, sizeof outdir, "%s/out", dir);
  const char *args[] = {"bench", "suite", "--quick", "--out", outdir, "--docs", dir, NULL};
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  char want[8400];
  snprintf(want, sizeof want, "zscan bench suite: %s/%s\n", dir, b->message);
  ck_assert_msg(rc == 1, "exit %d: %s", rc, err);
  ck_assert_str_eq(err, want);
  ck_assert_msg(!zs_test_exists(outdir), "%s: made before the templates were checked", outdir);
}
END_TEST

START_TEST(no_templates_is_one_line) {
  char dir[4096], results[4200], outdir[4200];
  snprintf(dir, sizeof dir, "%s", scratch("results-none", 0));
  snprintf(results, sizeof results, "%s/results", dir);
  ck_assert_int_eq(unlink(results), 0);
  snprintf(outdir, sizeof outdir, "%s/out", dir);
  const char *args[] = {"bench", "suite", "--quick", "--out", outdir, "--docs", dir, NULL};
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  char want[8400];
  snprintf(want, sizeof want, "zscan bench suite: %s: cannot open: %s\n", results,
           strerror(ENOENT));
  ck_assert_int_eq(rc, 1);
  ck_assert_str_eq(err, want);
  ck_assert_int_eq(zs_os_mkdir(results), 0);
  rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  snprintf(want, sizeof want, "zscan bench suite: %s: no templates (*.md)\n", results);
  ck_assert_int_eq(rc, 1);
  ck_assert_str_eq(err, want);
}
END_TEST

int main(void) {
  Suite *s = suite_create("results");
  TCase *tc = tcase_create("results");
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, the_quick_page_has_the_committed_sections_and_commands);
  tcase_add_loop_test(tc, a_bad_template_is_one_line_before_anything_runs, 0, NBAD);
  tcase_add_test(tc, no_templates_is_one_line);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
