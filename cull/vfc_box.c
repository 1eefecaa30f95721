/* vfc-box, the conservative-visibility paper's test: an instance is drawn
 * when its centre lies in the view box around the frustum (six
 * comparisons after transforming the centre alone).  Approximate: an
 * instance whose centre lies outside is lost. */
#include "cull/internal.h"

static void draw_centres_inside(frame_ctx *f) {
  zs_view_box vb;
  zs_view_box_make(&vb, f->view, f->proj);
  for (int32_t i = 0; i < f->s->ninst && f->status == ZS_OK; i++) {
    double centre[3];
    for (int k = 0; k < 3; k++) centre[k] = 0.5 * (f->s->inst[i].lo[k] + f->s->inst[i].hi[k]);
    f->st->frustum_tests++;
    zs_device_cpu_work(f->dev, ZS_CPU_FRUSTUM_TEST, 1);
    if (zs_view_box_contains(&vb, centre)) cull_draw_instance(f, i);
  }
}

const cull_ops cull_vfc_box = {.name = "vfc-box", .frame = draw_centres_inside};
