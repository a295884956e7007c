#!/usr/bin/env bash
# Optional check against the external benchmark (not part of the test suite): runs
# `breastfit register` on every case of ../shared/bench (or BENCH_DIR) through the bench's own
# referee, evaluate.py, and prints its table. Extra arguments go to `breastfit register`.
# Usage: scripts/bench_check.sh [--only CASE...] [--no-landmarks | --landmark-subset NAME,...] [--cases DIR]
#                               [--out DIR] [-- REGISTER_ARGS...]
# --landmark-subset: register with only the named landmarks of each case (e.g.
# sternal_notch,nipple_R,nipple_L), copies written to OUT/landmarks/CASE.mrk.json; the referee still
# scores all 12.
# --cases: another case directory in the bench's layout, e.g. extra cases made with the bench's
# generator from scripts/make_validation_recipes.py (see docs/REGISTRATION.md "Validation cases").
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench="${BENCH_DIR:-$here/../shared/bench}"
bin="${BREASTFIT_BIN:-$here/build/bin/breastfit}"
out="$here/out/bench"
cases=""
only=()
eval_flags=()
subset=
while [ $# -gt 0 ]; do
  case "$1" in
    --only) shift; while [ $# -gt 0 ] && [[ "$1" != --* ]]; do only+=("$1"); shift; done; continue ;;
    --no-landmarks) eval_flags+=(--no-landmarks) ;;
    --landmark-subset) subset="$2"; shift ;;
    --out) out="$2"; shift ;;
    --cases) cases="$2"; shift ;;
    --) shift; break ;;
    *) echo "bench_check.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
  shift
done
extra="$*"
if [ ! -f "$bench/evaluate.py" ]; then
  echo "bench_check.sh: no benchmark at $bench (set BENCH_DIR); skipped" >&2
  exit 0
fi
[ -x "$bin" ] || { echo "bench_check.sh: $bin not built (run scripts/setup.sh)" >&2; exit 1; }
mkdir -p "$out"
[ -n "$cases" ] || cases="$bench/cases"
[ -d "$cases" ] || { echo "bench_check.sh: no case directory $cases" >&2; exit 1; }
args=(--cases "$cases" --work "$out/results" --out "$out/report.md" --json "$out/report.json")
[ ${#only[@]} -gt 0 ] && args+=(--only "${only[@]}")
landmarks_arg="--landmarks {landmarks}"
[ ${#eval_flags[@]} -gt 0 ] && landmarks_arg=""
if [ -n "$subset" ]; then
  mkdir -p "$out/landmarks"
  /usr/bin/python3 - "$cases" "$out/landmarks" "$subset" <<'PY'
import json, pathlib, sys
cases, dest, names = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]), set(sys.argv[3].split(","))
for case in sorted(p for p in cases.iterdir() if (p / "landmarks.mrk.json").is_file()):
    m = json.loads((case / "landmarks.mrk.json").read_text())
    for markup in m["markups"]:
        markup["controlPoints"] = [cp for cp in markup["controlPoints"] if cp.get("label") in names]
    (dest / (case.name + ".mrk.json")).write_text(json.dumps(m, indent=1))
PY
  landmarks_arg="--landmarks $out/landmarks/{case}.mrk.json"
fi
/usr/bin/python3 "$bench/evaluate.py" "${args[@]}" "${eval_flags[@]}" \
  --tool "$bin register {scan} $landmarks_arg --out {out} --force --quiet $extra"
