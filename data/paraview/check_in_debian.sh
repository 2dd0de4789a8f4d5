#!/usr/bin/env bash
# Runs data/paraview/open_run.py in Debian 12's real ParaView, in a throw-away root, on run folders
# made by `thaw run`, and saves one screenshot per run. Not a CTest test: on Debian 12 installing
# paraview removes libvtk9-dev (thaw's build dependency), so ParaView never goes on the build
# machine; it goes into a copy of a minimal debootstrapped root (as /work/shared/tools/
# fresh-debian.sh makes one) that is thrown away after the run. Needs root (chroot, mount).
# usage: data/paraview/check_in_debian.sh OUT_DIR RUN_DIR...
#   OUT_DIR/<run name>.png: the screenshot of each RUN_DIR (its middle time step, 640x480)
#   OUT_DIR/<run name>.log: what pvbatch printed
# env: FRESH_ROOT (the minimal root, default /tmp/fresh-root), FRESH_RUN (the copy, default
#   /tmp/pv-check-run; removed first), PV_DEB_CACHE (downloaded .debs kept between runs, default
#   /tmp/pv-check-debs), PV_PROGRAM (pvbatch or pvpython), PV_REUSE=1 (keep FRESH_RUN if it already
#   has ParaView: only the run folders are copied in again; for repeated checks).
# Debian's ParaView has no EGL/OSMesa offscreen build: it renders under Xvfb (xvfb-run) here.
set -eu
[ $# -ge 2 ] || { echo "usage: $0 OUT_DIR RUN_DIR..." >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
out=$(mkdir -p "$1" && cd "$1" && pwd); shift
ROOT=${FRESH_ROOT:-/tmp/fresh-root}
RUN=${FRESH_RUN:-/tmp/pv-check-run}
DEBS=${PV_DEB_CACHE:-/tmp/pv-check-debs}
PROGRAM=${PV_PROGRAM:-pvbatch}
[ -f "$ROOT/.done" ] || { echo "no minimal root at $ROOT: run /work/shared/tools/fresh-debian.sh once" >&2; exit 2; }
for m in proc sys dev var/cache/apt/archives; do umount -l "$RUN/$m" 2>/dev/null || true; done
# Never remove through a mount that is still there (the host's /dev or /sys).
if grep -q " $RUN/" /proc/mounts; then echo "$RUN: something is still mounted under it" >&2; exit 1; fi
reuse=
[ -n "${PV_REUSE:-}" ] && [ -x "$RUN/usr/bin/pvbatch" ] && [ -x "$RUN/usr/bin/xvfb-run" ] && reuse=1
if [ -z "$reuse" ]; then
  rm -rf "$RUN"
  cp -a "$ROOT" "$RUN"
fi
rm -rf "$RUN/check"
cp /etc/resolv.conf "$RUN/etc/resolv.conf"
mkdir -p "$DEBS/partial" "$RUN/check/runs" "$RUN/check/out"
cp "$here/open_run.py" "$RUN/check/"
for dir in "$@"; do cp -a "$dir" "$RUN/check/runs/$(basename "$dir")"; done
mount -t proc proc "$RUN/proc"
mount --rbind /sys "$RUN/sys"
mount --rbind /dev "$RUN/dev"
mount --bind "$DEBS" "$RUN/var/cache/apt/archives"
trap 'for m in proc sys dev var/cache/apt/archives; do umount -l "$RUN/$m" 2>/dev/null || true; done' EXIT
in_root() {
  chroot "$RUN" /usr/bin/env -i HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    LANG=C.UTF-8 DEBIAN_FRONTEND=noninteractive bash -c "$1"
}
[ -n "$reuse" ] || in_root "apt-get update -qq && apt-get install -y -qq --no-install-recommends \
  paraview python3-paraview xvfb xauth >/check/out/apt.log 2>&1 || { tail -20 /check/out/apt.log; exit 1; }"
in_root "dpkg-query -W paraview"
status=0
for dir in "$@"; do
  name=$(basename "$dir")
  # A second try when Xvfb was not up in time ("bad X server connection", seen under load).
  if in_root "cd /check && for try in 1 2; do xvfb-run -a -s '-screen 0 1280x1024x24' $PROGRAM \
      open_run.py runs/$name --screenshot out/$name.png >out/$name.log 2>&1 && exit 0; \
      grep -q 'bad X server connection' out/$name.log || exit 1; done; exit 1"; then
    echo "$name: ok"
  else
    echo "$name: FAILED (exit $?)"
    status=1
  fi
  cp "$RUN/check/out/$name.log" "$out/$name.log"
  sed 's/^/  /' "$out/$name.log"
  [ -f "$RUN/check/out/$name.png" ] && cp "$RUN/check/out/$name.png" "$out/$name.png"
done
exit $status
