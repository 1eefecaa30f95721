/* The trace of the row scan (raster.h, "trace"): the scan's own
 * integers, and the same values in the lecture's real units.
 *
 * In pixel-centre units (column c has centre x = c) the DDA of an edge
 * holds x = ceil(u) with u = num / D the exact edge position, and
 * rem = x D - num, so u = x - rem / D; one row down adds
 * (X1 - X0) / (Y1 - Y0) to u.  Depth: the plane is in units of
 * 2^-(32 + zshift) of the window depth. */
#include <math.h>
#include <stdlib.h>

#include "raster/edge_dda.h"
#include "raster/scan.h"

static double depth_real(int64_t z, int zshift) { return ldexp((double)z, -(32 + zshift)); }

static double edge_dx(const zs_edge *e) {
  return ((double)e->X1 - e->X0) / ((double)e->Y1 - e->Y0);
}

void zs_trace_pair_of(const zs_active *a, const zs_poly *p, int32_t y, zs_trace_pair *out) {
  out->id = p->id;
  out->dy = p->row1 - y;
  out->xl = a->l.x;
  out->reml = a->l.rem;
  out->dl = a->l.d;
  out->xr = a->r.x;
  out->remr = a->r.rem;
  out->dr = a->r.d;
  out->xl_real = (double)a->l.x - (double)a->l.rem / (double)a->l.d;
  out->xr_real = (double)a->r.x - (double)a->r.rem / (double)a->r.d;
  /* q + rs / d is the step 256 (X1 - X0) / D = (X1 - X0) / (Y1 - Y0) */
  out->dxl = (double)a->l.q + (double)a->l.rs / (double)a->l.d;
  out->dxr = (double)a->r.q + (double)a->r.rs / (double)a->r.d;
  out->dxl_num = (int64_t)a->l.q * a->l.d + a->l.rs;
  out->dxr_num = (int64_t)a->r.q * a->r.d + a->r.rs;
  out->dyl = a->l.last - y;
  out->dyr = a->r.last - y;
  out->zl = zs_plane_at(a->zrow, a->dzdx, a->l.x); /* the lecture's zl, at xl */
  out->zshift = p->zshift;
  out->zl_real = depth_real(out->zl, p->zshift);
  out->dzx = depth_real(p->dzdx, p->zshift);
  out->dzy = depth_real(p->dzdy, p->zshift);
  out->left = a->left;
  out->right = a->right;
}

void zs_trace_tables(const zs_batch *b, const zs_trace_observer *obs) {
  if (!obs->tables) return;
  zs_trace_poly *tp = malloc((size_t)(b->npolys > 0 ? b->npolys : 1) * sizeof *tp);
  zs_trace_edge *te = malloc((size_t)(b->nedges > 0 ? b->nedges : 1) * sizeof *te);
  if (!tp || !te) {
    free(tp);
    free(te);
    return;
  }
  for (int32_t i = 0; i < b->npolys; i++) {
    const zs_poly *p = &b->polys[i];
    tp[i] = (zs_trace_poly){p->id,     p->rgb,    p->row0,     p->row1,  p->ox, p->oy,
                            p->zshift, p->zc,     p->dzdx,     p->dzdy,
                            depth_real(p->zc, p->zshift), depth_real(p->dzdx, p->zshift),
                            depth_real(p->dzdy, p->zshift), p->edge0, p->nleft, p->nright};
    for (int32_t k = 0; k < p->nleft + p->nright; k++) {
      const zs_edge *e = &b->edges[p->edge0 + k];
      zs_edge_dda top;
      const int32_t row0 = zs_first_row(e->Y0), row1 = zs_last_row(e->Y1);
      zs_edge_dda_start(&top, e, row0);
      te[p->edge0 + k] = (zs_trace_edge){
          p->id, k < p->nleft ? 0 : 1, row0, row1, e->X0, e->Y0, e->X1, e->Y1,
          (double)top.x - (double)top.rem / (double)top.d, edge_dx(e)};
    }
  }
  obs->tables(obs->user, tp, b->npolys, te, b->nedges);
  free(tp);
  free(te);
}
