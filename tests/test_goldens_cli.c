/* zscan golden (the manifest runner) and zscan diff, as a golden-image
 * user meets them: update then check, a case whose camera moved by a
 * hundredth failing alone in the report, the JUnit file and the HTML page
 * (read by headless Chromium), tolerances, shards, and bad manifests named
 * by their JSON path. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "lib/image.h"
#include "tests/testutil.h"

enum { BIG = 1 << 16 };
static char out[BIG], err[BIG];
static char dir[4096];

static const char *in_dir(const char *name) {
  static char buf[4][4300];
  static int k;
  k = (k + 1) % 4;
  snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
  return buf[k];
}

static void write_text(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  ck_assert_ptr_nonnull(f);
  fputs(text, f);
  ck_assert_int_eq(fclose(f), 0);
}

static char *slurp(const char *path) {
  size_t n;
  return (char *)zs_test_slurp(path, &n);
}

/* Five cases: generated scenes, a file with its own camera (its input
 * relative to the manifest), hidden lines, the scanline mode. */
static const char manifest_text[] =
    "{\"cases\": [\n"
    "  {\"name\": \"cubes\", \"input\": \"builtin:cubes?n=3\", \"size\": \"160x120\"},\n"
    "  {\"name\": \"teapots-id\", \"input\": \"builtin:teapots?count=20&level=3\",\n"
    "   \"size\": [200, 150], \"shade\": \"id\"},\n"
    "  {\"name\": \"cyclic\", \"input\": \"cyclic.obj\", \"size\": \"160x160\",\n"
    "   \"eye\": [0.3, 0.2, 8], \"target\": \"0,0,0\"%s},\n"
    "  {\"name\": \"hidden-lines\", \"input\": \"builtin:cubes?n=2\", \"size\": \"160x120\",\n"
    "   \"style\": \"hidden-line\"},\n"
    "  {\"name\": \"scanline\", \"input\": \"builtin:default?level=2\", \"size\": \"160x120\",\n"
    "   \"algo\": \"scanline\"}\n"
    "]}\n";

/* The manifest with the cyclic case's extra keys (after its target). */
static void write_manifest(const char *name, const char *cyclic_extra, double eye_x) {
  char text[4096], extra[256];
  snprintf(extra, sizeof extra, "%s", cyclic_extra);
  snprintf(text, sizeof text, manifest_text, extra);
  char eye[32];
  snprintf(eye, sizeof eye, "[%.2f,", eye_x);
  char *at = strstr(text, "[0.3,");
  ck_assert_ptr_nonnull(at);
  char fixed[4200];
  snprintf(fixed, sizeof fixed, "%.*s%s%s", (int)(at - text), text, eye, at + 5);
  write_text(in_dir(name), fixed);
}

static void setup(void) {
  snprintf(dir, sizeof dir, "%s/goldens-cli-XXXXXX", ZS_BINARY_DIR);
  ck_assert_ptr_nonnull(mkdtemp(dir));
  char cmd[9000];
  snprintf(cmd, sizeof cmd, "cp %s %s/cyclic.obj", zs_test_src("tests/data/scenes/cyclic.obj"),
           dir);
  ck_assert_int_eq(system(cmd), 0);
}

static void teardown(void) {
  char cmd[4200];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  ck_assert_int_eq(system(cmd), 0);
}

static int golden(const char *verb, const char *manifest, const char *a, const char *b,
                  const char *c, const char *d) {
  const char *args[] = {"golden", verb, manifest, a, b, c, d, NULL};
  return zs_test_run_zscan(args, out, sizeof out, err, sizeof err);
}

/* The line of case name in the runner's output. */
static const char *line_of(const char *text, const char *name) {
  static char line[512];
  size_t n = strlen(name);
  for (const char *l = text; *l; l = strchr(l, '\n') + 1) {
    if (strncmp(l, name, n) == 0 && l[n] == ' ') {
      snprintf(line, sizeof line, "%.*s", (int)(strchr(l, '\n') - l), l);
      return line;
    }
    if (!strchr(l, '\n')) break;
  }
  return NULL;
}

START_TEST(update_then_check_passes) {
  write_manifest("m.json", "", 0.3);
  ck_assert_msg(golden("update", in_dir("m.json"), NULL, NULL, NULL, NULL) == 0, "%s", err);
  ck_assert_ptr_nonnull(strstr(out, "golden update: 5 passed, 0 failed\n"));
  ck_assert(zs_test_exists(in_dir("golden/cyclic.png"))); /* golden/ beside the manifest */
  ck_assert_msg(golden("check", in_dir("m.json"), "--jobs", "2", NULL, NULL) == 0, "%s%s", out,
                err);
  ck_assert_ptr_nonnull(strstr(out, "golden check: 5 passed, 0 failed\n"));
  const char *l = line_of(out, "teapots-id");
  ck_assert_msg(l && strstr(l, " pass ") && strstr(l, "0 pixels differ"), "%s", out);
  /* a golden is the image zscan render writes with the same options */
  const char *png = in_dir("render.png");
  const char *args[] = {"render", in_dir("cyclic.obj"), "--size", "160x160", "--eye", "0.3,0.2,8",
                        "--target", "0,0,0", "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, err, sizeof err), 0);
  zs_image a, b;
  zs_error e;
  zs_error_clear(&e);
  ck_assert_int_eq(zs_png_read(png, &a, &e), ZS_OK);
  ck_assert_int_eq(zs_png_read(in_dir("golden/cyclic.png"), &b, &e), ZS_OK);
  ck_assert_uint_eq(zs_image_hash(&a), zs_image_hash(&b));
  zs_image_free(&a);
  zs_image_free(&b);
}
END_TEST

/* A key given as an array of strings is its option once for each: two
 * lights in a case are two --light options, the same golden as render's. */
START_TEST(an_array_of_strings_repeats_its_option) {
  write_text(in_dir("lit.json"),
             "{\"cases\": [{\"name\": \"lit\", \"input\": \"builtin:default?level=2\",\n"
             "  \"size\": \"160x120\", \"light\": [\"dir:0,-1,-1\", \"ambient:0.2,0.2,0.2\"]}]}\n");
  ck_assert_msg(golden("update", in_dir("lit.json"), NULL, NULL, NULL, NULL) == 0, "%s", err);
  const char *png = in_dir("render.png");
  const char *args[] = {"render", "builtin:default?level=2", "--size", "160x120", "--light",
                        "dir:0,-1,-1", "--light", "ambient:0.2,0.2,0.2", "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(args, out, sizeof out, err, sizeof err), 0);
  zs_image a, b;
  zs_error e;
  zs_error_clear(&e);
  ck_assert_int_eq(zs_png_read(png, &a, &e), ZS_OK);
  ck_assert_int_eq(zs_png_read(in_dir("golden/lit.png"), &b, &e), ZS_OK);
  ck_assert_uint_eq(zs_image_hash(&a), zs_image_hash(&b));
  zs_image_free(&a);
  zs_image_free(&b);
  /* one light alone differs from the two */
  const char *one[] = {"render", "builtin:default?level=2", "--size", "160x120", "--light",
                       "dir:0,-1,-1", "-o", png, NULL};
  ck_assert_int_eq(zs_test_run_zscan(one, out, sizeof out, err, sizeof err), 0);
  ck_assert_int_eq(zs_png_read(png, &a, &e), ZS_OK);
  ck_assert_int_eq(zs_png_read(in_dir("golden/lit.png"), &b, &e), ZS_OK);
  ck_assert_uint_ne(zs_image_hash(&a), zs_image_hash(&b));
  zs_image_free(&a);
  zs_image_free(&b);
}
END_TEST

/* Chromium's DOM of a page, or NULL (with why) when it could not run. */
static int dump_dom(const char *html, char *dom, size_t cap) {
  char cmd[9000];
  snprintf(cmd, sizeof cmd,
           "timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-quic "
           "--no-first-run --disable-background-networking --disable-component-update "
           "--disable-sync --user-data-dir=%s/chromium --dump-dom 'file://%s' 2>/dev/null",
           dir, html);
  FILE *p = popen(cmd, "r");
  if (!p) return -1;
  size_t n = fread(dom, 1, cap - 1, p);
  dom[n] = '\0';
  int rc = pclose(p);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

START_TEST(moved_camera_fails_alone_with_a_report) {
  write_manifest("m.json", "", 0.3);
  ck_assert_int_eq(golden("update", in_dir("m.json"), NULL, NULL, NULL, NULL), 0);
  write_manifest("moved.json", "", 0.31); /* the eye moved by a hundredth */
  const char *rep = in_dir("report");
  ck_assert_int_eq(golden("check", in_dir("moved.json"), "--dir", in_dir("golden"), "--report",
                          rep),
                   1);
  const char *l = line_of(out, "cyclic");
  ck_assert_msg(l && strstr(l, " FAIL ") && strstr(l, "pixels differ"), "%s", out);
  ck_assert_ptr_nonnull(strstr(out, "golden check: 4 passed, 1 failed\n"));
  ck_assert(zs_test_exists(in_dir("report/cyclic.actual.png")));
  ck_assert(zs_test_exists(in_dir("report/cyclic.diff.png")));
  ck_assert(!zs_test_exists(in_dir("report/cubes.diff.png")));
  char *junit = slurp(in_dir("report/junit.xml"));
  ck_assert_ptr_nonnull(strstr(junit, "tests=\"5\" failures=\"1\""));
  const char *fail = strstr(junit, "<failure");
  ck_assert_ptr_nonnull(fail);
  ck_assert_ptr_null(strstr(fail + 1, "<failure")); /* one failure */
  /* the one failure is cyclic's: it comes after cyclic's testcase and
   * before the next one */
  const char *cyclic = strstr(junit, "name=\"cyclic\"");
  const char *next = cyclic ? strstr(cyclic, "<testcase") : NULL;
  ck_assert(cyclic && cyclic < fail && (!next || fail < next));
  free(junit);
  /* the page, as a browser builds it */
  static char dom[1 << 22];
  int rc = dump_dom(in_dir("report/index.html"), dom, sizeof dom);
  ck_assert_msg(rc == 0, "chromium could not read the report (exit %d): tools/setup.sh installs it",
                rc);
  ck_assert_ptr_nonnull(strstr(dom, "1 of 5 failed"));
  ck_assert_ptr_nonnull(strstr(dom, "<h2 class=\"fail\">FAIL cyclic</h2>"));
  ck_assert_ptr_nonnull(strstr(dom, "<li class=\"pass\">cubes"));
  ck_assert_ptr_null(strstr(dom, "FAIL cubes"));
  const char *imgs = strstr(dom, "FAIL cyclic");
  int pictures = 0;
  for (const char *p = imgs; (p = strstr(p, "src=\"data:image/png;base64,")); p++) pictures++;
  ck_assert_int_eq(pictures, 3); /* golden, actual, diff */
  /* the case's tolerance lets it pass */
  write_manifest("tolerant.json", ", \"max_diff_pixels\": 50", 0.31);
  ck_assert_msg(golden("check", in_dir("tolerant.json"), "--dir", in_dir("golden"), NULL, NULL) ==
                    0,
                "%s", out);
}
END_TEST

/* update writes the pixel version beside the goldens; a failing check
 * against goldens of another version, or of none, says so. */
START_TEST(failing_check_names_the_goldens_pixel_version) {
  write_manifest("m.json", "", 0.3);
  ck_assert_int_eq(golden("update", in_dir("m.json"), NULL, NULL, NULL, NULL), 0);
  char *v = slurp(in_dir("golden/PIXEL-VERSION"));
  char want[256];
  snprintf(want, sizeof want, "%d\n", ZSCAN_PIXEL_VERSION);
  ck_assert_str_eq(v, want);
  free(v);
  ck_assert_str_eq(zs_pixel_changes(1), "the first numbered: every output as zscan 0.9.0 draws it");
  ck_assert_ptr_null(zs_pixel_changes(0));
  ck_assert_ptr_null(zs_pixel_changes(ZSCAN_PIXEL_VERSION + 1));
  write_manifest("moved.json", "", 0.31);
  /* the same version: no word of it */
  ck_assert_int_eq(golden("check", in_dir("moved.json"), "--dir", in_dir("golden"), NULL, NULL), 1);
  ck_assert_ptr_null(strstr(out, "pixel version"));
  /* goldens of a later zscan */
  char later[64];
  snprintf(later, sizeof later, "%d\n", ZSCAN_PIXEL_VERSION + 1);
  write_text(in_dir("golden/PIXEL-VERSION"), later);
  ck_assert_int_eq(golden("check", in_dir("moved.json"), "--dir", in_dir("golden"), NULL, NULL), 1);
  snprintf(want, sizeof want, "made with pixel version %d; this zscan draws pixel version %d (an "
           "older zscan)\n", ZSCAN_PIXEL_VERSION + 1, ZSCAN_PIXEL_VERSION);
  ck_assert_msg(strstr(out, want) != NULL, "%s", out);
  /* goldens of an older version: the versions since, each with its changes */
  write_text(in_dir("golden/PIXEL-VERSION"), "1\n");
  ck_assert_int_eq(golden("check", in_dir("moved.json"), "--dir", in_dir("golden"), NULL, NULL), 1);
  snprintf(want, sizeof want, "made with pixel version 1; this zscan draws pixel version %d, "
           "which changed:\n", ZSCAN_PIXEL_VERSION);
  ck_assert_msg(strstr(out, want) != NULL, "%s", out);
  for (int k = 2; k <= ZSCAN_PIXEL_VERSION; k++) {
    char line[1024];
    snprintf(line, sizeof line, "  pixel version %d: %s\n", k, zs_pixel_changes(k));
    ck_assert_msg(strstr(out, line) != NULL, "%s", out);
  }
  /* goldens that carry none */
  unlink(in_dir("golden/PIXEL-VERSION"));
  ck_assert_int_eq(golden("check", in_dir("moved.json"), "--dir", in_dir("golden"), NULL, NULL), 1);
  ck_assert_msg(strstr(out, "PIXEL-VERSION is missing: the goldens' pixel version is unknown")
                    != NULL, "%s", out);
  /* a passing check says nothing of it */
  ck_assert_int_eq(golden("check", in_dir("m.json"), "--dir", in_dir("golden"), NULL, NULL), 0);
  ck_assert_ptr_null(strstr(out, "pixel version"));
}
END_TEST

START_TEST(shards_check_every_case_once) {
  write_manifest("m.json", "", 0.3);
  ck_assert_int_eq(golden("update", in_dir("m.json"), NULL, NULL, NULL, NULL), 0);
  static char first[BIG];
  ck_assert_int_eq(golden("check", in_dir("m.json"), "--shard", "1/2", NULL, NULL), 0);
  memcpy(first, out, sizeof first);
  ck_assert_int_eq(golden("check", in_dir("m.json"), "--shard", "2/2", NULL, NULL), 0);
  static const char *const names[] = {"cubes", "teapots-id", "cyclic", "hidden-lines", "scanline"};
  for (int i = 0; i < 5; i++) {
    int in1 = line_of(first, names[i]) != NULL, in2 = line_of(out, names[i]) != NULL;
    ck_assert_msg(in1 + in2 == 1, "%s: in shard 1 %d, in shard 2 %d", names[i], in1, in2);
  }
}
END_TEST

START_TEST(bad_manifests_named_by_json_path) {
  static const struct {
    const char *text, *msg;
  } cases[] = {
      {"{\"cases\": [{\"input\": \"builtin:cubes\"}]}",
       "cases[0].name: expected a name of letters, digits, '-', '_' and '.'"},
      {"{\"cases\": [{\"name\": \"a/b\", \"input\": \"builtin:cubes\"}]}", "cases[0].name"},
      {"{\"cases\": [{\"name\": \"a\"}]}", "cases[0].input: expected a file or builtin:NAME"},
      {"{\"cases\": [{\"name\": \"a\", \"input\": \"builtin:cubes\", \"size\": \"12\"}]}",
       "cases[0] (a): --size: expected WxH, got '12'"},
      {"{\"cases\": [{\"name\": \"a\", \"input\": \"builtin:cubes\", \"frobnicate\": 1}]}",
       "cases[0] (a): unknown option '--frobnicate'"},
      {"{\"cases\": [{\"name\": \"a\", \"input\": \"builtin:cubes\", \"stats\": true}]}",
       "cases[0] (a): --stats: not here (the image is kept in memory)"},
      {"{\"cases\": [{\"name\": \"a\", \"input\": \"builtin:cubes\", \"max_diff_pixels\": -1}]}",
       "cases[0].max_diff_pixels: expected a whole number"},
      {"{\"cases\": [{\"name\": \"a\", \"input\": \"builtin:cubes\"},"
       " {\"name\": \"a\", \"input\": \"builtin:cubes\"}]}",
       "cases[1].name: 'a' is cases[0]'s name too"},
      {"{\"cases\": []}", "cases: expected an array of at least one case"},
      {"{\"cases\": [\n{\"name\": \"a\",, }]}", ":2: not JSON"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    write_text(in_dir("bad.json"), cases[i].text);
    ck_assert_int_eq(golden("check", in_dir("bad.json"), NULL, NULL, NULL, NULL), 1);
    ck_assert_msg(strncmp(err, "zscan golden: ", 14) == 0 && strstr(err, "bad.json") &&
                      strstr(err, cases[i].msg) && strchr(err, '\n') == err + strlen(err) - 1,
                  "case %zu: '%s' lacks '%s'", i, err, cases[i].msg);
  }
  /* usage errors: exit 2 */
  ck_assert_int_eq(golden("check", NULL, NULL, NULL, NULL, NULL), 2);
  ck_assert_int_eq(golden("verify", in_dir("bad.json"), NULL, NULL, NULL, NULL), 2);
  write_manifest("m.json", "", 0.3);
  ck_assert_int_eq(golden("check", in_dir("m.json"), "--shard", "3/2", NULL, NULL), 2);
  ck_assert_ptr_nonnull(strstr(err, "--shard: expected K/N"));
  /* a missing golden fails the check */
  ck_assert_int_eq(golden("check", in_dir("m.json"), NULL, NULL, NULL, NULL), 1);
  ck_assert_ptr_nonnull(strstr(out, "no golden (zscan golden update writes it)"));
}
END_TEST

/* zscan diff: tolerances, the heat map, side by side, exit statuses. */
START_TEST(diff_tolerances_and_pictures) {
  zs_image a, b;
  zs_error e;
  zs_error_clear(&e);
  ck_assert_int_eq(zs_image_alloc(&a, 8, 4, &e), ZS_OK);
  ck_assert_int_eq(zs_image_alloc(&b, 8, 4, &e), ZS_OK);
  for (int i = 0; i < 32; i++) a.rgb[i] = b.rgb[i] = 0x808080;
  b.rgb[3] = 0x818080;  /* 1 in red */
  b.rgb[9] = 0x80FF80;  /* 127 in green */
  ck_assert_int_eq(zs_png_write(in_dir("a.png"), &a, &e), ZS_OK);
  ck_assert_int_eq(zs_png_write(in_dir("b.png"), &b, &e), ZS_OK);
  const char *plain[] = {"diff", in_dir("a.png"), in_dir("b.png"), "-o", in_dir("heat.png"),
                         "--side-by-side", in_dir("all.png"), NULL};
  ck_assert_int_eq(zs_test_run_zscan(plain, out, sizeof out, err, sizeof err), 1);
  ck_assert_str_eq(out, "pixels_differing 2 of 32\nmax_channel_diff 127\n");
  zs_image heat, all;
  ck_assert_int_eq(zs_png_read(in_dir("heat.png"), &heat, &e), ZS_OK);
  ck_assert_uint_eq(heat.rgb[3] & 0xFF00FF, 0xFF0000);   /* yellow to red: red full, no blue */
  ck_assert_uint_gt(heat.rgb[3] >> 8 & 0xFF, heat.rgb[9] >> 8 & 0xFF); /* 1 more yellow than 127 */
  ck_assert_uint_eq(heat.rgb[0] >> 16, heat.rgb[0] & 0xFF); /* unchanged: grey */
  ck_assert_uint_ge(heat.rgb[0] & 0xFF, 160);                /* faded */
  ck_assert_int_eq(zs_png_read(in_dir("all.png"), &all, &e), ZS_OK);
  ck_assert_int_eq(all.width, 3 * 8 + 16);
  ck_assert_int_eq(all.height, 4);
  zs_image_free(&heat);
  zs_image_free(&all);
  const char *chan[] = {"diff", in_dir("a.png"), in_dir("b.png"), "--max-channel-diff", "1", NULL};
  ck_assert_int_eq(zs_test_run_zscan(chan, out, sizeof out, err, sizeof err), 1);
  ck_assert_str_eq(out, "pixels_differing 1 of 32\nmax_channel_diff 127\n");
  const char *pix[] = {"diff", in_dir("a.png"), in_dir("b.png"), "--max-channel-diff", "1",
                       "--max-diff-pixels", "1", NULL};
  ck_assert_int_eq(zs_test_run_zscan(pix, out, sizeof out, err, sizeof err), 0);
  const char *help[] = {"diff", "--help", NULL};
  ck_assert_int_eq(zs_test_run_zscan(help, out, sizeof out, err, sizeof err), 0);
  ck_assert_ptr_nonnull(strstr(out, "usage: zscan diff A.png B.png"));
  const char *bad[] = {"diff", in_dir("a.png"), in_dir("b.png"), "--max-channel-diff", "300",
                       NULL};
  ck_assert_int_eq(zs_test_run_zscan(bad, out, sizeof out, err, sizeof err), 2);
  ck_assert_ptr_nonnull(strstr(err, "--max-channel-diff: 300 is outside 0 .. 255"));
  zs_image_free(&a);
  zs_image_free(&b);
}
END_TEST

int main(void) {
  Suite *s = suite_create("goldens_cli");
  TCase *tc = tcase_create("goldens_cli");
  tcase_set_timeout(tc, 300);
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, update_then_check_passes);
  tcase_add_test(tc, an_array_of_strings_repeats_its_option);
  tcase_add_test(tc, moved_camera_fails_alone_with_a_report);
  tcase_add_test(tc, failing_check_names_the_goldens_pixel_version);
  tcase_add_test(tc, shards_check_every_case_once);
  tcase_add_test(tc, bad_manifests_named_by_json_path);
  tcase_add_test(tc, diff_tolerances_and_pictures);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
