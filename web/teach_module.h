/* zscan web — the teaching page's engine (teach_module.c): a lesson in,
 * its trace or its errors out, as JSON text. */
#ifndef ZS_WEB_TEACH_MODULE_H
#define ZS_WEB_TEACH_MODULE_H

/* The answer to lesson_json (teach_module.c says both shapes); the
 * caller frees it with zs_teach_free.  NULL only when out of memory. */
char *zs_teach_run(const char *lesson_json);
void zs_teach_free(char *answer);

#endif
