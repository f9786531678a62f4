#include "app/command_line_hint.h"

#include <algorithm>
#include <cctype>
#include <limits>

namespace sortlast {

namespace {

// Optimal string alignment distance: Levenshtein with the swap of two neighbours as one edit
// (the commonest typo, "redner").
size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

std::string didYouMean(const std::string& near) {
  return near.empty() ? "" : "; did you mean '" + near + "'?";
}

// The option names of `app` as typed on a command line: --long and -s.
std::vector<std::string> optionNames(CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options()) {
    for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
    for (const std::string& s : o->get_snames()) names.push_back("-" + s);
  }
  return names;
}

bool knownOption(const std::string& word, const std::vector<std::string>& names) {
  const std::string name = word.substr(0, word.find('='));  // --set=x
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

std::string nearestName(const std::string& typed, const std::vector<std::string>& known) {
  const size_t limit = std::min<size_t>(2, std::max<size_t>(1, typed.size() / 3));
  std::string best;
  size_t best_d = std::numeric_limits<size_t>::max();
  for (const std::string& k : known) {
    const size_t d = editDistance(typed, k);
    if (d < best_d) best_d = d, best = k;
  }
  return best_d <= limit ? best : "";
}

std::string commandLineHint(CLI::App& app, int argc, const char* const* argv) {
  std::vector<std::string> subcommands;
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    subcommands.push_back(sub->get_name());
  // The first word that is not an option names the subcommand.
  CLI::App* chosen = nullptr;
  int i = 1;
  for (; i < argc && argv[i][0] == '-'; ++i) {
  }
  if (i < argc) {
    const std::string word = argv[i];
    if (std::find(subcommands.begin(), subcommands.end(), word) == subcommands.end())
      return "unknown subcommand '" + word + "'" + didYouMean(nearestName(word, subcommands)) +
             " (sortlast --help lists them)";
    chosen = app.get_subcommand(word);
  }
  // An option neither the program nor its subcommand knows.
  std::vector<std::string> names = optionNames(app);
  if (chosen) {
    std::vector<std::string> own = optionNames(*chosen);
    names.insert(names.end(), own.begin(), own.end());
  }
  for (int j = 1; j < argc; ++j) {
    const std::string word = argv[j];
    if (word.size() < 2 || word[0] != '-' || word == "--") continue;
    if (std::isdigit(static_cast<unsigned char>(word[1])) || word[1] == '.') continue;  // a negative number
    if (!knownOption(word, names)) {
      const std::string name = word.substr(0, word.find('='));
      return "unknown option '" + name + "'" + (chosen ? " for '" + chosen->get_name() + "'" : "") +
             didYouMean(nearestName(name, names)) + " (sortlast " +
             (chosen ? chosen->get_name() + " " : "") + "--help lists them)";
    }
  }
  return "";
}

}  // namespace sortlast
