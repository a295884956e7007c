#!/usr/bin/python3
"""Plots of `breastfit experiments` (one PNG per figure of Mazier et al. 2022).

    /usr/bin/python3 experiments/plot.py OUT/experiments.json OUT_DIR [--prefix PREFIX]

(--prefix experiments_ with OUT_DIR docs/images refreshes the images of docs/EXPERIMENTS.md.)

Writes, for the experiments present in the JSON:
    fig4_landmarks.png              landmark and surface MAE vs number of landmarks used
    fig5_blendshapes_standing.png   surface MAE vs number of blendshapes, one line per case
    fig6_blendshapes_supine.png     the same, supine
    fig7_lambda_surface.png         surface MAE vs each lambda (x its default), mean over cases
    fig8_lambda_landmarks.png       landmark MAE vs each lambda
    resolution.png                  time and errors vs template vertices
Needs matplotlib only (Debian's python3-matplotlib).
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

POSE_COLOR = {"standing": "tab:blue", "supine": "tab:orange", "all": "tab:gray"}
POSE_LABEL = {"standing": "standing (paper: preoperative)", "supine": "supine (paper: intra-operative)"}
LANDMARK_SHORT = {
    "sternal_notch": "notch", "xiphoid": "xiphoid", "acromion_R": "acromion R", "acromion_L": "acromion L",
    "midaxillary_R": "mid-axill. R", "midaxillary_L": "mid-axill. L", "pectoral_insertion_R": "pect. ins. R",
    "pectoral_insertion_L": "pect. ins. L", "nipple_R": "nipple R", "nipple_L": "nipple L",
    "lowest_breast_R": "lowest br. R", "lowest_breast_L": "lowest br. L"}
LAMBDA_COLOR = {"lambda_data": "tab:blue", "lambda_scale": "tab:green", "lambda_blendshapes": "tab:purple",
                "lambda_joints": "tab:brown", "lambda_landmarks": "tab:red"}

plt.rcParams.update({"font.size": 11, "axes.grid": True, "grid.alpha": 0.3, "figure.dpi": 110,
                     "savefig.bbox": "tight"})


PREFIX = ""


def path(out, name):
    return os.path.join(out, PREFIX + name)


def get(d, *path):
    for p in path:
        if not isinstance(d, dict) or d.get(p) is None:
            return None
        d = d[p]
    return d


def series(summary, key, pose, *path):
    """(x, y) of a summary list: x = entry[key], y = entry[pose][path...] where present."""
    xs, ys = [], []
    for e in summary:
        v = get(e, pose, *path)
        if v is not None:
            xs.append(e[key])
            ys.append(v)
    return xs, ys


def poses_in(summary):
    return [p for p in ("standing", "supine") if any(p in e for e in summary)]


def has_truth(summary):
    return any(get(e, p, "truth") is not None for e in summary for p in ("standing", "supine", "all"))


def footer(fig, text):
    fig.text(0.01, -0.02, text, ha="left", va="top", fontsize=9, color="0.3", wrap=True)


def fig4(j, out):
    lm = j["landmarks"]
    s = lm["summary"]
    truth = has_truth(s)
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.2))
    for ax, metric, title in ((axes[0], "landmarks", "Landmark error (all 12 landmarks)"),
                              (axes[1], "surface", "Surface error")):
        for pose in poses_in(s):
            c = POSE_COLOR[pose]
            if truth:
                x, y = series(s, "count", pose, "truth", metric, "mae")
                ax.plot(x, y, "-o", color=c, label=POSE_LABEL[pose] + ", vs ground truth")
            x, y = series(s, "count", pose, "paper", metric, "mae")
            ax.plot(x, y, "--s", color=c, mfc="none",
                    label=POSE_LABEL[pose] + ", the paper's way (model to scan / to the placed landmarks)")
            # not converged / failed runs
            for e in s:
                g = get(e, pose) or {}
                bad = (g.get("n_not_converged") or 0) + (g.get("n_not_usable") or 0) + (g.get("n_error") or 0)
                if bad:
                    yv = get(e, pose, "truth" if truth else "paper", metric, "mae")
                    if yv is not None:
                        ax.annotate("%d✗" % bad, (e["count"], yv), textcoords="offset points", xytext=(4, 6),
                                    fontsize=8, color=c)
        if metric == "landmarks":
            ax.plot([0, 12], [20.1, 8.03], "k*", ms=13, label="paper (text): 20.1 mm → 8.03 mm")
            ax.plot([], [], " ", label="k✗ next to a point: k fits flagged not converged (still averaged)")
            ax.set_yscale("log")
            ax.yaxis.set_major_locator(matplotlib.ticker.LogLocator(subs=(1.0, 2.0, 3.0, 5.0)))
            ax.yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
            ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.axvspan(-0.5, 2.5, color="0.9", zorder=0)
        ax.text(1.0, 0.03, "< 3 landmarks:\nlandmark-free\ninitialisation", transform=ax.get_xaxis_transform(),
                ha="center", va="bottom", fontsize=8, color="0.35")
        ax.set_xlim(-0.5, 12.5)
        ax.set_xticks(range(13))
        labels = ["0"] + ["%d\n%s" % (i + 1, LANDMARK_SHORT.get(n, n)) for i, n in enumerate(lm["order"])]
        ax.set_xticklabels(labels, rotation=90, fontsize=8)
        ax.set_xlabel("number of landmarks used in the fit (the n-th one added is named)")
        ax.set_ylabel("MAE (mm)")
        ax.set_title(title)
    fig.suptitle("Fig. 4 — MAE as landmarks are added in the paper's order (mean over cases)")
    fig.tight_layout()
    fig.legend(*axes[0].get_legend_handles_labels(), loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=2,
               fontsize=9, frameon=False)
    fig.savefig(path(out, "fig4_landmarks.png"))
    plt.close(fig)


def fig56(j, out):
    bs = j["blendshapes"]
    runs = bs["runs"]
    for pose, name, num in (("standing", "fig5_blendshapes_standing.png", 5),
                            ("supine", "fig6_blendshapes_supine.png", 6)):
        cases = sorted({r["case"] for r in runs if r.get("pose") == pose})
        if not cases:
            continue
        truth = any(get(r, "truth") for r in runs if r.get("pose") == pose)
        panels = [("paper", "model → scan (the paper's measure)")] + ([("truth", "vs ground truth")] if truth else [])
        fig, axes = plt.subplots(1, len(panels), figsize=(6.5 * len(panels), 5), squeeze=False)
        cmap = plt.get_cmap("tab10")
        for ax, (kind, title) in zip(axes[0], panels):
            for k, cid in enumerate(cases):
                pts = sorted((r["count"], get(r, kind, "surface", "mae")) for r in runs
                             if r["case"] == cid and get(r, kind, "surface", "mae") is not None)
                if pts:
                    ax.plot([p[0] for p in pts], [p[1] for p in pts], "-o", ms=3, color=cmap(k % 10), label=cid)
            x, y = series(bs["summary"], "count", pose, kind, "surface", "mae")
            ax.plot(x, y, "--", color="k", lw=2, label="mean over cases")
            if kind == "paper":
                ax.axhline(2.41 if pose == "standing" else 2.28, color="k", ls=":", lw=1,
                           label="paper, all 55 blendshapes")
            ax.set_xlabel("number of blendshapes free (the first n of %d)" % bs["total"])
            ax.set_ylabel("surface MAE (mm)")
            ax.set_title(title)
            ax.legend(fontsize=8, ncol=2)
        fig.suptitle("Fig. %d — surface MAE vs number of blendshapes, %s" % (num, POSE_LABEL[pose]))
        fig.tight_layout()
        fig.savefig(path(out, name))
        plt.close(fig)


def fig78(j, out):
    lam = j["lambdas"]
    s = lam["summary"]
    truth = has_truth(s)
    poses = poses_in(s)
    for metric, name, num in (("surface", "fig7_lambda_surface.png", 7), ("landmarks", "fig8_lambda_landmarks.png", 8)):
        kinds = ([("truth", "vs ground truth")] if truth else []) + [
            ("paper", "model → scan" if metric == "surface" else "model → landmarks placed on the scan")]
        fig, axes = plt.subplots(len(kinds), len(poses), figsize=(6.2 * len(poses), 4.3 * len(kinds)), squeeze=False)
        for r, (kind, ktitle) in enumerate(kinds):
            for c, pose in enumerate(poses):
                ax = axes[r][c]
                for spec in lam["lambdas"]:
                    pts = [(e["factor"], get(e, pose, kind, metric, "mae")) for e in s if e["lambda"] == spec["field"]]
                    pts = sorted(p for p in pts if p[1] is not None)
                    ax.plot([p[0] for p in pts], [p[1] for p in pts], "-o", ms=4,
                            color=LAMBDA_COLOR.get(spec["field"]),
                            label="%s (default %g)" % (spec["symbol"], spec["default"]))
                ax.axvline(1.0, color="k", lw=0.8, ls=":")
                ax.set_xscale("log")
                ax.set_xlabel("λ / default λ (one λ changed at a time; smaller λ = stronger term)")
                ax.set_ylabel("%s MAE (mm)" % ("surface" if metric == "surface" else "landmark"))
                ax.set_title("%s, %s" % (pose, ktitle))
                ax.legend(fontsize=8)
        fig.suptitle("Fig. %d — sensitivity of the %s MAE to the weights (mean over cases)" %
                     (num, "surface" if metric == "surface" else "landmark"))
        fig.tight_layout()
        fig.savefig(path(out, name))
        plt.close(fig)


def resolution(j, out):
    res = j["resolution"]
    s = res["summary"]
    poses = poses_in(s)
    truth = has_truth(s)
    fig, axes = plt.subplots(1, 3, figsize=(17, 4.8))
    for pose in poses:
        c = POSE_COLOR[pose]
        x, y = series(s, "vertices", pose, "time_s")
        axes[0].plot(x, y, "-o", color=c, label=POSE_LABEL[pose])
        for kind, style in ((("truth", "-o"),) if truth else ()) + (("paper", "--s"),):
            label = "%s, %s" % (pose, "vs ground truth" if kind == "truth" else
                                "the paper's way (model to scan / to the placed landmarks)")
            x, y = series(s, "vertices", pose, kind, "surface", "mae")
            axes[1].plot(x, y, style, color=c, mfc="none" if kind == "paper" else c, label=label)
            x, y = series(s, "vertices", pose, kind, "landmarks", "mae")
            axes[2].plot(x, y, style, color=c, mfc="none" if kind == "paper" else c, label=label)
    for ax, yl, t in ((axes[0], "registration time (s)", "Time"), (axes[1], "surface MAE (mm)", "Surface error"),
                      (axes[2], "landmark MAE (mm)", "Landmark error")):
        ax.set_xscale("log")
        ax.set_xlabel("template vertices")
        ax.set_ylabel(yl)
        ax.set_title(t)
        ax.set_xticks([lv["vertices"] for lv in res["levels"]])
        ax.set_xticklabels(["%d\n(%g mm)" % (lv["vertices"], lv["edge_mm"]) for lv in res["levels"]], fontsize=9)
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_xlabel("template vertices (target edge length)")
    axes[0].legend(fontsize=8, loc="upper left")
    axes[0].set_ylim(bottom=0)
    edges = ", ".join("%g mm → %d" % (lv["edge_mm"], lv["vertices"]) for lv in res["levels"])
    fig.suptitle("Template resolution (edge length → vertices: %s), mean over cases" % edges)
    fig.tight_layout()
    fig.legend(*axes[1].get_legend_handles_labels(), loc="upper center", bbox_to_anchor=(0.62, 0.0), ncol=2,
               fontsize=9, frameon=False)
    fig.savefig(path(out, "resolution.png"))
    plt.close(fig)


def main(argv):
    global PREFIX
    if len(argv) == 5 and argv[3] == "--prefix":
        PREFIX = argv[4]
        argv = argv[:3]
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    with open(argv[1]) as fh:
        j = json.load(fh)
    out = argv[2]
    os.makedirs(out, exist_ok=True)
    done = []
    for key, fn in (("landmarks", fig4), ("blendshapes", fig56), ("lambdas", fig78), ("resolution", resolution)):
        if key in j and j[key].get("runs"):
            fn(j, out)
            done.append(key)
    print("plot.py: wrote figures for %s in %s" % (", ".join(done) or "nothing", out))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
