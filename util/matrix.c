/* Matrices and the camera, with the conventions of zscan/zscan.h: row-major
 * double[16] acting on column vectors, OpenGL's gluLookAt, gluPerspective
 * and glOrtho. */
#include <math.h>
#include <string.h>

#include "util/matrix.h"

#include "util/exactmath.h"

void zs_mat_identity(double m[16]) {
  memset(m, 0, 16 * sizeof m[0]);
  m[0] = m[5] = m[10] = m[15] = 1.0;
}

void zs_mat_mul(double out[16], const double a[16], const double b[16]) {
  double r[16];
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) {
      double s = 0.0;
      for (int k = 0; k < 4; k++) s += a[4 * i + k] * b[4 * k + j];
      r[4 * i + j] = s;
    }
  memcpy(out, r, sizeof r);
}

void zs_mat_translate(double m[16], double x, double y, double z) {
  zs_mat_identity(m);
  m[3] = x;
  m[7] = y;
  m[11] = z;
}

void zs_mat_scale(double m[16], double x, double y, double z) {
  zs_mat_identity(m);
  m[0] = x;
  m[5] = y;
  m[10] = z;
}

void zs_vec3_in_range(const double v[3], double out[3]) {
  const double big = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
  int e = 0;
  if (big > 0x1p500 || (big > 0.0 && big < 0x1p-500)) frexp(big, &e);
  for (int k = 0; k < 3; k++) out[k] = e ? ldexp(v[k], -e) : v[k];
}

void zs_mat_rotate_turns(double m[16], double turns, double x, double y, double z) {
  zs_mat_identity(m);
  double len = sqrt(x * x + y * y + z * z);
  if (len == 0.0) return;
  x /= len;
  y /= len;
  z /= len;
  /* Exact at quarter turns: exact zeros and ones, so a cube rotated by 90
   * degrees lands on the same grid points as before. */
  double c, s;
  zs_sincos_turns(turns, &s, &c);
  double t = 1.0 - c;
  m[0] = t * x * x + c;     m[1] = t * x * y - s * z; m[2] = t * x * z + s * y;
  m[4] = t * x * y + s * z; m[5] = t * y * y + c;     m[6] = t * y * z - s * x;
  m[8] = t * x * z - s * y; m[9] = t * y * z + s * x; m[10] = t * z * z + c;
}

/* zs_sincos_deg is zs_sincos_turns of deg / 360: the same bits. */
void zs_mat_rotate(double m[16], double deg, double x, double y, double z) {
  zs_mat_rotate_turns(m, deg / 360.0, x, y, z);
}

int zs_mat_look_at(double m[16], const double eye[3], const double target[3],
                   const double up[3]) {
  double f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
  double fl = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  if (!(fl > 0.0) || !isfinite(fl)) return 0;
  for (int i = 0; i < 3; i++) f[i] /= fl;
  /* s = f x up, u = s x f (gluLookAt) */
  double s[3] = {f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2],
                 f[0] * up[1] - f[1] * up[0]};
  double sl = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  double upl = sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]);
  /* up parallel to the view (or zero) leaves no sideways direction. */
  if (!(sl > 1e-12 * upl) || !isfinite(sl)) return 0;
  for (int i = 0; i < 3; i++) s[i] /= sl;
  double u[3] = {s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2],
                 s[0] * f[1] - s[1] * f[0]};
  zs_mat_identity(m);
  for (int i = 0; i < 3; i++) {
    m[i] = s[i];
    m[4 + i] = u[i];
    m[8 + i] = -f[i];
  }
  m[3] = -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]);
  m[7] = -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]);
  m[11] = f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2];
  return 1;
}

void zs_mat_perspective(double m[16], double fovy_deg, double aspect,
                        double znear, double zfar) {
  double s, c; /* f = cot(fovy / 2) */
  zs_sincos_deg(0.5 * fovy_deg, &s, &c);
  double f = c / s;
  memset(m, 0, 16 * sizeof m[0]);
  m[0] = f / aspect;
  m[5] = f;
  m[10] = (zfar + znear) / (znear - zfar);
  m[11] = 2.0 * zfar * znear / (znear - zfar);
  m[14] = -1.0;
}

void zs_mat_ortho(double m[16], double left, double right, double bottom,
                  double top, double znear, double zfar) {
  zs_mat_identity(m);
  m[0] = 2.0 / (right - left);
  m[3] = -(right + left) / (right - left);
  m[5] = 2.0 / (top - bottom);
  m[7] = -(top + bottom) / (top - bottom);
  m[10] = -2.0 / (zfar - znear);
  m[11] = -(zfar + znear) / (zfar - znear);
}
