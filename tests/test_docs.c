/* The documentation, followed as a newcomer would.
 *
 * README.md: every line of its ```sh blocks is run as shown (build/zscan
 * is the command this build made) and must exit 0, except the set-up
 * commands it shows for a fresh machine (the quick-start scripts, apt-get
 * and cmake), which are named here one by one; any other command fails
 * the test, so a new one cannot slip in unrun.  The README has at most
 * 300 lines.
 * The pages of docs/: every "$ build/zscan" line of their text blocks is run, must
 * exit 0, and must print exactly the lines shown under it, when any are
 * shown (docs/CLI.md: every command's --help); where what is shown is one
 * error line ("zscan CMD: ..."), the command must exit 1 and print exactly
 * that line on standard error.
 * Every page: each relative link names a file that exists, and no page
 * tells the project's history: no working period by name, no tracker
 * number.
 * A block that shows a file is that file's bytes.  The convention: the
 * last line before the block's opening fence ends with the file's path
 * from the root of the source tree in backquotes and a colon
 * ("`docs/examples/golden.json`:"); the block must then hold exactly the
 * file's bytes.  So that none is missed, a block of a file type (```json,
 * ```c, ```cmake, ...) whose paragraph names a file of that type that
 * exists must carry the mark (README.md and every page below docs/).
 *
 * The commands run in a scratch directory of the build tree that reaches
 * the source's scene/, tests/ and docs/ through symbolic links, so that
 * their inputs are found as the pages name them and their outputs land
 * outside the source tree. */
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tests/testutil.h"
#include "util/os.h"

static char out[1 << 20], err[1 << 16];

/* The pages besides the README, and what each must hold at the least:
 * commands run, outputs compared. */
typedef struct page {
  const char *path;
  int min_commands, min_compared;
} page;

static const page pages[] = {
    {"docs/ALGORITHMS.md", 7, 2}, {"docs/SCENES.md", 10, 0}, {"docs/CULLING.md", 5, 0},
    {"docs/GOLDEN.md", 7, 2},     {"docs/CLI.md", 13, 13},   {"docs/ARCHITECTURE.md", 0, 0},
    {"docs/RESULTS.md", 0, 0},    {"docs/REFERENCES.md", 0, 0}, {"docs/TEACHING.md", 4, 0},
    {"docs/API.md", 0, 0},
};
enum { NPAGES = sizeof pages / sizeof pages[0] };

/* What the README may show without the test running it: the set-up of a
 * fresh machine (it installs packages, builds, or runs this very suite). */
static const char *const setup_commands[] = {"tools/render-demo.sh", "tools/run-tests.sh",
                                             "apt-get ", "sudo apt-get ", "cmake "};

/* Splits a command line at spaces; double quotes group (and are dropped). */
static int split(char *line, const char **argv, int max) {
  int n = 0;
  char *p = line;
  while (*p && n < max - 1) {
    while (*p == ' ') p++;
    if (!*p) break;
    char *w = p, *o = p;
    int quoted = 0;
    for (; *p && (quoted || *p != ' '); p++) {
      if (*p == '"') quoted = !quoted;
      else *o++ = *p;
    }
    if (*p) p++;
    *o = '\0';
    argv[n++] = w;
  }
  argv[n] = NULL;
  return n;
}

/* The whole file at rel (below the source tree), NUL-terminated, in a
 * buffer the caller frees. */
static char *slurp(const char *rel) {
  size_t n;
  return (char *)zs_test_slurp(zs_test_src(rel), &n);
}

/* Into the scratch directory, where scene/, tests/ and docs/ lead to the
 * source tree's. */
static void enter_scratch(void) {
  char dir[4096], link[4200];
  snprintf(dir, sizeof dir, "%s/docs-run", ZS_BINARY_DIR);
  int e = zs_os_mkdir(dir);
  ck_assert_msg(e == 0 || e == EEXIST, "%s: %s", dir, strerror(e));
  static const char *const shared[] = {"scene", "tests", "docs"};
  for (int i = 0; i < 3; i++) {
    snprintf(link, sizeof link, "%s/%s", dir, shared[i]);
    unlink(link);
    ck_assert_msg(symlink(zs_test_src(shared[i]), link) == 0, "%s: %s", link, strerror(errno));
  }
  ck_assert_int_eq(chdir(dir), 0);
}

/* Runs "build/zscan ARGS" (line without the "build/zscan "), which must
 * exit 0, or 1 when it is shown failing. */
static void run_zscan(const char *where, const char *line, const char *args, int fails) {
  char cmd[4096];
  snprintf(cmd, sizeof cmd, "%s", args);
  const char *argv[64];
  split(cmd, argv, 64);
  int rc = zs_test_run_zscan(argv, out, sizeof out, err, sizeof err);
  ck_assert_msg(rc == (fails ? 1 : 0), "%s: '%s' exited %d: %s", where, line, rc, err);
}

/* Every "$ build/zscan" line of the page's text blocks: run it, and
 * compare what it prints with the lines under it up to the next command
 * or the end of the block. */
static void run_page(const page *pg) {
  char *doc = slurp(pg->path);
  int commands = 0, compared = 0, in_block = 0;
  char *line = doc;
  while (line && *line) {
    char *nl = strchr(line, '\n');
    if (nl) *nl = '\0';
    char *next = nl ? nl + 1 : NULL;
    if (strncmp(line, "```", 3) == 0) {
      in_block = !in_block;
    } else if (in_block && strncmp(line, "$ build/zscan ", 14) == 0) {
      static char expect[1 << 16];
      size_t len = 0;
      expect[0] = '\0';
      char *l = next;
      while (l && strncmp(l, "```", 3) != 0 && strncmp(l, "$ ", 2) != 0) {
        char *e = strchr(l, '\n');
        size_t k = e ? (size_t)(e - l) : strlen(l);
        if (len + k + 2 < sizeof expect) {
          memcpy(expect + len, l, k);
          len += k;
          expect[len++] = '\n';
          expect[len] = '\0';
        }
        l = e ? e + 1 : NULL;
      }
      int fails = len > 6 && memcmp(expect, "zscan ", 6) == 0 &&
                  strchr(expect, '\n') == expect + len - 1;
      run_zscan(pg->path, line, line + 14, fails);
      if (len) {
        const char *got = fails ? err : out;
        ck_assert_msg(strcmp(got, expect) == 0, "%s: '%s' printed\n%s\nthe page shows\n%s",
                      pg->path, line, got, expect);
        compared++;
      }
      commands++;
      next = l;
    }
    line = next;
  }
  free(doc);
  ck_assert_msg(commands >= pg->min_commands, "%s: %d commands, expected %d or more", pg->path,
                commands, pg->min_commands);
  ck_assert_msg(compared >= pg->min_compared, "%s: %d outputs compared, expected %d or more",
                pg->path, compared, pg->min_compared);
}

START_TEST(every_command_of_every_page) {
  enter_scratch();
  run_page(&pages[_i]);
}
END_TEST

START_TEST(every_command_of_the_readme) {
  char *doc = slurp("README.md");
  int lines = 0;
  for (const char *p = doc; *p; p++) lines += *p == '\n';
  ck_assert_msg(lines <= 300, "README.md has %d lines; at most 300", lines);
  enter_scratch();
  int run = 0, setup = 0, in_sh = 0, in_block = 0;
  char *line = doc;
  while (line && *line) {
    char *nl = strchr(line, '\n');
    if (nl) *nl = '\0';
    char *next = nl ? nl + 1 : NULL;
    if (strncmp(line, "```", 3) == 0) {
      in_sh = !in_block && strcmp(line, "```sh") == 0;
      in_block = !in_block;
    } else if (in_sh && line[0] && line[0] != '#') {
      int known = 0;
      for (size_t k = 0; k < sizeof setup_commands / sizeof setup_commands[0]; k++)
        known |= strncmp(line, setup_commands[k], strlen(setup_commands[k])) == 0;
      if (known) {
        setup++;
      } else {
        ck_assert_msg(strncmp(line, "build/zscan ", 12) == 0,
                      "README.md shows '%s', which this test does not know how to run", line);
        run_zscan("README.md", line, line + 12, 0);
        run++;
      }
    }
    line = next;
  }
  free(doc);
  /* the four "if you want to" sections' commands; the quick start, apt-get, cmake */
  ck_assert_msg(run >= 8, "README.md: %d commands run, expected 8 or more", run);
  ck_assert_msg(setup == 4, "README.md: %d set-up commands, expected 4", setup);
}
END_TEST

/* The relative links of a page ("](path)" and "](path#anchor)") name
 * files that exist; and the page names no working period and no tracker
 * number (the words are spelt in pieces here, so that this file holds
 * neither). */
static void check_page_text(const char *rel) {
  char *doc = slurp(rel);
  char dir[4096];
  snprintf(dir, sizeof dir, "%s", rel);
  char *slash = strrchr(dir, '/');
  if (slash) slash[1] = '\0';
  else dir[0] = '\0';
  for (char *p = strstr(doc, "]("); p; p = strstr(p + 2, "](")) {
    char target[1024];
    size_t k = strcspn(p + 2, ")#\n");
    if (k == 0 || k >= sizeof target) continue; /* "](#anchor)" */
    memcpy(target, p + 2, k);
    target[k] = '\0';
    if (strstr(target, "://")) continue;
    char rel_target[sizeof dir + sizeof target];
    snprintf(rel_target, sizeof rel_target, "%s%s", dir, target);
    ck_assert_msg(zs_test_exists(zs_test_src(rel_target)), "%s: the link to '%s' leads nowhere",
                  rel, target);
  }
  for (char *p = doc; *p; p++) {
    static const char period[] = "ses" "sion", tracker[] = "iss" "ue ";
    if (strncasecmp(p, period, 7) == 0 && (p == doc || !isalpha((unsigned char)p[-1])))
      ck_abort_msg("%s: names a working period: '%.60s'", rel, p);
    if (strncasecmp(p, tracker, 6) == 0 && isdigit((unsigned char)p[6]))
      ck_abort_msg("%s: names a tracker number: '%.60s'", rel, p);
  }
  free(doc);
}

START_TEST(links_lead_somewhere) {
  check_page_text("README.md");
  for (int i = 0; i < NPAGES; i++) check_page_text(pages[i].path);
}
END_TEST

/* The file types of a fence's info string, and the names a file of that
 * type ends with. */
static const struct {
  const char *info, *ends[3];
} file_types[] = {
    {"json", {".json", NULL, NULL}},          {"c", {".c", ".h", NULL}},
    {"cpp", {".cpp", ".hpp", ".h"}},          {"cmake", {"CMakeLists.txt", ".cmake", NULL}},
    {"python", {".py", NULL, NULL}},          {"sh", {".sh", NULL, NULL}},
    {"toml", {".toml", NULL, NULL}},          {"yaml", {".yml", ".yaml", NULL}},
};

static int ends_with(const char *s, size_t n, const char *end) {
  size_t k = strlen(end);
  return n >= k && memcmp(s + n - k, end, k) == 0;
}

/* The path that line marks ("... `PATH`:" at its end, PATH with a '/'
 * or a '.' and not an option), into path; 0 when it marks none. */
static int marked_path(const char *line, size_t n, char *path, size_t cap) {
  if (n < 4 || line[n - 1] != ':' || line[n - 2] != '`') return 0;
  const char *open = line + n - 3;
  while (open > line && *open != '`') open--;
  size_t k = (size_t)(line + n - 2 - open) - 1;
  if (*open != '`' || k == 0 || k >= cap || memchr(open + 1, ' ', k)) return 0;
  memcpy(path, open + 1, k);
  path[k] = '\0';
  return path[0] != '-' && strpbrk(path, "/.") != NULL;
}

/* Whether the text [p, end) names in backquotes a file of the source tree
 * whose name ends in one of ends; its name into name. */
static int names_file_of_type(const char *p, const char *end, const char *const *ends,
                              char *name, size_t cap) {
  for (const char *q = memchr(p, '`', (size_t)(end - p)); q && q < end;) {
    const char *close = memchr(q + 1, '`', (size_t)(end - q - 1));
    if (!close) break;
    size_t k = (size_t)(close - q - 1);
    for (int e = 0; e < 3 && ends[e]; e++)
      if (k > 0 && k < cap && ends_with(q + 1, k, ends[e])) {
        memcpy(name, q + 1, k);
        name[k] = '\0';
        if (!strchr(name, ' ') && zs_test_exists(zs_test_src(name))) return 1;
      }
    q = memchr(close + 1, '`', (size_t)(end - close - 1));
  }
  return 0;
}

/* Every fenced block of the page at path (absolute) that shows a file. */
static void check_blocks(const char *path, void *shown) {
  size_t size;
  char *doc = (char *)zs_test_slurp(path, &size);
  /* the last paragraph before this line, and its last line */
  const char *para = doc, *para_end = doc, *last = NULL;
  size_t last_len = 0;
  int blank = 1;
  for (const char *line = doc; *line;) {
    const char *nl = strchr(line, '\n');
    size_t len = nl ? (size_t)(nl - line) : strlen(line);
    const char *next = nl ? nl + 1 : line + len;
    if (len == 0) {
      blank = 1;
    } else if (strncmp(line, "```", 3) == 0) {
      const char *body = next, *close = body;
      while (*close && strncmp(close, "```", 3) != 0) {
        const char *e = strchr(close, '\n');
        close = e ? e + 1 : close + strlen(close);
      }
      char file[1024], named[1024], info[32];
      snprintf(info, sizeof info, "%.*s", (int)(len - 3 < 31 ? len - 3 : 31), line + 3);
      if (last && marked_path(last, last_len, file, sizeof file)) {
        ck_assert_msg(zs_test_exists(zs_test_src(file)),
                      "%s: a block marked as %s, which is no file", path, file);
        size_t n;
        char *bytes = (char *)zs_test_slurp(zs_test_src(file), &n);
        ck_assert_msg((size_t)(close - body) == n && memcmp(body, bytes, n) == 0,
                      "%s: the block marked as %s is not that file's bytes", path, file);
        free(bytes);
        ++*(int *)shown;
      } else {
        for (size_t t = 0; t < sizeof file_types / sizeof file_types[0]; t++)
          if (strcmp(info, file_types[t].info) == 0 &&
              names_file_of_type(para, para_end, file_types[t].ends, named, sizeof named))
            ck_abort_msg("%s: a ```%s block after a paragraph naming %s, without the mark "
                         "(\"`%s`:\" ending the line before it) that says it shows that file",
                         path, info, named, named);
      }
      next = *close ? (strchr(close, '\n') ? strchr(close, '\n') + 1 : close + strlen(close))
                    : close;
      para = para_end = next;
      last = NULL;
      blank = 1;
      line = next;
      continue;
    } else {
      if (blank) para = line;
      blank = 0;
      para_end = next;
      last = line;
      last_len = len;
    }
    line = next;
  }
  free(doc);
}

START_TEST(every_file_shown_is_that_file) {
  int shown = 0;
  check_blocks(zs_test_src("README.md"), &shown);
  static const char *const md[] = {".md"};
  char docs[4096];
  snprintf(docs, sizeof docs, "%s", zs_test_src("docs"));
  zs_test_each_file(docs, md, 1, check_blocks, &shown);
  /* docs/GOLDEN.md's manifest, docs/SCENES.md's scene file */
  ck_assert_msg(shown >= 2, "%d blocks shown as files, expected 2 or more", shown);
}
END_TEST

int main(void) {
  Suite *s = suite_create("docs");
  TCase *tc = tcase_create("docs");
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, every_command_of_the_readme);
  tcase_add_loop_test(tc, every_command_of_every_page, 0, NPAGES);
  tcase_add_test(tc, links_lead_somewhere);
  tcase_add_test(tc, every_file_shown_is_that_file);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
