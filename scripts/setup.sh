#!/usr/bin/env bash
# Installs what aster needs to build on a fresh Debian machine: the HDF5 C
# library (MED files are HDF5) and pkg-config to find it, and the DejaVu
# fonts that `aster sweep` loads at run time to write the text of its PNG
# plots. Idempotent: does nothing when they are already there.
set -euo pipefail
need=()
pkg-config --exists hdf5 2>/dev/null || need+=(libhdf5-dev)
command -v pkg-config >/dev/null 2>&1 || need+=(pkg-config)
[ -f /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf ] || need+=(fonts-dejavu-core)
if [ ${#need[@]} -gt 0 ]; then
  echo "setup: installing ${need[*]}" >&2
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need[@]}" pkg-config >/dev/null
fi
# In CI, also install the independent MED readers that tests/med_interop.py
# compares our files with (the test is skipped, with a notice, without them).
if [ "${CI:-}" = "true" ]; then
  python3 -c "import medcoupling" 2>/dev/null || python3 -c "import meshio" 2>/dev/null || \
    python3 -m pip install --quiet meshio h5py medcoupling >/dev/null 2>&1 || \
    echo "setup: could not install medcoupling/meshio; the MED interop test will be skipped" >&2
fi
