#!/bin/sh
# Every script in tools/ answers --help with what it does (its header) and
# status 0, instead of building, installing or running anything.
# Usage: tools-help.sh SOURCE_DIR
set -eu
src=$1
for t in "$src"/tools/*; do
	[ -x "$t" ] || continue
	case "$t" in *.py | *.in) continue ;; esac
	out=$(cd /tmp && "$t" --help 2>&1) || { echo "$t --help: status $?" >&2; exit 1; }
	first=$(echo "$out" | head -n 1)
	[ -n "$first" ] || { echo "$t --help: no text" >&2; exit 1; }
done
echo "tools: every script answers --help"
