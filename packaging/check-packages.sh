#!/usr/bin/env bash
# The packaging test (ctest -L packaging): makes the .debs of a built tree with
# cpack and checks what they hold, their control data, the systemd unit and
# what lintian says. Every tool it needs is required: a missing one fails the
# test with its name (packaging/install-deps.sh installs them all).
# Usage: check-packages.sh BUILD_DIR OUT_DIR [GUI]
#   GUI: OFF for a build with LUCENT_BUILD_GUI=OFF (no workstation, no desktop entry).
set -euo pipefail

if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  echo "usage: $0 BUILD_DIR OUT_DIR [GUI]" >&2
  exit 2
fi
build=$(realpath "$1")
out=$2
gui=${3:-ON}
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
pass() { echo "ok: $*"; }

for tool in cpack dpkg-deb dpkg-shlibdeps lintian systemd-analyze; do
  if ! command -v "$tool" >/dev/null; then
    echo "FAIL: $tool is not installed; packaging/install-deps.sh installs it" >&2
    exit 1
  fi
done
[ -f "$build/CPackConfig.cmake" ] || { echo "FAIL: $build has no CPackConfig.cmake" >&2; exit 1; }

rm -rf "$out"
mkdir -p "$out"
started=$SECONDS
if ! cpack -G DEB --config "$build/CPackConfig.cmake" -B "$out" >"$out/cpack.log" 2>&1; then
  cat "$out/cpack.log" >&2
  echo "FAIL: cpack -G DEB failed (log above)" >&2
  exit 1
fi
echo "cpack: $((SECONDS - started)) s"

# The one .deb of PACKAGE, or fail.
deb_of() {
  local found=("$out"/"$1"_*.deb)
  if [ ${#found[@]} -ne 1 ] || [ ! -f "${found[0]}" ]; then
    echo "FAIL: cpack made no single $1_*.deb in $out" >&2
    exit 1
  fi
  echo "${found[0]}"
}
lucent=$(deb_of lucent)
server=$(deb_of lucent-server)
common=$(deb_of lucent-common)

# PACKAGE's .deb holds each PATH (as dpkg-deb -c lists it, without "./").
expect_files() {
  local deb=$1
  shift
  local listing
  listing=$(dpkg-deb -c "$deb" | awk '{print $6}' | sed 's|^\./||')
  for path in "$@"; do
    if grep -qx "$path" <<<"$listing"; then
      pass "$(basename "$deb") holds $path"
    else
      fail "$(basename "$deb") lacks $path"
    fi
  done
}
expect_files "$lucent" usr/bin/lucent-cli usr/share/man/man1/lucent-cli.1.gz \
  usr/share/doc/lucent/copyright usr/share/doc/lucent/changelog.gz
if [ "$gui" != OFF ]; then
  expect_files "$lucent" usr/bin/lucent usr/share/man/man1/lucent.1.gz \
    usr/share/applications/lucent.desktop usr/share/icons/hicolor/scalable/apps/lucent.svg
fi
expect_files "$server" usr/bin/lucent-server usr/share/man/man1/lucent-server.1.gz \
  lib/systemd/system/lucent-server.service etc/lucent/lucent-server.conf \
  usr/share/doc/lucent-server/copyright usr/share/doc/lucent-server/changelog.gz
expect_files "$common" usr/share/lucent/presets/ct-bone.json usr/share/lucent/hanging/mpr-2x2.json usr/libexec/lucent/lucent-frame-decoder \
  usr/share/doc/lucent-common/copyright usr/share/doc/lucent-common/changelog.gz

# Control data: dependencies that dpkg-shlibdeps found, the conffile, the
# maintainer scripts.
for deb in "$lucent" "$server"; do
  depends=$(dpkg-deb -f "$deb" Depends)
  if grep -q 'libc6 (>=' <<<"$depends" && grep -q 'libqt6core6 (>=' <<<"$depends"; then
    pass "$(basename "$deb") Depends (dpkg-shlibdeps): $depends"
  else
    fail "$(basename "$deb") Depends lacks the libraries dpkg-shlibdeps finds: '$depends'"
  fi
  grep -q 'lucent-common (= ' <<<"$depends" || fail "$(basename "$deb") does not depend on lucent-common"
  # Qt loads its SQLite driver (the study store's index) at run time.
  grep -q 'libqt6sql6-sqlite' <<<"$depends" || fail "$(basename "$deb") does not depend on libqt6sql6-sqlite"
  # JPEG-LS frames are decoded by dcmtk's dcmdjpls, run as a program.
  grep -q 'dcmtk' <<<"$depends" || fail "$(basename "$deb") does not depend on dcmtk"
done
# lucent-common holds lucent-frame-decoder (a program): its libraries from dpkg-shlibdeps.
grep -q 'libgdcm' <<<"$(dpkg-deb -f "$common" Depends)" ||
  fail "lucent-common does not depend on GDCM, which lucent-frame-decoder links"
grep -q 'adduser' <<<"$(dpkg-deb -f "$server" Depends)" || fail "lucent-server does not depend on adduser"
control=$out/control-server
dpkg-deb -e "$server" "$control"
if [ "$(cat "$control/conffiles" 2>/dev/null)" = /etc/lucent/lucent-server.conf ]; then
  pass "conffiles: /etc/lucent/lucent-server.conf"
else
  fail "lucent-server's conffiles is not /etc/lucent/lucent-server.conf"
fi
for script in postinst prerm postrm; do
  [ -x "$control/$script" ] || fail "lucent-server has no executable $script"
done
grep -q 'adduser --system' "$control/postinst" || fail "lucent-server's postinst makes no system user"
if [ "$gui" != OFF ]; then
  desktop=$(dpkg-deb --fsys-tarfile "$lucent" | tar -xO ./usr/share/applications/lucent.desktop)
  if grep -q '^MimeType=application/dicom;' <<<"$desktop"; then
    pass "lucent.desktop opens application/dicom"
  else
    fail "lucent.desktop has no MimeType=application/dicom;"
  fi
fi

# The unit, in the package's tree beside the host's units (for the targets
# it names): systemd-analyze verify says nothing, and its exposure stays at
# most 2.0 (of 10).
root=$out/root
dpkg-deb -x "$server" "$root"
cp -an /lib/systemd/system/. "$root/lib/systemd/system/"
if verify=$(systemd-analyze verify --man=no --root="$root" lucent-server.service 2>&1) && [ -z "$verify" ]; then
  pass "systemd-analyze verify lucent-server.service"
else
  fail "systemd-analyze verify lucent-server.service: $verify"
fi
if security=$(systemd-analyze security --offline=true --root="$root" --threshold=20 \
  lucent-server.service 2>&1); then
  pass "systemd-analyze security: $(grep 'Overall exposure' <<<"$security")"
else
  echo "$security" >&2
  fail "systemd-analyze security: exposure above 2.0"
fi

# lintian: no error on any package (warnings and notes are printed).
started=$SECONDS
if lintian --fail-on error --display-level '>=warning' "$lucent" "$server" "$common" \
  >"$out/lintian.log" 2>&1; then
  pass "lintian: no error ($((SECONDS - started)) s)"
else
  fail "lintian reports errors"
fi
grep -v '^running with root privileges' "$out/lintian.log" || true

if [ "$failures" -ne 0 ]; then
  echo "check-packages: $failures check(s) failed" >&2
  exit 1
fi
echo "check-packages: the packages in $out are as they should be"
