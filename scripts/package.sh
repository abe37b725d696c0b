#!/usr/bin/env bash
# Builds handlab's Debian package, build-package/handlab_<version>_amd64.deb, from this tree:
# a Release build for any x86-64 CPU (HANDLAB_CPU=generic, the Debian baseline), installed into
# a staging root as /usr, with Depends computed by dpkg-shlibdeps from what the programs link,
# then checked by lintian. The version is CMakeLists.txt's project() version.
# Usage: scripts/package.sh [--no-lintian]
set -euo pipefail
cd "$(dirname "$0")/.."
umask 022
lint=1
if [ "${1:-}" = "--no-lintian" ]; then lint=0; fi

scripts/install-deps.sh
tree=build-package
mkdir -p "$tree"
cmake -S . -B "$tree" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr \
  -DHANDLAB_CPU=generic -DHANDLAB_WERROR=ON -DHANDLAB_BUILD_TESTS=OFF \
  -DHANDLAB_BUILD_BENCHMARKS=OFF >"$tree/configure.log" 2>&1 ||
  { cat "$tree/configure.log"; exit 1; }
# The man pages' date: the commit's, so that the same commit packages the same bytes.
SOURCE_DATE_EPOCH=$(git log -1 --format=%ct 2>/dev/null || date +%s)
export SOURCE_DATE_EPOCH
cmake --build "$tree" -j "$(nproc)"

version=$(sed -n 's/^project(handlab VERSION \([0-9.]*\) .*/\1/p' CMakeLists.txt)
if [ -z "$version" ]; then
  echo "package.sh: no version in CMakeLists.txt's project()" >&2
  exit 1
fi
stage=$tree/stage
rm -rf "$stage"
DESTDIR="$PWD/$stage" cmake --install "$tree" --strip >/dev/null
doc=$stage/usr/share/doc/handlab
install -d "$doc"
install -m 644 scripts/package/copyright "$doc/copyright"
# The Debian changelog names the version; what changed in it is CHANGELOG.md.
maintainer="handlab developers <maintainers@handlab.invalid>"  # no list exists: .invalid says so
when=$(git log -1 --format=%aD 2>/dev/null || date -R)
printf 'handlab (%s) unstable; urgency=medium\n\n  * handlab %s: /usr/share/doc/handlab/CHANGELOG.md.gz says what changed.\n\n -- %s  %s\n' \
  "$version" "$version" "$maintainer" "$when" | gzip -9n >"$doc/changelog.gz"
gzip -9n -c CHANGELOG.md >"$doc/CHANGELOG.md.gz"
gzip -9n "$stage"/usr/share/man/man1/*.1

# Depends: the shared libraries' packages (dpkg-shlibdeps reads a control file of a source
# package; a throwaway one names the package), and the Qt platform plugins, which Qt loads at
# run time rather than links: the app's window (xcb) and the CLI's offscreen drawing.
shlibs=$tree/shlibs
rm -rf "$shlibs" && mkdir -p "$shlibs/debian"
printf 'Source: handlab\n\nPackage: handlab\nArchitecture: amd64\n' >"$shlibs/debian/control"
depends=$(cd "$shlibs" && dpkg-shlibdeps -O -e"$OLDPWD/$stage/usr/bin/handlab" \
  -e"$OLDPWD/$stage/usr/bin/handlab-cli" | sed -n 's/^shlibs:Depends=//p')
if [ -z "$depends" ]; then
  echo "package.sh: dpkg-shlibdeps found no dependencies" >&2
  exit 1
fi
depends="$depends, qt6-qpa-plugins"

install -d "$stage/DEBIAN"
cat >"$stage/DEBIAN/control" <<CONTROL
Package: handlab
Version: $version
Architecture: amd64
Maintainer: $maintainer
Installed-Size: $(du -sk --exclude=DEBIAN "$stage" | cut -f1)
Depends: $depends
Recommends: libopenxr-loader1, libvulkan1
Section: science
Priority: optional
Description: user studies of fine virtual manipulation with tracked hands
 handlab runs and analyses user studies in which a tracked hand (Leap Motion or
 OpenXR hand tracking) drives a simulated soft hand of another size through pose
 retargeting, to pick and place small cubes: the study "Fine Virtual
 Manipulation with Hands of Different Sizes" (ISMAR 2021) and designs beyond it.
 .
 The package holds the app (handlab), the headless command line (handlab-cli:
 sessions, simulated participants, repeated-measures analysis equal to R,
 reports, power analysis), the study's protocol and published values, example
 protocols and real Leap Motion recordings under /usr/share/handlab.
CONTROL
(cd "$stage" && find usr -type f -print0 | sort -z | xargs -0 md5sum >DEBIAN/md5sums)
chmod 644 "$stage/DEBIAN/control" "$stage/DEBIAN/md5sums"

rm -f "$tree"/handlab_*_amd64.deb  # one package in the tree: this version's
deb=$tree/handlab_${version}_amd64.deb
dpkg-deb --root-owner-group -Zxz --build "$stage" "$deb" >/dev/null
echo "package.sh: wrote $deb ($(du -h "$deb" | cut -f1))"
if [ "$lint" = 1 ]; then
  # lintian exits 1 when it reports errors, above 1 when it could not check.
  status=0
  lintian --tag-display-limit 0 "$deb" >"$tree/lintian.txt" 2>"$tree/lintian.err" || status=$?
  cat "$tree/lintian.txt"
  if [ "$status" -gt 1 ]; then
    cat "$tree/lintian.err" >&2
    echo "package.sh: lintian could not check the package (exit $status)" >&2
    exit 1
  fi
  if grep -q '^E:' "$tree/lintian.txt"; then
    echo "package.sh: lintian found errors (above)" >&2
    exit 1
  fi
  echo "package.sh: lintian: no errors ($(grep -c '^W:' "$tree/lintian.txt" || true) warnings)"
fi
