"""Where the binding finds libzscan: $ZSCAN_LIBRARY, else beside the
package, else the checkout's build/; a clear error naming the places
otherwise.  Each case runs in a fresh interpreter."""

import ctypes.util
import os
import shutil
import subprocess
import sys

import pytest

import zscan
from zscan import _lib
from conftest import INSTALLED, PYTHON_DIR, SOURCE_DIR, library_file

PACKAGE = os.path.join(PYTHON_DIR, "zscan")

PROBE = "import zscan; print(zscan.library_path()); print(zscan.__version__)"


def run(pythonpath, env_library, code=PROBE):
    env = dict(os.environ)
    env.pop("ZSCAN_LIBRARY", None)
    if env_library is not None:
        env["ZSCAN_LIBRARY"] = env_library
    env["PYTHONPATH"] = pythonpath
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    # python -c puts the working directory first on sys.path: one without a package
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=env, timeout=60, cwd=os.sep)


def copy_package(dest):
    shutil.copytree(PACKAGE, os.path.join(dest, "zscan"),
                    ignore=shutil.ignore_patterns("__pycache__", "libzscan.so*"))
    return os.path.join(dest, "zscan")


def test_from_the_environment():
    lib = library_file()
    p = run(PYTHON_DIR, lib)
    assert p.returncode == 0, p.stderr
    assert p.stdout.split() == [lib, "0.12.3"]


def test_a_wrong_environment_variable_is_an_error(tmp_path):
    p = run(PYTHON_DIR, str(tmp_path / "nowhere.so"))
    assert p.returncode != 0
    assert "ZSCAN_LIBRARY: %s" % (tmp_path / "nowhere.so") in p.stderr


def test_beside_the_package(tmp_path):
    pkg = copy_package(tmp_path)
    shutil.copy(library_file(), os.path.join(pkg, "libzscan.so.0"))
    p = run(str(tmp_path), None)
    assert p.returncode == 0, p.stderr
    assert p.stdout.split()[0] == os.path.join(pkg, "libzscan.so.0")


def test_the_checkouts_build_directory(tmp_path):
    # tmp/python/zscan finds tmp/build/libzscan.so
    copy_package(tmp_path / "python")
    os.makedirs(tmp_path / "build")
    shutil.copy(library_file(), tmp_path / "build" / "libzscan.so")
    p = run(str(tmp_path / "python"), None)
    assert p.returncode == 0, p.stderr
    assert p.stdout.split()[0] == str(tmp_path / "build" / "libzscan.so")


@pytest.mark.skipif(ctypes.util.find_library("zscan") is not None,
                    reason="a libzscan is installed on the system's library path")
def test_nowhere_names_every_place(tmp_path):
    copy_package(tmp_path / "python")
    p = run(str(tmp_path / "python"), None)
    assert p.returncode != 0
    err = p.stderr
    assert "zscan.LibraryError" in err or "LibraryError" in err
    assert "ZSCAN_LIBRARY: not set" in err
    assert os.path.join(str(tmp_path / "python" / "zscan"), "libzscan.so") in err
    assert str(tmp_path / "build" / "libzscan.so") in err
    assert "libzscan.so.0" in err


def test_import_and_plugin_need_no_library(tmp_path):
    copy_package(tmp_path / "python")
    code = "import zscan, zscan.pytest_plugin; print(zscan.render.__name__)"
    p = run(str(tmp_path / "python"), None, code)
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == "render"


@pytest.mark.skipif(not INSTALLED, reason="for an installed package (tools/check-wheel.sh)")
def test_the_installed_package_holds_its_library():
    # neither the checkout nor an environment variable: the library inside
    # the package, which is not the checkout's
    assert "ZSCAN_LIBRARY" not in os.environ
    package = os.path.dirname(os.path.abspath(zscan.__file__))
    assert not package.startswith(SOURCE_DIR + os.sep)
    assert zscan.library_path() == os.path.join(package, "libzscan.so.0")
    assert zscan.__version__ == _lib.BINDING_VERSION
