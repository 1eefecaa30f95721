/* libFuzzer target: the teaching page's engine (web/teach_module.c) on
 * arbitrary lessons: its answer is always JSON holding a trace or at
 * least one error with a place and a one-line message. */
#include <cjson/cJSON.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "web/teach_module.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char *lesson = malloc(size + 1);
  if (!lesson) return 0;
  memcpy(lesson, data, size);
  lesson[size] = '\0';
  char *answer = zs_teach_run(lesson);
  free(lesson);
  cJSON *a = answer ? cJSON_Parse(answer) : NULL;
  zs_teach_free(answer);
  if (!a) abort();
  const cJSON *trace = cJSON_GetObjectItem(a, "trace"), *errors = cJSON_GetObjectItem(a, "errors");
  if (!!trace == !!errors) abort(); /* one or the other */
  for (const cJSON *e = errors ? errors->child : NULL; e; e = e->next) {
    const char *msg = cJSON_GetStringValue(cJSON_GetObjectItem(e, "message"));
    if (!cJSON_GetStringValue(cJSON_GetObjectItem(e, "path")) || !msg || !*msg || strchr(msg, '\n'))
      abort();
  }
  cJSON_Delete(a);
  return 0;
}
