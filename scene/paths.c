/* zscan scene — the named camera paths (see paths.h for each motion). */
#include "scene/paths.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/exactmath.h"
#include "util/matrix.h"

const char zs_path_names[] = "static, translate, roll, yaw, fast";

typedef enum path_kind { PATH_STATIC, PATH_TRANSLATE, PATH_ROLL, PATH_YAW, PATH_FAST } path_kind;

static const struct {
  const char *name;
  path_kind kind;
} kinds[] = {
    {"static", PATH_STATIC}, {"translate", PATH_TRANSLATE}, {"roll", PATH_ROLL},
    {"yaw", PATH_YAW},       {"fast", PATH_FAST},
};

/* The camera's frame: distance, view direction, right and up (unit,
 * orthogonal).  Returns 0 when eye == target or up is along the view. */
typedef struct view_frame {
  double dist, fwd[3], right[3], up[3];
} view_frame;

static void cross(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

static double norm(const double a[3]) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

static int make_frame(const zs_camera *c, view_frame *v) {
  double d[3];
  for (int i = 0; i < 3; i++) d[i] = c->target[i] - c->eye[i];
  v->dist = norm(d);
  if (!(v->dist > 0.0) || !isfinite(v->dist)) return 0;
  for (int i = 0; i < 3; i++) v->fwd[i] = d[i] / v->dist;
  cross(v->fwd, c->up, v->right);
  double r = norm(v->right), ul = norm(c->up);
  /* the same test as gluLookAt's failure: up (nearly) along the view */
  if (!(r > 1e-12 * ul) || !isfinite(r)) return 0;
  for (int i = 0; i < 3; i++) v->right[i] /= r;
  cross(v->right, v->fwd, v->up);
  return 1;
}

/* w = 0, 1, 2, 1, 0, -1, -2, -1, ... : the fast path's offset in steps. */
static int zigzag(int32_t f) {
  static const int w[8] = {0, 1, 2, 1, 0, -1, -2, -1};
  return w[f % 8];
}

static void make_key(path_kind kind, const zs_camera *base, const view_frame *v, int32_t f,
                     zs_keyframe *k) {
  k->frame = f;
  memcpy(k->eye, base->eye, sizeof k->eye);
  memcpy(k->target, base->target, sizeof k->target);
  memcpy(k->up, v->up, sizeof k->up);
  double s = 0.0;
  switch (kind) {
  case PATH_STATIC:
    return;
  case PATH_TRANSLATE:
    s = ZS_PATH_TRANSLATE_STEP * f * v->dist;
    break;
  case PATH_FAST:
    s = ZS_PATH_FAST_STEP * zigzag(f) * v->dist;
    break;
  case PATH_ROLL: {
    double ca, sa;
    zs_sincos_deg(ZS_PATH_ROLL_DEG * f, &sa, &ca);
    for (int i = 0; i < 3; i++) k->up[i] = ca * v->up[i] + sa * v->right[i];
    return;
  }
  case PATH_YAW: {
    double cb, sb;
    zs_sincos_deg(ZS_PATH_YAW_DEG * f, &sb, &cb);
    for (int i = 0; i < 3; i++)
      k->target[i] = base->eye[i] + v->dist * (cb * v->fwd[i] - sb * v->right[i]);
    return;
  }
  }
  for (int i = 0; i < 3; i++) {
    k->eye[i] += s * v->right[i];
    k->target[i] += s * v->right[i];
  }
}

zs_status zs_path_named(const char *name, const zs_camera *base, int32_t frames, zs_path *out,
                        zs_error *err) {
  out->keys = NULL;
  out->nkeys = out->frames = 0;
  int found = -1;
  for (size_t i = 0; i < sizeof kinds / sizeof kinds[0] && name; i++)
    if (strcmp(name, kinds[i].name) == 0) found = (int)i;
  if (found < 0)
    return zs_error_set(err, ZS_ERR_ARG, "unknown named path '%s' (%s)", name ? name : "",
                        zs_path_names);
  if (frames < 1 || frames > ZS_PATH_MAX_FRAMES)
    return zs_error_set(err, ZS_ERR_ARG, "frames %d: must be 1 to %d", (int)frames,
                        ZS_PATH_MAX_FRAMES);
  for (int i = 0; i < 3; i++)
    if (!isfinite(base->eye[i]) || !isfinite(base->target[i]) || !isfinite(base->up[i]))
      return zs_error_set(err, ZS_ERR_ARG, "camera: not a finite number");
  view_frame v;
  if (!make_frame(base, &v)) {
    if (memcmp(base->eye, base->target, sizeof base->eye) == 0)
      return zs_error_set(err, ZS_ERR_ARG, "eye and target are the same point");
    return zs_error_set(err, ZS_ERR_ARG, "up %g,%g,%g: zero or parallel to the view direction",
                        base->up[0], base->up[1], base->up[2]);
  }
  out->keys = malloc((size_t)frames * sizeof *out->keys);
  if (!out->keys) return zs_error_set(err, ZS_ERR_NOMEM, "path: out of memory");
  for (int32_t f = 0; f < frames; f++) make_key(kinds[found].kind, base, &v, f, &out->keys[f]);
  out->nkeys = out->frames = frames;
  return ZS_OK;
}

void zs_path_free(zs_path *p) {
  if (!p) return;
  free(p->keys);
  p->keys = NULL;
  p->nkeys = p->frames = 0;
}

/* "%.6f" of x, without a minus sign on a value that prints as zero. */
static const char *fixed6(double x, char buf[64]) {
  snprintf(buf, 64, "%.6f", x);
  if (strcmp(buf, "-0.000000") == 0) memmove(buf, buf + 1, strlen(buf));
  return buf;
}

int zs_path_format(char *buf, size_t cap, int32_t f, const zs_camera *c) {
  char t[9][64];
  const double *v[3] = {c->eye, c->target, c->up};
  for (int i = 0; i < 9; i++) fixed6(v[i / 3][i % 3], t[i]);
  return snprintf(buf, cap, "frame %d eye %s,%s,%s target %s,%s,%s up %s,%s,%s\n", (int)f, t[0],
                  t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8]);
}
