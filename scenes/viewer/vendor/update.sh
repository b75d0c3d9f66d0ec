#!/usr/bin/env bash
# Rebuilds three.min.js from the npm registry's `three` package: the parts of three.js that
# entry.js names, and OrbitControls (three/examples/jsm), as one minified script that defines the
# global THREE. Also copies three.js's LICENSE and records the version. Needs node and npm (only
# here: the build and the page never touch a network).
#   bash scenes/viewer/vendor/update.sh [VERSION]     (default: the version in VERSION)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
version=${1:-$(cat "$here/VERSION")}
esbuild_version=0.28.2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
npm init -y >/dev/null
npm install --no-audit --no-fund --save-exact "three@$version" "esbuild@$esbuild_version" >/dev/null
cp "$here/entry.js" .
npx esbuild entry.js --bundle --minify --format=iife --global-name=THREE --target=es2020 \
    --legal-comments=eof --outfile=bundle.js
{
  echo "/* three.js $version (npm package \"three\", https://threejs.org), MIT licence: LICENSE."
  echo "   The parts named in entry.js and examples/jsm/controls/OrbitControls.js, bundled by"
  echo "   esbuild $esbuild_version into the global THREE (update.sh). */"
  cat bundle.js
} > "$here/three.min.js"
cp node_modules/three/LICENSE "$here/LICENSE"
echo "$version" > "$here/VERSION"
echo "three.min.js: three $version, $(wc -c < "$here/three.min.js") bytes"
