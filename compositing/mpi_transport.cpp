#include "compositing/mpi_transport.h"

#include <climits>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "compositing/pixel_cost.h"

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

void MpiTransport::receivePlaced(const std::vector<PlacedReceive>& parts) {
  const size_t n = parts.size();
  for (const PlacedReceive& p : parts)
    if (p.rows < 1 || p.row_bytes < 1 || p.stride < size_t(p.row_bytes) || p.stride > size_t(INT_MAX))
      throw std::invalid_argument("placed receive from rank " + std::to_string(p.from) +
                                  ": bad shape");
  // Every receive posted before waiting on any, so the parts travel together and none waits for
  // this rank to ask for it (a large message goes by rendezvous).
  std::vector<MPI_Datatype> types(n);
  std::vector<MPI_Request> requests(n);
  for (size_t i = 0; i < n; ++i) {
    const PlacedReceive& p = parts[i];
    MPI_Type_vector(p.rows, p.row_bytes, int(p.stride), MPI_BYTE, &types[i]);
    MPI_Type_commit(&types[i]);
    MPI_Irecv(p.dst, 1, types[i], p.from, p.tag, comm_, &requests[i]);
  }
  std::string error;
  for (size_t done = 0; done < n; ++done) {
    int i = MPI_UNDEFINED;
    MPI_Status st;
    MPI_Waitany(int(n), requests.data(), &i, &st);
    if (i == MPI_UNDEFINED) break;
    int count = 0;
    MPI_Get_count(&st, types[size_t(i)], &count);
    const PlacedReceive& p = parts[size_t(i)];
    if (count != 1 && error.empty())
      error = "placed receive: the message from rank " + std::to_string(p.from) + " is not the " +
              std::to_string(1LL * p.rows * p.row_bytes) + " bytes of its rectangle";
    // MPI unpacks a strided receive into place: a copy of the message's bytes on this rank, as it
    // arrives (so while the other parts are still on the wire).
    chargePixels(PixelWork::Place, 1LL * p.rows * p.row_bytes / 4);
  }
  for (MPI_Datatype& t : types) MPI_Type_free(&t);
  if (!error.empty()) throw std::runtime_error(error);
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
