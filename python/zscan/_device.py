"""zscan.Device: the device itself (zs_device_*), for culling experiments
in a notebook: draws, occlusion queries answered after the modelled
latency, the modelled clock and the counters."""

import ctypes

from . import _lib
from ._mesh import Mesh, _numpy


def _d3(name, v):
    from . import _vec3

    return (ctypes.c_double * 3)(*_vec3(name, v))


def _matrix(name, transform):
    if transform is None:
        return None
    np = _numpy()
    t = np.asarray(transform, dtype=np.float64)
    if t.shape != (4, 4):
        raise ValueError("%s: expected a 4 x 4 matrix, got shape %s" % (name, t.shape))
    bad = ~np.isfinite(t)
    if bad.any():
        i, j = np.argwhere(bad)[0]
        raise ValueError("%s[%d, %d]: %r is not a finite number" % (name, i, j, t[i, j]))
    return (ctypes.c_double * 16)(*t.reshape(-1).tolist())


# The background zscan.render draws (and the zscan command), 0xRRGGBB.
RENDER_BACKGROUND = 0x1E2228


class Device(_lib.Handle):
    """A zscan device of size (width, height): algo 'zbuffer' (queries,
    depth and id buffers) or 'scanline'; shade as render() takes it
    (default 'auto', as render's); background 0xRRGGBB (default
    zscan.RENDER_BACKGROUND, render's, so that the two draw the same bytes);
    clock a dict of zs_clock_params fields in nanoseconds (the rest the
    documented defaults), e.g. {"query_latency_ns": 50000}; normals=True
    gives finish()'s image .normals, the eye-space unit normal of each
    pixel as float32 (height, width, 3), 0, 0, 0 where no face shaded from
    attributes is (zs_device_set_normals).

        dev = zscan.Device((320, 240), clock={"query_latency_ns": 20000})
        dev.camera(eye=(0, 0, 8), target=(0, 0, 0))
        dev.clear()
        dev.draw(wall)                      # a zscan.Mesh
        q = dev.query_box((-1, -1, -5), (1, 1, -3))
        dev.query_ready(q), dev.query_result(q)   # samples, after the latency
        image = dev.finish()
        dev.stats, dev.clock, dev.frame_ps

    A mesh drawn is kept alive until finish (the device reads its arrays
    then); its faces are drawn as given (convex, 3 .. 64 corners), not
    split as a scene splits them."""

    _DESTROY = "zs_device_destroy"

    def __init__(self, size=(1024, 768), algo="zbuffer", shade="auto", threads=1,
                 cull_back=False, background=None, clock=None, normals=False):
        from . import _choice, _int, _raise

        lib = _lib.load()
        self._lib = lib
        self._ptr = None
        cfg = _lib.zs_device_config()
        try:
            w, h = size
        except (TypeError, ValueError):
            raise TypeError("size: expected (width, height), got %r" % (size,)) from None
        cfg.width, cfg.height = _int("size", w), _int("size", h)
        if not (1 <= cfg.width <= _lib.ZS_MAX_IMAGE_SIDE and 1 <= cfg.height <= _lib.ZS_MAX_IMAGE_SIDE):
            raise ValueError("size: %dx%d: each side must be 1 to %d"
                             % (cfg.width, cfg.height, _lib.ZS_MAX_IMAGE_SIDE))
        cfg.algo = _choice("algo", algo, _lib.ALGOS[:2])
        cfg.shade = _choice("shade", shade, _lib.SHADES)
        self.shade = shade
        cfg.threads = _int("threads", threads)
        cfg.cull_back = 1 if cull_back else 0
        if not isinstance(normals, bool):
            raise TypeError("normals: expected True or False, got %r" % (normals,))
        cfg.background = (RENDER_BACKGROUND if background is None
                          else _int("background", background) & 0xFFFFFF)
        handle = ctypes.c_void_p()
        err = _lib.zs_error()
        if lib.zs_device_create(ctypes.byref(cfg), ctypes.byref(handle), ctypes.byref(err)):
            _raise(err)
        self._ptr = handle
        self.width, self.height = cfg.width, cfg.height
        self._drawn = []
        self._normals = normals
        if normals:
            self._check(lib.zs_device_set_normals(handle, 1, ctypes.byref(err)), err)
        if clock is not None:
            self.set_clock(clock)

    def _handle(self):
        if self._ptr is None:
            raise ValueError("zscan.Device: used after close()")
        return self._ptr

    def _check(self, status, err):
        from . import _raise

        if status:
            _raise(err)

    def set_clock(self, params):
        """The modelled clock's parameters: a dict of zs_clock_params
        fields (nanoseconds); those left out keep the documented defaults."""
        p = _lib.zs_clock_params()
        self._lib.zs_clock_params_default(ctypes.byref(p))
        names = [n for n, _ in _lib.zs_clock_params._fields_]
        for k, v in dict(params).items():
            if k not in names:
                raise ValueError("clock: unknown parameter %r (%s)" % (k, ", ".join(names)))
            setattr(p, k, float(v))
        err = _lib.zs_error()
        self._check(self._lib.zs_device_set_clock(self._handle(), ctypes.byref(p),
                                                  ctypes.byref(err)), err)

    def camera(self, eye, target=(0.0, 0.0, 0.0), up=(0.0, 1.0, 0.0), fovy=45.0, near=0.1,
               far=1000.0):
        """The camera for the following draws: zs_mat_look_at and
        zs_mat_perspective with the device's aspect ratio."""
        from . import Error, _number

        view, proj = (ctypes.c_double * 16)(), (ctypes.c_double * 16)()
        if not self._lib.zs_mat_look_at(view, _d3("eye", eye), _d3("target", target),
                                        _d3("up", up)):
            raise Error("camera: eye and target coincide, or up is along the view", 1)
        fovy, near, far = _number("fovy", fovy), _number("near", near), _number("far", far)
        if not (0 < fovy < 180 and 0 < near < far):
            raise Error("camera: fovy %g, near %g, far %g: 0 < fovy < 180, 0 < near < far"
                        % (fovy, near, far), 1)
        self._lib.zs_mat_perspective(proj, fovy, self.width / self.height, near, far)
        self._lib.zs_device_set_camera(self._handle(), view, proj)

    def lights(self, lights):
        """The lights of the lit shadings from the next draw on (a list of
        zscan.Light; [] for the headlight)."""
        from . import _light_list

        lights = list(lights)
        if lights:
            lights = _light_list("lights", lights)
        arr = (_lib.zs_light * max(1, len(lights)))(*[l._c for l in lights])
        err = _lib.zs_error()
        self._check(self._lib.zs_device_set_lights(self._handle(), arr, len(lights),
                                                   ctypes.byref(err)), err)

    def clear(self):
        """Starts a frame: clears colour, depth, ids and the counters."""
        self._lib.zs_device_clear(self._handle())
        self._drawn = []

    def draw(self, mesh, transform=None, id_base=0, color=None):
        """Draws mesh (a zscan.Mesh) placed by transform; its faces get ids
        id_base + f and colour color (0xRRGGBB; None: the mesh's own)."""
        from . import _int

        if not isinstance(mesh, Mesh):
            raise TypeError("mesh: expected a zscan.Mesh, got %r" % type(mesh).__name__)
        rgb = _lib.ZS_RGB_MESH if color is None else _int("color", color) & 0xFFFFFF
        model = _matrix("transform", transform)
        c = mesh._c()
        err = _lib.zs_error()
        self._check(self._lib.zs_device_draw(self._handle(), ctypes.byref(c), model,
                                             _int("id_base", id_base), rgb, ctypes.byref(err)),
                    err)
        self._drawn.append((mesh, c, model))

    def query_begin(self):
        """Starts an occlusion query; returns its number."""
        q = ctypes.c_uint32()
        err = _lib.zs_error()
        self._check(self._lib.zs_device_query_begin(self._handle(), ctypes.byref(q),
                                                    ctypes.byref(err)), err)
        return q.value

    def query_end(self):
        err = _lib.zs_error()
        self._check(self._lib.zs_device_query_end(self._handle(), ctypes.byref(err)), err)

    def query_box(self, lo, hi):
        """A query of the world box lo..hi alone (begin, box, end): its
        number.  Between query_begin and query_end, add_query_box adds a
        box to the open query instead."""
        q = self.query_begin()
        self.add_query_box(lo, hi)
        self.query_end()
        return q

    def add_query_box(self, lo, hi):
        err = _lib.zs_error()
        self._check(self._lib.zs_device_query_box(self._handle(), _d3("lo", lo), _d3("hi", hi),
                                                  ctypes.byref(err)), err)

    def query_ready(self, q):
        """Whether q's result is there at the modelled CPU time now."""
        return bool(self._lib.zs_device_query_ready(self._handle(), self._issued(q)))

    def query_result(self, q):
        """q's samples (the modelled CPU waits for them when not ready)."""
        return self._lib.zs_device_query_result(self._handle(), self._issued(q))

    def _issued(self, q):
        from . import _int

        q = _int("q", q)
        n = self._lib.zs_device_queries(self._handle())
        if not 0 <= q < n:
            raise ValueError("q: query %d was not begun in this frame (%s)"
                             % (q, "none was" if n == 0 else "0 .. %d were" % (n - 1)))
        return q

    def cpu_work(self, kind, count=1):
        """Reports the caller's own work to the modelled CPU clock: 'node',
        'frustum_test' or 'cost_eval', count times."""
        from . import _choice, _int

        self._lib.zs_device_cpu_work(self._handle(), _choice("kind", kind, _lib.CPU_WORK),
                                     _int("count", count))

    def finish(self):
        """Ends the frame: the image (zs_device_finish's rows)."""
        from . import Image, _raise

        np = _numpy()
        w = self.width
        rows = np.zeros((self.height, w, 3), np.uint8)
        normals = np.zeros((self.height, w, 3), np.float32) if self._normals else None

        def sink(_user, row):
            r = row.contents
            px = np.ctypeslib.as_array(r.rgb, shape=(w,))
            for c, shift in enumerate((16, 8, 0)):
                rows[r.y, :, c] = (px >> shift) & 0xFF
            if normals is not None and r.normal:
                normals[r.y] = np.ctypeslib.as_array(r.normal, shape=(w, 3))

        cb = _lib.zs_row_sink(sink)
        err = _lib.zs_error()
        status = self._lib.zs_device_finish(self._handle(), cb, None, ctypes.byref(err))
        self._drawn = []
        if status:
            _raise(err)
        image = Image(w, self.height, rows.tobytes())
        image.shade = self.shade
        image.normals = normals
        return image

    def _buffer(self, fn):
        p = fn(self._handle())
        if not p:
            raise ValueError("zscan.Device: the scanline mode keeps no full-frame buffers")
        np = _numpy()
        return np.ctypeslib.as_array(p, shape=(self.height * self.width,)).reshape(
            self.height, self.width).copy()

    @property
    def depth_buffer(self):
        """The depth buffer (zbuffer mode) as uint32 (height, width), 2^32 - 1 far."""
        return self._buffer(self._lib.zs_device_depth_buffer)

    @property
    def id_buffer(self):
        """The id buffer (zbuffer mode) as uint32 (height, width), 2^32 - 1 for none."""
        return self._buffer(self._lib.zs_device_id_buffer)

    @property
    def stats(self):
        """The frame's counters (zs_raster_stats) as a dict."""
        s = self._lib.zs_device_stats(self._handle()).contents
        return {n: getattr(s, n) for n, _ in _lib.zs_raster_stats._fields_}

    @property
    def clock(self):
        """The modelled clock's counters (zs_clock_stats) as a dict, times
        in integer picoseconds."""
        s = self._lib.zs_device_clock(self._handle()).contents
        return {n: getattr(s, n) for n, _ in _lib.zs_clock_stats._fields_}

    @property
    def frame_ps(self):
        """The frame's modelled time so far, integer picoseconds."""
        return self._lib.zs_device_frame_ps(self._handle())
