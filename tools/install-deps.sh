#!/usr/bin/env bash
# Installs the Debian 12 packages fdrmesh needs to build, test and benchmark (PostgreSQL + PostGIS:
# the PostGIS tests start a throw-away server of their own, tools/postgis/cluster.sh).
# Usage: tools/install-deps.sh [--no-qgis] [--fuzz]   (root, or sudo available)
#   --fuzz also installs clang and libFuzzer for tools/fuzz/run.sh (not needed by CI).
set -euo pipefail
want_qgis=1
want_fuzz=0
for a in "$@"; do
  [ "$a" = "--no-qgis" ] && want_qgis=0
  [ "$a" = "--fuzz" ] && want_fuzz=1
done
pkgs=(build-essential cmake ninja-build pkg-config git
      libcgal-dev libgmp-dev libmpfr-dev libboost-dev
      libgdal-dev gdal-bin libsqlite3-dev libpq-dev libproj-dev proj-bin libgeographiclib-dev
      libgtest-dev libgmock-dev libbenchmark-dev
      libmuparser-dev libcli11-dev libnetcdf-dev netcdf-bin nlohmann-json3-dev libjemalloc-dev
      gmsh python3 python3-matplotlib python3-numpy python3-gdal python3-netcdf4 python3-pytest
      python3-dev python3-pybind11 pybind11-dev
      tetgen python3-meshio python3-scipy
      postgresql-15 postgresql-15-postgis-3 postgresql-client-15)
[ "$want_qgis" = 1 ] && pkgs+=(qgis python3-qgis)
[ "$want_fuzz" = 1 ] && pkgs+=(clang-14 libfuzzer-14-dev libclang-rt-14-dev)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -eq 0 ]; then
  echo "install-deps: all ${#pkgs[@]} packages present"
  exit 0
fi
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
