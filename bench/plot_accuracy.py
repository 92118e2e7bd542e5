#!/usr/bin/env python3
"""Error against wall time (a Pareto plot) per scene, from accuracy_study's CSV.
usage: plot_accuracy.py STUDY.csv OUT_DIR   -> OUT_DIR/accuracy_<backend>_<scene>.png and a Markdown table on stdout"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def pareto(points):
    """Points no other point beats in both wall time and error."""
    front = []
    for p in sorted(points, key=lambda q: (q["wall"], q["error"])):
        if not front or p["error"] < front[-1]["error"]:
            front.append(p)
    return front


COLOURS = {"fp32": "tab:blue", "fp64": "tab:red", "fp32_full": "tab:green"}


def main():
    rows = [r for r in csv.DictReader(open(sys.argv[1])) if r.get("scene") not in (None, "", "scene")]
    out = sys.argv[2]
    os.makedirs(out, exist_ok=True)
    for key in sorted({(r["backend"], r["scene"]) for r in rows}):
        points = [dict(r, wall=float(r["wall_s"]), error=max(float(r["error"]), 1e-17)) for r in rows
                  if (r["backend"], r["scene"]) == key]
        front = pareto(points)
        fig, ax = plt.subplots(figsize=(6.4, 4.8))
        for p in points:
            colour = COLOURS[p["precision"]]
            marker = "o" if p["model"] == "linear" else "s"
            ax.scatter(p["wall"], p["error"], c=colour, marker=marker, edgecolors="k" if p in front else "none")
            ax.annotate(p["fraction"], (p["wall"], p["error"]), fontsize=7, xytext=(3, 3), textcoords="offset points")
        ax.plot([p["wall"] for p in front], [p["error"] for p in front], "k--", lw=0.8, label="Pareto front")
        for precision, c in COLOURS.items():
            for model, m in (("linear", "o"), ("Hertz", "s")):
                ax.scatter([], [], c=c, marker=m, label=f"{precision} {model}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("wall time [s]")
        ax.set_ylabel("relative error")
        ax.set_title(f"{key[1]} on {key[0]} (labels: dt / contact time)")
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(out, f"accuracy_{key[0]}_{key[1]}.png"), dpi=120)
        print(f"\n### {key[1]} ({key[0]})\n\n| model | precision | dt/t_c | wall [s] | error | Pareto |\n|---|---|---|---|---|---|")
        for p in sorted(points, key=lambda q: (q["model"], q["precision"], float(q["fraction"]))):
            print(f"| {p['model']} | {p['precision']} | {p['fraction']} | {p['wall']:.3g} | {p['error']:.2e} | "
                  f"{'yes' if p in front else ''} |")


if __name__ == "__main__":
    main()
