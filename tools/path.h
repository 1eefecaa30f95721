/* zscan tools — `zscan path SCENE`: the cameras of the scene's walk. */
#ifndef ZS_TOOLS_PATH_H
#define ZS_TOOLS_PATH_H

int zs_cmd_path(int argc, char **argv);

#endif
