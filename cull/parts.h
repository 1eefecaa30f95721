/* zscan cull — tighter bounds for the occlusion queries of objects.
 *
 * An object's box is a loose bound of a teapot or a vessel: its corners
 * are empty, and a query over them finds samples where the object has
 * none.  CHC++ queries the union of the boxes below a node when that is
 * much smaller than the node's own box; zscan applies the same to the
 * parts of an object: the faces of its mesh are split in two again and
 * again, each time the group whose split (by face centroid, binned along
 * an axis) saves the most box volume, while a split saves at least 0.2 %
 * of the mesh's box, into at most one part per ZS_FACES_PER_PART faces
 * and at most ZS_PARTS_MAX parts; each part gets the world box of its
 * vertices.  A query draws up to three faces a box, so the parts cost it
 * at most about 3 % of the polygons a draw of the object sets up.  The
 * union holds every face, so a query over it is as exact as one over the
 * box; an object of one part is asked about with its box.
 *
 * The part boxes of an instance are kept until its placement changes.
 */
#ifndef ZS_CULL_PARTS_H
#define ZS_CULL_PARTS_H

#include <stdint.h>

#include "raster/raster.h"
#include "scene/scene.h"

enum { ZS_PARTS_MAX = 32, ZS_FACES_PER_PART = 100 };

typedef struct zs_parts zs_parts;

/* An empty cache (meshes and instances are added as they are asked for);
 * NULL when out of memory. */
zs_parts *zs_parts_create(void);
void zs_parts_destroy(zs_parts *p);

/* The boxes to query for instance i of s: *n boxes (1 .. ZS_PARTS_MAX) at
 * *lo and *hi, valid until the next call.  Returns 0 when out of memory. */
int zs_parts_of(zs_parts *p, const zs_scene *s, int32_t i, const double (**lo)[3],
                const double (**hi)[3], int *n);

#endif
