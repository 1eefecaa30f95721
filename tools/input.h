/* zscan tools — what INPUT names on the command line.
 *
 *   (none)                 the embedded default scene (a small teapot field)
 *   FILE.obj               a Wavefront OBJ file (scene/obj.h)
 *   builtin:NAME[?k=v&..]  a generated scene: builtin:default[?level=L]
 *                          (teapots tessellated at level L, default 6),
 *                          builtin:cubes?n=N (N x N x N unit cubes)
 */
#ifndef ZS_TOOLS_INPUT_H
#define ZS_TOOLS_INPUT_H

#include "raster/error.h"
#include "scene/model.h"

zs_status zs_input_load(const char *spec, zs_model *out, zs_error *err);

#endif
