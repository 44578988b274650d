#!/usr/bin/env bash
# Writes, for every built-in contact scene, the variant that times its linear solves without
# contact: the same scene with its [[contact]] pairs removed. Mesh, materials and supports are
# unchanged, so the Newton systems have the same displacement block A (free contact surfaces,
# natural boundary conditions) and no multipliers. Where the contact was the only load (a
# rigid plane that moves: hertz-cylinder-2d, hertz-sphere-3d), a small uniform traction on
# the contact surface, towards the body, stands in for it.
#
# Why not the older variants (reports/contact-levels-0-2/scenes/): they prescribed the
# displacement of the whole contact surface, which for the Hertz scenes is the whole curved
# boundary. That stiffens A (Dirichlet on every surface node): its linear solves are easier
# than the contact scene's displacement block, and the contact-over-no-contact ratio then
# also counts that difference. reports/contact-levels-0-2-pair-removed/ measures both.
#
# Usage: scripts/contact-free-variants.sh <output directory>
set -euo pipefail
out=${1:?usage: $0 <output directory>}
here=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"

# scene -> traction tables to append (empty: the scene has loads of its own)
declare -A stand_in=(
  [hertz-cylinder-2d]=$'[[traction]]\nboundary = "surface"\nvalue = [0.0, 1.0e-3]\n'
  [hertz-sphere-3d]=$'[[traction]]\nboundary = "surface"\nvalue = [0.0, 1.0e-3, 0.0]\n'
  [hertz-cylinders-2d]=""
  [hertz-spheres-3d]=""
  [sliding-block-2d]=""
  [contact-patch-2d]=""
  [self-contact-2d]=""
)

for scene in "${!stand_in[@]}"; do
  src="$here/harness/scenes/$scene.toml"
  dst="$out/$scene-pair-removed.toml"
  {
    echo "# Variant of the built-in scene $scene written by scripts/contact-free-variants.sh:"
    echo "# its contact pairs removed (same mesh, materials, supports), to time the linear solves"
    echo "# without contact."
    # Drop every [[contact]] table (up to the next table header) and rename the scene; the
    # stand-in traction goes before [load].
    awk -v name="$scene" -v extra="${stand_in[$scene]}" '
      /^\[\[contact\]\]/ { skip = 1; next }
      /^\[/ { skip = 0 }
      /^\[load\]/ && extra != "" { print extra }
      skip { next }
      $0 == "name = \"" name "\"" { print "name = \"" name "-pair-removed\""; next }
      { print }' "$src"
  } >"$dst"
  grep -q '^\[\[contact\]\]' "$dst" && { echo "$dst: a contact table is left" >&2; exit 1; }
  echo "$dst"
done
