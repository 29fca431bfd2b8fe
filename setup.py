"""Build hook: the step loops of the default methods compiled ahead of time [T382].

``pip install`` (editable or not) compiles them with numba's ``pycc`` into the extension module
``jointdyn.integrators._loops`` (≈ 35 s of CPU). It needs a C compiler; where the build fails
the package installs without the module (the reason is printed, which pip shows with ``-v``) and
the loops compile at first use as before; ``jointdyn cache info`` tells which."""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SRC = os.path.join(os.path.dirname(os.path.abspath(__file__)), "src")


class BuildLoops(build_ext):
    """Compile the loops into the extension's path (in place for an editable install)."""

    def build_extension(self, ext):
        out = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(out), exist_ok=True)
        # the sources go first on sys.path inside the child: pip's isolated build environment
        # reaches its packages through PYTHONPATH (kept as it is) and its sitecustomize drops the
        # paths of the running interpreter's site-packages (an installed jointdyn's among them)
        with tempfile.TemporaryDirectory() as cache:  # the build's own numba cache, not the user's
            env = {**os.environ, "NUMBA_CACHE_DIR": cache}
            code = "\n".join(
                (
                    "import sys",
                    f"sys.path.insert(0, {SRC!r})",
                    "from jointdyn.integrators import aot",
                    f"aot.build({out!r})",
                )
            )
            r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
        if r.returncode != 0:
            tail = "\n".join(r.stderr.strip().splitlines()[-5:])
            print(
                f"jointdyn: the step loops were not compiled ahead of time ({tail}); "
                "they compile at first use instead",
                file=sys.stderr,
            )


setup(
    ext_modules=[Extension("jointdyn.integrators._loops", sources=[], optional=True)],
    cmdclass={"build_ext": BuildLoops},
)
