/* zscan trace against the lecture: the active edge table of its
 * two-polygon example at scanline y = 6, the z-buffer grids of its two
 * z-buffer examples, and ids that match `zscan render --shade id`. */
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
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
