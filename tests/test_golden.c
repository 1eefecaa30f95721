/* Golden images: every test scene in every hidden-surface mode and shading,
 * checked by the hash of its pixels (zs_image_hash) against
 * tests/golden/hashes.txt.  The same file must hold for every build (gcc,
 * clang, -O0, -O3: CI runs this suite in each), the two modes must agree,
 * and shuffling the faces of the scene must change no byte.
 *
 * On a mismatch the image is written to the build directory as
 * golden-NAME.png, with golden-NAME.txt listing the differing rows.
 * To accept new images (with a reason in the commit message):
 *   ZS_GOLDEN_UPDATE=1 build/test_golden   (rewrites tests/golden/hashes.txt)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/rng.h"
#include "scene/camera.h"
#include "scene/model.h"
#include "tests/testutil.h"
#include "lib/frame.h"
#include "lib/frame_camera.h"
#include "lib/image.h"
#include "lib/input.h"
#include "lib/scene_draw.h"

typedef struct golden_case {
  const char *name;
  const char *input; /* relative to the source tree, or builtin: */
  int width, height;
  zs_shade shade;
  int cull_back;
  int has_eye;
  double eye[3], target[3];
  zs_frame_style style;
  zs_filter filter;
  int shadows; /* every directional and spot light casts them (zscan render --shadows) */
  int samples, supersample; /* anti-aliasing (zscan render --samples, --supersample) */
  double line_width, point_size; /* --line-width, --point-size; 0: 1 */
  zs_point_shape point_shape;    /* --point-shape */
} golden_case;

/* assimp-testmodels (tools/setup.sh installs it) */
#define BOX_TEXTURED "/usr/share/assimp/models/glTF2/BoxTextured-glTF"

static const golden_case cases[] = {
    {"default-flat", "builtin:default", 320, 240, ZS_SHADE_FLAT, 0, 0, {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"default-id", "builtin:default", 320, 240, ZS_SHADE_ID, 0, 0, {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"default-depth", "builtin:default", 320, 240, ZS_SHADE_DEPTH, 0, 0, {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"default-culled", "builtin:default", 200, 150, ZS_SHADE_ID, 1, 0, {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"default-close", "builtin:default", 256, 256, ZS_SHADE_FLAT, 0, 1, {1.5, 1.2, 2.0}, {0, 0.5, 0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"cubes-4", "builtin:cubes?n=4", 320, 240, ZS_SHADE_FLAT, 0, 0, {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"cubes-4-inside", "builtin:cubes?n=4", 160, 120, ZS_SHADE_ID, 0, 1, {3.1, 3.2, 3.3}, {0, 0, 0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"cyclic", "tests/data/scenes/cyclic.obj", 160, 160, ZS_SHADE_ID, 0, 1, {0.3, 0.2, 8}, {0, 0, 0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"interpenetrate", "tests/data/scenes/interpenetrate.obj", 200, 150, ZS_SHADE_FLAT, 0, 0, {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"interpenetrate-depth", "tests/data/scenes/interpenetrate.obj", 200, 150, ZS_SHADE_DEPTH, 0, 0, {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"sphere-ell", "tests/data/scenes/sphere_ell.obj", 200, 150, ZS_SHADE_FLAT, 0, 0, {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"sphere-ell-overdraw", "tests/data/scenes/sphere_ell.obj", 200, 150, ZS_SHADE_OVERDRAW, 0, 0, {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"default-hidden-line", "builtin:default", 320, 240, ZS_SHADE_FLAT, 0, 1, {12, 9, 16}, {0, 1, 0}, 1, 0, 0, 0, 0, 0, 0, 0},
    {"cubes-3-hidden-line", "builtin:cubes?n=3", 240, 180, ZS_SHADE_FLAT, 0, 0, {0}, {0}, 1, 0, 0, 0, 0, 0, 0, 0},
    /* shading from the files' attributes (auto: Phong for a model with them) */
    {"default-auto", "builtin:default", 320, 240, ZS_SHADE_AUTO, 0, 0, {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"default-gouraud", "builtin:default", 320, 240, ZS_SHADE_GOURAUD, 0, 0, {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"default-normal", "builtin:default", 320, 240, ZS_SHADE_NORMAL, 0, 0, {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"spheres-auto", "builtin:spheres?count=200", 320, 240, ZS_SHADE_AUTO, 0, 0, {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"teapot-textured", "scene/examples/teapot_textured.json", 320, 240, ZS_SHADE_AUTO, 0, 0,
     {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"teapot-textured-gouraud", "scene/examples/teapot_textured.json", 320, 240,
     ZS_SHADE_GOURAUD, 0, 0, {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"checker-nearest", "scene/examples/checker/checker_plane.json", 320, 240, ZS_SHADE_AUTO, 0,
     0, {0}, {0}, 0, ZS_FILTER_NEAREST, 0, 0, 0, 0, 0, 0},
    {"checker-bilinear", "scene/examples/checker/checker_plane.json", 320, 240, ZS_SHADE_AUTO,
     0, 0, {0}, {0}, 0, ZS_FILTER_BILINEAR, 0, 0, 0, 0, 0, 0},
    {"checker-trilinear", "scene/examples/checker/checker_plane.json", 320, 240, ZS_SHADE_AUTO,
     0, 0, {0}, {0}, 0, ZS_FILTER_TRILINEAR, 0, 0, 0, 0, 0, 0},
    {"crate-obj", "tests/data/scenes/crate.obj", 240, 180, ZS_SHADE_AUTO, 0, 1, {3, 2.5, 4},
     {0, 0, 0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"crate-obj-unlit", "tests/data/scenes/crate.obj", 240, 180, ZS_SHADE_UNLIT, 0, 1,
     {3, 2.5, 4}, {0, 0, 0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"ply-colours", "tests/data/models/rgb_quad.ply", 160, 120, ZS_SHADE_AUTO, 0, 0, {0}, {0},
     0, 0, 0, 0, 0, 0, 0, 0},
    {"ply-colours-unlit", "tests/data/models/rgb_quad.ply", 160, 120, ZS_SHADE_UNLIT, 0, 0,
     {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"gltf-painted", "tests/data/models/painted_triangle.gltf", 160, 120, ZS_SHADE_AUTO, 0, 0,
     {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"gltf-box-textured", BOX_TEXTURED "/BoxTextured.gltf", 240, 180, ZS_SHADE_AUTO, 0, 0, {0},
     {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    {"glb-box-textured", BOX_TEXTURED "-Binary/BoxTextured.glb", 240, 180, ZS_SHADE_AUTO, 0, 0,
     {0}, {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    /* shadow maps: the key light's from above left, a spot's of the scene file */
    {"default-shadows", "builtin:default", 320, 240, ZS_SHADE_AUTO, 0, 0, {0}, {0}, 0, 0, 1, 0, 0, 0, 0, 0},
    {"spot-shadow", "scene/examples/spotlight.json", 240, 180, ZS_SHADE_AUTO, 0, 0, {0},
     {0}, 0, 0, 0, 0, 0, 0, 0, 0},
    /* anti-aliased: multisampled, supersampled, hidden lines */
    {"default-msaa4", "builtin:default", 320, 240, ZS_SHADE_AUTO, 0, 0, {0}, {0}, 0, 0, 0, 4, 0, 0, 0, 0},
    {"default-ssaa4", "builtin:default", 320, 240, ZS_SHADE_AUTO, 0, 0, {0}, {0}, 0, 0, 0, 4, 1, 0, 0, 0},
    {"checker-msaa8", "scene/examples/checker/checker_plane.json", 320, 240, ZS_SHADE_AUTO, 0,
     0, {0}, {0}, 0, 0, 0, 8, 0, 0, 0, 0},
    {"cubes-3-hidden-line-aa16", "builtin:cubes?n=3", 240, 180, ZS_SHADE_FLAT, 0, 0, {0}, {0},
     1, 0, 0, 16, 0, 0, 0, 0},
    /* the visible edges over the faces, flat and Phong, and anti-aliased */
    {"cubes-3-wireframe", "builtin:cubes?n=3", 240, 180, ZS_SHADE_FLAT, 0, 0, {0}, {0}, 2, 0, 0,
     0, 0, 0, 0, 0},
    {"default-wireframe-msaa4", "builtin:default", 320, 240, ZS_SHADE_AUTO, 0, 1,
     {12, 9, 16}, {0, 1, 0}, 2, 0, 0, 4, 0, 0, 0, 0},
    {"cubes-3-wireframe-width3", "builtin:cubes?n=3", 240, 180, ZS_SHADE_FLAT, 0, 0, {0}, {0}, 2,
     0, 0, 0, 0, 3, 0, 0},
    {"cubes-3-hidden-line-width2", "builtin:cubes?n=3", 240, 180, ZS_SHADE_FLAT, 0, 0, {0}, {0},
     1, 0, 0, 0, 0, 2, 0, 0},
    /* transparent panes and a glass ball, composited in the A-buffer */
    {"glass", "scene/examples/glass.json", 320, 240, ZS_SHADE_AUTO, 0, 0, {0}, {0}, 0, 0, 0, 0,
     0, 0, 0, 0},
    {"glass-gouraud-msaa4", "scene/examples/glass.json", 240, 180, ZS_SHADE_GOURAUD, 0, 0, {0},
     {0}, 0, 0, 0, 4, 0, 0, 0, 0},
    /* OBJ's l and p: a spiral 3 pixels wide round a cube, discs of 9 at
     * its corners; the same anti-aliased; a PLY point cloud in squares */
    {"lines-wire-cube", "tests/data/scenes/wire_cube.obj", 320, 240, ZS_SHADE_AUTO, 0, 0, {0},
     {0}, 0, 0, 0, 0, 0, 3, 9, ZS_POINT_DISC},
    {"lines-wire-cube-msaa4", "tests/data/scenes/wire_cube.obj", 320, 240, ZS_SHADE_AUTO, 0, 0,
     {0}, {0}, 0, 0, 0, 4, 0, 3, 9, ZS_POINT_DISC},
    {"lines-wire-cube-id", "tests/data/scenes/wire_cube.obj", 160, 120, ZS_SHADE_ID, 0, 0, {0},
     {0}, 0, 0, 0, 0, 0, 2, 5, ZS_POINT_SQUARE},
    {"cloud-points", "tests/data/models/cloud.ply", 240, 240, ZS_SHADE_AUTO, 0, 0, {0}, {0}, 0,
     0, 0, 0, 0, 0, 4, ZS_POINT_SQUARE},
};
enum { NCASES = sizeof cases / sizeof cases[0] };

/* Loads the case's input; 0 (skipped) for a model of a package that is
 * not installed, or of a format this build reads without (assimp). */
static int load_input(const char *input, zs_scene *s) {
  zs_error err;
  zs_error_clear(&err);
  const char *spec = strncmp(input, "builtin:", 8) == 0 || input[0] == '/' ? input
                                                                           : zs_test_src(input);
  char path[4096];
  snprintf(path, sizeof path, "%s", spec);
  if (input[0] == '/' && !zs_test_exists(path)) {
    printf("golden: %s not installed, skipped\n", path);
    return 0;
  }
  zs_status st = zs_input_load_scene(path, s, &err);
  if (st == ZS_ERR_UNSUPPORTED) {
    printf("golden: %s: %s, skipped\n", input, err.msg);
    return 0;
  }
  ck_assert_msg(st == ZS_OK, "%s", err.msg);
  return 1;
}

/* The case's camera: a scene file's own (as zscan render takes it), else
 * the automatic one, with the case's eye and target when it gives them. */
static zs_camera case_camera(const golden_case *c, const zs_scene *s) {
  zs_camera cam;
  zs_camera_default(&cam);
  const size_t n = strlen(c->input);
  if (n > 5 && strcmp(c->input + n - 5, ".json") == 0) cam = s->camera;
  if (c->has_eye) {
    memcpy(cam.eye, c->eye, sizeof cam.eye);
    memcpy(cam.target, c->target, sizeof cam.target);
    cam.has_eye = cam.has_target = 1;
  }
  return cam;
}

static uint64_t render_case_threads(const golden_case *c, const zs_scene *s, zs_algo algo,
                                    int threads, zs_image *keep, zs_raster_stats *stats) {
  const zs_camera cam = case_camera(c, s);
  const zs_shadow_opts so = {c->shadows, 0, ZS_SHADOW_BIAS_UNITS, ZS_SHADOW_BIAS_SLOPE};
  zs_frame_opts o = {c->width,  c->height, algo, c->shade, c->cull_back,
                     threads,   c->style, c->filter, NULL, 0, &so, c->samples, c->supersample,
                     c->line_width, c->point_size, c->point_shape};
  zs_image im;
  zs_error err;
  zs_error_clear(&err);
  ck_assert_msg(zs_frame_render(s, &cam, &o, &im, NULL, stats, &err) == ZS_OK, "%s", err.msg);
  uint64_t h = zs_image_hash(&im);
  if (keep) *keep = im;
  else zs_image_free(&im);
  return h;
}

/* The case on a device whose span fill and vertex stage stop at spans
 * (zscan.h, zs_span_fill): the same bytes at every level. */
static uint64_t render_case_spans(const golden_case *c, const zs_scene *s, zs_algo algo,
                                  zs_span_fill spans) {
  const zs_camera cam = case_camera(c, s);
  zs_error err;
  zs_error_clear(&err);
  double view[16], proj[16];
  ck_assert_int_eq(zs_frame_camera(s, &cam, c->width, c->height, view, proj, &err), ZS_OK);
  zs_device_config cfg = {c->width, c->height, algo, c->shade, c->cull_back, 1,
                          ZS_BACKGROUND_RGB, spans, (int)c->filter};
  zs_device *d = NULL;
  ck_assert_msg(zs_device_create(&cfg, &d, &err) == ZS_OK, "%s", err.msg);
  const zs_shadow_opts so = {c->shadows, 0, ZS_SHADOW_BIAS_UNITS, ZS_SHADOW_BIAS_SLOPE};
  zs_shadow_set maps = {0};
  ck_assert_msg(zs_frame_lights_and_shadows(d, s, NULL, 0, &so, view, 1, &maps, &err) == ZS_OK,
                "%s", err.msg);
  zs_image im;
  const zs_frame_look look = {c->style, c->line_width, c->point_size, c->point_shape};
  ck_assert_int_eq(zs_image_alloc(&im, c->width, c->height, &err), ZS_OK);
  ck_assert_msg(zs_frame_render_samples(d, s, view, proj, &look, c->samples,
                                        c->supersample, &im, NULL, &err) == ZS_OK,
                "%s", err.msg);
  const uint64_t h = zs_image_hash(&im);
  zs_image_free(&im);
  zs_device_destroy(d);
  zs_shadow_set_free(&maps);
  return h;
}

static uint64_t render_case(const golden_case *c, const zs_scene *s, zs_algo algo,
                            zs_image *keep) {
  return render_case_threads(c, s, algo, 1, keep, NULL);
}

/* The faces of every mesh in a seeded random order (each keeping its id
 * and colour), and the instances drawn in a seeded random order. */
static void shuffle_scene(zs_scene *s, uint64_t seed) {
  zs_rng rng;
  zs_rng_seed(&rng, seed);
  for (int32_t k = 0; k < s->nmeshes; k++) {
    zs_mesh *m = &s->meshes[k].mesh;
    int32_t n = m->nfaces;
    if (n == 0) continue; /* lines or points alone: no faces to shuffle */
    int32_t *perm = malloc((size_t)(n ? n : 1) * sizeof *perm);
    int32_t *start = malloc((size_t)(n + 1) * sizeof *start);
    int32_t *vert = malloc((size_t)(m->face_start[n] ? m->face_start[n] : 1) * sizeof *vert);
    uint32_t *rgb = malloc((size_t)(n ? n : 1) * sizeof *rgb);
    int32_t *id = malloc((size_t)(n ? n : 1) * sizeof *id);
    /* the corners' attribute vertices move with them, a face's material
     * with it */
    int32_t *attr = malloc((size_t)(m->face_start[n] ? m->face_start[n] : 1) * sizeof *attr);
    int32_t *mat = malloc((size_t)(n ? n : 1) * sizeof *mat);
    for (int32_t i = 0; i < n; i++) perm[i] = i;
    zs_rng_shuffle(&rng, perm, (size_t)n, sizeof *perm);
    start[0] = 0;
    for (int32_t i = 0; i < n; i++) {
      int32_t f = perm[i], fs = m->face_start[f], len = m->face_start[f + 1] - fs;
      memcpy(&vert[start[i]], &m->face_vert[fs], (size_t)len * sizeof *vert);
      if (m->corner_attr)
        memcpy(&attr[start[i]], &m->corner_attr[fs], (size_t)len * sizeof *attr);
      if (m->face_material) mat[i] = m->face_material[f];
      start[i + 1] = start[i] + len;
      rgb[i] = m->face_rgb[f];
      id[i] = m->face_id[f];
    }
    memcpy(m->face_start, start, (size_t)(n + 1) * sizeof *start);
    memcpy(m->face_vert, vert, (size_t)start[n] * sizeof *vert);
    memcpy(m->face_rgb, rgb, (size_t)n * sizeof *rgb);
    memcpy(m->face_id, id, (size_t)n * sizeof *id);
    if (m->corner_attr) memcpy(m->corner_attr, attr, (size_t)start[n] * sizeof *attr);
    if (m->face_material) memcpy(m->face_material, mat, (size_t)n * sizeof *mat);
    free(attr);
    free(mat);
    free(perm);
    free(start);
    free(vert);
    free(rgb);
    free(id);
  }
  zs_rng_shuffle(&rng, s->inst, (size_t)s->ninst, sizeof *s->inst);
}

static void write_artefacts(const golden_case *c, const zs_image *im) {
  char path[4096];
  snprintf(path, sizeof path, "%s/golden-%s.png", ZS_BINARY_DIR, c->name);
  zs_error err;
  zs_error_clear(&err);
  zs_png_write(path, im, &err);
  fprintf(stderr, "golden %s: image written to %s\n", c->name, path);
}

START_TEST(golden_case_matches) {
  const golden_case *c = &cases[_i];
  zs_scene m;
  if (!load_input(c->input, &m)) return;
  zs_image im;
  uint64_t hz = render_case(c, &m, ZS_ALGO_ZBUFFER, &im);
  /* hidden lines and the wireframe draw into the z-buffer's full frame
   * only (lines and points, into scanline mode's rows too) */
  const int zbuffer_only = c->style != ZS_STYLE_SOLID;
  uint64_t hs = zbuffer_only ? hz : render_case(c, &m, ZS_ALGO_SCANLINE, NULL);
  ck_assert_msg(hz == hs, "%s: zbuffer %016llx != scanline %016llx", c->name,
                (unsigned long long)hz, (unsigned long long)hs);
  zs_scene shuffled;
  ck_assert(load_input(c->input, &shuffled));
  shuffle_scene(&shuffled, 1000 + (uint64_t)_i);
  uint64_t hsh = render_case(c, &shuffled, ZS_ALGO_ZBUFFER, NULL);
  ck_assert_msg(hz == hsh, "%s: shuffled faces give %016llx, not %016llx", c->name,
                (unsigned long long)hsh, (unsigned long long)hz);
  /* the same bytes and the same counters for every number of threads, in
   * both modes (scanline mode walks bands of rows on threads) */
  for (int algo = 0; algo < (zbuffer_only ? 1 : 2); algo++) {
    const zs_algo a = algo ? ZS_ALGO_SCANLINE : ZS_ALGO_ZBUFFER;
    zs_raster_stats one, many;
    render_case_threads(c, &m, a, 1, NULL, &one);
    for (int threads = 2; threads <= 4; threads++) {
      uint64_t ht = render_case_threads(c, &m, a, threads, NULL, &many);
      ck_assert_msg(hz == ht, "%s, %s: %d threads give %016llx, not %016llx", c->name,
                    zs_algo_name(a), threads, (unsigned long long)ht, (unsigned long long)hz);
      ck_assert_msg(memcmp(&one, &many, sizeof one) == 0, "%s, %s: %d threads change the counters",
                    c->name, zs_algo_name(a), threads);
    }
  }
  /* and at every SIMD level of the span fill and the vertex stage */
  const zs_span_fill fills[] = {ZS_SPANS_SCALAR, ZS_SPANS_SSE2, ZS_SPANS_AVX2, ZS_SPANS_BEST};
  for (int f = 0; f < 4; f++)
    for (int algo = 0; algo < (zbuffer_only ? 1 : 2); algo++) {
      const zs_algo a = algo ? ZS_ALGO_SCANLINE : ZS_ALGO_ZBUFFER;
      const uint64_t hf = render_case_spans(c, &m, a, fills[f]);
      ck_assert_msg(hz == hf, "%s, %s: span fill %d gives %016llx, not %016llx", c->name,
                    zs_algo_name(a), (int)fills[f], (unsigned long long)hf,
                    (unsigned long long)hz);
    }
  uint64_t want = 0;
  const int golden = zs_golden_check("hashes.txt", c->name, hz, &want);
  ck_assert_msg(golden >= 0, "%s: no golden hash (run with ZS_GOLDEN_UPDATE=1)", c->name);
  if (!golden) write_artefacts(c, &im);
  ck_assert_msg(golden, "%s: hash %016llx, golden %016llx", c->name, (unsigned long long)hz,
                (unsigned long long)want);
  zs_image_free(&im);
  zs_scene_free(&shuffled);
  zs_scene_free(&m);
}
END_TEST

int main(void) {
  Suite *s = suite_create("golden");
  TCase *tc = tcase_create("images");
  tcase_set_timeout(tc, 600);
  tcase_add_loop_test(tc, golden_case_matches, 0, NCASES);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
