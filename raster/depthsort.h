/* zscan raster — depth sort with frame coherence (depthsort.c): the
 * painter's algorithm of the frame-coherence paper.  The face stage notes
 * each face in view with its key; at finish the batch's faces are ordered
 * far to near, re-using the last frame's order where the camera's motion
 * allows, and each polygon gets its painter's depth.  Opaque: the device
 * holds one, made with zs_depthsort_create. */
#ifndef ZS_RASTER_DEPTHSORT_H
#define ZS_RASTER_DEPTHSORT_H

#include "raster/setup.h"

typedef struct zs_depthsort zs_depthsort;

zs_depthsort *zs_depthsort_create(void); /* NULL: out of memory */
void zs_depthsort_destroy(zs_depthsort *ds);
/* The camera's projection: where the circle around the window lies whose
 * faces are ordered (a roll keeps that set whole). */
void zs_depthsort_set_projection(zs_depthsort *ds, const double proj[16], int perspective);
/* A new frame: no face noted yet. */
void zs_depthsort_clear(zs_depthsort *ds);
/* The next frame sorts from scratch. */
void zs_depthsort_forget(zs_depthsort *ds);
const zs_depthsort_stats *zs_depthsort_stats_of(const zs_depthsort *ds);
double zs_depthsort_ms(const zs_depthsort *ds);

/* Records a face in view (whether or not it covers a pixel centre). */
int zs_depthsort_note(zs_depthsort *ds, uint32_t id, double key);
/* Orders the batch's faces and gives each polygon its painter's depth. */
int zs_depthsort_order(zs_depthsort *ds, zs_batch *b, const double view[16]);

/* Whether the painter orders a face that set-up has seen (result r): it
 * meets the circle around the window and, where back faces are culled,
 * is or may be turned to the eye.  An unclipped face (clipped NULL;
 * corners fv, clip-space in clip[], snapped in snap[]) or the clipped
 * polygon of n corners; scratch holds n corners. */
int zs_depthsort_selects(const zs_depthsort *ds, const zs_setup_params *sp, zs_setup_result r,
                         const zs_clip_vert *clip, const zs_snap_vert *snap, const int32_t *fv,
                         const zs_clip_vert *clipped, int n, zs_clip_vert *scratch);

#endif
