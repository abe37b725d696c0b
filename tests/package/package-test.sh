#!/usr/bin/env bash
# The Debian package where nothing was built: makes it (scripts/package.sh), makes a clean
# Debian 12 root with mmdebstrap, installs the package there with apt (which resolves its
# Depends from the Debian archive), runs the programs from the installed files alone, then
# removes the package and checks that none of its files is left. A root that cannot be made
# (no way to the Debian archive) fails the test, saying why.
# Usage: package-test.sh SOURCE_DIR OUTPUT_DIR (the screenshot of the installed app goes there)
set -euo pipefail
src=$(cd "$1" && pwd)
out=$(mkdir -p "$2" && cd "$2" && pwd)
started=$(date +%s)
if [ "$(id -u)" -ne 0 ]; then  # a user with sudo, as the Quick start allows
  if sudo -n true 2>/dev/null; then exec sudo -n "$0" "$@"; fi
  echo "package-test: needs root or sudo without a password (mmdebstrap --mode=root, chroot," \
    "mount); the package was not tested" >&2
  exit 1
fi

"$src/scripts/package.sh"
version=$(sed -n 's/^project(handlab VERSION \([0-9.]*\) .*/\1/p' "$src/CMakeLists.txt")
deb=$src/build-package/handlab_${version}_amd64.deb

root=$(mktemp -d /tmp/handlab-debian-root.XXXXXX)
cleanup() {
  for m in dev/pts dev proc; do
    umount "$root/$m" 2>/dev/null || umount -l "$root/$m" 2>/dev/null || true
  done
  rm -rf --one-file-system "$root"
}
trap cleanup EXIT
if ! mmdebstrap --variant=apt --mode=root --include=xvfb,xauth,ca-certificates bookworm \
  "$root" >"$out/mmdebstrap.log" 2>&1; then
  tail -5 "$out/mmdebstrap.log" >&2
  echo "package-test: cannot make a clean Debian 12 root (mmdebstrap failed: above, and" \
    "$out/mmdebstrap.log); the package was not tested" >&2
  exit 1
fi
mount -t proc proc "$root/proc"
mount --bind /dev "$root/dev"
mount --bind /dev/pts "$root/dev/pts"
in_root() { chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root \
  LANG=C.UTF-8 /bin/bash -euo pipefail -c "$1"; }

cp "$deb" "$root/tmp/"
if ! in_root "apt-get update -q >/dev/null && apt-get install -y -q /tmp/$(basename "$deb") >/tmp/install.log 2>&1"; then
  cp "$root/tmp/install.log" "$out/install.log" 2>/dev/null || true
  tail -5 "$out/install.log" >&2 || true
  echo "package-test: apt could not install the package (above, and $out/install.log)" >&2
  exit 1
fi
echo "package-test: installed handlab $version into a clean Debian 12 root"
in_root "dpkg -L handlab" >"$out/package-files.txt"

# The programs, from the installed files alone, in a folder of their own.
in_root "mkdir /tmp/work && cd /tmp/work
  handlab-cli --version | grep -q 'handlab-cli $version (commit '
  handlab --version | grep -q '$version (commit '
  handlab-cli simulate --protocol /usr/share/handlab/studies/fine-manipulation-2021.json \
    --participants 2 --world proxy --seed 1 --db study.db --quiet >simulate.txt
  handlab-cli study info --db study.db | grep -q 'handlab $version (commit '
  handlab-cli analyze --db study.db >analysis.txt
  grep -q 'manipulation' analysis.txt
  handlab-cli export --db study.db --out export >/dev/null
  test -s export/trials.csv
  handlab-cli report --db study.db --out report >/dev/null
  test -s report/report.html && test -s report/report.pdf
  handlab-cli replications study.db --published studies/fine-manipulation-2021-published.json \
    >/dev/null
  handlab-cli sim pinch --cube 0.01 | grep -q ': held,'
  handlab-cli tracking info data/leap/pinch.json.lz >/dev/null
  man -w handlab-cli >/dev/null 2>&1 || test -s /usr/share/man/man1/handlab-cli.1.gz
  test -s /usr/share/bash-completion/completions/handlab-cli
  test -s /usr/share/applications/handlab.desktop
  xvfb-run -a handlab --study study.db --screenshot app.png
  test -s app.png"
cp "$root/tmp/work/app.png" "$out/installed-app.png"
echo "package-test: the installed programs ran (simulate, study info, analyze, export, report," \
  "replications, sim pinch, tracking, the app's screenshot: $out/installed-app.png)"

# Removed, nothing of it is left.
in_root "apt-get remove --purge -y -q handlab >/dev/null"
left=0
while read -r f; do
  if [ -f "$root$f" ] || [ -L "$root$f" ]; then echo "package-test: left behind: $f" >&2; left=1; fi
  case $f in /usr/share/handlab*) if [ -e "$root$f" ]; then echo "package-test: left: $f" >&2; left=1; fi ;; esac
done <"$out/package-files.txt"
if [ "$left" = 1 ]; then exit 1; fi
echo "package-test: removed; none of its $(wc -l <"$out/package-files.txt") paths is left"
echo "package-test: passed in $(($(date +%s) - started)) s"
