#!/usr/bin/env bash
# Screenshots an sst-eval report with headless Chromium, to look at a report (or attach it to a
# review) without a desktop. The window is tall because a headless screenshot captures the window
# only, not the whole page.
#   scripts/report_screenshot.sh results/X/report.html out.png [width] [height]
set -euo pipefail

if [ $# -lt 2 ] || [ $# -gt 4 ]; then
  echo "usage: $0 report.html out.png [width (1400)] [height (5000)]" >&2
  exit 2
fi
report=$1
out=$2
width=${3:-1400}
height=${4:-5000}

chromium=""
for candidate in chromium chromium-browser google-chrome; do
  if command -v "$candidate" >/dev/null 2>&1; then chromium=$(command -v "$candidate"); break; fi
done
if [ -z "$chromium" ]; then
  echo "error: chromium not found (install it: apt-get install chromium)" >&2
  exit 1
fi
if [ ! -f "$report" ]; then
  echo "error: $report: no such file" >&2
  exit 1
fi
if ! [[ "$width" =~ ^[0-9]+$ && "$height" =~ ^[0-9]+$ ]]; then
  echo "error: width and height must be whole numbers of pixels (got '$width', '$height')" >&2
  exit 2
fi

report_abs=$(realpath "$report")
mkdir -p "$(dirname "$out")"
out_abs=$(realpath "$out")
# A throwaway profile: never touch the user's, and leave nothing behind.
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
rm -f "$out_abs"

timeout 120 "$chromium" --headless=new --no-sandbox --disable-gpu --hide-scrollbars \
  --user-data-dir="$profile" --window-size="$width,$height" --screenshot="$out_abs" \
  "file://$report_abs" >/dev/null 2>&1 || true
if [ ! -s "$out_abs" ]; then
  echo "error: chromium wrote no screenshot to $out (run it by hand to see why)" >&2
  exit 1
fi
echo "$out"
