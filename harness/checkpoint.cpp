#include "checkpoint.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <mpi.h>

#include "common/error.hpp"

namespace stiction::harness {

namespace {

// Format 2 appends the linear-solve tally to format 1, format 3 the cut-back's state to
// format 2; the older two are still read.
constexpr char kMagic[8] = {'S', 'T', 'I', 'C', 'K', 'P', 'T', '3'};
constexpr char kMagicFormat1[8] = {'S', 'T', 'I', 'C', 'K', 'P', 'T', '1'};
constexpr char kMagicFormat2[8] = {'S', 'T', 'I', 'C', 'K', 'P', 'T', '2'};

class Writer {
public:
  explicit Writer(std::ostream& out) : out_(out) {}
  void u64(std::uint64_t v) { out_.write(reinterpret_cast<const char*>(&v), sizeof v); }
  void f64(double v) { out_.write(reinterpret_cast<const char*>(&v), sizeof v); }
  void text(const std::string& s) {
    u64(s.size());
    out_.write(s.data(), static_cast<std::streamsize>(s.size()));
  }
  void doubles(const std::vector<double>& v) {
    u64(v.size());
    out_.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(double)));
  }

private:
  std::ostream& out_;
};

class Reader {
public:
  Reader(std::istream& in, std::string path) : in_(in), path_(std::move(path)) {}
  std::uint64_t u64() {
    std::uint64_t v = 0;
    read(&v, sizeof v);
    return v;
  }
  double f64() {
    double v = 0;
    read(&v, sizeof v);
    return v;
  }
  std::string text() {
    std::string s(checked_size(u64(), 1), '\0');
    read(s.data(), s.size());
    return s;
  }
  std::vector<double> doubles() {
    std::vector<double> v(checked_size(u64(), sizeof(double)));
    read(v.data(), v.size() * sizeof(double));
    return v;
  }

private:
  // A size read from the file that could not fit in it marks a damaged file.
  size_t checked_size(std::uint64_t n, size_t unit) {
    if (n > (std::uint64_t{1} << 40) / unit) fail();
    return static_cast<size_t>(n);
  }
  void read(void* p, size_t bytes) {
    in_.read(static_cast<char*>(p), static_cast<std::streamsize>(bytes));
    if (!in_) fail();
  }
  [[noreturn]] void fail() const { throw Error(fmt::format("checkpoint '{}' is truncated or damaged", path_)); }
  std::istream& in_;
  std::string path_;
};

void write_to(std::ostream& out, const Checkpoint& c) {
  out.write(kMagic, sizeof kMagic);
  Writer w(out);
  w.text(c.scene);
  w.u64(static_cast<std::uint64_t>(c.level));
  w.u64(static_cast<std::uint64_t>(c.state.step));
  w.f64(c.state.time);
  w.doubles(c.state.u);
  w.doubles(c.state.lambda);
  w.u64(c.state.constraints.size());
  for (const auto& s : c.state.constraints) w.doubles(s);
  w.u64(static_cast<std::uint64_t>(c.tally.solves));
  w.u64(static_cast<std::uint64_t>(c.tally.failures));
  w.u64(static_cast<std::uint64_t>(c.cut_back.cut));
  w.u64(static_cast<std::uint64_t>(c.cut_back.converged_at_cut));
  w.u64(c.cut_back.probing ? 1 : 0);
  w.u64(c.cut_back.wait.size());
  for (int n : c.cut_back.wait) w.u64(static_cast<std::uint64_t>(n));
}

// `path` names the source in messages.
Checkpoint read_from(std::istream& in, const std::string& path) {
  char magic[sizeof kMagic];
  in.read(magic, sizeof magic);
  const bool format1 = in && std::equal(magic, magic + sizeof magic, kMagicFormat1);
  const bool format2 = in && std::equal(magic, magic + sizeof magic, kMagicFormat2);
  if (!in || (!format1 && !format2 && !std::equal(magic, magic + sizeof magic, kMagic)))
    throw Error(fmt::format("'{}' is not a stiction checkpoint", path));
  Reader r(in, path);
  Checkpoint c;
  c.scene = r.text();
  c.level = static_cast<int>(r.u64());
  c.state.step = static_cast<int>(r.u64());
  c.state.time = r.f64();
  c.state.u = r.doubles();
  c.state.lambda = r.doubles();
  const std::uint64_t n = r.u64();
  if (n > 1000) throw Error(fmt::format("checkpoint '{}' is truncated or damaged", path));
  for (std::uint64_t k = 0; k < n; ++k) c.state.constraints.push_back(r.doubles());
  if (!format1) {
    c.tally.solves = static_cast<int>(r.u64());
    c.tally.failures = static_cast<int>(r.u64());
  }
  if (!format1 && !format2) {
    c.cut_back.cut = static_cast<int>(r.u64());
    c.cut_back.converged_at_cut = static_cast<int>(r.u64());
    c.cut_back.probing = r.u64() != 0;
    const std::uint64_t sizes = r.u64();
    if (sizes > 1000) throw Error(fmt::format("checkpoint '{}' is truncated or damaged", path));
    for (std::uint64_t k = 0; k < sizes; ++k) c.cut_back.wait.push_back(static_cast<int>(r.u64()));
  }
  return c;
}

void broadcast(MPI_Comm comm, std::string& bytes) {
  unsigned long long size = bytes.size();
  MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG_LONG, 0, comm);
  bytes.resize(size);
  MPI_Bcast(bytes.data(), static_cast<int>(size), MPI_CHAR, 0, comm);
}

}  // namespace

void write_checkpoint(const std::string& path, const Checkpoint& c) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw Error(fmt::format("cannot write checkpoint '{}'", path));
    write_to(out, c);
    if (!out) throw Error(fmt::format("cannot write checkpoint '{}'", path));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw Error(fmt::format("cannot write checkpoint '{}'", path));
}

Checkpoint read_checkpoint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(fmt::format("no checkpoint '{}' to restart from", path));
  return read_from(in, path);
}

Checkpoint read_checkpoint(MPI_Comm comm, const std::string& path) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  // Rank 0 sends the checkpoint without u, or the message of its failure, as bytes.
  std::string bytes, failure;
  Checkpoint c;
  if (rank == 0) {
    try {
      c = read_checkpoint(path);
      std::vector<double> u = std::move(c.state.u);  // kept out of the bytes, not copied
      c.state.u.clear();
      std::ostringstream out;
      write_to(out, c);
      bytes = out.str();
      c.state.u = std::move(u);
    } catch (const Error& e) {
      failure = e.what();
    }
  }
  broadcast(comm, failure);
  if (!failure.empty()) throw Error(failure);
  broadcast(comm, bytes);
  if (rank == 0) return c;
  std::istringstream in(bytes);
  return read_from(in, path);
}

}  // namespace stiction::harness
