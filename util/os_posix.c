/* util/os.h on POSIX systems: the one file that calls them. */
#ifndef _WIN32

#include "util/os.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/utsname.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

static zs_path_kind kind_of(mode_t m) {
  return S_ISREG(m)    ? ZS_PATH_FILE
         : S_ISLNK(m)  ? ZS_PATH_LINK
         : S_ISDIR(m)  ? ZS_PATH_DIR
         : S_ISCHR(m)  ? ZS_PATH_CHAR
         : S_ISFIFO(m) ? ZS_PATH_FIFO
         : S_ISSOCK(m) ? ZS_PATH_SOCKET
         : S_ISBLK(m)  ? ZS_PATH_BLOCK
                       : ZS_PATH_OTHER;
}

static int info_of(int rc, const struct stat *st, zs_path_info *info) {
  *info = (zs_path_info){ZS_PATH_NONE, 0, 0};
  if (rc != 0) return errno == ENOENT ? 0 : errno;
  *info = (zs_path_info){kind_of(st->st_mode), (unsigned)(st->st_mode & 07777),
                         (long long)st->st_size};
  return 0;
}

int zs_os_lstat(const char *path, zs_path_info *info) {
  struct stat st;
  int rc = lstat(path, &st);
  return info_of(rc, &st, info);
}

int zs_os_stat(const char *path, zs_path_info *info) {
  struct stat st;
  int rc = stat(path, &st);
  return info_of(rc, &st, info);
}

int zs_os_fstat(FILE *f, zs_path_info *info) {
  struct stat st;
  int rc = fstat(fileno(f), &st);
  if (rc != 0 && errno == ENOENT) errno = EBADF; /* (an open stream is there) */
  return info_of(rc, &st, info);
}

char *zs_os_readlink(const char *path, int *e) {
  struct stat st;
  if (lstat(path, &st) != 0) {
    *e = errno;
    return NULL;
  }
  size_t cap = st.st_size > 0 ? (size_t)st.st_size + 1 : 4096;
  char *text = malloc(cap);
  if (!text) {
    *e = ENOMEM;
    return NULL;
  }
  ssize_t n = readlink(path, text, cap);
  if (n < 0 || (size_t)n >= cap) {
    *e = n < 0 ? errno : EAGAIN; /* (it changed while read) */
    free(text);
    return NULL;
  }
  text[n] = '\0';
  return text;
}

int zs_os_is_separator(char c) { return c == '/'; }

size_t zs_os_root_length(const char *path) { return path[0] == '/'; }

void zs_os_binary_stream(FILE *f) { (void)f; }

/* A Unix socket, connected to as a stream. */
static int open_socket(const char *path) {
  struct sockaddr_un addr;
  if (strlen(path) >= sizeof addr.sun_path) {
    errno = ENAMETOOLONG;
    return -1;
  }
  int fd = socket(AF_UNIX, SOCK_STREAM, 0);
  if (fd < 0) return -1;
  memset(&addr, 0, sizeof addr);
  addr.sun_family = AF_UNIX;
  strcpy(addr.sun_path, path);
  if (connect(fd, (const struct sockaddr *)&addr, sizeof addr) != 0) {
    int e = errno;
    close(fd);
    errno = e;
    return -1;
  }
  return fd;
}

FILE *zs_os_open_direct(const char *path, zs_path_kind kind, int *e) {
  int fd = kind == ZS_PATH_SOCKET ? open_socket(path) : open(path, O_WRONLY | O_NOCTTY);
  FILE *f = fd >= 0 ? fdopen(fd, "wb") : NULL;
  if (!f) {
    *e = errno;
    if (fd >= 0) close(fd);
  }
  return f;
}

FILE *zs_os_create_beside(const char *path, unsigned mode, char *name, size_t cap, int *e) {
  if ((size_t)snprintf(name, cap, "%s.tmp.XXXXXX", path) >= cap) {
    *e = ENAMETOOLONG;
    return NULL;
  }
  int fd = mkstemp(name);
  if (fd < 0) {
    *e = errno;
    return NULL;
  }
  FILE *f = fchmod(fd, (mode_t)mode) == 0 ? fdopen(fd, "wb") : NULL;
  if (!f) {
    *e = errno;
    close(fd);
    remove(name);
  }
  return f;
}

unsigned zs_os_new_file_mode(void) {
  mode_t mask = umask(0);
  umask(mask);
  return 0666u & ~(unsigned)mask;
}

int zs_os_replace(const char *from, const char *to) { return rename(from, to) == 0 ? 0 : errno; }

int zs_os_dir_writable(const char *dir) { return access(dir, W_OK) == 0 ? 0 : errno; }

int zs_os_mkdir(const char *path) { return mkdir(path, 0777) == 0 ? 0 : errno; }

int zs_os_rmdir(const char *path) { return rmdir(path) == 0 ? 0 : errno; }

int zs_os_readable(const char *path) { return access(path, R_OK) == 0; }

int zs_os_scratch_dir(const char *prefix, char *buf, size_t cap) {
  const char *tmp = getenv("TMPDIR");
  if ((size_t)snprintf(buf, cap, "%s/%s-XXXXXX", tmp && *tmp ? tmp : "/tmp", prefix) >= cap)
    return ENAMETOOLONG;
  return mkdtemp(buf) ? 0 : errno;
}

int zs_os_each_name(const char *dir, int (*each)(const char *name, void *ctx), void *ctx) {
  DIR *d = opendir(dir);
  if (!d) return -errno;
  int rc = 0;
  for (struct dirent *e; rc == 0 && (e = readdir(d)) != NULL;)
    if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0) rc = each(e->d_name, ctx);
  closedir(d);
  return rc;
}

double zs_os_monotonic_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

int zs_os_stderr_is_terminal(void) { return isatty(STDERR_FILENO); }

int zs_os_cpu_count(void) {
  long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n < 1 ? 1 : n > 4096 ? 4096 : (int)n;
}

void zs_os_machine(char *buf, size_t cap) {
  struct utsname u;
  snprintf(buf, cap, "%s", uname(&u) == 0 ? u.machine : "unknown");
}

int zs_os_setenv(const char *name, const char *value) {
  return (value ? setenv(name, value, 1) : unsetenv(name)) == 0 ? 0 : errno;
}

int zs_os_program_available(const char *name) {
  const char *path = getenv("PATH");
  if (!path) return 0;
  char buf[4096];
  snprintf(buf, sizeof buf, "%s", path);
  char *save = NULL;
  for (char *dir = strtok_r(buf, ":", &save); dir; dir = strtok_r(NULL, ":", &save)) {
    char exe[4200];
    snprintf(exe, sizeof exe, "%s/%s", dir, name);
    if (access(exe, X_OK) == 0) return 1;
  }
  return 0;
}

int zs_os_spawn_wait(char *const argv[], const char *out_path, const char *err_path) {
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, out_path ? out_path : "/dev/null",
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (out_path && err_path && strcmp(out_path, err_path) == 0)
    posix_spawn_file_actions_adddup2(&fa, 1, 2); /* one file, one offset */
  else
    posix_spawn_file_actions_addopen(&fa, 2, err_path ? err_path : "/dev/null",
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid;
  int rc = posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

int zs_os_self_path(char *buf, size_t cap) {
  ssize_t n = readlink("/proc/self/exe", buf, cap - 1);
  if (n <= 0) return 0;
  buf[n] = '\0';
  return 1;
}

int zs_memfile_open(zs_memfile *m) {
  *m = (zs_memfile){NULL, NULL, 0};
  m->f = open_memstream(&m->data, &m->size);
  return m->f ? 0 : errno;
}

int zs_memfile_close(zs_memfile *m) {
  int rc = fclose(m->f) == 0 ? 0 : errno;
  m->f = NULL;
  if (rc != 0 || !m->data) {
    free(m->data);
    m->data = NULL;
    m->size = 0;
    return rc ? rc : ENOMEM;
  }
  return 0;
}

#endif
