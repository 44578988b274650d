#!/usr/bin/env bash
# Replaces a committed report folder with a finished sweep's: the explicit step after
# `make bench` (scripts/paper-tables.sh). Copies SWEEP_DIR to REPORT_DIR without what is
# not committed (the recorded Newton systems, checkpoints, empty logs) and with large
# contact.csv files gzipped; the old REPORT_DIR stays in git's history.
# Usage: scripts/publish-report.sh SWEEP_DIR REPORT_DIR
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 SWEEP_DIR REPORT_DIR" >&2; exit 2; }
from=$1 to=$2
[ -f "$from/report.md" ] || { echo "$from holds no finished sweep (no report.md)" >&2; exit 2; }
[ "$(realpath "$from")" != "$(realpath -m "$to")" ] || { echo "$from is $to already" >&2; exit 2; }
staging=$(mktemp -d "$(dirname "$to")/.publish.XXXXXX")
trap 'rm -rf "$staging"' EXIT
tar -C "$from" --exclude=./records --exclude=checkpoint.bin --exclude='*.log' -cf - . | tar -C "$staging" -xf -
find "$staging" -name contact.csv -size +1M -exec gzip -9 {} +
find "$staging" -type f -empty -delete
rm -rf "$to"
mv "$staging" "$to"
trap - EXIT
echo "published $from as $to" >&2
