#!/usr/bin/env bash
# Installs Lucent's packages into a fresh Debian 12 root and uses them there as
# a user and an administrator would: lucent-cli info on the demo CT, and
# lucent-server started as its system user on a token file of mode 0600 (after
# a token file others can read was refused), its page fetched on loopback.
# The root is made by mmdebstrap from this machine's apt sources and removed
# at the end; the commands run chrooted, in a mount namespace of their own,
# without systemd (the unit is checked with systemd-analyze instead).
#
# Usage (as root): packaging/try-packages.sh [DEB_DIR]
#   DEB_DIR: a folder of lucent_*.deb, lucent-server_*.deb, lucent-common_*.deb.
#   Without it: configures build-deb (Release, no distributed renderer, so the
#   packages do not pull in Open MPI and ParaView), builds it and runs cpack.
set -euo pipefail
cd "$(dirname "$0")/.."

say() { echo "try-packages: $*"; }
die() {
  echo "try-packages: $*" >&2
  exit 1
}
[ "$(id -u)" -eq 0 ] || die "needs root (mmdebstrap makes the root as root, then chroot)"
for tool in mmdebstrap cmake cpack unshare chroot systemd-analyze; do
  command -v "$tool" >/dev/null || die "$tool is not installed; packaging/install-deps.sh installs it"
done

if [ $# -ge 1 ]; then
  debs=$(realpath "$1")
else
  say "building the packages in build-deb (-DLUCENT_DISTRIBUTED=OFF -DLUCENT_BUILD_TESTS=OFF)"
  cmake -S . -B build-deb -G Ninja -DLUCENT_DISTRIBUTED=OFF -DLUCENT_BUILD_TESTS=OFF >/dev/null
  cmake --build build-deb -j2 >/dev/null
  rm -rf build-deb/debs
  cpack -G DEB --config build-deb/CPackConfig.cmake -B build-deb/debs >/dev/null
  debs=$(realpath build-deb/debs)
fi
packages=()
for name in lucent lucent-server lucent-common; do
  found=("$debs/${name}"_*.deb)
  [ -f "${found[0]}" ] || die "$debs holds no ${name}_*.deb"
  packages+=("${found[0]}")
done
say "packages: ${packages[*]##*/}"

work=$(mktemp -d /var/tmp/lucent-try.XXXXXX)
trap 'rm -rf "$work"' EXIT
root=$work/root
mkdir -p "$work/debs"
cp "${packages[@]}" "$work/debs/"
# Run by mmdebstrap with the root as $1: the packages through apt, which
# fetches what they depend on.
cat >"$work/install-hook.sh" <<'HOOK'
set -eu
chroot "$1" sh -c 'DEBIAN_FRONTEND=noninteractive apt-get install -y -q /tmp/debs/*.deb \
  invesalius-examples curl' >"$1/tmp/apt.log" 2>&1 || { cat "$1/tmp/apt.log"; exit 1; }
grep -E "^(Setting up lucent|[0-9]+ upgraded)" "$1/tmp/apt.log"
HOOK

# The machine's apt sources (deb822 or one-line), as apt itself reads them.
sources=()
for file in /etc/apt/sources.list /etc/apt/sources.list.d/*.sources /etc/apt/sources.list.d/*.list; do
  [ -s "$file" ] && sources+=("$file")
done
[ ${#sources[@]} -gt 0 ] || die "this machine has no apt sources in /etc/apt"

say "mmdebstrap --variant=apt bookworm, then apt-get install of the three packages," \
  "invesalius-examples (the demo CT) and curl"
started=$SECONDS
mmdebstrap --quiet --variant=apt --include=ca-certificates \
  --customize-hook="copy-in $work/debs /tmp" \
  --customize-hook="sh $work/install-hook.sh \"\$1\"" \
  bookworm "$root" "${sources[@]}"
say "root ready in $((SECONDS - started)) s: $(du -sh "$root" | cut -f1)"

# Everything else runs in the root, in a mount namespace that takes /proc,
# /dev and /sys with it when it ends.
cat >"$work/inside.sh" <<'INSIDE'
set -euo pipefail
root=$1
mount -t proc proc "$root/proc"
mount --rbind /dev "$root/dev"
mount -t sysfs -o ro sysfs "$root/sys"
in_root() {
  echo "+ $*"
  chroot "$root" "$@"
}

echo "== installed"
chroot "$root" dpkg-query -W -f '${Package} ${Version} ${Status}\n' lucent lucent-server lucent-common
echo "== what postinst made"
in_root getent passwd lucent
in_root stat -c '%A %U:%G %n' /etc/lucent /etc/lucent/lucent-server.conf /var/lib/lucent /var/lib/lucent/store
in_root dpkg-statoverride --list /etc/lucent

echo "== lucent-cli info on the demo CT"
in_root lucent-cli info /usr/share/doc/invesalius-examples/examples/Cranium.inv3

echo "== the server refuses a token file others can read"
chroot "$root" install -o lucent -g lucent -m 0644 /dev/null /etc/lucent/tokens
od -An -N24 -tx1 /dev/urandom | tr -d ' \n' >"$root/etc/lucent/tokens"
echo >>"$root/etc/lucent/tokens"
set +e
in_root runuser -u lucent -- lucent-server --listen 127.0.0.1:0 --store /var/lib/lucent/store \
  --token-file /etc/lucent/tokens --check
status=$?
set -e
echo "exit status $status"
[ "$status" -eq 3 ] || { echo "FAIL: lucent-server started on a token file of mode 0644"; exit 1; }

echo "== the server as the user lucent on a token file of mode 0600"
in_root chmod 0600 /etc/lucent/tokens
in_root stat -c '%A %U:%G %n' /etc/lucent/tokens
log=$root/tmp/lucent-server.log
echo "+ runuser -u lucent -- lucent-server --listen 127.0.0.1:0 --store /var/lib/lucent/store" \
  "--token-file /etc/lucent/tokens --backend cpu --data .../Cranium.inv3 &"
chroot "$root" runuser -u lucent -- lucent-server --listen 127.0.0.1:0 \
  --store /var/lib/lucent/store --token-file /etc/lucent/tokens --backend cpu \
  --data /usr/share/doc/invesalius-examples/examples/Cranium.inv3 >"$log" 2>&1 &
server=$!
port=
for _ in $(seq 1 120); do
  port=$(sed -n 's/^listening on 127\.0\.0\.1:\([0-9]*\)$/\1/p' "$log")
  [ -n "$port" ] || ! kill -0 "$server" 2>/dev/null && break
  sleep 0.5
done
cat "$log"
if [ -z "$port" ]; then
  echo "FAIL: lucent-server did not start"
  exit 1
fi
# The server process (not runuser) among this root's processes: its user.
for proc in /proc/[0-9]*; do
  if [ "$(cat "$proc/comm" 2>/dev/null)" = lucent-server ] &&
    [ "$(readlink "$proc/root")" = "$root" ]; then
    uid=$(awk '/^Uid:/ {print $2}' "$proc/status")
    echo "lucent-server runs as uid $uid ($(chroot "$root" id -nu "$uid")), pid ${proc#/proc/}"
  fi
done
echo "+ curl http://127.0.0.1:$port/ (in the root)"
page=$(chroot "$root" curl -sS --max-time 10 -w '\nHTTP %{http_code} %{content_type} %{size_download} bytes\n' \
  "http://127.0.0.1:$port/")
grep -m1 -i '<title>' <<<"$page" || true
tail -n 1 <<<"$page"
grep -q '^HTTP 200 text/html' <<<"$(tail -n 1 <<<"$page")" || { echo "FAIL: no page"; exit 1; }
echo "== a frame of the demo CT rendered by the server for lucent-cli (WebSocket, the token)"
echo "+ lucent-cli render .../Cranium.inv3 --backend ws://127.0.0.1:$port --token (the token)" \
  "--size 256x256 --preset ct-bone -o /tmp/frame.png"
chroot "$root" lucent-cli render /usr/share/doc/invesalius-examples/examples/Cranium.inv3 \
  --backend "ws://127.0.0.1:$port" --token "$(cat "$root/etc/lucent/tokens")" --size 256x256 \
  --preset ct-bone -o /tmp/frame.png
cp "$root/tmp/frame.png" /var/tmp/lucent-try-frame.png
echo "frame: /var/tmp/lucent-try-frame.png, $(stat -c %s /var/tmp/lucent-try-frame.png) bytes"
kill "$server"
wait "$server" || true

echo "== purge: /etc/lucent goes, the study store and the user stay"
chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get purge -y -q lucent-server |
  grep -E "^(Removing|Purging) "
in_root ls -ld /var/lib/lucent/store
in_root getent passwd lucent
[ ! -e "$root/etc/lucent" ] || { echo "FAIL: /etc/lucent is still there after purge"; exit 1; }
echo "/etc/lucent: gone; statoverrides left: $(chroot "$root" dpkg-statoverride --list | wc -l)"
INSIDE
unshare --mount --propagation private bash "$work/inside.sh" "$root"

say "the unit: systemd-analyze verify and security --offline on the package's files"
unit_root=$work/unit
dpkg-deb -x "${packages[1]}" "$unit_root"
cp -an /lib/systemd/system/. "$unit_root/lib/systemd/system/"
systemd-analyze verify --man=no --root="$unit_root" lucent-server.service && say "verify: no complaint"
systemd-analyze security --offline=true --root="$unit_root" lucent-server.service | tail -n 1
say "done: the packages install, lucent-cli reads the demo CT, lucent-server serves its page" \
  "and renders it, purge leaves the study store"
