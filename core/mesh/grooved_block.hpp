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
// chosen here: 5 grooves 1 mm wide and 8 mm deep (tread depth), so 6 strips 7.5 mm wide
// and 8 mm tall. Why 1 mm: with the top clamped, the strip bottoms pressed up 1.5 mm and
// held while moved 6 mm along -x (linear, E = 1, nu = 0.3, no self-contact; the default
// mesh), the walls bulge into the grooves at mid-height, closing them by up to 1.9 mm:
// 2 mm grooves stay 0.09-0.8 mm open, 1 mm ones overlap by 0.2-0.8 mm at every groove, so
// the walls touch. With the paper's mu = 0.3 the bottoms slip once they lag the ground by
// about 2 mm (mean |sigma_xz / sigma_zz| reaches 0.3 there); then 1 mm grooves keep about
// 0.5 mm and 0.5 mm ones just close (-0.03 to 0.2 mm), at worse tetrahedra (the narrow
// groove ceilings: smallest mean-ratio quality 0.21 against 0.32); set groove_width = 0.5
// for that case (level 0: about 2 890 vertices, 9 600 tetrahedra). Sizes: contact_size on the strip bottoms, linear in z up to h at the top,
// tuned so that level 0 has 2 751 vertices and 9 108 tetrahedra (Table 1: 2 654, 9 714;
// level 1: 16 923 vertices against 16 916), and 1 245 vertices on the strip bottoms and
// one wall side (the paper's 3 771 multipliers / 3 = 1 257).
struct GroovedBlockSpec {
  std::array<double, 3> size{50.0, 50.0, 16.0};  // lx, ly, lz
  int grooves = 5;
  double groove_width = 1.0;
  double groove_depth = 8.0;
  double h = 4.8;              // element size at the top (z = lz)
  double contact_size = 2.05;  // element size on the strip bottoms (z = 0); at most h
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
