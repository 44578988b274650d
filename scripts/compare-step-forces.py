#!/usr/bin/env python3
"""Sums up runs' steps.csv files and compares their forces at the load steps both reached.

  scripts/compare-step-forces.py RUN.csv [REFERENCE.csv] [--force reaction_slab/base]

For each file (a run chained over several processes by --restart, its parts' rows one after
the other): the last pseudo-time converged, converged increments, failed attempts, Newton
and Krylov iterations and seconds of steps (rows of an increment that a restart computed
again count twice, as they were computed twice). With a reference: at every pseudo-time
both converged (the last row of each, where a restart repeated it), the largest relative
difference of the force's components and the digits that agree at least, over every such
time and over those both runs reached through the same increments (a frictional path
depends on them, so a run that cut a step the other took whole may differ by its path, not
by its linear solver).
"""
import argparse
import csv
import math
import sys


def read_steps(path):
    """The data rows of a steps.csv, each as a dict under the column line above it."""
    rows, columns = [], None
    with open(path, newline="") as f:
        for fields in csv.reader(f):
            if not fields or fields[0].startswith("#"):
                continue
            if fields[0] == "step":
                columns = fields
                continue
            if columns is None:
                sys.exit(f"{path}: a data line before the column line")
            rows.append(dict(zip(columns, fields)))
    return rows


def summary(rows):
    converged = [r for r in rows if r["converged"] == "1"]
    total = lambda column: sum(float(r.get(column) or 0) for r in rows)
    return {
        "reached": max((float(r["time"]) for r in converged), default=0.0),
        "increments": len(converged),
        "failed": len(rows) - len(converged),
        "newton": int(total("newton_iterations")),
        "krylov": int(total("krylov_iterations")),
        "seconds": total("wall_seconds"),
    }


def converged_by_time(rows):
    return {round(float(r["time"]), 9): r for r in rows if r["converged"] == "1"}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run")
    parser.add_argument("reference", nargs="?")
    parser.add_argument("--force", default="reaction_slab/base", help="column prefix of the force (_x, _y)")
    args = parser.parse_args()

    files = [args.run] + ([args.reference] if args.reference else [])
    tables = {path: read_steps(path) for path in files}
    print("| file | reached t | converged increments | failed attempts | Newton | Krylov | s of steps |")
    print("|---|---|---|---|---|---|---|")
    for path, rows in tables.items():
        s = summary(rows)
        print(f"| {path} | {s['reached']:g} | {s['increments']} | {s['failed']} | {s['newton']} | {s['krylov']} "
              f"| {s['seconds']:.0f} |")
    if not args.reference:
        return 0

    run, ref = converged_by_time(tables[args.run]), converged_by_time(tables[args.reference])
    common = sorted(set(run) & set(ref))
    if not common:
        sys.exit("no pseudo-time converged in both files")
    # A frictional path depends on the increments: where one run cut a step the other took
    # whole, their forces may differ by the path, not by the linear solver.
    path = lambda times, t: [u for u in times if u <= t]
    run_times, ref_times = sorted(run), sorted(ref)
    same = [t for t in common if path(run_times, t) == path(ref_times, t)]
    print(f"\n{len(common)} pseudo-times converged in both, t = {common[0]:g} to {common[-1]:g}; "
          f"{len(same)} of them reached through the same increments in both:")
    for axis in ("x", "y"):
        column = f"{args.force}_{axis}"
        for label, times in (("every common time", common), ("same increments", same)):
            differences = [(abs(float(run[t][column]) - float(ref[t][column])) /
                            max(abs(float(ref[t][column])), 1e-300), t) for t in times]
            if not differences:
                continue
            worst, t = max(differences)
            digits = "all printed" if worst == 0 else f"{-math.log10(worst):.1f}"
            print(f"  {column}, {label}: largest relative difference {worst:.2e} at t = {t:g} "
                  f"({float(run[t][column]):.10g} against {float(ref[t][column]):.10g}), digits agreeing {digits}; "
                  f"above 1e-6 at {sum(d > 1e-6 for d, _ in differences)} times")
            above = [u for d, u in differences if d > 1e-6]
            after = [(d, u) for d, u in differences if above and u > max(above)]
            if after:
                print(f"    after t = {max(above):g}: {len(after)} times, largest relative difference "
                      f"{max(after)[0]:.2e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
