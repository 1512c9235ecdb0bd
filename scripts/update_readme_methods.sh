#!/usr/bin/env bash
# Rewrites docs/methods.md's generated section on methods and parameters (from the line
# "<!-- methods: ..." through "<!-- end methods -->") with the output of
# `sst-render --list-methods --markdown`, which prints that section, markers included.
# tests/app/readme_test.cpp fails when the section differs from what the program prints.
# Usage: scripts/update_readme_methods.sh [path/to/sst-render]   (default: build/sst-render)
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-build/sst-render}
doc=docs/methods.md
generated=$(mktemp)
updated=$(mktemp)
trap 'rm -f "$generated" "$updated"' EXIT
"$exe" --list-methods --markdown > "$generated"
awk -v generated="$generated" -v doc="$doc" '
  /^<!-- methods:/ { while ((getline line < generated) > 0) print line; skipping = 1; found = 1; next }
  skipping && /^<!-- end methods -->$/ { skipping = 0; next }
  !skipping { print }
  END { if (!found || skipping) { print "error: " doc ": no <!-- methods: ... --> ... <!-- end methods --> section" > "/dev/stderr"; exit 1 } }
' "$doc" > "$updated"
cat "$updated" > "$doc"
