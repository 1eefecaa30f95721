/* Clipping in homogeneous clip space (Sutherland–Hodgman).
 *
 * Planes, each as "inside when d >= 0":
 *   near   z + w >= 0     nothing behind the eye is ever rasterized: for a
 *                         perspective camera w = -z_eye >= near > 0 inside
 *   far    w - z >= 0
 *   guard  gx w -+ x >= 0, gy w -+ y >= 0
 * The guard band is wider than the viewport (gx = 1 + 2^15 / width), so
 * faces are clipped in x and y only when their window coordinates would
 * leave +-2^15 pixels and overflow the fixed-point setup; everything else
 * is left to the rasterizer's own span and row limits, which are exact.
 *
 * Watertightness: an edge shared by two faces is clipped by both.  The
 * intersection is always computed from the inside vertex towards the
 * outside one, so both faces get the very same point, bit for bit.
 *
 * Precision: the point lies on the plane, so its coordinate across the
 * plane is set from the plane (y = gy w on the top plane, z = -w on the
 * near plane, ...) rather than interpolated.  Interpolating it between two
 * vertices 1e30 apart would subtract numbers of 1e30 to get one of 1e3,
 * and lose every digit (a triangle with vertices at 1e30 came out half its
 * size before this).
 */
#include "raster/clip.h"

/* The point where the edge from `in` (d_in >= 0) to `out` (d_out < 0)
 * crosses plane p, with its coordinate across the plane taken from the
 * plane itself. */
static zs_clip_vert intersect(const zs_clip_vert *in, double d_in,
                              const zs_clip_vert *out, double d_out, int p,
                              double gx, double gy) {
  double t = d_in / (d_in - d_out);
  zs_clip_vert r;
  r.x = in->x + t * (out->x - in->x);
  r.y = in->y + t * (out->y - in->y);
  r.z = in->z + t * (out->z - in->z);
  r.w = in->w + t * (out->w - in->w);
  switch (p) {
    case ZS_CLIP_NEAR: r.z = -r.w; break;
    case ZS_CLIP_FAR: r.z = r.w; break;
    case ZS_CLIP_LEFT: r.x = -gx * r.w; break;
    case ZS_CLIP_RIGHT: r.x = gx * r.w; break;
    case ZS_CLIP_BOTTOM: r.y = -gy * r.w; break;
    default: r.y = gy * r.w; break;
  }
  return r;
}

int zs_clip_polygon(const zs_clip_vert *in, int n, unsigned mask, double gx,
                    double gy, zs_clip_vert *out) {
  zs_clip_vert buf[2][ZS_CLIP_MAX_VERTS];
  const zs_clip_vert *src = in;
  int count = n;
  int which = 0;
  for (int p = ZS_CLIP_NEAR; p <= ZS_CLIP_TOP; p <<= 1) {
    if (!(mask & (unsigned)p)) continue;
    zs_clip_vert *dst = buf[which];
    int m = 0;
    for (int i = 0; i < count; i++) {
      const zs_clip_vert *a = &src[i];
      const zs_clip_vert *b = &src[(i + 1) % count];
      double da = zs_clip_plane_dist(a, p, gx, gy), db = zs_clip_plane_dist(b, p, gx, gy);
      int ain = da >= 0.0, bin = db >= 0.0;
      /* A convex polygon gains at most one vertex per plane; only a face
       * that is not convex in clip space could come near this bound. */
      if (m + 2 > ZS_CLIP_MAX_VERTS) return 0;
      if (ain) dst[m++] = *a;
      if (ain && !bin) dst[m++] = intersect(a, da, b, db, p, gx, gy);
      else if (!ain && bin) dst[m++] = intersect(b, db, a, da, p, gx, gy);
    }
    count = m;
    src = dst;
    which ^= 1;
    if (count < 3) return 0;
  }
  for (int i = 0; i < count; i++) out[i] = src[i];
  return count;
}

/* Liang-Barsky in clip space, over the same planes in the same order as
 * the polygons; the point where the segment leaves a plane is
 * interpolated from both ends (a line has no neighbour to agree with). */
int zs_clip_segment(zs_clip_vert *a, zs_clip_vert *b, double gx, double gy) {
  double t0 = 0.0, t1 = 1.0;
  for (int p = ZS_CLIP_NEAR; p <= ZS_CLIP_TOP; p <<= 1) {
    const double da = zs_clip_plane_dist(a, p, gx, gy), db = zs_clip_plane_dist(b, p, gx, gy);
    if (da < 0 && db < 0) return 0;
    if (da < 0) {
      double t = da / (da - db);
      if (t > t0) t0 = t;
    } else if (db < 0) {
      double t = da / (da - db);
      if (t < t1) t1 = t;
    }
  }
  if (t0 > t1) return 0;
  zs_clip_vert A = *a, B = *b;
  if (t0 > 0) *a = (zs_clip_vert){A.x + t0 * (B.x - A.x), A.y + t0 * (B.y - A.y),
                                  A.z + t0 * (B.z - A.z), A.w + t0 * (B.w - A.w)};
  if (t1 < 1) *b = (zs_clip_vert){A.x + t1 * (B.x - A.x), A.y + t1 * (B.y - A.y),
                                  A.z + t1 * (B.z - A.z), A.w + t1 * (B.w - A.w)};
  return 1;
}
