#include "tests/testutil.h"

#include <math.h>

#include <stdlib.h>
#include <string.h>

#include <stdio.h>

int zs_test_run(Suite *s) {
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_ENV);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed == 0 ? 0 : 1;
}

const char *zs_test_src(const char *rel) {
  static char buf[4096];
  snprintf(buf, sizeof buf, "%s/%s", ZS_SOURCE_DIR, rel);
  return buf;
}

const char *zs_test_bin(const char *rel) {
  static char buf[4096];
  snprintf(buf, sizeof buf, "%s/%s", ZS_BINARY_DIR, rel);
  return buf;
}

uint64_t zs_test_fnv1a(const void *data, size_t n) {
  const unsigned char *p = data;
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < n; i++) {
    h ^= p[i];
    h *= 0x100000001b3ull;
  }
  return h;
}

unsigned char *zs_test_slurp(const char *path, size_t *n) {
  FILE *f = fopen(path, "rb");
  ck_assert_msg(f != NULL, "%s: cannot open", path);
  size_t cap = 1 << 16, len = 0, got;
  unsigned char *b = malloc(cap);
  ck_assert_ptr_nonnull(b);
  while ((got = fread(b + len, 1, cap - len, f)) > 0) {
    len += got;
    if (len == cap) {
      b = realloc(b, cap *= 2);
      ck_assert_ptr_nonnull(b);
    }
  }
  fclose(f);
  b[len] = '\0'; /* the loop leaves len < cap */
  *n = len;
  return b;
}

void zs_test_assert_same_file(const char *a, const char *b) {
  size_t na, nb;
  unsigned char *x = zs_test_slurp(a, &na), *y = zs_test_slurp(b, &nb);
  ck_assert_msg(na == nb && na > 0 && memcmp(x, y, na) == 0,
                "%s (%zu bytes) and %s (%zu bytes) differ", a, na, b, nb);
  free(x);
  free(y);
}

uint64_t zs_test_hash_values(const uint64_t *v, size_t n) {
  unsigned char b[8];
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < n; i++) {
    for (int k = 0; k < 8; k++) b[k] = (unsigned char)(v[i] >> (8 * k));
    for (int k = 0; k < 8; k++) {
      h ^= b[k];
      h *= 0x100000001b3ull;
    }
  }
  return h;
}

/* The golden file's lines, at most this many of this length. */
enum { GOLDEN_LINES = 1024, GOLDEN_LINE = 256 };

static int golden_read(const char *file, char (*lines)[GOLDEN_LINE]) {
  char rel[256];
  snprintf(rel, sizeof rel, "tests/golden/%s", file);
  FILE *f = fopen(zs_test_src(rel), "r");
  int n = 0;
  while (f && n < GOLDEN_LINES && fgets(lines[n], GOLDEN_LINE, f)) n++;
  if (f) fclose(f);
  return n;
}

/* The line of name among lines[0..n-1], or -1. */
static int golden_find(char (*lines)[GOLDEN_LINE], int n, const char *name) {
  const size_t len = strlen(name);
  for (int i = 0; i < n; i++)
    if (strncmp(lines[i], name, len) == 0 && lines[i][len] == ' ') return i;
  return -1;
}

/* The pixel version a golden line's value was made at: its third field
 * (zscan.h, ZSCAN_PIXEL_VERSION), 0 when it has none. */
static int golden_line_version(const char *line) {
  const char *sp = strchr(line, ' ');
  sp = sp ? strchr(sp + 1, ' ') : NULL;
  return sp ? atoi(sp + 1) : 0;
}

/* Writes name's value with the pixel version it is made at; a value that
 * changes is refused unless the pixel version was raised since it was
 * written (the suite is frozen at its versions: an output does not change
 * without the number). */
static void golden_store(const char *file, const char *name, uint64_t got) {
  static char lines[GOLDEN_LINES][GOLDEN_LINE];
  int n = golden_read(file, lines), i = golden_find(lines, n, name);
  ck_assert_msg(i >= 0 || n < GOLDEN_LINES, "tests/golden/%s: full", file);
  if (i >= 0 && strtoull(lines[i] + strlen(name) + 1, NULL, 16) != got)
    ck_assert_msg(golden_line_version(lines[i]) < ZSCAN_PIXEL_VERSION,
                  "%s changed (to %016llx) at pixel version %d: raise ZSCAN_PIXEL_VERSION "
                  "(include/zscan/zscan.h) and say what changed in docs/CHANGES.md and "
                  "zs_pixel_changes (lib/api.c)", name, (unsigned long long)got,
                  golden_line_version(lines[i]));
  else if (i >= 0)
    return; /* the same value, made when its line says */
  if (i < 0) i = n++;
  snprintf(lines[i], GOLDEN_LINE, "%s %016llx %d\n", name, (unsigned long long)got,
           ZSCAN_PIXEL_VERSION);
  char rel[256], path[4096], tmp[4200];
  snprintf(rel, sizeof rel, "tests/golden/%s", file);
  snprintf(path, sizeof path, "%s", zs_test_src(rel));
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  FILE *f = fopen(tmp, "w");
  ck_assert_msg(f != NULL, "%s: cannot write", tmp);
  for (int k = 0; k < n; k++) fputs(lines[k], f);
  ck_assert_msg(fclose(f) == 0 && rename(tmp, path) == 0, "%s: cannot write", path);
}

int zs_golden_check(const char *file, const char *name, uint64_t got, uint64_t *want) {
  if (getenv("ZS_GOLDEN_UPDATE")) {
    golden_store(file, name, got);
    if (want) *want = got;
    return 1;
  }
  static char lines[GOLDEN_LINES][GOLDEN_LINE];
  int n = golden_read(file, lines), i = golden_find(lines, n, name);
  if (i < 0) return -1;
  ck_assert_msg(golden_line_version(lines[i]) <= ZSCAN_PIXEL_VERSION,
                "tests/golden/%s: %s made at pixel version %d, after the library's %d", file, name,
                golden_line_version(lines[i]), ZSCAN_PIXEL_VERSION);
  unsigned long long v = strtoull(lines[i] + strlen(name) + 1, NULL, 16);
  if (want) *want = v;
  return v == got;
}

void zs_golden_assert(const char *file, const char *name, uint64_t got) {
  uint64_t want = 0;
  int r = zs_golden_check(file, name, got, &want);
  ck_assert_msg(r >= 0, "%s: not in tests/golden/%s (run with ZS_GOLDEN_UPDATE=1)", name, file);
  ck_assert_msg(r == 1, "%s: %016llx, golden %016llx (tests/golden/%s)", name,
                (unsigned long long)got, (unsigned long long)want, file);
}

#include <dirent.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/os.h"

static void slurp(const char *path, char *buf, size_t cap) {
  buf[0] = '\0';
  FILE *f = fopen(path, "rb");
  if (!f) return;
  size_t n = fread(buf, 1, cap - 1, f);
  buf[n] = '\0';
  fclose(f);
}

int zs_test_run_zscan(const char *const *args, char *out, size_t out_cap, char *err,
                      size_t err_cap) {
  char exe[4096], out_path[4200], err_path[4200];
  snprintf(exe, sizeof exe, "%s/zscan", ZS_BINARY_DIR);
  snprintf(out_path, sizeof out_path, "%s/zscan-test-%d.out", ZS_BINARY_DIR, (int)getpid());
  snprintf(err_path, sizeof err_path, "%s/zscan-test-%d.err", ZS_BINARY_DIR, (int)getpid());
  const char *argv[64];
  int n = 0;
  argv[n++] = exe;
  for (int i = 0; args[i] && n < 63; i++) argv[n++] = args[i];
  argv[n] = NULL;
  int rc = zs_os_spawn_wait((char *const *)argv, out_path, err_path);
  if (out) slurp(out_path, out, out_cap);
  if (err) slurp(err_path, err, err_cap);
  unlink(out_path);
  unlink(err_path);
  return rc;
}

size_t zs_test_read(const char *path, char *buf, size_t cap) {
  FILE *f = fopen(path, "rb");
  ck_assert_msg(f != NULL, "%s: cannot open", path);
  size_t n = fread(buf, 1, cap - 1, f);
  buf[n] = '\0';
  fclose(f);
  return n;
}

int zs_test_exists(const char *path) {
  struct stat st;
  return stat(path, &st) == 0;
}

void zs_test_each_file(const char *dir, const char *const *suffixes, int n,
                       void (*fn)(const char *path, void *user), void *user) {
  DIR *d = opendir(dir);
  if (!d) return;
  for (struct dirent *e; (e = readdir(d));) {
    if (e->d_name[0] == '.') continue;
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    struct stat st;
    if (stat(path, &st) != 0) continue;
    if (S_ISDIR(st.st_mode)) {
      zs_test_each_file(path, suffixes, n, fn, user);
      continue;
    }
    size_t len = strlen(e->d_name);
    for (int k = 0; k < n; k++) {
      size_t m = strlen(suffixes[k]);
      if (len > m && strcasecmp(e->d_name + len - m, suffixes[k]) == 0) {
        fn(path, user);
        break;
      }
    }
  }
  closedir(d);
}

/* ---- meshes built by hand ---- */

int32_t mb_vert(mesh_buf *b, double x, double y, double z) {
  if (b->m.nverts == b->cap_v) {
    b->cap_v = b->cap_v ? 2 * b->cap_v : 64;
    b->m.pos = realloc(b->m.pos, (size_t)b->cap_v * 3 * sizeof(double));
  }
  double *p = &b->m.pos[3 * b->m.nverts];
  p[0] = x;
  p[1] = y;
  p[2] = z;
  return b->m.nverts++;
}

void mb_face(mesh_buf *b, const int32_t *v, int n, uint32_t rgb) {
  if (b->m.nfaces + 1 >= b->cap_f) {
    b->cap_f = b->cap_f ? 2 * b->cap_f : 64;
    b->m.face_start = realloc(b->m.face_start, (size_t)(b->cap_f + 1) * sizeof(int32_t));
    b->m.face_rgb = realloc(b->m.face_rgb, (size_t)b->cap_f * sizeof(uint32_t));
    if (b->m.nfaces == 0) b->m.face_start[0] = 0;
  }
  int32_t s = b->m.face_start[b->m.nfaces];
  if (s + n > b->cap_fv) {
    while (s + n > b->cap_fv) b->cap_fv = b->cap_fv ? 2 * b->cap_fv : 256;
    b->m.face_vert = realloc(b->m.face_vert, (size_t)b->cap_fv * sizeof(int32_t));
  }
  memcpy(&b->m.face_vert[s], v, (size_t)n * sizeof(int32_t));
  b->m.face_rgb[b->m.nfaces] = rgb;
  b->m.nfaces++;
  b->m.face_start[b->m.nfaces] = s + n;
}

void mb_free(mesh_buf *b) {
  free(b->m.pos);
  free(b->m.face_start);
  free(b->m.face_vert);
  free(b->m.face_rgb);
  memset(b, 0, sizeof *b);
}


void mb_fan(mesh_buf *b, double cx, double cy, double r, int n) {
  int32_t c = mb_vert(b, cx, cy, 0);
  int32_t first = b->m.nverts;
  for (int i = 0; i < n; i++) {
    double a = 2 * ZS_PI * i / n;
    mb_vert(b, cx + r * cos(a), cy + r * sin(a), 0);
  }
  for (int i = 0; i < n; i++) {
    int32_t v[3] = {c, first + i, first + (i + 1) % n};
    mb_face(b, v, 3, 0xFFFFFF);
  }
}

void mb_sphere(mesh_buf *b, double cx, double cy, double cz, double r, int slices, int stacks,
               int inward) {
  int32_t top = mb_vert(b, cx, cy + r, cz);
  for (int i = 1; i < stacks; i++)
    for (int j = 0; j < slices; j++) {
      double phi = ZS_PI * i / stacks, th = 2 * ZS_PI * j / slices;
      mb_vert(b, cx + r * sin(phi) * cos(th), cy + r * cos(phi), cz + r * sin(phi) * sin(th));
    }
  int32_t bottom = mb_vert(b, cx, cy - r, cz);
#define RING(i, j) (top + 1 + (i) * slices + ((j) % slices))
  for (int j = 0; j < slices; j++) {
    int32_t t[3] = {top, RING(0, j + 1), RING(0, j)};
    int32_t u[3] = {bottom, RING(stacks - 2, j), RING(stacks - 2, j + 1)};
    if (inward) {
      int32_t s = t[1];
      t[1] = t[2];
      t[2] = s;
      s = u[1];
      u[1] = u[2];
      u[2] = s;
    }
    mb_face(b, t, 3, 0xFFFFFF);
    mb_face(b, u, 3, 0xFFFFFF);
  }
  for (int i = 0; i + 1 < stacks - 1; i++)
    for (int j = 0; j < slices; j++) {
      int32_t q[4] = {RING(i, j), RING(i, j + 1), RING(i + 1, j + 1), RING(i + 1, j)};
      if (inward) {
        int32_t s = q[1];
        q[1] = q[3];
        q[3] = s;
      }
      mb_face(b, q, 4, 0xFFFFFF);
    }
#undef RING
}
