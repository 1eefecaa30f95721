/* zscan util — what zscan asks of the operating system, and nothing else.
 *
 * Every call that is not standard C stands behind these functions, in one
 * file a system: util/os_posix.c (Linux, the BSDs, macOS, musl) and
 * util/os_win32.c (Windows: mingw-w64, and written for MSVC too).  Each
 * compiles to nothing on the other.  The rest of zscan, library and
 * command alike, includes no system header beyond the C library's.
 *
 * Errors come back as errno values (0: success), so messages read the
 * same on both (strerror). */
#ifndef ZS_UTIL_OS_H
#define ZS_UTIL_OS_H

#include <stddef.h>
#include <stdio.h>

/* What stands at a path. */
typedef enum zs_path_kind {
  ZS_PATH_NONE,   /* nothing */
  ZS_PATH_FILE,   /* a regular file */
  ZS_PATH_LINK,   /* a symbolic link (never on Windows: its calls follow them) */
  ZS_PATH_DIR,    /* a directory */
  ZS_PATH_CHAR,   /* a character device (/dev/null, NUL, CON) */
  ZS_PATH_FIFO,   /* a named pipe */
  ZS_PATH_SOCKET, /* a Unix socket */
  ZS_PATH_BLOCK,  /* a block device */
  ZS_PATH_OTHER
} zs_path_kind;

typedef struct zs_path_info {
  zs_path_kind kind;
  unsigned mode;      /* the permission bits (07777; Windows: 0666 or 0444) */
  long long size;     /* bytes (a link: its text's length) */
} zs_path_info;

/* What is at path, the last link not followed (lstat); kind NONE and 0
 * when nothing is there, else an errno value. */
int zs_os_lstat(const char *path, zs_path_info *info);

/* The same, every link followed (stat). */
int zs_os_stat(const char *path, zs_path_info *info);

/* What the open stream f reads (fstat); 0 or an errno value. */
int zs_os_fstat(FILE *f, zs_path_info *info);

/* A link's text (malloc'd), or NULL with *e set. */
char *zs_os_readlink(const char *path, int *e);

/* Whether the separator of path names at c ('/', and '\\' on Windows). */
int zs_os_is_separator(char c);

/* The length of path's root: "/" (1); on Windows also "C:\\" (3), "C:" (2),
 * "\\" (1); 0 for a relative path. */
size_t zs_os_root_length(const char *path);

/* Stream f (stdout, stderr) takes bytes as they are (Windows: no CR
 * before each LF). */
void zs_os_binary_stream(FILE *f);

/* Opens a device, FIFO or socket for writing as it is (no temporary). */
FILE *zs_os_open_direct(const char *path, zs_path_kind kind, int *e);

/* Creates a new file named path followed by a unique suffix of the
 * system's choosing, written into name[cap]; with permission bits mode
 * (Windows: always writable).  NULL with *e set on failure. */
FILE *zs_os_create_beside(const char *path, unsigned mode, char *name, size_t cap, int *e);

/* The permission bits a new file gets (0666 less the umask). */
unsigned zs_os_new_file_mode(void);

/* Renames from over to, replacing it in one step; 0 or an errno value. */
int zs_os_replace(const char *from, const char *to);

/* 0 when files can be created in directory dir, else an errno value. */
int zs_os_dir_writable(const char *dir);

/* Creates directory path; 0, or an errno value (EEXIST when something is
 * there already). */
int zs_os_mkdir(const char *path);

/* Removes an empty directory; 0 or an errno value. */
int zs_os_rmdir(const char *path);

/* Whether a file can be read at path. */
int zs_os_readable(const char *path);

/* A new private folder in the system's temporary folder (TMPDIR, else
 * /tmp; on Windows its temporary folder), named PREFIX-unique, into
 * buf[cap]; 0 or an errno value. */
int zs_os_scratch_dir(const char *prefix, char *buf, size_t cap);

/* The names in directory dir (not . and ..), given to each in turn; each
 * returns 0 to go on.  0, each's first non-zero, or an errno value
 * (negated, so a caller tells the two apart) when dir cannot be read. */
int zs_os_each_name(const char *dir, int (*each)(const char *name, void *ctx), void *ctx);

/* A steady clock's milliseconds (for wall times only: never an output). */
double zs_os_monotonic_ms(void);

/* Whether standard error is a terminal. */
int zs_os_stderr_is_terminal(void);

/* The number of processors online (at least 1). */
int zs_os_cpu_count(void);

/* The processor's architecture as uname -m names it ("x86_64", "aarch64"). */
void zs_os_machine(char *buf, size_t cap);

/* Sets environment variable name to value (unsets it: NULL), for this
 * process and the programs it starts; 0 or an errno value. */
int zs_os_setenv(const char *name, const char *value);

/* Whether an executable of that name is on the PATH. */
int zs_os_program_available(const char *name);

/* Runs argv[0] (looked up on the PATH) with argv as they are (no shell),
 * its standard output and error to the files named (discarded when NULL;
 * the same name for both: one file, in order), and waits.  Its exit
 * status, or -1 when it could not be started or did not exit. */
int zs_os_spawn_wait(char *const argv[], const char *out_path, const char *err_path);

/* The path of this very program (to run it again as a child), into
 * buf[cap]; 0 when it cannot be found. */
int zs_os_self_path(char *buf, size_t cap);

/* A stream whose bytes are kept in memory: written with stdio, then
 * closed with zs_memfile_close, which hands over the bytes. */
typedef struct zs_memfile {
  FILE *f;     /* where to write; NULL when it could not be opened */
  char *data;  /* after the close: the bytes, NUL-terminated (malloc'd) */
  size_t size; /* after the close: their count */
} zs_memfile;

/* 0, or an errno value (f is NULL then). */
int zs_memfile_open(zs_memfile *m);

/* Closes m->f; 0 with data and size set, or an errno value (data NULL). */
int zs_memfile_close(zs_memfile *m);

#endif
