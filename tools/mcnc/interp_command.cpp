#include "tools/mcnc/interp_command.hpp"

#include "channel/interp/dialect.hpp"
#include "channel/interp/interpreter.hpp"
#include "channel/interp/output/command_json.hpp"
#include "common/config/dialect_names.hpp"
#include "tools/mcnc/interp_params.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <optional>
#include <sstream>

namespace mcnc::tools {

namespace {

// The real clock and calendar for #3001/#3002 and #3011/#3012.
class SystemEnvironment final : public interp::InterpreterEnvironment {
 public:
  double milliseconds() const override {
    return std::chrono::duration<double, std::milli>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
  }
  double date() const override {
    const std::tm t = now();
    return (t.tm_year + 1900) * 10000.0 + (t.tm_mon + 1) * 100.0 + t.tm_mday;
  }
  double time_of_day() const override {
    const std::tm t = now();
    return t.tm_hour * 10000.0 + t.tm_min * 100.0 + t.tm_sec;
  }

 private:
  static std::tm now() {
    const std::time_t s = std::time(nullptr);
    std::tm t{};
    localtime_r(&s, &t);
    return t;
  }
};

void flush(std::string& buffer) {
  std::fwrite(buffer.data(), 1, buffer.size(), stdout);
  buffer.clear();
}

// Ends the process once everything is written: a large program's parsed form is not worth
// freeing piece by piece just before the process ends (the retained variables were saved when
// the program ended).
[[noreturn]] void finish(int code) {
  std::fflush(stdout);
  std::_Exit(code);
}

}  // namespace

void add_interp_options(CLI::App& app, InterpArguments& args) {
  app.add_option("--system", args.system, "G-code system A (default) or B")
      ->check(CLI::IsMember({"A", "B"}));
  args.dialect_option = app.add_option("--dialect", args.dialect,
                                       "dialect: " + config::dialect_choices() +
                                           "; default dafeng; without a name: list them")
                            ->expected(0, 1);
  app.add_option("--channel", args.channel, "channel number (default 1)")
      ->check(CLI::Range(1, 255));
  app.add_option("--param", args.param_file, "interpreter parameter file (YAML)")
      ->check(CLI::ExistingFile);
  app.add_option("--progdir", args.program_dir, "program directory searched by O number")
      ->check(CLI::ExistingDirectory);
  app.add_option("FILE", args.file, "program file (required unless --dialect lists)")
      ->check(CLI::ExistingFile);
}

int execute_interp(const InterpArguments& args) {
  if (args.dialect_option != nullptr && args.dialect_option->count() > 0 && args.dialect.empty()) {
    for (const std::string_view n : config::kDialectNames) {
      std::printf("%.*s\n", static_cast<int>(n.size()), n.data());
    }
    for (const config::DialectAlias& a : config::kDialectAliases) {
      std::printf("%.*s (%.*s)\n", static_cast<int>(a.alias.size()), a.alias.data(),
                  static_cast<int>(a.name.size()), a.name.data());
    }
    return 0;
  }
  if (args.file.empty()) {
    std::fprintf(stderr, "mcnc interp: FILE is required\n");
    return 2;
  }
  interp::InterpreterConfig config;
  if (!args.dialect.empty()) {
    // Before the parameter file, whose axes (and further settings) apply on top of it.
    const std::optional<interp::Dialect> d = interp::dialect_named(args.dialect);
    if (!d) {
      std::fprintf(stderr, "mcnc interp: --dialect must be %s\n",
                   config::dialect_choices().c_str());
      return 2;
    }
    interp::select_dialect(config, *d);
  }
  try {
    if (!args.param_file.empty()) {
      load_interp_params(args.param_file, config);
    }
  } catch (const ParamError& e) {
    std::fprintf(stderr, "mcnc interp: %s: %s\n", args.param_file.c_str(), e.what());
    return 2;
  }
  if (!args.dialect.empty() &&
      interp::dialect_name(config.dialect) != config::canonical_dialect_name(args.dialect)) {
    std::fprintf(stderr, "mcnc interp: %s: the parameter file's dialect is not --dialect %s\n",
                 args.param_file.c_str(), args.dialect.c_str());
    return 2;
  }
  if (args.system == "A" && config.dialect == interp::Dialect::fanuc_mill) {
    std::fprintf(stderr, "mcnc interp: the mill dialect is G-code system B (G90/G91, G92)\n");
    return 2;
  }
  if (!args.system.empty()) {
    config.system = args.system == "A" ? interp::GCodeSystem::a : interp::GCodeSystem::b;
  }
  if (args.channel != 0) {
    config.channel = args.channel;
  }
  if (!args.program_dir.empty()) {
    config.program_dir = args.program_dir;
  }
  if (!std::ifstream(args.file, std::ios::binary)) {
    std::fprintf(stderr, "mcnc interp: cannot read %s\n", args.file.c_str());
    return 2;
  }
  SystemEnvironment environment;
  interp::Interpreter interpreter(config, &environment);
  std::string out;
  out.reserve(1 << 17);
  // The file is read as the program runs: memory does not grow with the program.
  if (auto alarm = interpreter.start_file(args.file, args.file)) {
    interp::output::append_json(out, *alarm);
    flush(out);
    finish(1);
  }
  const auto print_warnings = [&] {
    for (const interp::ProgramAlarm& w : interpreter.take_warnings()) {
      std::fprintf(stderr, "warning: %s:%d:%d: %s\n", w.program.c_str(), w.line, w.column,
                   w.text.c_str());
    }
  };
  while (auto result = interpreter.next()) {
    print_warnings();
    if (const auto* alarm = std::get_if<interp::ProgramAlarm>(&*result)) {
      interp::output::append_json(out, *alarm);
      flush(out);
      finish(1);
    }
    interp::output::append_json(out, std::get<interp::Command>(*result), config.axes, args.file);
    if (out.size() > (1 << 16)) {
      flush(out);
    }
  }
  print_warnings();
  flush(out);
  finish(0);
}

}  // namespace mcnc::tools
