"""ctypes declarations of libzscan's public API (include/zscan/zscan.h and
include/zscan/error.h) and the search for the shared library.

The structures mirror the header field by field; their sizes and offsets
are checked against the C compiler's in the tests.  The library is loaded
on first use, not on import, so that the pytest plugin can be registered in
an environment without the library and fail only where it is used.
"""

import ctypes
import ctypes.util
import os
import threading

# The header this binding mirrors (ZSCAN_VERSION_STRING).  Before 1.0 the
# structs may change between minor versions, so the library's MAJOR.MINOR
# must be this one's.
BINDING_VERSION = "0.12.3"

ZS_ERROR_MSG_MAX = 512
ZS_MAX_IMAGE_SIDE = 16384

# zs_status
STATUS_NAMES = (
    "ZS_OK",
    "ZS_ERR_ARG",
    "ZS_ERR_IO",
    "ZS_ERR_PARSE",
    "ZS_ERR_LIMIT",
    "ZS_ERR_NOMEM",
    "ZS_ERR_UNSUPPORTED",
)

# zs_algo and zs_shade, in the header's enum order
ALGOS = ("zbuffer", "scanline", "depthsort")
SHADES = ("auto", "flat", "id", "depth", "overdraw", "unlit", "gouraud", "phong", "normal")
STYLES = ("solid", "hidden-line", "solid+wireframe")
POINT_SHAPES = ("square", "disc")  # zs_point_shape


class zs_error(ctypes.Structure):
    _fields_ = [
        ("code", ctypes.c_int),  # zs_status
        ("msg", ctypes.c_char * ZS_ERROR_MSG_MAX),
    ]


class zs_image(ctypes.Structure):
    _fields_ = [
        ("width", ctypes.c_int),
        ("height", ctypes.c_int),
        ("rgb", ctypes.POINTER(ctypes.c_uint32)),
    ]


class zs_diff_result(ctypes.Structure):
    _fields_ = [
        ("differing", ctypes.c_uint64),
        ("total", ctypes.c_uint64),
        ("max_channel_diff", ctypes.c_int),
    ]


class zs_load_opts(ctypes.Structure):
    _fields_ = [
        ("allow_empty", ctypes.c_int),
        ("skip_missing_textures", ctypes.c_int),
    ]


class zs_light(ctypes.Structure):
    _fields_ = [
        ("kind", ctypes.c_int),  # zs_light_kind
        ("color", ctypes.c_double * 3),
        ("position", ctypes.c_double * 3),
        ("direction", ctypes.c_double * 3),
        ("inner_deg", ctypes.c_double),
        ("outer_deg", ctypes.c_double),
        ("eye_space", ctypes.c_int),
        ("shadow", ctypes.c_int),
    ]


class zs_render_opts(ctypes.Structure):
    _fields_ = [
        ("width", ctypes.c_int),
        ("height", ctypes.c_int),
        ("algo", ctypes.c_int),  # zs_algo
        ("shade", ctypes.c_int),  # zs_shade
        ("cull_back", ctypes.c_int),
        ("threads", ctypes.c_int),
        ("hidden_line", ctypes.c_int),
        ("has_eye", ctypes.c_int),
        ("has_target", ctypes.c_int),
        ("has_up", ctypes.c_int),
        ("eye", ctypes.c_double * 3),
        ("target", ctypes.c_double * 3),
        ("up", ctypes.c_double * 3),
        ("fovy", ctypes.c_double),
        ("znear", ctypes.c_double),
        ("zfar", ctypes.c_double),
        ("filter", ctypes.c_int),  # zs_filter
        ("lights", ctypes.POINTER(zs_light)),
        ("nlights", ctypes.c_int),
        ("shadows", ctypes.c_int),
        ("shadow_size", ctypes.c_int),
        ("has_shadow_bias", ctypes.c_int),
        ("shadow_bias", ctypes.c_double * 2),
        ("samples", ctypes.c_int),
        ("supersample", ctypes.c_int),
        ("wireframe", ctypes.c_int),
        ("line_width", ctypes.c_double),
        ("point_size", ctypes.c_double),
        ("point_shape", ctypes.c_int),  # zs_point_shape
    ]


class zs_material(ctypes.Structure):
    _fields_ = [
        ("base", ctypes.c_uint8 * 4),
        ("specular", ctypes.c_uint8 * 3),
        ("emissive", ctypes.c_uint8 * 3),
        ("shininess", ctypes.c_uint16),
        ("double_sided", ctypes.c_uint8),
        ("base_texture", ctypes.c_void_p),  # const zs_texture *
        ("wrap_s", ctypes.c_int),  # zs_wrap
        ("wrap_t", ctypes.c_int),
        ("filter", ctypes.c_int),  # zs_filter
        ("ignore_alpha", ctypes.c_uint8),
        ("alpha_cutoff", ctypes.c_uint8),
    ]


_p_i32 = ctypes.POINTER(ctypes.c_int32)
_p_u32 = ctypes.POINTER(ctypes.c_uint32)


class zs_mesh(ctypes.Structure):
    _fields_ = [
        ("pos", ctypes.POINTER(ctypes.c_double)),
        ("nverts", ctypes.c_int32),
        ("face_start", _p_i32),
        ("face_vert", _p_i32),
        ("nfaces", ctypes.c_int32),
        ("face_rgb", _p_u32),
        ("face_id", _p_i32),
        ("nattrs", ctypes.c_int32),
        ("corner_attr", _p_i32),
        ("normal", ctypes.POINTER(ctypes.c_float)),
        ("color", ctypes.POINTER(ctypes.c_uint8)),
        ("uv", ctypes.POINTER(ctypes.c_float)),
        ("face_material", _p_i32),
        ("materials", ctypes.POINTER(zs_material)),
        ("nmaterials", ctypes.c_int32),
        ("line_vert", _p_i32),
        ("nlines", ctypes.c_int32),
        ("line_rgb", _p_u32),
        ("point_vert", _p_i32),
        ("npoints", ctypes.c_int32),
        ("point_rgb", _p_u32),
        ("prim_id", ctypes.c_int32),
    ]


WRAPS = ("repeat", "clamp", "mirror")  # zs_wrap
FILTERS = ("default", "nearest", "bilinear", "trilinear")  # zs_filter
LIGHT_KINDS = ("directional", "point", "spot", "ambient")  # zs_light_kind
ZS_MAX_LIGHTS = 16
ZS_RGB_MESH = 0xFF000000
ZS_MAX_TEXTURE_SIDE = 8192
ZS_MAX_SHININESS = 4096


class zs_raster_stats(ctypes.Structure):
    _fields_ = [
        (name, ctypes.c_uint64)
        for name in (
            "draws",
            "vertices",
            "polygons_in",
            "polygons_outside",
            "polygons_clipped",
            "polygons_culled_back",
            "polygons_degenerate",
            "polygons_offscreen",
            "polygons_rasterized",
            "spans",
            "pixels_tested",
            "pixels_written",
        )
    ]


class zs_device_config(ctypes.Structure):
    _fields_ = [
        ("width", ctypes.c_int),
        ("height", ctypes.c_int),
        ("algo", ctypes.c_int),  # zs_algo
        ("shade", ctypes.c_int),  # zs_shade
        ("cull_back", ctypes.c_int),
        ("threads", ctypes.c_int),
        ("background", ctypes.c_uint32),
        ("spans", ctypes.c_int),  # zs_span_fill
        ("filter", ctypes.c_int),
    ]


class zs_row(ctypes.Structure):
    _fields_ = [
        ("y", ctypes.c_int),
        ("width", ctypes.c_int),
        ("rgb", ctypes.POINTER(ctypes.c_uint32)),
        ("depth", ctypes.POINTER(ctypes.c_uint32)),
        ("id", ctypes.POINTER(ctypes.c_uint32)),
        ("count", ctypes.POINTER(ctypes.c_uint32)),
        ("normal", ctypes.POINTER(ctypes.c_float)),
    ]


zs_row_sink = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.POINTER(zs_row))


class zs_clock_params(ctypes.Structure):
    _fields_ = [
        (name, ctypes.c_double)
        for name in (
            "per_call_ns", "per_vertex_ns", "per_polygon_ns", "per_span_ns", "per_pixel_ns",
            "per_write_ns", "per_query_pixel_ns", "switch_ns", "query_latency_ns",
            "cpu_per_call_ns", "cpu_per_query_ns", "cpu_per_node_ns", "cpu_per_frustum_ns",
            "cpu_per_cost_eval_ns", "hzb_pass_ns", "hzb_per_texel_ns", "hzb_per_box_ns",
            "hzb_per_read_ns",
        )
    ]


class zs_clock_stats(ctypes.Structure):
    _fields_ = [
        ("queries", ctypes.c_uint64),
        ("query_waits", ctypes.c_uint64),
        ("stalls", ctypes.c_uint64),
        ("query_pixels", ctypes.c_uint64),
        ("switches", ctypes.c_uint64),
        ("sync_ps", ctypes.c_int64),
        ("stall_ps", ctypes.c_int64),
        ("gpu_ps", ctypes.c_int64),
        ("cpu_ps", ctypes.c_int64),
        ("draw_ps", ctypes.c_int64),
        ("query_ps", ctypes.c_int64),
        ("switch_ps", ctypes.c_int64),
        ("hzb_texels", ctypes.c_uint64),
        ("hzb_boxes", ctypes.c_uint64),
        ("hzb_reads", ctypes.c_uint64),
    ]


CPU_WORK = ("node", "frustum_test", "cost_eval")  # zs_cpu_work

_c_status = ctypes.c_int
_p_error = ctypes.POINTER(zs_error)
_p_image = ctypes.POINTER(zs_image)
_p_d16 = ctypes.POINTER(ctypes.c_double)
_p_d3 = ctypes.POINTER(ctypes.c_double)

class zs_object_visibility(ctypes.Structure):
    _fields_ = [
        ("name", ctypes.c_char_p),
        ("object", ctypes.c_int32),
        ("first_face", ctypes.c_uint32),
        ("visible", ctypes.c_uint64),
        ("box_samples", ctypes.c_uint64),
    ]


# name: (restype, argtypes)
_SIGNATURES = {
    "zs_version": (ctypes.c_char_p, []),
    "zs_pixel_version": (ctypes.c_int, []),
    "zs_pixel_changes": (ctypes.c_char_p, [ctypes.c_int]),
    "zs_algo_parse": (ctypes.c_int, [ctypes.c_char_p]),
    "zs_scene_load": (
        _c_status,
        [ctypes.c_char_p, ctypes.POINTER(zs_load_opts), ctypes.POINTER(ctypes.c_void_p), _p_error],
    ),
    "zs_scene_destroy": (None, [ctypes.c_void_p]),
    "zs_scene_objects": (ctypes.c_int32, [ctypes.c_void_p]),
    "zs_scene_faces": (ctypes.c_uint64, [ctypes.c_void_p]),
    "zs_render": (
        _c_status,
        [
            ctypes.c_void_p,
            ctypes.POINTER(zs_render_opts),
            _p_image,
            ctypes.POINTER(ctypes.POINTER(ctypes.c_float)),
            ctypes.POINTER(zs_raster_stats),
            _p_error,
        ],
    ),
    "zs_render_normals": (
        _c_status,
        [ctypes.c_void_p, ctypes.POINTER(zs_render_opts),
         ctypes.POINTER(ctypes.POINTER(ctypes.c_float)), _p_error],
    ),
    "zs_query_objects": (
        _c_status,
        [ctypes.c_void_p, ctypes.POINTER(zs_render_opts),
         ctypes.POINTER(ctypes.POINTER(zs_object_visibility)), ctypes.POINTER(ctypes.c_int32),
         _p_error],
    ),
    "zs_scene_id_objects": (
        _c_status,
        [ctypes.c_void_p, ctypes.POINTER(ctypes.POINTER(ctypes.c_int32)),
         ctypes.POINTER(ctypes.c_uint32), _p_error],
    ),
    "zs_scene_create": (_c_status, [ctypes.POINTER(ctypes.c_void_p), _p_error]),
    "zs_scene_add_object": (
        _c_status,
        [ctypes.c_void_p, ctypes.POINTER(zs_mesh), ctypes.POINTER(ctypes.c_double),
         ctypes.c_char_p, _p_error],
    ),
    "zs_texture_create": (
        _c_status,
        [ctypes.c_int, ctypes.c_int, ctypes.c_void_p, ctypes.POINTER(ctypes.c_void_p), _p_error],
    ),
    "zs_texture_destroy": (None, [ctypes.c_void_p]),
    "zs_material_default": (zs_material, []),
    "zs_device_create": (
        _c_status,
        [ctypes.POINTER(zs_device_config), ctypes.POINTER(ctypes.c_void_p), _p_error],
    ),
    "zs_device_destroy": (None, [ctypes.c_void_p]),
    "zs_device_config_of": (ctypes.POINTER(zs_device_config), [ctypes.c_void_p]),
    "zs_device_set_camera": (None, [ctypes.c_void_p, _p_d16, _p_d16]),
    "zs_device_set_lights": (
        _c_status, [ctypes.c_void_p, ctypes.POINTER(zs_light), ctypes.c_int, _p_error]),
    "zs_device_clear": (None, [ctypes.c_void_p]),
    "zs_device_draw": (
        _c_status,
        [ctypes.c_void_p, ctypes.POINTER(zs_mesh), _p_d16, ctypes.c_uint32, ctypes.c_uint32,
         _p_error],
    ),
    "zs_device_finish": (_c_status, [ctypes.c_void_p, zs_row_sink, ctypes.c_void_p, _p_error]),
    "zs_device_stats": (ctypes.POINTER(zs_raster_stats), [ctypes.c_void_p]),
    "zs_device_depth_buffer": (ctypes.POINTER(ctypes.c_uint32), [ctypes.c_void_p]),
    "zs_device_id_buffer": (ctypes.POINTER(ctypes.c_uint32), [ctypes.c_void_p]),
    "zs_device_query_begin": (
        _c_status, [ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint32), _p_error]),
    "zs_device_query_end": (_c_status, [ctypes.c_void_p, _p_error]),
    "zs_device_query_box": (_c_status, [ctypes.c_void_p, _p_d3, _p_d3, _p_error]),
    "zs_device_query_ready": (ctypes.c_int, [ctypes.c_void_p, ctypes.c_uint32]),
    "zs_device_query_result": (ctypes.c_uint64, [ctypes.c_void_p, ctypes.c_uint32]),
    "zs_device_queries": (ctypes.c_uint32, [ctypes.c_void_p]),
    "zs_device_set_normals": (_c_status, [ctypes.c_void_p, ctypes.c_int, _p_error]),
    "zs_clock_params_default": (None, [ctypes.POINTER(zs_clock_params)]),
    "zs_device_set_clock": (
        _c_status, [ctypes.c_void_p, ctypes.POINTER(zs_clock_params), _p_error]),
    "zs_device_cpu_work": (None, [ctypes.c_void_p, ctypes.c_int, ctypes.c_uint64]),
    "zs_device_clock": (ctypes.POINTER(zs_clock_stats), [ctypes.c_void_p]),
    "zs_device_frame_ps": (ctypes.c_int64, [ctypes.c_void_p]),
    "zs_mat_look_at": (ctypes.c_int, [_p_d16, _p_d3, _p_d3, _p_d3]),
    "zs_mat_perspective": (
        None, [_p_d16, ctypes.c_double, ctypes.c_double, ctypes.c_double, ctypes.c_double]),
    "zs_image_alloc": (_c_status, [_p_image, ctypes.c_int, ctypes.c_int, _p_error]),
    "zs_image_free": (None, [_p_image]),
    "zs_image_hash": (ctypes.c_uint64, [_p_image]),
    "zs_image_diff": (
        _c_status,
        [_p_image, _p_image, _p_image, ctypes.POINTER(zs_diff_result), _p_error],
    ),
    "zs_png_write": (_c_status, [ctypes.c_char_p, _p_image, _p_error]),
    "zs_png_read": (_c_status, [ctypes.c_char_p, _p_image, _p_error]),
}

_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))
# The names the library may have beside the package, when installed there.
_PACKAGE_NAMES = ("libzscan.so", "libzscan.so.0", "libzscan.so." + BINDING_VERSION)
# The checkout's build directory, when the package is used from python/.
_CHECKOUT_BUILD = os.path.normpath(os.path.join(_PACKAGE_DIR, "..", "..", "build"))

_lock = threading.Lock()
_lib = None


class LibraryError(ImportError):
    """libzscan could not be found or loaded, or is not the version this binding
    mirrors (a subclass of ImportError)."""


LibraryError.__module__ = "zscan"


def _not_found(tried):
    env_set = "env" in tried
    skipped = "not tried, since ZSCAN_LIBRARY is set"
    beside = os.path.join(_PACKAGE_DIR, "libzscan.so{,.0,.%s}" % BINDING_VERSION)
    build = os.path.join(_CHECKOUT_BUILD, "libzscan.so")
    lines = [
        "cannot load libzscan, the zscan shared library. Looked in:",
        "  1. the environment variable ZSCAN_LIBRARY: " + tried.get("env", "not set"),
        "  2. beside the package, %s: %s"
        % (beside, skipped if env_set else tried.get("beside", "not there")),
        "  3. the checkout's build directory, %s: %s"
        % (build, skipped if env_set else tried.get("build", "not there")),
        "  4. the system's library path (libzscan.so.0, as `cmake --install` puts it): "
        + (skipped if env_set else tried.get("system", "not found")),
        "Build the library (cmake -S . -B build && cmake --build build) or set "
        "ZSCAN_LIBRARY to the path of libzscan.so.",
    ]
    return LibraryError("\n".join(lines))


def _open(path):
    return ctypes.CDLL(path)


def _find_and_open():
    tried = {}
    env = os.environ.get("ZSCAN_LIBRARY")
    if env:
        # An explicit choice is the only one tried: a wrong path is an error,
        # not a reason to load some other library silently.
        try:
            return _open(env), env
        except OSError as e:
            tried["env"] = str(e)
            raise _not_found(tried) from None
    for name in _PACKAGE_NAMES:
        p = os.path.join(_PACKAGE_DIR, name)
        if os.path.exists(p):
            try:
                return _open(p), p
            except OSError as e:
                tried["beside"] = str(e)
            break
    build = os.path.join(_CHECKOUT_BUILD, "libzscan.so")
    if os.path.exists(build):
        try:
            return _open(build), build
        except OSError as e:
            tried["build"] = str(e)
    name = ctypes.util.find_library("zscan") or "libzscan.so.0"
    try:
        return _open(name), name
    except OSError as e:
        tried["system"] = str(e)
    raise _not_found(tried)


def _declare(lib):
    for name, (restype, argtypes) in _SIGNATURES.items():
        try:
            fn = getattr(lib, name)
        except AttributeError:
            raise LibraryError(
                "%s does not export %s: it is not the libzscan this binding (%s) was written for"
                % (lib._name, name, BINDING_VERSION)
            ) from None
        fn.restype = restype
        fn.argtypes = argtypes


class Handle:
    """What owns a library object (self._ptr) and frees it with the library
    function named by _DESTROY: at close(), at the end of a with block, or
    when collected."""

    _DESTROY = None
    _ptr = None

    def close(self):
        if self._ptr is not None:
            getattr(self._lib, self._DESTROY)(self._ptr)
            self._ptr = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        if getattr(self, "_ptr", None) is not None:
            self.close()


_libc = ctypes.CDLL(None)
_libc.free.argtypes = [ctypes.c_void_p]
_libc.free.restype = None


def free(p):
    """free() of what the library allocated (zs_render's depth)."""
    _libc.free(ctypes.cast(p, ctypes.c_void_p))


def load():
    """The loaded library (found and checked once, on first use)."""
    global _lib
    if _lib is not None:
        return _lib
    with _lock:
        if _lib is None:
            lib, path = _find_and_open()
            _declare(lib)
            version = lib.zs_version().decode("ascii", "replace")
            if version.split(".")[:2] != BINDING_VERSION.split(".")[:2]:
                raise LibraryError(
                    "%s is libzscan %s, but this binding mirrors the structs of %s "
                    "(before 1.0 they may change between minor versions)"
                    % (path, version, BINDING_VERSION)
                )
            for i, algo in enumerate(ALGOS):
                if lib.zs_algo_parse(algo.encode()) != i:
                    raise LibraryError(
                        "%s numbers the algorithm %r %d, this binding %d: it is not the "
                        "libzscan this binding (%s) mirrors"
                        % (path, algo, lib.zs_algo_parse(algo.encode()), i, BINDING_VERSION)
                    )
            lib.zscan_path = path
            _lib = lib
    return _lib
