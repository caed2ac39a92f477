#!/usr/bin/env bash
# Runs the shell commands that the documentation shows, so that a documented
# command that no longer works is caught.
#
# Usage: scripts/check-docs.sh [--list] [FILE.md ...]
#
#   FILE.md ...  the documents to check (default: README.md and docs/*.md)
#   --list       only print every command found and what would be done with
#                it (run, skip with the reason, or not a command); run nothing
#
# Commands are taken from fenced ```sh blocks (one command per line; `\`
# continues a line; `#` lines are comments) and from inline code spans that
# start with `immerse `, `cargo ` or `scripts/` (in prose and in tables).
# Spans that are usage synopses (placeholders such as CURVE or FILE,
# `[...]`, `...`) and bare mentions such as `immerse morph` are not
# commands and are only counted.
#
# Each runnable command runs under bash in a fresh temporary folder holding
# copies of curves/ and meshes/, with a 60-second limit, so its outputs never
# land in the repository:
#   - `immerse ...` runs the release binary target/release/immerse;
#   - `cargo run --release -- ARGS` runs that binary with ARGS;
#   - `cargo run --release --example NAME [-- ARGS]` runs the example built
#     into target/release/examples/NAME.
# The binary and the examples are built first (`cargo build --release`), in
# the repository, where only target/ changes.
#
# A command shown in several places runs once; a failure names every place.
# A command fails when it exits with a non-zero status or takes longer than
# 60 s; the script then names the document, the line and the command, shows
# the end of its output, and exits 1 after running the rest. Commands on the
# skip list below are not run; the script prints them with the reason.
# Exit status: 0 all ran, 1 a documented command failed, 2 usage or set-up
# problem.
set -uo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
limit=60

# Commands that are not run, as bash glob patterns matched against the
# command (trailing comment removed), each with the reason.
skip=(
  'cargo test --release --workspace|the whole test suite takes several minutes on 2 cores; CI runs it'
  'cargo bench*|criterion benchmarks take minutes; see benches/README.md'
  'scripts/bench-table.sh*|runs every benchmark (several minutes); its output is docs/benchmarks.md'
  'scripts/certify-pairs.sh*|morphs and certifies the 22 motion pairs (about a minute with the build); its totals are in docs/design.md §13.3'
  'scripts/peer-compare.sh*|needs node, npm and the npm registry (installs flubber into a temporary folder)'
  'cargo run --release --example make_pairs*|rewrites curves/pairs/ in the repository itself (the example writes under CARGO_MANIFEST_DIR)'
  'cargo run --release --example peer_check*|needs the flubber frames that scripts/peer-compare.sh makes (node, npm)'
  'cargo run --release -- serve*|starts the playground server, which runs until Ctrl-C (tests/integration/web.rs and scripts/browser-test.sh test it)'
  'immerse serve*|starts the playground server, which runs until Ctrl-C (tests/integration/web.rs and scripts/browser-test.sh test it)'
  'scripts/browser-test.sh*|the browser test: installs chromium (apt) and npm packages; .ci/run runs it'
  'cargo test --release --test integration*|part of the test suite; CI runs the whole suite'
  'cargo test --release --test hostile*|the hostile-traffic test of the playground server (about a minute); .ci/run runs it'
  'cargo run --release --example stress -- --pairs 10000*|the long stress run takes a quarter of an hour; its figures are in docs/stress.md'
  'cargo run --release --example stress -- --pairs 2000*|the stress run of CI takes minutes; .ci/run runs it'
  'scripts/python-test.sh*|builds the Python wheel from scratch and runs pytest (several minutes); .ci/run runs it'
  'pip install*|installs the Python package (docs/python.md); scripts/python-test.sh does it in a fresh venv'
  'python*|Python commands of docs/python.md and docs/inkscape.md need the package installed; scripts/python-test.sh runs their tests'
  'cargo install*|installs the binary into ~/.cargo/bin (docs/inkscape.md)'
  'cargo run --release --features experimental*|builds the crate again with the experimental options (minutes); .ci/run builds and tests that feature'
  'cp inkscape/*|installs the Inkscape extension into a user folder; scripts/python-test.sh runs it through Inkscape'
  'cargo run --release --example stress -- --replay*|replays tests/stress-regressions/, which the test suite replays too (stress_regressions_all_morph)'
)

die() { echo "check-docs: $*" >&2; exit 2; }

list_only=0
docs=()
for arg in "$@"; do
  case $arg in
    --list) list_only=1 ;;
    -h|--help) sed -n '2,/^set -uo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) die "unknown option '$arg' (use --list or name .md files)" ;;
    *) [[ -f $arg ]] || die "no such document: $arg"; docs+=("$arg") ;;
  esac
done
if [[ ${#docs[@]} -eq 0 ]]; then
  docs=(README.md docs/*.md)
fi
command -v python3 >/dev/null || die "python3 is needed to read the Markdown"

# One line per command: FILE <tab> LINE <tab> KIND <tab> COMMAND, where KIND is
# "sh" (fenced block) or "inline".
extract() {
  python3 - "$@" <<'PY'
import re, sys

PREFIXES = ("immerse ", "cargo ", "scripts/")

def out(path, line, kind, cmd):
    cmd = " ".join(cmd.split())
    if cmd:
        print(f"{path}\t{line}\t{kind}\t{cmd}")

for path in sys.argv[1:]:
    lines = open(path, encoding="utf-8").read().split("\n")
    i, para, para_start = 0, [], 0

    def flush():
        text = " ".join(para)
        for m in re.finditer(r"(`+)(.+?)\1", text):
            span = m.group(2).strip().replace("\\|", "|")
            if span.startswith(PREFIXES):
                # The line the span starts on.
                before = text[: m.start()]
                line = para_start
                for k, part in enumerate(para):
                    if len(" ".join(para[: k + 1])) >= len(before):
                        line = para_start + k
                        break
                out(path, line, "inline", span)

    while i < len(lines):
        fence = re.match(r"^\s*(```+)\s*(\S*)", lines[i])
        if fence:
            flush(); para = []
            lang, start = fence.group(2), i + 1
            i += 1
            pending, pending_line = "", 0
            while i < len(lines) and not lines[i].strip().startswith(fence.group(1)):
                if lang in ("sh", "bash", "shell", "console"):
                    s = lines[i].strip()
                    if lang == "console" and s.startswith("$ "):
                        s = s[2:]
                    if s and not s.startswith("#"):
                        if not pending:
                            pending_line = i + 1
                        if s.endswith("\\"):
                            pending += s[:-1] + " "
                        else:
                            out(path, pending_line, "sh", pending + s)
                            pending = ""
                i += 1
            i += 1
            continue
        if lines[i].strip() == "" or lines[i].lstrip().startswith("|"):
            flush(); para = []
            if lines[i].lstrip().startswith("|"):
                para, para_start = [lines[i]], i + 1
                flush(); para = []
        else:
            if not para:
                para_start = i + 1
            para.append(lines[i])
        i += 1
    flush()
PY
}

# Strip a trailing shell comment (" # ...") for matching and display.
bare() { sed -E 's/[[:space:]]+#[[:space:]].*$//' <<<"$1"; }

is_synopsis() {
  local c=$1
  [[ $c == *'['* || $c == *'...'* || $c == *'…'* ]] && return 0
  # An upper-case placeholder word: CURVE, FILE.png, DIR/x, A, B, N.
  grep -qE '(^|[[:space:]/=])[A-Z][A-Z_]*([./][^[:space:]]*)?([[:space:]]|$)' <<<"$c" && return 0
  return 1
}

is_mention() {
  # `immerse morph`, `cargo bench`: a name in prose, not a command line.
  local -a w
  read -r -a w <<<"$1"
  [[ (${w[0]} == immerse || ${w[0]} == cargo) && ${#w[@]} -eq 2 && ${w[1]} != -* ]]
}

skip_reason() {
  local c=$1 entry
  for entry in "${skip[@]}"; do
    # shellcheck disable=SC2053
    if [[ $c == ${entry%%|*} ]]; then
      echo "${entry#*|}"
      return 0
    fi
  done
  return 1
}

mapfile -t found < <(extract "${docs[@]}")
[[ ${#found[@]} -gt 0 ]] || die "no commands found in ${docs[*]}"

# Classify. A command shown in several places runs once.
runs=() skipped=() notcmd=() examples=()
declare -A where=()
for rec in "${found[@]}"; do
  IFS=$'\t' read -r file line kind cmd <<<"$rec"
  c=$(bare "$cmd")
  if [[ -n ${where[$c]:-} ]]; then
    where[$c]+=", $file:$line"
    continue
  fi
  where[$c]="$file:$line"
  if is_synopsis "$c"; then
    notcmd+=("$c	usage synopsis")
  elif [[ $kind == inline ]] && is_mention "$c"; then
    notcmd+=("$c	a name, not a command line")
  elif reason=$(skip_reason "$c"); then
    skipped+=("$c	$reason")
  else
    runs+=("$c")
    if [[ $c =~ ^cargo\ run\ --release\ --example\ ([A-Za-z0-9_]+) ]]; then
      examples+=("${BASH_REMATCH[1]}")
    fi
  fi
done

if [[ $list_only -eq 1 ]]; then
  for c in "${runs[@]}"; do echo "run   ${where[$c]}: $c"; done
  for r in "${skipped[@]}"; do IFS=$'\t' read -r c why <<<"$r"; echo "skip  ${where[$c]}: $c  ($why)"; done
  for r in "${notcmd[@]}"; do IFS=$'\t' read -r c why <<<"$r"; echo "none  ${where[$c]}: $c  ($why)"; done
  exit 0
fi

start=$SECONDS
command -v cargo >/dev/null || die "cargo is not on PATH"
build=(cargo build --release --quiet --bin immerse)
for e in $(printf '%s\n' "${examples[@]}" | sort -u); do
  build+=(--example "$e")
done
echo "check-docs: building: ${build[*]}" >&2
"${build[@]}" || die "the build failed: ${build[*]}"
bin=$root/target/release/immerse

work=$(mktemp -d "${TMPDIR:-/tmp}/immerse-check-docs.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/bin"
ln -s "$bin" "$work/bin/immerse"

failed=0 ok=0 n=0
for c in "${runs[@]}"; do
  at=${where[$c]}
  n=$((n + 1))
  run=$c
  if [[ $run =~ ^cargo\ run\ --release\ --example\ ([A-Za-z0-9_]+)(\ --)?(.*)$ ]]; then
    run="\"$root/target/release/examples/${BASH_REMATCH[1]}\"${BASH_REMATCH[3]}"
  elif [[ $run =~ ^cargo\ run\ --release\ --\ (.*)$ ]]; then
    run="immerse ${BASH_REMATCH[1]}"
  elif [[ $run =~ ^cargo\  ]]; then
    echo "check-docs: FAILED: $at: \`$c\`: a cargo command the script cannot run outside the repository; add it to the skip list with a reason" >&2
    failed=$((failed + 1))
    continue
  fi
  dir=$work/run-$n
  mkdir -p "$dir"
  cp -R curves meshes "$dir/"
  t0=$SECONDS
  (cd "$dir" && PATH="$work/bin:$PATH" timeout "$limit" bash -c "$run") >"$dir.out" 2>&1
  status=$?
  took=$((SECONDS - t0))
  if [[ $status -eq 0 ]]; then
    ok=$((ok + 1))
    printf 'check-docs: ok   %3ds  %s  (%s)\n' "$took" "$c" "$at" >&2
  else
    failed=$((failed + 1))
    if [[ $status -eq 124 ]]; then
      why="took longer than ${limit}s (shorten it in the docs, or add it to the skip list with a reason)"
    else
      why="exited with status $status"
    fi
    echo "check-docs: FAILED: $at: \`$c\` $why; the end of its output:" >&2
    tail -n 15 "$dir.out" | sed 's/^/    /' >&2
  fi
  rm -rf "$dir" "$dir.out"
done

echo >&2
echo "check-docs: ${#notcmd[@]} synopses and names in code spans are not commands (--list shows them)." >&2
if [[ ${#skipped[@]} -gt 0 ]]; then
  echo "check-docs: skipped ${#skipped[@]} command(s):" >&2
  for r in "${skipped[@]}"; do
    IFS=$'\t' read -r c why <<<"$r"
    echo "  $c    (${where[$c]})" >&2
    echo "      reason: $why" >&2
  done
fi
echo "check-docs: $ok of $n documented command(s) ran fine, $failed failed ($((SECONDS - start)) s)." >&2
[[ $failed -eq 0 ]] || exit 1
