#pragma once
// The binary payload of a VTK XML file (VTU): every DataArray as one zlib-compressed block
// sequence in the file's appended section, the layout vtkXMLWriter writes with
// header_type="UInt64" and compressor="vtkZLibDataCompressor", so ParaView/VTK read it
// as their own. Why: ASCII costs about 12x the disk and the parse time of this, and the
// text round-trip loses digits.
//
// Layout of one array, at byte `offset` after the `_` that opens <AppendedData encoding="raw">:
//   UInt64 [n_blocks, block_size, last_block_size, compressed size of each block]
//   then the zlib stream of each block. Block k holds raw bytes [k, k+1) * block_size of the
//   array (little-endian, as in memory); last_block_size is the uncompressed size of a
//   partial last block, 0 when the last block is full.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace stiction::harness {

// VTK's name of an array element type (the DataArray `type` attribute).
template <class T> constexpr const char* vtk_type_name() = delete;
template <> constexpr const char* vtk_type_name<double>() { return "Float64"; }
template <> constexpr const char* vtk_type_name<std::int64_t>() { return "Int64"; }
template <> constexpr const char* vtk_type_name<std::int32_t>() { return "Int32"; }
template <> constexpr const char* vtk_type_name<std::uint8_t>() { return "UInt8"; }

// Attributes of the <VTKFile> element that announce this encoding.
inline constexpr const char* vtk_compressed_file_attributes =
    R"(header_type="UInt64" compressor="vtkZLibDataCompressor")";

class VtkAppendedData {
public:
  static constexpr std::size_t block_size = 32768;  // vtkXMLWriter's default

  // Compresses an array and appends it; returns its offset (the DataArray `offset` attribute).
  std::uint64_t add(const void* data, std::size_t n_bytes);
  template <class T> std::uint64_t add(const std::vector<T>& v) { return add(v.data(), v.size() * sizeof(T)); }

  // The bytes to write between `_` and </AppendedData>.
  const std::string& bytes() const { return bytes_; }

private:
  std::string bytes_;
};

}  // namespace stiction::harness
