#pragma once
// What both example simulations share around their physics: reading `--name value` options, the
// in-situ session from an actions file or from built-in actions, the per-step log line, and
// writing a gathered dump. Header-only, so each example stays a self-contained program.
#include <mpi.h>
#include <sortlast/insitu.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace example {

// Walks argv once. Every rank parses the same argv, so every rank fails (or not) alike.
class ArgReader {
 public:
  ArgReader(int argc, char** argv) : args_(argv + 1, argv + argc) {}
  bool done() const { return at_ >= args_.size(); }
  bool value(const char* name, long long& out) {
    return take(name, [&](const std::string& v) { out = whole(v, std::stoll(v, &used_)); });
  }
  bool value(const char* name, int& out) {
    return take(name, [&](const std::string& v) { out = whole(v, std::stoi(v, &used_)); });
  }
  bool value(const char* name, double& out) {
    return take(name, [&](const std::string& v) { out = whole(v, std::stod(v, &used_)); });
  }
  bool value(const char* name, std::string& out) {
    return take(name, [&](const std::string& v) { out = v; });
  }
  bool flag(const char* name, bool& out) {
    if (args_[at_] != name) return false;
    out = true;
    ++at_;
    return true;
  }
  [[noreturn]] void unknown() const {
    throw std::invalid_argument("unknown option '" + args_[at_] + "' (try --help)");
  }

 private:
  template <class Set>
  bool take(const char* name, Set set) {
    if (args_[at_] != name) return false;
    if (at_ + 1 >= args_.size()) throw std::invalid_argument(std::string(name) + " needs a value");
    const std::string& v = args_[at_ + 1];
    try {
      set(v);
    } catch (const std::logic_error&) {  // stoi and friends: invalid_argument, out_of_range
      throw std::invalid_argument(std::string(name) + ": bad value '" + v + "'");
    }
    at_ += 2;
    return true;
  }
  // "12abc" is not 12: the number must use the whole argument.
  template <class T>
  T whole(const std::string& v, T parsed) const {
    if (used_ != v.size()) throw std::invalid_argument(v);
    return parsed;
  }
  std::vector<std::string> args_;
  size_t at_ = 0;
  size_t used_ = 0;
};

// The session: the user's actions file if one was given, else the example's built-in actions (so
// the example runs with no file at all, and --every / --width can shape its pictures).
inline sortlast::InSitu openInSitu(MPI_Comm comm, const std::string& actions_file,
                                   const std::string& builtin) {
  if (!actions_file.empty()) return sortlast::InSitu(comm, actions_file);
  return sortlast::InSitu::fromText(comm, builtin);
}

// One line per step on rank 0: what the step cost the simulation, what it cost to look at it, and
// the memory sortlast added for it (host buffers plus this rank's brick texture).
inline void printStep(int rank, long long step, double sim_s, const sortlast::ExecuteReport& r) {
  if (rank != 0) return;
  std::printf("step %lld sim_s %.6f vis_s %.6f mem_mib %.3f added_mib %.3f texture_mib %.3f%s%s\n",
              step, sim_s, r.seconds, r.memory_added_mib + r.texture_mib, r.memory_added_mib,
              r.texture_mib, r.error.empty() ? "" : " error ", r.error.c_str());
  std::fflush(stdout);
}

// A string as a double-quoted YAML scalar (an --out folder may hold spaces, quotes, colons).
inline std::string yamlQuoted(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') q += '\\';
    q += c;
  }
  return q + "\"";
}

inline void writeRaw(const std::string& file, const std::vector<float>& values) {
  std::ofstream out(file, std::ios::binary);
  out.write(reinterpret_cast<const char*>(values.data()),
            std::streamsize(values.size() * sizeof(float)));
  if (!out) throw std::runtime_error("cannot write " + file);
}

}  // namespace example
