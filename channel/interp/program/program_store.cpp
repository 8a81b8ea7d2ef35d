#include "channel/interp/program/program_store.hpp"

#include "channel/interp/program/program_format_alarms.hpp"
#include "channel/interp/program_chars.hpp"

#include <sys/inotify.h>
#include <sys/stat.h>
#include <unistd.h>
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

}  // namespace

ProgramStore::ProgramStore(std::filesystem::path directory) : directory_(std::move(directory)) {
  watch_fd_ = ::inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
  if (watch_fd_ >= 0 &&
      ::inotify_add_watch(watch_fd_, directory_.c_str(),
                          IN_CREATE | IN_DELETE | IN_MODIFY | IN_CLOSE_WRITE | IN_MOVED_FROM |
                              IN_MOVED_TO | IN_ATTRIB | IN_DELETE_SELF | IN_MOVE_SELF) < 0) {
    ::close(watch_fd_);
    watch_fd_ = -1;  // no directory yet, or no inotify: compare sizes and times instead
  }
}

ProgramStore::~ProgramStore() {
  if (watch_fd_ >= 0) {
    ::close(watch_fd_);
  }
}

std::uint64_t ProgramStore::files_read() const {
  return files_read_;
}

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

bool ProgramStore::changed() {
  if (watch_fd_ < 0) {
    return true;
  }
  bool any = false;
  alignas(inotify_event) char buffer[4096];
  while (::read(watch_fd_, buffer, sizeof buffer) > 0) {
    any = true;  // which file does not matter: sizes and times tell
  }
  return any;
}

std::optional<ProgramAlarm> ProgramStore::refresh() {
  if (indexed_ && !changed()) {
    return std::nullopt;
  }
  const std::string dir = directory_.string();
  std::error_code ec;
  std::map<std::string, IndexedFile> now;
  for (fs::directory_iterator it(directory_, ec), last; !ec && it != last; it.increment(ec)) {
    std::error_code type_ec;
    if (!it->is_regular_file(type_ec) ||
        !equal_ignoring_case(it->path().extension().string(), ".nc")) {
      continue;
    }
    const std::string path = it->path().string();
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
      continue;  // gone since it was listed
    }
    const std::int64_t size = st.st_size;
    const std::int64_t mtime =
        static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
    auto known = files_.find(path);
    if (known != files_.end() && known->second.size == size && known->second.mtime_ns == mtime) {
      now.emplace(path, std::move(known->second));
      continue;
    }
    IndexedFile f;
    f.size = size;
    f.mtime_ns = mtime;
    SplitResult split = load_file(it->path());
    ++files_read_;
    f.alarm = std::move(split.alarm);
    f.programs = std::move(split.programs);
    for (Program& p : f.programs) {
      p.text.reset();  // the file is opened again when the program is found
    }
    now.emplace(path, std::move(f));
  }
  if (ec) {
    indexed_ = false;
    files_.clear();
    return file_alarm(alarm::kDirectoryUnreadable,
                      "cannot read program directory " + dir + ": " + ec.message(), dir);
  }
  files_ = std::move(now);
  indexed_ = true;
  return std::nullopt;
}

ProgramResult ProgramStore::find(int number) {
  ProgramResult result;
  const std::string dir = directory_.string();
  if (number < 0 || number > kMaxProgramNumber) {
    result.alarm =
        file_alarm(alarm::kProgramNumberOutOfRange,
                   "program number " + std::to_string(number) + " is not within 0-9999", dir);
    return result;
  }
  return find_indexed(number, false);
}

ProgramResult ProgramStore::find_indexed(int number, bool retried) {
  ProgramResult result;
  const std::string dir = directory_.string();
  if (auto bad = refresh()) {
    result.alarm = std::move(bad);
    return result;
  }

  const std::string short_name = "O" + std::to_string(number);
  const std::string padded_name = program_label(number);
  std::vector<std::pair<const IndexedFile*, const Program*>> found;
  for (const auto& [path, indexed] : files_) {
    if (indexed.alarm) {
      result.alarm = indexed.alarm;
      return result;
    }
    const std::string stem = fs::path(path).stem().string();
    const bool named =
        equal_ignoring_case(stem, short_name) || equal_ignoring_case(stem, padded_name);
    bool defines = false;
    for (const Program& program : indexed.programs) {
      if (program.number ? *program.number == number : named) {
        found.emplace_back(&indexed, &program);
        defines = true;
        break;  // split_programs has rejected a second one in the same file
      }
    }
    if (named && !defines) {
      // O0012.nc that holds other programs only: the name promises what the file does not hold.
      result.alarm = file_alarm(alarm::kFileNameMismatch,
                                "file " + path + " does not define " + padded_name, path);
      return result;
    }
  }

  if (found.empty()) {
    result.alarm =
        file_alarm(alarm::kProgramNotFound, "program " + padded_name + " not found in " + dir, dir);
    return result;
  }
  if (found.size() > 1) {
    const Program& second = *found[1].second;
    result.alarm = ProgramAlarm{
        alarm::kProgramAmbiguous,
        padded_name + " is defined in both " + found[0].second->file + " and " + second.file,
        second.file, second.header_line, second.header_column};
    return result;
  }
  Program program = *found.front().second;
  std::string error;
  program.text = TextSource::open_file(program.file, error);
  if (program.text &&
      static_cast<std::int64_t>(program.text->size()) != found.front().first->size && !retried) {
    indexed_ = false;  // written since it was indexed: index it again
    return find_indexed(number, true);
  }
  if (!program.text) {
    indexed_ = false;  // it went: read the directory again next time
    result.alarm =
        file_alarm(alarm::kFileUnreadable,
                   "cannot read program file " + program.file + ": " + error, program.file);
    return result;
  }
  program.number = number;
  result.program = std::move(program);
  return result;
}

}  // namespace mcnc::interp::program
