/* vfc: hierarchical view-frustum culling.  The traversal tests the nodes'
 * tight boxes against the frustum (plane masking, p/n-vertex tests) and
 * drops what lies outside; every element inside is opened or drawn. */
#include "cull/internal.h"

static void visit(frame_ctx *f, elem e, unsigned mask) {
  elem_state *es = cull_state(f, e);
  es->visible = 1;
  es->last_visited = f->c->frame;
  cull_traverse_node(f, e, mask);
}

const cull_hooks cull_vfc_hooks = {.visit = visit};
const cull_ops cull_vfc = {.name = "vfc", .frame = cull_traverse_octree, .hooks = &cull_vfc_hooks};
