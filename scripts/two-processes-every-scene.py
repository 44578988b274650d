#!/usr/bin/env python3
"""Every built-in scene on one process and under `mpirun -n 2`: the same Newton path?

  scripts/two-processes-every-scene.py STICTION OUT_DIR [--solver lu-mumps] [--scenes a,b] [--level L]

Runs `stiction solve <scene> --quick --solver S --no-vtu --quiet [--level L]` alone and under
`mpirun -n 2` (each run in OUT_DIR/<scene>/np{1,2}), then compares the two steps.csv files
row by row: Newton iterations, cut-backs and reasons must be the same, and the force
columns (reactions, tractions, contact forces) are compared by their largest difference over
the largest force of the run. Prints a markdown table (scene, Newton iterations of each,
force difference, the two-process run's header line saying what each process held) and
exits 1 when a path differs or a force differs by more than 1e-8.
"""
import argparse
import csv
import os
import subprocess
import sys


def read_steps(path):
    """(header comment lines, data rows as dicts) of a steps.csv."""
    comments, rows, columns = [], [], None
    with open(path, newline="") as f:
        for fields in csv.reader(f):
            if not fields:
                continue
            if fields[0].startswith("#"):
                comments.append(",".join(fields))
                continue
            if fields[0] == "step":
                columns = fields
                continue
            rows.append(dict(zip(columns, fields)))
    return comments, rows


def is_force(column):
    return column.startswith(("reaction_", "traction_", "contact_")) and column.rsplit("_", 1)[-1] in "xyz"


def scenes(stiction):
    out = subprocess.run([stiction, "scenes"], capture_output=True, text=True, check=True).stdout
    return [line.split()[0] for line in out.splitlines() if line and not line.startswith(" ")]


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("stiction")
    p.add_argument("out")
    p.add_argument("--solver", default="lu-mumps")
    p.add_argument("--scenes", default="")
    p.add_argument("--level", type=int, default=None, help="mesh level (default: each scene's own)")
    a = p.parse_args()
    mpirun = ["mpirun", "-n", "2", "--oversubscribe"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    failed = False
    print("| scene | Newton (one / two) | force difference | two processes held |")
    print("|---|---|---|---|")
    for scene in a.scenes.split(",") if a.scenes else scenes(a.stiction):
        steps = {}
        for n, launcher in ((1, []), (2, mpirun)):
            out = os.path.join(a.out, scene, f"np{n}")
            cmd = launcher + [a.stiction, "solve", scene, "--quick", "--solver", a.solver, "--no-vtu", "--quiet",
                              "--out", out] + ([] if a.level is None else ["--level", str(a.level)])
            run = subprocess.run(cmd, env=env, capture_output=True, text=True)
            if run.returncode != 0:
                print(f"| {scene} | np={n} failed: {run.stderr.strip().splitlines()[-1:]} | | |")
                failed = True
                break
            steps[n] = read_steps(os.path.join(out, "steps.csv"))
        if len(steps) < 2:
            continue
        (_, one), (comments, two) = steps[1], steps[2]
        same_path = len(one) == len(two) and all(
            x[k] == y[k] for x, y in zip(one, two) for k in ("step", "cut", "converged", "reason", "newton_iterations"))
        scale = max((abs(float(v)) for row in one for k, v in row.items() if is_force(k) and v), default=0.0)
        diff = max((abs(float(v) - float(y[k])) for x, y in zip(one, two) for k, v in x.items()
                    if is_force(k) and v and y.get(k)), default=0.0)
        relative = diff / scale if scale > 0 else float("nan")
        # What the header says each process held, after "cells split by <partitioner>".
        held = next((c.split("(", 1)[1].rstrip(" )").split(" ", 4)[-1].lstrip(";, ") for c in comments
                     if c.startswith("# MPI processes")), "?")
        newton = lambda rows: sum(int(r["newton_iterations"]) for r in rows)
        print(f"| {scene} | {newton(one)} / {newton(two)}{'' if same_path else ' (path differs)'} | {relative:.1e} | {held} |")
        failed |= not same_path or not relative <= 1e-8
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
