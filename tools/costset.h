/* zscan tools — the cost model's parameters on the command line.
 *
 *   --cost-set KEY=VALUE    set one parameter of chc-prob's (and auto's,
 *                           chcpp-prob's) cost model, cull/cull.h:
 *     w1, w2                P(a visible node stays visible), P(a hidden one
 *                           stays hidden), 0 .. 1 (auto learns its own)
 *     ttri_ns, tcall_ns,    Ttri, Tcall, T and Tq of formulas (6) and (10),
 *     t_ns, tq_ns           in ns, 0 .. 1e12 (by default the device clock's)
 *     rho                   pixels per unit of the box area S, 0 .. 1e6
 *     learn                 0 (the default): w1 and w2 as given; else
 *                           learnt from the method's own query outcomes,
 *                           starting from w1 and w2 as if this many
 *                           outcomes had borne them out, 0 .. 1e6
 * An unknown key or a value out of its range is an error naming the key. */
#ifndef ZS_TOOLS_COSTSET_H
#define ZS_TOOLS_COSTSET_H

#include "cull/cull.h"

zs_status zs_cost_set(const char *assignment, zs_cost_params *p, zs_error *err);

/* The options of the device clock, the cost model and the queries that
 * render and walk share: --clock FILE.json, --clock-set K=V, --cost-set
 * K=V and --bounds parts|box at argv[*i] (advancing *i past the value).
 * 1: taken; 0: not one of them; -1: an error, in err. */
int zs_cull_option(int argc, char **argv, int *i, zs_clock_params *clock, zs_cost_params *cost,
                   zs_query_bounds *bounds, zs_error *err);

#endif
