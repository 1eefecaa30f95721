/* Generated meshes and scenes: the spec parser and the dispatch to the
 * generators (scene/gen_*.c).  See generate.h for the specs. */
#include "scene/generate.h"
#include "scene/text.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/gen_internal.h"

static const zs_gen_def *const scene_defs[] = {
    &zs_gen_teapots_def, &zs_gen_spheres_def, &zs_gen_city_def,
    &zs_gen_plant_def,   &zs_gen_cubes_def,   &zs_gen_default_def};
enum { NSCENE_DEFS = sizeof scene_defs / sizeof scene_defs[0] };

/* ---- arguments --------------------------------------------------------- */

static int param_index(const zs_gen_def *def, const char *key) {
  for (int i = 0; i < def->nparams; i++)
    if (strcmp(def->params[i].key, key) == 0) return i;
  return -1;
}

int zs_gen_int(const zs_gen_args *a, const char *key) {
  int i = param_index(a->def, key);
  return i < 0 ? 0 : (int)a->value[i];
}

double zs_gen_real(const zs_gen_args *a, const char *key) {
  int i = param_index(a->def, key);
  return i < 0 ? 0.0 : a->value[i];
}

int zs_gen_given(const zs_gen_args *a, const char *key) {
  int i = param_index(a->def, key);
  return i >= 0 && a->given[i];
}

/* ---- strict numbers ---------------------------------------------------- */

static int is_digit(char c) { return c >= '0' && c <= '9'; }

/* [-]digits */
static int is_whole(const char *s) {
  if (*s == '-') s++;
  if (!is_digit(*s)) return 0;
  while (is_digit(*s)) s++;
  return *s == '\0';
}

static zs_status parse_value(const zs_gen_args *a, const zs_gen_param *p,
                             const char *text, double *value, uint64_t *seed,
                             zs_error *err) {
  switch (p->kind) {
    case ZS_GEN_SEED: {
      char *end;
      errno = 0;
      unsigned long long v = strtoull(text, &end, 10);
      if (!is_digit(text[0]) || *end != '\0' || errno == ERANGE)
        return zs_error_set(err, ZS_ERR_ARG,
                            "%s: %s: expected a whole number from 0 to %llu, got '%s'",
                            a->spec, p->key, (unsigned long long)UINT64_MAX, text);
      *seed = (uint64_t)v;
      return ZS_OK;
    }
    case ZS_GEN_INT: {
      if (!is_whole(text))
        return zs_error_set(err, ZS_ERR_ARG, "%s: %s: expected a whole number, got '%s'",
                            a->spec, p->key, text);
      errno = 0;
      long long v = strtoll(text, NULL, 10);
      if (errno == ERANGE || (double)v < p->lo || (double)v > p->hi)
        return zs_error_set(err, ZS_ERR_ARG, "%s: %s: %s is outside %.0f .. %.0f", a->spec,
                            p->key, text, p->lo, p->hi);
      *value = (double)v;
      return ZS_OK;
    }
    case ZS_GEN_REAL: {
      if (!zs_text_is_decimal(text))
        return zs_error_set(err, ZS_ERR_ARG, "%s: %s: expected a number, got '%s'", a->spec,
                            p->key, text);
      double v = strtod(text, NULL);
      if (!isfinite(v) || v < p->lo || v > p->hi)
        return zs_error_set(err, ZS_ERR_ARG, "%s: %s: %s is outside %g .. %g", a->spec,
                            p->key, text, p->lo, p->hi);
      *value = v;
      return ZS_OK;
    }
  }
  return ZS_ERR_ARG;
}

/* "a, b, c" of the names in a table, or of a def's parameters. */
static void name_list(char *out, size_t cap, const zs_gen_def *const *defs, int n) {
  size_t len = 0;
  out[0] = '\0';
  for (int i = 0; i < n && len < cap; i++)
    len += (size_t)snprintf(out + len, cap - len, "%s%s", i ? ", " : "", defs[i]->name);
}

static void param_list(char *out, size_t cap, const zs_gen_def *def) {
  size_t len = 0;
  out[0] = '\0';
  for (int i = 0; i < def->nparams && len < cap; i++)
    len += (size_t)snprintf(out + len, cap - len, "%s%s", i ? ", " : "", def->params[i].key);
}

/* Parses spec against the table defs (what: "scene" or "mesh" for the
 * message about an unknown name).  buf receives the spec's body. */
static zs_status parse_spec(const char *spec, const zs_gen_def *const *defs, int ndefs,
                            const char *what, char *buf, zs_gen_args *a, zs_error *err) {
  memset(a, 0, sizeof *a);
  a->spec = spec;
  a->seed = ZS_GEN_DEFAULT_SEED;
  if (strlen(spec) > ZS_GEN_SPEC_MAX)
    return zs_error_set(err, ZS_ERR_ARG, "%.40s...: longer than %d bytes", spec,
                        (int)ZS_GEN_SPEC_MAX);
  const char *body = strncmp(spec, "builtin:", 8) == 0 ? spec + 8 : spec;
  strcpy(buf, body);
  /* NAME?k=v&k=v, or NAME,k=v,k=v: the same, with nothing the shell reads */
  char *query = buf + strcspn(buf, "?,");
  if (*query) *query++ = '\0';
  else query = NULL;

  for (int i = 0; i < ndefs && !a->def; i++)
    if (strcmp(defs[i]->name, buf) == 0) a->def = defs[i];
  if (!a->def) {
    char names[256];
    name_list(names, sizeof names, defs, ndefs);
    return zs_error_set(err, ZS_ERR_ARG, "%s: unknown generated %s '%s' (%s)", spec, what,
                        buf, names);
  }
  const zs_gen_def *def = a->def;
  for (int i = 0; i < def->nparams; i++) a->value[i] = def->params[i].def;

  /* key=value&key=value (or with commas): each item split in place. */
  for (char *item = query; item;) {
    char *amp = item + strcspn(item, "&,");
    if (*amp) *amp = '\0';
    else amp = NULL;
    char *eq = strchr(item, '=');
    if (!eq || eq == item)
      return zs_error_set(err, ZS_ERR_ARG, "%s: expected key=value, got '%s'", spec, item);
    *eq = '\0';
    int k = param_index(def, item);
    if (k < 0) {
      char keys[256];
      param_list(keys, sizeof keys, def);
      return zs_error_set(err, ZS_ERR_ARG, "%s: unknown parameter '%s' (%s)", spec, item,
                          keys);
    }
    if (a->given[k])
      return zs_error_set(err, ZS_ERR_ARG, "%s: %s given twice", spec, item);
    if (parse_value(a, &def->params[k], eq + 1, &a->value[k], &a->seed, err))
      return err->code;
    a->given[k] = 1;
    item = amp ? amp + 1 : NULL;
  }
  return ZS_OK;
}

/* ---- dispatch ---------------------------------------------------------- */

/* The generators may rely on a clear error of their own; what they report
 * is passed on to the caller's err (first error wins there). */
static zs_status pass_on(zs_status st, const zs_error *mine, const char *spec,
                         zs_error *err) {
  if (st == ZS_OK) return ZS_OK;
  if (mine->code == ZS_OK) /* a path that forgot to say why */
    return zs_error_set(err, st, "%s: cannot be generated", spec);
  return zs_error_set(err, st, "%s", mine->msg);
}

/* Parses spec against defs and builds what it names: the mesh into m, or
 * (m NULL) the scene into s, finished. */
static zs_status run_spec(const char *spec, const zs_gen_def *const *defs, int ndefs,
                          const char *what, zs_model *m, zs_scene *s, zs_error *err) {
  char buf[ZS_GEN_SPEC_MAX + 1];
  zs_gen_args a;
  zs_error mine;
  zs_error_clear(&mine);
  zs_status st = parse_spec(spec, defs, ndefs, what, buf, &a, &mine);
  if (st == ZS_OK) st = m ? a.def->mesh(&a, m, &mine) : a.def->scene(&a, s, &mine);
  if (st == ZS_OK && !m) st = zs_scene_finish(s, &mine);
  return pass_on(st, &mine, spec, err);
}

zs_status zs_gen_mesh(const char *spec, zs_model *out, zs_error *err) {
  zs_model_init(out);
  if (!spec) return zs_error_set(err, ZS_ERR_ARG, "no mesh spec");
  const zs_gen_def *defs[16];
  int n = zs_gen_mesh_ndefs < 16 ? zs_gen_mesh_ndefs : 16;
  for (int i = 0; i < n; i++) defs[i] = &zs_gen_mesh_defs[i];
  zs_status st = run_spec(spec, defs, n, "mesh", out, NULL, err);
  if (st != ZS_OK) zs_model_free(out); /* leaves it empty */
  return st;
}

zs_status zs_gen_scene(const char *spec, zs_scene *out, zs_error *err) {
  zs_scene_init(out);
  zs_status st = run_spec(spec ? spec : "default", scene_defs, NSCENE_DEFS, "scene", NULL, out,
                          err);
  if (st != ZS_OK) zs_scene_free(out); /* leaves it empty */
  return st;
}

/* ---- counts ------------------------------------------------------------ */

void zs_gen_count(const zs_scene *s, zs_gen_counts *out) {
  memset(out, 0, sizeof *out);
  int64_t *tris = calloc(s->nmeshes > 0 ? (size_t)s->nmeshes : 1, sizeof *tris);
  if (!tris) return;
  for (int32_t m = 0; m < s->nmeshes; m++) {
    const zs_mesh *me = &s->meshes[m].mesh;
    for (int32_t f = 0; f < me->nfaces; f++)
      tris[m] += me->face_start[f + 1] - me->face_start[f] - 2;
  }
  for (int32_t i = 0; i < s->ninst; i++) {
    const zs_model *m = &s->meshes[s->inst[i].mesh];
    out->objects++;
    out->faces += m->nsource_faces;
    out->triangles += tris[s->inst[i].mesh];
    out->vertices += m->mesh.nverts;
  }
  free(tris);
}
