/* Hidden lines as SVG (lib/svg.h). */
#include "lib/svg.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "lib/outfile.h"

zs_status zs_svg_write_lines(zs_out_set *set, const char *path, int width, int height, const zs_line_run *runs,
                             int32_t n, int line_width, uint32_t paper, uint32_t ink,
                             zs_error *err) {
  zs_out out;
  zs_status st = zs_out_open(&out, path, err);
  if (st != ZS_OK) return st;
  FILE *f = out.fp;
  int ok = fprintf(f,
                   "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                   "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
                   "viewBox=\"0 0 %d %d\">\n"
                   "<rect width=\"%d\" height=\"%d\" fill=\"#%06x\"/>\n",
                   width, height, width, height, width, height, (unsigned)(paper & 0xFFFFFFu)) > 0;
  if (ok && n > 0) {
    ok = fprintf(f, "<path fill=\"none\" stroke=\"#%06x\" stroke-width=\"%d\" "
                    "stroke-linecap=\"butt\" d=\"",
                 (unsigned)(ink & 0xFFFFFFu), line_width) > 0;
    for (int32_t i = 0; i < n && ok; i++)
      ok = fprintf(f, "%sM%.3f %.3fL%.3f %.3f", i % 4 ? "" : "\n", runs[i].x0, runs[i].y0,
                   runs[i].x1, runs[i].y1) > 0;
    ok = ok && fputs("\"/>\n", f) >= 0;
  }
  ok = ok && fputs("</svg>\n", f) >= 0;
  if (!ok) {
    st = zs_error_set(err, ZS_ERR_IO, "%s: cannot write: %s", path, strerror(errno));
    zs_out_discard(&out);
    return st;
  }
  return zs_out_finish(&out, set, err);
}
