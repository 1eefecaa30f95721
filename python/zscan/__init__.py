"""zscan: render models and scenes with libzscan, the software scanline
z-buffer renderer, from Python (ctypes; no compiler needed).

    import zscan
    im = zscan.render("model.obj", size=(320, 240), eye=(9, 7, 14))
    im.hash          # 16 hex digits: the image_hash `zscan render --stats` prints
    im.array         # numpy uint8 array, shape (240, 320, 3)
    im.save("out.png")

The library is found from $ZSCAN_LIBRARY, else beside this package, else
the checkout's build/ directory (see README.md).  It is loaded on first use:
importing zscan never fails for want of it.  zscan.__version__ is the
library's own version (zs_version()).
"""

import ctypes
import math
import numbers
import os
import sys

from . import _lib
from ._lib import LibraryError
from ._mesh import Light, Material, Mesh, Texture
from ._device import RENDER_BACKGROUND, Device

__all__ = [
    "Device",
    "DiffResult",
    "Error",
    "Image",
    "LibraryError",
    "Light",
    "Material",
    "Mesh",
    "RENDER_BACKGROUND",
    "Scene",
    "Texture",
    "diff",
    "library_path",
    "load",
    "pixel_changes",
    "pixel_version",
    "read_png",
    "render",
]

ALGOS = _lib.ALGOS
SHADES = _lib.SHADES
STYLES = _lib.STYLES


def __getattr__(name):
    # zscan.__version__ asks the library (PEP 562: loaded on first use)
    if name == "__version__":
        return _lib.load().zs_version().decode("ascii")
    raise AttributeError("module 'zscan' has no attribute %r" % name)


def pixel_version():
    """The library's pixel version (zs_pixel_version): raised whenever any
    output of an unchanged input changes; docs/CHANGES.md lists them."""
    return _lib.load().zs_pixel_version()


def pixel_changes(version):
    """What changed in pixel version `version` against the one before, or
    None for a version this library does not know."""
    s = _lib.load().zs_pixel_changes(_int("version", version))
    return None if s is None else s.decode("utf-8", "replace")


def library_path():
    """The path of the libzscan that this process loaded (loading it)."""
    return _lib.load().zscan_path


class Error(Exception):
    """An error reported by libzscan: str(e) is the library's one-line
    message; e.code is the zs_status number, e.status its name."""

    def __init__(self, message, code=1):
        super().__init__(message)
        self.message = message
        self.code = code
        self.status = (
            _lib.STATUS_NAMES[code] if 0 <= code < len(_lib.STATUS_NAMES) else str(code)
        )


def _raise(err):
    raise Error(err.msg.decode("utf-8", "replace"), err.code)


def _path_arg(path):
    return os.fsencode(path)


# ---- pixels: 0xRRGGBB words <-> R,G,B bytes ----

def _channel_bytes():
    """The byte of R, G and B within a native-endian uint32 0xRRGGBB."""
    return (2, 1, 0) if sys.byteorder == "little" else (1, 2, 3)


def _words_to_rgb(raw, npix):
    """raw: 4 * npix bytes, one native-endian uint32 0xRRGGBB per pixel."""
    out = bytearray(3 * npix)
    for c, at in enumerate(_channel_bytes()):
        out[c::3] = raw[at::4]
    return bytes(out)


def _rgb_to_words(rgb, npix):
    raw = bytearray(4 * npix)
    for c, at in enumerate(_channel_bytes()):
        raw[at::4] = rgb[c::3]
    return raw


def _take(im):
    """Copies a zs_image the library allocated into an Image and frees it."""
    try:
        w, h = im.width, im.height
        npix = w * h
        raw = ctypes.string_at(im.rgb, 4 * npix) if npix else b""
        hash_ = _lib.load().zs_image_hash(ctypes.byref(im))
        return Image(w, h, _words_to_rgb(raw, npix), _hash=hash_)
    finally:
        _lib.load().zs_image_free(ctypes.byref(im))


class Image:
    """An RGB image: width, height and rgb (bytes, R, G, B per pixel, row 0
    at the top).  Images come from render() and read_png(), or from
    Image(width, height, rgb)."""

    __slots__ = ("width", "height", "rgb", "stats", "depth", "normals", "shade", "_owner",
                 "_hash")

    def __init__(self, width, height, rgb, _hash=None):
        width, height = int(width), int(height)
        if width < 0 or height < 0:
            raise ValueError("Image: negative size %dx%d" % (width, height))
        rgb = bytes(rgb)
        if len(rgb) != 3 * width * height:
            raise ValueError(
                "Image: %dx%d needs %d bytes of R, G, B, got %d"
                % (width, height, 3 * width * height, len(rgb))
            )
        self.width = width
        self.height = height
        self.rgb = rgb
        self.stats = None
        self.depth = None  # render(depth=True): float32 (height, width), 1 = far
        self.normals = None  # render(normals=True): float32 (height, width, 3)
        self.shade = None  # the shading it was rendered with
        self._owner = None  # a scene's render with shade='id': the object of each id
        self._hash = _hash

    def _as_zs_image(self):
        """A zs_image over a copy of the pixels that Python owns (keep the
        returned buffer alive while the struct is used; never zs_image_free
        it)."""
        npix = self.width * self.height
        buf = (ctypes.c_uint32 * max(npix, 1)).from_buffer(
            _rgb_to_words(self.rgb, npix) if npix else bytearray(4)
        )
        im = _lib.zs_image(self.width, self.height, ctypes.cast(buf, ctypes.POINTER(ctypes.c_uint32)))
        return im, buf

    @property
    def hash_int(self):
        """zs_image_hash of the image as a number."""
        if self._hash is None:
            im, buf = self._as_zs_image()
            self._hash = _lib.load().zs_image_hash(ctypes.byref(im))
            del buf
        return self._hash

    @property
    def hash(self):
        """zs_image_hash as 16 hex digits: the image_hash that
        `zscan render --stats` prints for the same image."""
        return "%016x" % self.hash_int

    @property
    def array(self):
        """A new numpy uint8 array of shape (height, width, 3)."""
        try:
            import numpy
        except ImportError as e:
            raise ImportError(
                "zscan.Image.array needs numpy, which is not installed "
                "(pip install numpy, or Debian's python3-numpy); Image.rgb has "
                "the same pixels as bytes"
            ) from e
        return numpy.frombuffer(self.rgb, dtype=numpy.uint8).reshape(
            self.height, self.width, 3
        ).copy()

    @property
    def ids(self):
        """The face ids of an image rendered with shade='id', as a new numpy
        int32 array of shape (height, width): -1 where no face is (the
        colour of id i is i + 1 as 24 bits, the background 0)."""
        if self.shade != "id":
            raise ValueError("Image.ids: the image was not rendered with shade='id'")
        import numpy

        a = numpy.frombuffer(self.rgb, dtype=numpy.uint8).reshape(self.height, self.width, 3)
        a = a.astype(numpy.int32)
        return (a[:, :, 0] << 16 | a[:, :, 1] << 8 | a[:, :, 2]) - 1

    @property
    def objects(self):
        """The objects (their numbers in the scene, from 0, in the order
        they were loaded or added) of a scene's render with shade='id', as
        a new numpy int32 array of shape (height, width): -1 where none is."""
        ids = self.ids
        if self._owner is None:
            raise ValueError("Image.objects: only a Scene's render knows its objects (a "
                             "Device draws meshes, not objects: use Image.ids and id_base)")
        import numpy

        # the background's id, -1, reads the entry appended: -1
        return numpy.append(self._owner, numpy.int32(-1))[ids]

    def _repr_png_(self):
        """The PNG bytes, for notebooks (IPython shows the image inline)."""
        import tempfile

        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "image.png")
            self.save(path)
            with open(path, "rb") as f:
                return f.read()

    def pixel(self, x, y):
        """(R, G, B) of the pixel in column x, row y (row 0 at the top)."""
        if not (0 <= x < self.width and 0 <= y < self.height):
            raise IndexError("pixel (%d, %d) outside %dx%d" % (x, y, self.width, self.height))
        i = 3 * (y * self.width + x)
        return tuple(self.rgb[i : i + 3])

    def save(self, path):
        """Writes the image as an 8-bit RGB PNG (zs_png_write: the same bytes
        as `zscan render -o` for the same pixels)."""
        lib = _lib.load()
        im, buf = self._as_zs_image()
        err = _lib.zs_error()
        if lib.zs_png_write(_path_arg(path), ctypes.byref(im), ctypes.byref(err)):
            _raise(err)
        del buf

    def __eq__(self, other):
        if not isinstance(other, Image):
            return NotImplemented
        return (self.width, self.height, self.rgb) == (other.width, other.height, other.rgb)

    __hash__ = None  # mutable-looking value type; use .hash for the image hash

    def __repr__(self):
        return "<zscan.Image %dx%d %s>" % (self.width, self.height, self.hash)


def read_png(path):
    """Reads a PNG of any colour type and depth (zs_png_read; alpha is
    dropped, no gamma applied)."""
    lib = _lib.load()
    im = _lib.zs_image()
    err = _lib.zs_error()
    if lib.zs_png_read(_path_arg(path), ctypes.byref(im), ctypes.byref(err)):
        _raise(err)
    return _take(im)


class DiffResult:
    """What diff() found: differing (pixels whose RGB differ), total
    (width * height), max_channel_diff (the largest |a - b| over R, G, B),
    and image: zs_image_diff's picture (equal pixels a darkened grey of a,
    differing ones red)."""

    __slots__ = ("differing", "total", "max_channel_diff", "image")

    def __init__(self, differing, total, max_channel_diff, image):
        self.differing = differing
        self.total = total
        self.max_channel_diff = max_channel_diff
        self.image = image

    def __bool__(self):
        # true when the images differ
        return self.differing != 0

    def __repr__(self):
        return "<zscan.DiffResult %d of %d pixels differ, max channel difference %d>" % (
            self.differing,
            self.total,
            self.max_channel_diff,
        )


def diff(a, b):
    """Compares two images of the same size (zs_image_diff)."""
    lib = _lib.load()
    ia, ba = a._as_zs_image()
    ib, bb = b._as_zs_image()
    out = _lib.zs_image()
    res = _lib.zs_diff_result()
    err = _lib.zs_error()
    if lib.zs_image_diff(
        ctypes.byref(ia), ctypes.byref(ib), ctypes.byref(out), ctypes.byref(res), ctypes.byref(err)
    ):
        _raise(err)
    del ba, bb
    return DiffResult(res.differing, res.total, res.max_channel_diff, _take(out))


# ---- scenes and rendering ----

def _number(name, v):
    if isinstance(v, bool):
        raise TypeError("%s: expected a number, got %r" % (name, v))
    try:
        f = float(v)
    except (TypeError, ValueError):
        raise TypeError("%s: expected a number, got %r" % (name, v)) from None
    if not math.isfinite(f):
        raise ValueError("%s: expected a finite number, got %r" % (name, v))
    return f


def _vec3(name, v):
    try:
        t = tuple(v)
    except TypeError:
        raise TypeError("%s: expected three numbers x, y, z, got %r" % (name, v)) from None
    if len(t) != 3:
        raise ValueError("%s: expected three numbers x, y, z, got %r" % (name, v))
    return tuple(_number(name, c) for c in t)


def _int(name, v):
    if isinstance(v, bool) or not isinstance(v, numbers.Integral):
        raise TypeError("%s: expected an integer, got %r" % (name, v))
    return int(v)


def _choice(name, value, choices):
    if value not in choices:
        raise ValueError(
            "%s: expected %s, got %r" % (name, ", ".join(repr(c) for c in choices), value)
        )
    return choices.index(value)


_ARG = 1  # ZS_ERR_ARG


def _render_opts(size, eye, target, up, fovy, near, far, algo, shade, style, threads, cull_back,
                 shadows=False, samples=1, supersample=False, line_width=1, point_size=1,
                 point_shape="square"):
    """The zs_render_opts for render()'s arguments.  Types and names are
    checked here (TypeError, ValueError); values are the library's to judge
    (zscan.Error), except those that zs_render_opts cannot carry: 0 there
    means "the default", which None means here, so a 0 given is refused
    here with the library's words."""
    o = _lib.zs_render_opts()
    if size is not None:
        try:
            w, h = size
        except (TypeError, ValueError):
            raise TypeError("size: expected (width, height), got %r" % (size,)) from None
        w, h = _int("size", w), _int("size", h)
        if w < 1 or h < 1:
            raise Error("image size %dx%d: each side must be 1 to %d"
                        % (w, h, _lib.ZS_MAX_IMAGE_SIDE), _ARG)
        o.width, o.height = w, h
    o.algo = _choice("algo", algo, _lib.ALGOS)
    o.shade = _choice("shade", shade, _lib.SHADES)
    k = _choice("style", style, _lib.STYLES)
    o.hidden_line, o.wireframe = k == 1, k == 2
    if not isinstance(shadows, bool):
        raise TypeError("shadows: expected True or False, got %r" % (shadows,))
    o.shadows = 1 if shadows else 0
    samples = _int("samples", samples)
    if samples not in (1, 2, 4, 8, 16):
        raise Error("samples: %d: expected 1, 2, 4, 8 or 16" % samples, _ARG)
    if not isinstance(supersample, bool):
        raise TypeError("supersample: expected True or False, got %r" % (supersample,))
    o.samples, o.supersample = samples, 1 if supersample else 0
    for name, v in (("line_width", line_width), ("point_size", point_size)):
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise TypeError("%s: expected a number of pixels, got %r" % (name, v))
        if not (0 < v <= 64):
            raise Error("zs_render_opts.%s: %g: above 0 and at most 64 (0: 1)" % (name, v), _ARG)
    o.line_width, o.point_size = float(line_width), float(point_size)
    o.point_shape = _choice("point_shape", point_shape, _lib.POINT_SHAPES)
    threads = _int("threads", threads)
    if threads < 1:
        raise Error("threads must be 1 to 64", _ARG)
    o.threads = threads
    o.cull_back = 1 if cull_back else 0
    if eye is not None:
        o.eye[:] = _vec3("eye", eye)
        o.has_eye = 1
    if target is not None:
        o.target[:] = _vec3("target", target)
        o.has_target = 1
    if up is not None:
        o.up[:] = _vec3("up", up)
        o.has_up = 1
    if fovy is not None:
        o.fovy = _number("fovy", fovy)
        if o.fovy == 0:
            raise Error("fovy 0: must be between 0 and 180 degrees", _ARG)
    if near is not None:
        o.znear = _number("near", near)
        if o.znear == 0:
            raise Error("near 0: must be greater than 0", _ARG)
    if far is not None:
        o.zfar = _number("far", far)
        if o.zfar == 0:
            raise Error("far 0: must be greater than 0", _ARG)
    return o


_CAMERA_KEYS = ("eye", "target", "up", "fovy", "near", "far")


def _light_list(name, lights):
    """lights as a checked list of 1 to ZS_MAX_LIGHTS zscan.Light."""
    try:
        lights = list(lights)
    except TypeError:
        raise TypeError("%s: expected a list of zscan.Light, got %r"
                        % (name, type(lights).__name__)) from None
    for i, l in enumerate(lights):
        if not isinstance(l, Light):
            raise TypeError("%s[%d]: expected a zscan.Light, got %r" % (name, i, type(l).__name__))
    if not 1 <= len(lights) <= _lib.ZS_MAX_LIGHTS:
        raise ValueError("%s: %d lights: 1 to %d (None: the scene's own, else the headlight)"
                         % (name, len(lights), _lib.ZS_MAX_LIGHTS))
    return lights


class Scene(_lib.Handle):
    """A scene to render several times: loaded from a file or a generated
    scene (zscan.load(input), or Scene(input)), or built in code: Scene()
    is empty, scene.add(mesh, transform) places a zscan.Mesh in it as an
    object, scene.lights (a list of zscan.Light) and scene.camera (a dict
    of render()'s eye, target, up, fovy, near, far) are the defaults of
    its renders.  Close it (or use it in a with block) to free it at once;
    otherwise it is freed when collected."""

    _DESTROY = "zs_scene_destroy"

    def __init__(self, input=None, allow_empty=False):
        lib = _lib.load()
        self._lib = lib
        self._ptr = None
        self._meshes = []  # what the scene's textures belong to
        self.input = input
        self._lights = None
        self._camera = {}
        handle = ctypes.c_void_p()
        err = _lib.zs_error()
        if input is None:
            status = lib.zs_scene_create(ctypes.byref(handle), ctypes.byref(err))
        else:
            opts = _lib.zs_load_opts(1 if allow_empty else 0)
            status = lib.zs_scene_load(_path_arg(input), ctypes.byref(opts), ctypes.byref(handle),
                                       ctypes.byref(err))
        if status:
            _raise(err)
        self._ptr = handle

    def add(self, mesh, transform=None, name=None):
        """Adds mesh (a zscan.Mesh, or anything shaped like a trimesh mesh)
        as one object, placed by transform (4 x 4, local to world, acting
        on column vectors as numpy's matrices do; None: identity).  Its
        face ids follow those of the objects added before it."""
        if not isinstance(mesh, Mesh):
            if hasattr(mesh, "vertices") and hasattr(mesh, "faces"):
                mesh = Mesh.from_trimesh(mesh)
            else:
                raise TypeError("mesh: expected a zscan.Mesh or a trimesh-like mesh, got %r"
                                % type(mesh).__name__)
        model = None
        if transform is not None:
            import numpy

            t = numpy.asarray(transform, dtype=numpy.float64)
            if t.shape != (4, 4):
                raise ValueError("transform: expected a 4 x 4 matrix, got shape %s" % (t.shape,))
            bad = ~numpy.isfinite(t)
            if bad.any():
                i, j = numpy.argwhere(bad)[0]
                raise ValueError("transform[%d, %d]: %r is not a finite number" % (i, j, t[i, j]))
            model = (ctypes.c_double * 16)(*t.reshape(-1).tolist())
        c = mesh._c()
        err = _lib.zs_error()
        if self._lib.zs_scene_add_object(self._handle(), ctypes.byref(c), model,
                                         None if name is None else str(name).encode("utf-8"),
                                         ctypes.byref(err)):
            _raise(err)
        self._meshes.append(mesh)
        return self

    def _handle(self):
        if self._ptr is None:
            raise ValueError("zscan.Scene: used after close()")
        return self._ptr

    @property
    def lights(self):
        """The lights of the renders that give none (a list of zscan.Light,
        1 to ZS_MAX_LIGHTS), or None: the scene's own, else the headlight.
        Checked when set."""
        return None if self._lights is None else list(self._lights)

    @lights.setter
    def lights(self, lights):
        self._lights = None if lights is None else _light_list("scene.lights", lights)

    @property
    def camera(self):
        """The camera of the renders that give none: a dict of render()'s
        eye, target, up (three numbers), fovy, near, far (numbers); a key
        left out, or None, is the scene's own.  Checked when set."""
        return dict(self._camera)

    @camera.setter
    def camera(self, camera):
        if camera is None:
            camera = {}
        if not isinstance(camera, dict):
            raise TypeError("scene.camera: expected a dict, got %r" % type(camera).__name__)
        checked = {}
        for k, v in camera.items():
            if k not in _CAMERA_KEYS:
                raise ValueError("scene.camera: unknown key %r (%s)" % (k, ", ".join(_CAMERA_KEYS)))
            check = _vec3 if k in ("eye", "target", "up") else _number
            checked[k] = None if v is None else check("scene.camera[%r]" % k, v)
        self._camera = checked

    @property
    def objects(self):
        """Instances (objects) in the scene."""
        return self._lib.zs_scene_objects(self._handle())

    @property
    def faces(self):
        """Source faces over the instances."""
        return self._lib.zs_scene_faces(self._handle())

    def _camera_with(self, **given):
        """The scene's camera with what the caller gave (not None) put over it."""
        cam = dict(self._camera)
        for k, v in given.items():
            if k not in cam or v is not None:
                cam[k] = v
        return cam

    def query(self, size=None, eye=None, target=None, up=None, fovy=None, near=None,
              far=None, cull_back=False, samples=1):
        """Per object, as `zscan query` prints it (in order of first face): a
        dict of its name, 'visible' (the pixels of the frame, zbuffer mode,
        that show one of its faces) and 'bbox' (the samples of an occlusion
        query on its world box against the finished depth buffer).  With
        samples N (2, 4, 8 or 16) both count samples, N a pixel, as GL's
        sample-counting queries do (`zscan query --samples N`)."""
        cam = self._camera_with(eye=eye, target=target, up=up, fovy=fovy, near=near, far=far)
        opts = _render_opts(size, cam["eye"], cam["target"], cam["up"], cam["fovy"], cam["near"],
                            cam["far"], "zbuffer", "id", "solid", 1, cull_back, False, 1, False,
                            1, 1, "square")
        opts.samples = _int("samples", samples)
        if opts.samples not in (1, 2, 4, 8, 16):
            raise ValueError("samples: expected 1, 2, 4, 8 or 16, got %d" % opts.samples)
        rows = ctypes.POINTER(_lib.zs_object_visibility)()
        n = ctypes.c_int32()
        err = _lib.zs_error()
        if self._lib.zs_query_objects(self._handle(), ctypes.byref(opts), ctypes.byref(rows),
                                      ctypes.byref(n), ctypes.byref(err)):
            _raise(err)
        try:
            return [{"name": rows[i].name.decode("utf-8", "replace"),
                     "visible": rows[i].visible, "bbox": rows[i].box_samples}
                    for i in range(n.value)]
        finally:
            _lib.free(rows)

    def render(self, size=None, eye=None, target=None, up=None, fovy=None, near=None,
               far=None, algo="zbuffer", shade="auto", style="solid", threads=1,
               cull_back=False, shadows=False, samples=1, supersample=False, line_width=1,
               point_size=1, point_shape="square", lights=None, depth=False, normals=False):
        """Renders the scene as zscan.render() does; lights (a list of
        zscan.Light, None: scene.lights, else the scene's own or the
        headlight) and the camera arguments left None take the scene's.
        depth=True also gives image.depth, the window depth of each pixel
        as a float32 (height, width) array (1 = far); normals=True
        image.normals, the eye-space unit normal of each pixel as float32
        (height, width, 3) (0, 0, 0 where no face is); shade='id' also
        image.objects."""
        cam = self._camera_with(eye=eye, target=target, up=up, fovy=fovy, near=near, far=far)
        opts = _render_opts(size, cam["eye"], cam["target"], cam["up"], cam["fovy"], cam["near"],
                            cam["far"], algo, shade, style, threads, cull_back, shadows, samples,
                            supersample, line_width, point_size, point_shape)
        lights = self._lights if lights is None else _light_list("lights", lights)
        if lights is not None:
            arr = (_lib.zs_light * len(lights))(*[l._c for l in lights])
            opts.lights = arr
            opts.nlights = len(lights)
        for name, flag in (("depth", depth), ("normals", normals)):
            if not isinstance(flag, bool):
                raise TypeError("%s: expected True or False, got %r" % (name, flag))
        im = _lib.zs_image()
        stats = _lib.zs_raster_stats()
        err = _lib.zs_error()
        dp = ctypes.POINTER(ctypes.c_float)()
        if self._lib.zs_render(self._handle(), ctypes.byref(opts), ctypes.byref(im),
                               ctypes.byref(dp) if depth else None, ctypes.byref(stats),
                               ctypes.byref(err)):
            _raise(err)
        image = _take(im)
        image.shade = shade
        image.stats = {name: getattr(stats, name) for name, _ in _lib.zs_raster_stats._fields_}
        if depth:
            try:
                import numpy

                n = image.width * image.height
                image.depth = numpy.ctypeslib.as_array(dp, shape=(n,)).reshape(
                    image.height, image.width).copy()
            finally:
                _lib.free(dp)
        if normals:
            image.normals = self._floats(self._lib.zs_render_normals, opts,
                                         (image.height, image.width, 3))
        if shade == "id":
            owner = ctypes.POINTER(ctypes.c_int32)()
            n = ctypes.c_uint32()
            if self._lib.zs_scene_id_objects(self._handle(), ctypes.byref(owner), ctypes.byref(n),
                                             ctypes.byref(err)):
                _raise(err)
            try:
                import numpy

                image._owner = numpy.ctypeslib.as_array(owner, shape=(max(n.value, 1),))[
                    : n.value].copy()
            finally:
                _lib.free(owner)
        return image

    def _floats(self, fn, opts, shape):
        """The float array fn (zs_render_normals) allocates for opts, as numpy."""
        import numpy

        p = ctypes.POINTER(ctypes.c_float)()
        err = _lib.zs_error()
        if fn(self._handle(), ctypes.byref(opts), ctypes.byref(p), ctypes.byref(err)):
            _raise(err)
        try:
            return numpy.ctypeslib.as_array(p, shape=(int(numpy.prod(shape)),)).reshape(
                shape).copy()
        finally:
            _lib.free(p)


def load(input=None, allow_empty=False):
    """Loads a model (FILE.obj, .ply, .stl, .off, .gltf, ... through assimp
    when the library has it), a scene file (FILE.json) or builtin:NAME[?k=v];
    None is builtin:default.  Raises zscan.Error with the library's message."""
    return Scene("builtin:default" if input is None else input, allow_empty=allow_empty)


def _scene_of(input, allow_empty):
    """The scene of zscan.render's and zscan.query's input: a zscan.Mesh or a
    trimesh-like mesh as its one object, else a path or builtin: spec
    loaded (None: builtin:default)."""
    if isinstance(input, Mesh) or (hasattr(input, "vertices") and hasattr(input, "faces")):
        scene = Scene()
        scene.add(input)
        return scene
    return Scene("builtin:default" if input is None else input, allow_empty=allow_empty)


def query(input, size=None, eye=None, target=None, up=None, fovy=None, near=None, far=None,
          cull_back=False, samples=1, allow_empty=False):
    """Loads input (a path, a builtin: spec, a zscan.Mesh or a trimesh-like
    mesh) and gives Scene.query()'s list: per object its name, 'visible'
    and 'bbox', as `zscan query INPUT` prints them."""
    with _scene_of(input, allow_empty) as scene:
        return scene.query(size=size, eye=eye, target=target, up=up, fovy=fovy, near=near,
                           far=far, cull_back=cull_back, samples=samples)


def render(input, size=None, eye=None, target=None, up=None, fovy=None, near=None,
           far=None, algo="zbuffer", shade="auto", style="solid", threads=1,
           cull_back=False, allow_empty=False, shadows=False, samples=1, supersample=False,
           line_width=1, point_size=1, point_shape="square", lights=None, depth=False,
           normals=False):
    """Loads input and renders one frame: the image `zscan render INPUT` makes
    with the same options, byte for byte (its .hash is the CLI's image_hash).

    size       (width, height); None: the scene's own, else 1024 x 768
    eye, target, up   3-sequences; None: the scene's camera, completed from
               its bounds (the automatic camera)
    fovy       degrees; None: the scene's (45 unless it says)
    near, far  the clip planes' distances; None: from the bounds
    algo       'zbuffer', 'scanline' or 'depthsort'
    shade      'auto' (flat, or phong for a model with normals, colours or
               textures), 'flat', 'unlit', 'gouraud', 'phong', 'normal', 'id',
               'depth' or 'overdraw'
    style      'solid', 'hidden-line' (zbuffer and flat only) or
               'solid+wireframe' (the edges over the faces; zbuffer only)
    threads    1 .. 64 (depthsort: its walk only)
    cull_back  drop faces turned away from the camera (--cull-back)
    shadows    every directional and spot light casts shadows, a scene
               without lights gets the key light (--shadows)
    samples    anti-aliasing: 1, 2, 4, 8 or 16 samples a pixel (--samples)
    supersample   shade each sample, not each pixel (--supersample)
    line_width, point_size   the model's lines and points, and line_width the
               edges of the hidden-line and wireframe styles too, pixels
               (--line-width, --point-size; GL's rounding; zbuffer and
               scanline modes)
    point_shape   'square' (GL's aliased point) or 'disc' (--point-shape)
    allow_empty   render a model without faces (--allow-empty)
    lights     a list of zscan.Light (None: the scene's, else the headlight)
    depth      also give image.depth, float32 (height, width), 1 = far
    normals    also give image.normals, float32 (height, width, 3): the
               eye-space unit normal of each pixel, 0, 0, 0 where no face is
    shade='id' gives image.ids (face ids) and image.objects (the object of
               each pixel), int32 (height, width), -1 where none is

    input may also be a zscan.Mesh, or anything shaped like a trimesh mesh,
    rendered as the one object of a scene.

    An argument of the wrong type, an unknown name or a number that is not
    finite raises TypeError or ValueError; whatever the library refuses (a
    file it cannot read, a size or camera out of range) raises zscan.Error
    with the library's one-line message, as `zscan render` prints it.  The returned Image also has
    .stats, the frame's counters (zs_raster_stats) as a dict.
    """
    # check the options before the (possibly slow) load
    _render_opts(size, eye, target, up, fovy, near, far, algo, shade, style, threads, cull_back,
                 shadows, samples, supersample, line_width, point_size, point_shape)
    with _scene_of(input, allow_empty) as scene:
        return scene.render(size=size, eye=eye, target=target, up=up, fovy=fovy, near=near,
                            far=far, algo=algo, shade=shade, style=style, threads=threads,
                            cull_back=cull_back, shadows=shadows, samples=samples,
                            supersample=supersample, line_width=line_width,
                            point_size=point_size, point_shape=point_shape, lights=lights,
                            depth=depth, normals=normals)
