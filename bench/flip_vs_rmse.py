#!/usr/bin/env python3
"""Where FLIP and RMSE disagree: over the speed-error study's per-scene reports
(bench/results/<machine>/speed-error/report/<scene>/report.json), per scene and sample count, the rank
correlation (Spearman) of the techniques' mean HDR-FLIP with their shaded-image and visibility
RMSE against the converged reference, and the pairs of techniques the two order differently by
more than 25% each way.

    python3 bench/flip_vs_rmse.py bench/results/cpu-2core-llvmpipe/speed-error > flip-vs-rmse.txt
"""
import json
import pathlib
import sys


def ranks(values):
    order = sorted(range(len(values)), key=lambda i: values[i])
    r = [0.0] * len(values)
    i = 0
    while i < len(order):
        j = i
        while j + 1 < len(order) and values[order[j + 1]] == values[order[i]]:
            j += 1
        for k in range(i, j + 1):
            r[order[k]] = (i + j) / 2.0
        i = j + 1
    return r


def spearman(a, b):
    ra, rb = ranks(a), ranks(b)
    n = len(a)
    ma, mb = sum(ra) / n, sum(rb) / n
    cov = sum((x - ma) * (y - mb) for x, y in zip(ra, rb))
    va = sum((x - ma) ** 2 for x in ra) ** 0.5
    vb = sum((y - mb) ** 2 for y in rb) ** 0.5
    return cov / (va * vb) if va > 0 and vb > 0 else float("nan")


def main(root):
    print("FLIP against RMSE (both against the converged reference), per scene and sample count")
    print("rho: Spearman rank correlation over the techniques; disagreements: pairs A, B where FLIP(A) < FLIP(B) / 1.25")
    print("while img RMSE(A) > 1.25 x img RMSE(B)\n")
    for report in sorted(pathlib.Path(root).glob("report/*/report.json")):
        j = json.loads(report.read_text())
        by_preset = {}
        for run in j["runs"]:
            if run.get("status") != "ok" or "flip" not in run or "convergedErrors" not in run:
                continue
            if run["name"] == "raytrace-converged":
                continue
            by_preset.setdefault(run["preset"], []).append(
                (run["name"], run["flip"]["mean"], run["convergedErrors"]["shaded"]["rmse"],
                 run["convergedErrors"]["visibility"]["rmse"]))
        for preset, rows in by_preset.items():
            if len(rows) < 3:
                continue
            flip = [r[1] for r in rows]
            img = [r[2] for r in rows]
            vis = [r[3] for r in rows]
            flips = []
            for a in rows:
                for b in rows:
                    if a[1] * 1.25 < b[1] and a[2] > 1.25 * b[2]:
                        flips.append(f"{a[0]} (FLIP {a[1]:.3f}, RMSE {a[2]:.4f}) vs {b[0]} (FLIP {b[1]:.3f}, RMSE {b[2]:.4f})")
            print(f"{j['sceneName']} @ {preset}: rho(FLIP, img RMSE) {spearman(flip, img):.2f}, "
                  f"rho(FLIP, vis RMSE) {spearman(flip, vis):.2f}; FLIP {min(flip):.3f}-{max(flip):.3f}")
            for f in flips:
                print("    FLIP prefers " + f)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "bench/results/cpu-2core-llvmpipe/speed-error")
