/* util/os.h on Windows: the one file that calls it (the Win32 API and the
 * C runtime's own _-prefixed calls, as mingw-w64 and MSVC both have them). */
#ifdef _WIN32

#include "util/os.h"

#include <direct.h>
#include <errno.h>
#include <fcntl.h>
#include <io.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <windows.h>

/* A Win32 error as the errno value strerror explains. */
static int errno_of(DWORD code) {
  switch (code) {
    case ERROR_FILE_NOT_FOUND:
    case ERROR_PATH_NOT_FOUND:
    case ERROR_INVALID_DRIVE:
      return ENOENT;
    case ERROR_ACCESS_DENIED:
    case ERROR_SHARING_VIOLATION:
    case ERROR_LOCK_VIOLATION:
      return EACCES;
    case ERROR_ALREADY_EXISTS:
    case ERROR_FILE_EXISTS:
      return EEXIST;
    case ERROR_NOT_ENOUGH_MEMORY:
    case ERROR_OUTOFMEMORY:
      return ENOMEM;
    case ERROR_DISK_FULL:
    case ERROR_HANDLE_DISK_FULL:
      return ENOSPC;
    case ERROR_FILENAME_EXCED_RANGE:
      return ENAMETOOLONG;
    case ERROR_DIRECTORY:
      return ENOTDIR;
    case ERROR_INVALID_NAME:
    case ERROR_BAD_PATHNAME:
      return EINVAL;
    case ERROR_WRITE_PROTECT:
      return EROFS;
    case ERROR_NOT_SAME_DEVICE:
      return EXDEV;
    case ERROR_DIR_NOT_EMPTY:
      return ENOTEMPTY;
    default:
      return EIO;
  }
}

/* The kind of what st describes. */
static void info_of(const struct _stat64 *st, zs_path_info *info) {
  unsigned m = (unsigned)st->st_mode;
  info->kind = (m & _S_IFMT) == _S_IFREG   ? ZS_PATH_FILE
               : (m & _S_IFMT) == _S_IFDIR ? ZS_PATH_DIR
               : (m & _S_IFMT) == _S_IFCHR ? ZS_PATH_CHAR
               : (m & _S_IFMT) == _S_IFIFO ? ZS_PATH_FIFO
                                           : ZS_PATH_OTHER;
  info->mode = (m & _S_IWRITE) ? 0666u : 0444u;
  info->size = (long long)st->st_size;
}

int zs_os_fstat(FILE *f, zs_path_info *info) {
  *info = (zs_path_info){ZS_PATH_NONE, 0, 0};
  struct _stat64 st;
  if (_fstat64(_fileno(f), &st) != 0) return errno;
  info_of(&st, info);
  return 0;
}

int zs_os_is_separator(char c) { return c == '/' || c == '\\'; }

size_t zs_os_root_length(const char *path) {
  const int drive = ((path[0] | 32) >= 'a' && (path[0] | 32) <= 'z') && path[1] == ':';
  if (drive) return zs_os_is_separator(path[2]) ? 3 : 2;
  return zs_os_is_separator(path[0]);
}

/* A device's name (NUL, CON, COM1): the runtime's stat finds no file. */
static int is_device(const char *path) {
  HANDLE h = CreateFileA(path, 0, FILE_SHARE_READ | FILE_SHARE_WRITE, NULL, OPEN_EXISTING, 0, NULL);
  if (h == INVALID_HANDLE_VALUE) return 0;
  const int dev = GetFileType(h) == FILE_TYPE_CHAR;
  CloseHandle(h);
  return dev;
}

int zs_os_stat(const char *path, zs_path_info *info) {
  *info = (zs_path_info){ZS_PATH_NONE, 0, 0};
  /* the runtime's stat finds no "dir/": separators after the root go */
  char trimmed[MAX_PATH + 1];
  size_t n = strlen(path), root = zs_os_root_length(path);
  if (n > root && zs_os_is_separator(path[n - 1])) {
    if (n > MAX_PATH) return ENAMETOOLONG;
    while (n > root && zs_os_is_separator(path[n - 1])) n--;
    memcpy(trimmed, path, n);
    trimmed[n] = '\0';
    path = trimmed;
  }
  struct _stat64 st;
  if (_stat64(path, &st) != 0) {
    if (errno != ENOENT) return errno;
    if (is_device(path)) *info = (zs_path_info){ZS_PATH_CHAR, 0666u, 0};
    return 0;
  }
  info_of(&st, info);
  return 0;
}

/* A symbolic link or junction: a reparse point, which the runtime's
 * calls follow but MoveFileEx would replace. */
int zs_os_lstat(const char *path, zs_path_info *info) {
  DWORD a = GetFileAttributesA(path);
  if (a != INVALID_FILE_ATTRIBUTES && (a & FILE_ATTRIBUTE_REPARSE_POINT)) {
    *info = (zs_path_info){ZS_PATH_LINK, 0666u, 0};
    return 0;
  }
  return zs_os_stat(path, info);
}

/* Windows' answer for a link: the final path of what it leads to, every
 * link on the way followed (so the caller's next look finds no link). */
char *zs_os_readlink(const char *path, int *e) {
  HANDLE h = CreateFileA(path, 0, FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE, NULL,
                         OPEN_EXISTING, FILE_FLAG_BACKUP_SEMANTICS, NULL);
  if (h == INVALID_HANDLE_VALUE) {
    *e = errno_of(GetLastError());
    return NULL;
  }
  char buf[32768];
  DWORD n = GetFinalPathNameByHandleA(h, buf, sizeof buf, FILE_NAME_NORMALIZED | VOLUME_NAME_DOS);
  CloseHandle(h);
  if (n == 0 || n >= sizeof buf) {
    *e = n == 0 ? errno_of(GetLastError()) : ENAMETOOLONG;
    return NULL;
  }
  const char *p = strncmp(buf, "\\\\?\\", 4) == 0 ? buf + 4 : buf; /* (the long-path prefix) */
  char *text = malloc(strlen(p) + 1);
  if (!text) *e = ENOMEM;
  else strcpy(text, p);
  return text;
}

void zs_os_binary_stream(FILE *f) {
  fflush(f);
  _setmode(_fileno(f), _O_BINARY);
}

FILE *zs_os_open_direct(const char *path, zs_path_kind kind, int *e) {
  (void)kind;
  FILE *f = fopen(path, "wb");
  if (!f) *e = errno;
  return f;
}

/* A new file named base followed by .tmp.PID-K for the first K free,
 * into name[cap], opened with the runtime's flags and stdio's mode.  Each
 * is created writable: Windows neither replaces nor removes a read-only
 * file, so a read-only target's own refusal is the error. */
static FILE *create_unique(const char *base, int flags, const char *mode, char *name, size_t cap,
                           int *e) {
  /* _O_EXCL makes each name this process's or an error: try the next */
  DWORD pid = GetCurrentProcessId();
  for (unsigned k = 0; k < 10000; k++) {
    if ((size_t)snprintf(name, cap, "%s.tmp.%lu-%u", base, (unsigned long)pid, k) >= cap) {
      *e = ENAMETOOLONG;
      return NULL;
    }
    int fd = _open(name, flags | _O_CREAT | _O_EXCL | _O_BINARY, _S_IREAD | _S_IWRITE);
    if (fd < 0 && errno == EEXIST) continue;
    if (fd < 0) {
      *e = errno;
      return NULL;
    }
    FILE *f = _fdopen(fd, mode);
    if (!f) {
      *e = errno;
      _close(fd);
      remove(name);
    }
    return f;
  }
  *e = EEXIST;
  return NULL;
}

FILE *zs_os_create_beside(const char *path, unsigned mode, char *name, size_t cap, int *e) {
  (void)mode;
  return create_unique(path, _O_WRONLY, "wb", name, cap, e);
}

unsigned zs_os_new_file_mode(void) { return 0666u; }

int zs_os_replace(const char *from, const char *to) {
  if (MoveFileExA(from, to, MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH)) return 0;
  return errno_of(GetLastError());
}

int zs_os_dir_writable(const char *dir) { return _access(dir, 2) == 0 ? 0 : errno; }

int zs_os_mkdir(const char *path) { return _mkdir(path) == 0 ? 0 : errno; }

int zs_os_rmdir(const char *path) { return _rmdir(path) == 0 ? 0 : errno; }

int zs_os_readable(const char *path) { return _access(path, 4) == 0; }

int zs_os_scratch_dir(const char *prefix, char *buf, size_t cap) {
  char tmp[MAX_PATH + 1];
  DWORD n = GetTempPathA(sizeof tmp, tmp);
  if (n == 0 || n > MAX_PATH) return errno_of(GetLastError());
  DWORD pid = GetCurrentProcessId();
  for (unsigned k = 0; k < 10000; k++) {
    if ((size_t)snprintf(buf, cap, "%s%s-%lu-%u", tmp, prefix, (unsigned long)pid, k) >= cap)
      return ENAMETOOLONG;
    if (_mkdir(buf) == 0) return 0;
    if (errno != EEXIST) return errno;
  }
  return EEXIST;
}

int zs_os_each_name(const char *dir, int (*each)(const char *name, void *ctx), void *ctx) {
  char pattern[MAX_PATH + 3];
  if ((size_t)snprintf(pattern, sizeof pattern, "%s\\*", dir) >= sizeof pattern)
    return -ENAMETOOLONG;
  WIN32_FIND_DATAA d;
  HANDLE h = FindFirstFileA(pattern, &d);
  if (h == INVALID_HANDLE_VALUE) {
    DWORD code = GetLastError();
    return code == ERROR_FILE_NOT_FOUND ? 0 : -errno_of(code);
  }
  int rc = 0;
  do {
    if (strcmp(d.cFileName, ".") != 0 && strcmp(d.cFileName, "..") != 0) rc = each(d.cFileName, ctx);
  } while (rc == 0 && FindNextFileA(h, &d));
  FindClose(h);
  return rc;
}

double zs_os_monotonic_ms(void) {
  LARGE_INTEGER now, hz;
  QueryPerformanceCounter(&now);
  QueryPerformanceFrequency(&hz);
  return (double)(now.QuadPart / hz.QuadPart) * 1e3 +
         (double)(now.QuadPart % hz.QuadPart) * 1e3 / (double)hz.QuadPart;
}

int zs_os_stderr_is_terminal(void) { return _isatty(_fileno(stderr)); }

int zs_os_cpu_count(void) {
  SYSTEM_INFO si;
  GetSystemInfo(&si);
  return si.dwNumberOfProcessors < 1 ? 1 : (int)si.dwNumberOfProcessors;
}

void zs_os_machine(char *buf, size_t cap) {
  SYSTEM_INFO si;
  GetNativeSystemInfo(&si);
  const char *name = si.wProcessorArchitecture == PROCESSOR_ARCHITECTURE_AMD64   ? "x86_64"
                     : si.wProcessorArchitecture == PROCESSOR_ARCHITECTURE_ARM64 ? "aarch64"
                     : si.wProcessorArchitecture == PROCESSOR_ARCHITECTURE_INTEL ? "i686"
                                                                                 : "unknown";
  snprintf(buf, cap, "%s", name);
}

int zs_os_setenv(const char *name, const char *value) {
  return _putenv_s(name, value ? value : "") == 0 ? 0 : EINVAL; /* ("": removed) */
}

/* Whether file is there and not a directory. */
static int is_file(const char *file) {
  DWORD a = GetFileAttributesA(file);
  return a != INVALID_FILE_ATTRIBUTES && !(a & FILE_ATTRIBUTE_DIRECTORY);
}

/* The program name runs as, into exe[cap]: a path, with .exe or as it
 * is, else the first NAME.exe or NAME on the PATH (not the current folder first, as
 * CreateProcess alone would look); 0 when there is none. */
static int find_program(const char *name, char *exe, size_t cap) {
  if (strpbrk(name, "/\\:")) {
    if (snprintf(exe, cap, "%s.exe", name) < (int)cap && is_file(exe)) return 1;
    return snprintf(exe, cap, "%s", name) < (int)cap && is_file(exe);
  }
  const char *path = getenv("PATH");
  if (!path) return 0;
  for (const char *dir = path; *dir;) {
    size_t n = strcspn(dir, ";");
    if (n > 0 && n < 4000) {
      snprintf(exe, cap, "%.*s\\%s.exe", (int)n, dir, name);
      if (is_file(exe)) return 1;
      snprintf(exe, cap, "%.*s\\%s", (int)n, dir, name);
      if (is_file(exe)) return 1;
    }
    dir += n + (dir[n] == ';');
  }
  return 0;
}

int zs_os_program_available(const char *name) {
  char exe[4200];
  return find_program(name, exe, sizeof exe);
}

/* Appends arg to the command line as the C runtime's parser reads it back
 * (quotes around, backslashes before a quote doubled); 0 when it is full. */
static int append_arg(char *line, size_t cap, size_t *len, const char *arg) {
  char *p = line + *len, *end = line + cap - 2; /* (a space and the NUL) */
  if (*len && p < end) *p++ = ' ';
  if (p < end) *p++ = '"';
  for (const char *s = arg;; s++) {
    size_t slashes = 0;
    while (*s == '\\') s++, slashes++;
    /* before a quote or the closing one: doubled, then the quote escaped */
    size_t times = *s == '"' ? 2 * slashes + 1 : *s == '\0' ? 2 * slashes : slashes;
    for (size_t k = 0; k < times && p < end; k++) *p++ = '\\';
    if (*s == '\0') break;
    if (p < end) *p++ = *s;
  }
  if (p >= end) return 0;
  *p++ = '"';
  *p = '\0';
  *len = (size_t)(p - line);
  return 1;
}

/* A handle a child inherits, writing to path (NUL when NULL). */
static HANDLE inheritable_output(const char *path) {
  SECURITY_ATTRIBUTES sa = {sizeof sa, NULL, TRUE};
  return CreateFileA(path ? path : "NUL", GENERIC_WRITE, FILE_SHARE_READ | FILE_SHARE_WRITE, &sa,
                     CREATE_ALWAYS, FILE_ATTRIBUTE_NORMAL, NULL);
}

int zs_os_spawn_wait(char *const argv[], const char *out_path, const char *err_path) {
  static char line[32768]; /* (Windows' own limit on a command line) */
  size_t len = 0;
  line[0] = '\0';
  char exe[4200];
  if (!find_program(argv[0], exe, sizeof exe)) return -1;
  for (int i = 0; argv[i]; i++)
    if (!append_arg(line, sizeof line, &len, argv[i])) return -1;
  HANDLE out = inheritable_output(out_path);
  HANDLE err = out_path && err_path && strcmp(out_path, err_path) == 0 ? out
                                                                       : inheritable_output(err_path);
  STARTUPINFOA si;
  memset(&si, 0, sizeof si);
  si.cb = sizeof si;
  si.dwFlags = STARTF_USESTDHANDLES;
  si.hStdInput = GetStdHandle(STD_INPUT_HANDLE);
  si.hStdOutput = out;
  si.hStdError = err;
  PROCESS_INFORMATION pi;
  int status = -1;
  if (out != INVALID_HANDLE_VALUE && err != INVALID_HANDLE_VALUE &&
      CreateProcessA(exe, line, NULL, NULL, TRUE, 0, NULL, NULL, &si, &pi)) {
    DWORD code;
    if (WaitForSingleObject(pi.hProcess, INFINITE) == WAIT_OBJECT_0 &&
        GetExitCodeProcess(pi.hProcess, &code))
      status = (int)code;
    CloseHandle(pi.hProcess);
    CloseHandle(pi.hThread);
  }
  if (err != out && err != INVALID_HANDLE_VALUE) CloseHandle(err);
  if (out != INVALID_HANDLE_VALUE) CloseHandle(out);
  return status;
}

int zs_os_self_path(char *buf, size_t cap) {
  DWORD n = GetModuleFileNameA(NULL, buf, (DWORD)cap);
  return n > 0 && n < cap;
}

/* No memory stream in the C runtime: a temporary file in the temporary
 * folder (tmpfile() would make it in the drive's root, closed to most
 * users), removed when closed, read back. */
int zs_memfile_open(zs_memfile *m) {
  *m = (zs_memfile){NULL, NULL, 0};
  char dir[MAX_PATH + 1], base[MAX_PATH + 16], name[MAX_PATH + 64];
  DWORD n = GetTempPathA(sizeof dir, dir);
  if (n == 0 || n > MAX_PATH) return errno_of(GetLastError());
  snprintf(base, sizeof base, "%szscan-text", dir);
  int e = 0;
  m->f = create_unique(base, _O_RDWR | _O_TEMPORARY, "w+b", name, sizeof name, &e);
  return m->f ? 0 : e;
}

int zs_memfile_close(zs_memfile *m) {
  int rc = 0;
  long long n = fflush(m->f) == 0 && !ferror(m->f) ? _ftelli64(m->f) : -1;
  if (n < 0 || fseek(m->f, 0, SEEK_SET) != 0) rc = errno ? errno : EIO;
  if (!rc && !(m->data = malloc((size_t)n + 1))) rc = ENOMEM;
  if (!rc && fread(m->data, 1, (size_t)n, m->f) != (size_t)n) rc = EIO;
  fclose(m->f);
  m->f = NULL;
  if (rc) {
    free(m->data);
    m->data = NULL;
    m->size = 0;
    return rc;
  }
  m->data[n] = '\0';
  m->size = (size_t)n;
  return 0;
}

#endif
