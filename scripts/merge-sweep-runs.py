#!/usr/bin/python3
"""Merges the runs of one bench sweep into another (a level-2 row made over several sittings
in a scratch directory into reports/paper-tables/, say), then `stiction report TO` rebuilds
the report.

    merge-sweep-runs.py FROM TO [RUN ...]

RUN names a run as its directory does (block-strips-L2-fieldsplit-schur); without any, every
run of FROM/runs.csv is merged. For each: its row replaces TO's row of the same scene, level,
solver and processes (or is appended), its linear solves replace that run's lines of
TO/steps.csv, and FROM/runs/RUN replaces TO/runs/RUN (contact.csv gzipped). A comment line in
TO/runs.csv names what was merged from where, with that sweep's command line and last
resumption; the run's own files keep each segment's command line, revision and machine.

Columns are matched by name: a column one table lacks is empty in its rows. A row without
`mumps_factor_fraction` (a sweep made before the column) gets it from the run's metrics.toml
by the rule the bench uses (harness/bench_command.cpp, solve_figures): the factor entries MUMPS
stored over its full-rank estimate, summed over the factorisations.
"""
import csv
import gzip
import shutil
import sys
import tomllib
from pathlib import Path

KEY = ("scene", "level", "solver", "processes")


def read_table(path):
    comments, lines = [], []
    for line in path.read_text().splitlines():
        (comments if line.startswith("#") else lines).append(line)
    reader = csv.DictReader(lines)
    rows = list(reader)
    for row in rows:  # a field more than the header has would be dropped on writing
        if None in row:
            sys.exit(f"merge-sweep-runs: {path} has a line with more fields than its header: {row[None]}")
    return comments, list(reader.fieldnames or []), rows


def run_id(row):
    processes = int(row.get("processes") or 1)
    return f"{row['scene']}-L{row['level']}-{row['solver']}" + (f"-np{processes}" if processes > 1 else "")


def key(row):
    return tuple(row.get(k) or ("1" if k == "processes" else "") for k in KEY)


def factor_fraction(metrics_path):
    if not metrics_path.exists():
        return ""
    with metrics_path.open("rb") as f:
        solves = tomllib.load(f).get("linear_solve", [])
    stored = full_rank = 0.0
    for s in solves:
        for prefix in ("", "ll_"):
            a, b = s.get(prefix + "mumps_factor_entries"), s.get(prefix + "mumps_factor_entries_full_rank")
            if a is not None and b:
                stored, full_rank = stored + a, full_rank + b
    return f"{stored / full_rank:.3f}" if full_rank > 0 else ""


def is_int(text):
    return text.lstrip("-").isdigit()


def step_line_key(line):
    """(scene, level, solver, processes) of a steps.csv line, in either of its formats: with
    the processes column (its 7th field, `converged`, is 0 or 1) or without (the 7th field is
    the linear solver's reason)."""
    f = line.split(",")
    if len(f) > 6 and is_int(f[6]):
        return tuple(f[:4])
    return tuple(f[:3]) + ("1",)


def with_processes(line):
    f = line.split(",")
    return line if len(f) > 6 and is_int(f[6]) else ",".join(f[:3] + ["1"] + f[3:])


def merge_steps(source, target, merged):
    new_lines = [l for l in source.read_text().splitlines() if l and not l.startswith("#")]
    header, new_lines = new_lines[0], new_lines[1:]
    comments, kept = [], []
    for line in target.read_text().splitlines():
        if line.startswith("#"):
            comments.append(line)
        elif line and not line.startswith("scene,") and step_line_key(line) not in merged:
            kept.append(with_processes(line))
    added = [l for l in new_lines if step_line_key(l) in merged]
    target.write_text("\n".join(comments + [header] + kept + added) + "\n")


def provenance(comments):
    """How the source sweep was made: its command line and its last resumption, if any."""
    made = [c[2:] for c in comments if c.startswith("# command:")][:1]
    made += [c[2:] for c in comments if c.startswith("# resumed:")][-1:]
    return "".join(f"; that sweep's {m}" for m in made)


def merged_columns(to_columns, from_columns):
    if set(to_columns) <= set(from_columns):
        return from_columns
    extra = [c for c in from_columns if c not in to_columns]
    return to_columns[:-1] + extra + to_columns[-1:] if to_columns[-1:] == ["detail"] else to_columns + extra


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    source, target, wanted = Path(argv[1]), Path(argv[2]), set(argv[3:])
    from_comments, from_columns, from_rows = read_table(source / "runs.csv")
    comments, to_columns, to_rows = read_table(target / "runs.csv")
    rows = [r for r in from_rows if not wanted or run_id(r) in wanted]
    missing = wanted - {run_id(r) for r in rows}
    if missing:
        sys.exit(f"merge-sweep-runs: no row for {', '.join(sorted(missing))} in {source / 'runs.csv'}")
    columns = merged_columns(to_columns, from_columns)
    merged = {key(r) for r in rows}
    out_rows = [r for r in to_rows if key(r) not in merged] + rows
    for r in out_rows:
        if "mumps_factor_fraction" in columns and not r.get("mumps_factor_fraction"):
            r["mumps_factor_fraction"] = factor_fraction(target / "runs" / run_id(r) / "metrics.toml") \
                if key(r) not in merged else factor_fraction(source / "runs" / run_id(r) / "metrics.toml")
    comments.append(f"# merged from {source}: {', '.join(run_id(r) for r in rows)}{provenance(from_comments)}")
    with (target / "runs.csv").open("w", newline="") as f:
        f.write("\n".join(comments) + "\n")
        writer = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore", lineterminator="\n")
        writer.writeheader()
        for r in out_rows:
            writer.writerow({c: r.get(c) or "" for c in columns})

    # steps.csv: the merged runs' lines replace theirs, as the sweeps wrote them (a field may
    # hold an unquoted comma); lines of a sweep made before the processes column get it.
    merge_steps(source / "steps.csv", target / "steps.csv", merged)

    for r in rows:
        src, dst = source / "runs" / run_id(r), target / "runs" / run_id(r)
        if dst.exists():
            shutil.rmtree(dst)
        shutil.copytree(src, dst, ignore=shutil.ignore_patterns("checkpoint.bin*", "contact.csv"))
        if (src / "contact.csv").exists():
            with (src / "contact.csv").open("rb") as i, gzip.open(dst / "contact.csv.gz", "wb") as o:
                shutil.copyfileobj(i, o)
        print(f"merge-sweep-runs: {run_id(r)} -> {dst}", file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv)
