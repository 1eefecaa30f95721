/* `zscan teach -o FILE.html [--lesson LESSON.json]`: writes the live
 * teaching page (web/teach.html), its WebAssembly engine inlined, so it
 * works opened from disk and offline.  A lesson given is checked by the
 * same engine, compiled natively (web/teach_module.c), before the page
 * opens on it. */
#include "tools/commands.h"

#include <cjson/cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/outfile.h"
#include "scene/load_common.h"
#include "tools/cli.h"
#include "web/teach_module.h"
#include "web/teach_page.h"

static const char usage[] =
    "usage: zscan teach -o FILE.html [options]\n"
    "  -o FILE.html        the page: the grid and the polygons, editable (drag a\n"
    "                      vertex or type x, y, z), the z-buffer or the scanline\n"
    "                      z-buffer stepped by scanline or by pixel, the sorted and\n"
    "                      active tables with the exact fractions, exercises, the\n"
    "                      lecture's examples; recomputed by zscan's own walk,\n"
    "                      compiled to WebAssembly and inlined (no network needed)\n"
    "  --lesson FILE.json  open on this lesson: {\"width\": W, \"height\": H,\n"
    "                      \"algo\": \"scanline\"|\"zbuffer\", \"polygons\": [{\"vertices\":\n"
    "                      [[x, y, z], ...]}, ...]} (docs/TEACHING.md); it is checked\n"
    "                      first, and refused with the page's own messages\n";

/* The lesson file, checked by the engine: its text, or an error naming
 * the file and the place in it. */
static zs_status read_lesson(const char *path, char **text, zs_error *err) {
  size_t len;
  if (zs_load_file(path, path, 1 << 20, 0, text, &len, err)) return err->code;
  char *answer = zs_teach_run(*text);
  cJSON *a = answer ? cJSON_Parse(answer) : NULL;
  zs_teach_free(answer);
  if (!a) return zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
  const cJSON *e = cJSON_GetArrayItem(cJSON_GetObjectItem(a, "errors"), 0);
  if (e) {
    const char *where = cJSON_GetStringValue(cJSON_GetObjectItem(e, "path"));
    const char *why = cJSON_GetStringValue(cJSON_GetObjectItem(e, "message"));
    zs_error_set(err, ZS_ERR_PARSE, "%s: %s%s%s", path, where && *where ? where : "",
                 where && *where ? ": " : "", why ? why : "");
  }
  cJSON_Delete(a);
  if (err->code) return err->code;
  /* the page gets the lesson as cJSON prints it: JSON the engine has read */
  cJSON *l = cJSON_Parse(*text);
  free(*text);
  *text = l ? cJSON_PrintUnformatted(l) : NULL;
  cJSON_Delete(l);
  return *text ? ZS_OK : zs_error_set(err, ZS_ERR_NOMEM, "out of memory");
}

/* The page with the engine and the lesson (JSON; "null": the page's
 * first example) put in their places. */
static void write_page(FILE *f, const char *lesson) {
  static const char *const marks[2] = {"/*@ZSCAN_TEACH_MODULE@*/", "/*@ZSCAN_TEACH_LESSON@*/"};
  const char *p = zs_teach_page_html, *m = strstr(p, marks[0]);
  fwrite(p, 1, (size_t)(m - p), f);
  fputs(zs_teach_module_js, f);
  p = m + strlen(marks[0]);
  m = strstr(p, marks[1]);
  fwrite(p, 1, (size_t)(m - p), f);
  /* "</" would end the script element: in JSON it can stand only in a
   * string, where "<\/" reads the same */
  for (const char *s = lesson; *s; s++) {
    if (s[0] == '<' && s[1] == '/') fputc('<', f), fputc('\\', f);
    else fputc(*s, f);
  }
  fputs(m + strlen(marks[1]), f);
}

int zs_cmd_teach(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, NULL)) return 0;
  zs_error err;
  zs_error_clear(&err);
  const char *out = NULL, *lesson_path = NULL;
  char *lesson = NULL;
  int parsing = 1, rc = 1;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = NULL;
    if (strcmp(a, "-o") == 0) {
      if (zs_cli_output_value(argc, argv, &i, &v, &err) || zs_cli_output_format(a, v, "html", &err))
        goto fail;
      out = v;
    } else if (strcmp(a, "--lesson") == 0) {
      if (zs_cli_value(argc, argv, &i, &v, &err)) goto fail;
      lesson_path = v;
    } else {
      zs_error_set(&err, ZS_ERR_ARG, "unknown option '%s' (see zscan teach --help)", a);
      goto fail;
    }
  }
  if (!out) {
    zs_error_set(&err, ZS_ERR_ARG, "missing -o FILE.html (see zscan teach --help)");
    goto fail;
  }
  parsing = 0;
  if (!zs_teach_module_js[0]) {
    zs_error_set(&err, ZS_ERR_UNSUPPORTED,
                 "this zscan was built without the page's WebAssembly engine (emscripten's emcc "
                 "and cJSON's sources were not found; tools/setup.sh installs them)");
    goto fail;
  }
  if (lesson_path && read_lesson(lesson_path, &lesson, &err)) goto fail;
  zs_out page;
  if (zs_out_open(&page, out, &err)) goto fail_out;
  write_page(page.fp, lesson ? lesson : "null");
  if (zs_out_commit(&page, &err)) goto fail_out;
  rc = 0;
  goto done;
fail_out:
  zs_out_error_option(&err, "-o");
fail:
  rc = zs_cli_fail("zscan teach", &err, parsing);
done:
  free(lesson);
  return rc;
}
