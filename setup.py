"""setuptools' side of `pip install .` (pyproject.toml): the extension module is built by
CMake, in build-pip/ beside build/ so that the compiler cache serves both trees, and its
`wheel` install component (the module and libqmotion.so, found through $ORIGIN) goes into
the wheel. QMOTION_CMAKE_ARGS adds configure options (the test passes the tree's own, so the
cache's entries match); QMOTION_PIP_BUILD_DIR moves the build folder."""
import os
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def version():
    with open(os.path.join(ROOT, "kernel", "include", "qmotion", "version.hpp")) as f:
        return re.search(r'#define QMOTION_VERSION_STRING "([0-9.]+)"', f.read()).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.environ.get("QMOTION_PIP_BUILD_DIR") or os.path.join(ROOT, "build-pip")
        stage = os.path.join(build, "wheel-stage")
        env = dict(os.environ)
        args = ["-DCMAKE_BUILD_TYPE=Release", "-DQMOTION_BUILD_TESTS=OFF",
                "-DQMOTION_BUILD_EXAMPLES=OFF", "-DQMOTION_BUILD_PYTHON=ON",
                "-DPython_EXECUTABLE=" + sys.executable]
        if shutil.which("ccache"):
            args.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
            env.setdefault("CCACHE_BASEDIR", ROOT)
            env.setdefault("CCACHE_NOHASHDIR", "1")
        args += env.get("QMOTION_CMAKE_ARGS", "").split()
        jobs = str(os.cpu_count() or 2)
        subprocess.run(["cmake", "-S", ROOT, "-B", build] + args, check=True, env=env)
        subprocess.run(["cmake", "--build", build, "--target", "qmotion_python", "-j", jobs],
                       check=True, env=env)
        shutil.rmtree(stage, ignore_errors=True)
        subprocess.run(["cmake", "--install", build, "--component", "wheel", "--prefix", stage],
                       check=True, env=env)
        out = os.path.dirname(os.path.abspath(self.get_ext_fullpath(ext.name)))
        os.makedirs(out, exist_ok=True)
        for name in os.listdir(stage):
            shutil.copy2(os.path.join(stage, name), os.path.join(out, name))


# setuptools' own folders go under build-pip too (its default, build/, is CMake's tree).
setup(version=version(), packages=[], py_modules=[],
      ext_modules=[Extension("qmotion", sources=[])],
      cmdclass={"build_ext": CMakeBuild},
      options={"build": {"build_base": os.path.join("build-pip", "setuptools")},
               "egg_info": {"egg_base": "build-pip"}})
