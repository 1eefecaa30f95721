/* zscan tools — `zscan bench raster`: raster throughput (bench_raster.c). */
#ifndef ZS_TOOLS_BENCH_RASTER_H
#define ZS_TOOLS_BENCH_RASTER_H

int zs_cmd_bench_raster(int argc, char **argv);

/* The whole scenes bench raster measures (and bench samples after it). */
extern const char *const zs_bench_scenes[];
extern const int zs_bench_nscenes;

#endif
