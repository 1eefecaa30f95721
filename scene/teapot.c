/* The Utah teapot: Newell's 32 bicubic Bézier patches, tessellated into
 * quads.  See teapot.h for the data, the placement and the counts. */
#include "scene/teapot.h"

#include <math.h>

#include <stddef.h>

#include "util/matrix.h"

/* The 306 control points (x, y, z), z up, in the order of the published
 * table.  Vertices 205, 206, 216 and 223 of that table (1-based; the points
 * at distance 0.002 from the lid's pole) are used by no patch; they stay so
 * that the patch table keeps its well-known numbers. */
static const double teapot_points[ZS_TEAPOT_CONTROL_POINTS][3] = {
    /* 1 */
    {1.4, 0.0, 2.4}, {1.4, -0.784, 2.4}, {0.784, -1.4, 2.4},
    {0.0, -1.4, 2.4}, {1.3375, 0.0, 2.53125}, {1.3375, -0.749, 2.53125},
    {0.749, -1.3375, 2.53125}, {0.0, -1.3375, 2.53125},
    {1.4375, 0.0, 2.53125}, {1.4375, -0.805, 2.53125},
    {0.805, -1.4375, 2.53125}, {0.0, -1.4375, 2.53125},
    {1.5, 0.0, 2.4}, {1.5, -0.84, 2.4}, {0.84, -1.5, 2.4},
    {0.0, -1.5, 2.4}, {-0.784, -1.4, 2.4}, {-1.4, -0.784, 2.4},
    {-1.4, 0.0, 2.4}, {-0.749, -1.3375, 2.53125},
    /* 21 */
    {-1.3375, -0.749, 2.53125}, {-1.3375, 0.0, 2.53125},
    {-0.805, -1.4375, 2.53125}, {-1.4375, -0.805, 2.53125},
    {-1.4375, 0.0, 2.53125}, {-0.84, -1.5, 2.4}, {-1.5, -0.84, 2.4},
    {-1.5, 0.0, 2.4}, {-1.4, 0.784, 2.4}, {-0.784, 1.4, 2.4},
    {0.0, 1.4, 2.4}, {-1.3375, 0.749, 2.53125}, {-0.749, 1.3375, 2.53125},
    {0.0, 1.3375, 2.53125}, {-1.4375, 0.805, 2.53125},
    {-0.805, 1.4375, 2.53125}, {0.0, 1.4375, 2.53125}, {-1.5, 0.84, 2.4},
    {-0.84, 1.5, 2.4}, {0.0, 1.5, 2.4},
    /* 41 */
    {0.784, 1.4, 2.4}, {1.4, 0.784, 2.4}, {0.749, 1.3375, 2.53125},
    {1.3375, 0.749, 2.53125}, {0.805, 1.4375, 2.53125},
    {1.4375, 0.805, 2.53125}, {0.84, 1.5, 2.4}, {1.5, 0.84, 2.4},
    {1.75, 0.0, 1.875}, {1.75, -0.98, 1.875}, {0.98, -1.75, 1.875},
    {0.0, -1.75, 1.875}, {2.0, 0.0, 1.35}, {2.0, -1.12, 1.35},
    {1.12, -2.0, 1.35}, {0.0, -2.0, 1.35}, {2.0, 0.0, 0.9},
    {2.0, -1.12, 0.9}, {1.12, -2.0, 0.9}, {0.0, -2.0, 0.9},
    /* 61 */
    {-0.98, -1.75, 1.875}, {-1.75, -0.98, 1.875}, {-1.75, 0.0, 1.875},
    {-1.12, -2.0, 1.35}, {-2.0, -1.12, 1.35}, {-2.0, 0.0, 1.35},
    {-1.12, -2.0, 0.9}, {-2.0, -1.12, 0.9}, {-2.0, 0.0, 0.9},
    {-1.75, 0.98, 1.875}, {-0.98, 1.75, 1.875}, {0.0, 1.75, 1.875},
    {-2.0, 1.12, 1.35}, {-1.12, 2.0, 1.35}, {0.0, 2.0, 1.35},
    {-2.0, 1.12, 0.9}, {-1.12, 2.0, 0.9}, {0.0, 2.0, 0.9},
    {0.98, 1.75, 1.875}, {1.75, 0.98, 1.875},
    /* 81 */
    {1.12, 2.0, 1.35}, {2.0, 1.12, 1.35}, {1.12, 2.0, 0.9},
    {2.0, 1.12, 0.9}, {2.0, 0.0, 0.45}, {2.0, -1.12, 0.45},
    {1.12, -2.0, 0.45}, {0.0, -2.0, 0.45}, {1.5, 0.0, 0.225},
    {1.5, -0.84, 0.225}, {0.84, -1.5, 0.225}, {0.0, -1.5, 0.225},
    {1.5, 0.0, 0.15}, {1.5, -0.84, 0.15}, {0.84, -1.5, 0.15},
    {0.0, -1.5, 0.15}, {-1.12, -2.0, 0.45}, {-2.0, -1.12, 0.45},
    {-2.0, 0.0, 0.45}, {-0.84, -1.5, 0.225},
    /* 101 */
    {-1.5, -0.84, 0.225}, {-1.5, 0.0, 0.225}, {-0.84, -1.5, 0.15},
    {-1.5, -0.84, 0.15}, {-1.5, 0.0, 0.15}, {-2.0, 1.12, 0.45},
    {-1.12, 2.0, 0.45}, {0.0, 2.0, 0.45}, {-1.5, 0.84, 0.225},
    {-0.84, 1.5, 0.225}, {0.0, 1.5, 0.225}, {-1.5, 0.84, 0.15},
    {-0.84, 1.5, 0.15}, {0.0, 1.5, 0.15}, {1.12, 2.0, 0.45},
    {2.0, 1.12, 0.45}, {0.84, 1.5, 0.225}, {1.5, 0.84, 0.225},
    {0.84, 1.5, 0.15}, {1.5, 0.84, 0.15},
    /* 121: handle */
    {-1.6, 0.0, 2.025}, {-1.6, -0.3, 2.025}, {-1.5, -0.3, 2.25},
    {-1.5, 0.0, 2.25}, {-2.3, 0.0, 2.025}, {-2.3, -0.3, 2.025},
    {-2.5, -0.3, 2.25}, {-2.5, 0.0, 2.25}, {-2.7, 0.0, 2.025},
    {-2.7, -0.3, 2.025}, {-3.0, -0.3, 2.25}, {-3.0, 0.0, 2.25},
    {-2.7, 0.0, 1.8}, {-2.7, -0.3, 1.8}, {-3.0, -0.3, 1.8},
    {-3.0, 0.0, 1.8}, {-1.5, 0.3, 2.25}, {-1.6, 0.3, 2.025},
    {-2.5, 0.3, 2.25}, {-2.3, 0.3, 2.025},
    /* 141 */
    {-3.0, 0.3, 2.25}, {-2.7, 0.3, 2.025}, {-3.0, 0.3, 1.8},
    {-2.7, 0.3, 1.8}, {-2.7, 0.0, 1.575}, {-2.7, -0.3, 1.575},
    {-3.0, -0.3, 1.35}, {-3.0, 0.0, 1.35}, {-2.5, 0.0, 1.125},
    {-2.5, -0.3, 1.125}, {-2.65, -0.3, 0.9375}, {-2.65, 0.0, 0.9375},
    {-2.0, -0.3, 0.9}, {-1.9, -0.3, 0.6}, {-1.9, 0.0, 0.6},
    {-3.0, 0.3, 1.35}, {-2.7, 0.3, 1.575}, {-2.65, 0.3, 0.9375},
    {-2.5, 0.3, 1.125}, {-1.9, 0.3, 0.6},
    /* 161 */
    {-2.0, 0.3, 0.9},
    /* 162: spout */
    {1.7, 0.0, 1.425}, {1.7, -0.66, 1.425}, {1.7, -0.66, 0.6},
    {1.7, 0.0, 0.6}, {2.6, 0.0, 1.425}, {2.6, -0.66, 1.425},
    {3.1, -0.66, 0.825}, {3.1, 0.0, 0.825}, {2.3, 0.0, 2.1},
    {2.3, -0.25, 2.1}, {2.4, -0.25, 2.025}, {2.4, 0.0, 2.025},
    {2.7, 0.0, 2.4}, {2.7, -0.25, 2.4}, {3.3, -0.25, 2.4},
    {3.3, 0.0, 2.4}, {1.7, 0.66, 0.6}, {1.7, 0.66, 1.425},
    {3.1, 0.66, 0.825},
    /* 181 */
    {2.6, 0.66, 1.425}, {2.4, 0.25, 2.025}, {2.3, 0.25, 2.1},
    {3.3, 0.25, 2.4}, {2.7, 0.25, 2.4}, {2.8, 0.0, 2.475},
    {2.8, -0.25, 2.475}, {3.525, -0.25, 2.49375}, {3.525, 0.0, 2.49375},
    {2.9, 0.0, 2.475}, {2.9, -0.15, 2.475}, {3.45, -0.15, 2.5125},
    {3.45, 0.0, 2.5125}, {2.8, 0.0, 2.4}, {2.8, -0.15, 2.4},
    {3.2, -0.15, 2.4}, {3.2, 0.0, 2.4}, {3.525, 0.25, 2.49375},
    {2.8, 0.25, 2.475}, {3.45, 0.15, 2.5125},
    /* 201 */
    {2.9, 0.15, 2.475}, {3.2, 0.15, 2.4}, {2.8, 0.15, 2.4},
    /* 204: lid */
    {0.0, 0.0, 3.15}, {0.0, -0.002, 3.15}, {0.002, 0.0, 3.15},
    {0.8, 0.0, 3.15}, {0.8, -0.45, 3.15}, {0.45, -0.8, 3.15},
    {0.0, -0.8, 3.15}, {0.0, 0.0, 2.85}, {0.2, 0.0, 2.7},
    {0.2, -0.112, 2.7}, {0.112, -0.2, 2.7}, {0.0, -0.2, 2.7},
    {-0.002, 0.0, 3.15}, {-0.45, -0.8, 3.15}, {-0.8, -0.45, 3.15},
    {-0.8, 0.0, 3.15}, {-0.112, -0.2, 2.7},
    /* 221 */
    {-0.2, -0.112, 2.7}, {-0.2, 0.0, 2.7}, {0.0, 0.002, 3.15},
    {-0.8, 0.45, 3.15}, {-0.45, 0.8, 3.15}, {0.0, 0.8, 3.15},
    {-0.2, 0.112, 2.7}, {-0.112, 0.2, 2.7}, {0.0, 0.2, 2.7},
    {0.45, 0.8, 3.15}, {0.8, 0.45, 3.15}, {0.112, 0.2, 2.7},
    {0.2, 0.112, 2.7}, {0.4, 0.0, 2.55}, {0.4, -0.224, 2.55},
    {0.224, -0.4, 2.55}, {0.0, -0.4, 2.55}, {1.3, 0.0, 2.55},
    {1.3, -0.728, 2.55}, {0.728, -1.3, 2.55},
    /* 241 */
    {0.0, -1.3, 2.55}, {1.3, 0.0, 2.4}, {1.3, -0.728, 2.4},
    {0.728, -1.3, 2.4}, {0.0, -1.3, 2.4}, {-0.224, -0.4, 2.55},
    {-0.4, -0.224, 2.55}, {-0.4, 0.0, 2.55}, {-0.728, -1.3, 2.55},
    {-1.3, -0.728, 2.55}, {-1.3, 0.0, 2.55}, {-0.728, -1.3, 2.4},
    {-1.3, -0.728, 2.4}, {-1.3, 0.0, 2.4}, {-0.4, 0.224, 2.55},
    {-0.224, 0.4, 2.55}, {0.0, 0.4, 2.55}, {-1.3, 0.728, 2.55},
    {-0.728, 1.3, 2.55}, {0.0, 1.3, 2.55},
    /* 261 */
    {-1.3, 0.728, 2.4}, {-0.728, 1.3, 2.4}, {0.0, 1.3, 2.4},
    {0.224, 0.4, 2.55}, {0.4, 0.224, 2.55}, {0.728, 1.3, 2.55},
    {1.3, 0.728, 2.55}, {0.728, 1.3, 2.4}, {1.3, 0.728, 2.4},
    /* 270: bottom */
    {0.0, 0.0, 0.0}, {1.5, 0.0, 0.15}, {1.5, 0.84, 0.15},
    {0.84, 1.5, 0.15}, {0.0, 1.5, 0.15}, {1.5, 0.0, 0.075},
    {1.5, 0.84, 0.075}, {0.84, 1.5, 0.075}, {0.0, 1.5, 0.075},
    {1.425, 0.0, 0.0}, {1.425, 0.798, 0.0},
    /* 281 */
    {0.798, 1.425, 0.0}, {0.0, 1.425, 0.0}, {-0.84, 1.5, 0.15},
    {-1.5, 0.84, 0.15}, {-1.5, 0.0, 0.15}, {-0.84, 1.5, 0.075},
    {-1.5, 0.84, 0.075}, {-1.5, 0.0, 0.075}, {-0.798, 1.425, 0.0},
    {-1.425, 0.798, 0.0}, {-1.425, 0.0, 0.0}, {-1.5, -0.84, 0.15},
    {-0.84, -1.5, 0.15}, {0.0, -1.5, 0.15}, {-1.5, -0.84, 0.075},
    {-0.84, -1.5, 0.075}, {0.0, -1.5, 0.075}, {-1.425, -0.798, 0.0},
    {-0.798, -1.425, 0.0}, {0.0, -1.425, 0.0},
    /* 301 */
    {0.84, -1.5, 0.15}, {1.5, -0.84, 0.15}, {0.84, -1.5, 0.075},
    {1.5, -0.84, 0.075}, {0.798, -1.425, 0.0}, {1.425, -0.798, 0.0}};

/* The 32 patches as published: 16 control point numbers, counted from 1,
 * four rows of four.  Within a row the parameter u runs around the part
 * (clockwise seen from above for the surfaces of revolution); from row to
 * row v runs from the top of the part down (rim: from its inner edge over
 * the lip; lid and bottom: from the pole out).  With that, the cross product
 * dP/du x dP/dv points out of the teapot on every patch (the tests check). */
static const short teapot_patches[ZS_TEAPOT_PATCHES][16] = {
    /* rim */
    {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16},
    {4, 17, 18, 19, 8, 20, 21, 22, 12, 23, 24, 25, 16, 26, 27, 28},
    {19, 29, 30, 31, 22, 32, 33, 34, 25, 35, 36, 37, 28, 38, 39, 40},
    {31, 41, 42, 1, 34, 43, 44, 5, 37, 45, 46, 9, 40, 47, 48, 13},
    /* upper body */
    {13, 14, 15, 16, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60},
    {16, 26, 27, 28, 52, 61, 62, 63, 56, 64, 65, 66, 60, 67, 68, 69},
    {28, 38, 39, 40, 63, 70, 71, 72, 66, 73, 74, 75, 69, 76, 77, 78},
    {40, 47, 48, 13, 72, 79, 80, 49, 75, 81, 82, 53, 78, 83, 84, 57},
    /* lower body */
    {57, 58, 59, 60, 85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95, 96},
    {60, 67, 68, 69, 88, 97, 98, 99, 92, 100, 101, 102, 96, 103, 104, 105},
    {69, 76, 77, 78, 99, 106, 107, 108, 102, 109, 110, 111, 105, 112, 113,
     114},
    {78, 83, 84, 57, 108, 115, 116, 85, 111, 117, 118, 89, 114, 119, 120, 93},
    /* handle */
    {121, 122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134,
     135, 136},
    {124, 137, 138, 121, 128, 139, 140, 125, 132, 141, 142, 129, 136, 143,
     144, 133},
    {133, 134, 135, 136, 145, 146, 147, 148, 149, 150, 151, 152, 69, 153, 154,
     155},
    {136, 143, 144, 133, 148, 156, 157, 145, 152, 158, 159, 149, 155, 160, 161,
     69},
    /* spout */
    {162, 163, 164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 174, 175,
     176, 177},
    {165, 178, 179, 162, 169, 180, 181, 166, 173, 182, 183, 170, 177, 184,
     185, 174},
    {174, 175, 176, 177, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195,
     196, 197},
    {177, 184, 185, 174, 189, 198, 199, 186, 193, 200, 201, 190, 197, 202,
     203, 194},
    /* lid: knob */
    {204, 204, 204, 204, 207, 208, 209, 210, 211, 211, 211, 211, 212, 213,
     214, 215},
    {204, 204, 204, 204, 210, 217, 218, 219, 211, 211, 211, 211, 215, 220,
     221, 222},
    {204, 204, 204, 204, 219, 224, 225, 226, 211, 211, 211, 211, 222, 227,
     228, 229},
    {204, 204, 204, 204, 226, 230, 231, 207, 211, 211, 211, 211, 229, 232,
     233, 212},
    /* lid: shell */
    {212, 213, 214, 215, 234, 235, 236, 237, 238, 239, 240, 241, 242, 243,
     244, 245},
    {215, 220, 221, 222, 237, 246, 247, 248, 241, 249, 250, 251, 245, 252,
     253, 254},
    {222, 227, 228, 229, 248, 255, 256, 257, 251, 258, 259, 260, 254, 261,
     262, 263},
    {229, 232, 233, 212, 257, 264, 265, 234, 260, 266, 267, 238, 263, 268,
     269, 242},
    /* bottom */
    {270, 270, 270, 270, 279, 280, 281, 282, 275, 276, 277, 278, 271, 272,
     273, 274},
    {270, 270, 270, 270, 282, 289, 290, 291, 278, 286, 287, 288, 274, 283,
     284, 285},
    {270, 270, 270, 270, 291, 298, 299, 300, 288, 295, 296, 297, 285, 292,
     293, 294},
    {270, 270, 270, 270, 300, 305, 306, 279, 297, 303, 304, 275, 294, 301,
     302, 271}};

void zs_teapot_control_point(int c, double out[3]) {
  for (int k = 0; k < 3; k++) out[k] = teapot_points[c][k];
}

void zs_teapot_patch(int p, int out[16]) {
  for (int k = 0; k < 16; k++) out[k] = teapot_patches[p][k] - 1;
}

/* The cubic Bernstein polynomials B0..B3 at t, with s = 1 - t passed in so
 * that t = 0 and t = 1 give exactly (1,0,0,0) and (0,0,0,1): the corners of
 * a patch are then its corner control points, bit for bit.  B1 and B2 are
 * written so that swapping t and s swaps them exactly. */
static void bernstein3(double t, double s, double b[4]) {
  b[0] = s * s * s;
  b[1] = 3.0 * (t * (s * s));
  b[2] = 3.0 * (s * (t * t));
  b[3] = t * t * t;
}

/* The cubic with control values p[0..3] at the basis b.  Summed as
 * (outer pair) + (inner pair), which is the same sum in either direction,
 * so two patches that share a boundary curve but run along it in opposite
 * directions (the bottom and the lower body) still get the very same points.
 * Four equal control values (the poles of the lid and the bottom) give that
 * value exactly, so the quads at a pole have exactly zero area there. */
static double cubic(const double b[4], const double p[4]) {
  if (p[0] == p[1] && p[1] == p[2] && p[2] == p[3]) return p[0];
  return (b[0] * p[0] + b[3] * p[3]) + (b[1] * p[1] + b[2] * p[2]);
}

/* P(u, v) = sum over rows r and columns c of B_r(v) B_c(u) P[r][c]: first
 * each row's cubic in u, then the cubic in v through those four points. */
static void patch_point(const double cp[16][3], const double bu[4],
                        const double bv[4], double out[3]) {
  for (int k = 0; k < 3; k++) {
    double row[4];
    for (int r = 0; r < 4; r++) {
      double p[4] = {cp[4 * r][k], cp[4 * r + 1][k], cp[4 * r + 2][k],
                     cp[4 * r + 3][k]};
      row[r] = cubic(bu, p);
    }
    out[k] = cubic(bv, row);
  }
}

/* The derivatives of the cubic Bernstein polynomials at t (s = 1 - t). */
static void bernstein3_d(double t, double s, double d[4]) {
  d[0] = -3.0 * (s * s);
  d[1] = 3.0 * (s * (s - 2.0 * t));
  d[2] = 3.0 * (t * (2.0 * s - t));
  d[3] = 3.0 * (t * t);
}

/* The patch's normal du x dv at the bases (bu, bv) and their derivatives
 * (du, dv): outward (the quads turn counter-clockwise around it); zero
 * where the patch folds to a point (the poles of the lid and the bottom),
 * and there left for zs_model_compute_normals. */
static void patch_normal(const double cp[16][3], const double bu[4], const double bv[4],
                         const double du[4], const double dv[4], float out[3]) {
  double tu[3] = {0, 0, 0}, tv[3] = {0, 0, 0};
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 4; c++)
      for (int k = 0; k < 3; k++) {
        tu[k] += bv[r] * du[c] * cp[4 * r + c][k];
        tv[k] += dv[r] * bu[c] * cp[4 * r + c][k];
      }
  const double n[3] = {tu[1] * tv[2] - tu[2] * tv[1], tu[2] * tv[0] - tu[0] * tv[2],
                       tu[0] * tv[1] - tu[1] * tv[0]};
  const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  const double uu = tu[0] * tu[0] + tu[1] * tu[1] + tu[2] * tu[2];
  const double vv = tv[0] * tv[0] + tv[1] * tv[1] + tv[2] * tv[2];
  const double len = sqrt(nn);
  const int folded = !(nn > 1e-12 * uu * vv) || !(len > 0.0);
  for (int k = 0; k < 3; k++) out[k] = folded ? 0.0f : (float)(n[k] / len);
}

zs_status zs_teapot_add(zs_model *m, int level, const double xform[16],
                        uint32_t rgb, int32_t obj, zs_error *err) {
  if (level < 1 || level > ZS_TEAPOT_MAX_LEVEL)
    return zs_error_set(err, ZS_ERR_ARG,
                        "teapot: level %d is not in 1 .. %d", level,
                        (int)ZS_TEAPOT_MAX_LEVEL);
  const int side = level + 1;

  /* The basis at each grid parameter i / level, shared by u and v. */
  double basis[ZS_TEAPOT_MAX_LEVEL + 1][4], deriv[ZS_TEAPOT_MAX_LEVEL + 1][4];
  for (int i = 0; i < side; i++) {
    double t = (double)i / level;
    double s = (double)(level - i) / level;
    bernstein3(t, s, basis[i]);
    bernstein3_d(t, s, deriv[i]);
  }

  for (int p = 0; p < ZS_TEAPOT_PATCHES; p++) {
    double cp[16][3];
    for (int k = 0; k < 16; k++) {
      /* z up to y up: (x, y, z) -> (x, z, -y); 0.0 - y rather than -y
       * keeps a zero positive. */
      const double *q = teapot_points[teapot_patches[p][k] - 1];
      cp[k][0] = q[0];
      cp[k][1] = q[2];
      cp[k][2] = 0.0 - q[1];
    }

    /* Vertex (i, j) of the grid, u = i / level, v = j / level, gets index
     * first + j * side + i. */
    int32_t first = m->mesh.nverts, first_attr = m->mesh.nattrs;
    for (int j = 0; j < side; j++) {
      for (int i = 0; i < side; i++) {
        double pt[3];
        patch_point(cp, basis[i], basis[j], pt);
        /* the patch's own normal and parameters (u, v) as texture
         * coordinates; xform moves positions only (callers pass a
         * rotation and a uniform scale, or none) */
        float nrm[3], uv[2] = {(float)i / (float)level, (float)j / (float)level};
        patch_normal(cp, basis[i], basis[j], deriv[i], deriv[j], nrm);
        if (xform) {
          double w[3];
          for (int r = 0; r < 3; r++)
            w[r] = xform[4 * r] * nrm[0] + xform[4 * r + 1] * nrm[1] + xform[4 * r + 2] * nrm[2];
          for (int r = 0; r < 3; r++) nrm[r] = (float)w[r];
        }
        if (zs_model_add_attr(m, nrm, NULL, uv) < 0)
          return zs_error_set(err, ZS_ERR_NOMEM, "teapot: out of memory");
        if (xform) {
          double h[4];
          zs_mat_apply(xform, pt, h);
          pt[0] = h[0];
          pt[1] = h[1];
          pt[2] = h[2];
        }
        if (zs_model_add_vertex(m, pt[0], pt[1], pt[2]) < 0)
          return zs_error_set(err, ZS_ERR_NOMEM, "teapot: out of memory");
      }
    }

    /* Quads in the order (u0,v0) (u1,v0) (u1,v1) (u0,v1): counter-clockwise
     * around du x dv, which points outward. */
    for (int j = 0; j < level; j++) {
      for (int i = 0; i < level; i++) {
        int32_t a = first + j * side + i, t = first_attr + j * side + i;
        int32_t quad[4] = {a, a + 1, a + side + 1, a + side};
        int32_t attr[4] = {t, t + 1, t + side + 1, t + side};
        zs_status st = zs_model_add_face(m, quad, attr, 4, rgb, -1, obj);
        if (st != ZS_OK)
          return zs_error_set(err, st, "teapot: cannot add a face");
      }
    }
  }
  /* the poles' normals, from the faces around them */
  if (!zs_model_compute_normals(m, ZS_TEAPOT_CREASE_DEG))
    return zs_error_set(err, ZS_ERR_NOMEM, "teapot: out of memory");
  return ZS_OK;
}
