#!/usr/bin/env bash
# The Python package and the Inkscape extension, from scratch (docs/python.md,
# docs/inkscape.md):
#   1. installs python3-venv with apt when a venv cannot be made;
#   2. makes a fresh virtual environment in target/python-venv;
#   3. installs the pinned test requirements (python/requirements-test.txt;
#      inkex without its GUI dependency);
#   4. builds the abi3 wheel from scratch with maturin (python/target is
#      removed first) and installs the package with `pip install ./python`;
#   5. runs the pytest suite in python/tests (the API, the matplotlib example
#      of docs/examples/, the Inkscape extension headless), against the
#      release binary for the command-line comparisons;
#   6. runs the extension once through Inkscape's command line (installs
#      inkscape and xvfb with apt when missing; the binary fallback, since
#      the Python Inkscape runs has no immerse package).
# Prints the seconds each step took. Exit status: that of the first failure.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
step() { printf '\n-- [%ds] %s\n' "$SECONDS" "$*"; }

step "python3 and venv"
if ! python3 -c 'import venv, ensurepip' 2>/dev/null; then
  apt-get update -q && apt-get install -y -q python3-venv python3-pip
fi
python3 --version

venv=$root/target/python-venv
rm -rf "$venv"
python3 -m venv "$venv"
py=$venv/bin/python

step "pinned test requirements"
"$py" -m pip install -q --upgrade pip
grep -v '^inkex' python/requirements-test.txt > "$venv/requirements.txt"
"$py" -m pip install -q -r "$venv/requirements.txt"
"$py" -m pip install -q --no-deps "$(grep '^inkex==' python/requirements-test.txt)"

step "the release binary (command-line comparisons, the extension's fallback)"
cargo build --release --quiet --bin immerse
export IMMERSE_BIN=$root/target/release/immerse

step "maturin build from scratch"
rm -rf python/target
build_start=$SECONDS
(cd python && "$venv/bin/maturin" build --release --locked --quiet --out "$venv/dist")
ls "$venv"/dist/*.whl
step "pip install ./python"
"$py" -m pip install -q ./python
echo "built and installed from scratch in $((SECONDS - build_start)) s"
"$py" -c 'import immerse; print("immerse", immerse.__version__, "from", immerse.__file__)'

step "pytest (python/tests)"
# The venv's pytest script, not `python -m pytest`: -m puts the working
# folder first on sys.path, where python/immerse (the sources, without the
# compiled module) would shadow the installed package.
(cd python && "$venv/bin/pytest" -q tests)

step "the extension through Inkscape's command line"
# Debian's inkscape and a virtual display (extension actions need one):
# about a minute with apt.
if ! command -v inkscape >/dev/null || ! command -v xvfb-run >/dev/null; then
  apt-get update -q && apt-get install -y -q inkscape xvfb xauth
fi
inkscape --version 2>/dev/null | head -1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/config/inkscape/extensions" "$work/bin"
cp inkscape/immerse_inbetween.inx inkscape/immerse_inbetween.py "$work/config/inkscape/extensions/"
ln -s "$IMMERSE_BIN" "$work/bin/immerse"
"$py" python/tests/inkscape_cli.py make "$work/in.svg"
# Inkscape runs the extension with the system python3, which has no immerse
# package: the binary fallback, found on PATH.
XDG_CONFIG_HOME=$work/config PATH=$work/bin:/usr/bin:/bin HOME=$work \
  timeout 300 xvfb-run -a inkscape --batch-process \
  --actions="select-by-id:a,b;org.immerse.inbetween.noprefs;export-filename:$work/out.svg;export-do" \
  "$work/in.svg" 2>&1 | grep -v -E 'WARNING|^$' || true
"$py" python/tests/inkscape_cli.py verify "$work/out.svg" 5
step "done"
