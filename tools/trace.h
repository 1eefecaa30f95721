/* zscan tools — `zscan trace`: the scanline z-buffer's tables, row by row. */
#ifndef ZS_TOOLS_TRACE_H
#define ZS_TOOLS_TRACE_H

int zs_cmd_trace(int argc, char **argv);

#endif
