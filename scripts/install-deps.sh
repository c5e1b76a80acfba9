#!/usr/bin/env bash
# Installs what the build and the tests need, all from Debian's packages (run as root).
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
packages=(
  build-essential cmake            # compiler and build
  libeigen3-dev                    # geometry and small linear algebra
  libglpk-dev                      # the PRD linear programs
  libsuitesparse-dev               # KLU: the PRD LP's kept basis (prd/kept_basis.hpp); CHOLMOD: its interior point (prd/interior.hpp)
  libbox2d-dev                     # DEM contact geometry
  nlohmann-json3-dev               # case and result files
  liblzma-dev xz-utils             # the runs kept under reports/ as results.json.xz (read; xz writes them)
  libcli11-dev                     # the command line
  libopenmpi-dev openmpi-bin       # masonry sweep across machines (mpirun); its tests start mpirun
  libgtest-dev                     # tests
  libexpat1-dev                    # tests: every SVG and HTML page written is well-formed XML
  libbenchmark-dev                 # benchmarks
  chromium                         # compare tests: report.html in a headless browser
  jq                               # the PRD report scripts under reports/
  python3-jsonschema               # the schema test: every file masonry writes against schemas/ (JSON Schema 2020-12)
  python3-dev pybind11-dev python3-pybind11  # the Python module (import masonry, python/): headers and bindings
  python3-numpy                    # the Python module's arrays (results' d, reactions, poses; blocks' vertices)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
