#!/usr/bin/env bash
# The browser test of the playground (`immerse serve`) and of the Lottie
# output: tests/browser/playground.test.mjs in Debian's Chromium, driven by
# playwright-core, with lottie-web (both pinned in tests/browser/package.json
# and package-lock.json, installed by `npm ci` into tests/browser/node_modules,
# which git ignores). Installs Chromium with apt when /usr/bin/chromium is
# missing; never lets a tool download a browser of its own.
#
# Prints the measured pixel differences, the layout at 1280x800 and 390x844
# and the run time; saves screenshots of the playground at both sizes to
# docs/img/playground.png and docs/img/playground-phone.png (SCREENSHOT=path
# and SCREENSHOT_PHONE=path to change).
#
#   scripts/browser-test.sh            # build the release binary, run the test
#   IMMERSE_BIN=path scripts/browser-test.sh   # test another binary (no build)
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)

as_root() {
    if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi
}

if [ ! -x "${CHROMIUM:-/usr/bin/chromium}" ]; then
    echo "== installing Debian's chromium (apt)"
    as_root apt-get update -qq
    DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq chromium >/dev/null
fi
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
    echo "== installing node and npm (apt)"
    as_root apt-get update -qq
    DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq nodejs npm >/dev/null
fi

# playwright-core downloads nothing by itself; say so anyway.
export PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1
lock=tests/browser/package-lock.json
stamp=tests/browser/node_modules/.installed-lock.json
if ! cmp -s "$lock" "$stamp" 2>/dev/null; then
    echo "== npm ci (tests/browser)"
    (cd tests/browser && npm ci --no-audit --no-fund --ignore-scripts --loglevel=error)
    cp "$lock" "$stamp"
fi

if [ -z "${IMMERSE_BIN:-}" ]; then
    echo "== cargo build --release --bin immerse"
    cargo build --release --quiet --bin immerse
    export IMMERSE_BIN=target/release/immerse
fi

echo "== node --test tests/browser/playground.test.mjs"
node --test --test-reporter=spec tests/browser/playground.test.mjs
echo "== browser test passed in $(($(date +%s) - start)) s (including installs and the build)"
