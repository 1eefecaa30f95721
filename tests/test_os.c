/* util/os.h, the operating system's part, on the system it runs on: the
 * same answers from util/os_posix.c and util/os_win32.c (CI runs this
 * suite natively and under wine). */
#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/testutil.h"
#include "util/os.h"

#ifdef _WIN32
#define NULL_DEVICE "NUL"
#else
#define NULL_DEVICE "/dev/null"
#endif

/* The arguments a child is given, awkward for a command line: spaces,
 * quotes, backslashes before a quote and at the end, nothing, UTF-8. */
static const char *const awkward[] = {"plain", "with space", "", "a\"quote", "back\\slash",
                                      "trailing\\", "\\\"both\\\\\"", "čaj テスト", NULL};

/* As a child (--echo): each argument on a line, then a line to standard
 * error between two to standard output, exit status 3. */
static int echo(int argc, char **argv) {
  zs_os_binary_stream(stdout); /* (as zscan's main: LF line ends) */
  zs_os_binary_stream(stderr);
  for (int i = 2; i < argc; i++) printf("[%s]\n", argv[i]);
  fflush(stdout);
  fputs("to stderr\n", stderr);
  fflush(stderr);
  puts("after");
  return 3;
}

START_TEST(roots_and_separators) {
  ck_assert(zs_os_is_separator('/'));
  ck_assert_uint_eq(zs_os_root_length("/tmp/x"), 1);
  ck_assert_uint_eq(zs_os_root_length("tmp/x"), 0);
#ifdef _WIN32
  ck_assert(zs_os_is_separator('\\'));
  ck_assert_uint_eq(zs_os_root_length("C:\\x.png"), 3);
  ck_assert_uint_eq(zs_os_root_length("c:/x.png"), 3);
  ck_assert_uint_eq(zs_os_root_length("C:x.png"), 2);
  ck_assert_uint_eq(zs_os_root_length("\\x.png"), 1);
#else
  ck_assert(!zs_os_is_separator('\\'));
  ck_assert_uint_eq(zs_os_root_length("C:\\x.png"), 0);
#endif
}
END_TEST

START_TEST(kinds_of_paths) {
  char dir[4096], file[4200], slash[4200];
  ck_assert_int_eq(zs_os_scratch_dir("zscan-test-os", dir, sizeof dir), 0);
  zs_path_info info;
  ck_assert_int_eq(zs_os_stat(dir, &info), 0);
  ck_assert_int_eq(info.kind, ZS_PATH_DIR);
  snprintf(slash, sizeof slash, "%s/", dir); /* (Windows' stat alone finds no "dir/") */
  ck_assert_int_eq(zs_os_stat(slash, &info), 0);
  ck_assert_int_eq(info.kind, ZS_PATH_DIR);
  snprintf(file, sizeof file, "%s/five", dir);
  FILE *f = fopen(file, "wb");
  ck_assert_ptr_nonnull(f);
  fputs("12345", f);
  fclose(f);
  ck_assert_int_eq(zs_os_lstat(file, &info), 0);
  ck_assert_int_eq(info.kind, ZS_PATH_FILE);
  ck_assert_int_eq(info.size, 5);
  ck_assert(zs_os_readable(file));
  f = fopen(file, "rb");
  ck_assert_int_eq(zs_os_fstat(f, &info), 0);
  ck_assert_int_eq(info.kind, ZS_PATH_FILE);
  ck_assert_int_eq(info.size, 5);
  fclose(f);
  ck_assert_int_eq(zs_os_stat(NULL_DEVICE, &info), 0);
  ck_assert_int_eq(info.kind, ZS_PATH_CHAR);
  snprintf(slash, sizeof slash, "%s/none", dir);
  ck_assert_int_eq(zs_os_lstat(slash, &info), 0); /* nothing there: no error */
  ck_assert_int_eq(info.kind, ZS_PATH_NONE);
  ck_assert(!zs_os_readable(slash));
  ck_assert_int_ne(zs_os_rmdir(dir), 0); /* not empty: refused */
  ck_assert_int_eq(remove(file), 0);
  ck_assert_int_eq(zs_os_rmdir(dir), 0);
  ck_assert_int_eq(zs_os_stat(dir, &info), 0);
  ck_assert_int_eq(info.kind, ZS_PATH_NONE);
}
END_TEST

/* Names seen, joined with '|'. */
static int note_name(const char *name, void *ctx) {
  char *seen = ctx;
  strcat(seen, name);
  strcat(seen, "|");
  return 0;
}

START_TEST(a_temporary_replaces_its_file) {
  char dir[4096], target[4200], tmp[4300];
  ck_assert_int_eq(zs_os_scratch_dir("zscan-test-os", dir, sizeof dir), 0);
  snprintf(target, sizeof target, "%s/out.txt", dir);
  FILE *f = fopen(target, "wb");
  fputs("old", f);
  fclose(f);
  int e = 0;
  f = zs_os_create_beside(target, zs_os_new_file_mode(), tmp, sizeof tmp, &e);
  ck_assert_msg(f != NULL, "%s", strerror(e));
  ck_assert(strncmp(tmp, target, strlen(target)) == 0 && strlen(tmp) > strlen(target));
  fputs("new", f);
  ck_assert_int_eq(fclose(f), 0);
  char seen[512] = "";
  ck_assert_int_eq(zs_os_each_name(dir, note_name, seen), 0);
  ck_assert_ptr_nonnull(strstr(seen, "out.txt|")); /* the file and its temporary */
  ck_assert_ptr_nonnull(strstr(seen, tmp + strlen(dir) + 1));
  ck_assert_int_eq(zs_os_replace(tmp, target), 0);
  seen[0] = '\0';
  ck_assert_int_eq(zs_os_each_name(dir, note_name, seen), 0);
  ck_assert_str_eq(seen, "out.txt|"); /* the temporary is the file now */
  char got[16];
  ck_assert_uint_eq(zs_test_read(target, got, sizeof got), 3);
  ck_assert_str_eq(got, "new");
  ck_assert_int_eq(remove(target), 0);
  ck_assert_int_eq(zs_os_rmdir(dir), 0);
  snprintf(target, sizeof target, "%s/gone", dir);
  ck_assert_int_lt(zs_os_each_name(target, note_name, seen), 0); /* an errno, negated */
}
END_TEST

START_TEST(a_memory_stream_keeps_every_byte) {
  zs_memfile m;
  ck_assert_int_eq(zs_memfile_open(&m), 0);
  for (int i = 0; i < 20000; i++) fprintf(m.f, "%d\n", i);
  fputc('\0', m.f); /* (bytes, not only text) */
  fputs("end", m.f);
  ck_assert_int_eq(zs_memfile_close(&m), 0);
  ck_assert_ptr_null(m.f);
  size_t want = 4;
  for (int i = 0; i < 20000; i++) want += (size_t)snprintf(NULL, 0, "%d\n", i);
  ck_assert_uint_eq(m.size, want);
  ck_assert(strncmp(m.data, "0\n1\n2\n", 6) == 0);
  ck_assert_str_eq(m.data + want - 3, "end"); /* and NUL-terminated */
  free(m.data);
}
END_TEST

static char self[4096];

START_TEST(a_child_gets_its_arguments_as_they_are) {
  char *argv[16];
  int n = 0;
  argv[n++] = self;
  argv[n++] = "--echo";
  for (int i = 0; awkward[i]; i++) argv[n++] = (char *)awkward[i];
  argv[n] = NULL;
  char out[4200];
  snprintf(out, sizeof out, "%s", zs_test_bin("test-os-child.txt"));
  /* one file for both streams: one offset, so the lines keep their order */
  ck_assert_int_eq(zs_os_spawn_wait(argv, out, out), 3);
  char got[1024], want[1024] = "";
  zs_test_read(out, got, sizeof got);
  for (int i = 0; awkward[i]; i++) {
    strcat(want, "[");
    strcat(want, awkward[i]);
    strcat(want, "]\n");
  }
  strcat(want, "to stderr\nafter\n");
  ck_assert_str_eq(got, want);
  ck_assert_int_eq(zs_os_spawn_wait(argv, NULL, NULL), 3); /* discarded */
  char *none[] = {"zscan-no-such-program", NULL};
  ck_assert(!zs_os_program_available(none[0]));
  ck_assert_int_eq(zs_os_spawn_wait(none, NULL, NULL), -1);
  remove(out);
}
END_TEST

START_TEST(the_environment_set_and_unset) {
  ck_assert_int_eq(zs_os_setenv("ZSCAN_TEST_OS", "yes"), 0);
  ck_assert_str_eq(getenv("ZSCAN_TEST_OS"), "yes");
  ck_assert_int_eq(zs_os_setenv("ZSCAN_TEST_OS", NULL), 0);
  ck_assert_ptr_null(getenv("ZSCAN_TEST_OS"));
  ck_assert_int_ge(zs_os_cpu_count(), 1);
  char machine[64];
  zs_os_machine(machine, sizeof machine);
  ck_assert(machine[0] != '\0');
}
END_TEST

int main(int argc, char **argv) {
  if (argc > 1 && strcmp(argv[1], "--echo") == 0) return echo(argc, argv);
  if (!zs_os_self_path(self, sizeof self)) return 1;
  Suite *s = suite_create("os");
  TCase *tc = tcase_create("os");
  tcase_add_test(tc, roots_and_separators);
  tcase_add_test(tc, kinds_of_paths);
  tcase_add_test(tc, a_temporary_replaces_its_file);
  tcase_add_test(tc, a_memory_stream_keeps_every_byte);
  tcase_add_test(tc, a_child_gets_its_arguments_as_they_are);
  tcase_add_test(tc, the_environment_set_and_unset);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
