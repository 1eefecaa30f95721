/* docs/ALGORITHMS.md, followed as a newcomer would: every "$ build/zscan"
 * line of its text blocks is run from the source tree, must succeed, and
 * must print exactly the lines shown under it (when any are shown). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tests/testutil.h"

static char out[1 << 20], err[1 << 16];

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

START_TEST(every_command_of_the_page) {
  char path[4096];
  snprintf(path, sizeof path, "%s", zs_test_src("docs/ALGORITHMS.md"));
  FILE *f = fopen(path, "r");
  ck_assert_ptr_nonnull(f);
  ck_assert_int_eq(chdir(ZS_SOURCE_DIR), 0);
  static char doc[1 << 20];
  size_t n = fread(doc, 1, sizeof doc - 1, f);
  doc[n] = '\0';
  fclose(f);
  int commands = 0, compared = 0, in_block = 0;
  char *line = doc;
  while (line && *line) {
    char *nl = strchr(line, '\n');
    if (nl) *nl = '\0';
    char *next = nl ? nl + 1 : NULL;
    if (strncmp(line, "```", 3) == 0) {
      in_block = !in_block;
    } else if (in_block && strncmp(line, "$ build/zscan ", 14) == 0) {
      /* the expected output: the lines up to the next command or the end
       * of the block */
      char expect[1 << 16] = "";
      size_t len = 0;
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
      char cmd[4096];
      snprintf(cmd, sizeof cmd, "%s", line + 14);
      const char *argv[64];
      split(cmd, argv, 64);
      int rc = zs_test_run_zscan(argv, out, sizeof out, err, sizeof err);
      ck_assert_msg(rc == 0, "'%s' exited %d: %s", line, rc, err);
      if (len) {
        ck_assert_msg(strcmp(out, expect) == 0, "'%s' printed\n%s\nthe page shows\n%s", line, out,
                      expect);
        compared++;
      }
      commands++;
      next = l;
    }
    line = next;
  }
  ck_assert_int_ge(commands, 7);
  ck_assert_int_ge(compared, 2);
}
END_TEST

int main(void) {
  Suite *s = suite_create("docs");
  TCase *tc = tcase_create("algorithms");
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, every_command_of_the_page);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
