"""The pytest plugin zscan.pytest_plugin, run on test files of its own with
pytester: a missing golden fails and says how to make it, --zscan-update
writes it, a changed image fails with the counts and leaves the actual and
diff images."""

import os
import re

import zscan
from conftest import DATA_DIR

MODEL = os.path.join(DATA_DIR, "scenes", "interpenetrate.obj")
SIZE = (64, 48)

TEST_FILE = """
import zscan

def test_view(zscan_golden):
    zscan_golden(zscan.render({model!r}, size={size!r}, eye={eye!r}), "view")
"""


def write_test(pytester, eye=(6, 5, 9), size=SIZE):
    return pytester.makepyfile(test_view=TEST_FILE.format(model=MODEL, size=size, eye=eye))


def run(pytester, *args):
    return pytester.runpytest("-p", "zscan.pytest_plugin", *args)


def test_missing_then_update_then_pass(pytester):
    write_test(pytester)
    golden = pytester.path / "golden" / "view.png"

    r = run(pytester)
    r.assert_outcomes(failed=1)
    out = r.stdout.str()
    assert "no golden image" in out and "--zscan-update" in out
    assert str(golden) in out
    assert not golden.exists()

    r = run(pytester, "--zscan-update")
    r.assert_outcomes(passed=1)
    assert golden.exists()
    want = zscan.render(MODEL, size=SIZE, eye=(6, 5, 9))
    assert zscan.read_png(golden) == want

    r = run(pytester)
    r.assert_outcomes(passed=1)
    # a pass leaves nothing beside the golden but the golden and its version
    assert sorted(os.listdir(pytester.path / "golden")) == ["PIXEL-VERSION", "view.png"]
    assert (pytester.path / "golden" / "PIXEL-VERSION").read_text() == "%d\n" % zscan.pixel_version()


def test_a_changed_image_fails_with_counts_and_files(pytester):
    write_test(pytester)
    run(pytester, "--zscan-update").assert_outcomes(passed=1)
    golden_dir = pytester.path / "golden"

    write_test(pytester, eye=(6.5, 5, 9))   # another eye
    r = run(pytester)
    r.assert_outcomes(failed=1)
    out = r.stdout.str()
    old = zscan.render(MODEL, size=SIZE, eye=(6, 5, 9))
    new = zscan.render(MODEL, size=SIZE, eye=(6.5, 5, 9))
    d = zscan.diff(old, new)
    assert d.differing > 0
    m = re.search(r"(\d+) of (\d+) pixels differ from \S+, largest channel difference (\d+)", out)
    assert m, out
    assert tuple(int(g) for g in m.groups()) == (d.differing, d.total, d.max_channel_diff)
    assert "--zscan-update" in out
    actual, diff_png = golden_dir / "view.actual.png", golden_dir / "view.diff.png"
    assert str(actual) in out and str(diff_png) in out
    assert zscan.read_png(actual) == new
    assert zscan.read_png(diff_png) == d.image
    assert zscan.read_png(golden_dir / "view.png") == old   # the golden is kept

    # accepting the change, then passing, clears the actual and diff images
    run(pytester, "--zscan-update").assert_outcomes(passed=1)
    run(pytester).assert_outcomes(passed=1)
    assert sorted(os.listdir(golden_dir)) == ["PIXEL-VERSION", "view.png"]


def test_output_directory(pytester):
    write_test(pytester)
    run(pytester, "--zscan-update").assert_outcomes(passed=1)
    write_test(pytester, eye=(6, 5, 9.5))
    r = run(pytester, "--zscan-output", "report")
    r.assert_outcomes(failed=1)
    assert sorted(os.listdir(pytester.path / "report")) == ["view.actual.png", "view.diff.png"]
    assert sorted(os.listdir(pytester.path / "golden")) == ["PIXEL-VERSION", "view.png"]


def test_goldens_of_an_older_pixel_version_say_what_changed(pytester):
    write_test(pytester)
    run(pytester, "--zscan-update").assert_outcomes(passed=1)
    version = pytester.path / "golden" / "PIXEL-VERSION"
    write_test(pytester, eye=(6.5, 5, 9))
    r = run(pytester)
    r.assert_outcomes(failed=1)
    assert "pixel version" not in r.stdout.str()   # the same version: no word of it
    version.write_text("1\n")
    r = run(pytester)
    r.assert_outcomes(failed=1)
    out = " ".join(r.stdout.str().split())
    ours = zscan.pixel_version()
    assert "the goldens were made with pixel version 1; this zscan draws version %d, which " \
        "changed:" % ours in out, out
    for v in range(2, ours + 1):
        assert " ".join(("%d: %s" % (v, zscan.pixel_changes(v))).split()) in out, out
    assert zscan.pixel_changes(0) is None and zscan.pixel_changes(ours + 1) is None


def test_another_size_fails_with_both_sizes(pytester):
    write_test(pytester)
    run(pytester, "--zscan-update").assert_outcomes(passed=1)
    write_test(pytester, size=(32, 24))
    r = run(pytester)
    r.assert_outcomes(failed=1)
    r.stdout.fnmatch_lines(["*the image is 32x24, the golden * is 64x48*"])
    assert (pytester.path / "golden" / "view.actual.png").exists()


def test_bad_name_and_options_listed(pytester):
    pytester.makepyfile(test_bad="""
import pytest, zscan

def test_bad(zscan_golden):
    with pytest.raises(ValueError):
        zscan_golden(zscan.Image(1, 1, b"abc"), "../escape")
    with pytest.raises(TypeError):
        zscan_golden(b"abc", "x")
""")
    run(pytester).assert_outcomes(passed=1)
    r = run(pytester, "--help")
    r.stdout.fnmatch_lines(["*--zscan-update*", "*--zscan-output*"])
