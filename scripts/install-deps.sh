#!/usr/bin/env bash
# Installs the Debian 12 packages bhnsid needs, and only those that are missing: `apt-get update`
# runs once, and not at all when everything is already there. Safe to run any number of times.
# `--bench` adds what the peer comparison (bench/compare_hypre.sh) needs: hypre and MPI; `--viz`
# what `make test-viz` needs: ParaView and a virtual X display; `--slurm` what `make test-slurm` needs:
# SLURM's controller, node daemon and client, and munge (scripts/slurm-local.sh runs them).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git   # toolchain
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libfmt-dev  # core: parameter files, CLI, JSON, formatting
  libeigen3-dev libhdf5-dev                          # physics plugins: small dense algebra, field output
  catch2                                             # tests
  clang libclang-rt-14-dev libomp-dev                # make fuzz, make fuzz-check (libFuzzer, OpenMP for clang)
  python3 python3-numpy python3-matplotlib python3-h5py  # validation plots, reading data.h5
  python3-scipy python3-yaml                         # bhnsid sequence: splines, sequence files
)
for option in "$@"; do
  case "$option" in
    --bench) packages+=(libhypre-dev libopenmpi-dev openmpi-bin) ;;  # the hypre peer of bench/compare_hypre.sh
    --viz) packages+=(paraview python3-paraview xvfb xauth) ;;  # make test-viz: pvbatch and its Python modules (a Recommends, which --no-install-recommends skips), on a virtual X display
    --slurm) packages+=(slurm-wlm munge) ;;  # make test-slurm: slurmctld + slurmd + munge on this machine
    *) echo "install-deps: unknown option $option (expected --bench, --viz or --slurm)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then sudo="sudo"; else
    echo "install-deps: missing ${missing[*]}; run as root or install sudo" >&2
    exit 1
  fi
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update
$sudo apt-get install -y --no-install-recommends "${missing[@]}"
