"""Meshes, materials, textures and lights made in code from numpy arrays,
checked here (shape, dtype, finite values, indices in range) with the
argument and its first bad element named, then handed to libzscan's
zs_scene_add_object, which draws them as it draws the OBJ file of the
same data.

Colours follow numpy's habit: an integer array is 0..255, a floating one
0..1 (clamped, then rounded to the byte as the OBJ reader rounds `Kd` and
`v x y z r g b`: half away from zero), so that a mesh and its OBJ file
give the same bytes.
"""

import ctypes
import math
import numbers

from . import _lib


def _numpy():
    try:
        import numpy
    except ImportError as e:  # pragma: no cover - Debian's python3-numpy is a test dependency
        raise ImportError(
            "zscan.Mesh needs numpy (Debian's python3-numpy, or pip install numpy)"
        ) from e
    return numpy


def _where(index):
    """'[i]' or '[i, j]' for an element's index."""
    return "[" + ", ".join(str(int(i)) for i in index) + "]"


def _check_finite(name, a, after=""):
    bad = ~_numpy().isfinite(a)
    if bad.any():
        at = tuple(_numpy().argwhere(bad)[0])
        raise ValueError("%s%s: %r is not a finite number%s" % (name, _where(at), a[at].item(), after))


def _check_range(name, a, n, where=None, after=""):
    """Every index of a in 0 .. n - 1; where(i) the index to name for the
    flat index i (None: a's own)."""
    np = _numpy()
    bad = (a < 0) | (a >= n)
    if bad.any():
        at = tuple(np.argwhere(bad)[0])
        shown = where(at[0]) if where else at
        raise ValueError("%s%s: vertex %d out of range (%d vertices)%s"
                         % (name, _where(shown), a[at], n, after))


def _array(name, value, dtype, width, copy):
    """value as a C-contiguous numpy array of dtype with rows of `width`
    (None: 1-D), checked; the same object when it already is one."""
    np = _numpy()
    if isinstance(value, np.ndarray):
        a = value
    else:
        try:
            a = np.asarray(value)
        except (TypeError, ValueError) as e:
            raise TypeError("%s: expected an array, got %r (%s)" % (name, type(value).__name__, e)) from None
    if a.dtype == object or not (np.issubdtype(a.dtype, np.number) or a.dtype == bool):
        raise TypeError("%s: expected numbers, got an array of %s" % (name, a.dtype))
    if np.issubdtype(a.dtype, np.complexfloating) or a.dtype == bool:
        raise TypeError("%s: expected real numbers, got an array of %s" % (name, a.dtype))
    widths = width if isinstance(width, tuple) else (width,)
    if width == "polygons":
        if a.ndim != 2 or a.shape[1] < 3:
            raise ValueError("%s: expected shape (M, 3), (M, 4) or (M, k), k >= 3, or a list "
                             "of polygons, got shape %s" % (name, a.shape))
    elif width is None:
        if a.ndim != 1:
            raise ValueError("%s: expected a 1-D array, got shape %s" % (name, a.shape))
    elif a.ndim != 2 or a.shape[1] not in widths:
        raise ValueError(
            "%s: expected shape (N, %s), got %s"
            % (name, " or ".join(str(w) for w in widths), a.shape)
        )
    if np.issubdtype(a.dtype, np.floating):
        _check_finite(name, a)
    if np.issubdtype(dtype, np.integer) and not np.issubdtype(a.dtype, np.integer):
        raise TypeError("%s: expected integers, got an array of %s" % (name, a.dtype))
    if a.dtype == dtype and a.flags.c_contiguous:
        return a
    if copy is False:
        raise ValueError(
            "%s: copy=False needs a C-contiguous %s array, got %s%s"
            % (name, np.dtype(dtype).name, a.dtype,
               "" if a.flags.c_contiguous else " (not C-contiguous)")
        )
    if np.issubdtype(dtype, np.integer):
        info = np.iinfo(dtype)
        if a.size and (a.min() < info.min or a.max() > info.max):
            at = tuple(np.argwhere((a < info.min) | (a > info.max))[0])
            raise ValueError("%s%s: %d does not fit in %s" % (name, _where(at), a[at], np.dtype(dtype).name))
    return np.ascontiguousarray(a, dtype=dtype)


def _bytes_of_colours(name, value, widths, copy):
    """Colours as a C-contiguous uint8 array of rows of one of widths:
    integers 0..255 as they are, floats 0..1 rounded as the OBJ reader
    does."""
    np = _numpy()
    a = value if isinstance(value, np.ndarray) else np.asarray(value)
    if np.issubdtype(a.dtype, np.floating):
        if copy is False:
            raise ValueError("%s: copy=False needs a C-contiguous uint8 array, got %s (floats "
                             "are converted to bytes)" % (name, a.dtype))
        a = _array(name, a, np.float64, widths, None)
        bad = (a < 0.0) | (a > 1.0)
        if bad.any():
            at = tuple(np.argwhere(bad)[0])
            raise ValueError("%s%s: %r is outside 0..1 (floats are 0..1, integers 0..255)"
                             % (name, _where(at), a[at].item()))
        y = a * 255.0
        r = np.floor(y)
        # lround: half away from zero (y - r is exact for 0 <= y <= 255)
        return np.ascontiguousarray(r + (y - r >= 0.5), dtype=np.uint8)
    a = _array(name, a, a.dtype if np.issubdtype(a.dtype, np.integer) else np.int64, widths, None)
    bad = (a < 0) | (a > 255)
    if bad.any():
        at = tuple(np.argwhere(bad)[0])
        raise ValueError("%s%s: %d is outside 0..255 (integers are 0..255, floats 0..1)"
                         % (name, _where(at), a[at]))
    if a.dtype == np.uint8 and a.flags.c_contiguous:
        return a
    if copy is False:
        raise ValueError("%s: copy=False needs a C-contiguous uint8 array, got %s" % (name, a.dtype))
    return np.ascontiguousarray(a, dtype=np.uint8)


def _colour(name, value, n):
    """A colour of n channels as bytes (a sequence of ints 0..255 or of
    floats 0..1)."""
    np = _numpy()
    a = np.asarray(value)
    if a.shape != (n,) and not (n == 4 and a.shape == (3,)):
        raise ValueError("%s: expected %d numbers, got %r" % (name, n, value))
    row = _bytes_of_colours(name, a.reshape(1, -1), (a.shape[0],), None)[0]
    out = list(int(c) for c in row)
    return out + [255] * (n - len(out))


class Texture(_lib.Handle):
    """A base-colour texture: an H x W x 3 or x 4 uint8 array (row 0 at the
    top, as an image is read), made into a zs_texture with its mip chain.
    Keep it as long as a scene that uses it (the Mesh and Scene holding it
    do)."""

    _DESTROY = "zs_texture_destroy"

    def __init__(self, pixels):
        np = _numpy()
        a = pixels.array if hasattr(pixels, "array") and not isinstance(pixels, np.ndarray) else pixels
        a = np.asarray(a)
        if a.dtype != np.uint8:
            raise TypeError("texture: expected a uint8 array, got %s" % a.dtype)
        if a.ndim != 3 or a.shape[2] not in (3, 4):
            raise ValueError("texture: expected shape (H, W, 3) or (H, W, 4), got %s" % (a.shape,))
        h, w = a.shape[:2]
        side = _lib.ZS_MAX_TEXTURE_SIDE
        if not (1 <= w <= side and 1 <= h <= side):
            raise ValueError("texture: %dx%d: each side must be 1 to %d" % (w, h, side))
        if a.shape[2] == 3:
            a = np.concatenate([a, np.full((h, w, 1), 255, np.uint8)], axis=2)
        a = np.ascontiguousarray(a)
        self.width, self.height = w, h
        self.opaque = bool((a[:, :, 3] == 255).all())
        lib = _lib.load()
        self._lib = lib
        self._ptr = None
        handle = ctypes.c_void_p()
        err = _lib.zs_error()
        if lib.zs_texture_create(w, h, a.ctypes.data, ctypes.byref(handle), ctypes.byref(err)):
            from . import Error

            raise Error(err.msg.decode("utf-8", "replace"), err.code)
        self._ptr = handle


    def __repr__(self):
        return "<zscan.Texture %dx%d>" % (self.width, self.height)


def _flag(name, v):
    if not isinstance(v, bool):
        raise TypeError("%s: expected True or False, got %r" % (name, v))
    return 1 if v else 0


class Material:
    """A surface's material (zs_material): each colour three integers 0..255
    or three floats 0..1, as arrays are read (so (1, 0, 0) is nearly black
    and (1.0, 0, 0) red); alpha a number 0..1.  The defaults
    are zs_material_default's (mid grey, opaque, no highlight,
    double-sided), so Material(color=(1.0, 1.0, 1.0)) is what an MTL
    `Kd 1 1 1` gives."""

    def __init__(self, color=None, alpha=None, specular=None, shininess=None, emissive=None,
                 double_sided=None, texture=None, wrap=("repeat", "repeat"), filter="default",
                 ignore_alpha=False, alpha_cutoff=None):
        m = _lib.load().zs_material_default()
        if color is not None:
            m.base[0:3] = _colour("material.color", color, 4)[:3]
        if alpha is not None:
            a = _number("material.alpha", alpha)
            if not 0.0 <= a <= 1.0:
                raise ValueError("material.alpha: expected 0 .. 1, got %r" % (alpha,))
            m.base[3] = _colour("material.alpha", [a] * 3, 3)[0]
        if specular is not None:
            m.specular[:] = _colour("material.specular", specular, 3)
        if emissive is not None:
            m.emissive[:] = _colour("material.emissive", emissive, 3)
        if shininess is not None:
            if isinstance(shininess, bool) or not isinstance(shininess, numbers.Real) or \
                    not (0 <= shininess <= _lib.ZS_MAX_SHININESS):
                raise ValueError("material.shininess: expected 0 .. %d, got %r"
                                 % (_lib.ZS_MAX_SHININESS, shininess))
            # as MTL's Ns is read
            m.shininess = int(math.floor(shininess + 0.5))
        if double_sided is not None:
            m.double_sided = _flag("material.double_sided", double_sided)
        if isinstance(wrap, str):
            wrap = (wrap, wrap)
        for k, w in enumerate(tuple(wrap)[:2]):
            if w not in _lib.WRAPS:
                raise ValueError("material.wrap: expected %s, got %r"
                                 % (", ".join(repr(x) for x in _lib.WRAPS), w))
            setattr(m, ("wrap_s", "wrap_t")[k], _lib.WRAPS.index(w))
        if filter not in _lib.FILTERS:
            raise ValueError("material.filter: expected %s, got %r"
                             % (", ".join(repr(x) for x in _lib.FILTERS), filter))
        m.filter = _lib.FILTERS.index(filter)
        m.ignore_alpha = _flag("material.ignore_alpha", ignore_alpha)
        if alpha_cutoff is not None:
            c = _number("material.alpha_cutoff", alpha_cutoff)
            if not (0.0 < c <= 1.0):
                raise ValueError("material.alpha_cutoff: expected above 0 and at most 1, got %r" % c)
            m.alpha_cutoff = max(1, int(math.ceil(255.0 * c)))
        if texture is not None and not isinstance(texture, Texture):
            texture = Texture(texture)
        self.texture = texture
        m.base_texture = texture._ptr if texture is not None else None
        self._c = m

    @property
    def color(self):
        return tuple(self._c.base[0:3])


def _number(name, v):
    if isinstance(v, bool) or not isinstance(v, numbers.Real) or not math.isfinite(v):
        raise ValueError("%s: expected a finite number, got %r" % (name, v))
    return float(v)


def _pointer(a, ctype):
    return a.ctypes.data_as(ctypes.POINTER(ctype)) if a is not None else None


def _corner_of(start):
    """The (face, corner) of the flat corner index i, faces starting at start."""
    def where(i):
        f = int(_numpy().searchsorted(start, i, side="right") - 1)
        return f, int(i - start[f])
    return where


class Mesh:
    """A mesh from arrays, to add to a Scene (or render alone with
    Mesh.render).

    vertices       N x 3 numbers (float64 is handed over as it is)
    faces          M x 3 or M x 4 integers, or a list of polygons of any
                   sizes >= 3, indices 0 .. N - 1
    face_colors    M x 3 (or M x 4, alpha 255), bytes or floats 0..1
    vertex_colors  N x 3 or N x 4 (alpha below 255 is transparency)
    normals        N x 3, per vertex; without them a mesh with colours,
                   uvs or a texture gets normals computed (a crease of
                   60 degrees, as for files)
    uvs            N x 2 texture coordinates, (0, 0) the bottom left
    texture        an H x W x 3/4 uint8 array, a zscan.Image or a Texture
    material       a Material (with a texture and no material: white)
    lines          K x 2 vertex indices; points: K indices (zbuffer mode)
    copy           None: convert arrays that are not already C-contiguous
                   of the library's dtype; False: refuse them (ValueError)

    Anything shaped like a trimesh mesh (.vertices, .faces, and
    .visual.vertex_colors, .visual.uv, .vertex_normals when present) is
    accepted by Mesh.from_trimesh without importing trimesh.
    """

    def __init__(self, vertices, faces=None, face_colors=None, vertex_colors=None, normals=None,
                 uvs=None, texture=None, material=None, lines=None, points=None, copy=None):
        np = _numpy()
        if copy not in (None, False):
            raise ValueError("copy: expected None or False, got %r" % (copy,))
        self.vertices = _array("vertices", vertices, np.float64, 3, copy)
        n = self.vertices.shape[0]
        if n >= 2 ** 31:
            raise ValueError("vertices: %d is more than a mesh holds" % n)
        self.face_start, self.face_vert = self._faces(faces, n, copy)
        m = self.face_start.shape[0] - 1
        self.face_rgb = None
        if face_colors is not None:
            c = _bytes_of_colours("face_colors", face_colors, (3, 4), copy)
            if c.shape[0] != m:
                raise ValueError("face_colors: %d rows for %d faces" % (c.shape[0], m))
            if c.shape[1] == 4 and (c[:, 3] != 255).any():
                i = int(np.argwhere(c[:, 3] != 255)[0][0])
                raise ValueError("face_colors[%d, 3]: alpha %d: a face colour is opaque (give "
                                 "transparency by vertex_colors or the material's alpha)"
                                 % (i, c[i, 3]))
            c = c.astype(np.uint32)
            self.face_rgb = np.ascontiguousarray(c[:, 0] << 16 | c[:, 1] << 8 | c[:, 2])
        self.color = None
        if vertex_colors is not None:
            c = _bytes_of_colours("vertex_colors", vertex_colors, (3, 4), copy)
            if c.shape[0] != n:
                raise ValueError("vertex_colors: %d rows for %d vertices" % (c.shape[0], n))
            if c.shape[1] == 3:
                c = np.concatenate([c, np.full((n, 1), 255, np.uint8)], axis=1)
            self.color = np.ascontiguousarray(c)
        self.normal = None
        if normals is not None:
            self.normal = _array("normals", normals, np.float32, 3, copy)
            if self.normal.shape[0] != n:
                raise ValueError("normals: %d rows for %d vertices" % (self.normal.shape[0], n))
        self.uv = None
        if uvs is not None:
            self.uv = _array("uvs", uvs, np.float32, 2, copy)
            if self.uv.shape[0] != n:
                raise ValueError("uvs: %d rows for %d vertices" % (self.uv.shape[0], n))
        if material is not None and not isinstance(material, Material):
            raise TypeError("material: expected a zscan.Material, got %r" % type(material).__name__)
        if texture is not None:
            if material is None:
                material = Material(color=(255, 255, 255), texture=texture)
            elif material.texture is None:
                raise ValueError("texture: give it to the material (Material(texture=...)) when "
                                 "there is one")
            if self.uv is None:
                raise ValueError("texture: needs uvs, the texture coordinates of the vertices")
        self.material = material
        if material is not None and self.face_rgb is None:
            # the colour flat shading draws, as an OBJ face takes its Kd
            c = material.color
            self.face_rgb = np.full(m, c[0] << 16 | c[1] << 8 | c[2], np.uint32)
        self.line_vert = self._indices("lines", lines, n, 2, copy)
        self.point_vert = self._indices("points", points, n, None, copy)
        if m == 0 and self.line_vert is None and self.point_vert is None:
            raise ValueError("faces: a mesh needs faces, lines or points")
        given = dict(vertices=(self.vertices, vertices), normals=(self.normal, normals),
                     uvs=(self.uv, uvs), faces=(self.face_vert, faces),
                     lines=(self.line_vert, lines), points=(self.point_vert, points))
        # the arrays the caller still holds: _recheck looks at these again
        self._shared = {k for k, (a, v) in given.items()
                        if isinstance(v, np.ndarray) and np.may_share_memory(a, v)}

    @staticmethod
    def _indices(name, value, n, width, copy):
        np = _numpy()
        if value is None:
            return None
        a = _array(name, value, np.int32, width, copy)
        _check_range(name, a, n)
        return a.reshape(-1)

    @staticmethod
    def _faces(faces, n, copy):
        np = _numpy()
        if faces is None:
            return np.zeros(1, np.int32), np.zeros(0, np.int32)
        regular = isinstance(faces, np.ndarray) or (
            len(faces) > 0 and all(hasattr(f, "__len__") and len(f) == len(faces[0]) for f in faces)
        )
        if regular:
            a = _array("faces", faces, np.int32, "polygons", copy)
            k = a.shape[1]
            start = np.arange(0, k * a.shape[0] + 1, k, dtype=np.int32)
            vert = a.reshape(-1)
        else:
            sizes, flat = [], []
            for i, f in enumerate(faces):
                try:
                    f = list(f)
                except TypeError:
                    raise TypeError("faces[%d]: expected a polygon, a sequence of indices, got %r"
                                    % (i, f)) from None
                for j, v in enumerate(f):
                    if isinstance(v, bool) or not isinstance(v, numbers.Integral):
                        raise TypeError("faces[%d][%d]: expected a vertex index, got %r" % (i, j, v))
                sizes.append(len(f))
                flat.extend(f)
            small = [i for i, s in enumerate(sizes) if s < 3]
            if small:
                raise ValueError("faces[%d]: %d corners (at least 3 needed)"
                                 % (small[0], sizes[small[0]]))
            start = np.zeros(len(sizes) + 1, np.int64)
            np.cumsum(sizes, out=start[1:])
            big = np.abs(np.asarray(flat, np.int64)) >= 2 ** 31 if flat else np.zeros(0, bool)
            if big.any():
                i = int(np.argwhere(big)[0][0])
                f = int(np.searchsorted(start, i, side="right") - 1)
                raise ValueError("faces[%d][%d]: vertex %d out of range (%d vertices)"
                                 % (f, i - start[f], flat[i], n))
            vert = np.asarray(flat, np.int32)
            start = start.astype(np.int32)
        _check_range("faces", vert, n, _corner_of(start))
        if start.shape[0] - 1 >= 2 ** 31:
            raise ValueError("faces: more than a mesh holds")
        return start, vert

    @classmethod
    def from_trimesh(cls, mesh, **kw):
        """A Mesh of anything shaped like a trimesh.Trimesh: .vertices and
        .faces, with .visual.vertex_colors (when its .visual.kind is
        'vertex', or it has no kind), .visual.uv and .vertex_normals taken
        when present, unless given in kw."""
        visual = getattr(mesh, "visual", None)
        if visual is not None and "vertex_colors" not in kw and getattr(visual, "kind", "vertex") == "vertex":
            vc = getattr(visual, "vertex_colors", None)
            if vc is not None:
                kw["vertex_colors"] = vc
        if visual is not None and "uvs" not in kw and getattr(visual, "uv", None) is not None:
            kw["uvs"] = visual.uv
        if "normals" not in kw and getattr(mesh, "vertex_normals", None) is not None:
            kw["normals"] = mesh.vertex_normals
        return cls(mesh.vertices, mesh.faces, **kw)

    def _recheck(self):
        """The values checked again where the arrays are the caller's own
        (handed over without a copy): one changed since the Mesh was made
        is named as its argument, not as the library's field."""
        after = " (changed since the Mesh was made)"
        shared = self._shared
        for name, a in (("vertices", self.vertices), ("normals", self.normal), ("uvs", self.uv)):
            if name in shared:
                _check_finite(name, a, after)
        n = self.vertices.shape[0]
        if "faces" in shared:
            _check_range("faces", self.face_vert, n, _corner_of(self.face_start), after)
        if "lines" in shared:
            _check_range("lines", self.line_vert, n, lambda i: (i // 2, i % 2), after)
        if "points" in shared:
            _check_range("points", self.point_vert, n, None, after)

    def _c(self):
        """The zs_mesh over this mesh's arrays (valid while the mesh is)."""
        self._recheck()
        m = _lib.zs_mesh()
        m.pos = _pointer(self.vertices, ctypes.c_double)
        m.nverts = self.vertices.shape[0]
        m.face_start = _pointer(self.face_start, ctypes.c_int32)
        m.face_vert = _pointer(self.face_vert, ctypes.c_int32)
        m.nfaces = self.face_start.shape[0] - 1
        m.face_rgb = _pointer(self.face_rgb, ctypes.c_uint32)
        m.nattrs = m.nverts if any(a is not None for a in (self.normal, self.color, self.uv)) else 0
        m.normal = _pointer(self.normal, ctypes.c_float)
        m.color = _pointer(self.color, ctypes.c_uint8)
        m.uv = _pointer(self.uv, ctypes.c_float)
        if self.material is not None:
            self._mat = (_lib.zs_material * 1)(self.material._c)
            m.materials = self._mat
            m.nmaterials = 1
        if self.line_vert is not None:
            m.line_vert = _pointer(self.line_vert, ctypes.c_int32)
            m.nlines = self.line_vert.shape[0] // 2
        if self.point_vert is not None:
            m.point_vert = _pointer(self.point_vert, ctypes.c_int32)
            m.npoints = self.point_vert.shape[0]
        return m

    def __repr__(self):
        return "<zscan.Mesh %d vertices, %d faces>" % (self.vertices.shape[0],
                                                       self.face_start.shape[0] - 1)


class Light:
    """A light (zs_light): kind 'directional', 'point', 'spot' or 'ambient';
    color linear RGB >= 0; position (point, spot) and direction
    (directional, spot: the way the light travels); inner and outer half
    angles in degrees (spot); eye_space: position and direction in the
    camera's coordinates; shadow: casts shadows (directional, spot)."""

    def __init__(self, kind, color=(1.0, 1.0, 1.0), position=(0.0, 0.0, 0.0),
                 direction=(0.0, 0.0, -1.0), inner=20.0, outer=30.0, eye_space=False,
                 shadow=False):
        if kind not in _lib.LIGHT_KINDS:
            raise ValueError("light kind: expected %s, got %r"
                             % (", ".join(repr(k) for k in _lib.LIGHT_KINDS), kind))
        c = _lib.zs_light()
        c.kind = _lib.LIGHT_KINDS.index(kind)
        for field, v in (("color", color), ("position", position), ("direction", direction)):
            t = tuple(v)
            if len(t) != 3:
                raise ValueError("light %s: expected three numbers, got %r" % (field, v))
            getattr(c, field)[:] = [_number("light " + field, x) for x in t]
        c.inner_deg = _number("light inner", inner)
        c.outer_deg = _number("light outer", outer)
        c.eye_space = _flag("light eye_space", eye_space)
        c.shadow = _flag("light shadow", shadow)
        self.kind = kind
        self._c = c

    def __repr__(self):
        return "<zscan.Light %s>" % self.kind
