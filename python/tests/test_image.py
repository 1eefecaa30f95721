"""zscan.Image: .array, .rgb and .save() agree with the PNG (read back by
the library and by a decoder here), with the command's PNG, and with the
documented hash; the ctypes structs mirror the header."""

import ctypes
import os
import re
import struct
import sys
import zlib

import pytest

import zscan
from zscan import _lib
from conftest import DATA_DIR, SOURCE_DIR

MODEL = os.path.join(DATA_DIR, "scenes", "interpenetrate.obj")


def decode_png(path):
    """(width, height, rgb bytes) of an 8-bit RGB PNG, decoded here without
    the library: row 0 is the PNG's first row, the top."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, ihdr = 8, b"", None
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
    w, h, depth, ctype = ihdr[:4]
    assert (depth, ctype) == (8, 2), "not 8-bit RGB"
    raw = zlib.decompress(idat)
    stride, bpp = 3 * w, 3
    out, prev = bytearray(), bytearray(stride)
    for y in range(h):
        ftype = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if ftype == 1:
                line[i] = (line[i] + a) & 255
            elif ftype == 2:
                line[i] = (line[i] + b) & 255
            elif ftype == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif ftype == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
            else:
                assert ftype == 0
        out += line
        prev = line
    return w, h, bytes(out)


def fnv1a(width, height, rgb):
    h = 0xCBF29CE484222325
    for byte in struct.pack("<II", width, height) + rgb:
        h = ((h ^ byte) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return "%016x" % h


@pytest.fixture(scope="module")
def image():
    return zscan.render(MODEL, size=(64, 48), eye=(6, 5, 9))


def test_array_shape_dtype_and_the_pngs_pixels(image, tmp_path):
    np = pytest.importorskip("numpy")
    a = image.array
    assert a.shape == (48, 64, 3)
    assert a.dtype == np.uint8
    png = tmp_path / "im.png"
    image.save(png)
    back = zscan.read_png(png)                  # through zs_png_read
    assert (back.width, back.height) == (64, 48)
    assert a.tobytes() == back.rgb == image.rgb
    assert decode_png(png) == (64, 48, image.rgb)   # and without the library
    assert back.hash == image.hash
    # not one colour: the comparison means something
    assert len(np.unique(a.reshape(-1, 3), axis=0)) > 3


def test_pixels_are_rows_from_the_top_in_rgb_order(image):
    np = pytest.importorskip("numpy")
    a = image.array
    for x, y in ((0, 0), (63, 0), (0, 47), (31, 20), (40, 30)):
        assert tuple(int(c) for c in a[y, x]) == image.pixel(x, y)
        i = 3 * (y * 64 + x)
        assert image.pixel(x, y) == tuple(image.rgb[i:i + 3])


def test_png_is_the_commands(cli, image, tmp_path):
    mine, theirs = tmp_path / "mine.png", tmp_path / "cli.png"
    image.save(mine)
    r = cli(MODEL, "--size", "64x48", "--eye", "6,5,9", out=theirs)
    assert r.returncode == 0, r.stderr
    assert zscan.read_png(theirs).rgb == image.rgb
    assert mine.read_bytes() == theirs.read_bytes()
    assert r.stats["image_hash"] == image.hash


def test_hash_is_fnv1a_of_size_and_pixels(image):
    assert image.hash == fnv1a(64, 48, image.rgb)
    assert image.hash_int == int(image.hash, 16)
    made = zscan.Image(3, 2, bytes(range(18)))
    assert made.hash == fnv1a(3, 2, bytes(range(18)))


def test_array_is_a_copy(image):
    pytest.importorskip("numpy")
    a = image.array
    a[:] = 7
    assert image.array.tobytes() == image.rgb != a.tobytes()


def test_array_without_numpy(image, monkeypatch):
    monkeypatch.setitem(sys.modules, "numpy", None)  # import numpy fails
    with pytest.raises(ImportError, match="needs numpy"):
        image.array
    assert len(image.rgb) == 64 * 48 * 3


def test_image_made_saved_and_read(tmp_path):
    rgb = bytes([255, 0, 0, 0, 255, 0, 0, 0, 255, 1, 2, 3])
    im = zscan.Image(2, 2, rgb)
    p = tmp_path / "four.png"
    im.save(str(p))
    back = zscan.read_png(p)
    assert back == im and back.rgb == rgb
    assert decode_png(p) == (2, 2, rgb)
    with pytest.raises(ValueError):
        zscan.Image(2, 2, rgb[:-1])


def test_diff_counts_and_picture():
    a = zscan.Image(3, 1, bytes([10, 10, 10, 200, 100, 50, 0, 0, 0]))
    b = zscan.Image(3, 1, bytes([10, 10, 10, 190, 100, 80, 0, 0, 0]))
    d = zscan.diff(a, b)
    assert (d.differing, d.total, d.max_channel_diff) == (1, 3, 30)
    assert d.image.pixel(1, 0) == (255, 0, 0)
    assert d.image.pixel(0, 0) != (255, 0, 0)
    assert not zscan.diff(a, a) and zscan.diff(a, a).total == 3
    with pytest.raises(zscan.Error) as e:
        zscan.diff(a, zscan.Image(1, 1, b"\0\0\0"))
    assert e.value.status == "ZS_ERR_ARG"


def test_png_errors(tmp_path):
    with pytest.raises(zscan.Error) as e:
        zscan.read_png(tmp_path / "missing.png")
    assert e.value.status == "ZS_ERR_IO" and "missing.png" in str(e.value)
    junk = tmp_path / "junk.png"
    junk.write_bytes(b"not a png")
    with pytest.raises(zscan.Error):
        zscan.read_png(junk)
    with pytest.raises(zscan.Error) as e:
        zscan.Image(1, 1, b"\0\0\0").save(tmp_path / "no" / "dir" / "x.png")
    assert "x.png" in str(e.value)


def test_stats_are_the_frames_counters(image):
    assert set(image.stats) == {n for n, _ in _lib.zs_raster_stats._fields_}
    assert image.stats["pixels_written"] > 0
    assert zscan.Image(1, 1, b"\0\0\0").stats is None


# ---- the ctypes structs against the header ----

CTYPE_OF = {
    "int": ctypes.c_int, "double": ctypes.c_double, "uint64_t": ctypes.c_uint64,
    "uint32_t": ctypes.c_uint32, "zs_algo": ctypes.c_int, "zs_shade": ctypes.c_int,
    "zs_status": ctypes.c_int, "zs_filter": ctypes.c_int, "const zs_light": _lib.zs_light,
    "zs_point_shape": ctypes.c_int, "int32_t": ctypes.c_int32, "uint8_t": ctypes.c_uint8,
    "uint16_t": ctypes.c_uint16, "float": ctypes.c_float, "const zs_material": _lib.zs_material,
    "zs_wrap": ctypes.c_int, "zs_span_fill": ctypes.c_int, "int64_t": ctypes.c_int64,
    "const uint32_t": ctypes.c_uint32, "const float": ctypes.c_float,
}
# pointers to opaque types are void pointers here
OPAQUE = {"const zs_texture"}


def header_fields(struct_name):
    """[(field, C type, array length or None)] of a typedef struct in the
    public headers, in order."""
    text = ""
    for h in ("zscan.h", "error.h", "clock.h"):
        with open(os.path.join(SOURCE_DIR, "include", "zscan", h)) as f:
            text += f.read()
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    m = re.search(r"typedef struct %s \{(.*?)\} %s;" % (struct_name, struct_name), text, re.S) or \
        re.search(r"\nstruct %s \{(.*?)\};" % struct_name, text, re.S)
    assert m, struct_name
    out = []
    for decl in m.group(1).split(";"):
        decl = decl.strip()
        if not decl:
            continue
        t, names = re.match(r"((?:const\s+)?\w+(?:\s*\*)*)\s+(.*)", decl).groups()
        for n in names.split(","):
            n = n.strip()
            pointer = n.startswith("*")
            n = n.lstrip("*").strip()
            am = re.match(r"(\w+)\s*\[(\w+)\]", n)
            name, count = (am.group(1), am.group(2)) if am else (n, None)
            out.append((name, t.strip() + ("*" if pointer else ""), count))
    return out


@pytest.mark.parametrize("name", ["zs_render_opts", "zs_image", "zs_error", "zs_diff_result",
                                  "zs_load_opts", "zs_raster_stats", "zs_mesh", "zs_material",
                                  "zs_device_config", "zs_row", "zs_clock_params",
                                  "zs_clock_stats"])
def test_structs_mirror_the_header(name):
    ours = getattr(_lib, name)._fields_
    theirs = header_fields(name)
    assert [f[0] for f in ours] == [f[0] for f in theirs]
    for (fname, ctype), (_, ctype_c, count) in zip(ours, theirs):
        if ctype_c.endswith("*") and ctype_c.rstrip("*").strip() in OPAQUE:
            assert ctype is ctypes.c_void_p, fname
        elif ctype_c.endswith("*"):
            assert issubclass(ctype, ctypes._Pointer), fname
            assert ctype._type_ is CTYPE_OF[ctype_c.rstrip("*").strip()], fname
        elif count is not None:
            assert issubclass(ctype, ctypes.Array), fname
            want = _lib.ZS_ERROR_MSG_MAX if count == "ZS_ERROR_MSG_MAX" else int(count)
            assert ctype._length_ == want, fname
            assert ctype._type_ is (ctypes.c_char if ctype_c == "char" else CTYPE_OF[ctype_c])
        else:
            assert ctype is CTYPE_OF[ctype_c], fname


@pytest.mark.skipif(ctypes.sizeof(ctypes.c_void_p) != 8 or ctypes.sizeof(ctypes.c_int) != 4,
                    reason="offsets measured on an LP64 ABI")
def test_struct_sizes_and_offsets_are_the_c_compilers():
    # as offsetof and sizeof print them on x86-64 Linux (gcc 12)
    o = _lib.zs_render_opts
    assert ctypes.sizeof(o) == 224
    assert [getattr(o, f).offset for f in ("algo", "hidden_line", "has_up", "eye", "target",
                                           "up", "fovy", "znear", "zfar", "filter", "lights",
                                           "nlights", "shadows", "shadow_size",
                                           "has_shadow_bias", "shadow_bias", "samples",
                                           "supersample", "wireframe")] == \
        [8, 24, 36, 40, 64, 88, 112, 120, 128, 136, 144, 152, 156, 160, 164, 168, 184, 188, 192]
    assert ctypes.sizeof(_lib.zs_light) == 104
    assert ctypes.sizeof(_lib.zs_image) == 16 and _lib.zs_image.rgb.offset == 8
    assert ctypes.sizeof(_lib.zs_error) == 516 and _lib.zs_error.msg.offset == 4
    assert ctypes.sizeof(_lib.zs_diff_result) == 24
    assert _lib.zs_diff_result.max_channel_diff.offset == 16
    assert ctypes.sizeof(_lib.zs_raster_stats) == 96
    assert ctypes.sizeof(_lib.zs_mesh) == 176
    assert [_lib.zs_mesh.corner_attr.offset, _lib.zs_mesh.materials.offset,
            _lib.zs_mesh.prim_id.offset] == [64, 104, 168]
    assert ctypes.sizeof(_lib.zs_material) == 40
    assert [_lib.zs_material.base_texture.offset, _lib.zs_material.wrap_s.offset,
            _lib.zs_material.filter.offset, _lib.zs_material.ignore_alpha.offset,
            _lib.zs_material.alpha_cutoff.offset] == [16, 24, 32, 36, 37]
    assert ctypes.sizeof(_lib.zs_load_opts) == 8
    assert _lib.zs_load_opts.skip_missing_textures.offset == 4
