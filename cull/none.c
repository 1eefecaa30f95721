/* none: every instance drawn, in the scene's order, without a test: the
 * reference image. */
#include "cull/internal.h"

static void draw_all(frame_ctx *f) {
  for (int32_t i = 0; i < f->s->ninst && f->status == ZS_OK; i++) cull_draw_instance(f, i);
}

const cull_ops cull_none = {.name = "none", .frame = draw_all};
