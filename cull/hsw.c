/* hsw: hierarchical stop-and-wait.  Front to back, every element in the
 * frustum is queried and its answer waited for before going on; a visible
 * one is opened or drawn (query_queue.c). */
#include "cull/internal.h"

static void visit(frame_ctx *f, elem e, unsigned mask) {
  if (cull_too_close(f, e)) { /* cannot be asked: taken as visible */
    cull_traverse_node(f, e, mask);
    return;
  }
  cull_issue_query(f, e, mask, 0);
  if (f->status == ZS_OK) cull_take_result(f); /* stop and wait */
}

static const cull_hooks hooks = {.visit = visit, .draw_visible = cull_draw_visible};
const cull_ops cull_hsw = {.name = "hsw", .frame = cull_traverse_octree, .hooks = &hooks};
