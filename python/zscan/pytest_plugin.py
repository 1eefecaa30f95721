"""Golden-image tests for pytest, on zscan's exact images.

Load it with `pytest -p zscan.pytest_plugin` (or installed, through its
pytest11 entry point), then in a test:

    def test_teapot(zscan_golden):
        zscan_golden(zscan.render("teapot.obj", size=(320, 240)), "teapot")

compares the image with golden/teapot.png beside the test file.  zscan's
images are the same bytes on every machine, so the comparison is exact:
on a mismatch the test fails with the number of differing pixels and the
largest channel difference, and writes teapot.actual.png and
teapot.diff.png (zs_image_diff's picture: equal pixels a darkened grey,
differing ones red) beside the golden, or into --zscan-output DIR.

    pytest --zscan-update        writes (or rewrites) the goldens, and
                                 golden/PIXEL-VERSION beside them
    pytest --zscan-output DIR    actual and diff images into DIR

A mismatch against goldens of another pixel version (zscan.pixel_version)
says so, with what changed in the versions since.

The library is loaded only when the fixture is used, so registering this
plugin never breaks a test run that does not use it.
"""

import os
import re

import pytest

_NAME = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.\-]*$")


def pytest_addoption(parser):
    group = parser.getgroup("zscan", "zscan golden images")
    group.addoption(
        "--zscan-update",
        action="store_true",
        default=False,
        help="write the images zscan_golden is given as the new golden images",
    )
    group.addoption(
        "--zscan-output",
        metavar="DIR",
        default=None,
        help="write NAME.actual.png and NAME.diff.png of failing zscan_golden "
        "checks into DIR (default: beside the golden)",
    )


def _output_dir(config, golden_dir):
    out = config.getoption("zscan_output")
    if not out:
        return golden_dir
    return os.path.join(str(config.invocation_params.dir), out)


def _check_name(name):
    if not isinstance(name, str) or not _NAME.match(name) or name.endswith(".png"):
        raise ValueError(
            "zscan_golden: name %r: use letters, digits, '_', '-' and '.', without "
            "a directory or the .png suffix" % (name,)
        )


def _version_note(golden_dir):
    """'' when golden_dir's PIXEL-VERSION is this zscan's, else a sentence
    naming both versions and the changes between."""
    import zscan

    ours = zscan.pixel_version()
    try:
        with open(os.path.join(golden_dir, "PIXEL-VERSION")) as f:
            theirs = int(f.read().split()[0])
    except (OSError, ValueError, IndexError):
        return " (the goldens carry no PIXEL-VERSION: made before zscan kept one?)"
    if theirs == ours:
        return ""
    if theirs > ours:
        return (" (the goldens were made with pixel version %d; this zscan draws version %d, "
                "an older one)" % (theirs, ours))
    changes = "; ".join("%d: %s" % (v, zscan.pixel_changes(v)) for v in range(theirs + 1, ours + 1))
    return (" (the goldens were made with pixel version %d; this zscan draws version %d, "
            "which changed: %s)" % (theirs, ours, changes))


def _remove(path):
    try:
        os.remove(path)
    except FileNotFoundError:
        pass


@pytest.fixture
def zscan_golden(request):
    """zscan_golden(image, name): compares image (a zscan.Image) with
    golden/NAME.png beside the test file; rewrites it under --zscan-update."""
    import zscan

    config = request.config
    test_dir = os.path.dirname(str(request.node.path if hasattr(request.node, "path")
                                   else request.node.fspath))
    golden_dir = os.path.join(test_dir, "golden")
    update = config.getoption("zscan_update")

    def check(image, name):
        __tracebackhide__ = True
        if not isinstance(image, zscan.Image):
            raise TypeError("zscan_golden: expected a zscan.Image, got %r" % (image,))
        _check_name(name)
        golden = os.path.join(golden_dir, name + ".png")
        out_dir = _output_dir(config, golden_dir)
        actual = os.path.join(out_dir, name + ".actual.png")
        diff_png = os.path.join(out_dir, name + ".diff.png")
        if update:
            os.makedirs(golden_dir, exist_ok=True)
            image.save(golden)
            with open(os.path.join(golden_dir, "PIXEL-VERSION"), "w") as f:
                f.write("%d\n" % zscan.pixel_version())
            _remove(actual)
            _remove(diff_png)
            return
        if not os.path.exists(golden):
            os.makedirs(out_dir, exist_ok=True)
            image.save(actual)
            pytest.fail(
                "zscan_golden %s: no golden image %s (the image is in %s); run pytest "
                "with --zscan-update to write it" % (name, golden, actual),
                pytrace=False,
            )
        want = zscan.read_png(golden)
        if (want.width, want.height) != (image.width, image.height):
            os.makedirs(out_dir, exist_ok=True)
            image.save(actual)
            _remove(diff_png)
            pytest.fail(
                "zscan_golden %s: the image is %dx%d, the golden %s is %dx%d; actual "
                "image: %s (run pytest with --zscan-update to accept it)"
                % (name, image.width, image.height, golden, want.width, want.height, actual),
                pytrace=False,
            )
        d = zscan.diff(want, image)
        if d.differing:
            os.makedirs(out_dir, exist_ok=True)
            image.save(actual)
            d.image.save(diff_png)
            pytest.fail(
                "zscan_golden %s: %d of %d pixels differ from %s, largest channel "
                "difference %d; actual image: %s, diff image: %s (run pytest with "
                "--zscan-update to accept it)%s"
                % (name, d.differing, d.total, golden, d.max_channel_diff, actual, diff_png,
                   _version_note(golden_dir)),
                pytrace=False,
            )
        # a pass clears what an earlier failure left
        _remove(actual)
        _remove(diff_png)

    return check
