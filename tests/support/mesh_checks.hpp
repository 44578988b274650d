#pragma once
// Equality of meshes and of mesh parts, entity by entity and bit for bit (refinement in parts
// must compute every coordinate as the whole mesh's refinement does).
#include "mesh/local_mesh.hpp"
#include "mesh/mesh.hpp"

namespace stiction::test {

void expect_same_mesh(const mesh::Mesh& actual, const mesh::Mesh& expected);
void expect_same_part(const mesh::LocalMesh& actual, const mesh::LocalMesh& expected);

}  // namespace stiction::test
