#!/usr/bin/env bash
# The report's pictures for the documentation: the PDF's pages as PNG (pdftoppm) and the HTML
# as a headless browser shows it (Debian's Chromium, installed here when missing: it is not a
# dependency of handlab, only of this script).
# Usage: scripts/report-screenshots.sh STUDY.db [OUT_DIR=docs/images]
set -euo pipefail
db=${1:?usage: scripts/report-screenshots.sh STUDY.db [OUT_DIR]}
out=${2:-docs/images}
root=$(cd "$(dirname "$0")/.." && pwd)
cli=${HANDLAB_CLI:-$root/build/app/handlab-cli}
if ! command -v chromium > /dev/null; then
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo=sudo
  $sudo apt-get install -y --no-install-recommends chromium
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$cli" report --db "$db" --out "$work"
mkdir -p "$out"
pdftoppm -r 80 -png "$work/report.pdf" "$work/page"
for f in "$work"/page-*.png; do
  n=$(basename "$f" .png | sed 's/page-0*//')
  cp "$f" "$out/report-page-$n.png"
done
chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1100,2200 \
  --screenshot="$out/report-html.png" "file://$work/report.html" 2> /dev/null
echo "wrote $out/report-page-*.png and $out/report-html.png"
