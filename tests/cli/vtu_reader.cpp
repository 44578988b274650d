#include "vtu_reader.hpp"

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace stiction::test {

namespace {

std::map<std::string, std::string> attributes_of(const std::string& tag) {
  std::map<std::string, std::string> a;
  static const std::regex attribute(R"re((\w+)="([^"]*)")re");
  for (auto it = std::sregex_iterator(tag.begin(), tag.end(), attribute); it != std::sregex_iterator(); ++it)
    a[(*it)[1]] = (*it)[2];
  return a;
}

std::uint64_t read_u64(const std::string& bytes, std::size_t at) {
  if (at + 8 > bytes.size()) throw std::runtime_error("appended data: header runs past the end of the file");
  std::uint64_t v;
  std::memcpy(&v, bytes.data() + at, 8);
  return v;
}

// The raw bytes of the array whose compression header starts at `offset` in `appended`:
// [n_blocks, block_size, last_block_size (0: full), compressed sizes...], then the blocks.
std::string inflate_array(const std::string& appended, std::uint64_t offset) {
  const std::uint64_t n_blocks = read_u64(appended, offset), block = read_u64(appended, offset + 8),
                      last = read_u64(appended, offset + 16);
  std::size_t at = offset + 24 + 8 * n_blocks;
  std::string raw;
  for (std::uint64_t k = 0; k < n_blocks; ++k) {
    const std::uint64_t compressed = read_u64(appended, offset + 24 + 8 * k);
    const std::uint64_t expected = k + 1 == n_blocks && last != 0 ? last : block;
    if (at + compressed > appended.size()) throw std::runtime_error("appended data: block runs past the end");
    raw.resize(raw.size() + expected);
    uLongf n = expected;
    const int status = uncompress(reinterpret_cast<Bytef*>(raw.data() + raw.size() - expected), &n,
                                  reinterpret_cast<const Bytef*>(appended.data() + at), compressed);
    if (status != Z_OK || n != expected)
      throw std::runtime_error("appended data: block " + std::to_string(k) + " does not inflate to " +
                               std::to_string(expected) + " bytes (zlib status " + std::to_string(status) + ")");
    at += compressed;
  }
  return raw;
}

template <class T>
std::vector<double> decode_as(const std::string& raw) {
  if (raw.size() % sizeof(T) != 0) throw std::runtime_error("appended data: size not a multiple of the type");
  std::vector<double> v(raw.size() / sizeof(T));
  for (std::size_t i = 0; i < v.size(); ++i) {
    T x;
    std::memcpy(&x, raw.data() + i * sizeof(T), sizeof(T));
    v[i] = static_cast<double>(x);
  }
  return v;
}

std::vector<double> decode(const std::string& type, const std::string& raw) {
  if (type == "Float64") return decode_as<double>(raw);
  if (type == "Int64") return decode_as<std::int64_t>(raw);
  if (type == "Int32") return decode_as<std::int32_t>(raw);
  if (type == "UInt8") return decode_as<std::uint8_t>(raw);
  throw std::runtime_error("unsupported DataArray type " + type);
}

std::vector<double> parse_ascii(const std::string& text) {
  std::istringstream in(text);
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  if (!in.eof()) throw std::runtime_error("ascii DataArray: not a number near '" + text.substr(0, 40) + "'");
  return v;
}

}  // namespace

const VtuArray& VtuFile::array(const std::string& name) const {
  for (const auto& a : arrays)
    if (a.name == name) return a;
  throw std::runtime_error("no DataArray named " + name);
}

VtuFile read_vtu(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

  // The XML part ends where the appended bytes begin: after the `_` that follows <AppendedData ...>.
  const std::size_t appended_tag = text.find("<AppendedData");
  const std::string head = text.substr(0, appended_tag);
  std::string appended;
  if (appended_tag != std::string::npos) {
    const std::size_t tag_end = text.find('>', appended_tag);
    if (attributes_of(text.substr(appended_tag, tag_end - appended_tag))["encoding"] != "raw")
      throw std::runtime_error("AppendedData is not encoding=\"raw\"");
    const std::size_t underscore = text.find_first_not_of(" \t\r\n", tag_end + 1);
    if (underscore == std::string::npos || text[underscore] != '_')
      throw std::runtime_error("AppendedData does not start with '_'");
    const std::string tail = "\n</AppendedData>\n</VTKFile>\n";
    if (text.size() < underscore + 1 + tail.size() || text.compare(text.size() - tail.size(), tail.size(), tail) != 0)
      throw std::runtime_error("file does not end with </AppendedData></VTKFile>");
    appended = text.substr(underscore + 1, text.size() - tail.size() - underscore - 1);
  } else if (text.find("</VTKFile>") == std::string::npos) {
    throw std::runtime_error("no </VTKFile>");
  }

  VtuFile file;
  std::smatch m;
  if (!std::regex_search(head, m, std::regex(R"(<VTKFile([^>]*)>)"))) throw std::runtime_error("no <VTKFile>");
  file.attributes = attributes_of(m[1]);
  if (std::regex_search(head, m, std::regex(R"(<Piece([^>]*)>)"))) file.piece = attributes_of(m[1]);
  const std::size_t points_begin = head.find("<Points>"), points_end = head.find("</Points>");

  static const std::regex data_array(R"(<DataArray([^>]*?)(/?)>)");
  for (auto it = std::sregex_iterator(head.begin(), head.end(), data_array); it != std::sregex_iterator(); ++it) {
    auto a = attributes_of((*it)[1]);
    const std::size_t at = it->position();
    VtuArray array;
    array.name = a.count("Name") ? a["Name"] : at > points_begin && at < points_end ? "Points" : "";
    array.type = a["type"];
    array.format = a["format"];
    array.n_components = a.count("NumberOfComponents") ? std::stoi(a["NumberOfComponents"]) : 1;
    if (array.format == "ascii") {
      const std::size_t begin = at + it->length(), end = head.find("</DataArray>", begin);
      if ((*it)[2] == "/" || end == std::string::npos) throw std::runtime_error(array.name + ": ascii array not closed");
      array.values = parse_ascii(head.substr(begin, end - begin));
    } else if (array.format == "appended") {
      if (appended_tag == std::string::npos) throw std::runtime_error(array.name + ": appended but no AppendedData");
      if (file.attributes["header_type"] != "UInt64" || file.attributes["compressor"] != "vtkZLibDataCompressor")
        throw std::runtime_error("appended data other than UInt64 headers with vtkZLibDataCompressor");
      array.values = decode(array.type, inflate_array(appended, std::stoull(a.at("offset"))));
    } else {
      throw std::runtime_error(array.name + ": unsupported format '" + array.format + "'");
    }
    file.arrays.push_back(std::move(array));
  }
  return file;
}

}  // namespace stiction::test
