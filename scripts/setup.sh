#!/usr/bin/env bash
# Installs every build and run dependency from Debian 12's packages, and the repository's
# commit-msg hook (CONTRIBUTING.md). Idempotent; needs root or sudo.
set -euo pipefail
if git -C "$(dirname "$0")/.." rev-parse --git-dir > /dev/null 2>&1; then
  git -C "$(dirname "$0")/.." config core.hooksPath scripts/git-hooks
fi
packages=(
  cmake g++ make pkg-config git
  libeigen3-dev libhdf5-dev hdf5-tools libfftw3-dev
  libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler
  libsqlite3-dev sqlite3 libspdlog-dev libfmt-dev
  libtomlplusplus-dev libcli11-dev nlohmann-json3-dev zlib1g-dev
  libcairo2-dev fonts-dejavu-core ffmpeg
  libgtest-dev libgmock-dev libbenchmark-dev
  # The code's habits checked in the tests (CONTRIBUTING.md): layout by clang-format, and
  # clang-tidy's checks (.clang-tidy) on the files a change touches.
  clang-format clang-tidy
  # libFuzzer (scripts/fuzz.sh, tests/fuzz): clang, its runtime libraries and its OpenMP (the
  # engine is built with OpenMP there too).
  clang libclang-rt-14-dev libomp-14-dev
  # The Python client (python/, docs/python.md) and its test: Debian's python3 with gRPC, protobuf,
  # h5py, numpy; pandas for its tables (tests/python/client_test.py).
  python3 python3-grpcio python3-protobuf python3-h5py python3-numpy python3-pandas
  # fields.xmf opened in ParaView offscreen by pvbatch, and a screenshot of it under Xvfb
  # (tests/python/paraview_test.py); xarray for dlmfd.open (python/dlmfd/run.py); the venv and pip
  # that install the Python package in its test; pdftotext reads the text of the pictures' PDFs
  # (tests/e2e/publication_test.cc).
  paraview python3-paraview xvfb xauth python3-xarray python3-venv python3-pip python3-setuptools
  python3-wheel poppler-utils
  # The web dashboard (web/, docs/dashboard.md): cpp-httplib (it brings OpenSSL, zlib and brotli),
  # and its tests in Debian's headless Chromium driven by Selenium, screenshots read by Pillow.
  libcpp-httplib-dev chromium chromium-driver python3-selenium python3-pil
  # The boundary prototypes of issue 33 (bench/boundary_prototypes.py): sparse direct solves.
  python3-scipy
  # A real single-node Slurm for the tests labelled slurm (scripts/slurm-dev.sh, docs/cluster.md).
  slurmctld
  slurmd
  slurm-client
  munge
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "setup: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
