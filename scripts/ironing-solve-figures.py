#!/usr/bin/python3
"""Time and Krylov iterations per linear solve of the ironing runs, by level, over the same
pseudo-times: the per-solve figures of reports/ironing-2d-L2/README.md ("Key figures").

    ironing-solve-figures.py [REPORTS]      (REPORTS: the reports/ folder, default ./reports)

Level 0 from REPORTS/ironing-2d/runs/, level 1 from REPORTS/ironing-2d-L1/ (the frictionless
schur-amg run at Krylov tolerance 1e-8, as at level 2), level 2 from REPORTS/ironing-2d-L2/.
Each scene's figures cover the solves whose increment ends at or before the level-2
schur-amg run's last pseudo-time, failed attempts included. A run chained by --restart
shares the machine with other work now and then: a Krylov solve that took more than
PAUSED_SECONDS per Krylov iteration (set-up and solve) is taken as paused and left out, and
the count of solves kept is printed. Direct solves (one "iteration") are not filtered. Also
printed: level 2's lu-mumps per solve over its whole run. The table counts the solves on one
process; a sitting on two processes (its header says "# MPI processes: 2") is printed apart.
"""
import csv
import sys
from pathlib import Path

PAUSED_SECONDS = 0.3

SCENES = {  # scene -> level -> solver -> iterations.csv, relative to REPORTS
    "ironing-2d": {
        0: {s: f"ironing-2d/runs/ironing-2d-L0-{s}/iterations.csv" for s in ("schur-amg", "lu-mumps")},
        1: {s: f"ironing-2d-L1/{s}-frictional-iterations.csv" for s in ("schur-amg", "lu-mumps")},
        2: {s: f"ironing-2d-L2/{s}-frictional-iterations.csv" for s in ("schur-amg", "lu-mumps")},
    },
    "ironing-2d-frictionless": {
        0: {s: f"ironing-2d/runs/ironing-2d-frictionless-L0-{s}/iterations.csv" for s in ("schur-amg", "lu-mumps")},
        1: {"schur-amg": "ironing-2d-L1/schur-amg-frictionless-1e-8-iterations.csv",
            "lu-mumps": "ironing-2d-L1/lu-mumps-frictionless-iterations.csv"},
        2: {s: f"ironing-2d-L2/{s}-frictionless-iterations.csv" for s in ("schur-amg", "lu-mumps")},
    },
}


def solves(path, processes=1):
    """The rows of an iterations.csv solved on `processes` MPI processes. Each sitting of a
    chained run starts with its header comments; "# MPI processes: N" says it ran on N."""
    lines, ran_on = [], 1
    for line in path.read_text().splitlines():
        if line.startswith("# command:"):
            ran_on = 1
        elif line.startswith("# MPI processes:"):
            ran_on = int(line.split(":")[1].split()[0])
        elif line and not line.startswith("#") and (ran_on == processes or line.startswith("step")):
            lines.append(line)
    return [row for row in csv.DictReader(lines) if row.get("step") != "step"]  # a restart repeats the header


def figures(rows, t_max):
    """(solves kept, solves up to t_max, Krylov per solve, seconds per solve) over the kept."""
    upto = [r for r in rows if float(r["time"]) <= t_max + 1e-12]
    kept = []
    for r in upto:
        krylov = int(r["krylov_iterations"])
        seconds = float(r["setup_seconds"]) + float(r["solve_seconds"])
        if krylov > 1 and seconds > PAUSED_SECONDS * krylov:
            continue
        kept.append((krylov, seconds))
    n = len(kept)
    return (n, len(upto), sum(k for k, _ in kept) / n if n else float("nan"),
            sum(s for _, s in kept) / n if n else float("nan"))


def main():
    reports = Path(sys.argv[1] if len(sys.argv) > 1 else "reports")
    print("| level | schur-amg Krylov / solve | schur-amg s / solve | lu-mumps s / solve |")
    print("|---|---|---|---|")
    notes = []
    for scene, levels in SCENES.items():
        t_max = max(float(r["time"]) for r in solves(reports / levels[2]["schur-amg"]))
        print(f"| **{scene}** (t <= {t_max:g}) | | | |")
        for level, files in levels.items():
            amg = figures(solves(reports / files["schur-amg"]), t_max)
            lu = figures(solves(reports / files["lu-mumps"]), t_max)
            print(f"| {level} | {amg[2]:.1f} | {amg[3]:.2f} | {lu[3]:.2f} |")
            notes.append(f"{scene} level {level}: schur-amg {amg[0]} of {amg[1]} solves kept, lu-mumps {lu[0]}")
        whole = figures(solves(reports / levels[2]["lu-mumps"]), float("inf"))
        notes.append(f"{scene} level 2, lu-mumps over its whole run: {whole[3]:.2f} s per solve ({whole[0]} solves)")
        two = solves(reports / levels[2]["schur-amg"], processes=2)
        if two:
            amg = figures(two, float("inf"))
            notes.append(f"{scene} level 2, schur-amg on two processes (t = {float(two[0]['time']):g} to "
                         f"{float(two[-1]['time']):g}, left out above): {amg[2]:.1f} Krylov iterations and "
                         f"{amg[3]:.2f} s per solve ({amg[0]} of {len(two)} solves kept)")
    print()
    print("\n".join(notes))


if __name__ == "__main__":
    main()
