/* The teaching page's engine (web/teach_module.c), built natively: a
 * lesson's trace is the one `zscan trace --format json` prints for the
 * same polygons, line for line, in both algorithms and with intensities;
 * every bad lesson is refused with the place and the reason the page
 * shows beside the field. */
#include <check.h>
#include <cjson/cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/testutil.h"
#include "web/teach_module.h"

static char out[1 << 20], err[1 << 16];

/* The engine's answer to lesson, parsed. */
static cJSON *teach(const char *lesson) {
  char *a = zs_teach_run(lesson);
  ck_assert_ptr_nonnull(a);
  cJSON *j = cJSON_Parse(a);
  zs_teach_free(a);
  ck_assert_ptr_nonnull(j);
  return j;
}

/* The lesson's trace equals the command's on obj (a file of the same
 * polygons), each line the same JSON value; the command's arguments are
 * the answer's "args". */
static void same_as_command(const char *lesson, const char *obj) {
  cJSON *a = teach(lesson);
  ck_assert_ptr_null(cJSON_GetObjectItem(a, "errors"));
  const cJSON *trace = cJSON_GetObjectItem(a, "trace"), *args = cJSON_GetObjectItem(a, "args");
  const char *argv[32] = {"trace", obj};
  int n = 2;
  for (const cJSON *v = args->child; v; v = v->next) argv[n++] = v->valuestring;
  argv[n++] = "--format";
  argv[n++] = "json";
  argv[n] = NULL;
  ck_assert_int_eq(zs_test_run_zscan(argv, out, sizeof out, err, sizeof err), 0);
  int lines = 0;
  char *save = NULL;
  for (char *l = strtok_r(out, "\n", &save); l; l = strtok_r(NULL, "\n", &save), lines++) {
    cJSON *want = cJSON_Parse(l);
    ck_assert_ptr_nonnull(want);
    ck_assert_msg(cJSON_Compare(cJSON_GetArrayItem(trace, lines), want, 1), "line %d differs: %s",
                  lines, l);
    cJSON_Delete(want);
  }
  ck_assert_int_eq(lines, cJSON_GetArraySize(trace));
  ck_assert_int_gt(lines, 2);
  /* and its OBJ file is one the command reads to the same trace */
  FILE *f = fopen(ZS_BINARY_DIR "/teach-lesson.obj", "w");
  ck_assert_ptr_nonnull(f);
  fputs(cJSON_GetObjectItem(a, "obj")->valuestring, f);
  fclose(f);
  char copy[sizeof out];
  argv[1] = obj;
  ck_assert_int_eq(zs_test_run_zscan(argv, copy, sizeof copy, err, sizeof err), 0);
  argv[1] = ZS_BINARY_DIR "/teach-lesson.obj";
  ck_assert_int_eq(zs_test_run_zscan(argv, out, sizeof out, err, sizeof err), 0);
  ck_assert_str_eq(out, copy);
  cJSON_Delete(a);
}

START_TEST(lecture_lessons_trace_as_the_command) {
  char obj[4096];
  snprintf(obj, sizeof obj, "%s", zs_test_src("tests/data/lecture/two_polygons.obj"));
  same_as_command("{\"width\":12,\"height\":10,\"algo\":\"scanline\",\"polygons\":["
                  "{\"vertices\":[[1,9,-2],[7,9,-2.6],[7,3,-2]]},"
                  "{\"vertices\":[[8,9,-3],[6,7,-1],[11,1,-1.5]]}]}",
                  obj);
  snprintf(obj, sizeof obj, "%s", zs_test_src("tests/data/lecture/zbuffer_two.obj"));
  same_as_command("{\"width\":8,\"height\":6,\"algo\":\"zbuffer\",\"polygons\":["
                  "{\"vertices\":[[1.5,0.5,-1],[5.5,0.5,-1],[5.5,4.5,-1],[1.5,4.5,-1]]},"
                  "{\"vertices\":[[1.5,1.5,2.5],[6.5,1.5,-2.5],[6.5,3.5,-2.5],[1.5,3.5,2.5]]}]}",
                  obj);
  /* the intensities: I is the vertex colour's channel, 0.2 = 51 */
  snprintf(obj, sizeof obj, "%s", zs_test_src("tests/data/lecture/gouraud.obj"));
  same_as_command("{\"width\":12,\"height\":10,\"polygons\":["
                  "{\"vertices\":[[1,9,-2,51],[7,9,-2.6,255],[7,3,-2,153]]},"
                  "{\"vertices\":[[8,9,-3,255],[6,7,-1,51],[11,1,-1.5,153]]}]}",
                  obj);
  /* a plane instead of z: z = 0.1 x - 0.2 y + 1 at each corner */
  cJSON *p = teach("{\"width\":6,\"height\":5,\"polygons\":[{\"plane\":[0.1,-0.2,1],"
                   "\"vertices\":[[0,0],[5,0],[2,4]]}]}");
  cJSON *q = teach("{\"width\":6,\"height\":5,\"polygons\":[{"
                   "\"vertices\":[[0,0,1],[5,0,1.5],[2,4,0.3999999999999999]]}]}");
  ck_assert(cJSON_Compare(cJSON_GetObjectItem(p, "trace"), cJSON_GetObjectItem(q, "trace"), 1));
  cJSON_Delete(p);
  cJSON_Delete(q);
}
END_TEST

START_TEST(bad_lessons_name_the_field) {
  static const struct {
    const char *lesson, *path, *message;
  } cases[] = {
      {"[1, 2]", "", "the lesson is not a JSON object"},
      {"{\"width\":1,\"height\":10,\"polygons\":[]}", "width", "expected a whole number 2 to 32"},
      {"{\"width\":12,\"height\":10.5,\"polygons\":[]}", "height", "expected a whole number 2 to 24"},
      {"{\"width\":12,\"height\":10,\"polygons\":[]}", "polygons", "expected at least one polygon"},
      {"{\"width\":12,\"height\":10,\"algo\":\"painter\",\"polygons\":[{\"vertices\":[[1,1,0],[2,1,0],[1,2,0]]}]}",
       "algo", "expected \"scanline\" or \"zbuffer\""},
      {"{\"width\":12,\"height\":10,\"polygons\":[{\"vertices\":[[1,1,0],[2,1,0]]}]}", "polygons[0]",
       "a polygon needs at least 3 vertices"},
      {"{\"width\":12,\"height\":10,\"polygons\":[{\"vertices\":[[1,1,0],[2,1,0],[2,2,0],[1,2,0],"
       "[1,3,0],[1,4,0],[1,5,0],[1,6,0],[1,7,0]]}]}",
       "polygons[0]", "9 vertices: at most 8"},
      {"{\"width\":12,\"height\":10,\"polygons\":[{\"vertices\":[[1,1,0],[12,1,0],[1,2,0]]}]}",
       "polygons[0].vertices[1]", "x = 12 is off the grid: 0 to 11"},
      {"{\"width\":12,\"height\":10,\"polygons\":[{\"vertices\":[[1,-1,0],[2,1,0],[1,2,0]]}]}",
       "polygons[0].vertices[0]", "y = -1 is off the grid: 0 to 9"},
      {"{\"width\":12,\"height\":10,\"polygons\":[{\"vertices\":[[1,1,-5],[2,1,0],[1,2,0]]}]}",
       "polygons[0].vertices[0]", "z = -5: expected above -5 (the background) and below 10"},
      {"{\"width\":12,\"height\":10,\"polygons\":[{\"vertices\":[[1,1,0,256],[2,1,0],[1,2,0]]}]}",
       "polygons[0].vertices[0]", "I = 256: expected a whole number 0 to 255"},
      {"{\"width\":12,\"height\":10,\"polygons\":[{\"vertices\":[[1,1,0],[2,2,0],[3,3,0]]}]}",
       "polygons[0]", "degenerate: its corners are on one line (no area)"},
      {"{\"width\":12,\"height\":10,\"polygons\":[{\"vertices\":[[1,1,0],[1,1,2],[3,3,0]]}]}",
       "polygons[0].vertices[1]", "the same point as vertex 0: a polygon's corners must differ"},
      {"{\"width\":12,\"height\":10,\"polygons\":[{\"vertices\":[[1,1,0],[\"2\",1,0],[3,3,0]]}]}",
       "polygons[0].vertices[1]", "expected numbers"},
      {"{\"width\":12,\"height\":10,\"polygons\":[{\"plane\":[1,2],\"vertices\":[[1,1],[2,1],[3,3]]}]}",
       "polygons[0]", "plane: expected [a, b, c], for z = a x + b y + c"},
      {"{\"width\":12,\"height\":10,\"polygons\":[{\"plane\":[0,0,1],\"vertices\":[[1,1,0,0],[2,1],[3,3]]}]}",
       "polygons[0].vertices[0]", "expected [x, y] or [x, y, I] (the plane gives z)"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    cJSON *a = teach(cases[k].lesson);
    ck_assert_msg(!cJSON_GetObjectItem(a, "trace"), "case %zu: a trace", k);
    const cJSON *e = cJSON_GetArrayItem(cJSON_GetObjectItem(a, "errors"), 0);
    ck_assert_msg(e != NULL, "case %zu: no error", k);
    ck_assert_str_eq(cJSON_GetObjectItem(e, "path")->valuestring, cases[k].path);
    ck_assert_str_eq(cJSON_GetObjectItem(e, "message")->valuestring, cases[k].message);
    cJSON_Delete(a);
  }
  /* not JSON at all, and nothing */
  cJSON *a = teach("{\"width\":");
  ck_assert_str_eq(cJSON_GetArrayItem(cJSON_GetObjectItem(a, "errors"), 0)->child->next->valuestring,
                   "the lesson is not a JSON object");
  cJSON_Delete(a);
  a = teach(NULL);
  ck_assert_ptr_nonnull(cJSON_GetObjectItem(a, "errors"));
  cJSON_Delete(a);
}
END_TEST

int main(void) {
  Suite *s = suite_create("teach");
  TCase *tc = tcase_create("engine");
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, lecture_lessons_trace_as_the_command);
  tcase_add_test(tc, bad_lessons_name_the_field);
  suite_add_tcase(s, tc);
  return zs_test_run(s);
}
