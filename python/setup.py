"""Builds the Python package afv (pyproject.toml has its metadata).

The package is ctypes over the C library: this script builds libafv.so
with the repository's Makefile (its compiler and flags, the same as `make
shared`) and puts it in the package, so that an installed afv loads the
library it was built with, from any directory, without PYTHONPATH.  The
version is the C library's (AFV_VERSION in afv.h)."""
import os
import re
import subprocess

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)          # the repository: afv.h, Makefile


def c_version():
    with open(os.path.join(ROOT, "afv.h")) as fp:
        m = re.search(r'#define AFV_VERSION "([^"]+)"', fp.read())
    if not m:
        raise SystemExit("setup.py: no AFV_VERSION in %s/afv.h" % ROOT)
    return m.group(1)


class BuildWithLibrary(build_py):
    """build_py, then `make libafv.so` in the repository, copied into the
    package beside __init__.py (where the module looks first)."""

    def run(self):
        build_py.run(self)
        subprocess.check_call(["make", "-C", ROOT, "libafv.so"])
        self.copy_file(os.path.join(ROOT, "libafv.so"),
                       os.path.join(self.build_lib, "afv", "libafv.so"))


class BinaryDistribution(Distribution):
    """A wheel for this platform (it holds a compiled library)."""

    def has_ext_modules(self):
        return True


setup(version=c_version(), packages=["afv"],
      cmdclass={"build_py": BuildWithLibrary}, distclass=BinaryDistribution)
