#!/usr/bin/env bash
# Certifies the motion between consecutive frames of `immerse morph` on
# every pair of curves/motion-pairs.list (docs/design.md §13.3): one row
# per pair and the totals, as markdown.
# Usage: scripts/certify-pairs.sh [--frames N] [--player exact|f64|f32] [--list FILE] [--bin IMMERSE]
# Needs python3 (to read the JSON reports). Builds the release binary
# unless --bin is given.
set -euo pipefail
cd "$(dirname "$0")/.."
frames=40
player=exact
list=curves/motion-pairs.list
bin=""
while [ $# -gt 0 ]; do
  case "$1" in
    --frames) frames=$2; shift 2 ;;
    --player) player=$2; shift 2 ;;
    --list) list=$2; shift 2 ;;
    --bin) bin=$2; shift 2 ;;
    *) echo "unknown argument $1" >&2; exit 2 ;;
  esac
done
if [ -z "$bin" ]; then
  cargo build --release --quiet
  bin=target/release/immerse
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "| pair | segments | certified | by frame i's triangulation | by frame i's or i+1's | invalid | undecided |"
echo "|---|---|---|---|---|---|---|"
grep -v '^\s*#' "$list" | grep -v '^\s*$' | while read -r a b; do
  "$bin" morph "curves/$a" "curves/$b" --frames "$frames" --json "$tmp/m.json" --force -q >/dev/null
  "$bin" certify "$tmp/m.json" --player "$player" --json="$tmp/r.json" --force >/dev/null || true
  python3 - "$a → $b" "$tmp/r.json" <<'PY'
import json, sys
name, path = sys.argv[1], sys.argv[2]
r = json.load(open(path))
segs = [s for p in r["paths"] for s in p["segments"]]
one = lambda s, ok: s["answer"] == "certified" and len(s["pieces"]) == 1 and s["pieces"][0]["source"] in ok
print("| %s | %d | %d | %d | %d | %d | %d |" % (
    name, len(segs), r["certified"],
    sum(one(s, [{"given": 0}]) for s in segs),
    sum(one(s, [{"given": 0}, {"given": 1}]) for s in segs),
    r["invalid"], r["undecided"]))
PY
  cat "$tmp/r.json" >> "$tmp/all.jsonl"
done
python3 - "$tmp/all.jsonl" <<'PY'
import json, sys
text = open(sys.argv[1]).read()
dec, i, reports = json.JSONDecoder(), 0, []
while i < len(text):
    while i < len(text) and text[i].isspace():
        i += 1
    if i >= len(text):
        break
    r, i = dec.raw_decode(text, i)
    reports.append(r)
segs = [s for r in reports for p in r["paths"] for s in p["segments"]]
one = lambda s, ok: s["answer"] == "certified" and len(s["pieces"]) == 1 and s["pieces"][0]["source"] in ok
print("| **all %d pairs** | %d | %d | %d | %d | %d | %d |" % (
    len(reports), len(segs), sum(s["answer"] == "certified" for s in segs),
    sum(one(s, [{"given": 0}]) for s in segs),
    sum(one(s, [{"given": 0}, {"given": 1}]) for s in segs),
    sum(s["answer"] == "invalid" for s in segs),
    sum(s["answer"] == "undecided" for s in segs)))
PY
