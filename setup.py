# SPDX-License-Identifier: MIT
"""Builds the compiled part of the Python module (smb._smb) with the project's own CMake, so
that pip and CTest build the same target from the same sources."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = Path(self.build_temp).resolve() / "cmake"
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build_dir),
            "-DCMAKE_BUILD_TYPE=Release",
            "-DSMB_BUILD_PYTHON=ON",
            "-DSMB_BUILD_TESTS=OFF", "-DSMB_BUILD_TOOLS=OFF", "-DSMB_BUILD_BENCHMARKS=OFF",
            "-DSMB_BUILD_EXAMPLES=OFF", "-DSMB_INSTALL=OFF",
            # The interpreter pip runs under is the one the module is for.
            f"-DPython3_EXECUTABLE={sys.executable}",
        ]
        subprocess.run(configure, check=True)
        jobs = os.environ.get("SMB_JOBS", "2")
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "smb_python", "--parallel", jobs], check=True)
        built = list((build_dir / "python" / "smb").glob("_smb*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one compiled module in {build_dir / 'python' / 'smb'}, found {built}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


setup(
    packages=["smb"],
    package_dir={"": "python"},
    package_data={"smb": ["__init__.pyi", "py.typed"]},
    ext_modules=[CMakeExtension("smb._smb")],
    cmdclass={"build_ext": CMakeBuild},
    # Beside the CMake build folders (ignored as /build*/), not in a folder named build/ that a
    # checkout may use for its own CMake build.
    options={"build": {"build_base": "build-pip"}},
    zip_safe=False,
)
