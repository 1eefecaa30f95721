/* The tuning outcomes bench tradeoff reports after its walks: comparisons
 * of methods on small walks that hold for the defaults as they are tuned
 * now, and that a change of a default or of the clock may turn.  Each is
 * printed with its figures and whether it holds; none is asserted (the
 * tests check what must hold whatever the tuning: exact images). */
#include "tools/bench_tuning.h"

#include <string.h>

#include "lib/input.h"
#include "zscan/walk.h"

/* A method's sums over a walk. */
typedef struct tuning_run {
  const char *method;
  double modelled_ms;
  uint64_t queries, objects;
} tuning_run;

/* frames frames of scene's walk (every step-th frame of its path) at
 * w x h, once per method, each on a fresh copy of the scene. */
static zs_status walk_each(const char *scene, int frames, int step, int w, int h, tuning_run *runs,
                           int n, zs_error *err) {
  for (int k = 0; k < n; k++) {
    zs_scene s;
    if (zs_input_load_scene(scene, &s, err)) return err->code;
    zs_walk_opts o = {runs[k].method, w, h, step};
    zs_walk *wk = NULL;
    zs_status st = zs_walk_create(&s, &o, &wk, err);
    for (int f = 0; f < frames && st == ZS_OK; f++) {
      zs_walk_frame fr;
      if ((st = zs_walk_next(wk, &fr, err))) break;
      runs[k].modelled_ms += fr.modelled_ms;
      runs[k].queries += fr.queries;
      runs[k].objects += fr.objects_drawn;
    }
    zs_walk_destroy(wk);
    zs_scene_free(&s);
    if (st) return st;
  }
  return ZS_OK;
}

static const char *holds(int yes) { return yes ? "holds" : "does not hold"; }

/* On the plant: CHC++ with all its features against CHC and each
 * ablation, in modelled time; chcpp-prob's queries against its parents'. */
static zs_status plant(FILE *f, zs_error *err) {
  static const char scene[] = "builtin:plant,detail=0.25";
  tuning_run r[] = {{"chcpp", 0, 0, 0},         {"chc", 0, 0, 0},
                    {"chcpp-nobatch", 0, 0, 0}, {"chcpp-nodefer", 0, 0, 0},
                    {"chcpp-nomulti", 0, 0, 0}, {"chc-prob", 0, 0, 0},
                    {"chcpp-prob", 0, 0, 0}};
  enum { N = sizeof r / sizeof r[0] };
  if (walk_each(scene, 12, 8, 160, 120, r, N, err)) return err->code;
  fprintf(f, "%s, 12 frames, every 8th, 160x120:\n", scene);
  int fastest = 1;
  for (int k = 1; k < 5; k++) fastest &= r[0].modelled_ms < r[k].modelled_ms;
  fprintf(f, "  chcpp is faster than chc and than each ablation (modelled ms): %s\n", holds(fastest));
  for (int k = 0; k < 5; k++) fprintf(f, "    %-14s %9.3f\n", r[k].method, r[k].modelled_ms);
  const int fewest = r[6].queries > 0 && r[6].queries < r[5].queries && r[6].queries < r[0].queries;
  fprintf(f, "  chcpp-prob asks fewer queries than chc-prob and chcpp: %s\n", holds(fewest));
  fprintf(f, "    %-14s %9llu\n    %-14s %9llu\n    %-14s %9llu\n", r[6].method,
          (unsigned long long)r[6].queries, r[5].method, (unsigned long long)r[5].queries,
          r[0].method, (unsigned long long)r[0].queries);
  return ZS_OK;
}

/* On the cubes: the oracles against view-frustum culling.  The oracle is
 * the floor of time as well as of objects: it draws only what owns a
 * pixel, front to back as the traversals do (drawn in the scene's order
 * it would write nearer cubes over farther ones and cost more than vfc
 * on this walk). */
static zs_status cubes(FILE *f, zs_error *err) {
  static const char scene[] = "builtin:cubes";
  tuning_run r[] = {{"vfc", 0, 0, 0}, {"ideal", 0, 0, 0}, {"ideal-box", 0, 0, 0}};
  if (walk_each(scene, 50, 1, 1024, 768, r, 3, err)) return err->code;
  fprintf(f, "%s, 50 frames, 1024x768:\n", scene);
  fprintf(f, "  ideal draws fewer objects than vfc, and ideal and ideal-box take less modelled "
             "time: %s\n",
          holds(r[1].objects < r[0].objects && r[1].modelled_ms < r[0].modelled_ms &&
                r[2].modelled_ms < r[0].modelled_ms));
  for (int k = 0; k < 3; k++)
    fprintf(f, "    %-14s %9llu objects %9.3f ms\n", r[k].method, (unsigned long long)r[k].objects,
            r[k].modelled_ms);
  return ZS_OK;
}

zs_status zs_bench_tuning_report(FILE *f, zs_error *err) {
  fprintf(f, "tuning outcomes: what the defaults give now, not guarantees\n");
  return plant(f, err) || cubes(f, err) ? err->code : ZS_OK;
}
