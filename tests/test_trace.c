/* zscan trace against the lecture: the active edge table of its
 * two-polygon example at scanline y = 6, the z-buffer grids of its two
 * z-buffer examples, ids that match `zscan render --shade id`, and the
 * Gouraud intensities of the example with vertex colours, by hand and
 * against `zscan render --shade unlit`. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "util/rng.h"
#include "tests/testutil.h"
#include "lib/image.h"

static char out[1 << 20], err[1 << 16];

#define TWO_POLYGONS_VIEW "--ortho", "-0.5,11.5,-0.5,9.5", "--eye", "0,0,10", "--target", "0,0,0", \
                          "--size", "12x10"
#define ZBUFFER_VIEW "--ortho", "-0.5,7.5,-0.5,5.5", "--eye", "0,0,0", "--target", "0,0,-1", \
                     "--near", "-10", "--far", "5", "--size", "8x6"

/* The JSON line of scanline y in the trace output (the first line holds
 * the tables). */
static cJSON *scanline(int y) {
  for (char *line = out; line && *line;) {
    char *nl = strchr(line, '\n');
    if (nl) *nl = '\0';
    cJSON *o = cJSON_Parse(line);
    if (nl) *nl = '\n';
    cJSON *yy = o ? cJSON_GetObjectItem(o, "y") : NULL;
    if (yy && (int)yy->valuedouble == y) return o;
    cJSON_Delete(o);
    line = nl ? nl + 1 : NULL;
  }
  return NULL;
}

static const char *str(const cJSON *o, const char *k) {
  const cJSON *v = cJSON_GetObjectItem(o, k);
  return cJSON_IsString(v) ? v->valuestring : "";
}

static double num(const cJSON *o, const char *k) {
  const cJSON *v = cJSON_GetObjectItem(o, k);
  return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

START_TEST(two_polygons_active_edges_at_y6) {
  /* The lecture: at y = 6 (row 3 here) the active edge table holds
   *   xl=4, dxl=1, dyl=3, xr=7, dxr=0, dyr=3, id=1
   *   xl=41/6, dxl=5/6, dyl=5, xr=73/8, dxr=3/8, dyr=5, id=2
   * (its ids 1 and 2 are our faces 0 and 1). */
  const char *args[] = {"trace", zs_test_src("tests/data/lecture/two_polygons.obj"), TWO_POLYGONS_VIEW,
                        "--format", "json", NULL};
  char path[4096];
  snprintf(path, sizeof path, "%s", args[1]);
  args[1] = path;
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, err, sizeof err), 0);
  cJSON *row = scanline(3);
  ck_assert_ptr_nonnull(row);
  cJSON *edges = cJSON_GetObjectItem(row, "active_edges");
  ck_assert_int_eq(cJSON_GetArraySize(edges), 2);
  /* each pair: its polygon, its edges' x and slope as fractions, and
   * their rows left */
  static const struct {
    double id, dyl, dyr;
    const char *xl, *dxl, *xr, *dxr;
  } want[2] = {{0, 3, 3, "4", "1", "7", "0"}, {1, 5, 5, "41/6", "5/6", "73/8", "3/8"}};
  for (int k = 0; k < 2; k++) {
    const cJSON *e = cJSON_GetArrayItem(edges, k);
    ck_assert_double_eq(num(e, "id"), want[k].id);
    ck_assert_str_eq(str(e, "xl_fraction"), want[k].xl);
    ck_assert_str_eq(str(e, "dxl_fraction"), want[k].dxl);
    ck_assert_double_eq(num(e, "dyl"), want[k].dyl);
    ck_assert_str_eq(str(e, "xr_fraction"), want[k].xr);
    ck_assert_str_eq(str(e, "dxr_fraction"), want[k].dxr);
    ck_assert_double_eq(num(e, "dyr"), want[k].dyr);
  }
  ck_assert_double_eq_tol(num(cJSON_GetArrayItem(edges, 1), "xl"), 41.0 / 6.0, 1e-12);
  /* spans: columns 4..6 for polygon 1, 7..9 for polygon 2 */
  cJSON *spans = cJSON_GetObjectItem(row, "spans");
  ck_assert_int_eq(cJSON_GetArraySize(spans), 2);
  ck_assert_double_eq(num(cJSON_GetArrayItem(spans, 0), "x0"), 4);
  ck_assert_double_eq(num(cJSON_GetArrayItem(spans, 0), "x1"), 6);
  ck_assert_double_eq(num(cJSON_GetArrayItem(spans, 1), "x0"), 7);
  ck_assert_double_eq(num(cJSON_GetArrayItem(spans, 1), "x1"), 9);
  cJSON_Delete(row);

  /* the text format says the same */
  const char *targs[] = {"trace", path, TWO_POLYGONS_VIEW, "--rows", "3:3", NULL};
  ck_assert_int_eq(zs_test_run_zscan(targs, out, sizeof out, err, sizeof err), 0);
  ck_assert_ptr_nonnull(strstr(out, "xl 4 dxl 1 dyl 3 | xr 7 dxr 0 dyr 3"));
  ck_assert_ptr_nonnull(strstr(out, "xl 41/6 dxl 5/6 dyl 5 | xr 73/8 dxr 3/8 dyr 5"));
  /* the lower left edge of polygon 2 starts a row below its vertex (6, 7):
   * the lecture's "non-extreme vertex shortened by one" */
  ck_assert_ptr_nonnull(strstr(out, "     3      1  left   6.833333        5/6    5"));
}
END_TEST

START_TEST(ids_match_render_shade_id) {
  char path[4096], png[4096];
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/lecture/two_polygons.obj"));
  snprintf(png, sizeof png, "%s/trace-ids.png", ZS_BINARY_DIR);
  const char *rargs[] = {"render", path, TWO_POLYGONS_VIEW, "--algo", "scanline", "--shade", "id",
                         "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(rargs, out, sizeof out, err, sizeof err), 0);
  zs_image im;
  zs_error e;
  zs_error_clear(&e);
  ck_assert_int_eq(zs_png_read(png, &im, &e), ZS_OK);
  const char *targs[] = {"trace", path, TWO_POLYGONS_VIEW, "--format", "json", NULL};
  ck_assert_int_eq(zs_test_run_zscan(targs, out, sizeof out, err, sizeof err), 0);
  int covered = 0;
  for (int y = 0; y < 10; y++) {
    cJSON *row = scanline(y);
    ck_assert_ptr_nonnull(row);
    cJSON *ids = cJSON_GetObjectItem(row, "ids");
    ck_assert_int_eq(cJSON_GetArraySize(ids), 12);
    for (int x = 0; x < 12; x++) {
      uint32_t want = im.rgb[y * 12 + x]; /* the id render: id + 1, background 0 */
      const cJSON *id = cJSON_GetArrayItem(ids, x);
      if (want == 0) {
        ck_assert(cJSON_IsNull(id)); /* no polygon */
      } else {
        ck_assert_uint_eq((uint32_t)id->valuedouble, want - 1); /* the polygon's own id */
        covered++;
      }
    }
    cJSON_Delete(row);
  }
  ck_assert_int_gt(covered, 20);
  zs_image_free(&im);
}
END_TEST

static void check_grid(const char *obj, const int want[6][8]) {
  char path[4096];
  snprintf(path, sizeof path, "%s", zs_test_src(obj));
  const char *args[] = {"trace", path, ZBUFFER_VIEW, "--format", "json", NULL};
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, err, sizeof err), 0);
  for (int y = 0; y < 6; y++) {
    cJSON *row = scanline(y);
    ck_assert_ptr_nonnull(row);
    cJSON *z = cJSON_GetObjectItem(row, "z_view");
    for (int x = 0; x < 8; x++) {
      double v = cJSON_GetArrayItem(z, x)->valuedouble;
      ck_assert_msg(fabs(v - want[y][x]) < 1e-6, "%s row %d column %d: %g, lecture %d", obj, y, x,
                    v, want[y][x]);
    }
    cJSON_Delete(row);
  }
}

/* --grid 12x10 is the lecture's long option line; --brief drops the
 * fixed-point lines; the text's ids row numbers polygons as the spans do;
 * --rows beyond the image is an error. */
START_TEST(grid_brief_ids_rows) {
  char path[4096], longer[1 << 14];
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/lecture/two_polygons.obj"));
  const char *a[] = {"trace", path, TWO_POLYGONS_VIEW, "--near", "5", "--far", "15", NULL};
  ck_assert_int_eq(zs_test_run_zscan(a, longer, sizeof longer, err, sizeof err), 0);
  const char *b[] = {"trace", path, "--grid", "12x10", NULL};
  ck_assert_int_eq(zs_test_run_zscan(b, out, sizeof out, err, sizeof err), 0);
  ck_assert_str_eq(out, longer);
  ck_assert_ptr_nonnull(strstr(out, "fixed: "));
  ck_assert_ptr_nonnull(strstr(out, "  spans: [4,6] id 0 [7,9] id 1\n  ids: - - - - 0 0 0 1 1 1 - -\n"));
  const char *brief[] = {"trace", path, "--grid", "12x10", "--brief", NULL};
  ck_assert_int_eq(zs_test_run_zscan(brief, out, sizeof out, err, sizeof err), 0);
  ck_assert_ptr_null(strstr(out, "fixed: "));
  ck_assert_ptr_nonnull(strstr(out, "id 1: xl 41/6 dxl 5/6 dyl 5 | xr 73/8 dxr 3/8 dyr 5"));
  const char *rows[] = {"trace", path, "--grid", "12x10", "--rows", "10:12", NULL};
  ck_assert_int_eq(zs_test_run_zscan(rows, out, sizeof out, err, sizeof err), 1);
  ck_assert_str_eq(err, "zscan trace: --rows 10:12: the image has rows 0 to 9\n");
}
END_TEST

/* Chromium's DOM of page at #row=y, into dom; its exit status. */
static int page_dom(const char *page, int y, char *dom, size_t cap) {
  char cmd[9000];
  snprintf(cmd, sizeof cmd,
           "timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-quic "
           "--no-first-run --disable-background-networking --disable-component-update "
           "--disable-sync --user-data-dir=%s/trace-chromium --dump-dom 'file://%s#row=%d' "
           "2>/dev/null",
           ZS_BINARY_DIR, page, y);
  FILE *p = popen(cmd, "r");
  ck_assert_ptr_nonnull(p);
  size_t n = fread(dom, 1, cap - 1, p);
  dom[n] = '\0';
  int rc = pclose(p);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

/* The cells of the active edge table in dom: "xl dxl dyl xr dxr dyr" of
 * each pair, one line each, into want's format. */
static void aet_cells(const char *dom, char *cells, size_t cap) {
  const char *t = strstr(dom, "<div id=\"aet\">");
  ck_assert_ptr_nonnull(t);
  const char *end = strstr(t, "</table>");
  size_t n = 0;
  cells[0] = '\0';
  for (const char *r = strstr(t, "<tr><td>"); r && r < end; r = strstr(r + 1, "<tr><td>")) {
    const char *c = r;
    for (int k = 0; k < 6; k++) {
      c = strstr(c, "<td>") + 4;
      n += (size_t)snprintf(cells + n, cap - n, "%.*s%s", (int)(strchr(c, '<') - c), c,
                            k < 5 ? " " : "\n");
    }
  }
}

/* The page of --html: at #row=3 of the lecture's example its active edge
 * table shows the lecture's fractions, and on seeded random triangles
 * every scanline's pairs are the JSON trace's; nothing is loaded from
 * outside the file. */
START_TEST(html_page_steps_through_the_walk) {
  static char dom[1 << 20], json[1 << 18];
  char path[4096], page[4200];
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/lecture/two_polygons.obj"));
  snprintf(page, sizeof page, "%s/trace-page.html", ZS_BINARY_DIR);
  const char *args[] = {"trace", path, "--grid", "12x10", "--html", page, NULL};
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, err, sizeof err), 0);
  zs_test_read(page, dom, sizeof dom);
  ck_assert_ptr_null(strstr(dom, "src=\"http"));
  ck_assert_ptr_null(strstr(dom, "href="));
  ck_assert_ptr_null(strstr(dom, "@import"));
  ck_assert_ptr_null(strstr(dom, "url("));
  int rc = page_dom(page, 3, dom, sizeof dom);
  ck_assert_msg(rc == 0, "chromium could not open the page (exit %d): tools/setup.sh installs it",
                rc);
  ck_assert_ptr_nonnull(strstr(dom, "scanline 3 ("));
  char cells[4096];
  aet_cells(dom, cells, sizeof cells);
  ck_assert_str_eq(cells, "4 1 3 7 0 3\n41/6 5/6 5 73/8 3/8 5\n");
  /* without vertex colours the row buffer has no I row */
  const char *rb = strstr(dom, "<div id=\"rowbuf\">");
  ck_assert_ptr_nonnull(rb);
  ck_assert_ptr_nonnull(strstr(rb, "<td>z</td>"));
  ck_assert_ptr_null(strstr(rb, "<td>I</td>"));
  /* seeded random triangles: the page's pairs are the JSON trace's */
  char obj[4200];
  snprintf(obj, sizeof obj, "%s/trace-random.obj", ZS_BINARY_DIR);
  zs_rng rng;
  zs_rng_seed(&rng, 5);
  FILE *f = fopen(obj, "w");
  for (int i = 0; i < 18; i++)
    fprintf(f, "v %d %d %d\n", (int)zs_rng_below(&rng, 16), (int)zs_rng_below(&rng, 12),
            -(int)zs_rng_below(&rng, 5));
  for (int i = 0; i < 6; i++) fprintf(f, "f %d %d %d\n", 3 * i + 1, 3 * i + 2, 3 * i + 3);
  fclose(f);
  const char *rnd[] = {"trace", obj, "--grid", "16x12", "--html", page, NULL};
  ck_assert_msg(zs_test_run_zscan(rnd, out, sizeof out, err, sizeof err) == 0, "%s", err);
  const char *js[] = {"trace", obj, "--grid", "16x12", "--format", "json", NULL};
  ck_assert_int_eq(zs_test_run_zscan(js, json, sizeof json, err, sizeof err), 0);
  for (int y = 0; y < 12; y += 3) {
    ck_assert_int_eq(page_dom(page, y, dom, sizeof dom), 0);
    aet_cells(dom, cells, sizeof cells);
    /* the same row of the JSON, as the page's cells */
    char key[32], want[4096];
    snprintf(key, sizeof key, "{\"y\":%d,", y);
    cJSON *row = cJSON_Parse(strstr(json, key));
    ck_assert_ptr_nonnull(row);
    size_t w = 0;
    want[0] = '\0';
    for (const cJSON *p = cJSON_GetObjectItem(row, "active_edges")->child; p; p = p->next)
      w += (size_t)snprintf(want + w, sizeof want - w, "%s %s %d %s %s %d\n",
                            cJSON_GetObjectItem(p, "xl_fraction")->valuestring,
                            cJSON_GetObjectItem(p, "dxl_fraction")->valuestring,
                            cJSON_GetObjectItem(p, "dyl")->valueint,
                            cJSON_GetObjectItem(p, "xr_fraction")->valuestring,
                            cJSON_GetObjectItem(p, "dxr_fraction")->valuestring,
                            cJSON_GetObjectItem(p, "dyr")->valueint);
    cJSON_Delete(row);
    ck_assert_msg(strcmp(cells, want) == 0, "row %d: page\n%sJSON\n%s", y, cells, want);
  }
}
END_TEST

START_TEST(lecture_zbuffer_grids) {
  static const int square[6][8] = {
      {-5, -5, -5, -5, -5, -5, -5, -5}, {-5, -5, -1, -1, -1, -1, -5, -5},
      {-5, -5, -1, -1, -1, -1, -5, -5}, {-5, -5, -1, -1, -1, -1, -5, -5},
      {-5, -5, -1, -1, -1, -1, -5, -5}, {-5, -5, -5, -5, -5, -5, -5, -5}};
  static const int both[6][8] = {
      {-5, -5, -5, -5, -5, -5, -5, -5}, {-5, -5, -1, -1, -1, -1, -5, -5},
      {-5, -5, 2, 1, 0, -1, -2, -5},    {-5, -5, 2, 1, 0, -1, -2, -5},
      {-5, -5, -1, -1, -1, -1, -5, -5}, {-5, -5, -5, -5, -5, -5, -5, -5}};
  check_grid("tests/data/lecture/zbuffer_square.obj", square);
  check_grid("tests/data/lecture/zbuffer_two.obj", both);
  /* the plain z-buffer polygon by polygon (--algo zbuffer): its page's
   * depth grid after polygon 0 is the lecture's first grid, after
   * polygon 1 its second */
  char path[4096], page[4200];
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/lecture/zbuffer_two.obj"));
  snprintf(page, sizeof page, "%s/trace-zbuffer.html", ZS_BINARY_DIR);
  const char *args[] = {"trace", path, ZBUFFER_VIEW, "--algo", "zbuffer", "--html", page, NULL};
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, err, sizeof err), 0);
  static char dom[1 << 20];
  for (int step = 1; step <= 2; step++) {
    ck_assert_int_eq(page_dom(page, step, dom, sizeof dom), 0);
    const char *t = strstr(dom, "<div id=\"zgrid\">");
    ck_assert_ptr_nonnull(t);
    const int(*want)[8] = step == 1 ? square : both;
    const char *c = strstr(t, "</tr>"); /* past the header */
    for (int y = 0; y < 6; y++)
      for (int x = -1; x < 8; x++) { /* the row number, then the cells */
        c = strstr(c, "<td>") + 4;
        if (x >= 0) ck_assert_msg(atoi(c) == want[y][x], "step %d row %d column %d: %.8s", step, y, x, c);
      }
  }
}
END_TEST

START_TEST(step_pictures_one_per_scanline) {
  char dir[4096], path[4096];
  snprintf(dir, sizeof dir, "%s/trace-steps", ZS_BINARY_DIR);
  mkdir(dir, 0755);
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/lecture/two_polygons.obj"));
  const char *args[] = {"trace", path, TWO_POLYGONS_VIEW, "--png-dir", dir, "--scale", "4", NULL};
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, err, sizeof err), 0);
  /* at scale 4 the labels' cells are 1 pixel: a margin of 14 on the left
   * (row numbers), 8 on top (column numbers), 3 legend lines of 8 below */
  enum { S = 4, LEFT = 14, TOP = 8, W = 12, H = 10 };
  for (int y = 0; y < H; y++) {
    char png[4200];
    snprintf(png, sizeof png, "%s/scanline-%04d.png", dir, y);
    zs_image im;
    zs_error e;
    zs_error_clear(&e);
    ck_assert_msg(zs_png_read(png, &im, &e) == ZS_OK, "%s", e.msg);
    ck_assert_int_eq(im.width, LEFT + (2 * W + 1) * S);
    ck_assert_int_eq(im.height, TOP + H * S + 3 * 8 + 1);
    /* the current row's number, and only its, in yellow (5 pixels high,
     * from the top of its row) */
    int yellow = 0;
    for (int py = 0; py < im.height; py++)
      for (int px = 0; px < LEFT; px++)
        if (im.rgb[(size_t)py * im.width + px] == 0xFFFF00) {
          ck_assert_msg(py >= TOP + y * S && py < TOP + y * S + 5, "scanline %d: yellow at %d", y, py);
          yellow++;
        }
    ck_assert_int_gt(yellow, 0);
    /* both polygons' outlines over the grid (their colours halfway to
     * white), and in the legend their colours and the crossings' marks */
    static const uint32_t outline[2] = {0xA6BBD2, 0xF8C694}, legend[4] = {0x4E79A7, 0xF28E2B,
                                                                          0xFF3030, 0x30A0FF};
    int seen_outline[2] = {0, 0}, seen_legend[4] = {0, 0, 0, 0};
    for (int py = 0; py < im.height; py++)
      for (int px = 0; px < im.width; px++) {
        uint32_t c = im.rgb[(size_t)py * im.width + px];
        for (int i = 0; i < 2; i++)
          seen_outline[i] |= py < TOP + H * S && px < LEFT + W * S && c == outline[i];
        for (int i = 0; i < 4; i++) seen_legend[i] |= py >= TOP + H * S && c == legend[i];
      }
    ck_assert(seen_outline[0] && seen_outline[1]);
    ck_assert(seen_legend[0] && seen_legend[1] && seen_legend[2] && seen_legend[3]);
    zs_image_free(&im);
  }
  /* a file where the folder should be (a missing folder is made) */
  const char *bad[] = {"trace", path, "--png-dir", path, NULL};
  ck_assert_int_eq(zs_test_run_zscan(bad, out, sizeof out, err, sizeof err), 1);
  char want[8400];
  snprintf(want, sizeof want, "zscan trace: --png-dir %s: not a directory\n", path);
  ck_assert_str_eq(err, want);
}
END_TEST

/* The lecture's two polygons with a grey level at each corner
 * (tests/data/lecture/gouraud.obj: 0.2, 1, 0.6 read as 51, 255, 153).  At
 * y = 6 (row 3), by hand:
 *   polygon 1: the left edge runs from 51 at (1, 9) to 153 at (7, 3),
 *     halfway at y = 6: Il = 102, dIl = 102 / 6 = 17; the right from 255
 *     at (7, 9) to 153: Ir = 204, dIr = -17; dIx = (204 - 102) / (7 - 4) = 34
 *   polygon 2: the lower left edge from 51 at (6, 7) to 153 at (11, 1),
 *     1/6 of the way: Il = 68, dIl = 17; the right from 255 at (8, 9) to
 *     153 at (11, 1), 3/8 of the way: Ir = 255 - 3/8 102 = 867/4,
 *     dIr = -102 / 8 = -51/4; dIx = (867/4 - 68) / (73/8 - 41/6) = 714/11
 * and a pixel's I is Il + (x - xl) dIx. */
START_TEST(gouraud_intensities_at_y6) {
  char path[4096];
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/lecture/gouraud.obj"));
  const char *args[] = {"trace", path, "--grid", "12x10", "--format", "json", NULL};
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, err, sizeof err), 0);
  ck_assert_str_eq(err, "");
  cJSON *row = scanline(3);
  ck_assert_ptr_nonnull(row);
  cJSON *edges = cJSON_GetObjectItem(row, "active_edges");
  ck_assert_int_eq(cJSON_GetArraySize(edges), 2);
  static const char *const keys[5] = {"Il", "dIl", "Ir", "dIr", "dIx"};
  static const char *const want[2][5] = {{"102", "17", "204", "-17", "34"},
                                         {"68", "17", "867/4", "-51/4", "714/11"}};
  static const double value[2][5] = {{102, 17, 204, -17, 34},
                                      {68, 17, 867.0 / 4, -51.0 / 4, 714.0 / 11}};
  for (int k = 0; k < 2; k++) {
    const cJSON *e = cJSON_GetArrayItem(edges, k);
    for (int i = 0; i < 5; i++) {
      char key[32];
      snprintf(key, sizeof key, "%s_fraction", keys[i]);
      ck_assert_str_eq(str(e, key), want[k][i]);
      ck_assert_double_eq_tol(num(e, keys[i]), value[k][i], 1e-12);
    }
  }
  /* each pixel's: 102, 136, 170 across polygon 1, 68 + (x - 41/6) 714/11
   * across polygon 2, none beside */
  const cJSON *I = cJSON_GetObjectItem(row, "I");
  ck_assert_int_eq(cJSON_GetArraySize(I), 12);
  for (int x = 0; x < 12; x++) {
    const cJSON *v = cJSON_GetArrayItem(I, x);
    if (x < 4 || x > 9) {
      ck_assert(cJSON_IsNull(v));
      continue;
    }
    const double hand = x < 7 ? 102 + 34 * (x - 4) : 68 + (x - 41.0 / 6) * 714 / 11;
    ck_assert_msg(fabs(v->valuedouble - hand) < 1e-9, "column %d: %.12g, by hand %.12g", x,
                  v->valuedouble, hand);
  }
  cJSON_Delete(row);
  /* the edge table: I at each edge's top row, and per row down (polygon
   * 2's lower left edge enters at row 3 with 68) */
  cJSON *tables = cJSON_Parse(out);
  ck_assert_ptr_nonnull(tables);
  const cJSON *e4 = cJSON_GetArrayItem(cJSON_GetObjectItem(tables, "edge_table"), 4);
  ck_assert_double_eq(num(e4, "row"), 3);
  ck_assert_str_eq(str(e4, "I_fraction"), "68");
  ck_assert_str_eq(str(e4, "dI_fraction"), "17");
  cJSON_Delete(tables);

  /* the text says the same */
  const char *targs[] = {"trace", path, "--grid", "12x10", "--rows", "3:3", "--brief", NULL};
  ck_assert_int_eq(zs_test_run_zscan(targs, out, sizeof out, err, sizeof err), 0);
  ck_assert_ptr_nonnull(strstr(out, "   row     id  side          x         dx   dy          I         dI\n"));
  ck_assert_ptr_nonnull(strstr(out, "     3      1  left   6.833333        5/6    5         68         17\n"));
  ck_assert_ptr_nonnull(strstr(out, "| Il 102 dIl 17 | Ir 204 dIr -17 | dIx 34\n"));
  ck_assert_ptr_nonnull(strstr(out, "| Il 68 dIl 17 | Ir 867/4 dIr -51/4 | dIx 714/11\n"));
  ck_assert_ptr_nonnull(strstr(out, "  I:   - - - - 102.00 136.00 170.00 78.82 143.73 208.64 - -\n"));
}
END_TEST

/* Each pixel's I of a JSON trace in out against the red of an unlit
 * render: the render interpolates the same corners, so its byte is I
 * rounded (a half either way, for the rounding of its weights). */
static void check_unlit(const char *png, int w, int h, const char *what) {
  zs_image im;
  zs_error e;
  zs_error_clear(&e);
  ck_assert_int_eq(zs_png_read(png, &im, &e), ZS_OK);
  int covered = 0;
  for (int y = 0; y < h; y++) {
    cJSON *row = scanline(y);
    ck_assert_ptr_nonnull(row);
    const cJSON *I = cJSON_GetObjectItem(row, "I"), *ids = cJSON_GetObjectItem(row, "ids");
    for (int x = 0; x < w; x++) {
      const cJSON *v = cJSON_GetArrayItem(I, x);
      ck_assert_int_eq(cJSON_IsNull(v), cJSON_IsNull(cJSON_GetArrayItem(ids, x)));
      if (cJSON_IsNull(v)) continue;
      const double red = (double)(im.rgb[(size_t)y * (size_t)w + (size_t)x] >> 16);
      ck_assert_msg(fabs(red - v->valuedouble) <= 0.5 + 1e-4, "%s (%d, %d): render %g, trace %.6f",
                    what, x, y, red, v->valuedouble);
      covered++;
    }
    cJSON_Delete(row);
  }
  ck_assert_int_gt(covered, 10);
  zs_image_free(&im);
}

/* The trace's I is what zscan computes: under the orthographic grid its
 * perspective-correct interpolation is the textbook's linear one, so
 * `--shade unlit` (the vertex colours interpolated as given) draws each
 * pixel as the trace's I rounded, in both modes; on the lecture's example
 * and on seeded random coloured triangles. */
START_TEST(gouraud_matches_unlit_render) {
  static char json[1 << 18], rout[1 << 12];
  char path[4200], png[4200];
  snprintf(png, sizeof png, "%s/trace-unlit.png", ZS_BINARY_DIR);
  char obj[4200];
  snprintf(obj, sizeof obj, "%s/trace-random-colours.obj", ZS_BINARY_DIR);
  zs_rng rng;
  zs_rng_seed(&rng, 11);
  FILE *f = fopen(obj, "w");
  ck_assert_ptr_nonnull(f);
  for (int i = 0; i < 18; i++) {
    const int grey = (int)zs_rng_below(&rng, 256);
    fprintf(f, "v %d %d %d %.6f %.6f %.6f\n", (int)zs_rng_below(&rng, 16),
            (int)zs_rng_below(&rng, 12), -(int)zs_rng_below(&rng, 5), grey / 255.0,
            grey / 255.0, grey / 255.0);
  }
  for (int i = 0; i < 6; i++) fprintf(f, "f %d %d %d\n", 3 * i + 1, 3 * i + 2, 3 * i + 3);
  fclose(f);
  static const struct { const char *obj, *grid; int w, h; } inputs[2] = {
      {"lecture", "12x10", 12, 10}, {"random", "16x12", 16, 12}};
  for (int k = 0; k < 2; k++) {
    if (k == 0) snprintf(path, sizeof path, "%s", zs_test_src("tests/data/lecture/gouraud.obj"));
    else snprintf(path, sizeof path, "%s", obj);
    const char *targs[] = {"trace", path, "--grid", inputs[k].grid, "--format", "json", NULL};
    ck_assert_int_eq(zs_test_run_zscan(targs, json, sizeof json, err, sizeof err), 0);
    memcpy(out, json, strlen(json) + 1);
    for (int m = 0; m < 2; m++) {
      const char *rargs[] = {"render", path, "--grid", inputs[k].grid, "--algo",
                             m ? "zbuffer" : "scanline", "--shade", "unlit", "-o", png, NULL};
      ck_assert_int_eq(zs_test_run_zscan(rargs, rout, sizeof rout, err, sizeof err), 0);
      char what[64];
      snprintf(what, sizeof what, "%s, %s", inputs[k].obj, m ? "zbuffer" : "scanline");
      check_unlit(png, inputs[k].w, inputs[k].h, what);
    }
  }
}
END_TEST

/* Without vertex colours the trace is as it was: no I anywhere (the
 * tests above pin the rest); under a perspective view a mesh with them
 * shows none either, and a note says why. */
START_TEST(gouraud_needs_colours_and_ortho) {
  char path[4096];
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/lecture/two_polygons.obj"));
  const char *args[] = {"trace", path, "--grid", "12x10", "--format", "json", NULL};
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, err, sizeof err), 0);
  ck_assert_ptr_null(strstr(out, "\"I"));
  ck_assert_ptr_null(strstr(out, "\"dI"));
  const char *text[] = {"trace", path, "--grid", "12x10", NULL};
  ck_assert_int_eq(zs_test_run_zscan(text, out, sizeof out, err, sizeof err), 0);
  ck_assert_ptr_null(strstr(out, "| Il "));
  ck_assert_ptr_null(strstr(out, "  I:"));
  ck_assert_ptr_nonnull(strstr(out, "   row     id  side          x         dx   dy\n"));
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/lecture/gouraud.obj"));
  const char *persp[] = {"trace", path, "--rows", "3:3", NULL};
  ck_assert_int_eq(zs_test_run_zscan(persp, out, sizeof out, err, sizeof err), 0);
  ck_assert_ptr_null(strstr(out, "| Il "));
  ck_assert_str_eq(err, "zscan trace: note: no Gouraud intensities under a perspective view "
                        "(zscan interpolates perspective-correct); --grid or --ortho shows them\n");
  /* a quad whose corners' I are on no plane is noted (zscan shades its
   * fan); a pentagon's on one plane is not */
  static const char *const faces[2] = {"v 1 1 -1 0 0 0\nv 8 1 -1 1 1 1\nv 8 6 -1 0 0 0\n"
                                       "v 1 6 -1 1 1 1\nf 1 2 3 4\n",
                                       /* I = 10 x + 20 y */
                                       "v 1 1 -1 0.117647 0 0\nv 4 1 -1 0.235294 0 0\n"
                                       "v 8 1 -1 0.392157 0 0\nv 8 6 -1 0.784314 0 0\n"
                                       "v 1 6 -1 0.509804 0 0\nf 1 2 3 4 5\n"};
  for (int k = 0; k < 2; k++) {
    snprintf(path, sizeof path, "%s/trace-%s.obj", ZS_BINARY_DIR, k ? "pentagon" : "quad");
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fputs(faces[k], f);
    fclose(f);
    const char *a[] = {"trace", path, "--grid", "10x8", NULL};
    ck_assert_int_eq(zs_test_run_zscan(a, out, sizeof out, err, sizeof err), 0);
    ck_assert_ptr_nonnull(strstr(out, "| Il "));
    ck_assert_str_eq(err, k ? ""
                            : "zscan trace: note: polygon 0: its corners' I are not on one plane; "
                              "zscan shades it as the fan from its first corner, the tables along "
                              "its edges\n");
  }
}
END_TEST

/* The pictures gain a third panel, the intensities as grey, and a legend
 * line; the page's active edge table the I columns, its row buffer I. */
START_TEST(gouraud_pictures_and_page) {
  char dir[4096], path[4096], png[4200];
  snprintf(dir, sizeof dir, "%s/trace-gouraud-steps", ZS_BINARY_DIR);
  snprintf(path, sizeof path, "%s", zs_test_src("tests/data/lecture/gouraud.obj"));
  const char *args[] = {"trace", path, "--grid", "12x10", "--png-dir", dir, "--scale", "4",
                        "--rows", "3:3", "--quiet", NULL};
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, err, sizeof err), 0);
  enum { S = 4, LEFT = 14, TOP = 8, W = 12, H = 10, PANEL = LEFT + 2 * (W + 1) * S };
  snprintf(png, sizeof png, "%s/scanline-0003.png", dir);
  zs_image im;
  zs_error e;
  zs_error_clear(&e);
  ck_assert_msg(zs_png_read(png, &im, &e) == ZS_OK, "%s", e.msg);
  ck_assert_int_eq(im.width, LEFT + (3 * W + 2) * S);
  ck_assert_int_eq(im.height, TOP + H * S + 4 * 8 + 1);
  /* row 3's pixels: 102 at column 4, 170 at 6, 78.82 rounded at 7 */
  static const struct { int x; uint32_t grey; } px[3] = {{4, 102}, {6, 170}, {7, 79}};
  for (int i = 0; i < 3; i++) {
    uint32_t c = im.rgb[(size_t)(TOP + 3 * S + S / 2) * im.width + PANEL + px[i].x * S + S / 2];
    ck_assert_uint_eq(c, px[i].grey * 0x010101u);
  }
  zs_image_free(&im);

  static char dom[1 << 20];
  char page[4200];
  snprintf(page, sizeof page, "%s/trace-gouraud.html", ZS_BINARY_DIR);
  const char *html[] = {"trace", path, "--grid", "12x10", "--html", page, NULL};
  ck_assert_int_eq(zs_test_run_zscan(html, out, sizeof out, err, sizeof err), 0);
  ck_assert_int_eq(page_dom(page, 3, dom, sizeof dom), 0);
  const char *t = strstr(dom, "<div id=\"aet\">");
  ck_assert_ptr_nonnull(t);
  ck_assert_ptr_nonnull(strstr(t, "<th class=\"sym\">Il</th><th class=\"sym\">dIl</th><th class=\"sym\">Ir</th>"
                            "<th class=\"sym\">dIr</th><th class=\"sym\">dI/dx</th><th>id</th>"));
  ck_assert_ptr_nonnull(strstr(t, "<td>102</td><td>17</td><td>204</td><td>-17</td><td>34</td><td>0</td>"));
  ck_assert_ptr_nonnull(
      strstr(t, "<td>68</td><td>17</td><td>867/4</td><td>-51/4</td><td>714/11</td><td>1</td>"));
  const char *rb = strstr(dom, "<div id=\"rowbuf\">");
  ck_assert_ptr_nonnull(rb);
  ck_assert_ptr_nonnull(strstr(rb, "<td>I</td><td>-</td><td>-</td><td>-</td><td>-</td><td>102.00</td>"));
}
END_TEST

int main(void) {
  Suite *s = suite_create("trace");
  TCase *tc = tcase_create("lecture");
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, two_polygons_active_edges_at_y6);
  tcase_add_test(tc, ids_match_render_shade_id);
  tcase_add_test(tc, lecture_zbuffer_grids);
  tcase_add_test(tc, grid_brief_ids_rows);
  tcase_add_test(tc, html_page_steps_through_the_walk);
  tcase_add_test(tc, step_pictures_one_per_scanline);
  tcase_add_test(tc, gouraud_intensities_at_y6);
  tcase_add_test(tc, gouraud_matches_unlit_render);
  tcase_add_test(tc, gouraud_needs_colours_and_ortho);
  tcase_add_test(tc, gouraud_pictures_and_page);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
