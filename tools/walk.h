/* zscan tools — `zscan walk`: culling methods over a scene's camera path. */
#ifndef ZS_TOOLS_WALK_H
#define ZS_TOOLS_WALK_H

int zs_cmd_walk(int argc, char **argv);

#endif
