/* zscan tools — `zscan render [INPUT] [options]`. */
#ifndef ZS_TOOLS_RENDER_H
#define ZS_TOOLS_RENDER_H

/* argv[0] is "render".  Returns the process exit status. */
int zs_cmd_render(int argc, char **argv);

#endif
