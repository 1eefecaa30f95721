"""Builds libzscan with CMake while the package is built, and installs it
inside the package (zscan/libzscan.so.0, the first place the binding looks
after $ZSCAN_LIBRARY), so that an installed zscan needs no checkout and no
environment variable:

    python3 -m pip install --no-build-isolation ./python

Offline with Debian's python3-setuptools, python3-wheel and python3-pip
(no build isolation: nothing is downloaded).  The library is built from
the checkout this directory belongs to ($ZSCAN_SOURCE_DIR overrides it),
in Release, without its tests, against the system's libpng, libjpeg,
cJSON and assimp: the wheel is for machines with those.  $ZSCAN_LIBRARY_PREBUILT
names a libzscan.so to put in the package instead of building one.  The
rest of the package's settings are in pyproject.toml.
"""

import os
import re
import shutil
import subprocess

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py

HERE = os.path.dirname(os.path.abspath(__file__))


def source_dir():
    src = os.environ.get("ZSCAN_SOURCE_DIR") or os.path.dirname(HERE)
    cmake = os.path.join(src, "CMakeLists.txt")
    try:
        with open(cmake) as f:
            if re.search(r"^project\(zscan\b", f.read(), re.M):
                return src
    except OSError:
        pass
    raise SystemExit("zscan: no zscan checkout at %s to build libzscan from (set "
                     "ZSCAN_SOURCE_DIR, or ZSCAN_LIBRARY_PREBUILT to a built libzscan.so)" % src)


class build_with_library(build_py):
    """build_py, then libzscan beside the package's modules."""

    def run(self):
        super().run()
        dest = os.path.join(self.build_lib, "zscan", "libzscan.so.0")
        prebuilt = os.environ.get("ZSCAN_LIBRARY_PREBUILT")
        if prebuilt:
            shutil.copyfile(os.path.realpath(prebuilt), dest)
            return
        build = os.path.join(os.path.abspath(self.build_lib), "..", "zscan-cmake")
        configure = ["cmake", "-S", source_dir(), "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                     "-DZS_TESTS=OFF", "-DZS_MESA=OFF", "-DZS_INSTALL=OFF"]
        jobs = str(os.cpu_count() or 1)
        for cmd in (configure, ["cmake", "--build", build, "--target", "zscan_shared", "-j", jobs]):
            self.announce(" ".join(cmd), level=2)
            subprocess.run(cmd, check=True)
        # the real file, under the SONAME the binding looks for
        built = os.path.realpath(os.path.join(build, "libzscan.so"))
        shutil.copyfile(built, dest)


class BinaryDistribution(Distribution):
    """The wheel holds a shared library: a platform wheel, not a pure one."""

    def has_ext_modules(self):
        return True


setup(cmdclass={"build_py": build_with_library}, distclass=BinaryDistribution)
