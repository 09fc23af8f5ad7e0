# Sourced by scripts/build.sh and scripts/build-sanitized.sh, from the clone's top folder:
# sets `launcher` to the CMake arguments that compile through ccache when it is installed
# (else none), with paths relative to the clone, so that another clone (CI's) reuses the cache.
launcher=()
if command -v ccache >/dev/null 2>&1; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR=$PWD CCACHE_NOHASHDIR=1
fi
