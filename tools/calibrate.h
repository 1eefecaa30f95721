/* zscan tools — `zscan calibrate`: the device clock's constants measured
 * on this machine for zscan's own raster code. */
#ifndef ZS_TOOLS_CALIBRATE_H
#define ZS_TOOLS_CALIBRATE_H

int zs_cmd_calibrate(int argc, char **argv);

#endif
