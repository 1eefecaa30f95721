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

The marker, in pytest-mpl's manner: a test marked
@pytest.mark.zscan_compare returns a zscan.Image, compared with
baseline/TEST_NAME.png beside the test file (the marker's baseline_dir
and filename change them) or, with a hash library, with the 16-hex-digit
hash kept for the test: zscan's bytes are exact, so a suite may keep
hashes in its repository instead of images.

    --zscan-generate-path DIR            write each marked test's image
                                         there as its baseline, and pass
    --zscan-hash-library FILE.json       compare hashes with FILE's
    --zscan-generate-hash-library FILE.json   write (or update) FILE with
                                         the marked tests' hashes
    --zscan-results-path DIR             result, baseline and diff images
                                         of failing tests (default: a
                                         temporary directory, named in the
                                         failure)
    --zscan-summary html|json            a summary of every marked test
                                         in the results directory
                                         (summary.html with baseline,
                                         result and difference side by
                                         side; summary.json); repeatable

A failure names the command that accepts the new image.

The library is loaded only when the fixture or the marker is used, so
registering this plugin never breaks a test run that does not use it.
"""

import html
import json
import os
import re
import shlex
import tempfile

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
    group.addoption("--zscan-generate-path", metavar="DIR", default=None,
                    help="write the images of tests marked zscan_compare into DIR as "
                    "their baselines")
    group.addoption("--zscan-hash-library", metavar="FILE", default=None,
                    help="compare the images of tests marked zscan_compare with the hashes "
                    "in FILE (JSON)")
    group.addoption("--zscan-generate-hash-library", metavar="FILE", default=None,
                    help="write (or update) FILE (JSON) with the hashes of the images of the "
                    "tests marked zscan_compare")
    group.addoption("--zscan-results-path", metavar="DIR", default=None,
                    help="write the result, baseline and diff images of failing "
                    "zscan_compare tests into DIR (default: a temporary directory)")
    group.addoption("--zscan-summary", metavar="FORMAT", action="append", default=[],
                    choices=("html", "json"),
                    help="write a summary of the zscan_compare tests into the results "
                    "directory: html (images side by side) or json; repeatable")


def pytest_configure(config):
    config.addinivalue_line(
        "markers",
        "zscan_compare(filename=None, baseline_dir=None): the test returns a zscan.Image, "
        "compared exactly with its baseline image or its hash (zscan.pytest_plugin)")
    config._zscan_compare = _Compare(config)


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


# ---- the zscan_compare marker ---------------------------------------------

HASH_VERSION_KEY = "zscan-pixel-version"


def _safe(name):
    """A test's name as a file name: its parameters' brackets and odd
    characters as '_'."""
    return re.sub(r"[^A-Za-z0-9_.\-]", "_", name)


def _command(config, item, option, value):
    """The command that reruns item with option=value: what accepts it."""
    args = ["pytest", item.nodeid, "%s=%s" % (option, value)]
    if "zscan.pytest_plugin" in " ".join(config.invocation_params.args):
        args[1:1] = ["-p", "zscan.pytest_plugin"]
    return " ".join(shlex.quote(a) for a in args)


class _Compare:
    """The marker's state over a session: the hash library read, the one
    being generated, and a row per marked test for the summary."""

    def __init__(self, config):
        self.config = config
        self.invoked = str(config.invocation_params.dir)
        opt = config.getoption
        self.generate_dir = self._path(opt("zscan_generate_path"))
        self.hash_file = self._path(opt("zscan_hash_library"))
        self.generate_hash_file = self._path(opt("zscan_generate_hash_library"))
        self.summaries = opt("zscan_summary")
        self._results = self._path(opt("zscan_results_path"))
        self.generated = {}
        self.rows = []
        self._library = None
        if self.hash_file:
            self.library()  # a missing or broken library is a usage error, at once

    def _path(self, p):
        return None if not p else os.path.join(self.invoked, p)

    def results_dir(self):
        if self._results is None:
            self._results = tempfile.mkdtemp(prefix="zscan-results-")
        os.makedirs(self._results, exist_ok=True)
        return self._results

    def library(self):
        if self._library is None:
            try:
                with open(self.hash_file) as f:
                    self._library = json.load(f)
            except FileNotFoundError:
                raise pytest.UsageError("--zscan-hash-library: %s: no such file (make it with "
                                        "--zscan-generate-hash-library)" % self.hash_file)
            except ValueError as e:
                raise pytest.UsageError("--zscan-hash-library: %s: not JSON: %s"
                                        % (self.hash_file, e))
            if not isinstance(self._library, dict):
                raise pytest.UsageError("--zscan-hash-library: %s: expected a JSON object of "
                                        "test names and hashes" % self.hash_file)
        return self._library

    def check(self, item, image):
        """Compares the image a marked test returned; fails the test (with
        the command that accepts it) on a mismatch."""
        __tracebackhide__ = True
        import zscan

        if not isinstance(image, zscan.Image):
            pytest.fail("zscan_compare: %s returned %r, not a zscan.Image" % (item.name, image),
                        pytrace=False)
        mark = item.get_closest_marker("zscan_compare")
        test_dir = os.path.dirname(str(item.path if hasattr(item, "path") else item.fspath))
        baseline_dir = os.path.join(test_dir, mark.kwargs.get("baseline_dir", "baseline"))
        filename = mark.kwargs.get("filename") or _safe(item.name) + ".png"
        # the test's id from the root directory: two test files of one name
        # in two folders are two keys
        key = item.nodeid
        row = {"test": item.nodeid, "key": key, "hash": image.hash, "status": "passed",
               "message": "", "result": None, "baseline": None, "diff": None}
        self.rows.append(row)
        if self.generate_hash_file:
            self.generated[key] = image.hash
        if self.generate_dir:
            os.makedirs(self.generate_dir, exist_ok=True)
            image.save(os.path.join(self.generate_dir, filename))
            row["status"] = "generated"
            return
        if self.generate_hash_file:
            row["status"] = "generated"
            return
        if self.hash_file:
            self._check_hash(item, image, key, baseline_dir, filename, row)
        else:
            self._check_image(item, image, baseline_dir, filename, row)

    def _save_result(self, image, filename, row, want=None, diff=None):
        out = os.path.join(self.results_dir(), _safe(row["test"]))
        os.makedirs(out, exist_ok=True)
        stem = os.path.splitext(filename)[0]
        row["result"] = os.path.join(out, stem + "-result.png")
        image.save(row["result"])
        if want is not None:
            row["baseline"] = os.path.join(out, stem + "-baseline.png")
            want.save(row["baseline"])
        if diff is not None:
            row["diff"] = os.path.join(out, stem + "-diff.png")
            diff.image.save(row["diff"])
        return out

    def _fail(self, row, message):
        __tracebackhide__ = True
        row["status"], row["message"] = "failed", message
        pytest.fail(message, pytrace=False)

    def _check_image(self, item, image, baseline_dir, filename, row):
        __tracebackhide__ = True
        import zscan

        baseline = os.path.join(baseline_dir, filename)
        accept = _command(self.config, item, "--zscan-generate-path",
                          os.path.relpath(baseline_dir, self.invoked))
        if not os.path.exists(baseline):
            out = self._save_result(image, filename, row)
            self._fail(row, "zscan_compare %s: no baseline image %s (the result is in %s); "
                       "to accept it: %s" % (item.name, baseline, out, accept))
        want = zscan.read_png(baseline)
        if (want.width, want.height) != (image.width, image.height):
            out = self._save_result(image, filename, row, want)
            self._fail(row, "zscan_compare %s: the image is %dx%d, the baseline %s is %dx%d "
                       "(images in %s); to accept it: %s"
                       % (item.name, image.width, image.height, baseline, want.width,
                          want.height, out, accept))
        d = zscan.diff(want, image)
        if d.differing:
            out = self._save_result(image, filename, row, want, d)
            self._fail(row, "zscan_compare %s: %d of %d pixels differ from %s, largest "
                       "channel difference %d (result, baseline and diff images in %s); to "
                       "accept it: %s" % (item.name, d.differing, d.total, baseline,
                                          d.max_channel_diff, out, accept))
        row["baseline"] = baseline

    def _check_hash(self, item, image, key, baseline_dir, filename, row):
        __tracebackhide__ = True
        import zscan

        lib = self.library()
        accept = _command(self.config, item, "--zscan-generate-hash-library",
                          os.path.relpath(self.hash_file, self.invoked))
        want = lib.get(key)
        if want == image.hash:
            return
        baseline = os.path.join(baseline_dir, filename)
        base = zscan.read_png(baseline) if os.path.exists(baseline) else None
        d = None
        if base is not None and (base.width, base.height) == (image.width, image.height):
            d = zscan.diff(base, image)
        out = self._save_result(image, filename, row, base, d)
        if want is None:
            self._fail(row, "zscan_compare %s: no hash for %s in %s (the result is in %s); to "
                       "accept it: %s" % (item.name, key, self.hash_file, out, accept))
        note = ""
        theirs = lib.get(HASH_VERSION_KEY)
        if isinstance(theirs, int) and theirs != zscan.pixel_version():
            ours = zscan.pixel_version()
            changes = "; ".join("%d: %s" % (v, zscan.pixel_changes(v))
                                for v in range(theirs + 1, ours + 1)) if theirs < ours else ""
            note = (" (the hashes were made with pixel version %d; this zscan draws version "
                    "%d%s)" % (theirs, ours, ", which changed: " + changes if changes else ""))
        self._fail(row, "zscan_compare %s: hash %s, the library %s has %s (the result is in "
                   "%s); to accept it: %s%s" % (item.name, image.hash, self.hash_file, want,
                                                out, accept, note))

    def finish(self):
        """Writes the generated hash library and the summaries."""
        import zscan

        if self.generate_hash_file and self.generated:
            old = {}
            try:
                with open(self.generate_hash_file) as f:
                    old = json.load(f)
            except (OSError, ValueError):
                old = {}
            if not isinstance(old, dict):
                old = {}
            old.update(self.generated)
            old[HASH_VERSION_KEY] = zscan.pixel_version()
            d = os.path.dirname(self.generate_hash_file)
            if d:
                os.makedirs(d, exist_ok=True)
            tmp = self.generate_hash_file + ".tmp"
            with open(tmp, "w") as f:
                json.dump(dict(sorted(old.items())), f, indent=2)
                f.write("\n")
            os.replace(tmp, self.generate_hash_file)
        if not self.summaries or not self.rows:
            return
        out = self.results_dir()
        if "json" in self.summaries:
            with open(os.path.join(out, "summary.json"), "w") as f:
                json.dump(self.rows, f, indent=2)
                f.write("\n")
        if "html" in self.summaries:
            with open(os.path.join(out, "summary.html"), "w") as f:
                f.write(_summary_html(self.rows, out))

    def summary_line(self):
        if not self.summaries or not self.rows:
            return None
        return "zscan: summary of %d marked tests in %s" % (len(self.rows), self.results_dir())


def _summary_html(rows, out):
    def img(path):
        if not path:
            return "<td class=none>none</td>"
        rel = os.path.relpath(path, out)
        return '<td><img src="%s" alt="%s"></td>' % (html.escape(rel), html.escape(rel))

    failed = sum(r["status"] == "failed" for r in rows)
    lines = [
        "<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
        "<title>zscan image comparison</title>",
        "<style>body{font-family:sans-serif}td,th{border:1px solid #ccc;padding:4px;"
        "vertical-align:top}img{image-rendering:pixelated;max-width:320px}"
        ".failed{background:#fdd}.passed{background:#dfd}.generated{background:#ddf}"
        ".none{color:#888}</style></head><body>",
        "<h1>zscan image comparison</h1>",
        "<p>%d tests, %d failed</p>" % (len(rows), failed),
        "<table><tr><th>test</th><th>status</th><th>baseline</th><th>result</th>"
        "<th>difference</th></tr>",
    ]
    for r in sorted(rows, key=lambda r: (r["status"] != "failed", r["test"])):
        lines.append('<tr class="%s"><td>%s<br><code>%s</code><br>%s</td><td>%s</td>%s%s%s</tr>'
                     % (r["status"], html.escape(r["test"]), r["hash"],
                        html.escape(r["message"]), r["status"], img(r["baseline"]),
                        img(r["result"]), img(r["diff"])))
    lines += ["</table>", "</body></html>", ""]
    return "\n".join(lines)


@pytest.hookimpl(tryfirst=True)
def pytest_pyfunc_call(pyfuncitem):
    """Runs a test marked zscan_compare and checks the image it returns
    (calling it here keeps pytest from warning that it returned one)."""
    if pyfuncitem.get_closest_marker("zscan_compare") is None:
        return None
    __tracebackhide__ = True
    args = {a: pyfuncitem.funcargs[a] for a in pyfuncitem._fixtureinfo.argnames}
    image = pyfuncitem.obj(**args)
    pyfuncitem.config._zscan_compare.check(pyfuncitem, image)
    return True


def pytest_sessionfinish(session):
    c = getattr(session.config, "_zscan_compare", None)
    if c is not None:
        c.finish()


def pytest_terminal_summary(terminalreporter, config):
    c = getattr(config, "_zscan_compare", None)
    line = c.summary_line() if c is not None else None
    if line:
        terminalreporter.write_line(line)
