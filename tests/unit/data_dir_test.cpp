// Names resolved inside a directory (service/data_dir.h): nothing outside it is reachable.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "service/data_dir.h"
#include "tests/unit/input_error_of.h"

namespace sortlast {
namespace {

namespace fs = std::filesystem;

// dir_/data holds scenes; dir_/outside is a sibling the data directory must not reach.
class DataDir : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    dir_ = fs::temp_directory_path() / ("sortlast_data_dir_test_" + std::to_string(::getpid()) +
                                        "_" + std::to_string(counter++));
    data_ = dir_ / "data";
    fs::create_directories(data_ / "sub");
    fs::create_directories(dir_ / "outside");
    touch(data_ / "a.yaml");
    touch(data_ / "sub" / "b.yml");
    touch(data_ / "notes.txt");
    touch(dir_ / "outside" / "secret.yaml");
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  static void touch(const fs::path& p) { std::ofstream(p) << "volume: {}\n"; }
  fs::path dir_, data_;
};

TEST_F(DataDir, ResolvesFilesInside) {
  EXPECT_EQ(resolveUnder(data_, "a.yaml"), fs::canonical(data_ / "a.yaml"));
  EXPECT_EQ(resolveUnder(data_, "sub/b.yml"), fs::canonical(data_ / "sub" / "b.yml"));
  EXPECT_EQ(resolveUnder(data_, "./sub//b.yml"), fs::canonical(data_ / "sub" / "b.yml"));
}

TEST_F(DataDir, RefusesEmptyAbsoluteAndDotDot) {
  EXPECT_NE(inputErrorOf([&] { resolveUnder(data_, ""); }).find("empty"), std::string::npos);
  std::string abs = (data_ / "a.yaml").string();
  EXPECT_NE(inputErrorOf([&] { resolveUnder(data_, abs); }).find("absolute"), std::string::npos);
  EXPECT_NE(inputErrorOf([&] { resolveUnder(data_, "../outside/secret.yaml"); }).find(".."),
            std::string::npos);
  // ".." is refused even where it would land back inside.
  EXPECT_NE(inputErrorOf([&] { resolveUnder(data_, "sub/../a.yaml"); }).find(".."),
            std::string::npos);
  EXPECT_NE(inputErrorOf([&] { resolveUnder(data_, "missing.yaml"); }).find("no such file"),
            std::string::npos);
}

TEST_F(DataDir, SymlinkOutRefusedSymlinkInsideAllowed) {
  fs::create_symlink(dir_ / "outside" / "secret.yaml", data_ / "leak.yaml");
  fs::create_directory_symlink(dir_ / "outside", data_ / "leakdir");
  fs::create_symlink(data_ / "a.yaml", data_ / "alias.yaml");
  EXPECT_NE(inputErrorOf([&] { resolveUnder(data_, "leak.yaml"); }).find("outside"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([&] { resolveUnder(data_, "leakdir/secret.yaml"); }).find("outside"),
            std::string::npos);
  // A missing file behind a link out gets the same answer: existence outside is not revealed.
  EXPECT_NE(inputErrorOf([&] { resolveUnder(data_, "leakdir/none.yaml"); }).find("outside"),
            std::string::npos);
  EXPECT_EQ(resolveUnder(data_, "alias.yaml"), fs::canonical(data_ / "a.yaml"));
}

TEST_F(DataDir, DataDirItselfMayBeASymlink) {
  fs::create_directory_symlink(data_, dir_ / "link_to_data");
  EXPECT_EQ(resolveUnder(dir_ / "link_to_data", "a.yaml"), fs::canonical(data_ / "a.yaml"));
}

TEST_F(DataDir, ListsSceneFilesSortedAndOnlyThoseInside) {
  fs::create_symlink(dir_ / "outside" / "secret.yaml", data_ / "leak.yaml");
  fs::create_symlink(data_ / "a.yaml", data_ / "sub" / "alias.yaml");
  EXPECT_EQ(listSceneFiles(data_),
            (std::vector<std::string>{"a.yaml", "sub/alias.yaml", "sub/b.yml"}));
  EXPECT_FALSE(inputErrorOf([&] { listSceneFiles(dir_ / "nope"); }).empty());
}

// A file to write (a recording): it need not exist, but its folder must, inside the directory.
TEST_F(DataDir, NewFilesResolveInsideOnly) {
  EXPECT_EQ(resolveNewUnder(data_, "new.mp4"), fs::canonical(data_) / "new.mp4");
  EXPECT_EQ(resolveNewUnder(data_, "sub/new.mp4"), fs::canonical(data_) / "sub" / "new.mp4");
  EXPECT_EQ(resolveNewUnder(data_, "a.yaml"), fs::canonical(data_ / "a.yaml"));  // replaced
  fs::create_directory_symlink(dir_ / "outside", data_ / "leakdir");
  fs::create_symlink(dir_ / "outside" / "secret.yaml", data_ / "leak.mp4");
  EXPECT_NE(inputErrorOf([&] { resolveNewUnder(data_, "leakdir/x.mp4"); }).find("outside"), std::string::npos);
  EXPECT_NE(inputErrorOf([&] { resolveNewUnder(data_, "leak.mp4"); }).find("outside"), std::string::npos);
  EXPECT_NE(inputErrorOf([&] { resolveNewUnder(data_, "../x.mp4"); }).find(".."), std::string::npos);
  EXPECT_NE(inputErrorOf([&] { resolveNewUnder(data_, "/tmp/x.mp4"); }).find("absolute"), std::string::npos);
  EXPECT_NE(inputErrorOf([&] { resolveNewUnder(data_, "nofolder/x.mp4"); }).find("folder does not exist"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([&] { resolveNewUnder(data_, "sub"); }).find("not a file"), std::string::npos);
  EXPECT_NE(inputErrorOf([&] { resolveNewUnder(data_, "."); }).find("directory itself"), std::string::npos);
}

}  // namespace
}  // namespace sortlast
