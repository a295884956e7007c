#!/usr/bin/python3
"""CPU time of one `breastfit` run by phase, from a sampling profile (docs/PERFORMANCE.md).

Records the command with `perf record -e cpu-clock --call-graph dwarf` (a software clock: works
where hardware counters are not available) and attributes every sample to the first phase in
PHASES whose function is on the sample's stack (all threads together), then prints a Markdown
table of milliseconds of CPU and shares.

Usage: scripts/perf_phases.py [--freq 4000] [--repeat 3] -- build/bin/breastfit register SCAN -l L --out DIR --force --no-report-html --quiet
With --repeat N the command runs N times and the table gives the median per phase.
"""
import argparse
import collections
import os
import statistics
import subprocess
import sys
import tempfile

# (phase, functions whose presence on the stack puts a sample in it, and a function that must be
# on the stack too, or None); the first match wins, so inner phases come before outer ones.
STAGES = "breastfit::fit::minimize_stages"
PHASES = [
    ("read scan (PLY)", ["breastfit::io::read_mesh"], None),
    ("read landmarks", ["breastfit::io::read_landmarks"], None),
    ("load template (glTF)", ["breastfit::cli::load_template"], None),
    ("prepare scan (units, cleanup)", ["breastfit::pipeline::prepare_scan"], None),
    ("index build (scan BVH, samples)", ["breastfit::fit::ScanTarget::ScanTarget"], None),
    ("landmark frame check", ["breastfit::pipeline::diagnose_landmark_frame"], None),
    ("initialization (arms, normals)", ["breastfit::fit::initialize_arms", "breastfit::fit::Problem::orient_scan_normals",
                                         "breastfit::fit::initialize_from_landmarks",
                                         "breastfit::fit::initialize_without_landmarks"], None),
    ("stages: correspondences (model→scan)", ["breastfit::fit::find_correspondences"], STAGES),
    ("stages: reverse correspondences", ["breastfit::fit::find_reverse_correspondences"], STAGES),
    ("stages: assembly (Jacobians, JᵀJ)", ["breastfit::fit::Problem::evaluate"], STAGES),
    ("stages: solve (LM steps)", ["breastfit::fit::LevenbergMarquardtStrategy::compute_step"], STAGES),
    ("stages: posing (set_params)", ["breastfit::model::PoseEvaluator::set_params"], STAGES),
    ("stages: other", [STAGES], None),
    ("surface detail", ["breastfit::fit::fit_surface_detail"], None),
    ("final state, landmark checks", ["breastfit::fit::register_template"], None),
    ("transfer (drawings)", ["breastfit::transfer::transfer_drawings"], None),
    ("measurements", ["breastfit::transfer::measure_breasts", "breastfit::metrics::"], None),
    ("write scan_painted.ply", ["breastfit::transfer::write_scan_painted"], None),
    ("write other outputs", ["breastfit::pipeline::write_register_outputs"], None),
    ("rest of register_scan", ["breastfit::pipeline::register_scan"], None),
    ("pool workers (core/chunk_pool.h, outside a phase)", ["breastfit::detail::ChunkPool::work_forever"], None),
    ("hashing the inputs (provenance)", ["breastfit::io::file_sha256_hex"], None),
    # Eigen's blocked kernels use large stack buffers, so the DWARF unwinder often loses their
    # callers: these samples (mostly the assembly's rank updates, some sparse Cholesky of surface
    # detail and measurements) belong to a phase above but cannot be placed.
    ("Eigen kernels, caller lost by the unwinder", ["Eigen::internal::", "Eigen::Simplicial"], None),
    ("process start (dynamic linking)", ["_dl_start", "_dl_relocate_object", "_dl_fixup", "_dl_init"], None),
    ("process exit (unmapping memory)", ["exit_mmap", "do_exit", "__run_exit_handlers"], None),
]


def profile(cmd, freq):
    with tempfile.TemporaryDirectory() as tmp:
        data = os.path.join(tmp, "perf.data")
        subprocess.run(["perf", "record", "-q", "-e", "cpu-clock", "-F", str(freq), "--call-graph", "dwarf,16384",
                        "-o", data, "--"] + cmd, check=True, stdout=subprocess.DEVNULL)
        script = subprocess.run(["perf", "script", "-i", data, "-F", "ip,sym"], capture_output=True, text=True,
                                check=True).stdout
    counts = collections.Counter()
    total = 0
    for sample in script.split("\n\n"):
        frames = [l.strip().split(None, 1)[-1] for l in sample.strip().splitlines() if l.strip()]
        if not frames:
            continue
        total += 1
        phase = "process start, exit, rest"
        for name, funcs, within in PHASES:
            if any(f.startswith(fn) for f in frames for fn in funcs) and (
                    within is None or any(f.startswith(within) for f in frames)):
                phase = name
                break
        counts[phase] += 1
    ms = {k: v * 1000.0 / freq for k, v in counts.items()}
    ms["total"] = total * 1000.0 / freq
    return ms


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--freq", type=int, default=4000)
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("cmd", nargs=argparse.REMAINDER)
    a = p.parse_args()
    cmd = a.cmd[1:] if a.cmd and a.cmd[0] == "--" else a.cmd
    if not cmd:
        sys.exit("perf_phases.py: no command (give it after --)")
    runs = [profile(cmd, a.freq) for _ in range(a.repeat)]
    names = [n for n, _, _ in PHASES] + ["process start, exit, rest"]
    total = statistics.median(r["total"] for r in runs)
    print("| phase | CPU ms (median of %d) | share |" % a.repeat)
    print("|---|---:|---:|")
    for n in names:
        v = statistics.median(r.get(n, 0.0) for r in runs)
        if v > 0:
            print("| %s | %.1f | %.0f %% |" % (n, v, 100.0 * v / total))
    print("| **total CPU** | **%.1f** | |" % total)


if __name__ == "__main__":
    main()
