/* zscan tools — `zscan bench raster`: raster throughput (bench_raster.c). */
#ifndef ZS_TOOLS_BENCH_RASTER_H
#define ZS_TOOLS_BENCH_RASTER_H

int zs_cmd_bench_raster(int argc, char **argv);

#endif
