#include "common/listen_address.h"

#include <cstdlib>

#include "common/error.h"

namespace sortlast {

bool isDefaultLoopback(const std::string& address) {
  return address == "127.0.0.1" || address == "::1" || address == "localhost";
}

std::pair<std::string, int> parseListen(const std::string& listen) {
  std::string host, port;
  if (!listen.empty() && listen[0] == '[') {
    auto close = listen.find(']');
    if (close == std::string::npos || close + 1 >= listen.size() || listen[close + 1] != ':')
      throw InputError("--listen " + listen + ": expected [ADDRESS]:PORT");
    host = listen.substr(1, close - 1);
    port = listen.substr(close + 2);
  } else {
    auto colon = listen.rfind(':');
    if (colon == std::string::npos || colon == 0)
      throw InputError("--listen " + listen + ": expected ADDRESS:PORT, e.g. 127.0.0.1:8080");
    host = listen.substr(0, colon);
    port = listen.substr(colon + 1);
  }
  char* end = nullptr;
  long p = std::strtol(port.c_str(), &end, 10);
  if (port.empty() || *end != '\0' || p < 0 || p > 65535)
    throw InputError("--listen " + listen + ": the port must be a number in [0, 65535] (0: any free port)");
  return {host, int(p)};
}

}  // namespace sortlast
