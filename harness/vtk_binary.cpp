#include "vtk_binary.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <bit>

#include "common/error.hpp"

namespace stiction::harness {

static_assert(std::endian::native == std::endian::little, "VTU files are declared byte_order=\"LittleEndian\"");

std::uint64_t VtkAppendedData::add(const void* data, std::size_t n_bytes) {
  const std::uint64_t offset = bytes_.size();
  const std::size_t n_blocks = (n_bytes + block_size - 1) / block_size;
  std::vector<std::uint64_t> header = {n_blocks, block_size, n_bytes % block_size};
  std::string blocks;
  std::vector<Bytef> buffer(compressBound(block_size));
  const auto* in = static_cast<const Bytef*>(data);
  for (std::size_t k = 0; k < n_blocks; ++k) {
    const std::size_t n = std::min(block_size, n_bytes - k * block_size);
    uLongf compressed = buffer.size();
    const int status = compress2(buffer.data(), &compressed, in + k * block_size, n, Z_DEFAULT_COMPRESSION);
    if (status != Z_OK) throw Error(fmt::format("zlib compress2 failed ({})", status), ErrorKind::Internal);
    header.push_back(compressed);
    blocks.append(reinterpret_cast<const char*>(buffer.data()), compressed);
  }
  bytes_.append(reinterpret_cast<const char*>(header.data()), header.size() * sizeof(std::uint64_t));
  bytes_ += blocks;
  return offset;
}

}  // namespace stiction::harness
