/* Tests of scene/texture_file.c (textures from PNG and JPEG files), of
 * util/texture.c's mip chain, and of what scene/load_assimp.c reads of a
 * model's shading: normals, colours, texture coordinates, materials and
 * their textures.  The images are tests/data/textures (made by make.py
 * there, with cjpeg and djpeg for the JPEGs); files written go below the
 * build directory, in test_texture_out/.
 *
 * The SIMD check runs this program again (a child process) with
 * libjpeg-turbo's JSIMD_FORCENONE or JSIMD_FORCESSE2 set, which the
 * library reads once, when it first decodes: "test_texture --texel-hash
 * FILE" prints the hash of FILE's texels and exits. */
#include "tests/testutil.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "scene/load_assimp.h"
#include "scene/model.h"
#include "scene/texture_file.h"

#define ASSIMP_MODELS "/usr/share/assimp/models"

enum { PATH_LEN = 4096 };

/* ---- Helpers ---- */

/* tests/data/textures/name, into buf. */
static const char *data(char *buf, const char *name) {
  char rel[512];
  snprintf(rel, sizeof rel, "tests/data/textures/%s", name);
  snprintf(buf, PATH_LEN, "%s", zs_test_src(rel));
  return buf;
}

/* The directory of this suite's files, created on first use. */
static const char *out_dir(void) {
  static char dir[PATH_LEN];
  if (!dir[0]) {
    snprintf(dir, sizeof dir, "%s", zs_test_bin("test_texture_out"));
    if (mkdir(dir, 0777) != 0 && errno != EEXIST)
      ck_abort_msg("cannot create %s: %s", dir, strerror(errno));
  }
  return dir;
}

static void spit(const char *path, const void *bytes, size_t n) {
  FILE *fp = fopen(path, "wb");
  ck_assert_msg(fp != NULL, "%s: %s", path, strerror(errno));
  ck_assert_uint_eq(fwrite(bytes, 1, n, fp), n);
  ck_assert_int_eq(fclose(fp), 0);
}

static zs_texture *load(const char *path) {
  zs_texture *t = NULL;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_texture_load(path, &t, &err) == ZS_OK, "%s", err.msg);
  ck_assert_ptr_nonnull(t);
  return t;
}

/* Level 0 of t is w x h and holds exactly want (w * h * 4 bytes). */
static void expect_texels(const zs_texture *t, int w, int h, const uint8_t *want) {
  int tw, th;
  const uint8_t *p = zs_texture_level(t, 0, &tw, &th);
  ck_assert_int_eq(tw, w);
  ck_assert_int_eq(th, h);
  for (int i = 0; i < 4 * w * h; i++)
    ck_assert_msg(p[i] == want[i], "texel %d channel %d: %d, expected %d", i / 4, i % 4, p[i],
                  want[i]);
}

static uint64_t texel_hash(const zs_texture *t) {
  int w, h;
  const uint8_t *p = zs_texture_level(t, 0, &w, &h);
  uint64_t v[3] = {(uint64_t)w, (uint64_t)h, zs_test_fnv1a(p, 4 * (size_t)w * (size_t)h)};
  return zs_test_hash_values(v, 3);
}

/* The refusal of path by zs_texture_load (and of its bytes by
 * zs_texture_decode, under the name "embedded", when it can be read):
 * code, and the message "PATH" + tail. */
static void expect_refused(const char *path, zs_status code, const char *tail) {
  zs_texture *t = (zs_texture *)&t;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_texture_load(path, &t, &err), code);
  ck_assert_ptr_null(t);
  char want[PATH_LEN + 256];
  snprintf(want, sizeof want, "%s%s", path, tail);
  ck_assert_str_eq(err.msg, want);
  if (code == ZS_ERR_IO) return;
  size_t n;
  unsigned char *bytes = zs_test_slurp(path, &n);
  zs_error_clear(&err);
  t = (zs_texture *)&t;
  ck_assert_int_eq(zs_texture_decode(bytes, n, "embedded", &t, &err), code);
  ck_assert_ptr_null(t);
  snprintf(want, sizeof want, "embedded%s", tail);
  ck_assert_str_eq(err.msg, want);
  free(bytes);
}

/* A binary PPM (P6) or PGM (P5) as RGBA texels, opaque: what djpeg wrote. */
static uint8_t *read_pnm(const char *path, int *w, int *h) {
  size_t n;
  unsigned char *b = zs_test_slurp(path, &n);
  int maxval, off = 0, grey = b[1] == '5';
  ck_assert_msg(sscanf((char *)b, "P%*c %d %d %d%n", w, h, &maxval, &off) == 3, "%s", path);
  ck_assert_int_eq(maxval, 255);
  off++; /* the one blank after the header */
  const size_t count = (size_t)*w * (size_t)*h, per = grey ? 1 : 3;
  ck_assert_uint_eq(n, (size_t)off + per * count);
  uint8_t *rgba = malloc(4 * count);
  ck_assert_ptr_nonnull(rgba);
  for (size_t i = 0; i < count; i++) {
    for (int c = 0; c < 3; c++) rgba[4 * i + c] = b[off + per * i + (grey ? 0 : c)];
    rgba[4 * i + 3] = 255;
  }
  free(b);
  return rgba;
}

/* ---- PNG ---- */

START_TEST(png_rgba8_as_stored) {
  /* its gAMA of 1.0 changes nothing: the texels are the file's values */
  char path[PATH_LEN];
  zs_texture *t = load(data(path, "rgba8.png"));
  const uint8_t want[] = {255, 0, 0,   255, 0,   255, 0,   128, 0,   0,   255, 0,
                          1,   2, 3,   4,   128, 128, 128, 255, 250, 251, 252, 253};
  expect_texels(t, 3, 2, want);
  ck_assert_int_eq(zs_texture_levels(t), 2);
  zs_texture_destroy(t);
}
END_TEST

START_TEST(png_16_bit_scaled_without_gamma) {
  /* 0x8080 reads 0x80: no linear-light guess for a 16-bit file without
   * gAMA (libpng's simplified API would give 0xBC); the others rounded,
   * (v * 255 + 32895) >> 16 */
  char path[PATH_LEN];
  zs_texture *t = load(data(path, "rgba16.png"));
  const uint8_t want[] = {0x80, 0x80, 0x80, 0x80, 0xFF, 0x00, 0x12, 0xFF,
                          0x00, 0x00, 0xFF, 0xFF, 0x40, 0xBF, 0x80, 0x7F};
  expect_texels(t, 2, 2, want);
  zs_texture_destroy(t);
}
END_TEST

START_TEST(png_palette_and_grey) {
  char path[PATH_LEN];
  zs_texture *t = load(data(path, "palette.png"));
  const uint8_t pal[] = {10, 20, 30, 255, 200, 100, 50, 0x40, 0, 0, 0, 255, 255, 255, 255, 255};
  expect_texels(t, 4, 1, pal);
  zs_texture_destroy(t);
  t = load(data(path, "greya.png"));
  const uint8_t grey[] = {0x33, 0x33, 0x33, 0x80, 0xCC, 0xCC, 0xCC, 0xFF};
  expect_texels(t, 2, 1, grey);
  zs_texture_destroy(t);
}
END_TEST

START_TEST(decode_equals_load) {
  static const char *const names[] = {"rgba8.png", "palette.png", "tex.jpg", "prog.jpg"};
  for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
    char path[PATH_LEN];
    zs_texture *a = load(data(path, names[i]));
    size_t n;
    unsigned char *bytes = zs_test_slurp(path, &n);
    zs_texture *b = NULL;
    zs_error err;
    zs_error_clear(&err);
    ck_assert_msg(zs_texture_decode(bytes, n, names[i], &b, &err) == ZS_OK, "%s", err.msg);
    ck_assert_uint_eq(texel_hash(a), texel_hash(b));
    free(bytes);
    zs_texture_destroy(a);
    zs_texture_destroy(b);
  }
}
END_TEST

/* ---- JPEG ---- */

START_TEST(jpeg_texels_are_djpegs) {
  /* libjpeg-turbo's own djpeg -dct int (accurate integer IDCT, fancy
   * upsampling) wrote the reference: 4:2:0 colour, grey, progressive */
  static const char *const pairs[][2] = {{"tex.jpg", "tex-djpeg.ppm"},
                                         {"big.jpg", "big-djpeg.ppm"},
                                         {"prog.jpg", "prog-djpeg.ppm"},
                                         {"grey.jpg", "grey-djpeg.pgm"}};
  for (size_t i = 0; i < sizeof pairs / sizeof *pairs; i++) {
    char path[PATH_LEN];
    int w, h;
    uint8_t *want = read_pnm(data(path, pairs[i][1]), &w, &h);
    zs_texture *t = load(data(path, pairs[i][0]));
    expect_texels(t, w, h, want);
    free(want);
    zs_texture_destroy(t);
  }
  /* and a few texels written out: the bands' corners, the gradient */
  char path[PATH_LEN];
  zs_texture *t = load(data(path, "tex.jpg"));
  int w, h;
  const uint8_t *p = zs_texture_level(t, 0, &w, &h);
  const uint8_t first[] = {0xFF, 0x01, 0x00, 0xFF, 0xFA, 0x00, 0x00, 0xFF};
  ck_assert_mem_eq(p, first, sizeof first);
  ck_assert_int_eq(zs_texture_levels(t), 5); /* 19x13 9x6 4x3 2x1 1x1 */
  zs_texture_destroy(t);
}
END_TEST

/* The texel hash of path decoded by a child process with the variable
 * var set to 1 (NULL: every JSIMD_ variable unset). */
static uint64_t child_hash(const char *path, const char *var) {
  int fd[2];
  ck_assert_int_eq(pipe(fd), 0);
  char self[PATH_LEN];
  snprintf(self, sizeof self, "%s", zs_test_bin("test_texture"));
  pid_t pid = fork();
  ck_assert_int_ge(pid, 0);
  if (pid == 0) {
    static const char *const vars[] = {"JSIMD_FORCENONE", "JSIMD_FORCESSE2", "JSIMD_FORCEAVX2",
                                       "JSIMD_FORCESSE", "JSIMD_FORCEMMX"};
    for (size_t i = 0; i < sizeof vars / sizeof *vars; i++) unsetenv(vars[i]);
    if (var) setenv(var, "1", 1);
    dup2(fd[1], 1);
    close(fd[0]);
    close(fd[1]);
    execl(self, self, "--texel-hash", path, (char *)NULL);
    _exit(127);
  }
  close(fd[1]);
  char out[64] = "";
  size_t n = 0;
  for (ssize_t got; n + 1 < sizeof out && (got = read(fd[0], out + n, sizeof out - 1 - n)) > 0;)
    n += (size_t)got;
  out[n] = '\0';
  close(fd[0]);
  int status;
  ck_assert_int_eq(waitpid(pid, &status, 0), pid);
  ck_assert_msg(WIFEXITED(status) && WEXITSTATUS(status) == 0, "%s --texel-hash %s (%s): %s",
                self, path, var ? var : "SIMD", out);
  return strtoull(out, NULL, 16);
}

START_TEST(jpeg_simd_and_plain_agree) {
  static const char *const names[] = {"big.jpg", "prog.jpg", "tex.jpg", "grey.jpg"};
  for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
    char path[PATH_LEN];
    data(path, names[i]);
    zs_texture *t = load(path);
    const uint64_t here = texel_hash(t);
    zs_texture_destroy(t);
    const uint64_t simd = child_hash(path, NULL);
    ck_assert_msg(simd == here, "%s: %016llx with SIMD, %016llx here", names[i],
                  (unsigned long long)simd, (unsigned long long)here);
    const uint64_t plain = child_hash(path, "JSIMD_FORCENONE");
    ck_assert_msg(plain == here, "%s: %016llx without SIMD, %016llx with", names[i],
                  (unsigned long long)plain, (unsigned long long)here);
    const uint64_t sse2 = child_hash(path, "JSIMD_FORCESSE2");
    ck_assert_msg(sse2 == here, "%s: %016llx with SSE2 only, %016llx with all", names[i],
                  (unsigned long long)sse2, (unsigned long long)here);
  }
}
END_TEST

/* ---- Refusals ---- */

START_TEST(refused_inputs) {
  char path[PATH_LEN];
  expect_refused(data(path, "corrupt.png"), ZS_ERR_PARSE, ": corrupt PNG: IDAT: CRC error");
  expect_refused(data(path, "truncated.png"), ZS_ERR_PARSE,
                 ": corrupt PNG: unexpected end of file");
  expect_refused(data(path, "toolarge.png"), ZS_ERR_LIMIT,
                 ": 8193x1 texture: each side must be 1 to 8192");
  expect_refused(data(path, "truncated.jpg"), ZS_ERR_PARSE,
                 ": corrupt JPEG: Premature end of JPEG file");
  expect_refused(data(path, "extraneous.jpg"), ZS_ERR_PARSE,
                 ": corrupt JPEG: Corrupt JPEG data: 1 extraneous bytes before marker 0xd9");
  expect_refused(data(path, "noimage.jpg"), ZS_ERR_PARSE,
                 ": corrupt JPEG: JPEG datastream contains no image");
  expect_refused(data(path, "toolarge.jpg"), ZS_ERR_LIMIT,
                 ": 19x9000 texture: each side must be 1 to 8192");
  expect_refused(data(path, "make.py"), ZS_ERR_PARSE, ": not a PNG or JPEG image");
  expect_refused(data(path, "missing.png"), ZS_ERR_IO, ": cannot open: No such file or directory");
  expect_refused(out_dir(), ZS_ERR_IO, ": cannot read: Is a directory");
  /* empty, and shorter than a signature */
  char empty[PATH_LEN];
  snprintf(empty, sizeof empty, "%s/empty.png", out_dir());
  spit(empty, "", 0);
  expect_refused(empty, ZS_ERR_PARSE, ": not a PNG or JPEG image");
  spit(empty, "\x89PN", 3);
  expect_refused(empty, ZS_ERR_PARSE, ": not a PNG or JPEG image");
  /* a signature alone */
  spit(empty, "\xFF\xD8\xFF", 3);
  expect_refused(empty, ZS_ERR_PARSE, ": corrupt JPEG: Premature end of JPEG file");
  zs_texture *t = (zs_texture *)&t;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_texture_decode(NULL, 0, "nothing", &t, &err), ZS_ERR_PARSE);
  ck_assert_ptr_null(t);
  ck_assert_str_eq(err.msg, "nothing: not a PNG or JPEG image");
}
END_TEST

/* ---- The mip chain (util/texture.c) ---- */

/* Level k of t is w x h and holds want. */
static void expect_level(const zs_texture *t, int k, int w, int h, const uint8_t *want) {
  int lw, lh;
  const uint8_t *p = zs_texture_level(t, k, &lw, &lh);
  ck_assert_ptr_nonnull(p);
  ck_assert_int_eq(lw, w);
  ck_assert_int_eq(lh, h);
  for (int i = 0; i < 4 * w * h; i++)
    ck_assert_msg(p[i] == want[i], "level %d texel %d channel %d: %d, expected %d", k, i / 4,
                  i % 4, p[i], want[i]);
}

static zs_texture *create(int w, int h, const uint8_t *rgba) {
  zs_texture *t = NULL;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_texture_create(w, h, rgba, &t, &err) == ZS_OK, "%s", err.msg);
  return t;
}

START_TEST(mip_3x3) {
  /* 3 x 3 -> 1 x 1: the odd row and column fold into the one block, all
   * nine texels, (sum + 4) / 9 */
  const uint8_t base[36] = {
      1, 0, 255, 1,  2, 0, 255, 1,  3, 0, 255, 1,  /* R 1..9: 45 -> 5 */
      4, 0, 255, 1,  5, 0, 255, 2,  6, 0, 255, 2,  /* G: 4 -> 0 (0.44) */
      7, 0, 255, 2,  8, 0, 255, 2,  9, 4, 255, 2}; /* A: 14 -> 2 (1.56) */
  zs_texture *t = create(3, 3, base);
  ck_assert_int_eq(zs_texture_levels(t), 2);
  expect_level(t, 0, 3, 3, base);
  const uint8_t l1[4] = {5, 0, 255, 2};
  expect_level(t, 1, 1, 1, l1);
  ck_assert_ptr_null(zs_texture_level(t, 2, NULL, NULL));
  zs_texture_destroy(t);
}
END_TEST

START_TEST(mip_4x2) {
  /* 4 x 2 -> 2 x 1 -> 1 x 1, each level from the one above, rounded:
   * R's blocks sum 6 and 2 -> 2 (1.5) and 1 (0.5), then (2 + 1 + 1) / 2
   * = 2, where the mean of the base (1) would give 1 */
  const uint8_t base[32] = {
      0, 10, 0, 255,  3, 20, 0, 255,  1, 30, 0, 255,  0, 40, 0, 255,
      1, 10, 1, 255,  2, 20, 0, 255,  0, 30, 0, 255,  1, 41, 3, 254};
  zs_texture *t = create(4, 2, base);
  ck_assert_int_eq(zs_texture_levels(t), 3);
  const uint8_t l1[8] = {2, 15, 0, 255, 1, 35, 1, 255}; /* G 60/4, 141/4 = 35.25; B 1/4, 3/4 */
  expect_level(t, 1, 2, 1, l1);
  const uint8_t l2[4] = {2, 25, 1, 255}; /* G 50/2; B (0 + 1 + 1) / 2 */
  expect_level(t, 2, 1, 1, l2);
  zs_texture_destroy(t);
}
END_TEST

START_TEST(mip_5x2_folds_the_last_column) {
  /* 5 x 2 -> 2 x 1: texel 0 averages columns 0-1, texel 1 columns 2-4 */
  uint8_t base[40];
  for (int y = 0; y < 2; y++)
    for (int x = 0; x < 5; x++) {
      uint8_t *p = base + 4 * (5 * y + x);
      p[0] = (uint8_t)(10 * x + y); /* 0 10 20 30 40 / 1 11 21 31 41 */
      p[1] = x == 4 ? 60 : 0;       /* the folded column alone */
      p[2] = 7;
      p[3] = 255;
    }
  zs_texture *t = create(5, 2, base);
  ck_assert_int_eq(zs_texture_levels(t), 3);
  /* R: 22 / 4 = 5.5 -> 6; 183 / 6 = 30.5 -> 31.  G: 0; 120 / 6 = 20 */
  const uint8_t l1[8] = {6, 0, 7, 255, 31, 20, 7, 255};
  expect_level(t, 1, 2, 1, l1);
  const uint8_t l2[4] = {19, 10, 7, 255}; /* (6 + 31 + 1) / 2 */
  expect_level(t, 2, 1, 1, l2);
  zs_texture_destroy(t);
}
END_TEST

START_TEST(create_refuses_sizes) {
  uint8_t px[4] = {0};
  zs_texture *t = (zs_texture *)&t;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_texture_create(8193, 1, px, &t, &err), ZS_ERR_LIMIT);
  ck_assert_ptr_null(t);
  ck_assert_str_eq(err.msg, "texture: 8193x1: each side must be 1 to 8192");
  zs_error_clear(&err);
  ck_assert_int_eq(zs_texture_create(1, 0, px, &t, &err), ZS_ERR_LIMIT);
  ck_assert_str_eq(err.msg, "texture: 1x0: each side must be 1 to 8192");
}
END_TEST

/* ---- Shading attributes through assimp ---- */

static int have_assimp(void) {
  if (!zs_assimp_available()) {
    fprintf(stderr, "test_texture: built without assimp; assimp model tests skipped\n");
    return 0;
  }
  return 1;
}

static int have_assimp_models(void) {
  struct stat st;
  if (!have_assimp()) return 0;
  if (stat(ASSIMP_MODELS, &st) != 0 || !S_ISDIR(st.st_mode)) {
    fprintf(stderr, "test_texture: %s absent (Debian assimp-testmodels); skipped\n",
            ASSIMP_MODELS);
    return 0;
  }
  return 1;
}

static void load_model(const char *path, zs_model *m) {
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_assimp_load(path, m, &err) == ZS_OK, "%s", err.msg);
}

/* The attribute vertex of corner k of the mesh. */
static int32_t corner_attr(const zs_model *m, int32_t k) {
  ck_assert_ptr_nonnull(m->mesh.corner_attr);
  return m->mesh.corner_attr[k];
}

#define BOX_GLTF ASSIMP_MODELS "/glTF2/BoxTextured-glTF/BoxTextured.gltf"
#define BOX_GLB ASSIMP_MODELS "/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb"
#define BOX_EMBEDDED ASSIMP_MODELS "/glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf"

START_TEST(gltf_texture_and_uvs) {
  if (!have_assimp_models()) return;
  zs_model m;
  load_model(BOX_GLTF, &m);
  const zs_mesh *me = &m.mesh;
  /* 24 vertices, each with its normal and uv, 12 triangles */
  ck_assert_int_eq(me->nverts, 24);
  ck_assert_int_eq(m.nsource_faces, 12);
  ck_assert_int_eq(me->nattrs, 24);
  ck_assert_ptr_nonnull(me->normal);
  ck_assert_ptr_nonnull(me->uv);
  ck_assert_ptr_null(me->color);
  /* vertex 0: the file's (6, 0), v turned up by assimp: (6, 1) */
  ck_assert(me->uv[0] == 6.0f && me->uv[1] == 1.0f);
  ck_assert(me->uv[2] == 5.0f && me->uv[3] == 1.0f);
  ck_assert(me->uv[4] == 6.0f && me->uv[5] == 1.0f - 0.99999988f);
  /* its normal (0, 0, 1) turned by the root node's quarter turn about x */
  ck_assert(me->normal[0] == 0.0f && me->normal[1] == 1.0f && me->normal[2] == 0.0f);
  /* every corner has its vertex's attributes */
  for (int32_t k = 0; k < me->face_start[me->nfaces]; k++)
    ck_assert_int_eq(corner_attr(&m, k), me->face_vert[k]);
  /* one material, its texture the 211 x 211 PNG beside the file */
  ck_assert_int_eq(me->nmaterials, 1);
  ck_assert_int_eq(m.ntextures, 1);
  const zs_material *mat = &me->materials[0];
  ck_assert_ptr_eq(mat->base_texture, m.textures[0]);
  const uint8_t white[4] = {255, 255, 255, 255};
  ck_assert_mem_eq(mat->base, white, 4);
  ck_assert_int_eq(mat->wrap_s, ZS_WRAP_MIRROR); /* the sampler's 33648 */
  ck_assert_int_eq(mat->wrap_t, ZS_WRAP_CLAMP);  /* 33071 */
  ck_assert_int_eq(mat->filter, ZS_FILTER_TRILINEAR); /* min 9986 NEAREST_MIPMAP_LINEAR */
  ck_assert_int_eq(mat->double_sided, 0);
  ck_assert_int_eq(mat->shininess, 0);
  const zs_texture *tex = mat->base_texture;
  ck_assert_int_eq(zs_texture_width(tex), 211);
  ck_assert_int_eq(zs_texture_height(tex), 211);
  ck_assert_int_eq(zs_texture_levels(tex), 8);
  /* the same texels as the file read alone */
  zs_texture *alone = load(ASSIMP_MODELS "/glTF2/BoxTextured-glTF/CesiumLogoFlat.png");
  ck_assert_uint_eq(texel_hash(tex), texel_hash(alone));
  zs_texture_destroy(alone);
  /* the face colours stay the material's diffuse colour */
  for (int32_t f = 0; f < me->nfaces; f++) ck_assert_uint_eq(me->face_rgb[f], 0xFFFFFF);
  zs_model_free(&m);
}
END_TEST

START_TEST(glb_embedded_texture_same_texels) {
  if (!have_assimp_models()) return;
  zs_model a, b, c;
  load_model(BOX_GLTF, &a);
  load_model(BOX_GLB, &b);
  load_model(BOX_EMBEDDED, &c);
  ck_assert_int_eq(b.ntextures, 1);
  ck_assert_int_eq(c.ntextures, 1);
  ck_assert_uint_eq(texel_hash(b.textures[0]), texel_hash(a.textures[0]));
  ck_assert_uint_eq(texel_hash(c.textures[0]), texel_hash(a.textures[0]));
  ck_assert_int_eq(b.mesh.nattrs, a.mesh.nattrs);
  ck_assert_mem_eq(b.mesh.uv, a.mesh.uv, 2 * sizeof(float) * (size_t)a.mesh.nattrs);
  ck_assert_mem_eq(b.mesh.normal, a.mesh.normal, 3 * sizeof(float) * (size_t)a.mesh.nattrs);
  zs_model_free(&a);
  zs_model_free(&b);
  zs_model_free(&c);
}
END_TEST

START_TEST(gltf_missing_texture_is_refused) {
  if (!have_assimp_models()) return;
  /* the model and its buffer, without the PNG */
  char dir[PATH_LEN], gltf[PATH_LEN + 32], bin[PATH_LEN + 32];
  snprintf(dir, sizeof dir, "%s/box", out_dir());
  if (mkdir(dir, 0777) != 0) ck_assert_int_eq(errno, EEXIST);
  snprintf(gltf, sizeof gltf, "%s/BoxTextured.gltf", dir);
  snprintf(bin, sizeof bin, "%s/BoxTextured0.bin", dir);
  size_t n;
  unsigned char *bytes = zs_test_slurp(BOX_GLTF, &n);
  spit(gltf, bytes, n);
  free(bytes);
  bytes = zs_test_slurp(ASSIMP_MODELS "/glTF2/BoxTextured-glTF/BoxTextured0.bin", &n);
  spit(bin, bytes, n);
  free(bytes);
  zs_model m;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_int_eq(zs_assimp_load(gltf, &m, &err), ZS_ERR_IO);
  char want[3 * PATH_LEN];
  snprintf(want, sizeof want,
           "%s: texture %s/CesiumLogoFlat.png: cannot open: No such file or directory", gltf,
           dir);
  ck_assert_str_eq(err.msg, want);
  ck_assert_int_eq(m.mesh.nfaces, 0);
  ck_assert_int_eq(m.ntextures, 0);
}
END_TEST

/* glTF's alpha modes: the painted triangle's BLEND turned into OPAQUE
 * (every alpha ignored) and MASK with a cut-off of 0.6 (an 8-bit alpha of
 * 153 passes: 153 / 255 >= 0.6 in float, as a GPU compares it), and its
 * default of 0.5 (128). */
START_TEST(gltf_alpha_modes) {
  if (!have_assimp()) return;
  size_t n = 0;
  char *text = (char *)zs_test_slurp(zs_test_src("tests/data/models/painted_triangle.gltf"), &n);
  ck_assert_ptr_nonnull(text);
  const char *blend = "\"alphaMode\": \"BLEND\",";
  char *at = strstr(text, blend);
  ck_assert_ptr_nonnull(at);
  static const char *const modes[3] = {"\"alphaMode\": \"OPAQUE\",",
                                       "\"alphaMode\": \"MASK\", \"alphaCutoff\": 0.6,",
                                       "\"alphaMode\": \"MASK\","};
  const int ignore[3] = {1, 0, 0}, cutoff[3] = {0, 153, 128};
  for (int k = 0; k < 3; k++) {
    char path[PATH_LEN];
    snprintf(path, sizeof path, "%s/alpha_mode_%d.gltf", out_dir(), k);
    FILE *f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    fwrite(text, 1, (size_t)(at - text), f);
    fputs(modes[k], f);
    fputs(at + strlen(blend), f);
    fclose(f);
    zs_model m;
    load_model(path, &m);
    ck_assert_int_eq(m.mesh.nmaterials, 1);
    ck_assert_int_eq(m.mesh.materials[0].ignore_alpha, ignore[k]);
    ck_assert_int_eq(m.mesh.materials[0].alpha_cutoff, cutoff[k]);
    ck_assert_int_eq(m.mesh.materials[0].base[3], k == 0 ? 255 : 128);
    zs_model_free(&m);
  }
  free(text);
}
END_TEST

START_TEST(gltf_vertex_colours_and_material) {
  if (!have_assimp()) return;
  char path[PATH_LEN];
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/models/painted_triangle.gltf"));
  zs_model m;
  load_model(path, &m);
  const zs_mesh *me = &m.mesh;
  ck_assert_int_eq(me->nverts, 3);
  ck_assert_int_eq(me->nattrs, 3);
  /* COLOR_0, round(255 x) */
  const uint8_t rgba[12] = {255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 64};
  ck_assert_mem_eq(me->color, rgba, sizeof rgba);
  /* TEXCOORD_0 (0, 0), (2, 0), (0, -1) with v turned up */
  const float uv[6] = {0, 1, 2, 1, 0, 2};
  ck_assert_mem_eq(me->uv, uv, sizeof uv);
  /* no normals in the file: zscan's own, the triangle's plane (z = 0) */
  ck_assert_ptr_nonnull(me->normal);
  for (int32_t k = 0; k < 3; k++) {
    const float *n = me->normal + 3 * (size_t)corner_attr(&m, k);
    ck_assert_msg(n[0] == 0.0f && n[1] == 0.0f && n[2] > 0.0f, "corner %d: %g %g %g", k, n[0],
                  n[1], n[2]);
  }
  /* the material: baseColorFactor (1, 0.5, 0.25, 0.5) as BLEND, emissive
   * (0.2, 0.4, 0.6), double-sided, the embedded PNG by a nearest,
   * clamp-and-mirror sampler */
  ck_assert_int_eq(me->nmaterials, 1);
  const zs_material *mat = &me->materials[0];
  const uint8_t base[4] = {255, 128, 64, 128}, emissive[3] = {51, 102, 153}, none[3] = {0};
  ck_assert_mem_eq(mat->base, base, 4);
  ck_assert_mem_eq(mat->emissive, emissive, 3);
  ck_assert_mem_eq(mat->specular, none, 3);
  ck_assert_int_eq(mat->double_sided, 1);
  ck_assert_int_eq(mat->wrap_s, ZS_WRAP_CLAMP);
  ck_assert_int_eq(mat->wrap_t, ZS_WRAP_MIRROR);
  ck_assert_int_eq(mat->filter, ZS_FILTER_NEAREST);
  ck_assert_int_eq(m.ntextures, 1);
  char png[PATH_LEN];
  zs_texture *alone = load(data(png, "rgba8.png"));
  ck_assert_uint_eq(texel_hash(mat->base_texture), texel_hash(alone));
  zs_texture_destroy(alone);
  ck_assert(me->face_material == NULL || me->face_material[0] == 0);
  zs_model_free(&m);
}
END_TEST

START_TEST(ply_vertex_colours) {
  if (!have_assimp()) return;
  char path[PATH_LEN];
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/models/rgb_quad.ply"));
  zs_model m;
  load_model(path, &m);
  const zs_mesh *me = &m.mesh;
  ck_assert_int_eq(me->nverts, 4);
  ck_assert_int_eq(me->nattrs >= 4, 1);
  ck_assert_ptr_null(me->uv);
  const uint8_t want[4][4] = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255},
                              {10, 20, 30, 128}};
  /* each corner has its vertex's colour (the normals made may split
   * attribute vertices, never change their colours) */
  for (int32_t k = 0; k < me->face_start[me->nfaces]; k++) {
    const uint8_t *c = me->color + 4 * (size_t)corner_attr(&m, k);
    ck_assert_mem_eq(c, want[me->face_vert[k]], 4);
    const float *n = me->normal + 3 * (size_t)corner_attr(&m, k);
    ck_assert(n[0] == 0.0f && n[1] == 0.0f && n[2] > 0.0f);
  }
  /* PLY's default material: white, and no highlight (assimp calls it
   * Gouraud shaded, though it gives a white specular colour) */
  ck_assert_int_eq(me->nmaterials, 1);
  const uint8_t white[4] = {255, 255, 255, 255}, none[3] = {0};
  ck_assert_mem_eq(me->materials[0].base, white, 4);
  ck_assert_mem_eq(me->materials[0].specular, none, 3);
  ck_assert_ptr_null(me->materials[0].base_texture);
  ck_assert_uint_eq(me->face_rgb[0], 0xFFFFFF);
  zs_model_free(&m);
}
END_TEST

START_TEST(no_attributes_no_arrays) {
  if (!have_assimp()) return;
  /* a file with positions only ends without attribute arrays, so that
   * it draws flat, exactly as before attributes were read */
  static const char *const files[] = {"tests/data/models/tetra.ply",
                                      "tests/data/models/two_nodes.gltf"};
  for (size_t i = 0; i < sizeof files / sizeof *files; i++) {
    char path[PATH_LEN];
    snprintf(path, sizeof path, "%s", zs_test_src(files[i]));
    zs_model m;
    load_model(path, &m);
    ck_assert_int_eq(m.mesh.nattrs, 0);
    ck_assert_ptr_null(m.mesh.corner_attr);
    ck_assert_ptr_null(m.mesh.normal);
    ck_assert_ptr_null(m.mesh.color);
    ck_assert_ptr_null(m.mesh.uv);
    ck_assert_int_eq(m.ntextures, 0);
    zs_model_free(&m);
  }
}
END_TEST

START_TEST(node_transform_turns_normals) {
  if (!have_assimp_models()) return;
  /* BoxTextured's node turns the box (a rotation about x): its normals
   * are turned with it and stay of unit length */
  zs_model m;
  load_model(BOX_GLB, &m);
  const zs_mesh *me = &m.mesh;
  for (int32_t a = 0; a < me->nattrs; a++) {
    const float *n = me->normal + 3 * (size_t)a;
    const double len2 = (double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2];
    ck_assert_msg(len2 > 0.999999 && len2 < 1.000001, "normal %d: %g %g %g", a, n[0], n[1],
                  n[2]);
  }
  zs_model_free(&m);
}
END_TEST

static Suite *suite(void) {
  Suite *s = suite_create("texture");
  TCase *files = tcase_create("files");
  tcase_add_test(files, png_rgba8_as_stored);
  tcase_add_test(files, png_16_bit_scaled_without_gamma);
  tcase_add_test(files, png_palette_and_grey);
  tcase_add_test(files, decode_equals_load);
  tcase_add_test(files, jpeg_texels_are_djpegs);
  tcase_add_test(files, jpeg_simd_and_plain_agree);
  tcase_add_test(files, refused_inputs);
  suite_add_tcase(s, files);
  TCase *mip = tcase_create("mip");
  tcase_add_test(mip, mip_3x3);
  tcase_add_test(mip, mip_4x2);
  tcase_add_test(mip, mip_5x2_folds_the_last_column);
  tcase_add_test(mip, create_refuses_sizes);
  suite_add_tcase(s, mip);
  TCase *assimp = tcase_create("assimp");
  tcase_add_test(assimp, gltf_texture_and_uvs);
  tcase_add_test(assimp, glb_embedded_texture_same_texels);
  tcase_add_test(assimp, gltf_missing_texture_is_refused);
  tcase_add_test(assimp, gltf_vertex_colours_and_material);
  tcase_add_test(assimp, gltf_alpha_modes);
  tcase_add_test(assimp, ply_vertex_colours);
  tcase_add_test(assimp, no_attributes_no_arrays);
  tcase_add_test(assimp, node_transform_turns_normals);
  suite_add_tcase(s, assimp);
  return s;
}

int main(int argc, char **argv) {
  if (argc == 3 && strcmp(argv[1], "--texel-hash") == 0) {
    zs_texture *t;
    zs_error err;
    zs_error_clear(&err);
    if (zs_texture_load(argv[2], &t, &err) != ZS_OK) {
      printf("%s\n", err.msg);
      return 1;
    }
    printf("%016llx\n", (unsigned long long)texel_hash(t));
    zs_texture_destroy(t);
    return 0;
  }
  return zs_test_run(suite());
}
