#pragma once
// `sortlast serve --token-file PATH`: the token read from a file, so that it never appears on a
// command line (`--token` is in every rank's /proc/PID/cmdline, which `ps` shows to every user of
// the node).
#include <string>

namespace sortlast {

// The file's contents less one trailing line break ("\n" or "\r\n", as `echo` and editors leave
// it). Throws InputError naming the path and the problem when the file cannot be read, is not a
// regular file, is readable by its group or by others (a token they can read keeps none of them
// out, and on a cluster the group is often every user: chmod 600), is empty, holds a line break,
// a space or another control character within the token (it could not be sent in a header), or
// is longer than 4096 bytes.
std::string readTokenFile(const std::string& path);

}  // namespace sortlast
