#pragma once
// The address a service listens on (`serve --listen`, an in-situ action's `serve:`): parsed, and
// whether it needs a token. No sockets, no MPI, so the in-situ actions parser checks it too.
#include <string>
#include <utility>

namespace sortlast {

// Whether serving on this address needs no token: only the loopback names 127.0.0.1, ::1 and
// localhost (any other address, other 127.x included, may be reachable by others).
bool isDefaultLoopback(const std::string& address);

// "host:port" (or "[v6]:port"); throws InputError.
std::pair<std::string, int> parseListen(const std::string& listen);

}  // namespace sortlast
