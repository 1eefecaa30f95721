/* zscan tools — `zscan query INPUT`: per object, the pixels it owns and the
 * samples of its bounding box, for checking queries against another
 * renderer. */
#ifndef ZS_TOOLS_QUERY_H
#define ZS_TOOLS_QUERY_H

int zs_cmd_query(int argc, char **argv);

#endif
