/* zscan util — lights as the public API gives them (lights.c): checked,
 * and the device's default; shared by the device, the scene files and the
 * command line, each of which words its own errors around the check's. */
#ifndef ZS_UTIL_LIGHTS_H
#define ZS_UTIL_LIGHTS_H

#include "zscan/zscan.h"

/* Checks lights[0 .. n) (ZS_ERR_ARG: "lights[K].FIELD: reason"). */
zs_status zs_lights_check(const zs_light *lights, int n, zs_error *err);

/* The default lights (zscan.h, zs_device_set_lights) into out; their number. */
int zs_lights_default(zs_light out[ZS_MAX_LIGHTS]);

#endif
