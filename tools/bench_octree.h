/* zscan tools — `zscan bench octree`: the update cost of moving objects in
 * the loose and the plain octree (the CHC cost-model paper's experiment 1,
 * Fig. 6). */
#ifndef ZS_TOOLS_BENCH_OCTREE_H
#define ZS_TOOLS_BENCH_OCTREE_H

/* argv[0] is "octree".  Returns the process exit status. */
int zs_cmd_bench_octree(int argc, char **argv);

#endif
