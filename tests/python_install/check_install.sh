#!/usr/bin/env bash
# `pip install .` into a virtual environment, offline (Debian's setuptools and numpy, seen by the
# environment; no build isolation, no index): CMake builds the module from a fresh folder, the
# package imports from the environment, not from the source or build tree, reports the CMake
# project's version and runs a scene. Then `cmake --install` of the test's build still installs
# the package into a prefix. The CMake folder of the pip build is kept between runs (a clean
# clone builds it from scratch; a rerun is incremental); the environment and prefix are not.
#   check_install.sh SOURCE_DIR WORK_DIR BUILD_DIR
set -euo pipefail
src=$1 work=$2 build=$3
rm -rf "$work/venv" "$work/prefix"
mkdir -p "$work"
/usr/bin/python3 -m venv --system-site-packages "$work/venv"
SUPERDEX_CMAKE_BUILD_DIR="$work/cmake" SUPERDEX_BUILD_JOBS="${SUPERDEX_BUILD_JOBS:-2}" \
  "$work/venv/bin/pip" install --no-build-isolation --no-index --no-deps --quiet "$src"
version=$(sed -n 's/^project(superdex VERSION \([0-9.]*\).*/\1/p' "$src/CMakeLists.txt")
cd "$work"
env -u PYTHONPATH "$work/venv/bin/python" - "$work/venv" "$version" <<'PY'
import os, sys
import superdex as sd
venv, version = sys.argv[1], sys.argv[2]
assert os.path.realpath(sd.__file__).startswith(os.path.realpath(venv)), sd.__file__
assert sd.__version__ == version, (sd.__version__, version)
scene = sd.Scene()
scene.add_rigid_actor(sd.RigidActorDesc("ground", sd.RigidShape.plane(), dynamic=False))
d = sd.RigidActorDesc("ball", sd.RigidShape.sphere(0.1))
d.position = [0, 0, 0.2]
ball = scene.add_rigid_actor(d)
scene.run(0.1, 1e-3)  # falling freely: z = 0.2 - g t^2 / 2
assert abs(ball.position[2] - (0.2 - 0.5 * 9.81 * 0.1 ** 2)) < 1e-3, ball.position
print("pip install: superdex", sd.__version__, "from", os.path.dirname(sd.__file__))
PY
cmake --install "$build" --prefix "$work/prefix" > /dev/null
ls "$work"/prefix/lib/python3/dist-packages/superdex/_superdex*.so > /dev/null
test -f "$work/prefix/lib/python3/dist-packages/superdex/__init__.py"
test -x "$work/prefix/bin/superdex" || { echo "cmake --install: no bin/superdex" >&2; exit 1; }
echo "cmake --install: $work/prefix"
