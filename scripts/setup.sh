#!/usr/bin/env bash
# Installs what aster needs to build on a fresh Debian machine: the HDF5 C
# library (MED files are HDF5) and pkg-config to find it. Idempotent: does
# nothing when they are already there.
set -euo pipefail
need=()
pkg-config --exists hdf5 2>/dev/null || need+=(libhdf5-dev)
command -v pkg-config >/dev/null 2>&1 || need+=(pkg-config)
if [ ${#need[@]} -gt 0 ]; then
  echo "setup: installing ${need[*]}" >&2
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need[@]}" pkg-config >/dev/null
fi
