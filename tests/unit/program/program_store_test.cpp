// The program store over a temporary directory (issue 7, "program store": a file O<number>.nc or
// any .nc file that contains O<number>).
#include "channel/interp/program/program_store.hpp"
#include "channel/interp/program/program_format_alarms.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

namespace mcnc::interp::program {
namespace {

namespace fs = std::filesystem;

class ProgramStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device rd;
    dir_ = fs::temp_directory_path() / ("mcnc_progstore_" + std::to_string(rd()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

TEST_F(ProgramStoreTest, FoundByFileNameWithAndWithoutOLine) {
  write("O0012.nc", "%\nO0012 (TWELVE)\nM99\n%\n");
  write("O7.nc", "G00 X1\nM99\n");      // no O line: the name gives the number
  write("readme.txt", "O0013\nM99\n");  // not a .nc file
  ProgramStore store(dir_);
  const ProgramResult twelve = store.find(12);
  ASSERT_FALSE(twelve.alarm) << twelve.alarm->text;
  EXPECT_EQ(twelve.program->number, 12);
  EXPECT_EQ(twelve.program->name, "TWELVE");
  EXPECT_EQ(twelve.program->file, path("O0012.nc"));
  EXPECT_EQ(twelve.program->first_line, 2);
  const ProgramResult seven = store.find(7);
  ASSERT_FALSE(seven.alarm) << seven.alarm->text;
  EXPECT_EQ(seven.program->number, 7);
  EXPECT_EQ(seven.program->first_line, 1);
  const ProgramResult thirteen = store.find(13);
  ASSERT_TRUE(thirteen.alarm);
  EXPECT_EQ(thirteen.alarm->number, alarm::kProgramNotFound);
}

TEST_F(ProgramStoreTest, ZeroPaddedAndUnpaddedNamesAndCase) {
  write("o0012.NC", "M99\n");
  write("O5.nc", "O0005\nM99\n");
  ProgramStore store(dir_);
  EXPECT_EQ(store.find(12).program->file, path("o0012.NC"));
  EXPECT_EQ(store.find(5).program->header_line, 1);
}

TEST_F(ProgramStoreTest, FoundInsideAnotherFile) {
  write("part.nc", "%\nO0001\nM98 P1000\nM30\n\nO1000 (SUB)\nG00 X1\nM99\n%\n");
  write("main.nc", "G00 X0\nM30\n");  // unnumbered: never found by number
  ProgramStore store(dir_);
  const ProgramResult sub = store.find(1000);
  ASSERT_FALSE(sub.alarm) << sub.alarm->text;
  EXPECT_EQ(sub.program->file, path("part.nc"));
  EXPECT_EQ(sub.program->header_line, 6);
  EXPECT_EQ(sub.program->line_count, 3);
  EXPECT_EQ(store.find(1).program->line_count, 4);
}

TEST_F(ProgramStoreTest, AmbiguousNumberNamesBothFiles) {
  write("a.nc", "O0001\nM30\nO0012\nM99\n");
  write("b.nc", "(x)\n  O12\nM99\n");
  ProgramStore store(dir_);
  const ProgramResult r = store.find(12);
  ASSERT_TRUE(r.alarm);
  EXPECT_EQ(r.alarm->number, alarm::kProgramAmbiguous);
  EXPECT_NE(r.alarm->text.find(path("a.nc")), std::string::npos) << r.alarm->text;
  EXPECT_NE(r.alarm->text.find(path("b.nc")), std::string::npos) << r.alarm->text;
  EXPECT_EQ(r.alarm->program, path("b.nc"));
  EXPECT_EQ(r.alarm->line, 2);
  EXPECT_EQ(r.alarm->column, 3);
  EXPECT_FALSE(store.find(1).alarm);  // the other program of a.nc is unaffected
}

TEST_F(ProgramStoreTest, NamedFileAndAnotherDefinitionAreAmbiguous) {
  write("O0012.nc", "M99\n");
  write("lib.nc", "O0012\nM99\n");
  const ProgramResult r = ProgramStore(dir_).find(12);
  ASSERT_TRUE(r.alarm);
  EXPECT_EQ(r.alarm->number, alarm::kProgramAmbiguous);
}

TEST_F(ProgramStoreTest, BothPaddedAndUnpaddedFilesAreAmbiguous) {
  write("O0012.nc", "M99\n");
  write("O12.nc", "M99\n");
  const ProgramResult r = ProgramStore(dir_).find(12);
  ASSERT_TRUE(r.alarm);
  EXPECT_EQ(r.alarm->number, alarm::kProgramAmbiguous);
  EXPECT_EQ(r.alarm->line, 0);
  EXPECT_EQ(r.alarm->column, 0);
}

TEST_F(ProgramStoreTest, FileNameThatPromisesAnotherProgram) {
  write("O0012.nc", "O0013\nM99\n");
  const ProgramResult r = ProgramStore(dir_).find(12);
  ASSERT_TRUE(r.alarm);
  EXPECT_EQ(r.alarm->number, alarm::kFileNameMismatch);
  EXPECT_EQ(r.alarm->program, path("O0012.nc"));
}

TEST_F(ProgramStoreTest, BrokenFileFailsLookupsWithItsAlarm) {
  write("good.nc", "O0001\nM30\n");
  write("bad.nc", "O0002\nM99\nO0002\nM99\n");
  const ProgramResult r = ProgramStore(dir_).find(1);
  ASSERT_TRUE(r.alarm);
  EXPECT_EQ(r.alarm->number, alarm::kDuplicateProgramNumber);
  EXPECT_EQ(r.alarm->program, path("bad.nc"));
  EXPECT_EQ(r.alarm->line, 3);
  EXPECT_EQ(r.alarm->column, 1);
}

TEST_F(ProgramStoreTest, MissingNumberOutOfRangeAndMissingDirectory) {
  ProgramStore store(dir_);
  EXPECT_EQ(store.find(42).alarm->number, alarm::kProgramNotFound);
  EXPECT_EQ(store.find(-1).alarm->number, alarm::kProgramNumberOutOfRange);
  EXPECT_EQ(store.find(10000).alarm->number, alarm::kProgramNumberOutOfRange);
  const ProgramResult r = ProgramStore(dir_ / "nowhere").find(1);
  ASSERT_TRUE(r.alarm);
  EXPECT_EQ(r.alarm->number, alarm::kDirectoryUnreadable);
  EXPECT_FALSE(r.program);
}

TEST_F(ProgramStoreTest, LoadFileByPath) {
  write("job.nc", "%\nO0001\nM98 P2\nM30\nO0002\nM99\n%\n");
  const SplitResult r = ProgramStore::load_file(dir_ / "job.nc");
  ASSERT_FALSE(r.alarm);
  ASSERT_EQ(r.programs.size(), 2u);
  EXPECT_EQ(r.programs[0].file, path("job.nc"));
  EXPECT_EQ(r.programs[1].header_line, 5);

  const SplitResult missing = ProgramStore::load_file(dir_ / "none.nc");
  ASSERT_TRUE(missing.alarm);
  EXPECT_EQ(missing.alarm->number, alarm::kFileUnreadable);
  EXPECT_EQ(missing.alarm->program, path("none.nc"));
  EXPECT_EQ(missing.alarm->line, 0);

  write("bad.nc", "O0001 X1\n");
  const SplitResult bad = ProgramStore::load_file(dir_ / "bad.nc");
  ASSERT_TRUE(bad.alarm);
  EXPECT_EQ(bad.alarm->number, alarm::kWordsAfterProgramNumber);
  EXPECT_EQ(bad.alarm->column, 7);

  EXPECT_EQ(ProgramStore::load_file(dir_).alarm->number, alarm::kFileUnreadable);  // a directory
}

// The index (issue 23): a lookup in an unchanged directory reads no file; a file written,
// added or removed is read again (only that one), and what the lookup answers follows it.
TEST_F(ProgramStoreTest, AnUnchangedDirectoryIsNotReadAgain) {
  for (int k = 1; k <= 50; ++k) {
    write("O" + std::to_string(k) + ".nc", "G00 X" + std::to_string(k) + "\nM99\n");
  }
  ProgramStore store(dir_);
  ASSERT_TRUE(store.find(7).program);
  EXPECT_EQ(store.files_read(), 50U);
  for (int k = 1; k <= 50; ++k) {
    ASSERT_TRUE(store.find(k).program) << k;
  }
  EXPECT_EQ(store.files_read(), 50U) << "every lookup read the directory again";

  write("O7.nc", "G00 X70\nG00 Z1\nM99\n");  // longer: a new size
  const ProgramResult seven = store.find(7);
  ASSERT_TRUE(seven.program);
  EXPECT_EQ(seven.program->line_count, 3);
  EXPECT_EQ(store.files_read(), 51U);

  write("O0051.nc", "O0051\nM99\n");
  EXPECT_TRUE(store.find(51).program);
  fs::remove(dir_ / "O0051.nc");
  EXPECT_EQ(store.find(51).alarm->number, alarm::kProgramNotFound);
  write("O8.nc", "O0008\nM99\nO0051\nM99\n");  // now 51 is in O8.nc, with 8
  const ProgramResult moved = store.find(51);
  ASSERT_TRUE(moved.program) << moved.alarm->text;
  EXPECT_EQ(moved.program->file, path("O8.nc"));
  EXPECT_EQ(moved.program->first_line, 3);
  EXPECT_EQ(store.files_read(), 53U);
}

}  // namespace
}  // namespace mcnc::interp::program
