#pragma once
// The messages of the swap strategies, behind a thin interface: the strategies never include MPI
// (mpi_transport.h carries them between ranks; the unit tests carry them between threads).
#include <cstdint>
#include <vector>

namespace sortlast {

// A message received straight into its place: `rows` rows of `row_bytes` bytes each, the first
// at `dst` and each `stride` bytes after the one before (a rectangle of a frame). The message is
// those bytes and nothing else: the receiver knows the rectangle beforehand.
struct PlacedReceive {
  int from = 0, tag = 0;
  uint8_t* dst = nullptr;
  size_t stride = 0;
  int row_bytes = 0, rows = 0;
};

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
  // Receives every one of `parts`, in whatever order they arrive, each straight into its rows (MPI:
  // one strided datatype a part, so this rank copies nothing beyond MPI's own unpacking). Throws
  // std::runtime_error naming the sender if a message is not exactly rows * row_bytes bytes, after
  // every receive has ended (none is left writing into `dst`).
  virtual void receivePlaced(const std::vector<PlacedReceive>& parts) = 0;
  // Waits until every send started so far has completed.
  virtual void finishSends() = 0;
  // Every rank's `mine` (the same length on every rank), concatenated in rank order.
  virtual std::vector<int> allgather(const std::vector<int>& mine) = 0;
};

}  // namespace sortlast
