// flubber's in-betweens for the pairs exported by `peer_check export DIR`.
//
// Usage: node scripts/peer/flubber_frames.mjs DIR FLUBBER_PREFIX [MAX_SEGMENT_LENGTH [FRAMES]]
//
// DIR holds pair-NN.json ({"name", "from": {"points"}, "to": {"points"}});
// FLUBBER_PREFIX is the folder where `npm install flubber` was run.
// For each pair this writes DIR/flubber-NN.json:
// {"frames": [[[x, y], ...], ...], "ms": wall_time, "n": ring_length}
// with FRAMES frames at t = i / (FRAMES - 1). `ms` is the fastest of
// REPEATS runs of interpolate() plus the FRAMES evaluations, after one
// untimed warm-up run (so the JIT has compiled flubber).
// MAX_SEGMENT_LENGTH is flubber's maxSegmentLength option: "false" (the
// default here: no extra bisection, so flubber's rings have the same
// vertex count as immerse's) or a number in curve units. FRAMES is the
// number of in-betweens (default 41).

import { createRequire } from "node:module";
import { readdirSync, readFileSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { performance } from "node:perf_hooks";

const REPEATS = 3;

const [dir, prefix, segArg = "false", framesArg = "41"] = process.argv.slice(2);
if (!dir || !prefix) {
  console.error("usage: node flubber_frames.mjs DIR FLUBBER_PREFIX [MAX_SEGMENT_LENGTH [FRAMES]]");
  process.exit(2);
}
const require = createRequire(join(prefix, "package.json"));
const flubber = require("flubber");
const maxSegmentLength = segArg === "false" ? false : Number(segArg);
const FRAMES = Number(framesArg);

const ts = Array.from({ length: FRAMES }, (_, i) => i / (FRAMES - 1));

function run(from, to) {
  // flubber may mutate its inputs' copies only, but pass fresh arrays anyway.
  const f = flubber.interpolate(
    from.map((p) => p.slice()),
    to.map((p) => p.slice()),
    { string: false, maxSegmentLength },
  );
  return ts.map((t) => f(t));
}

const files = readdirSync(dir)
  .filter((f) => /^pair-\d+\.json$/.test(f))
  .sort();
if (files.length === 0) {
  console.error(`no pair-NN.json in ${dir}`);
  process.exit(1);
}
for (const file of files) {
  const pair = JSON.parse(readFileSync(join(dir, file), "utf8"));
  const from = pair.from.points;
  const to = pair.to.points;
  run(from, to); // warm-up
  let frames;
  let best = Infinity;
  for (let r = 0; r < REPEATS; r++) {
    const start = performance.now();
    frames = run(from, to);
    best = Math.min(best, performance.now() - start);
  }
  const out = file.replace(/^pair-/, "flubber-");
  writeFileSync(
    join(dir, out),
    JSON.stringify({ frames, ms: best, n: frames[0].length }),
  );
}
console.error(`flubber: wrote ${files.length} frame sets to ${dir}`);
