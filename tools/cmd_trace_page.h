/* zscan tools — the self-contained HTML page of `zscan trace --html`:
 * the head up to where the data go, and the tail after them. */
#ifndef ZS_TOOLS_CMD_TRACE_PAGE_H
#define ZS_TOOLS_CMD_TRACE_PAGE_H

extern const char zs_cmd_trace_page_head[];
extern const char zs_cmd_trace_page_tail[];

#endif
