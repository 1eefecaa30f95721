/* Transparency (raster/abuffer.h): the A-buffer's image equals a
 * depth-peeling reference built from each face drawn alone; it does not
 * depend on the order of the faces or the draws, the mode or the threads;
 * texture and vertex alpha; what queries (the device's and per object)
 * see through a transparent surface, and every exact culling method's image of a glass scene; the
 * fragment budget's error; opaque frames pay no memory.
 * (Golden cases of a scene file: test_golden's "glass".) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cull/cull.h"
#include "cull/octree.h"
#include "lib/input.h"
#include "raster/raster.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "tests/testutil.h"

enum { W = 64, H = 48, NQUADS = 6 };

static zs_error err;

/* Quads in x, y in [-1, 1] at eye depths z (left and right edges), each
 * with its own material; quad 0 and 1 are opaque, the rest transparent.
 * Quad 3 lies in quad 2's plane exactly (the id breaks the tie); quad 1
 * slants through the transparent ones. */
static const double quad_box[NQUADS][6] = {
    /* x0, x1, y0, y1, z at x0, z at x1 */
    {-1.0, 1.0, -1.0, 1.0, -4.0, -4.0},   /* the back wall, opaque */
    {-0.6, 0.9, -0.8, 0.5, -2.5, -0.5},   /* a slanting opaque card */
    {-0.9, 0.3, -0.5, 0.9, -1.5, -1.5},   /* red, alpha 128 */
    {-0.2, 0.6, -0.2, 0.6, -1.5, -1.5},   /* yellow, alpha 77, coplanar with red */
    {-0.3, 0.8, -0.9, 0.4, -2.0, -1.0},   /* green, alpha 100, slanting */
    {-0.5, 0.5, -0.3, 0.7, -1.2, -1.2}};  /* blue, alpha 200 */
static const uint8_t quad_rgba[NQUADS][4] = {{90, 90, 110, 255},  {220, 220, 220, 255},
                                             {230, 40, 40, 128},  {240, 220, 30, 77},
                                             {40, 200, 60, 100},  {40, 60, 230, 200}};

typedef struct quads {
  double pos[NQUADS * 12];
  int32_t start[NQUADS + 1], vert[NQUADS * 4], id[NQUADS], mat[NQUADS];
  uint32_t rgb[NQUADS];
  zs_material mats[NQUADS];
  zs_mesh mesh;
} quads;

/* The quads listed in order[0 .. n) as one mesh, each keeping its id;
 * opaque: every material's alpha 255. */
static void make_quads(quads *q, const int *order, int n, int opaque) {
  memset(q, 0, sizeof *q);
  for (int k = 0; k < NQUADS; k++) {
    q->mats[k] = zs_material_default();
    memcpy(q->mats[k].base, quad_rgba[k], 4);
    if (opaque) q->mats[k].base[3] = 255;
  }
  for (int i = 0; i < n; i++) {
    const double *b = quad_box[order[i]];
    const double c[4][3] = {{b[0], b[2], b[4]}, {b[1], b[2], b[5]}, {b[1], b[3], b[5]},
                            {b[0], b[3], b[4]}};
    memcpy(&q->pos[12 * i], c, sizeof c);
    q->start[i] = 4 * i;
    for (int j = 0; j < 4; j++) q->vert[4 * i + j] = 4 * i + j;
    q->id[i] = order[i];
    q->mat[i] = order[i];
  }
  q->start[n] = 4 * n;
  q->mesh = (zs_mesh){.pos = q->pos, .nverts = 4 * n, .face_start = q->start,
                      .face_vert = q->vert, .nfaces = n, .face_rgb = q->rgb, .face_id = q->id,
                      .nattrs = 4 * n, .face_material = q->mat, .materials = q->mats,
                      .nmaterials = NQUADS};
}

typedef struct frame {
  uint32_t rgb[W * H], depth[W * H], id[W * H];
} frame;

static void keep_rgb(void *user, const zs_row *row) {
  memcpy((uint32_t *)user + (size_t)row->y * (size_t)row->width, row->rgb,
         (size_t)row->width * sizeof(uint32_t));
}

static void keep_row(void *user, const zs_row *row) {
  frame *f = user;
  memcpy(&f->rgb[row->y * W], row->rgb, W * sizeof(uint32_t));
  memcpy(&f->depth[row->y * W], row->depth, W * sizeof(uint32_t));
  memcpy(&f->id[row->y * W], row->id, W * sizeof(uint32_t));
}

static zs_device *device(zs_algo algo, zs_shade shade, int threads) {
  zs_device_config cfg = {0};
  cfg.width = W, cfg.height = H, cfg.algo = algo, cfg.shade = shade, cfg.threads = threads;
  cfg.background = 0x102030;
  zs_device *d = NULL;
  zs_error_clear(&err);
  ck_assert_msg(zs_device_create(&cfg, &d, &err) == ZS_OK, "%s", err.msg);
  /* orthographic: x, y as given, eye depth -10 .. 10 to the depth range */
  const double view[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  const double proj[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -0.1, 0, 0, 0, 0, 1};
  zs_device_set_camera(d, view, proj);
  return d;
}

/* Draws each mesh in turn and finishes the frame into f. */
static void render(zs_device *d, zs_mesh *const *m, int n, frame *f) {
  zs_device_clear(d);
  zs_error_clear(&err);
  for (int i = 0; i < n; i++)
    ck_assert_msg(zs_device_draw(d, m[i], NULL, 0, ZS_RGB_MESH, &err) == ZS_OK, "%s", err.msg);
  ck_assert_msg(zs_device_finish(d, keep_row, f, &err) == ZS_OK, "%s", err.msg);
}

static void render_order(zs_algo algo, zs_shade shade, int threads, const int *order, frame *f) {
  zs_device *d = device(algo, shade, threads);
  quads *q = malloc(sizeof *q);
  make_quads(q, order, NQUADS, 0);
  zs_mesh *m = &q->mesh;
  render(d, &m, 1, f);
  free(q);
  zs_device_destroy(d);
}

/* The reference: each quad drawn alone and opaque gives its colour, depth
 * and id at every pixel; the opaque quads drawn together give the opaque
 * surface.  At each pixel the transparent quads' fragments in front of it
 * are peeled nearest first ((depth, id) ascending, as depth peeling's
 * passes find them) and composited front to back by abuffer.h's formula. */
static void reference(zs_shade shade, frame *out) {
  static frame alone[NQUADS];
  zs_device *d = device(ZS_ALGO_ZBUFFER, shade, 1);
  for (int k = 0; k < NQUADS; k++) {
    quads *q = malloc(sizeof *q);
    make_quads(q, &k, 1, 1);
    zs_mesh *m = &q->mesh;
    render(d, &m, 1, &alone[k]);
    free(q);
  }
  const int opaque_order[2] = {0, 1};
  quads *q = malloc(sizeof *q);
  make_quads(q, opaque_order, 2, 1);
  zs_mesh *m = &q->mesh;
  render(d, &m, 1, out);
  free(q);
  zs_device_destroy(d);
  for (int p = 0; p < W * H; p++) {
    uint32_t last_depth = 0, last_id = 0;
    int have_last = 0;
    uint64_t sum[3] = {0, 0, 0}, t = 1u << 16;
    for (;;) { /* one peel: the nearest fragment behind the last one */
      int best = -1;
      for (int k = 2; k < NQUADS; k++) {
        const uint32_t z = alone[k].depth[p], id = alone[k].id[p];
        if (id == ZS_ID_NONE) continue;
        if (!(z < out->depth[p] || (z == out->depth[p] && id < out->id[p]))) continue;
        if (have_last && !(z > last_depth || (z == last_depth && id > last_id))) continue;
        if (best < 0 || z < alone[best].depth[p] ||
            (z == alone[best].depth[p] && id < alone[best].id[p]))
          best = k;
      }
      if (best < 0 || t == 0) break;
      last_depth = alone[best].depth[p], last_id = alone[best].id[p], have_last = 1;
      const uint64_t a = quad_rgba[best][3];
      for (int c = 0; c < 3; c++) sum[c] += (alone[best].rgb[p] >> (16 - 8 * c) & 255) * a * t;
      t = (t * (255 - a) + 127) / 255;
    }
    uint32_t rgb = 0;
    for (int c = 0; c < 3; c++) {
      const uint64_t o = out->rgb[p] >> (16 - 8 * c) & 255;
      rgb |= (uint32_t)((sum[c] + 255 * o * t + (255u << 15)) / (255u << 16)) << (16 - 8 * c);
    }
    out->rgb[p] = rgb;
  }
}

static int count_differences(const frame *a, const frame *b) {
  int n = 0;
  for (int p = 0; p < W * H; p++) n += a->rgb[p] != b->rgb[p];
  return n;
}

/* The A-buffer against the peeling reference, unlit and lit, in both
 * modes, on one thread and three; and a pixel where all four transparent
 * quads lie over the card shows every one of them. */
START_TEST(abuffer_equals_depth_peeling) {
  static frame want, got, opaque_only;
  const zs_shade shades[2] = {ZS_SHADE_UNLIT, ZS_SHADE_PHONG};
  const int order[NQUADS] = {0, 1, 2, 3, 4, 5};
  for (int s = 0; s < 2; s++) {
    reference(shades[s], &want);
    for (int algo = 0; algo < 2; algo++)
      for (int threads = 1; threads <= 3; threads += 2) {
        render_order(algo ? ZS_ALGO_SCANLINE : ZS_ALGO_ZBUFFER, shades[s], threads, order, &got);
        const int n = count_differences(&want, &got);
        ck_assert_msg(n == 0, "%s, %s, %d threads: %d pixels differ from depth peeling",
                      zs_shade_name(shades[s]), algo ? "scanline" : "zbuffer", threads, n);
      }
  }
  /* the transparent quads change the opaque picture where they lie */
  zs_device *d = device(ZS_ALGO_ZBUFFER, ZS_SHADE_UNLIT, 1);
  quads *q = malloc(sizeof *q);
  make_quads(q, order, 2, 0);
  zs_mesh *m = &q->mesh;
  render(d, &m, 1, &opaque_only);
  free(q);
  zs_device_destroy(d);
  int changed = count_differences(&opaque_only, &got);
  printf("transparency: %d of %d pixels seen through glass\n", changed, W * H);
  ck_assert_int_gt(changed, W * H / 4);
}
END_TEST

/* Every order of the faces in one draw, and the quads drawn one a draw in
 * seeded random orders: the same bytes. */
START_TEST(any_order_gives_the_same_bytes) {
  static frame first, other;
  int order[NQUADS] = {0, 1, 2, 3, 4, 5};
  render_order(ZS_ALGO_ZBUFFER, ZS_SHADE_PHONG, 1, order, &first);
  uint64_t seed = 12345;
  for (int trial = 0; trial < 24; trial++) {
    for (int i = NQUADS - 1; i > 0; i--) { /* a seeded Fisher-Yates shuffle */
      seed = seed * 6364136223846793005u + 1442695040888963407u;
      const int j = (int)((seed >> 33) % (uint64_t)(i + 1)), t = order[i];
      order[i] = order[j], order[j] = t;
    }
    const zs_algo algo = trial & 1 ? ZS_ALGO_SCANLINE : ZS_ALGO_ZBUFFER;
    render_order(algo, ZS_SHADE_PHONG, 1 + trial % 3, order, &other);
    ck_assert_msg(count_differences(&first, &other) == 0, "trial %d: the order changed pixels",
                  trial);
    /* one quad a draw */
    zs_device *d = device(algo, ZS_SHADE_PHONG, 1);
    quads *q = malloc(NQUADS * sizeof *q);
    zs_mesh *m[NQUADS];
    for (int k = 0; k < NQUADS; k++) {
      make_quads(&q[k], &order[k], 1, 0);
      m[k] = &q[k].mesh;
    }
    render(d, m, NQUADS, &other);
    free(q);
    zs_device_destroy(d);
    ck_assert_msg(count_differences(&first, &other) == 0,
                  "trial %d: drawn a quad a draw, pixels changed", trial);
  }
}
END_TEST

/* A texture's alpha: a 2 x 1 texture, its left texel clear and its right
 * one opaque, over the wall: the left half shows the wall exactly, the
 * right the texel; ignoring alpha, both texels show; cut off (glTF's
 * MASK), each pixel all or nothing.  A mesh whose
 * vertex colours have alpha 0 leaves no trace. */
START_TEST(texture_and_vertex_alpha) {
  static frame wall, got;
  const uint8_t texels[8] = {255, 0, 0, 0, 10, 200, 30, 255};
  zs_texture *tex = NULL;
  zs_error_clear(&err);
  ck_assert_msg(zs_texture_create(2, 1, texels, &tex, &err) == ZS_OK, "%s", err.msg);
  ck_assert(!zs_texture_opaque(tex));
  const int back = 0;
  quads *wq = malloc(sizeof *wq);
  make_quads(wq, &back, 1, 0);
  zs_mesh *wm = &wq->mesh;
  zs_device *d = device(ZS_ALGO_ZBUFFER, ZS_SHADE_UNLIT, 1);
  render(d, &wm, 1, &wall);

  /* a quad over the whole frame at depth -1, textured */
  double pos[12] = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1};
  float uv[8] = {0, 0, 1, 0, 1, 1, 0, 1};
  int32_t start[2] = {0, 4}, vert[4] = {0, 1, 2, 3}, id[1] = {9};
  uint32_t rgb[1] = {0};
  zs_material mat = zs_material_default();
  mat.base[0] = mat.base[1] = mat.base[2] = 255;
  mat.base_texture = tex;
  mat.filter = ZS_FILTER_NEAREST;
  zs_mesh glass = {.pos = pos, .nverts = 4, .face_start = start, .face_vert = vert, .nfaces = 1,
                   .face_rgb = rgb, .face_id = id, .nattrs = 4, .uv = uv, .materials = &mat,
                   .nmaterials = 1};
  zs_mesh *both[2] = {wm, &glass};
  render(d, both, 2, &got);
  for (int y = 0; y < H; y++)
    for (int x = 0; x < W; x++) {
      const int p = y * W + x;
      if (x < W / 2)
        ck_assert_msg(got.rgb[p] == wall.rgb[p], "(%d, %d): %06x, the wall is %06x", x, y,
                      got.rgb[p], wall.rgb[p]);
      else
        ck_assert_msg(got.rgb[p] == 0x0AC81E, "(%d, %d): %06x, not the texel", x, y, got.rgb[p]);
    }

  /* a material that ignores alpha (glTF's OPAQUE mode): the texels as they are */
  mat.ignore_alpha = 1;
  render(d, both, 2, &got);
  for (int p = 0; p < W * H; p++)
    ck_assert_uint_eq(got.rgb[p], p % W < W / 2 ? 0xFF0000u : 0x0AC81Eu);
  mat.ignore_alpha = 0;

  /* glTF's MASK: the material's alpha 150 times the texel's; cut off at
   * 128 the right half is the texel, opaque; at 160 nothing is left */
  mat.base[3] = 150;
  for (int cut = 128; cut <= 160; cut += 32) {
    mat.alpha_cutoff = (uint8_t)cut;
    render(d, both, 2, &got);
    for (int p = 0; p < W * H; p++)
      ck_assert_uint_eq(got.rgb[p], p % W < W / 2 || cut == 160 ? wall.rgb[p] : 0x0AC81Eu);
  }
  mat.base[3] = 255;
  mat.alpha_cutoff = 0;

  /* vertex colours of alpha 0 */
  uint8_t clear[16] = {255, 255, 255, 0, 255, 255, 255, 0, 255, 255, 255, 0, 255, 255, 255, 0};
  zs_mesh ghost = {.pos = pos, .nverts = 4, .face_start = start, .face_vert = vert, .nfaces = 1,
                   .face_rgb = rgb, .face_id = id, .nattrs = 4, .color = clear};
  both[1] = &ghost;
  render(d, both, 2, &got);
  ck_assert_int_eq(count_differences(&wall, &got), 0);
  zs_device_destroy(d);
  zs_texture_destroy(tex);
  free(wq);
}
END_TEST

/* Queries: an opaque quad behind a transparent one counts every pixel it
 * would count alone (the glass occludes nothing), and the transparent
 * quad's own draw counts its pixels in front of the wall. */
START_TEST(queries_see_through_glass) {
  zs_device *d = device(ZS_ALGO_ZBUFFER, ZS_SHADE_PHONG, 1);
  const int wall = 0, card = 1, red = 2;
  quads *q = malloc(3 * sizeof *q);
  make_quads(&q[0], &wall, 1, 0);
  make_quads(&q[1], &card, 1, 0);
  make_quads(&q[2], &red, 1, 0);
  uint64_t alone, behind_glass, glass;
  for (int pass = 0; pass < 2; pass++) {
    zs_device_clear(d);
    zs_error_clear(&err);
    zs_query qa, qb;
    ck_assert(zs_device_draw(d, &q[0].mesh, NULL, 0, ZS_RGB_MESH, &err) == ZS_OK);
    if (pass) {
      ck_assert(zs_device_query_begin(d, &qb, &err) == ZS_OK);
      ck_assert_msg(zs_device_draw(d, &q[2].mesh, NULL, 0, ZS_RGB_MESH, &err) == ZS_OK, "%s",
                    err.msg);
      ck_assert(zs_device_query_end(d, &err) == ZS_OK);
      glass = zs_device_query_result(d, qb);
    }
    ck_assert(zs_device_query_begin(d, &qa, &err) == ZS_OK);
    ck_assert(zs_device_draw(d, &q[1].mesh, NULL, 0, ZS_RGB_MESH, &err) == ZS_OK);
    ck_assert(zs_device_query_end(d, &err) == ZS_OK);
    if (pass) behind_glass = zs_device_query_result(d, qa);
    else alone = zs_device_query_result(d, qa);
    ck_assert(zs_device_finish(d, NULL, NULL, &err) == ZS_OK);
  }
  /* the red quad covers x in [-0.9, 0.3], y in [-0.5, 0.9]: the centres
   * of columns 3 .. 41 and rows 12 .. 45 in window pixels */
  ck_assert_uint_eq(glass, 39 * 34);
  ck_assert_uint_gt(alone, 0);
  ck_assert_uint_eq(behind_glass, alone);
  free(q);
  zs_device_destroy(d);
}
END_TEST

/* Twenty transparent layers over an 8-pixel row pass its budget of 16 a
 * pixel: the draw fails with the row named; depthsort mode refuses
 * transparent faces; an opaque frame holds no A-buffer memory. */
START_TEST(budget_and_refusals) {
  enum { LAYERS = 20 };
  double pos[LAYERS * 12];
  int32_t start[LAYERS + 1], vert[LAYERS * 4], id[LAYERS];
  uint32_t rgb[LAYERS];
  for (int i = 0; i < LAYERS; i++) {
    const double z = -1.0 - 0.1 * i, c[12] = {-1, -1, z, 1, -1, z, 1, 1, z, -1, 1, z};
    memcpy(&pos[12 * i], c, sizeof c);
    start[i] = 4 * i;
    for (int j = 0; j < 4; j++) vert[4 * i + j] = 4 * i + j;
    id[i] = i;
    rgb[i] = 0;
  }
  start[LAYERS] = 4 * LAYERS;
  zs_material mat = zs_material_default();
  mat.base[3] = 40;
  zs_mesh stack = {.pos = pos, .nverts = 4 * LAYERS, .face_start = start, .face_vert = vert,
                   .nfaces = LAYERS, .face_rgb = rgb, .face_id = id, .nattrs = 4 * LAYERS,
                   .materials = &mat, .nmaterials = 1};
  zs_device_config cfg = {0};
  cfg.width = 8, cfg.height = 4, cfg.shade = ZS_SHADE_UNLIT;
  for (int algo = 0; algo < 3; algo++) {
    cfg.algo = (zs_algo)algo;
    zs_device *d = NULL;
    zs_error_clear(&err);
    ck_assert(zs_device_create(&cfg, &d, &err) == ZS_OK);
    const double id16[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1},
                 proj[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -0.1, 0, 0, 0, 0, 1};
    zs_device_set_camera(d, id16, proj);
    zs_device_clear(d);
    const zs_status st = zs_device_draw(d, &stack, NULL, 0, ZS_RGB_MESH, &err);
    if (cfg.algo == ZS_ALGO_DEPTHSORT) {
      ck_assert_int_eq(st, ZS_ERR_ARG);
      ck_assert_str_eq(err.msg,
                       "draw: transparent faces need the zbuffer or scanline mode, not depthsort");
    } else {
      ck_assert_int_eq(st, ZS_ERR_LIMIT);
      ck_assert_str_eq(err.msg, "draw: row 0 holds more than 128 transparent fragments (16 a pixel)");
      /* a caller that finishes the frame anyway gets it opaque, safely */
      zs_error_clear(&err);
      ck_assert_int_eq(zs_device_finish(d, NULL, NULL, &err), ZS_OK);
      uint32_t rows[8 * 4];
      ck_assert_int_eq(zs_device_finish(d, keep_rgb, rows, &err), ZS_OK);
      ck_assert_uint_eq(rows[0], 0);
    }
    /* sixteen layers fit */
    stack.nfaces = 16;
    zs_device_clear(d);
    zs_error_clear(&err);
    ck_assert_int_eq(zs_device_draw(d, &stack, NULL, 0, ZS_RGB_MESH, &err) == ZS_OK,
                     cfg.algo != ZS_ALGO_DEPTHSORT);
    stack.nfaces = LAYERS;
    zs_device_destroy(d);
  }
  /* an opaque frame (every material opaque): no A-buffer */
  zs_device *d = device(ZS_ALGO_ZBUFFER, ZS_SHADE_PHONG, 1);
  const zs_device_memory before = zs_device_memory_of(d);
  const int opaque[2] = {0, 1};
  quads *q = malloc(sizeof *q);
  make_quads(q, opaque, 2, 1);
  static frame f;
  zs_mesh *m = &q->mesh;
  render(d, &m, 1, &f);
  ck_assert_uint_eq(zs_device_memory_of(d).pixel_buffers, before.pixel_buffers);
  free(q);
  zs_device_destroy(d);
}
END_TEST

/* zs_query_objects (zscan query) sees through glass too: in the glass
 * scene the floor and the teapot own the pixels, and their boxes pass the
 * samples, of the scene without its four glass objects; the glass objects
 * own pixels of their own; drawn flat, the glass is opaque and hides
 * part of the teapot; and at 4 samples the same holds sample for sample. */
START_TEST(object_queries_see_through_glass) {
  zs_scene s;
  zs_error_clear(&err);
  ck_assert_msg(zs_input_load_scene(zs_test_src("scene/examples/glass.json"), &s, &err) == ZS_OK,
                "%s", err.msg);
  ck_assert_int_eq(s.ninst, 6); /* floor, teapot: opaque; three panes and a ball: glass */
  for (int samples = 1; samples <= 4; samples += 3) {
    zs_render_opts o = {0};
    o.width = 160;
    o.height = 120;
    o.samples = samples;
    zs_object_visibility *all, *opaque, *flat;
    int32_t n_all, n_opaque, n_flat;
    ck_assert_msg(zs_query_objects(&s, &o, &all, &n_all, &err) == ZS_OK, "%s", err.msg);
    o.shade = ZS_SHADE_FLAT;
    ck_assert_msg(zs_query_objects(&s, &o, &flat, &n_flat, &err) == ZS_OK, "%s", err.msg);
    o.shade = ZS_SHADE_AUTO;
    const int32_t ninst = s.ninst;
    s.ninst = 2; /* the same camera: the scene's own */
    ck_assert_msg(zs_query_objects(&s, &o, &opaque, &n_opaque, &err) == ZS_OK, "%s", err.msg);
    s.ninst = ninst;
    ck_assert_int_eq(n_all, 6);
    ck_assert_int_eq(n_opaque, 2);
    uint64_t vis[6] = {0}, box[6] = {0}, flat_vis[6] = {0};
    for (int k = 0; k < 6; k++) {
      vis[all[k].object] = all[k].visible;
      box[all[k].object] = all[k].box_samples;
      flat_vis[flat[k].object] = flat[k].visible;
    }
    for (int k = 0; k < 2; k++) {
      const int i = opaque[k].object;
      ck_assert_msg(vis[i] == opaque[k].visible, "%d samples: %s owns %llu, %llu without the glass",
                    samples, opaque[k].name, (unsigned long long)vis[i],
                    (unsigned long long)opaque[k].visible);
      ck_assert_uint_eq(box[i], opaque[k].box_samples);
      ck_assert_uint_gt(vis[i], 0);
    }
    for (int i = 2; i < 6; i++) ck_assert_uint_gt(vis[i], 0);
    ck_assert_uint_lt(flat_vis[1], vis[1]); /* opaque panes hide some of the teapot */
    free(all);
    free(opaque);
    free(flat);
  }
  zs_scene_free(&s);
}
END_TEST

/* Every exact culling method draws the glass scene as drawing everything
 * does, byte for byte, from cameras around it: what lies behind glass is
 * not culled (a transparent surface occludes nothing), and the glass
 * behind an opaque object drops out alone. */

START_TEST(culling_sees_through_glass) {
  static const zs_cull_method exact[] = {
      ZS_CULL_NONE, ZS_CULL_VFC,   ZS_CULL_HSW,  ZS_CULL_CHC,  ZS_CULL_CHC_PROB,
      ZS_CULL_AUTO, ZS_CULL_CHCPP, ZS_CULL_NOHC, ZS_CULL_IDEAL, ZS_CULL_IDEAL_BOX, ZS_CULL_HZB};
  enum { NM = sizeof exact / sizeof exact[0], CW = 160, CH = 120, VIEWS = 6 };
  /* round the scene, low and high, twice over (the temporal methods
   * reuse the last frame's answers); the last from behind the teapot */
  static const double eyes[VIEWS][3] = {{1.5, 2.4, 5.5}, {-4, 1.2, 3}, {4.5, 0.6, 2},
                                        {0.2, 5, 0.5},   {-1, 0.8, 6}, {0.3, 0.9, -4.5}};
  zs_scene s;
  zs_error_clear(&err);
  ck_assert_msg(zs_input_load_scene(zs_test_src("scene/examples/glass.json"), &s, &err) == ZS_OK,
                "%s", err.msg);
  zs_octree t;
  ck_assert_msg(zs_octree_build(&t, &s, NULL, &err) == ZS_OK, "%s", err.msg);
  zs_device *d[NM];
  zs_culler *c[NM];
  for (int k = 0; k < NM; k++) {
    zs_device_config cfg = {CW, CH, ZS_ALGO_ZBUFFER, ZS_SHADE_AUTO, 0, 1, 0x102030, 0, 0};
    ck_assert_int_eq(zs_device_create(&cfg, &d[k], &err), ZS_OK);
    ck_assert_int_eq(zs_device_set_lights(d[k], s.lights, s.nlights, &err), ZS_OK);
    ck_assert_int_eq(zs_culler_create(exact[k], NULL, &c[k], &err), ZS_OK);
  }
  uint32_t *ref = malloc(CW * CH * sizeof *ref), *img = malloc(CW * CH * sizeof *img);
  uint64_t drawn[NM] = {0};
  for (int round = 0; round < 2; round++)
    for (int v = 0; v < VIEWS; v++) {
      zs_camera cam = s.camera;
      memcpy(cam.eye, eyes[v], sizeof cam.eye);
      cam.has_eye = 1;
      zs_camera_complete(&cam, s.lo, s.hi, (double)CW / CH);
      double view[16], proj[16];
      ck_assert_int_eq(zs_camera_matrices(&cam, (double)CW / CH, view, proj, &err), ZS_OK);
      for (int k = 0; k < NM; k++) {
        zs_cull_stats st;
        ck_assert_msg(zs_culler_frame(c[k], d[k], &s, &t, view, proj, &st, &err) == ZS_OK,
                      "%s", err.msg);
        ck_assert_int_eq(zs_device_finish(d[k], keep_rgb, k == 0 ? ref : img, &err), ZS_OK);
        drawn[k] += st.objects_drawn;
        if (k == 0) continue;
        int n = 0;
        for (int i = 0; i < CW * CH; i++) n += img[i] != ref[i];
        ck_assert_msg(n == 0, "view %d: %s differs from drawing everything in %d pixels", v,
                      zs_cull_method_name(exact[k]), n);
      }
    }
  printf("transparency: objects drawn over %d frames: none %llu, chc %llu, ideal %llu\n",
         2 * VIEWS, (unsigned long long)drawn[0], (unsigned long long)drawn[3],
         (unsigned long long)drawn[8]);
  for (int k = 0; k < NM; k++) {
    zs_culler_destroy(c[k]);
    zs_device_destroy(d[k]);
  }
  free(ref);
  free(img);
  zs_octree_free(&t);
  zs_scene_free(&s);
}
END_TEST

int main(void) {
  Suite *s = suite_create("transparency");
  TCase *tc = tcase_create("abuffer");
  tcase_set_timeout(tc, 300);
  tcase_add_test(tc, abuffer_equals_depth_peeling);
  tcase_add_test(tc, any_order_gives_the_same_bytes);
  tcase_add_test(tc, texture_and_vertex_alpha);
  tcase_add_test(tc, queries_see_through_glass);
  tcase_add_test(tc, object_queries_see_through_glass);
  tcase_add_test(tc, budget_and_refusals);
  tcase_add_test(tc, culling_sees_through_glass);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
