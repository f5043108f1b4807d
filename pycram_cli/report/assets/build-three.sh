#!/usr/bin/env bash
# Rebuilds three.min.js, the three.js that report pages carry inline: the parts named in
# three-entry.js, from the npm package `three`, bundled by esbuild into one classic script
# (global THREE) so that a page opened from disk needs no module loading, network or server.
# Needs node and npm (the npm registry); run it when updating three.js, and commit the result.
set -euo pipefail
THREE_VERSION=0.187.0
ESBUILD_VERSION=0.28.2
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
npm init -y >/dev/null
npm install --no-audit --no-fund --silent "three@$THREE_VERSION" "esbuild@$ESBUILD_VERSION"
cp "$here/three-entry.js" entry.js
{
    printf '/* three.js %s (https://threejs.org), MIT License, Copyright 2010-2026 three.js authors: see three.LICENSE.\n' "$THREE_VERSION"
    printf '   Bundled for pycram reports by build-three.sh with esbuild %s. */\n' "$ESBUILD_VERSION"
    npx --no-install esbuild entry.js --bundle --minify --format=iife --global-name=THREE --legal-comments=none \
        --target=es2020 --log-level=warning
} > "$here/three.min.js"
cp node_modules/three/LICENSE "$here/three.LICENSE"
echo "wrote $here/three.min.js ($(wc -c < "$here/three.min.js") bytes)"
