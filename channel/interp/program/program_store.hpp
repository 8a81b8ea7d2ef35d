#pragma once
// Programs on disk: a program directory searched by O number (issue 7, "program store") and
// single files named by path (`--program FILE`). Every failure is returned as a ProgramAlarm;
// nothing here throws. The store keeps no cache: each call reads the directory again, so a
// program edited between two calls is seen; callers that call one program repeatedly keep the
// Program they got.
#include "channel/interp/program/program_text.hpp"

#include <filesystem>
#include <optional>

namespace mcnc::interp::program {

struct ProgramResult {
  std::optional<Program> program;  // set exactly when `alarm` is not
  std::optional<ProgramAlarm> alarm;
};

class ProgramStore {
 public:
  explicit ProgramStore(std::filesystem::path directory);

  // The program with O number `number` (0-9999). Every `.nc` file of the directory (extension
  // compared without regard to case) is read: a file named O<number>.nc or O<4-digit
  // number>.nc (O12.nc, O0012.nc) defines it through its O line, or by its name when it has no
  // O line; any other file defines it with an O line. Exactly one file must define it: none is
  // kProgramNotFound, two or more kProgramAmbiguous naming two of them. A file that fails to
  // split makes every lookup fail with that file's alarm, so a broken file cannot hide a
  // second definition. The returned program always has `number` set.
  ProgramResult find(int number) const;

  // Reads and splits one file. The programs' `file` (and the alarm's `program`) is `path` as
  // given.
  static SplitResult load_file(const std::filesystem::path& path);

  const std::filesystem::path& directory() const { return directory_; }

 private:
  std::filesystem::path directory_;
};

}  // namespace mcnc::interp::program
