"""zscan.render() against the command: the same image hash, counters and
errors as `zscan render ... --stats` for every model of tests/data and for
option combinations."""

import math
import os
import re
import subprocess

import pytest

import zscan
from conftest import CLI, CLI_ENV, DATA_DIR, PYTHON_DIR, model_files

SIZE = (64, 48)
STAT_KEYS = ("draws", "polygons_in", "polygons_outside", "polygons_clipped",
             "polygons_culled_back", "polygons_degenerate", "polygons_rasterized", "spans",
             "pixels_tested", "pixels_written")


def data(name):
    return os.path.join(DATA_DIR, name)


def test_every_model_of_tests_data_is_found():
    models = model_files()
    assert len(models) >= 40
    for suffix in (".obj", ".ply", ".stl", ".off", ".gltf"):
        assert any(m.endswith(suffix) for m in models), suffix


def check_same(cli_result, render):
    """render() -> Image; the command's result and the binding's agree."""
    if cli_result.returncode != 0:
        assert cli_result.error, cli_result.stderr
        with pytest.raises(zscan.Error) as e:
            render()
        assert str(e.value) == cli_result.error
        return None
    im = render()
    st = cli_result.stats
    assert (im.width, im.height) == (st["width"], st["height"])
    assert im.hash == st["image_hash"]
    for k in STAT_KEYS:
        assert im.stats[k] == st[k], k
    return im


@pytest.mark.parametrize("model", model_files())
def test_model_hash_matches_cli(cli, model):
    path = data(model)
    r = cli(path, "--size", "%dx%d" % SIZE)
    check_same(r, lambda: zscan.render(path, size=SIZE))


def test_models_rendered_and_refused(cli):
    # the comparison above is not vacuous: many models render, many are refused
    codes = [cli(data(m), "--size", "%dx%d" % SIZE).returncode for m in model_files()]
    assert codes.count(0) >= 10
    assert len(codes) - codes.count(0) >= 10


INPUTS = {
    "colors": data("obj/colors.obj"),
    "inter": data("scenes/interpenetrate.obj"),
    "sphere": data("scenes/sphere_ell.obj"),
    "gltf": data("models/two_nodes.gltf"),
    "cubes": "builtin:cubes",
    "teapots": "builtin:teapots",
}

# (input, render() keywords, the command's options)
COMBOS = [
    ("colors", dict(eye=(3, 2, 4)), ["--eye", "3,2,4"]),
    ("colors", dict(eye=(3, 2, 4), target=(0.5, 0.25, 0)), ["--eye", "3,2,4", "--target", "0.5,0.25,0"]),
    ("inter", dict(eye=(9, 7, 14), up=(0, 0, 1)), ["--eye", "9,7,14", "--up", "0,0,1"]),
    ("inter", dict(fovy=30), ["--fovy", "30"]),
    ("inter", dict(fovy=90, eye=(1, 2, 9)), ["--fovy", "90", "--eye", "1,2,9"]),
    ("sphere", dict(near=0.5), ["--near", "0.5"]),
    ("sphere", dict(far=7.5), ["--far", "7.5"]),
    ("sphere", dict(near=2, far=6), ["--near", "2", "--far", "6"]),
    ("inter", dict(algo="scanline"), ["--algo", "scanline"]),
    ("inter", dict(algo="depthsort"), ["--algo", "depthsort"]),
    ("inter", dict(shade="id"), ["--shade", "id"]),
    ("inter", dict(shade="depth"), ["--shade", "depth"]),
    ("inter", dict(shade="overdraw"), ["--shade", "overdraw"]),
    ("inter", dict(algo="scanline", shade="depth"), ["--algo", "scanline", "--shade", "depth"]),
    ("inter", dict(style="hidden-line"), ["--style", "hidden-line"]),
    ("inter", dict(style="solid"), ["--style", "solid"]),
    ("cubes", dict(style="hidden-line", eye=(5, 4, 9)), ["--style", "hidden-line", "--eye", "5,4,9"]),
    ("teapots", dict(threads=3), ["--threads", "3"]),
    ("teapots", dict(cull_back=True), ["--cull-back"]),
    ("teapots", dict(shade="id", algo="depthsort"), ["--shade", "id", "--algo", "depthsort"]),
    ("gltf", dict(eye=(2, 3, 5), fovy=60, near=1, far=20, shade="depth"),
     ["--eye", "2,3,5", "--fovy", "60", "--near", "1", "--far", "20", "--shade", "depth"]),
    ("teapots", dict(shadows=True), ["--shadows"]),
    ("teapots", dict(shadows=True, algo="scanline", threads=2),
     ["--shadows", "--algo", "scanline", "--threads", "2"]),
    ("teapots", dict(samples=4), ["--samples", "4"]),
    ("inter", dict(samples=8, supersample=True), ["--samples", "8", "--supersample"]),
    ("cubes", dict(style="solid+wireframe", shade="phong"),
     ["--style", "solid+wireframe", "--shade", "phong"]),
]


@pytest.mark.parametrize(
    "name,kw,args", COMBOS,
    ids=["%s-%s" % (c[0], "-".join("%s=%s" % i for i in sorted(c[1].items()))) for c in COMBOS])
def test_options_match_cli(cli, name, kw, args):
    size = (96, 72)
    r = cli(INPUTS[name], "--size", "%dx%d" % size, *args)
    # glTF needs a library built with assimp; without it both refuse the file
    assert r.returncode == 0 or name == "gltf", r.stderr
    check_same(r, lambda: zscan.render(INPUTS[name], size=size, **kw))


def test_options_change_the_image():
    base = zscan.render(INPUTS["inter"], size=(96, 72))
    hashes = {base.hash}
    for kw in (dict(eye=(9, 7, 14)), dict(fovy=30), dict(shade="id"), dict(style="hidden-line"),
               dict(near=2, far=6)):
        hashes.add(zscan.render(INPUTS["inter"], size=(96, 72), **kw).hash)
    assert len(hashes) == 6


def test_default_size_is_the_commands(cli):
    r = cli("builtin:cubes")
    im = check_same(r, lambda: zscan.render("builtin:cubes"))
    assert (im.width, im.height) == (1024, 768)


def test_none_input_is_builtin_default():
    a = zscan.render(None, size=(40, 30))
    b = zscan.render("builtin:default", size=(40, 30))
    assert a.hash == b.hash


def test_allow_empty(cli):
    path = data("bad_scene/nofaces.obj")
    with pytest.raises(zscan.Error, match="no faces"):
        zscan.render(path, size=(8, 8))
    r = cli(path, "--size", "8x8", "--allow-empty")
    check_same(r, lambda: zscan.render(path, size=(8, 8), allow_empty=True))


def test_threads_give_the_same_image():
    one = zscan.render("builtin:teapots", size=(120, 90), threads=1)
    four = zscan.render("builtin:teapots", size=(120, 90), threads=4)
    assert one.hash == four.hash and one.rgb == four.rgb


# Values the command refuses: the binding refuses them too, with a
# zscan.Error; where the library judges them for both, with the same
# message (the command checks a camera option's range itself, naming it).
REFUSED = [
    (dict(fovy=200), ["--fovy", "200"], False),
    (dict(fovy=-5), ["--fovy", "-5"], False),
    (dict(fovy=0), ["--fovy", "0"], False),
    (dict(near=0), ["--near", "0"], False),
    (dict(near=-1), ["--near", "-1"], False),
    (dict(near=5, far=2), ["--near", "5", "--far", "2"], False),
    (dict(far=0), ["--far", "0"], False),
    (dict(eye=(1, 1, 1), target=(1, 1, 1)), ["--eye", "1,1,1", "--target", "1,1,1"], True),
    (dict(up=(0, 0, 0)), ["--up", "0,0,0"], False),
    (dict(size=(20000, 10)), ["--size", "20000x10"], False),
    (dict(size=(0, 5)), ["--size", "0x5"], False),
    (dict(threads=65), ["--threads", "65"], False),
    (dict(threads=0), ["--threads", "0"], False),
    (dict(style="hidden-line", algo="scanline"), ["--style", "hidden-line", "--algo", "scanline"], False),
    (dict(style="hidden-line", shade="id"), ["--style", "hidden-line", "--shade", "id"], False),
]


@pytest.mark.parametrize("kw,args,same_message", REFUSED,
                         ids=[" ".join(r[1]) for r in REFUSED])
def test_refused_options(cli, kw, args, same_message):
    path = data("obj/colors.obj")
    size_args = [] if "size" in kw else ["--size", "32x24"]
    r = cli(path, *size_args, *args)
    assert r.returncode != 0
    kw = dict(kw)
    kw.setdefault("size", (32, 24))
    with pytest.raises(zscan.Error) as e:
        zscan.render(path, **kw)
    assert e.value.status == "ZS_ERR_ARG" or e.value.status == "ZS_ERR_LIMIT"
    if same_message:
        assert str(e.value) == r.error


@pytest.mark.parametrize("kw,exc", [
    (dict(algo="bogus"), ValueError),
    (dict(shade="glossy"), ValueError),
    (dict(style="wireframe"), ValueError),
    (dict(size="64x48"), TypeError),
    (dict(size=(64,)), TypeError),
    (dict(size=(64.5, 48)), TypeError),
    (dict(eye=(1, 2)), ValueError),
    (dict(eye=5), TypeError),
    (dict(eye=(math.nan, 0, 0)), ValueError),
    (dict(fovy=math.inf), ValueError),
    (dict(near="far"), TypeError),
    (dict(threads=1.5), TypeError),
    (dict(threads=True), TypeError),
])
def test_bad_arguments(kw, exc):
    with pytest.raises(exc):
        zscan.render(data("obj/colors.obj"), **kw)


def test_error_carries_code_and_status():
    with pytest.raises(zscan.Error) as e:
        zscan.render(data("no/such/file.obj"), size=(8, 8))
    assert e.value.status == "ZS_ERR_IO"
    assert e.value.code == 2
    assert "no/such/file.obj" in str(e.value)
    assert "\n" not in str(e.value)


def test_scene_renders_again_and_counts(cli):
    path = data("scenes/interpenetrate.obj")
    r = cli(path, "--size", "64x48")
    with zscan.load(path) as scene:
        assert scene.objects == r.stats["objects"]
        assert scene.faces == r.stats["faces"]
        a = scene.render(size=(64, 48))
        b = scene.render(size=(64, 48), shade="id")
        c = scene.render(size=(64, 48))
    assert a.hash == c.hash == r.stats["image_hash"]
    assert b.hash != a.hash
    with pytest.raises(ValueError):
        scene.render(size=(8, 8))


def test_version_is_the_librarys_and_the_packages(cli):
    out = subprocess.run([CLI, "--version"], capture_output=True, text=True, env=CLI_ENV).stdout
    m = re.search(r"library (\d+\.\d+\.\d+)", out)
    assert m, out
    assert zscan.__version__ == m.group(1)
    with open(os.path.join(PYTHON_DIR, "pyproject.toml")) as f:
        v = re.search(r'^version = "([^"]+)"', f.read(), re.M).group(1)
    assert v == zscan.__version__
    header = os.path.join(os.path.dirname(PYTHON_DIR), "include", "zscan", "zscan.h")
    with open(header) as f:
        h = re.search(r'#define ZSCAN_VERSION_STRING "([^"]+)"', f.read()).group(1)
    assert h == v
