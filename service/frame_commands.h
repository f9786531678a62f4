#pragma once
// How rank 0 tells the other ranks of a service what to do next: one broadcast of a fixed header,
// then the payload. Waiting ranks poll (MPI_Test and a short sleep) instead of blocking in
// MPI_Bcast, whose busy wait would take a core from rank 0 on a shared node while it is idle.
#include <mpi.h>

#include <atomic>
#include <string>

namespace sortlast {

enum class Command : int { kShutdown = 0, kFrame = 1, kLoad = 2 };

struct CommandMessage {
  Command command = Command::kShutdown;
  std::string payload;
  bool gave_up = false;  // receiveCommand: stopped by a signal, rank 0 silent (the broadcast is still open)
};

// Rank 0.
void sendCommand(const CommandMessage& m, MPI_Comm comm);
// The other ranks: waits for rank 0's next command. `stop` is this rank's own signal flag: if it
// is set and rank 0 says nothing for `grace_s`, the rank gives up (returns kShutdown) rather than
// hang; the caller must then abort (MPI_Abort), as the broadcast is still pending.
CommandMessage receiveCommand(MPI_Comm comm, const std::atomic<bool>& stop, double grace_s);

}  // namespace sortlast
