"""Builds the msbench extension with the project's CMake, against the interpreter running pip.

`pip install ./tools/python` (from the repository root; add --no-build-isolation to use the
system's setuptools, e.g. offline). The extension is configured with MSB_PYTHON set to this
interpreter (sys.executable), built as the single target msbench_python, and copied into the
wheel beside the pure-Python files. The worlds and scenarios stay in the checkout: the extension
names them by their absolute paths there.
"""
import os
import pathlib
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parents[2]


class CMakeBuild(build_ext):
    """Configures and builds the project's msbench_python target, then copies it in place."""

    def build_extension(self, ext):
        build_dir = pathlib.Path(self.build_temp).resolve() / "cmake"
        build_dir.mkdir(parents=True, exist_ok=True)
        jobs = os.environ.get("MSB_BUILD_JOBS", str(os.cpu_count() or 1))
        subprocess.run(
            ["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
             "-DMSB_BUILD_TESTS=OFF", f"-DMSB_PYTHON={sys.executable}"],
            check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "msbench_python", "-j", jobs], check=True)
        built = sorted((build_dir / "python" / "msbench").glob("_msbench*.so"))
        if not built:
            raise RuntimeError(f"msbench: the extension was not built in {build_dir}/python/msbench")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


setup(ext_modules=[Extension("msbench._msbench", sources=[])], cmdclass={"build_ext": CMakeBuild})
