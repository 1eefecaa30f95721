#define _XOPEN_SOURCE 700 /* mknod */
/* Outputs never clobber: every writer goes through lib/outfile.c, and
 * what happens at the path depends on what is there (a file, a link, a
 * device, a FIFO, a socket, "-", a directory, nothing). */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include "testutil.h"
#include "lib/outfile.h"
#include "util/os.h"

static char dir[4096];

static void make_dir(void) {
  snprintf(dir, sizeof dir, "%s/output-test-XXXXXX", ZS_BINARY_DIR);
  ck_assert_ptr_nonnull(mkdtemp(dir));
}

static void remove_dir(void) {
  char cmd[4200];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  ck_assert_int_eq(system(cmd), 0);
}

static const char *in_dir(const char *name) {
  static char buf[4][4200];
  static int k;
  k = (k + 1) % 4;
  snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
  return buf[k];
}

/* The whole file, malloc'd; *n its size. */

static void write_text(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  ck_assert_ptr_nonnull(f);
  fputs(text, f);
  ck_assert_int_eq(fclose(f), 0);
}

/* In a child: copies what arrives on in to a new file at path, then exits. */
_Noreturn static void copy_and_exit(int in, const char *path) {
  int out = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
  char buf[4096];
  ssize_t n;
  while (in >= 0 && out >= 0 && (n = read(in, buf, sizeof buf)) > 0)
    if (write(out, buf, (size_t)n) != n) _exit(1);
  _exit(in >= 0 && out >= 0 ? 0 : 1);
}


/* zscan render of a small frame to -o OUT; stdout to out_path (a file,
 * binary safe), stderr into err. */
static int render_to(const char *out, const char *out_path, char *err, size_t cap) {
  char exe[4096], err_path[4200];
  snprintf(exe, sizeof exe, "%s/zscan", ZS_BINARY_DIR);
  snprintf(err_path, sizeof err_path, "%s/stderr.txt", dir);
  char *argv[] = {exe, "render", "builtin:default", "--size", "64x48", "-o", (char *)out, NULL};
  int rc = zs_os_spawn_wait(argv, out_path, err_path);
  FILE *f = fopen(err_path, "r");
  size_t n = f ? fread(err, 1, cap - 1, f) : 0;
  err[n] = '\0';
  if (f) fclose(f);
  unlink(err_path);
  return rc;
}

/* The reference: the same frame written to a new regular file. */
static const char *reference(void) {
  char err[1024];
  const char *ref = in_dir("reference.png");
  ck_assert_int_eq(render_to(ref, NULL, err, sizeof err), 0);
  return ref;
}

/* No PATH.tmp.XXXXXX left in the folder. */
static void assert_no_temporaries(void) {
  DIR *d = opendir(dir);
  ck_assert_ptr_nonnull(d);
  struct dirent *e;
  while ((e = readdir(d)))
    ck_assert_msg(strstr(e->d_name, ".tmp.") == NULL, "left behind: %s", e->d_name);
  closedir(d);
}

START_TEST(stdout_equals_file_byte_for_byte) {
  make_dir();
  const char *ref = reference();
  char err[1024];
  const char *captured = in_dir("captured.png");
  ck_assert_int_eq(render_to("-", captured, err, sizeof err), 0);
  zs_test_assert_same_file(ref, captured);
  ck_assert(!zs_test_exists(in_dir("-")));
  /* standard output takes one stream: the image, or the stats */
  const char *args[] = {"render", "builtin:default", "--size", "64x48", "-o", "-", "--stats", NULL};
  char out[256], msg[1024];
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, msg, sizeof msg), 2);
  ck_assert_ptr_nonnull(strstr(msg, "standard output (-) takes one stream"));
  remove_dir();
}
END_TEST

START_TEST(symlink_is_followed_and_stays_a_link) {
  make_dir();
  const char *ref = reference();
  const char *target = in_dir("target.png"), *link = in_dir("link.png");
  write_text(target, "old contents\n");
  ck_assert_int_eq(symlink("target.png", link), 0); /* relative, as users make them */
  char err[1024];
  ck_assert_int_eq(render_to(link, NULL, err, sizeof err), 0);
  struct stat st;
  ck_assert_int_eq(lstat(link, &st), 0);
  ck_assert(S_ISLNK(st.st_mode));
  zs_test_assert_same_file(ref, target);
  /* a dangling link: its target is created */
  const char *dangling = in_dir("dangling.png");
  ck_assert_int_eq(symlink("made-by-render.png", dangling), 0);
  ck_assert_int_eq(render_to(dangling, NULL, err, sizeof err), 0);
  ck_assert_int_eq(lstat(dangling, &st), 0);
  ck_assert(S_ISLNK(st.st_mode));
  zs_test_assert_same_file(ref, in_dir("made-by-render.png"));
  assert_no_temporaries();
  remove_dir();
}
END_TEST

START_TEST(replaced_file_keeps_its_mode) {
  make_dir();
  const char *path = in_dir("private.png");
  write_text(path, "old\n");
  ck_assert_int_eq(chmod(path, 0640), 0);
  char err[1024];
  ck_assert_int_eq(render_to(path, NULL, err, sizeof err), 0);
  struct stat st;
  ck_assert_int_eq(stat(path, &st), 0);
  ck_assert_int_eq(st.st_mode & 0777, 0640);
  ck_assert_int_gt(st.st_size, 100);
  remove_dir();
}
END_TEST

START_TEST(fifo_written_directly_to_its_reader) {
  make_dir();
  const char *ref = reference();
  const char *fifo = in_dir("pipe"), *got = in_dir("from-pipe.png");
  ck_assert_int_eq(mkfifo(fifo, 0600), 0);
  pid_t reader = fork();
  ck_assert_int_ge(reader, 0);
  if (reader == 0) copy_and_exit(open(fifo, O_RDONLY), got);
  char err[1024];
  ck_assert_int_eq(render_to(fifo, NULL, err, sizeof err), 0);
  int status;
  ck_assert_int_eq(waitpid(reader, &status, 0), reader);
  ck_assert(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  struct stat st;
  ck_assert_int_eq(lstat(fifo, &st), 0);
  ck_assert(S_ISFIFO(st.st_mode)); /* still a FIFO, not replaced by a file */
  zs_test_assert_same_file(ref, got);
  assert_no_temporaries();
  remove_dir();
}
END_TEST

START_TEST(socket_written_directly_to_its_listener) {
  make_dir();
  const char *ref = reference();
  const char *sock = in_dir("sock"), *got = in_dir("from-socket.png");
  int fd = socket(AF_UNIX, SOCK_STREAM, 0);
  struct sockaddr_un addr = {.sun_family = AF_UNIX};
  ck_assert_uint_lt(strlen(sock), sizeof addr.sun_path);
  strcpy(addr.sun_path, sock);
  ck_assert_int_eq(bind(fd, (struct sockaddr *)&addr, sizeof addr), 0);
  ck_assert_int_eq(listen(fd, 1), 0);
  pid_t listener = fork();
  ck_assert_int_ge(listener, 0);
  if (listener == 0) copy_and_exit(accept(fd, NULL, NULL), got);
  close(fd);
  char err[1024];
  ck_assert_int_eq(render_to(sock, NULL, err, sizeof err), 0);
  int status;
  ck_assert_int_eq(waitpid(listener, &status, 0), listener);
  ck_assert(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  struct stat st;
  ck_assert_int_eq(lstat(sock, &st), 0);
  ck_assert(S_ISSOCK(st.st_mode));
  zs_test_assert_same_file(ref, got);
  remove_dir();
}
END_TEST

/* A character device made in the test's own folder (1,3 is the null
 * device; 1,7 the full device): never the machine's /dev/null. */
START_TEST(device_node_written_directly) {
  make_dir();
  const char *null_node = in_dir("null"), *full_node = in_dir("full");
  if (mknod(null_node, S_IFCHR | 0666, makedev(1, 3)) != 0) {
    /* without CAP_MKNOD, the machine's own /dev/full still shows a failed
     * write, and the rest below is covered by the other tests */
    ck_assert_msg(errno == EPERM, "mknod: %s", strerror(errno));
    remove_dir();
    return;
  }
  char err[1024];
  ck_assert_int_eq(render_to(null_node, NULL, err, sizeof err), 0);
  struct stat st;
  ck_assert_int_eq(lstat(null_node, &st), 0);
  ck_assert_msg(S_ISCHR(st.st_mode), "the device node was replaced");
  ck_assert_int_eq(mknod(full_node, S_IFCHR | 0666, makedev(1, 7)), 0);
  ck_assert_int_eq(render_to(full_node, NULL, err, sizeof err), 1);
  ck_assert_msg(strstr(err, "-o ") && strstr(err, "No space left on device"), "%s", err);
  ck_assert_int_eq(lstat(full_node, &st), 0);
  ck_assert(S_ISCHR(st.st_mode));
  assert_no_temporaries();
  remove_dir();
}
END_TEST

START_TEST(full_disk_is_an_error) {
  make_dir();
  char err[1024];
  ck_assert_int_eq(render_to("/dev/full", NULL, err, sizeof err), 1);
  ck_assert_msg(strstr(err, "zscan render: -o /dev/full: cannot write: No space left on device"),
                "%s", err);
  remove_dir();
}
END_TEST

/* The files of one render are replaced together: an output that fails
 * (the depth to the full device) leaves the others' files as they were,
 * and standard output, which cannot be taken back, empty. */
START_TEST(outputs_replace_their_files_together) {
  make_dir();
  char exe[4096], err_path[4200], png[4200], layer[4200], out_path[4200];
  snprintf(exe, sizeof exe, "%s/zscan", ZS_BINARY_DIR);
  snprintf(err_path, sizeof err_path, "%s/stderr.txt", dir);
  snprintf(png, sizeof png, "%s", in_dir("a.png"));
  snprintf(layer, sizeof layer, "%s", in_dir("a.zsl"));
  snprintf(out_path, sizeof out_path, "%s", in_dir("stdout.bin"));
  for (int k = 0; k < 2; k++) {
    FILE *f = fopen(k ? layer : png, "wb");
    ck_assert_ptr_nonnull(f);
    fputs("the old file\n", f);
    fclose(f);
  }
  char *to_files[] = {exe, "render", "builtin:default", "--size", "64x48", "-o", png,
                      "--layer", layer, "--depth", "/dev/full", NULL};
  ck_assert_int_eq(zs_os_spawn_wait(to_files, NULL, err_path), 1);
  size_t n = 0;
  char *said = (char *)zs_test_slurp(err_path, &n);
  ck_assert_ptr_nonnull(said);
  ck_assert_msg(strstr(said, "--depth /dev/full: cannot write: No space left on device"), "%s",
                said);
  free(said);
  for (int k = 0; k < 2; k++) {
    char *text = (char *)zs_test_slurp(k ? layer : png, &n);
    ck_assert_ptr_nonnull(text);
    ck_assert_msg(n == 13 && memcmp(text, "the old file\n", 13) == 0, "%s was replaced",
                  k ? layer : png);
    free(text);
  }
  char *to_stdout[] = {exe, "render", "builtin:default", "--size", "64x48", "-o", "-",
                       "--depth", "/dev/full", NULL};
  ck_assert_int_eq(zs_os_spawn_wait(to_stdout, out_path, err_path), 1);
  unsigned char *sent = zs_test_slurp(out_path, &n);
  ck_assert_ptr_nonnull(sent);
  ck_assert_msg(n == 0, "%zu bytes on standard output before the failure", n);
  free(sent);
  /* and when every output can be written, each is */
  char *all[] = {exe, "render", "builtin:default", "--size", "64x48", "-o", png,
                 "--layer", layer, "-q", NULL};
  ck_assert_int_eq(zs_os_spawn_wait(all, NULL, err_path), 0);
  zs_test_assert_same_file(reference(), png);
  unsigned char *l = zs_test_slurp(layer, &n);
  ck_assert_ptr_nonnull(l);
  ck_assert_int_eq(memcmp(l, "ZSLAYER 1\n", 10), 0);
  free(l);
  unlink(err_path);
  unlink(out_path);
  assert_no_temporaries();
  remove_dir();
}
END_TEST

START_TEST(directory_and_missing_folder_refused) {
  make_dir();
  const char *sub = in_dir("a-folder");
  ck_assert_int_eq(mkdir(sub, 0700), 0);
  char err[1024];
  ck_assert_int_eq(render_to(sub, NULL, err, sizeof err), 1);
  char want[4400];
  snprintf(want, sizeof want, "zscan render: -o %s: is a directory\n", sub);
  ck_assert_str_eq(err, want);
  struct stat st;
  ck_assert_int_eq(stat(sub, &st), 0);
  ck_assert(S_ISDIR(st.st_mode));
  const char *missing = in_dir("no-such-folder/x.png");
  ck_assert_int_eq(render_to(missing, NULL, err, sizeof err), 1);
  snprintf(want, sizeof want, "zscan render: -o %s: no such directory: %s/no-such-folder\n",
           missing, dir);
  ck_assert_str_eq(err, want);
  assert_no_temporaries();
  remove_dir();
}
END_TEST

/* The primitive itself: a discarded write leaves the old file and no
 * temporary; a committed one replaces it whole. */
START_TEST(discard_keeps_the_old_file) {
  make_dir();
  const char *path = in_dir("kept.txt");
  write_text(path, "old\n");
  zs_error err;
  zs_error_clear(&err);
  zs_out o;
  ck_assert_int_eq(zs_out_open(&o, path, &err), ZS_OK);
  fputs("half of something new", o.fp);
  zs_out_discard(&o);
  size_t n;
  unsigned char *b = zs_test_slurp(path, &n);
  ck_assert_int_eq(n, 4);
  ck_assert_int_eq(memcmp(b, "old\n", 4), 0);
  free(b);
  assert_no_temporaries();
  ck_assert_int_eq(zs_out_open(&o, path, &err), ZS_OK);
  fputs("new\n", o.fp);
  ck_assert_int_eq(zs_out_commit(&o, &err), ZS_OK);
  b = zs_test_slurp(path, &n);
  ck_assert_int_eq(memcmp(b, "new\n", 4), 0);
  free(b);
  assert_no_temporaries();
  remove_dir();
}
END_TEST

/* A folder a command fills is made when missing, with its parents. */
START_TEST(folders_made_when_missing) {
  make_dir();
  const char *pngs = in_dir("pictures/of/rows");
  const char *args[] = {"trace", zs_test_src("tests/data/lecture/two_polygons.obj"), "--size", "8x6",
                        "--png-dir", pngs, NULL};
  char out[1 << 14], err[1024];
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  ck_assert_msg(rc == 0, "%s", err);
  ck_assert(zs_test_exists(in_dir("pictures/of/rows/scanline-0000.png")));
  /* a file where the folder should be */
  const char *file = in_dir("plain-file");
  write_text(file, "");
  const char *bad[] = {"trace", zs_test_src("tests/data/lecture/two_polygons.obj"), "--size", "8x6",
                       "--png-dir", file, NULL};
  ck_assert_int_eq(zs_test_run_zscan(bad, out, sizeof out, err, sizeof err), 1);
  ck_assert_msg(strstr(err, "--png-dir ") && strstr(err, ": not a directory"), "%s", err);
  remove_dir();
}
END_TEST

/* walk --csv -: the CSV on standard output, the summary on standard error. */
START_TEST(walk_csv_to_stdout) {
  const char *args[] = {"walk", "builtin:cubes?n=3", "--cull", "vfc", "--frames", "2",
                        "--size", "64x48", "--csv", "-", "--quiet", NULL};
  char out[1 << 14], err[1 << 14];
  int rc = zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
  ck_assert_msg(rc == 0, "%s", err);
  ck_assert_msg(strncmp(out, "frame,method,", 13) == 0, "%s", out);
  ck_assert_ptr_nonnull(strstr(err, "frames at 64x48"));
  const char *two[] = {"walk", "builtin:cubes?n=3", "--cull", "vfc", "--csv", "-", "--md", "-",
                       NULL};
  ck_assert_int_eq(zs_test_run_zscan(two, out, sizeof out, err, sizeof err), 2);
  ck_assert_ptr_nonnull(strstr(err, "only one of --csv, --md, --plot and --tradeoff can be -"));
}
END_TEST

int main(void) {
  signal(SIGPIPE, SIG_IGN);
  Suite *s = suite_create("output");
  TCase *tc = tcase_create("output");
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, stdout_equals_file_byte_for_byte);
  tcase_add_test(tc, symlink_is_followed_and_stays_a_link);
  tcase_add_test(tc, replaced_file_keeps_its_mode);
  tcase_add_test(tc, fifo_written_directly_to_its_reader);
  tcase_add_test(tc, socket_written_directly_to_its_listener);
  tcase_add_test(tc, device_node_written_directly);
  tcase_add_test(tc, full_disk_is_an_error);
  tcase_add_test(tc, outputs_replace_their_files_together);
  tcase_add_test(tc, directory_and_missing_folder_refused);
  tcase_add_test(tc, discard_keeps_the_old_file);
  tcase_add_test(tc, folders_made_when_missing);
  tcase_add_test(tc, walk_csv_to_stdout);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
