#!/usr/bin/env bash
# Looks at a report as a reader does: a screenshot of index.html in headless Chromium,
# 1200 px wide (the width the report is laid out for).
#   reports/screenshot.sh REPORT_DIR/index.html OUT.png [HEIGHT, default 900]
# Needs Debian's `chromium`: ERYTHRO_BROWSER=1 ci/install-deps.sh installs it.
set -euo pipefail
if [[ $# -lt 2 ]]; then echo "usage: $0 INDEX.html OUT.png [HEIGHT]" >&2; exit 2; fi
page=$(realpath "$1") png=$(realpath -m "$2") height=${3:-900}
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
  --disable-background-networking --disable-component-update --disable-sync \
  --user-data-dir="$profile" --hide-scrollbars --virtual-time-budget=8000 \
  --window-size="1200,$height" --screenshot="$png" "file://$page" 2>/dev/null
echo "$png"
