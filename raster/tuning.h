/* zscan raster — every performance threshold of the device, in one place.
 *
 * None of these changes a pixel, a counter or the modelled clock: each
 * only picks between ways of computing the same bytes (tests/test_raster.c
 * renders either side of the limits).  Each line says why, and the bench
 * command that re-measures it; the figures are in docs/RESULTS.md. */
#ifndef ZS_RASTER_TUNING_H
#define ZS_RASTER_TUNING_H

enum {
  /* Threads a device may have, and bands of rows a traversal is cut
   * into: the fixed sizes of the per-thread and per-band records. */
  ZS_MAX_THREADS = 64,
  ZS_MAX_BANDS = 64,

  /* Drawing at once on threads: a draw from this many faces is set up in
   * parts over the threads; below, handing the work over costs more than
   * it saves.  zscan bench raster --case 'builtin:default,level=42'
   * --threads 2 */
  ZS_PARALLEL_SETUP_FACES = 4096,
  /* Deferred, draws below this many faces are queued (the queue is shared
   * out by faces); a queued draw is set up whole by one thread, so a
   * larger one is drawn at once in parts.  Same command. */
  ZS_DEFER_MAX_FACES = 262144,
  /* Below this many polygons a batch is traversed on one thread: waking
   * the threads costs more (a teapot's 688 faces).  zscan render
   * builtin:teapots --cull vfc --repeat 11, --threads 2 against 1 */
  ZS_BANDED_MIN_POLYS = 1024,
  /* Bands a thread for a banded traversal, taken in turn (the rows of a
   * picture do not hold equal work), and the fewest rows a band.  zscan
   * bench raster --threads 2 --speedup */
  ZS_BANDS_PER_THREAD = 4,
  ZS_BAND_MIN_ROWS = 16,

  /* Deferred flush: batches a thread for the chunks in flight (with one,
   * a thread waits on the slowest band before its next set-up; more gain
   * nothing), polls before an idle task sleeps, full chunks and quarter
   * chunks a thread (the last small, so no thread waits long on the
   * last), and the chunks a thread when only setting up (scanline mode).
   * zscan bench raster --case builtin:plant --threads 2 --speedup, and
   * with --algo scanline */
  ZS_DEFER_SLOTS_PER_THREAD = 2,
  ZS_FLUSH_SPINS = 1 << 14,
  ZS_DEFER_FULL_CHUNKS_PER_THREAD = 15,
  ZS_DEFER_SMALL_CHUNKS_PER_THREAD = 4,
  ZS_SETUP_CHUNKS_PER_THREAD = 16,

  /* The pool's polls before a worker sleeps: longer than most gaps between
   * a frame's jobs.  zscan bench raster --threads 2 --speedup */
  ZS_POOL_SPINS = 1 << 14,

  /* The face stage shades flat faces in runs of this many (the levels of
   * a run at once, eight a step with AVX-512).  zscan bench raster --case
   * builtin:teapots */
  ZS_FLAT_RUN = 64,

  /* Set-up asks for the batch's lines this many polygons and edges ahead
   * of its writes, with threads (PREFETCHW).  zscan bench raster --case
   * builtin:plant --threads 2 --speedup */
  ZS_SETUP_PREFETCH_POLYS = 16,
  ZS_SETUP_PREFETCH_EDGES = 64,
  /* A polygon of fewer rows than this is not tested for spans all inside
   * (the test costs more than it saves).  zscan bench raster --case
   * "triangles 4x4" */
  ZS_INNER_MIN_ROWS = 3,

  /* The traversals ask for the table's polygon records this many ahead,
   * and for the edges of the one this many ahead (its record has arrived
   * by then).  zscan bench raster --case "random 10x10 back to front" */
  ZS_TABLE_PREFETCH_POLYS = 16,
  ZS_TABLE_PREFETCH_EDGES = 8,

  /* The shortest span the SSE2 and AVX2 fills take (below, masked or
   * overlapping stores cost more than the loop), and the AVX-512 fill's
   * (its last step masked at no cost; not shorter, where a masked load
   * waits on the masked store of the span before).  zscan bench raster
   * --case "triangles 25x25" --callgrind; --case builtin:plant, --case
   * "triangles 10x10", --case "random 25x25 back to front" */
  ZS_SIMD_MIN_SPAN = 16,
  ZS_AVX512_MIN_SPAN = 10,
  /* A soup's polygons of at most this many rows (and edges) are painted
   * by their edge functions with AVX-512, where the DDA's starts cost
   * more.  zscan bench raster --algo zbuffer --case "random 4x4 back to
   * front" and --case "random 10x10 back to front" */
  ZS_SMALL_MAX_ROWS = 8,
  ZS_SMALL_MAX_EDGES = 6,
};

/* Polygon order or the row scan, per batch (polyorder.c): a batch is a
 * soup when more than half its polygons begin over two rows from the one
 * before; a mesh laid out in order over a quarter of the frame or more is
 * scanned by rows.  zscan bench raster (the tilings, the random triangles,
 * the scenes and small models) */
enum { ZS_SOUP_ROW_JUMP = 2, ZS_SCAN_FRAME_SHARE = 4 };

#endif
