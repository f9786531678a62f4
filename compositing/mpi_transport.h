#pragma once
// Transport over an MPI communicator: non-blocking sends, probed receives, strided receives into
// place (MPI_Type_vector), MPI_Allgather.
#include <mpi.h>

#include <memory>

#include "compositing/transport.h"

namespace sortlast {

class MpiTransport final : public Transport {
 public:
  explicit MpiTransport(MPI_Comm comm);
  ~MpiTransport() override;  // completes outstanding sends
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void send(int to, int tag, std::vector<uint8_t> bytes) override;
  std::vector<uint8_t> receive(int from, int tag) override;
  void receivePlaced(const std::vector<PlacedReceive>& parts) override;
  void finishSends() override;
  std::vector<int> allgather(const std::vector<int>& mine) override;

 private:
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  std::vector<std::unique_ptr<std::vector<uint8_t>>> buffers_;  // stable while their sends run
  std::vector<MPI_Request> requests_;
};

}  // namespace sortlast
