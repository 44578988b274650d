#pragma once
// Reads back the DataArrays of a VTU file as harness/vtu_writer writes them: inline ASCII,
// or appended raw binary compressed with zlib in VTK's block layout (header_type="UInt64").
// Written apart from the writer's encoder so a test can check the encoding against VTK's
// layout rather than against itself. Not a general VTK reader: one Piece, no base64, no
// inline binary, little-endian only.
#include <map>
#include <string>
#include <vector>

namespace stiction::test {

struct VtuArray {
  std::string name;    // "Points" for the point coordinates
  std::string type;    // Float64, Int64, Int32 or UInt8
  std::string format;  // ascii or appended
  int n_components = 1;
  std::vector<double> values;  // integers converted (exact below 2^53)
};

struct VtuFile {
  std::map<std::string, std::string> attributes;  // of <VTKFile>
  std::map<std::string, std::string> piece;       // of <Piece>
  std::vector<VtuArray> arrays;                   // in file order
  const VtuArray& array(const std::string& name) const;  // throws if absent
};

// Throws std::runtime_error naming what is malformed or unsupported.
VtuFile read_vtu(const std::string& path);

}  // namespace stiction::test
