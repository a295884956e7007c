#!/usr/bin/env bash
# Optional check against the external benchmark (not part of the test suite): runs
# `breastfit register` on every case of ../shared/bench (or BENCH_DIR) through the bench's own
# referee, evaluate.py, and prints its table. Extra arguments go to `breastfit register`.
# Usage: scripts/bench_check.sh [--only CASE...] [--no-landmarks] [--cases DIR] [--out DIR] [-- REGISTER_ARGS...]
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
while [ $# -gt 0 ]; do
  case "$1" in
    --only) shift; while [ $# -gt 0 ] && [[ "$1" != --* ]]; do only+=("$1"); shift; done; continue ;;
    --no-landmarks) eval_flags+=(--no-landmarks) ;;
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
/usr/bin/python3 "$bench/evaluate.py" "${args[@]}" "${eval_flags[@]}" \
  --tool "$bin register {scan} $landmarks_arg --out {out} --force --quiet $extra"
