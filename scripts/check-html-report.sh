#!/usr/bin/env bash
# Renders a qverify report.html in headless Chromium (Debian's package), saves a
# screenshot next to it, and fails unless the rendered page has its plot: an
# <svg> inside <figure id="plot"> with at least MIN_POINTS data points.
#   scripts/check-html-report.sh DIR/report.html [MIN_POINTS]
set -euo pipefail
html="$(realpath "$1")"; min="${2:-4}"
browser="$(command -v chromium || command -v chromium-browser || true)"
[ -n "$browser" ] || { echo "check-html-report: chromium is not installed (apt-get install chromium)" >&2; exit 77; }
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking
       --disable-component-update --disable-sync --user-data-dir="$tmp/profile" --window-size=1200,1600)
timeout 60 "$browser" "${flags[@]}" --dump-dom "file://$html" > "$tmp/dom.html" 2>/dev/null
timeout 60 "$browser" "${flags[@]}" --screenshot="${html%.html}.png" "file://$html" >/dev/null 2>&1
points=$(grep -o '<circle class="point"' "$tmp/dom.html" | wc -l)
if ! grep -q '<figure[^>]*id="plot' "$tmp/dom.html" || ! grep -q '<svg' "$tmp/dom.html"; then
  echo "check-html-report: no plot in the rendered page $html" >&2; exit 1
fi
if [ "$points" -lt "$min" ]; then
  echo "check-html-report: the plot has $points data points, expected at least $min" >&2; exit 1
fi
[ -s "${html%.html}.png" ] || { echo "check-html-report: no screenshot was rendered" >&2; exit 1; }
echo "check-html-report: $html renders with its plot ($points points); screenshot ${html%.html}.png"
