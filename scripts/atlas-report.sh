#!/usr/bin/env bash
# The stability atlas (reports/atlas/): the base scenes' keys swept one at a time for the
# Schur backends, PETSc's field split and lu-mumps, each cell its own process
# (`stiction atlas`, see README). ATLAS_OUT (default reports/atlas) and ATLAS_TIME_LIMIT
# (seconds per cell, default 600) adjust it; --resume continues an interrupted one.
# Usage: scripts/atlas-report.sh [build dir]
set -euo pipefail
build=${1:-build}
out=${ATLAS_OUT:-reports/atlas}
limit=${ATLAS_TIME_LIMIT:-600}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
source "$(dirname "$0")/ensure-gnuplot.sh"
mkdir -p "$out"
atlas() { local dir=$1; shift; "$build/stiction" atlas "$@" --time-limit "$limit" --out "$out/$dir" --resume; }

# Large sliding with friction, two deformable bodies: the pressing and the first two sliding
# steps (--quick). Indenter stiffness against the slab's 689.6: contrast 1 to 1e4.
atlas ironing-2d ironing-2d --quick --solvers schur-amg,schur-gamg,fieldsplit-schur,lu-mumps \
  --axis 'contact[0].friction=0,0.3,0.6,1,2' \
  --axis 'material[1].E=689.6,6896,68960,689600,6896000' \
  --axis 'contact[0].tangential_penalty=1e-6,1e-3,1,1e3,1e6' \
  --axis 'load.phases=[{until = 1.0, steps = 2}, {until = 2.0, steps = 200}];[{until = 1.0, steps = 5}, {until = 2.0, steps = 200}];[{until = 1.0, steps = 20}, {until = 2.0, steps = 200}]' \
  --axis 'level=0,1'

# Large slip per load step: the sliding phase of ironing-2d in 200 load steps (the scene's:
# 0.05 per step, about one facet of the slab top at level 0) down to 5 (2.0 per step, some 40
# facets), over the first 2.0 of sliding (t = 1.2), with the automatic cut-back (the cells
# say how many increments it cut) and without it (the raw method).
slip='load.phases=[{until = 1.0, steps = 10}, {until = 2.0, steps = 200}];[{until = 1.0, steps = 10}, {until = 2.0, steps = 50}];[{until = 1.0, steps = 10}, {until = 2.0, steps = 20}];[{until = 1.0, steps = 10}, {until = 2.0, steps = 10}];[{until = 1.0, steps = 10}, {until = 2.0, steps = 5}]'
atlas ironing-2d-large-slip ironing-2d --quick --set load.quick_until=1.2 \
  --solvers schur-amg,schur-gamg,fieldsplit-schur,lu-mumps --axis "$slip"
atlas ironing-2d-large-slip-no-cut ironing-2d --quick --set load.quick_until=1.2 --set load.max_cuts=0 \
  --solvers schur-amg,schur-gamg,fieldsplit-schur,lu-mumps --axis "$slip"

# Hard settings together: the stiffness contrast (indenter modulus 100, 1 000, 10 000 times
# the slab's) with friction and with the tangential penalty, every combination.
contrast='material[1].E=68960,689600,6896000'
atlas ironing-2d-pairs ironing-2d --quick --solvers schur-amg,schur-gamg,lu-mumps \
  --pair "$contrast" 'contact[0].friction=0,0.3,1' --pair "$contrast" 'contact[0].tangential_penalty=1,1e3,1e6'

# Grazing contact: sliding-block-2d pressed 1e-2 (the scene), then by less, down to exactly
# touching, then held off the plane by 1e-12 to 1e-6 (the gap tolerance is 1e-9 of the slave
# surface's diameter), while its top is pulled along the plane.
atlas sliding-block-2d-grazing sliding-block-2d --solvers schur-amg,schur-gamg,fieldsplit-schur,lu-mumps \
  --axis 'dirichlet[0].value=[-1e-2];[-1e-6];[-1e-9];[-1e-12];[0.0];[1e-12];[1e-9];[1e-6]'

# Near-incompressibility: bulk to shear modulus kappa / mu10 from 1e1 to 1e6, mixed u-p (the
# paper's) and displacement only.
kappa='material[0].kappa=10,100,1000,10000,100000,1000000'
atlas cook-membrane-2d-mixed cook-membrane-2d --solvers schur-amg,schur-gamg,fieldsplit-schur,lu-mumps --axis "$kappa"
atlas cook-membrane-2d-displacement cook-membrane-2d --set 'material[0].formulation="displacement"' \
  --solvers schur-amg,schur-gamg,gamg,lu-mumps --axis "$kappa"
# The paper's benchmark at level 0, its short version (pressing, then the first sliding load
# step): the ground's friction coefficient in the sliding phase from 0 to 2 (the grooves keep
# 0.3), and the sliding step from 0.75 mm to the whole 6 mm in one step (8 to 1 steps; with 8
# the short version runs the two steps to t = 5).
friction='contact[0].friction_table=[[0.0, 0.0], [4.0, 0.0]];[[0.0, 0.0], [4.0, 0.3]];[[0.0, 0.0], [4.0, 0.6]];[[0.0, 0.0], [4.0, 1.0]];[[0.0, 0.0], [4.0, 2.0]]'
slide='load.phases=[{until = 4.0, steps = 4}, {until = 8.0, steps = 8}];[{until = 4.0, steps = 4}, {until = 8.0, steps = 4}];[{until = 4.0, steps = 4}, {until = 8.0, steps = 2}];[{until = 4.0, steps = 4}, {until = 8.0, steps = 1}]'
atlas block-strips block-strips --quick --solvers schur-amg,schur-gamg,lu-mumps --axis "$friction" --axis "$slide"
echo "atlas-report: wrote $out" >&2
