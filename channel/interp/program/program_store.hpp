#pragma once
// Programs on disk: a program directory searched by O number (issue 7, "program store") and
// single files named by path (`--program FILE`). Every failure is returned as a ProgramAlarm;
// nothing here throws.
//
// The store keeps an index of the directory (issue 23): which programs each `.nc` file holds
// and where, read when first asked and read again, file by file, when the directory changes
// (inotify; where that is not available, each lookup compares the files' sizes and times). A
// lookup of an unchanged directory reads no file, so a program that calls subprograms in a
// loop does not read the directory each time. A store serves one thread: the channel gives its
// program checks and its runs one each, so that this core unit needs no lock.
#include "channel/interp/program/program_text.hpp"

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mcnc::interp::program {

struct ProgramResult {
  std::optional<Program> program;  // set exactly when `alarm` is not
  std::optional<ProgramAlarm> alarm;
};

class ProgramStore {
 public:
  explicit ProgramStore(std::filesystem::path directory);
  ~ProgramStore();
  ProgramStore(const ProgramStore&) = delete;
  ProgramStore& operator=(const ProgramStore&) = delete;

  // The program with O number `number` (0-9999). Among the `.nc` files of the directory
  // (extension compared without regard to case), a file named O<number>.nc or O<4-digit
  // number>.nc (O12.nc, O0012.nc) defines it through its O line, or by its name when it has no
  // O line; any other file defines it with an O line. Exactly one file must define it: none is
  // kProgramNotFound, two or more kProgramAmbiguous naming two of them. A file that fails to
  // split makes every lookup fail with that file's alarm, so a broken file cannot hide a
  // second definition. The returned program always has `number` set.
  ProgramResult find(int number);

  // Reads and splits one file. The programs' `file` (and the alarm's `program`) is `path` as
  // given.
  static SplitResult load_file(const std::filesystem::path& path);

  const std::filesystem::path& directory() const { return directory_; }
  // How many times files were read into the index (for tests: an unchanged directory adds none).
  [[nodiscard]] std::uint64_t files_read() const;

 private:
  // What the index knows of one file: its size and time when read, and its programs (their
  // text not held: the file is opened again when one is found) or its alarm.
  struct IndexedFile {
    std::int64_t size = -1;
    std::int64_t mtime_ns = -1;
    std::vector<Program> programs;
    std::optional<ProgramAlarm> alarm;
  };
  // find(); `retried`: the index was read again for it once already.
  ProgramResult find_indexed(int number, bool retried);
  // Brings the index up to date; the directory's alarm when it cannot be read.
  std::optional<ProgramAlarm> refresh();
  // Whether the directory changed since the last refresh (always true without inotify).
  bool changed();

  std::filesystem::path directory_;
  std::map<std::string, IndexedFile> files_;  // by path: sorted, so alarms do not depend on
                                              // the order of the directory
  bool indexed_ = false;
  int watch_fd_ = -1;  // inotify, or -1
  std::uint64_t files_read_ = 0;
};

}  // namespace mcnc::interp::program
