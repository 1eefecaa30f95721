/* zscan lib — a layer file written with other outputs (zscan/layer.h's
 * zs_layer_write, finished into a set of outputs that replace their files
 * together: lib/outfile.h). */
#ifndef ZS_LIB_LAYER_FILE_H
#define ZS_LIB_LAYER_FILE_H

#include "lib/outfile.h"
#include "zscan/layer.h"

/* zs_layer_write, the file finished into set (NULL: committed at once). */
zs_status zs_layer_write_in(zs_out_set *set, const char *path, const zs_layer *l, zs_error *err);

#endif
