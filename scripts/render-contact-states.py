#!/usr/bin/env python3
"""Render the contact states of a 3D run as a PNG, as the paper's Figures 11 and 12 do.

Reads a run's contact.csv (written by `stiction solve`: one row per multiplier node and
load step, deformed position x, y, z and the state inactive / stick / slip) and draws, at
the last load step (or --step): left, every slave node in 3D seen from below; right, the
strip bottoms' nodes in plan view with the groove-wall nodes that touch (stick or slip)
marked, so that one sees where strips touch. Headless (matplotlib's Agg backend, Debian's
python3-matplotlib).

Usage: render-contact-states.py CONTACT_CSV OUT_PNG [--step N] [--title TEXT]
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = {"inactive": "#b0b0b0", "stick": "#1f5fbf", "slip": "#d62728"}


def read_rows(path):
    with open(path, newline="") as f:
        lines = [line for line in f if not line.startswith("#")]
    return list(csv.DictReader(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("contact_csv")
    ap.add_argument("out_png")
    ap.add_argument("--step", type=int, default=None, help="load step (default: the last)")
    ap.add_argument("--title", default="")
    args = ap.parse_args()
    rows = read_rows(args.contact_csv)
    if not rows:
        sys.exit(f"{args.contact_csv}: no contact rows")
    step = args.step if args.step is not None else max(int(r["step"]) for r in rows)
    rows = [r for r in rows if int(r["step"]) == step]
    if not rows:
        sys.exit(f"{args.contact_csv}: no rows at load step {step}")
    pairs = sorted({r["pair"] for r in rows})

    fig = plt.figure(figsize=(13, 5.5))
    ax3 = fig.add_subplot(1, 2, 1, projection="3d")
    for state, colour in COLOURS.items():
        sel = [r for r in rows if r["state"] == state]
        if sel:
            ax3.scatter([float(r["x"]) for r in sel], [float(r["y"]) for r in sel], [float(r["z"]) for r in sel],
                        s=4, c=colour, label=f"{state} ({len(sel)})", depthshade=False)
    ax3.view_init(elev=-35, azim=-60)  # from below, where the strips meet the ground
    ax3.set_xlabel("x (mm)")
    ax3.set_ylabel("y (mm)")
    ax3.set_zlabel("z (mm)")
    ax3.legend(loc="upper left", fontsize=8, markerscale=3)
    ax3.set_title("slave nodes, deformed (seen from below)", fontsize=10)

    ax = fig.add_subplot(1, 2, 2)
    summary = []
    for pair in pairs:
        sel = [r for r in rows if r["pair"] == pair]
        touching = [r for r in sel if r["state"] != "inactive"]
        summary.append(f"{pair}: {len(touching)} of {len(sel)} nodes in contact")
        if "ground" in pair:  # the strip bottoms against the rigid ground: every node by state
            for state, colour in COLOURS.items():
                s = [r for r in sel if r["state"] == state]
                ax.scatter([float(r["x"]) for r in s], [float(r["y"]) for r in s], s=5, c=colour)
        else:  # self-contact between groove walls: the nodes that touch
            ax.scatter([float(r["x"]) for r in touching], [float(r["y"]) for r in touching], s=30, marker="x",
                       c="black", label=f"{pair}: touching wall nodes ({len(touching)})")
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title("plan view: strip bottoms by state, touching groove walls (x)", fontsize=10)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="upper right", fontsize=8)
    fig.suptitle((args.title + "\n" if args.title else "") + f"load step {step}: " + "; ".join(summary), fontsize=10)
    fig.tight_layout()
    fig.savefig(args.out_png, dpi=110)


if __name__ == "__main__":
    main()
