#pragma once
// The paper's "block with strips" (a rubber tyre-tread block): a box [0,lx]x[0,ly]x[0,lz]
// whose bottom face (z = 0) is cut by straight grooves running along y through the whole
// width, so that the bottom is a row of strips. Meshed with tetrahedra by Gmsh
// (OpenCASCADE: the box minus one box per groove).
//
//   z = lz     +---------------------------------------------+   top
//              |                                             |
//   z = depth  |      +--+      +--+             +--+        |   groove-floor (ceilings)
//              |strip |  | strip|  |    ...      |  | strip  |
//   z = 0      +------+  +------+  +---  ...  ---+  +--------+   strip-bottom
//                     ^  ^
//     groove-wall-left    groove-wall-right  (x0 and x1 of each groove)
//
// Groove i (0-based) spans x in groove_span(spec, i); the n + 1 strips all have the width
// (lx - n width) / (n + 1), the outer ones included.
#include <array>

#include "mesh/mesh.hpp"

namespace stiction::mesh {

// Defaults: the paper's block (50 x 50 x 16 mm). The paper gives no groove dimensions;
// chosen here: 5 grooves 0.5 mm wide and 8 mm deep (tread depth), so 6 strips 7.9 mm wide
// and 8 mm tall. Why 0.5 mm: the paper's load (bottoms pressed up 1.5 mm, then the ground
// slid 6 mm with mu = 0.3, linear E = 1, nu = 0.3) makes the walls bulge into the grooves;
// once the bottoms slip (they lag the ground by about 2 mm) the bulge closes a groove by
// about 0.5-0.7 mm. Solved with the groove walls as a contact pair, 1 mm grooves keep at
// least 0.33 mm open to the end (no wall node ever touches), 0.5 mm ones close: wall nodes
// touch and slip in the last three steps. Narrower grooves would need smaller elements at
// their ceilings (0.5 mm already lowers the smallest mean-ratio quality from 0.32 to 0.21).
// Sizes: contact_size on the strip bottoms, linear in z up to h at the top, tuned to
// Table 1 at level 0: 2 675 vertices, 8 900 tetrahedra, 49 482 displacement unknowns
// (Table 1: 2 654, 9 714, 50 748) and 818 + 525 = 1 343 multiplier nodes on the strip
// bottoms and the left walls (3 771 / 3 = 1 257); levels are uniform refinements.
struct GroovedBlockSpec {
  std::array<double, 3> size{50.0, 50.0, 16.0};  // lx, ly, lz
  int grooves = 5;
  double groove_width = 0.5;
  double groove_depth = 8.0;
  double h = 4.8;              // element size at the top (z = lz)
  double contact_size = 2.15;  // element size on the strip bottoms (z = 0); at most h
};

// x range [x0, x1] of groove i (0 <= i < grooves).
std::array<double, 2> groove_span(const GroovedBlockSpec& spec, int i);

// Facet names: "strip-bottom" (z = 0, every strip in one group), "groove-wall-left" (the
// wall at a groove's x0: material on its left, outward normal +x), "groove-wall-right" (at
// x1, outward normal -x), "groove-floor" (the groove ceilings at z = depth), "top" (z = lz),
// "xmin", "xmax", "ymin", "ymax" (the outer lateral faces, named as the box generator's).
// Cell tag 1 "body". The element size grows linearly in z from contact_size at z = 0 to h
// at z = lz (sizes at the geometry's corners, interpolated by Gmsh). Deterministic.
// Throws stiction::Error when the grooves do not fit (n width >= lx, depth >= lz) or a
// size is not positive.
Mesh generate_grooved_block(const GroovedBlockSpec& spec);

}  // namespace stiction::mesh
