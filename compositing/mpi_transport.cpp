#include "compositing/mpi_transport.h"

#include <cstdint>
#include <stdexcept>
#include <string>

namespace sortlast {

MpiTransport::MpiTransport(MPI_Comm comm) : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

MpiTransport::~MpiTransport() { finishSends(); }

void MpiTransport::send(int to, int tag, std::vector<uint8_t> bytes) {
  if (bytes.size() > size_t(INT32_MAX))
    throw std::runtime_error("message of " + std::to_string(bytes.size()) + " bytes is too large");
  buffers_.push_back(std::make_unique<std::vector<uint8_t>>(std::move(bytes)));
  requests_.emplace_back();
  MPI_Isend(buffers_.back()->data(), int(buffers_.back()->size()), MPI_BYTE, to, tag, comm_,
            &requests_.back());
}

std::vector<uint8_t> MpiTransport::receive(int from, int tag) {
  MPI_Status st;
  MPI_Probe(from, tag, comm_, &st);
  int count = 0;
  MPI_Get_count(&st, MPI_BYTE, &count);
  std::vector<uint8_t> bytes(static_cast<size_t>(count));
  MPI_Recv(bytes.data(), count, MPI_BYTE, from, tag, comm_, MPI_STATUS_IGNORE);
  return bytes;
}

void MpiTransport::finishSends() {
  if (!requests_.empty()) MPI_Waitall(int(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
  requests_.clear();
  buffers_.clear();
}

std::vector<int> MpiTransport::allgather(const std::vector<int>& mine) {
  std::vector<int> all(mine.size() * size_t(size_));
  MPI_Allgather(mine.data(), int(mine.size()), MPI_INT, all.data(), int(mine.size()), MPI_INT,
                comm_);
  return all;
}

}  // namespace sortlast
