#include "channel/interp/program/program_store.hpp"

#include "channel/interp/program/program_format_alarms.hpp"
#include "channel/interp/program_chars.hpp"

#include <algorithm>
#include <system_error>
#include <vector>

namespace mcnc::interp::program {

namespace {

namespace fs = std::filesystem;

bool equal_ignoring_case(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return to_upper(x) == to_upper(y);
         });
}

ProgramAlarm file_alarm(int number, std::string text, const std::string& file) {
  return ProgramAlarm{number, std::move(text), file, 0, 0};
}

// A definition of the looked-for number: the file and the program in it.
struct Definition {
  std::string file;
  Program program;
};

}  // namespace

ProgramStore::ProgramStore(std::filesystem::path directory) : directory_(std::move(directory)) {}

SplitResult ProgramStore::load_file(const std::filesystem::path& path) {
  const std::string file = path.string();
  SplitResult result;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    result.alarm = file_alarm(alarm::kFileUnreadable, "program file not found: " + file, file);
    return result;
  }
  std::string error;
  std::shared_ptr<const TextSource> text = TextSource::open_file(file, error);
  if (!text) {
    result.alarm =
        file_alarm(alarm::kFileUnreadable, "cannot read program file " + file + ": " + error, file);
    return result;
  }
  return split_programs(std::move(text), file);
}

ProgramResult ProgramStore::find(int number) const {
  ProgramResult result;
  const std::string dir = directory_.string();
  if (number < 0 || number > kMaxProgramNumber) {
    result.alarm =
        file_alarm(alarm::kProgramNumberOutOfRange,
                   "program number " + std::to_string(number) + " is not within 0-9999", dir);
    return result;
  }

  std::error_code ec;
  std::vector<fs::path> files;
  for (fs::directory_iterator it(directory_, ec), last; !ec && it != last; it.increment(ec)) {
    std::error_code type_ec;
    if (it->is_regular_file(type_ec) &&
        equal_ignoring_case(it->path().extension().string(), ".nc")) {
      files.push_back(it->path());
    }
  }
  if (ec) {
    result.alarm = file_alarm(alarm::kDirectoryUnreadable,
                              "cannot read program directory " + dir + ": " + ec.message(), dir);
    return result;
  }
  // Sorted, so that which two files an ambiguity alarm names does not depend on the directory
  // order of the file system.
  std::sort(files.begin(), files.end());

  const std::string short_name = "O" + std::to_string(number);
  const std::string padded_name = program_label(number);
  std::vector<Definition> found;
  for (const fs::path& path : files) {
    SplitResult split = load_file(path);
    if (split.alarm) {
      result.alarm = std::move(split.alarm);
      return result;
    }
    const std::string stem = path.stem().string();
    const bool named =
        equal_ignoring_case(stem, short_name) || equal_ignoring_case(stem, padded_name);
    bool defines = false;
    for (Program& program : split.programs) {
      const bool match = program.number ? *program.number == number : named;
      if (match) {
        program.number = number;
        found.push_back({path.string(), std::move(program)});
        defines = true;
        break;  // split_programs has rejected a second one in the same file
      }
    }
    if (named && !defines) {
      // O0012.nc that holds other programs only: the name promises what the file does not hold.
      result.alarm =
          file_alarm(alarm::kFileNameMismatch,
                     "file " + path.string() + " does not define " + padded_name, path.string());
      return result;
    }
  }

  if (found.empty()) {
    result.alarm =
        file_alarm(alarm::kProgramNotFound, "program " + padded_name + " not found in " + dir, dir);
    return result;
  }
  if (found.size() > 1) {
    const Definition& second = found[1];
    result.alarm =
        ProgramAlarm{alarm::kProgramAmbiguous,
                     padded_name + " is defined in both " + found[0].file + " and " + second.file,
                     second.file, second.program.header_line, second.program.header_column};
    return result;
  }
  result.program = std::move(found.front().program);
  return result;
}

}  // namespace mcnc::interp::program
