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


# ---- the zscan_compare marker, pytest-mpl's way ----

MARKED = """
import pytest
import zscan

@pytest.mark.zscan_compare
def test_view():
    return zscan.render({model!r}, size={size!r}, eye={eye!r})

@pytest.mark.zscan_compare(filename="still.png")
@pytest.mark.parametrize("n", [2, 3])
def test_cubes(n):
    return zscan.render("builtin:cubes?n=%d" % n, size={size!r})
"""


def write_marked(pytester, eye=(6, 5, 9)):
    return pytester.makepyfile(test_marked=MARKED.format(model=MODEL, size=SIZE, eye=eye))


def accept_command(out):
    m = re.search(r"to accept it: (pytest .*?)(?: \(the |$)", out, re.M)
    assert m, out
    return m.group(1).split()


def test_marker_baselines_generated_compared_and_accepted(pytester):
    write_marked(pytester)
    r = run(pytester)
    r.assert_outcomes(failed=3)
    out = r.stdout.str()
    assert "no baseline image" in out and str(pytester.path / "baseline" / "test_view.png") in out
    cmd = accept_command(out)
    assert cmd[-1] == "--zscan-generate-path=baseline"

    # the command the failure gives, for the whole file: writes the baselines
    run(pytester, "--zscan-generate-path=baseline").assert_outcomes(passed=3)
    assert sorted(os.listdir(pytester.path / "baseline")) == ["still.png", "test_view.png"]
    assert zscan.read_png(pytester.path / "baseline" / "test_view.png") == \
        zscan.render(MODEL, size=SIZE, eye=(6, 5, 9))
    # run twice: passes twice, and no warning about a test returning a value
    for _ in range(2):
        r = run(pytester, "-W", "error::pytest.PytestReturnNotNoneWarning", "-k", "view")
        r.assert_outcomes(passed=1)


def test_marker_change_fails_with_results_and_summary(pytester):
    write_marked(pytester)
    run(pytester, "--zscan-generate-path=baseline", "-k", "view").assert_outcomes(passed=1)
    write_marked(pytester, eye=(6.5, 5, 9))
    r = run(pytester, "-k", "view", "--zscan-results-path=results", "--zscan-summary=html",
            "--zscan-summary=json")
    r.assert_outcomes(failed=1)
    out = r.stdout.str()
    assert re.search(r"zscan_compare test_view: \d+ of 3072 pixels differ", out)
    results = pytester.path / "results"
    one = results / "test_marked.py__test_view"
    assert sorted(os.listdir(one)) == ["test_view-baseline.png", "test_view-diff.png",
                                       "test_view-result.png"]
    assert zscan.read_png(one / "test_view-result.png") == \
        zscan.render(MODEL, size=SIZE, eye=(6.5, 5, 9))
    page = (results / "summary.html").read_text()
    for name in ("test_view-baseline.png", "test_view-result.png", "test_view-diff.png"):
        assert 'src="test_marked.py__test_view/%s"' % name in page
    assert "1 tests, 1 failed" in page
    import json
    rows = json.loads((results / "summary.json").read_text())
    assert [(r["key"], r["status"]) for r in rows] == [("test_marked.py::test_view", "failed")]
    assert "summary of 1 marked tests in %s" % results in out
    # accepting it as the message says makes it pass
    cmd = accept_command(out)
    assert cmd[0] == "pytest" and cmd[-1] == "--zscan-generate-path=baseline"
    run(pytester, *cmd[1:]).assert_outcomes(passed=1)
    run(pytester, "-k", "view").assert_outcomes(passed=1)


def test_hash_library_instead_of_images(pytester):
    write_marked(pytester)
    lib = pytester.path / "hashes.json"
    run(pytester, "--zscan-generate-hash-library=hashes.json").assert_outcomes(passed=3)
    import json
    hashes = json.loads(lib.read_text())
    assert hashes == {
        "test_marked.py::test_view": zscan.render(MODEL, size=SIZE, eye=(6, 5, 9)).hash,
        "test_marked.py::test_cubes[2]": zscan.render("builtin:cubes?n=2", size=SIZE).hash,
        "test_marked.py::test_cubes[3]": zscan.render("builtin:cubes?n=3", size=SIZE).hash,
        "zscan-pixel-version": zscan.pixel_version(),
    }
    assert not (pytester.path / "baseline").exists()  # hashes alone, no images
    for _ in range(2):
        run(pytester, "--zscan-hash-library=hashes.json").assert_outcomes(passed=3)

    write_marked(pytester, eye=(6.5, 5, 9))
    r = run(pytester, "--zscan-hash-library=hashes.json", "--zscan-results-path=res",
            "--zscan-summary=html")
    r.assert_outcomes(passed=2, failed=1)
    out = r.stdout.str()
    new = zscan.render(MODEL, size=SIZE, eye=(6.5, 5, 9)).hash
    assert "zscan_compare test_view: hash %s, the library %s has %s" % (
        new, lib, hashes["test_marked.py::test_view"]) in out
    assert (pytester.path / "res" / "summary.html").exists()
    cmd = accept_command(out)
    assert cmd[-1] == "--zscan-generate-hash-library=hashes.json"
    run(pytester, *cmd[1:]).assert_outcomes(passed=1)
    updated = json.loads(lib.read_text())
    assert updated["test_marked.py::test_view"] == new
    assert updated["test_marked.py::test_cubes[2]"] == hashes["test_marked.py::test_cubes[2]"]
    run(pytester, "--zscan-hash-library=hashes.json").assert_outcomes(passed=3)


def test_hash_library_keys_are_test_ids(pytester):
    # two test files of one name in two packages: two keys, neither hiding the other
    for pkg, eye in (("a", (6, 5, 9)), ("b", (6.5, 5, 9))):
        d = pytester.mkpydir(pkg)
        (d / "test_x.py").write_text(MARKED.format(model=MODEL, size=SIZE, eye=eye))
    run(pytester, "--zscan-generate-hash-library=h.json", "-k", "view").assert_outcomes(passed=2)
    import json
    keys = sorted(k for k in json.loads((pytester.path / "h.json").read_text())
                  if k != "zscan-pixel-version")
    assert keys == ["a/test_x.py::test_view", "b/test_x.py::test_view"]
    run(pytester, "--zscan-hash-library=h.json", "-k", "view").assert_outcomes(passed=2)


def test_hash_library_of_another_pixel_version_says_so(pytester):
    write_marked(pytester)
    run(pytester, "--zscan-generate-hash-library=hashes.json").assert_outcomes(passed=3)
    import json
    lib = pytester.path / "hashes.json"
    h = json.loads(lib.read_text())
    h["test_marked.py::test_view"] = "0" * 16
    h["zscan-pixel-version"] = zscan.pixel_version() - 1
    lib.write_text(json.dumps(h))
    r = run(pytester, "--zscan-hash-library=hashes.json", "-k", "view")
    r.assert_outcomes(failed=1)
    v = zscan.pixel_version()
    assert "the hashes were made with pixel version %d; this zscan draws version %d, which " \
           "changed: %d: %s" % (v - 1, v, v, zscan.pixel_changes(v)) in r.stdout.str()
    r = run(pytester, "--zscan-hash-library=missing.json")
    assert r.ret == 4  # pytest's usage error
    assert "--zscan-hash-library: %s: no such file" % (pytester.path / "missing.json") in r.stderr.str()
