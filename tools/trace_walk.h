/* zscan tools — the walk `zscan trace` shows (cmd_trace.c), and the
 * teaching page's WebAssembly module shows (web/teach_module.c): the scene
 * drawn by the scanline z-buffer with the device's trace observer, or by
 * the plain z-buffer one polygon at a time, and the lecture's tables
 * printed as text or as JSON lines, the same bytes from both.
 *
 * Units: rows and columns of the image (row 0 at the top); x values in
 * pixel-centre units (column c has its centre at x = c), shown exactly as
 * fractions where the DDA holds them exactly; depth as window depth in
 * [0, 1], 0 at the near plane, beside the fixed-point integers; with vertex
 * colours, the Gouraud intensities beside them (cmd_trace_gouraud.h).
 *
 * The JSON lines: the tables (or, for the z-buffer, the size and mode),
 * one object per scanline (or per polygon drawn), and last the frame:
 * {"frame": {"image_hash", "polygons_rasterized", "spans", "pixels_tested",
 * "pixels_written"}}, image_hash being the hash `zscan render --shade id
 * --stats json` prints for the same frame. */
#ifndef ZS_TOOLS_TRACE_WALK_H
#define ZS_TOOLS_TRACE_WALK_H

#include <stdint.h>
#include <stdio.h>

#include "scene/scene.h"
#include "tools/cli.h"
#include "tools/cmd_trace_gouraud.h"
#include "tools/viewopts.h"
#include "zscan/trace.h"

typedef struct zs_trace_opts {
  const char *input, *png_dir;   /* (the command's: its input, --png-dir) */
  zs_view_opts view;
  int row0, row1, json, scale, quiet, brief, rows_given;
  const char *html; /* --html FILE: the page */
  int as_array;     /* the JSON lines as the elements of one array (a comma
                     * before each but the first): the pages read them so */
  int zbuffer;      /* --algo zbuffer: the plain z-buffer, a step per polygon */
} zs_trace_opts;

/* The walk being traced: what the observer saw of the row being finished,
 * kept until the sink hands over the row's ids and depths. */
typedef struct zs_tracer {
  const zs_trace_opts *o;
  double proj10, proj11;  /* the projection's depth row, for view-space z */
  int ortho;
  FILE *out;
  zs_trace_pair *pairs;
  zs_trace_span *spans;
  int npairs, nspans, cap;
  int failed;
  /* the step pictures: the frame so far */
  uint32_t *ids, *depth;
  zs_progress progress; /* of the pictures, on stderr */
  int lines;            /* JSON objects written */
  int pictures;
  /* the polygons' outlines: the edge table's edges, picture units */
  double (*outline)[4];
  uint32_t *outline_id;
  int noutline;
  uint32_t max_id; /* the largest polygon id, for the legend */
  /* Gouraud intensities (cmd_trace_gouraud.h), when the input has vertex
   * colours and the view is orthographic: the row's pairs', each pixel's
   * (NAN: none), and for the pictures the frame's so far */
  int shading;
  zs_gouraud gouraud;
  zs_gouraud_pair *gpairs;
  int *has_gpair;
  int gcap;
  double *row_I, *inten;
  uint32_t *frame;      /* the id image so far (id + 1, 0 for none), for its hash */
  zs_error err;
  /* the command's step pictures: called after each row traced (--png-dir) */
  void (*picture)(struct zs_tracer *t, int y);
} zs_tracer;

/* Draws model as o says (o->view: its camera and size, completed) and
 * prints the trace to out; t starts zeroed but for t->picture.  The
 * error of a camera, a device or memory. */
zs_status zs_trace_walk(zs_tracer *t, const zs_trace_opts *o, const zs_scene *model, FILE *out,
                        zs_error *err);

/* Frees what the walk allocated in t. */
void zs_tracer_free(zs_tracer *t);

#endif
