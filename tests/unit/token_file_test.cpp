// `sortlast serve --token-file` (service/token_file.h): the token as written, one trailing line
// break dropped, and each bad file refused by name.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "service/token_file.h"
#include "tests/unit/input_error_of.h"

namespace sortlast {
namespace {

namespace fs = std::filesystem;

class TokenFile : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    dir_ = fs::temp_directory_path() / ("sortlast_token_test_" + std::to_string(::getpid()) + "_" +
                                        std::to_string(counter++));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string file(const std::string& text, mode_t mode = 0600) {
    const fs::path p = dir_ / "token";
    std::ofstream(p, std::ios::binary | std::ios::trunc) << text;
    ::chmod(p.c_str(), mode);
    return p.string();
  }
  fs::path dir_;
};

TEST_F(TokenFile, ReadsTheTokenLessOneLineBreak) {
  EXPECT_EQ(readTokenFile(file("abc123")), "abc123");
  EXPECT_EQ(readTokenFile(file("abc123\n")), "abc123");
  EXPECT_EQ(readTokenFile(file("abc123\r\n")), "abc123");
  EXPECT_EQ(readTokenFile(file("abc123\n", 0400)), "abc123");
  EXPECT_EQ(readTokenFile(file(std::string(4096, 'x'))), std::string(4096, 'x'));
}

TEST_F(TokenFile, RefusesFilesOthersMayRead) {
  // Root reads any file, but the mode is checked all the same.
  for (mode_t mode : {0640, 0604, 0644}) {
    const std::string path = file("abc\n", mode);
    const std::string e = inputErrorOf([&] { readTokenFile(path); });
    EXPECT_NE(e.find("--token-file " + path + ": readable by its group or by others"), std::string::npos) << e;
    EXPECT_NE(e.find("chmod 600"), std::string::npos) << e;
  }
}

TEST_F(TokenFile, RefusesBadContents) {
  auto refusal = [&](const std::string& text) {
    const std::string path = file(text);
    return inputErrorOf([&] { readTokenFile(path); });
  };
  EXPECT_NE(refusal("").find("empty"), std::string::npos);
  EXPECT_NE(refusal("\n").find("empty"), std::string::npos);
  EXPECT_NE(refusal("abc\n\n").find("line break"), std::string::npos);
  EXPECT_NE(refusal("two words\n").find("a space"), std::string::npos);
  EXPECT_NE(refusal("a\tb").find("control character"), std::string::npos);
  EXPECT_NE(refusal(std::string(5000, 'x')).find("longer than 4096 bytes"), std::string::npos);
}

TEST_F(TokenFile, RefusesMissingFilesAndFolders) {
  const std::string missing = (dir_ / "nope").string();
  EXPECT_NE(inputErrorOf([&] { readTokenFile(missing); }).find(missing + ": No such file"), std::string::npos);
  EXPECT_NE(inputErrorOf([&] { readTokenFile(dir_.string()); }).find("not a regular file"), std::string::npos);
}

}  // namespace
}  // namespace sortlast
