// The channel's program checks off the cycle: a selected file of the program directory or MDI
// blocks, checked on the loader's thread; one request at a time; names that leave the program
// directory, and files it lacks, are alarms that name them.
#include "channel/loading/program_loader.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>

namespace mcnc::channel {
namespace {

namespace fs = std::filesystem;

class ProgramLoaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("mcnc-loader-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    std::ofstream(dir_ / "O2000.nc") << "O2000 (two blocks)\nG00 X10\nG00 Z5\nM30\n";
    std::ofstream(dir_ / "BAD.nc") << "G00 X10\nT0101\nM30\n";
    config_.channel = 1;
    config_.axes = {interp::AxisConfig{'X'}, interp::AxisConfig{'Z'}};
    config_.program_dir = dir_;
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The loader's answer, waited for (its thread checks the request). The 60 s are a backstop
  // for a loaded host, where the loader's thread may wait seconds for a core, not a measure.
  static LoadedProgram answer(ProgramLoader& loader) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
      if (std::optional<LoadedProgram> r = loader.take()) {
        return std::move(*r);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ADD_FAILURE() << "no answer within 60 s";
    return {};
  }

  fs::path dir_;
  interp::InterpreterConfig config_;
};

TEST_F(ProgramLoaderTest, ASelectedFileIsCheckedAndReadAgainAsItRuns) {
  ProgramLoader loader(config_);
  EXPECT_FALSE(loader.busy());
  ASSERT_TRUE(loader.submit(false, "O2000.nc"));
  EXPECT_TRUE(loader.busy());
  const LoadedProgram r = answer(loader);
  EXPECT_FALSE(loader.busy());
  EXPECT_FALSE(r.mdi);
  EXPECT_FALSE(r.program.alarm.has_value()) << r.program.alarm->text;
  EXPECT_EQ(r.program.name, "O2000.nc");
  EXPECT_EQ(r.program.block_count, 3U);                     // the O line is no block
  EXPECT_EQ(r.program.path, (dir_ / "O2000.nc").string());  // not held whole: read as it runs
  EXPECT_TRUE(r.program.text.empty());
}

TEST_F(ProgramLoaderTest, MdiBlocksAreCheckedAsTyped) {
  ProgramLoader loader(config_);
  ASSERT_TRUE(loader.submit(true, "G00 X3 Z4"));
  const LoadedProgram r = answer(loader);
  EXPECT_TRUE(r.mdi);
  EXPECT_FALSE(r.program.alarm.has_value()) << r.program.alarm->text;
  EXPECT_EQ(r.program.name, interp::kMdiName);
  EXPECT_EQ(r.program.text, "G00 X3 Z4");
  EXPECT_TRUE(r.program.path.empty());

  ASSERT_TRUE(loader.submit(true, "G00 X3 Y4"));  // no Y on this channel
  const LoadedProgram bad = answer(loader);
  ASSERT_TRUE(bad.program.alarm.has_value());
  EXPECT_EQ(bad.program.alarm->program, interp::kMdiName);
  EXPECT_EQ(bad.program.alarm->line, 1);
}

TEST_F(ProgramLoaderTest, OnlyFilesOfTheProgramDirectoryAreRead) {
  std::ofstream(dir_.parent_path() / "outside.nc") << "G00 X1\nM30\n";
  ProgramLoader loader(config_);
  for (const char* name : {"../outside.nc", "/etc/passwd", "..", "NONE.nc"}) {
    ASSERT_TRUE(loader.submit(false, name)) << name;
    const LoadedProgram r = answer(loader);
    ASSERT_TRUE(r.program.alarm.has_value()) << name;
    EXPECT_NE(r.program.alarm->text.find(name), std::string::npos) << r.program.alarm->text;
    EXPECT_TRUE(r.program.path.empty()) << name;
  }
  fs::remove(dir_.parent_path() / "outside.nc");
  ASSERT_TRUE(loader.submit(false, "BAD.nc"));
  const LoadedProgram bad = answer(loader);
  ASSERT_TRUE(bad.program.alarm.has_value());  // a T code, and no PLC
  EXPECT_EQ(bad.program.alarm->line, 2);
}

TEST_F(ProgramLoaderTest, OneRequestAtATimeAndTextsThatDoNotFitAreRefused) {
  ProgramLoader loader(config_);
  EXPECT_FALSE(loader.submit(true, ""));
  EXPECT_FALSE(loader.submit(true, std::string(ProgramLoader::kMaxText + 1, 'G')));
  ASSERT_TRUE(loader.submit(false, "O2000.nc"));
  EXPECT_FALSE(loader.submit(true, "G00 X1"));  // the first is checked or not taken yet
  (void)answer(loader);
  EXPECT_TRUE(loader.submit(true, "G00 X1"));
  (void)answer(loader);
}

}  // namespace
}  // namespace mcnc::channel
