#pragma once
// MPI_Alltoallv over vectors: what each process sends to each (out[r] to process r),
// received by source (in[r] from process r). Collective over comm.
#include <mpi.h>

#include <vector>

namespace stiction {

template <class T>
std::vector<std::vector<T>> all_to_all(MPI_Comm comm, const std::vector<std::vector<T>>& out, MPI_Datatype type) {
  const int size = static_cast<int>(out.size());
  std::vector<int> send_counts(size), recv_counts(size), send_displs(size + 1, 0), recv_displs(size + 1, 0);
  std::vector<T> send;
  for (int r = 0; r < size; ++r) {
    send_counts[r] = static_cast<int>(out[r].size());
    send_displs[r + 1] = send_displs[r] + send_counts[r];
    send.insert(send.end(), out[r].begin(), out[r].end());
  }
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm);
  for (int r = 0; r < size; ++r) recv_displs[r + 1] = recv_displs[r] + recv_counts[r];
  std::vector<T> recv(static_cast<size_t>(recv_displs[size]));
  MPI_Alltoallv(send.data(), send_counts.data(), send_displs.data(), type, recv.data(), recv_counts.data(),
                recv_displs.data(), type, comm);
  std::vector<std::vector<T>> in(size);
  for (int r = 0; r < size; ++r) in[r].assign(recv.begin() + recv_displs[r], recv.begin() + recv_displs[r + 1]);
  return in;
}

template <class T>
std::vector<T> concatenated(const std::vector<std::vector<T>>& parts) {
  std::vector<T> all;
  for (const auto& p : parts) all.insert(all.end(), p.begin(), p.end());
  return all;
}

}  // namespace stiction
