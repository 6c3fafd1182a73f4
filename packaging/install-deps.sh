#!/usr/bin/env bash
# Installs every Debian 12 package that building, running and testing Lucent need, and the
# npm packages of the tests (dcmjs, a foreign DICOM SEG writer: tests/segdicom/dcmjs).
# Idempotent: when everything is present it prints nothing and exits 0.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build ccache pkg-config git
  # libraries
  qt6-base-dev libqt6opengl6-dev libgl-dev libqt6sql6-sqlite
  libgdcm-dev libgdcm-tools libdcmtk-dev dcmtk libglm-dev libegl-dev libepoxy-dev
  zlib1g-dev nlohmann-json3-dev libpng-dev
  # .inv3 projects: the tar.gz read through libarchive, main.plist through libplist
  libarchive-dev libplist-dev
  # export: ZIP archives of DICOM files
  libzip-dev
  # the render server: WebSockets; JPEG frames through Qt's jpeg plugin (libjpeg-turbo)
  qt6-websockets-dev libqt6websockets6 libjpeg62-turbo
  # GL without a GPU, and a display for the GUI tests
  libegl-mesa0 libgl1-mesa-dri mesa-utils xvfb xauth
  # the demo study (real head CT, opened with no download)
  invesalius-examples
  # the test PACS: Orthanc with DICOMweb, started by the pacs tests on loopback
  orthanc orthanc-dicomweb
  # the distributed renderer: Open MPI, and IceT (shipped in Debian only inside ParaView 5.11)
  libopenmpi-dev openmpi-bin paraview-dev
  # surfaces: mesh decimation (meshoptimizer); VTK's marching cubes for the surface benchmark,
  # and VTK's volume mappers, the render benchmarks' anchor (app/bench/vtk_anchor.py)
  libmeshoptimizer-dev python3-vtk9
  # the web test: headless Chromium driven through chromedriver; openssl makes the TLS test's certificate
  chromium chromium-driver openssl
  # packages: cpack's DEB generator with dpkg-shlibdeps (dpkg-dev), lintian on the .debs,
  # systemd-analyze for the unit, mmdebstrap and curl for packaging/try-packages.sh
  dpkg-dev lintian systemd mmdebstrap curl
  clang libfuzzer-14-dev libomp-14-dev  # fuzzing: LUCENT_FUZZ=ON, packaging/fuzz.sh (OpenMP for clang)
  # reading tools: dciodvfy checks the measurement SR and segmentation SEG files
  dicom3tools
  # node runs dcmjs (OHIF's DICOM library), the SEG tests' foreign writer (its npm ships with
  # Debian's nodejs only through the npm package; NodeSource's nodejs carries its own)
  nodejs
  # teaching: QR codes for invite links; movies through FFmpeg's libraries (ffprobe checks them)
  libqrencode-dev libavcodec-dev libavformat-dev libavutil-dev libswscale-dev ffmpeg
  # the invite test reads the QR codes back with a real decoder (zbarimg)
  zbar-tools
  # rigid and affine registration of two series (core/registration): ITK 5.2
  libinsighttoolkit5-dev
  # the registration benchmark's anchor (tests/perf/bench_register_elastix): elastix 5.0.1
  elastix
  # the CPU render benchmark's shear-warp anchor (app/bench/VolPackAnchor): VolPack 1.0b3
  libvolpack1-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
if [ ${#missing[@]} -ne 0 ]; then
  echo "install-deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
command -v npm >/dev/null || $SUDO apt-get install -y -qq --no-install-recommends npm >/dev/null

# The tests' npm packages, pinned by their package-lock.json.
dcmjs_dir="$(cd "$(dirname "$0")/.." && pwd)/tests/segdicom/dcmjs"
if [ ! -d "$dcmjs_dir/node_modules/dcmjs" ]; then
  echo "install-deps: npm ci in $dcmjs_dir"
  (cd "$dcmjs_dir" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
fi
