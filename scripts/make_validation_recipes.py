#!/usr/bin/python3
"""Recipes for extra validation cases, made with the benchmark's own generator.

The bench keeps its held-out split away from us; to check that a change generalises beyond the
14 visible cases, make new subjects from random recipes (a seed of our own, not the held-out
ones) and run the referee on them:

    /usr/bin/python3 scripts/make_validation_recipes.py --subjects 6 --seed 20261121 --out /tmp/val/recipes.json
    /usr/bin/python3 ../shared/bench/make_cases.py /tmp/val/recipes.json /tmp/val/cases --jobs 2
    scripts/bench_check.sh --cases /tmp/val/cases --out /tmp/val/run -- --no-report-html

Each subject gets a standing and a supine case. Ranges follow the bench README (women 40-72,
small to large, firm to ptotic breasts); every third subject has a smaller left breast, every
sixth a firmer right one, every sixth (from the third) is scanned in metres. Never commit the
generated cases (their data derive from third-party assets).
"""
import argparse
import json
import random


def recipes(n_subjects, seed):
    rng = random.Random(seed)
    out = []
    for i in range(n_subjects):
        cup = round(rng.uniform(0.2, 0.95), 2)
        firmness = round(rng.uniform(0.1, 0.7), 2)
        subject = {
            "age": rng.randint(40, 72), "cup": cup, "firmness": firmness,
            "weight": round(rng.uniform(0.5, 1.0), 2), "muscle": round(rng.uniform(0.25, 0.6), 2),
            "ethnic": {"caucasian": 0.6, "african": 0.2, "asian": 0.2} if i % 2 else {"caucasian": 1.0},
            "modifiers": {"torso-scale-horiz": round(rng.uniform(-0.2, 0.5), 2)},
        }
        if i % 3 == 1:
            subject["cup_L"] = round(max(0.1, cup - 0.35), 2)       # smaller left breast
        if i % 6 == 3:
            subject["firmness_R"] = round(min(0.9, firmness + 0.3), 2)  # firmer right breast
        for pose in ("standing", "supine"):
            lo, hi = (10, 30) if pose == "standing" else (65, 90)
            scan = {
                "arc_deg": rng.choice([160, 200, 240]), "n_azimuth": 20, "elevations_deg": [0, 25],
                "distance_m": 1.0, "white_noise_mm": round(rng.uniform(0.6, 1.2), 2),
                "lowfreq_noise_mm": round(rng.uniform(0.4, 1.0), 2), "n_holes": rng.randint(2, 6),
                "hole_radius_mm": [8, 20], "n_fragments": rng.randint(2, 5), "misalign_rot_deg": 30,
                "misalign_trans_m": 0.5, "units": "m" if i % 6 == 2 else "mm",
            }
            out.append({
                "id": f"v{i}_{pose}", "seed": seed % 100000 + 10 * i + (pose == "supine"),
                "subject": subject,
                "pose": {"type": pose, "arm_abduction_deg": [rng.randint(lo, hi), rng.randint(lo, hi)],
                         "arm_flexion_deg": [3, 3]},
                "scan": scan,
            })
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--subjects", type=int, default=6, help="number of subjects (2 cases each)")
    ap.add_argument("--seed", type=int, default=20261121, help="random seed of the recipes")
    ap.add_argument("--out", required=True, help="recipes JSON to write (refuses to overwrite)")
    a = ap.parse_args()
    if a.subjects < 1:
        ap.error("--subjects must be >= 1")
    try:
        with open(a.out, "x") as f:
            json.dump(recipes(a.subjects, a.seed), f, indent=1)
    except FileExistsError:
        raise SystemExit(f"make_validation_recipes.py: {a.out} exists; not overwritten")
    print(f"wrote {a.out}: {2 * a.subjects} recipes")


if __name__ == "__main__":
    main()
