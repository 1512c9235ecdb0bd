#!/usr/bin/env bash
# Rewrites README.md's generated section on methods and parameters (from the line
# "<!-- methods: ..." through "<!-- end methods -->") with the output of
# `sst-render --list-methods --markdown`, which prints that section, markers included.
# Usage: scripts/update_readme_methods.sh [path/to/sst-render]   (default: build/sst-render)
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-build/sst-render}
generated=$(mktemp)
updated=$(mktemp)
trap 'rm -f "$generated" "$updated"' EXIT
"$exe" --list-methods --markdown > "$generated"
awk -v generated="$generated" '
  /^<!-- methods:/ { while ((getline line < generated) > 0) print line; skipping = 1; found = 1; next }
  skipping && /^<!-- end methods -->$/ { skipping = 0; next }
  !skipping { print }
  END { if (!found || skipping) { print "error: README.md: no <!-- methods: ... --> ... <!-- end methods --> section" > "/dev/stderr"; exit 1 } }
' README.md > "$updated"
cat "$updated" > README.md
