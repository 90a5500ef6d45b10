# SPDX-License-Identifier: MIT
"""Builds the compiled part of the Python module (smb._smb) with the project's own CMake, so
that pip and CTest build the same target from the same sources."""

import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class Progress:
    """Stage lines for whoever installs: on standard output, which pip shows with -v, and, when
    standard output is not a terminal (pip keeps a build's output to itself otherwise), on the
    controlling terminal if there is one, so that a build of several minutes is not silent."""

    def __init__(self):
        self.start = time.monotonic()
        self.told = False
        self.terminal = None
        if not sys.stdout.isatty():
            try:
                self.terminal = open("/dev/tty", "w")
            except OSError:
                self.terminal = None

    def say(self, text):
        line = f"smb: {text} ({time.monotonic() - self.start:.0f} s)"
        print(line, flush=True)
        if self.terminal is not None:
            # The first line starts a line of its own: pip's spinner leaves the cursor after its text.
            self.terminal.write(("" if self.told else "\n") + line + "\n")
            self.told = True
            self.terminal.flush()

    @staticmethod
    def percent(line):
        """How far a build line says it is: Make's "[ 42%]" or Ninja's "[12/40]"; else None."""
        make = re.match(r"\[\s*(\d+)%\]", line)
        if make:
            return int(make.group(1))
        ninja = re.match(r"\[(\d+)/(\d+)\]", line)
        if ninja and int(ninja.group(2)) > 0:
            return 100 * int(ninja.group(1)) // int(ninja.group(2))
        return None

    def run(self, command, what):
        """Runs `command`, passing its output through line by line and saying how far `what`
        has got at each tenth of CMake's percentage."""
        self.say(f"{what}: {' '.join(command)}")
        told = -10
        with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, bufsize=1) as child:
            for line in child.stdout:
                print(line, end="", flush=True)
                done = self.percent(line)
                if done is not None and done >= told + 10:
                    told = done
                    self.say(f"{what}: {told}%")
        if child.returncode != 0:
            self.say(f"{what} failed (exit status {child.returncode}); pip install -v shows the whole output")
            raise subprocess.CalledProcessError(child.returncode, command)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        progress = Progress()
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
        progress.say("building the library and the module with CMake, a few minutes of CPU; "
                     "pip install -v shows the compiler's output, SMB_JOBS sets the parallel jobs")
        progress.run(configure, "configuring")
        jobs = os.environ.get("SMB_JOBS", "2")
        progress.run(["cmake", "--build", str(build_dir), "--target", "smb_python", "--parallel", jobs], "building")
        built = list((build_dir / "python" / "smb").glob("_smb*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one compiled module in {build_dir / 'python' / 'smb'}, found {built}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)
        progress.say(f"built {target.name}")


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
