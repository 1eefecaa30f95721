/* zscan raster — the query box (raster.h, "query.c: occlusion queries"):
 * an axis-aligned world box as the faces a query draws, shared by the
 * exact queries (query.c) and the depth pyramid's test of the same boxes
 * (hzb.c), so that the two see one box. */
#ifndef ZS_RASTER_BOX_H
#define ZS_RASTER_BOX_H

#include <stdint.h>

/* The faces as seen from outside, counter-clockwise, by corner index (bit
 * 0 picks x, bit 1 y, bit 2 z); face 2a is the low side of axis a, 2a + 1
 * the high side. */
extern const int32_t zs_box_faces[6][4];

/* Corner b of the box [lo, hi]. */
static inline void zs_box_corner(const double lo[3], const double hi[3], int b, double out[3]) {
  out[0] = (b & 1) ? hi[0] : lo[0];
  out[1] = (b & 2) ? hi[1] : lo[1];
  out[2] = (b & 4) ? hi[2] : lo[2];
}

/* Whether the eye lies in the box (its faces then all show, from within). */
static inline int zs_box_holds(const double lo[3], const double hi[3], const double eye[3]) {
  for (int a = 0; a < 3; a++)
    if (eye[a] < lo[a] || eye[a] > hi[a]) return 0;
  return 1;
}

/* Whether face f of the box is turned to the eye. */
static inline int zs_box_face_turned_to(const double lo[3], const double hi[3],
                                        const double eye[3], int f) {
  const int a = f / 2;
  return (f % 2) ? eye[a] > hi[a] : eye[a] < lo[a];
}

/* What a query grows the box by on every side (raster.h): 1/32 of a
 * pixel at its farthest point, for a camera of view and projection on a
 * width x height window. */
double zs_box_margin(const double view[16], const double proj[16], int perspective, int width,
                     int height, const double lo[3], const double hi[3]);

#endif
