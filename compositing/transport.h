#pragma once
// The messages of the swap strategies, behind a thin interface: the strategies never include MPI
// (mpi_transport.h carries them between ranks; the unit tests carry them between threads).
#include <cstdint>
#include <vector>

namespace sortlast {

class Transport {
 public:
  virtual ~Transport() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // Starts sending; the transport owns `bytes` until finishSends().
  virtual void send(int to, int tag, std::vector<uint8_t> bytes) = 0;
  // Waits for the message from `from` with `tag` (messages of one tag between two ranks arrive in
  // the order they were sent).
  virtual std::vector<uint8_t> receive(int from, int tag) = 0;
  // Waits until every send started so far has completed.
  virtual void finishSends() = 0;
  // Every rank's `mine` (the same length on every rank), concatenated in rank order.
  virtual std::vector<int> allgather(const std::vector<int>& mine) = 0;
};

}  // namespace sortlast
