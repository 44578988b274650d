#!/usr/bin/env python3
"""The heap a run held at its peak, by the stiction function that asked for it.

Reads heaptrack's recordings (one per process: `mpirun -n 2 heaptrack build/stiction solve
...` writes heaptrack.stiction.<pid>.zst for each), has heaptrack_print write each one's
allocation stacks costed at the heap's peak, charges every stack to its innermost
`stiction::` frame (PETSc, hypre and the standard library allocate on stiction's behalf)
and prints one column per recording, largest first. Functions whose bytes are the same in
every column of a two-process run and in a one-process run of the same scene are the
replicated part: what every process holds whole (mesh, Newton state).

  scripts/heap-by-function.py [--rows N] one.zst [rank0.zst rank1.zst ...]

Needs heaptrack_print (Debian's heaptrack). Run stiction with GLIBC_TUNABLES set (for
example GLIBC_TUNABLES=glibc.malloc.hugetlb=1): otherwise it re-executes itself to set them
and heaptrack records only the process that started it.
"""
import argparse
import collections
import os
import re
import subprocess
import sys
import tempfile


def peak_stacks(recording):
    """(stack, bytes at the heap's peak) of every allocation stack of one recording."""
    with tempfile.TemporaryDirectory() as tmp:
        stacks = os.path.join(tmp, "stacks.txt")
        subprocess.run(["heaptrack_print", "-f", recording, "--print-flamegraph", stacks,
                        "--flamegraph-cost-type", "peak", "--print-peaks", "0", "--print-allocators", "0",
                        "--print-temporary", "0", "--print-leaks", "0"],
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        with open(stacks) as f:
            for line in f:
                stack, cost = line.rsplit(" ", 1)
                yield stack.split(";"), int(cost)


def by_function(recording):
    totals = collections.Counter()
    for frames, cost in peak_stacks(recording):
        ours = [f for f in frames if "stiction::" in f]
        totals[re.sub(r"\(.*", "", ours[-1]) if ours else "(outside stiction)"] += cost
    return totals


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("recordings", nargs="+")
    parser.add_argument("--rows", type=int, default=30)
    args = parser.parse_args()
    columns = [by_function(r) for r in args.recordings]
    names = set().union(*columns)
    print(" ".join(f"{os.path.basename(r)[-18:]:>18}" for r in args.recordings), " MB at the peak, by function")
    print(" ".join(f"{sum(c.values()) / 1e6:18.1f}" for c in columns), " total")
    for name in sorted(names, key=lambda n: -max(c[n] for c in columns))[:args.rows]:
        print(" ".join(f"{c[name] / 1e6:18.1f}" for c in columns), "", name)


if __name__ == "__main__":
    sys.exit(main())
