/* `zscan bench arrays [--quick] [--size WxH] [--md FILE]`
 *
 * What a mesh given as arrays costs (zs_scene_add_object, as the Python
 * binding's zscan.Mesh calls it) beside the same mesh read from its OBJ
 * file (zs_scene_load): a height field of n x n quads as 2 n^2 triangles
 * with a normal, a colour and a texture coordinate at every vertex, the
 * OBJ written with every number's shortest round trip so both are one
 * mesh.  For each size: the time to load the file, to build the scene
 * from the arrays, and to render each scene (Phong, one thread, the two
 * in turn), each the median of its repeats, and whether both images are
 * the same bytes (they must be).  The figures: docs/RESULTS.md, from
 * `zscan bench arrays`. */
#include "tools/bench_arrays.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tools/bench_report.h"
#include "tools/cli.h"
#include "util/os.h"
#include "zscan/zscan.h"

static const char usage[] =
    "usage: zscan bench arrays [--quick] [--size WxH] [--md FILE]\n"
    "  a mesh built from arrays (zs_scene_add_object) beside the same mesh loaded\n"
    "  from its OBJ file: load, build and render times (median of 11, wall time)\n"
    "  of a height field with normals, colours and texture coordinates.\n"
    "  --quick      the smallest mesh only, 3 times: a check that it runs\n"
    "  --size WxH   the image size (default 640x480)\n"
    "  --md FILE    the table in Markdown\n";

static const int grids[] = {32, 128, 256};
enum { NGRIDS = sizeof grids / sizeof grids[0], MAX_REPEAT = 11 };

/* how many times each is measured (--quick: 3) */
static int repeat = MAX_REPEAT;

/* the rows measured (--quick: 1) */
static int ngrids = NGRIDS;

typedef struct arrays_row {
  int triangles;
  double load_ms, build_ms, render_file_ms, render_arrays_ms;
  int same;
} arrays_row;

/* The height field's arrays: (n + 1)^2 vertices, n^2 quads split in two. */
typedef struct field {
  double *pos;
  float *normal, *uv;
  uint8_t *color;
  int32_t *start, *vert;
  int nverts, nfaces;
} field;

static void field_free(field *f) {
  free(f->pos), free(f->normal), free(f->uv), free(f->color), free(f->start), free(f->vert);
}

static int field_make(field *f, int n) {
  memset(f, 0, sizeof *f);
  f->nverts = (n + 1) * (n + 1);
  f->nfaces = 2 * n * n;
  f->pos = malloc(3 * (size_t)f->nverts * sizeof *f->pos);
  f->normal = malloc(3 * (size_t)f->nverts * sizeof *f->normal);
  f->uv = malloc(2 * (size_t)f->nverts * sizeof *f->uv);
  f->color = malloc(4 * (size_t)f->nverts);
  f->start = malloc(((size_t)f->nfaces + 1) * sizeof *f->start);
  f->vert = malloc(3 * (size_t)f->nfaces * sizeof *f->vert);
  if (!f->pos || !f->normal || !f->uv || !f->color || !f->start || !f->vert) return 0;
  for (int j = 0, v = 0; j <= n; j++)
    for (int i = 0; i <= n; i++, v++) {
      /* a paraboloid cap: z = 0.3 (1 - x^2)(1 - y^2), its normal by hand */
      const double x = -1.0 + 2.0 * i / n, y = -1.0 + 2.0 * j / n;
      const double gx = -0.6 * x * (1 - y * y), gy = -0.6 * y * (1 - x * x);
      f->pos[3 * v] = x, f->pos[3 * v + 1] = y, f->pos[3 * v + 2] = 0.3 * (1 - x * x) * (1 - y * y);
      f->normal[3 * v] = (float)-gx, f->normal[3 * v + 1] = (float)-gy, f->normal[3 * v + 2] = 1.0f;
      f->uv[2 * v] = (float)i / (float)n, f->uv[2 * v + 1] = (float)j / (float)n;
      f->color[4 * v] = (uint8_t)(255 * i / n), f->color[4 * v + 1] = (uint8_t)(255 * j / n);
      f->color[4 * v + 2] = 64, f->color[4 * v + 3] = 255;
    }
  for (int j = 0, k = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      const int32_t a = j * (n + 1) + i, q[2][3] = {{a, a + 1, a + n + 2}, {a, a + n + 2, a + n + 1}};
      for (int t = 0; t < 2; t++, k++) {
        f->start[k] = 3 * k;
        memcpy(f->vert + 3 * k, q[t], sizeof q[t]);
      }
    }
  f->start[f->nfaces] = 3 * f->nfaces;
  return 1;
}

/* The OBJ of the field: %.9g gives a float back exactly, %.17g a double. */
static int field_write_obj(const field *f, const char *path) {
  FILE *o = fopen(path, "w");
  if (!o) return 0;
  for (int v = 0; v < f->nverts; v++)
    fprintf(o, "v %.17g %.17g %.17g %.17g %.17g %.17g\n", f->pos[3 * v], f->pos[3 * v + 1],
            f->pos[3 * v + 2], f->color[4 * v] / 255.0, f->color[4 * v + 1] / 255.0,
            f->color[4 * v + 2] / 255.0);
  for (int v = 0; v < f->nverts; v++)
    fprintf(o, "vt %.9g %.9g\nvn %.9g %.9g %.9g\n", f->uv[2 * v], f->uv[2 * v + 1],
            f->normal[3 * v], f->normal[3 * v + 1], f->normal[3 * v + 2]);
  for (int k = 0; k < f->nfaces; k++) {
    fputc('f', o);
    for (int c = 0; c < 3; c++) fprintf(o, " %d/%d/%d", f->vert[3 * k + c] + 1,
                                        f->vert[3 * k + c] + 1, f->vert[3 * k + c] + 1);
    fputc('\n', o);
  }
  return fclose(o) == 0;
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *t) {
  qsort(t, (size_t)repeat, sizeof *t, cmp_double);
  return t[repeat / 2];
}

/* Renders the two scenes `repeat` times each, in turn (so that both see the
 * same machine): the median times, and whether the last images match. */
static zs_status time_renders(const zs_scene *const scenes[2], int w, int h, double ms[2],
                              int *same, zs_error *err) {
  zs_render_opts o = {.width = w, .height = h, .shade = ZS_SHADE_PHONG, .threads = 1,
                      .eye = {1.2, -1.6, 1.8}, .has_eye = 1};
  double t[2][MAX_REPEAT];
  uint64_t hash[2] = {0, 0};
  for (int r = 0; r < repeat; r++)
    for (int k = 0; k < 2; k++) {
      zs_image im = {0};
      const double t0 = zs_os_monotonic_ms();
      if (zs_render(scenes[k], &o, &im, NULL, NULL, err)) return err->code;
      t[k][r] = zs_os_monotonic_ms() - t0;
      hash[k] = zs_image_hash(&im);
      zs_image_free(&im);
    }
  ms[0] = median(t[0]);
  ms[1] = median(t[1]);
  *same = hash[0] == hash[1];
  return ZS_OK;
}

static zs_status measure(int n, int w, int h, const char *dir, arrays_row *row, zs_error *err) {
  field f;
  char path[4200];
  snprintf(path, sizeof path, "%s/field.obj", dir);
  if (!field_make(&f, n)) {
    field_free(&f);
    return zs_error_set(err, ZS_ERR_NOMEM, "bench arrays: out of memory");
  }
  if (!field_write_obj(&f, path)) {
    field_free(&f);
    return zs_error_set(err, ZS_ERR_IO, "%s: cannot write: %s", path, strerror(errno));
  }
  zs_mesh mesh = {.pos = f.pos, .nverts = f.nverts, .face_start = f.start, .face_vert = f.vert,
                  .nfaces = f.nfaces, .nattrs = f.nverts, .normal = f.normal, .color = f.color,
                  .uv = f.uv};
  double tl[MAX_REPEAT], tb[MAX_REPEAT];
  zs_scene *file = NULL, *built = NULL;
  zs_status st = ZS_OK;
  for (int r = 0; r < repeat && !st; r++) {
    zs_scene_destroy(file), zs_scene_destroy(built);
    file = built = NULL;
    double t0 = zs_os_monotonic_ms();
    if ((st = zs_scene_load(path, NULL, &file, err))) break;
    tl[r] = zs_os_monotonic_ms() - t0;
    t0 = zs_os_monotonic_ms();
    if ((st = zs_scene_create(&built, err)) || (st = zs_scene_add_object(built, &mesh, NULL, NULL, err)))
      break;
    tb[r] = zs_os_monotonic_ms() - t0;
  }
  double render_ms[2] = {0, 0};
  const zs_scene *const both[2] = {file, built};
  if (!st) st = time_renders(both, w, h, render_ms, &row->same, err);
  if (!st) {
    row->triangles = f.nfaces;
    row->load_ms = median(tl);
    row->build_ms = median(tb);
    row->render_file_ms = render_ms[0];
    row->render_arrays_ms = render_ms[1];
  }
  zs_scene_destroy(file), zs_scene_destroy(built);
  remove(path);
  field_free(&f);
  return st;
}

static void write_rows(FILE *f, const void *rows, int md) {
  const arrays_row *x = rows;
  if (md)
    fprintf(f, "| triangles | load the OBJ | build from arrays | render, from the file | render, "
               "from arrays | the same bytes |\n|---|---|---|---|---|---|\n");
  else
    fprintf(f, "%9s %10s %10s %14s %15s %5s\n", "triangles", "load_ms", "build_ms",
            "render_file_ms", "render_array_ms", "same");
  for (int i = 0; i < ngrids; i++) {
    if (md)
      fprintf(f, "| %d | %.1f ms | %.1f ms | %.1f ms | %.1f ms | %s |\n", x[i].triangles,
              x[i].load_ms, x[i].build_ms, x[i].render_file_ms, x[i].render_arrays_ms,
              x[i].same ? "yes" : "no");
    else
      fprintf(f, "%9d %10.1f %10.1f %14.1f %15.1f %5s\n", x[i].triangles, x[i].load_ms,
              x[i].build_ms, x[i].render_file_ms, x[i].render_arrays_ms, x[i].same ? "yes" : "no");
  }
}

int zs_cmd_bench_arrays(int argc, char **argv) {
  if (zs_cli_help(argc, argv, usage, NULL)) return 0;
  zs_error err;
  zs_error_clear(&err);
  int w = 640, h = 480, parsing = 1;
  const char *md = NULL;
  if (zs_bench_take_flag(&argc, argv, "--quick")) repeat = 3, ngrids = 1;
  zs_status st = zs_bench_size_md_args(argc, argv, "arrays", &w, &h, &md, &err);
  char dir[4096];
  int e = st ? 0 : zs_os_scratch_dir("zscan-arrays", dir, sizeof dir);
  if (e != 0)
    st = zs_error_set(&err, ZS_ERR_IO, "cannot create a scratch folder: %s", strerror(e));
  if (!st) parsing = 0;
  arrays_row x[NGRIDS];
  for (int i = 0; i < ngrids && !st; i++) st = measure(grids[i], w, h, dir, &x[i], &err);
  if (!parsing) zs_os_rmdir(dir);
  if (!st) {
    char title[96];
    snprintf(title, sizeof title, "a mesh from arrays and from its OBJ file at %dx%d", w, h);
    st = zs_bench_report(md, title, write_rows, x, &err);
  }
  return st ? zs_cli_fail("zscan bench arrays", &err, parsing) : 0;
}
