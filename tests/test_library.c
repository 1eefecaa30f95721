/* zscan as a library: the public headers compile alone as C11 and C++17
 * and include nothing private; libzscan.so exports the public functions
 * and nothing else; a zero-initialised config renders; and the example
 * render_hash, built against the shared library, prints the image_hash of
 * `zscan render` for every model of tests/data and of assimp's test
 * models. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "tests/testutil.h"
#include "zscan/clock.h"
#include "zscan/walk.h"
#include "zscan/zscan.h"

enum { BIG = 1 << 16 };

/* The compilers a consumer is built with: the build's own C compiler, and
 * its C++ sibling, with the build's sanitizers when it has them (the
 * sanitizer runtime must be the same as the library's). */
static const char *cc(void) { return ZS_C_COMPILER; }
static const char *cxx_compiler(void) { return strstr(ZS_C_COMPILER, "clang") ? "clang++" : "g++"; }
#ifdef ZS_SANITIZED
#define CONSUMER_FLAGS "-fsanitize=address,undefined"
#else
#define CONSUMER_FLAGS ""
#endif

/* Runs a shell command; its output (both streams) into out. */
static int shell(const char *cmd, char *out, size_t cap) {
  FILE *p = popen(cmd, "r");
  ck_assert_ptr_nonnull(p);
  size_t n = 0, got;
  while (n + 1 < cap && (got = fread(out + n, 1, cap - 1 - n, p)) > 0) n += got;
  out[n] = '\0';
  int rc = pclose(p);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

static char *slurp_text(const char *path) {
  size_t n;
  return (char *)zs_test_slurp(path, &n);
}

/* The public headers: every file of include/zscan. */
static const char *headers[16];
static int NHEADERS;

static void list_headers(void) {
  if (NHEADERS) return;
  char dir[4200];
  snprintf(dir, sizeof dir, "%s/include/zscan", ZS_SOURCE_DIR);
  DIR *d = opendir(dir);
  ck_assert_ptr_nonnull(d);
  for (struct dirent *e; (e = readdir(d)) && NHEADERS < 16;)
    if (strstr(e->d_name, ".h")) headers[NHEADERS++] = strdup(e->d_name);
  closedir(d);
  ck_assert_int_ge(NHEADERS, 6);
}

/* Each header alone, as the first include of a C11 and of a C++17 file,
 * with every warning an error. */
START_TEST(headers_compile_alone_as_c_and_cxx) {
  static char out[BIG];
  list_headers();
  for (int h = 0; h < NHEADERS; h++) {
    for (int cxx = 0; cxx < 2; cxx++) {
      char src[4200], cmd[9000];
      snprintf(src, sizeof src, "%s/header-%d.%s", ZS_BINARY_DIR, h, cxx ? "cpp" : "c");
      FILE *f = fopen(src, "w");
      fprintf(f, "#include <zscan/%s>\nint zs_check_%d;\n", headers[h], h);
      fclose(f);
      snprintf(cmd, sizeof cmd,
               "%s %s -Wall -Wextra -Werror -pedantic -I%s/include -c %s -o %s.o 2>&1",
               cxx ? cxx_compiler() : cc(), cxx ? "-std=c++17" : "-std=c11", ZS_SOURCE_DIR, src, src);
      ck_assert_msg(shell(cmd, out, sizeof out) == 0, "%s: %s", cmd, out);
    }
  }
}
END_TEST

/* A public header includes the standard library and other public headers
 * only. */
START_TEST(headers_include_nothing_private) {
  list_headers();
  for (int h = 0; h < NHEADERS; h++) {
    char path[4200];
    snprintf(path, sizeof path, "%s/include/zscan/%s", ZS_SOURCE_DIR, headers[h]);
    char *text = slurp_text(path);
    for (char *l = strstr(text, "#include"); l; l = strstr(l + 1, "#include")) {
      char *q = l + strlen("#include");
      while (*q == ' ') q++;
      ck_assert_msg(*q == '<' || strncmp(q, "\"zscan/", 7) == 0, "%s: %.40s", headers[h], l);
    }
    free(text);
  }
}
END_TEST

/* Every symbol libzscan.so defines is declared in a public header, and
 * every function the headers declare is there. */
START_TEST(shared_library_exports_the_api_only) {
  static char out[BIG];
  list_headers();
  char cmd[4400];
  snprintf(cmd, sizeof cmd, "nm -D --defined-only %s/libzscan.so | awk '{print $3}'",
           ZS_BINARY_DIR);
  ck_assert_int_eq(shell(cmd, out, sizeof out), 0);
  char *all = calloc(1, (size_t)NHEADERS * BIG);
  for (int h = 0; h < NHEADERS; h++) {
    char path[4200];
    snprintf(path, sizeof path, "%s/include/zscan/%s", ZS_SOURCE_DIR, headers[h]);
    char *text = slurp_text(path);
    strcat(all, text);
    free(text);
  }
  int exported = 0;
  for (char *sym = strtok(out, "\n"); sym; sym = strtok(NULL, "\n")) {
    char *at = strchr(sym, '@');
    if (at) *at = '\0';
    if (strncmp(sym, "ZSCAN_", 6) == 0) continue; /* the version node */
    char decl[256];
    snprintf(decl, sizeof decl, "%s(", sym);
    ck_assert_msg(strstr(all, decl) != NULL, "exported but not public: %s", sym);
    exported++;
  }
  /* the other way: as many functions as the headers declare, one per
   * line that starts a declaration */
  ck_assert_int_ge(exported, 50);
  snprintf(cmd, sizeof cmd,
           "grep -ho '^[a-z][a-zA-Z0-9_ ]*[ *]zs_[a-z0-9_]*(' %s/include/zscan/*.h | "
           "grep -v '^typedef\\|^static' | grep -o 'zs_[a-z0-9_]*($' | sort -u | wc -l",
           ZS_SOURCE_DIR);
  ck_assert_int_eq(shell(cmd, out, sizeof out), 0);
  ck_assert_int_eq(atoi(out), exported);
  free(all);
}
END_TEST

/* 0 means the default everywhere: a zeroed config is a 1024x768 zbuffer
 * device on one thread, and a zeroed zs_render_opts renders. */
START_TEST(zero_config_renders) {
  zs_error err = {0};
  zs_device_config cfg = {0};
  zs_device *dev = NULL;
  ck_assert_msg(zs_device_create(&cfg, &dev, &err) == ZS_OK, "%s", err.msg);
  const zs_device_config *got = zs_device_config_of(dev);
  ck_assert_int_eq(got->width, 1024);
  ck_assert_int_eq(got->height, 768);
  ck_assert_int_eq(got->threads, 1);
  double pos[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  int32_t start[] = {0, 4}, verts[] = {0, 1, 2, 3};
  zs_mesh quad = {.pos = pos, .nverts = 4, .face_start = start, .face_vert = verts, .nfaces = 1};
  double view[16], proj[16];
  const double eye[3] = {0, 0, 4}, target[3] = {0, 0, 0}, up[3] = {0, 1, 0};
  ck_assert(zs_mat_look_at(view, eye, target, up));
  zs_mat_perspective(proj, 45, 4.0 / 3.0, 1, 10);
  zs_device_set_camera(dev, view, proj);
  zs_device_clear(dev);
  ck_assert_int_eq(zs_device_draw(dev, &quad, NULL, 0, 0xFFFFFF, &err), ZS_OK);
  ck_assert_int_eq(zs_device_finish(dev, NULL, NULL, &err), ZS_OK);
  ck_assert_uint_gt(zs_device_stats(dev)->pixels_written, 100000);
  zs_device_destroy(dev);

  zs_scene *scene = NULL;
  ck_assert_int_eq(zs_scene_load("builtin:cubes?n=2", NULL, &scene, &err), ZS_OK);
  zs_image im = {0};
  float *depth = NULL;
  zs_raster_stats stats;
  ck_assert_msg(zs_render(scene, NULL, &im, &depth, &stats, &err) == ZS_OK, "%s", err.msg);
  ck_assert_int_eq(im.width, 1024);
  ck_assert_int_eq(im.height, 768);
  ck_assert_ptr_nonnull(depth);
  ck_assert_uint_gt(stats.pixels_written, 0);
  free(depth);
  zs_image_free(&im);
  zs_scene_destroy(scene);
  ck_assert_str_eq(zs_version(), ZSCAN_VERSION_STRING);
}
END_TEST

/* zs_load_opts.skip_missing_textures: a texture that cannot be opened
 * is an error without it; with it the model loads, and zs_scene_notes
 * says which texture was left out, the error's words and ": drawn
 * without it".  A scene without notes has "". */
START_TEST(scene_notes_name_a_skipped_texture) {
  char path[4096], want[8192];
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/obj/missing_texture.obj"));
  zs_error err = {0};
  zs_scene *scene = NULL;
  ck_assert_int_eq(zs_scene_load(path, NULL, &scene, &err), ZS_ERR_IO);
  ck_assert_ptr_null(scene);
  snprintf(want, sizeof want,
           "%s: map_Kd nothing here.png: cannot open: No such file or directory",
           zs_test_src("tests/data/obj/missing_texture.mtl:4"));
  ck_assert_str_eq(err.msg, want);
  zs_load_opts opts = {0};
  opts.skip_missing_textures = 1;
  zs_error_clear(&err);
  ck_assert_msg(zs_scene_load(path, &opts, &scene, &err) == ZS_OK, "%s", err.msg);
  strcat(want, ": drawn without it\n");
  ck_assert_str_eq(zs_scene_notes(scene), want);
  ck_assert_uint_eq(zs_scene_faces(scene), 1);
  zs_scene_destroy(scene);
  ck_assert_int_eq(zs_scene_load("builtin:cubes?n=2", &opts, &scene, &err), ZS_OK);
  ck_assert_str_eq(zs_scene_notes(scene), "");
  zs_scene_destroy(scene);
}
END_TEST

/* The library refuses what the command refuses, in its own words: the
 * fields of zs_render_opts, never the command's flags. */
START_TEST(library_errors_name_its_options_not_flags) {
  zs_error err = {0};
  zs_scene *scene = NULL;
  ck_assert_int_eq(zs_scene_load("builtin:cubes?n=2", NULL, &scene, &err), ZS_OK);
  const zs_algo algos[] = {ZS_ALGO_SCANLINE, ZS_ALGO_ZBUFFER};
  const zs_shade shades[] = {ZS_SHADE_FLAT, ZS_SHADE_ID};
  for (int k = 0; k < 2; k++) {
    zs_render_opts o = {0};
    o.width = 32;
    o.height = 24;
    o.hidden_line = 1;
    o.algo = algos[k];
    o.shade = shades[k];
    zs_image im = {0};
    zs_error_clear(&err);
    ck_assert_int_eq(zs_render(scene, &o, &im, NULL, NULL, &err), ZS_ERR_ARG);
    ck_assert_str_eq(err.msg, "hidden_line needs algo ZS_ALGO_ZBUFFER and shade ZS_SHADE_FLAT or ZS_SHADE_AUTO");
    ck_assert_ptr_null(im.rgb);
  }
  zs_scene_destroy(scene);
}
END_TEST

/* A scene built in code from arrays draws what the OBJ file of the same
 * data draws, byte for byte: the crate (corner normals, texture
 * coordinates, a PNG texture, one material), in flat and lit shadings. */
START_TEST(scene_from_arrays_equals_the_obj) {
  static const double pos[] = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1,
                               -1, -1, 1,  1, -1, 1,  1, 1, 1,  -1, 1, 1};
  static const float uv4[] = {0, 0, 1, 0, 1, 1, 0, 1};
  static const float nrm6[] = {0, 0, -1, 0, 0, 1, 0, -1, 0, 0, 1, 0, -1, 0, 0, 1, 0, 0};
  static const int32_t faces[6][4] = {{1, 4, 3, 2}, {5, 6, 7, 8}, {1, 2, 6, 5},
                                      {4, 8, 7, 3}, {1, 5, 8, 4}, {2, 3, 7, 6}};
  /* attribute vertex 4 f + k: face f's normal, texture corner k */
  float normal[24 * 3], uv[24 * 2];
  int32_t start[7], verts[24], attr[24];
  for (int f = 0; f < 6; f++) {
    start[f] = 4 * f;
    for (int k = 0; k < 4; k++) {
      const int c = 4 * f + k;
      verts[c] = faces[f][k] - 1;
      attr[c] = c;
      memcpy(normal + 3 * c, nrm6 + 3 * f, 3 * sizeof *normal);
      memcpy(uv + 2 * c, uv4 + 2 * k, 2 * sizeof *uv);
    }
  }
  start[6] = 24;
  zs_error err = {0};
  zs_image png = {0};
  ck_assert_msg(zs_png_read(zs_test_src("tests/data/scenes/crate.png"), &png, &err) == ZS_OK,
                "%s", err.msg);
  uint8_t *rgba = malloc(4 * (size_t)png.width * (size_t)png.height);
  ck_assert_ptr_nonnull(rgba);
  for (int i = 0; i < png.width * png.height; i++) {
    rgba[4 * i] = (uint8_t)(png.rgb[i] >> 16), rgba[4 * i + 1] = (uint8_t)(png.rgb[i] >> 8);
    rgba[4 * i + 2] = (uint8_t)png.rgb[i], rgba[4 * i + 3] = 255;
  }
  zs_texture *tex = NULL;
  ck_assert_int_eq(zs_texture_create(png.width, png.height, rgba, &tex, &err), ZS_OK);
  zs_material mat = zs_material_default();
  mat.base[0] = mat.base[1] = mat.base[2] = 255;
  mat.specular[0] = mat.specular[1] = mat.specular[2] = 77; /* Ks 0.3 */
  mat.shininess = 20;
  mat.base_texture = tex;
  uint32_t white[6] = {0xFFFFFF, 0xFFFFFF, 0xFFFFFF, 0xFFFFFF, 0xFFFFFF, 0xFFFFFF};
  int32_t face_mat[6] = {0};
  zs_mesh mesh = {.pos = (double *)pos, .nverts = 8, .face_start = start, .face_vert = verts,
                  .nfaces = 6, .face_rgb = white, .nattrs = 24, .corner_attr = attr,
                  .normal = normal, .uv = uv, .face_material = face_mat, .materials = &mat,
                  .nmaterials = 1};
  zs_scene *built = NULL, *loaded = NULL;
  ck_assert_int_eq(zs_scene_create(&built, &err), ZS_OK);
  ck_assert_msg(zs_scene_add_object(built, &mesh, NULL, "crate", &err) == ZS_OK, "%s", err.msg);
  ck_assert_int_eq(zs_scene_objects(built), 1);
  ck_assert_uint_eq(zs_scene_faces(built), 6);
  ck_assert_msg(zs_scene_load(zs_test_src("tests/data/scenes/crate.obj"), NULL, &loaded, &err) ==
                    ZS_OK, "%s", err.msg);
  const zs_shade shades[] = {ZS_SHADE_AUTO, ZS_SHADE_FLAT, ZS_SHADE_UNLIT, ZS_SHADE_PHONG,
                             ZS_SHADE_ID};
  for (size_t k = 0; k < sizeof shades / sizeof *shades; k++) {
    zs_render_opts o = {.width = 96, .height = 72, .shade = shades[k], .eye = {2.5, 2, 3.5},
                        .has_eye = 1};
    zs_image a = {0}, b = {0};
    ck_assert_msg(zs_render(built, &o, &a, NULL, NULL, &err) == ZS_OK, "%s", err.msg);
    ck_assert_msg(zs_render(loaded, &o, &b, NULL, NULL, &err) == ZS_OK, "%s", err.msg);
    ck_assert_msg(zs_image_hash(&a) == zs_image_hash(&b), "shade %d: %016llx from arrays, "
                  "%016llx from the file", (int)shades[k], (unsigned long long)zs_image_hash(&a),
                  (unsigned long long)zs_image_hash(&b));
    zs_image_free(&a);
    zs_image_free(&b);
  }
  zs_scene_destroy(built);
  zs_scene_destroy(loaded);
  zs_texture_destroy(tex);
  free(rgba);
  zs_image_free(&png);
}
END_TEST

/* Bad arrays are refused with the array and its element named, and the
 * scene keeps what it had. */
START_TEST(scene_from_arrays_names_the_bad_element) {
  double pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  int32_t start[] = {0, 3}, verts[] = {0, 1, 2};
  zs_mesh good = {.pos = pos, .nverts = 3, .face_start = start, .face_vert = verts, .nfaces = 1};
  zs_error err = {0};
  zs_scene *s = NULL;
  ck_assert_int_eq(zs_scene_create(&s, &err), ZS_OK);
  ck_assert_msg(zs_scene_add_object(s, &good, NULL, NULL, &err) == ZS_OK, "%s", err.msg);
  static const struct {
    int what;
    const char *msg;
  } cases[] = {
      {0, "zs_mesh.face_vert[2]: vertex 3 out of range (3 vertices)"},
      {1, "zs_mesh.pos[4]: not a finite number"},
      {2, "zs_mesh face 0: 2 corners (at least 3 needed)"},
      {3, "zs_scene_add_object: model[3] is not a finite number"},
      {4, "zs_scene_add_object: no faces, lines or points"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
    double p[9], model[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    int32_t st2[2] = {0, 3}, v[3] = {0, 1, 2};
    memcpy(p, pos, sizeof p);
    zs_mesh m = {.pos = p, .nverts = 3, .face_start = st2, .face_vert = v, .nfaces = 1};
    if (cases[k].what == 0) v[2] = 3;
    if (cases[k].what == 1) p[4] = NAN;
    if (cases[k].what == 2) st2[1] = 2;
    if (cases[k].what == 3) model[3] = INFINITY;
    if (cases[k].what == 4) m.nfaces = 0;
    zs_error_clear(&err);
    ck_assert_int_eq(zs_scene_add_object(s, &m, model, NULL, &err), ZS_ERR_ARG);
    ck_assert_str_eq(err.msg, cases[k].msg);
  }
  ck_assert_int_eq(zs_scene_objects(s), 1);
  ck_assert_uint_eq(zs_scene_faces(s), 1);
  zs_scene_destroy(s);
}
END_TEST

/* The last line of text, into line. */
static void last_line(const char *text, char *line, size_t cap) {
  const char *end = text + strlen(text);
  while (end > text && end[-1] == '\n') end--;
  const char *start = end;
  while (start > text && start[-1] != '\n') start--;
  snprintf(line, cap, "%.*s", (int)(end - start), start);
}

static int compare_one(const char *exe, const char *input, int *rendered) {
  static char out[BIG], cli[BIG], err[BIG];
  char cmd[9000];
  snprintf(cmd, sizeof cmd, "LD_LIBRARY_PATH=%s %s '%s' 96 72 2>/dev/null", ZS_BINARY_DIR, exe,
           input);
  int rc = shell(cmd, out, sizeof out);
  char png[4200];
  snprintf(png, sizeof png, "%s/library-cli.png", ZS_BINARY_DIR);
  const char *args[] = {"render", input, "--size", "96x72", "--stats", "-o", png, NULL};
  int cli_rc = zs_test_run_zscan(args, cli, sizeof cli, err, sizeof err);
  ck_assert_msg((rc == 0) == (cli_rc == 0), "%s: render_hash exit %d, zscan render exit %d (%s)",
                input, rc, cli_rc, err);
  if (rc != 0) return 0;
  char hash[64];
  last_line(out, hash, sizeof hash);
  const char *h = strstr(cli, "\"image_hash\":\"");
  ck_assert_ptr_nonnull(h);
  ck_assert_msg(strncmp(h + 14, hash, 16) == 0 && strlen(hash) == 16,
                "%s: render_hash %s, zscan render %.16s", input, hash, h + 14);
  (*rendered)++;
  return 1;
}

typedef struct comparison {
  const char *exe;    /* the example program */
  int rendered, seen; /* files rendered by both, and model files met */
} comparison;

static void compare_file(const char *path, void *user) {
  comparison *c = user;
  c->seen++;
  compare_one(c->exe, path, &c->rendered);
}

static const char *const model_suffixes[] = {".obj", ".ply", ".stl", ".off", ".gltf", ".glb"};
enum { NMODEL_SUFFIXES = sizeof model_suffixes / sizeof model_suffixes[0] };

/* Builds examples/NAME.EXT with the compiler (and standard) given, against
 * the source tree's public headers and the shared library, as a user
 * would; returns the program's path in exe. */
static void build_example(const char *compiler, const char *std, const char *file, char *exe,
                          size_t cap) {
  static char out[BIG];
  char cmd[9000];
  snprintf(exe, cap, "%s/%.*s", ZS_BINARY_DIR, (int)strcspn(file, "."), file);
  snprintf(cmd, sizeof cmd,
           "%s -std=%s -Wall -Wextra -Werror %s -I%s/include %s/examples/%s -L%s -lzscan -o %s 2>&1",
           compiler, std, CONSUMER_FLAGS, ZS_SOURCE_DIR, ZS_SOURCE_DIR, file, ZS_BINARY_DIR, exe);
  ck_assert_msg(shell(cmd, out, sizeof out) == 0, "%s: %s", cmd, out);
}

/* examples/render_hash.c built with cc against the public header and the
 * shared library, as a user would, gives the command's image_hash. */
START_TEST(render_hash_equals_the_command) {
  char exe[4200];
  build_example(cc(), "c11", "render_hash.c", exe, sizeof exe);
  comparison c = {exe, 0, 0};
  zs_test_each_file(zs_test_src("tests/data"), model_suffixes, NMODEL_SUFFIXES, compare_file, &c);
  /* tests/data holds the bad files too: both refuse those */
  ck_assert_int_ge(c.seen, 40);
  ck_assert_int_ge(c.rendered, 12);
  int ours = c.rendered;
  static const char *const assimp_dirs[] = {"OBJ", "PLY", "STL", "OFF", "glTF2"};
  for (size_t k = 0; k < sizeof assimp_dirs / sizeof assimp_dirs[0]; k++) {
    char dir[256];
    snprintf(dir, sizeof dir, "/usr/share/assimp/models/%s", assimp_dirs[k]);
    zs_test_each_file(dir, model_suffixes, NMODEL_SUFFIXES, compare_file, &c);
  }
#ifdef ZS_HAVE_ASSIMP
  ck_assert_int_ge(c.rendered - ours, 30); /* assimp-testmodels is installed by setup.sh */
#endif
  printf("render_hash: %d of %d model files rendered, each with the command's hash\n", c.rendered,
         c.seen);
}
END_TEST

/* The C++ example builds against the headers and runs: a box behind a
 * wall gets no sample, one beside it does. */
START_TEST(cxx_example_queries) {
  static char out[BIG];
  char exe[4200], cmd[9000];
  build_example(cxx_compiler(), "c++17", "query_mesh.cpp", exe, sizeof exe);
  snprintf(cmd, sizeof cmd, "LD_LIBRARY_PATH=%s %s", ZS_BINARY_DIR, exe);
  ck_assert_msg(shell(cmd, out, sizeof out) == 0, "%s: %s", cmd, out);
  ck_assert_msg(strstr(out, "box behind the wall: 0 samples\n") != NULL, "%s", out);
  const char *beside = strstr(out, "box beside the wall: ");
  ck_assert_ptr_nonnull(beside);
  ck_assert_int_gt(atoi(beside + strlen("box beside the wall: ")), 100);
}
END_TEST

/* The example at the top of zscan.h: its text with the comment's " * "
 * taken off, into buf. */
static void header_example(char *buf, size_t cap) {
  char path[4200];
  snprintf(path, sizeof path, "%s/include/zscan/zscan.h", ZS_SOURCE_DIR);
  char *text = slurp_text(path);
  const char *start = strstr(text, " *   #include <zscan/zscan.h>");
  ck_assert_ptr_nonnull(start);
  const char *end = strstr(start, "\n *   }\n");
  ck_assert_ptr_nonnull(end);
  end += strlen("\n *   }\n");
  size_t n = 0;
  for (const char *l = start; l < end; l = strchr(l, '\n') + 1) {
    const char *body = strncmp(l, " *   ", 5) == 0 ? l + 5 : l + 2; /* " *\n": a blank line */
    size_t len = (size_t)(strchr(l, '\n') - body);
    ck_assert_uint_lt(n + len + 2, cap);
    memcpy(buf + n, body, len);
    buf[n + len] = '\n';
    n += len + 1;
  }
  buf[n] = '\0';
  free(text);
}

/* The fifteen lines of zscan.h are the README's and docs/API.md's, word
 * for word, and they build and run: out.png, and the command's hash. */
START_TEST(the_example_everywhere_builds_and_runs) {
  static char example[8192], out[BIG];
  header_example(example, sizeof example);
  static const char *const pages[] = {"README.md", "docs/API.md"};
  for (int i = 0; i < 2; i++) {
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", ZS_SOURCE_DIR, pages[i]);
    char *text = slurp_text(path);
    ck_assert_msg(strstr(text, example) != NULL, "%s lacks the example of zscan.h:\n%s", pages[i],
                  example);
    free(text);
  }
  char dir[4200], src[4400], cmd[9000];
  snprintf(dir, sizeof dir, "%s/library-example", ZS_BINARY_DIR);
  mkdir(dir, 0777);
  snprintf(src, sizeof src, "%s/example.c", dir);
  FILE *f = fopen(src, "w");
  fputs(example, f);
  fclose(f);
  snprintf(cmd, sizeof cmd,
           "cd %s && rm -f out.png && %s -std=c11 -Wall -Wextra -Werror %s -I%s/include example.c "
           "-L%s -lzscan -o example 2>&1 && LD_LIBRARY_PATH=%s ./example builtin:cubes?n=3",
           dir, cc(), CONSUMER_FLAGS, ZS_SOURCE_DIR, ZS_BINARY_DIR, ZS_BINARY_DIR);
  ck_assert_msg(shell(cmd, out, sizeof out) == 0, "%s: %s", cmd, out);
  char png[4400];
  snprintf(png, sizeof png, "%s/out.png", dir);
  zs_image im = {0};
  zs_error err = {0};
  ck_assert_msg(zs_png_read(png, &im, &err) == ZS_OK, "%s", err.msg);
  char want[32];
  snprintf(want, sizeof want, "%016llx\n", (unsigned long long)zs_image_hash(&im));
  ck_assert_str_eq(out, want);
  zs_image_free(&im);
  static char cli[BIG], cerr[1024];
  const char *args[] = {"render", "builtin:cubes?n=3", "--stats", "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(args, cli, sizeof cli, cerr, sizeof cerr), 0);
  ck_assert_msg(strstr(cli, want) == NULL, "image_hash is printed without a newline");
  want[16] = '\0';
  ck_assert_ptr_nonnull(strstr(cli, want));
}
END_TEST

/* zs_query_objects gives the lines of `zscan query`. */
START_TEST(query_objects_equal_the_command) {
  static char cli[BIG], cerr[1024], mine[BIG];
  const char *input = "builtin:cubes?n=3";
  const char *args[] = {"query", input, "--size", "160x120", NULL};
  ck_assert_int_eq(zs_test_run_zscan(args, cli, sizeof cli, cerr, sizeof cerr), 0);
  zs_error err = {0};
  zs_scene *scene;
  ck_assert_int_eq(zs_scene_load(input, NULL, &scene, &err), ZS_OK);
  zs_render_opts o = {0};
  o.width = 160;
  o.height = 120;
  zs_object_visibility *v;
  int32_t n;
  ck_assert_msg(zs_query_objects(scene, &o, &v, &n, &err) == ZS_OK, "%s", err.msg);
  ck_assert_int_eq(n, 27);
  size_t len = 0;
  uint64_t seen = 0;
  for (int32_t k = 0; k < n; k++) {
    len += (size_t)snprintf(mine + len, sizeof mine - len, "object %s visible=%llu bbox=%llu\n",
                            v[k].name, (unsigned long long)v[k].visible,
                            (unsigned long long)v[k].box_samples);
    seen += v[k].visible;
  }
  ck_assert_uint_gt(seen, 0);
  ck_assert_msg(strncmp(cli, mine, len) == 0, "zscan query:\n%s\nzs_query_objects:\n%s", cli, mine);
  free(v);
  zs_scene_destroy(scene);
}
END_TEST

/* zs_render_normals is `zscan render --normals`, float for float; and
 * zs_scene_id_objects turns the id image into objects whose pixel counts
 * are zs_query_objects' (a scene of several objects, and an OBJ whose
 * objects interleave their faces' ids). */
START_TEST(normals_and_objects_equal_the_command) {
  static char out[BIG], cerr[1024];
  const char *input = "builtin:cubes?n=3";
  char pfm[4200];
  snprintf(pfm, sizeof pfm, "%s", zs_test_bin("library-normals.pfm"));
  const char *args[] = {"render", input, "--size", "160x120", "-o",
                        zs_test_bin("library-normals.png"), "--normals", pfm, NULL};
  ck_assert_msg(zs_test_run_zscan(args, out, sizeof out, cerr, sizeof cerr) == 0, "%s", cerr);
  size_t n = 0;
  unsigned char *file = zs_test_slurp(pfm, &n);
  const char *header = "PF\n160 120\n-1.0\n";
  ck_assert_uint_eq(n, strlen(header) + 160 * 120 * 3 * 4);
  ck_assert_int_eq(memcmp(file, header, strlen(header)), 0);
  zs_error err = {0};
  zs_scene *scene;
  ck_assert_int_eq(zs_scene_load(input, NULL, &scene, &err), ZS_OK);
  zs_render_opts o = {0};
  o.width = 160;
  o.height = 120;
  float *xyz = NULL;
  ck_assert_msg(zs_render_normals(scene, &o, &xyz, &err) == ZS_OK, "%s", err.msg);
  size_t lit = 0;
  for (int y = 0; y < 120; y++) /* the file's rows run bottom up */
    for (int x = 0; x < 3 * 160; x++) {
      uint32_t bits = 0, mine;
      const unsigned char *b = file + strlen(header) + 4 * ((size_t)(119 - y) * 480 + (size_t)x);
      for (int k = 0; k < 4; k++) bits |= (uint32_t)b[k] << (8 * k);
      memcpy(&mine, &xyz[(size_t)y * 480 + (size_t)x], 4);
      ck_assert_msg(bits == mine, "pixel %d, %d, channel %d: %08x in the file, %08x here", x / 3,
                    y, x % 3, bits, mine);
      lit += mine != 0;
    }
  ck_assert_uint_gt(lit, 1000);
  free(xyz);
  free(file);

  const char *inputs[] = {input, zs_test_src("tests/data/query/squares.obj")};
  for (int k = 0; k < 2; k++) {
    if (k) {
      zs_scene_destroy(scene);
      ck_assert_msg(zs_scene_load(inputs[k], NULL, &scene, &err) == ZS_OK, "%s", err.msg);
    }
    o.shade = ZS_SHADE_ID;
    zs_image im;
    ck_assert_msg(zs_render(scene, &o, &im, NULL, NULL, &err) == ZS_OK, "%s", err.msg);
    int32_t *owner = NULL;
    uint32_t nids = 0;
    ck_assert_msg(zs_scene_id_objects(scene, &owner, &nids, &err) == ZS_OK, "%s", err.msg);
    uint64_t count[64] = {0};
    int32_t nobj = zs_scene_objects(scene);
    ck_assert_int_le(nobj, 64);
    for (size_t p = 0; p < 160 * 120; p++) {
      uint32_t rgb = im.rgb[p] & 0xFFFFFFu;
      if (!rgb) continue;
      ck_assert_uint_lt(rgb - 1, nids);
      ck_assert_int_ge(owner[rgb - 1], 0);
      count[owner[rgb - 1]]++;
    }
    zs_object_visibility *v;
    int32_t nv;
    o.shade = ZS_SHADE_AUTO;
    ck_assert_msg(zs_query_objects(scene, &o, &v, &nv, &err) == ZS_OK, "%s", err.msg);
    ck_assert_int_eq(nv, nobj);
    ck_assert_int_ge(nobj, 2);
    for (int32_t i = 0; i < nv; i++)
      ck_assert_msg(count[v[i].object] == v[i].visible, "%s object %s: %llu pixels by id, %llu",
                    inputs[k], v[i].name, (unsigned long long)count[v[i].object],
                    (unsigned long long)v[i].visible);
    free(v);
    free(owner);
    zs_image_free(&im);
  }
  zs_scene_destroy(scene);
}
END_TEST

/* zs_walk's frames are the rows of `zscan walk --csv` for the same
 * method (wall time aside), moving objects and all. */
START_TEST(walk_frames_equal_the_command) {
  static char cli[BIG], cerr[4096];
  const char *input = "builtin:teapots?count=40&level=3&moving=8&frames=16";
  const char *args[] = {"walk", input, "--cull", "chc", "--size", "160x120", "--csv", "-",
                        "--quiet", NULL};
  ck_assert_msg(zs_test_run_zscan(args, cli, sizeof cli, cerr, sizeof cerr) == 0, "%s", cerr);
  zs_error err = {0};
  zs_scene *scene;
  ck_assert_int_eq(zs_scene_load(input, NULL, &scene, &err), ZS_OK);
  zs_walk_opts o = {0};
  o.method = "chc";
  o.width = 160;
  o.height = 120;
  zs_walk *w;
  ck_assert_msg(zs_walk_create(scene, &o, &w, &err) == ZS_OK, "%s", err.msg);
  ck_assert_int_eq(zs_walk_frames(w), 16);
  uint64_t queries = 0;
  for (int32_t f = 0; f < zs_walk_frames(w); f++) {
    zs_walk_frame fr;
    ck_assert_msg(zs_walk_next(w, &fr, &err) == ZS_OK, "%s", err.msg);
    char want[512], key[64];
    snprintf(key, sizeof key, "\n%d,chc,", fr.frame); /* the CLI's rows: none first, then chc */
    const char *row = strstr(cli, key);
    ck_assert_msg(row != NULL, "no row for frame %d", fr.frame);
    row++;
    /* frame,method,chosen,modelled_ms,stall_ms,(wall_ms),queries,queries_hidden,faces_drawn,
     * objects_drawn,nodes_visited */
    snprintf(want, sizeof want, "%d,chc,chc,%.6f,%.6f,", fr.frame, fr.modelled_ms, fr.stall_ms);
    ck_assert_msg(strncmp(row, want, strlen(want)) == 0, "frame %d: '%.80s', want '%s'", f, row,
                  want);
    const char *after_wall = strchr(row + strlen(want), ',') + 1;
    snprintf(want, sizeof want, "%llu,%llu,%llu,%llu,%llu,", (unsigned long long)fr.queries,
             (unsigned long long)fr.queries_hidden, (unsigned long long)fr.faces_drawn,
             (unsigned long long)fr.objects_drawn, (unsigned long long)fr.nodes_visited);
    ck_assert_msg(strncmp(after_wall, want, strlen(want)) == 0, "frame %d: '%.80s', want '%s'", f,
                  after_wall, want);
    queries += fr.queries;
  }
  ck_assert_uint_gt(queries, 0);
  zs_walk_destroy(w);
  zs_scene_destroy(scene);
  ck_assert_int_eq(zs_walk_create(NULL, &(zs_walk_opts){"magic", 0, 0, 0}, &w, &err),
                   ZS_ERR_ARG);
  ck_assert_ptr_nonnull(strstr(err.msg, "culling method 'magic'"));
}
END_TEST

/* The version three ways: the header, the library, the command; and the
 * pkg-config file made beside the library. */
START_TEST(one_version_everywhere) {
  static char out[BIG];
  const char *args[] = {"--version", NULL};
  char err[256];
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, err, sizeof err), 0);
  char want[128];
  snprintf(want, sizeof want, "zscan %s (library %s)\n", ZSCAN_VERSION_STRING, zs_version());
  ck_assert_msg(strncmp(out, want, strlen(want)) == 0, "%s", out);
  ck_assert_ptr_nonnull(strstr(out, "span fill: "));
  char cmd[4400];
  snprintf(cmd, sizeof cmd, "pkg-config --modversion %s/zscan.pc", ZS_BINARY_DIR);
  ck_assert_int_eq(shell(cmd, out, sizeof out), 0);
  snprintf(want, sizeof want, "%s\n", ZSCAN_VERSION_STRING);
  ck_assert_str_eq(out, want);
}
END_TEST

int main(void) {
  Suite *s = suite_create("library");
  TCase *tc = tcase_create("library");
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, headers_compile_alone_as_c_and_cxx);
  tcase_add_test(tc, headers_include_nothing_private);
  tcase_add_test(tc, shared_library_exports_the_api_only);
  tcase_add_test(tc, zero_config_renders);
  tcase_add_test(tc, library_errors_name_its_options_not_flags);
  tcase_add_test(tc, scene_notes_name_a_skipped_texture);
  tcase_add_test(tc, scene_from_arrays_equals_the_obj);
  tcase_add_test(tc, scene_from_arrays_names_the_bad_element);
  tcase_add_test(tc, render_hash_equals_the_command);
  tcase_add_test(tc, cxx_example_queries);
  tcase_add_test(tc, query_objects_equal_the_command);
  tcase_add_test(tc, normals_and_objects_equal_the_command);
  tcase_add_test(tc, walk_frames_equal_the_command);
  tcase_add_test(tc, the_example_everywhere_builds_and_runs);
  tcase_add_test(tc, one_version_everywhere);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
