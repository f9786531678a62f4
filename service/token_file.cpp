#include "service/token_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include "common/error.h"

namespace sortlast {

namespace {

constexpr size_t kMaxTokenBytes = 4096;

}  // namespace

std::string readTokenFile(const std::string& path) {
  const std::string where = "--token-file " + path + ": ";
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw InputError(where + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw InputError(where + "not a regular file");
  // As ssh does with a private key: a secret that others may read is refused, not used. A token
  // the group can read admits the whole group, and a cluster's primary group is often "users".
  if (st.st_mode & (S_IRGRP | S_IROTH)) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%04o", unsigned(st.st_mode & 07777));
    throw InputError(where + "readable by its group or by others (mode " + mode +
                     "): anyone who can read the token can use the service; chmod 600 " + path);
  }
  if (st.st_size > off_t(kMaxTokenBytes + 2))
    throw InputError(where + "longer than " + std::to_string(kMaxTokenBytes) + " bytes: not a token");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(where + "cannot be opened: " + std::strerror(errno));
  std::string token((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(where + "could not be read");
  if (!token.empty() && token.back() == '\n') token.pop_back();
  if (!token.empty() && token.back() == '\r') token.pop_back();
  if (token.empty()) throw InputError(where + "empty: write the token into it");
  if (token.size() > kMaxTokenBytes)
    throw InputError(where + "longer than " + std::to_string(kMaxTokenBytes) + " bytes: not a token");
  for (unsigned char c : token)
    if (c <= ' ' || c == 0x7f)
      throw InputError(where + "the token holds a space, a line break or another control character "
                       "(only one line break may end the file); a client could not send it in a header");
  return token;
}

}  // namespace sortlast
