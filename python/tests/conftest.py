"""Shared set-up of the binding's tests.

ZSCAN_BUILD_DIR names the build directory whose zscan command the tests
compare with (python/run-tests.sh sets it; default: the checkout's build/).
ZSCAN_LIBRARY, when unset, becomes that directory's libzscan.so, so that the
binding and the command under test come from the same build.
"""

import json
import os
import subprocess

import pytest

pytest_plugins = "pytester"

PYTHON_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SOURCE_DIR = os.path.dirname(PYTHON_DIR)
DATA_DIR = os.path.join(SOURCE_DIR, "tests", "data")
BUILD_DIR = os.path.abspath(os.environ.get("ZSCAN_BUILD_DIR") or os.path.join(SOURCE_DIR, "build"))
CLI = os.path.join(BUILD_DIR, "zscan")

# ZSCAN_TEST_INSTALLED=1: the package under test is an installed one, with
# the library inside it (tools/check-wheel.sh), found without ZSCAN_LIBRARY
INSTALLED = os.environ.get("ZSCAN_TEST_INSTALLED") == "1"
if INSTALLED:
    os.environ.pop("ZSCAN_LIBRARY", None)
elif not os.environ.get("ZSCAN_LIBRARY"):
    os.environ["ZSCAN_LIBRARY"] = os.path.join(BUILD_DIR, "libzscan.so")


def library_file():
    """The libzscan under test: $ZSCAN_LIBRARY's, or the installed package's."""
    if not INSTALLED:
        return os.environ["ZSCAN_LIBRARY"]
    import zscan

    return zscan.library_path()

# The zscan command runs without the sanitizer runtime that a sanitized
# library needs preloaded into Python (the command links its own).
CLI_ENV = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}

MODEL_SUFFIXES = (".obj", ".ply", ".stl", ".off", ".gltf")


def model_files():
    """Every model file below tests/data, relative to it, sorted."""
    out = []
    for root, _dirs, files in os.walk(DATA_DIR):
        for f in files:
            if f.endswith(MODEL_SUFFIXES):
                out.append(os.path.relpath(os.path.join(root, f), DATA_DIR))
    return sorted(out)


class CliResult:
    def __init__(self, proc):
        self.returncode = proc.returncode
        self.stdout = proc.stdout
        self.stderr = proc.stderr
        self.stats = None
        if proc.returncode == 0:
            lines = [l for l in proc.stdout.splitlines() if l.startswith("{")]
            if lines:
                self.stats = json.loads(lines[-1])

    @property
    def error(self):
        """The library's message, as the command prints it after its name."""
        msg = self.stderr.strip().splitlines()[-1] if self.stderr.strip() else ""
        prefix = "zscan render: "
        return msg[len(prefix):] if msg.startswith(prefix) else msg


@pytest.fixture(scope="package")  # one run of the suite
def cli():
    """Runs `zscan render ARGS -o OUT --stats` and returns a CliResult
    (remembered, when OUT is /dev/null, for the next call with the same
    arguments)."""
    if not os.access(CLI, os.X_OK):
        pytest.fail(
            "no zscan command at %s: build it, or set ZSCAN_BUILD_DIR to the build "
            "directory (python/run-tests.sh BUILD_DIR does)" % CLI
        )

    cache = {}

    def run(*args, out=os.devnull, stats=True):
        cmd = [CLI, "render"] + [str(a) for a in args] + ["-o", str(out)]
        if stats:
            cmd.append("--stats")
        key = tuple(cmd)
        if out == os.devnull and key in cache:
            return cache[key]
        proc = subprocess.run(cmd, capture_output=True, text=True, cwd=SOURCE_DIR, timeout=120,
                              env=CLI_ENV)
        cache[key] = result = CliResult(proc)
        return result

    return run
