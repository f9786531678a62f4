#include "service/frame_commands.h"

#include <chrono>
#include <thread>

namespace sortlast {

void sendCommand(const CommandMessage& m, MPI_Comm comm) {
  int header[2] = {int(m.command), int(m.payload.size())};
  MPI_Request r;
  MPI_Ibcast(header, 2, MPI_INT, 0, comm, &r);
  MPI_Wait(&r, MPI_STATUS_IGNORE);
  if (header[1] > 0) MPI_Bcast(const_cast<char*>(m.payload.data()), header[1], MPI_CHAR, 0, comm);
}

CommandMessage receiveCommand(MPI_Comm comm, const std::atomic<bool>& stop, double grace_s) {
  int header[2] = {0, 0};
  MPI_Request r;
  MPI_Ibcast(header, 2, MPI_INT, 0, comm, &r);
  auto stop_seen = std::chrono::steady_clock::time_point::max();
  for (int done = 0;;) {
    MPI_Test(&r, &done, MPI_STATUS_IGNORE);
    if (done) break;
    if (stop.load()) {
      auto now = std::chrono::steady_clock::now();
      if (stop_seen == std::chrono::steady_clock::time_point::max()) stop_seen = now;
      if (std::chrono::duration<double>(now - stop_seen).count() > grace_s) {
        CommandMessage m;
        m.gave_up = true;
        return m;
      }
    }
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  CommandMessage m;
  m.command = Command(header[0]);
  m.payload.resize(size_t(header[1]));
  if (header[1] > 0) MPI_Bcast(m.payload.data(), header[1], MPI_CHAR, 0, comm);
  return m;
}

}  // namespace sortlast
