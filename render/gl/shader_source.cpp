#include "render/gl/shader_source.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace sortlast {

ShaderSource& ShaderSource::define(const std::string& name, const std::string& value) {
  auto [at, added] = defines_.emplace(name, value);
  if (!added && at->second != value)
    throw std::logic_error("shader source: " + name + " defined as " + at->second + " and " +
                           value);
  return *this;
}

ShaderSource& ShaderSource::add(const GlslFile& chunk) {
  for (const GlslFile& c : chunks_)
    if (c.path == chunk.path)
      throw std::logic_error("shader source: " + std::string(chunk.path) + " added twice");
  chunks_.push_back(chunk);
  return *this;
}

std::string ShaderSource::text() const {
  std::string s = "#version 450 core\n";
  for (const auto& [name, value] : defines_) s += "#define " + name + " " + value + "\n";
  for (size_t k = 0; k < chunks_.size(); ++k) {
    if (std::count(chunks_[k].text.begin(), chunks_[k].text.end(), '\n') >= kChunkLines - 1)
      throw std::logic_error("shader source: " + std::string(chunks_[k].path) + " is too long");
    s += "#line " + std::to_string((k + 1) * kChunkLines + 1) + " " + std::to_string(k + 1) + "\n";
    s += chunks_[k].text;
    if (!chunks_[k].text.empty() && chunks_[k].text.back() != '\n') s += '\n';
  }
  return s;
}

namespace {
// The decimal number at s[i...], advancing i; false (i unchanged) if there is none.
bool number(std::string_view s, size_t& i, size_t& value) {
  size_t j = i;
  value = 0;
  while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j])) && j - i < 9)
    value = value * 10 + size_t(s[j++] - '0');
  if (j == i) return false;
  i = j;
  return true;
}
}  // namespace

std::string ShaderSource::locate(std::string_view log) const {
  std::string out;
  size_t start = 0;
  while (start < log.size()) {
    size_t end = log.find('\n', start);
    end = end == std::string_view::npos ? log.size() : end + 1;
    const std::string_view line = log.substr(start, end - start);
    start = end;
    size_t i = 0, k = 0, n = 0;
    // Mesa: "K:LINE(COL): error: ...". NVIDIA: "K(LINE) : error ...".
    const bool mesa = number(line, i, k) && i < line.size() && line[i] == ':' &&
                      number(line, ++i, n) && i < line.size() && line[i] == '(';
    i = 0;
    const bool nvidia = !mesa && number(line, i, k) && i < line.size() && line[i] == '(' &&
                        number(line, ++i, n) && i < line.size() && line[i] == ')';
    const size_t chunk = n / kChunkLines;
    if ((!mesa && !nvidia) || chunk > chunks_.size()) {
      out += line;
      continue;
    }
    const std::string file =
        chunk == 0 ? std::string("(version and defines)") : std::string(chunks_[chunk - 1].path);
    // The rest after LINE: "(COL): error ..." or ") : error ...".
    const size_t rest = mesa ? line.find('(') : line.find(')') + 1;
    out += file + ":" + std::to_string(n % kChunkLines) + std::string(line.substr(rest));
  }
  return out;
}

std::string ShaderSource::paths() const {
  std::string s;
  for (const GlslFile& c : chunks_) s += (s.empty() ? "" : ", ") + std::string(c.path);
  return s;
}

}  // namespace sortlast
