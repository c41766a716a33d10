#!/usr/bin/env bash
# Installs the Debian 12 packages Rift needs, only those missing. Non-interactive; needs root (or sudo).
set -euo pipefail
packages=(cmake ninja-build g++ ccache pkg-config
          libeigen3-dev libtbb-dev libhdf5-dev libmetis-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
          libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libspdlog-dev libfmt-dev
          libgtest-dev libgmock-dev libbenchmark-dev hdf5-tools
          libhypre-dev libopenmpi-dev
          python3-matplotlib python3-h5py python3-meshio   # matplotlib: rift plot and the sweep's plot;
                                                           # h5py, meshio: the readers tests, bench studies
          python3-jsonschema python3-ruamel.yaml           # the scene schema's test (a YAML 1.2 reader)
          paraview python3-paraview xvfb xauth)            # rift render, ParaView's readers test (headless)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "deps: all ${#packages[@]} Debian packages present"
  exit 0
fi
echo "deps: installing ${missing[*]}"
sudo_cmd=""
[ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
$sudo_cmd apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
