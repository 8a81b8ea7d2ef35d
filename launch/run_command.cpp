#include "launch/run_command.hpp"

#include "channel/interp/interpreter_source.hpp"
#include "channel/setup/interpreter_setup.hpp"
#include "common/process/exit_deadline.hpp"
#include "common/process/shm_cleanup.hpp"
#include "common/process/startup.hpp"
#include "launch/host_roudi.hpp"
#include "launch/host_service.hpp"
#include "launch/launcher.hpp"
#include "launch/machine_security.hpp"
#include "launch/port_reservation.hpp"
#include "launch/self_path.hpp"
#include "tools/report/run_report.hpp"

#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <utility>

namespace mcnc::launch {

namespace {

// Checks a program before the machine starts (InterpreterSource::load: parse and dry run).
// Prints "FILE:LINE:COL: alarm N: text" when bad (FILE: the called program's file when the
// alarm is in a called program).
bool program_is_good(const config::MachineConfig& machine, const config::ChannelConfig& ch,
                     const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  const std::string name = std::filesystem::path(path).filename().string();
  interp::InterpreterSource source(channel::interpreter_config_for(machine, ch));
  if (auto alarm = source.load(text.str(), name)) {
    // An alarm in a called program (M98, G65 from the program directory) is that file's: its
    // line and column are too.
    const std::string& where =
        alarm->program.empty() || alarm->program == name ? path : alarm->program;
    std::fprintf(stderr, "error: %s:%d:%d: alarm %d: %s\n", where.c_str(), alarm->line,
                 alarm->column, alarm->number, alarm->text.c_str());
    return false;
  }
  return true;
}

// The report: summary.txt (as `mcnc run` printed it), and from the trace the HTML page with the
// timeline and the toolpaths, each picture also as its own SVG file (docs/report.md).
void write_report(const std::string& dir, const config::MachineConfig& machine,
                  const LaunchResult& result, const std::string& trace_path) {
  std::filesystem::create_directories(dir);
  report::Trace trace;
  std::ifstream in(trace_path);
  for (std::string line; std::getline(in, line);) {
    nlohmann::json e = nlohmann::json::parse(line, nullptr, false);
    if (!e.is_discarded()) {
      trace.push_back(std::move(e));
    }
  }
  std::ofstream(dir + "/report.html") << report::report_html(machine, trace);
  std::ofstream(dir + "/timeline.svg") << report::timeline_svg(machine, trace);
  for (const config::ChannelConfig& c : machine.channels) {
    const std::string svg = report::toolpath_svg(machine, trace, c.name);
    if (!svg.empty()) {
      std::ofstream(dir + "/toolpath-" + c.name + ".svg") << svg;
    }
  }
  std::ofstream out(dir + "/summary.txt");
  out << "machine " << machine.name << ": " << (result.exit_code == 0 ? "ok" : "failed") << ", "
      << result.cycles << " cycles of " << machine.cycle_us << " us\n";
  for (const auto& p : result.channels) {
    out << p.name << ": ";
    if (p.ended) {
      out << "ended M" << p.end_code << " after "
          << static_cast<double>(p.end_cycle - p.run_start_cycle) * machine.cycle_s() << " s";
    } else {
      out << (p.has_program ? "did not end" : "no program");
    }
    out << ", " << p.alarms << " alarms\n";
  }
  for (const auto& a : result.alarms) {
    out << "alarm: " << a << "\n";
  }
  if (!result.failure.empty()) {
    out << "failure: " << result.failure << "\n";
  }
}

std::optional<ScriptedOperatorCommand> parse_operator_command(const config::MachineConfig& machine,
                                                              const std::string& spec) {
  const auto at = spec.rfind('@');
  if (at == std::string::npos) {
    return std::nullopt;
  }
  ScriptedOperatorCommand command;
  const std::string cycle = spec.substr(at + 1);
  char* end = nullptr;
  errno = 0;
  const unsigned long long value = std::strtoull(cycle.c_str(), &end, 10);
  if (cycle.empty() || *end != '\0' || errno != 0 || value == 0 || cycle[0] == '-') {
    return std::nullopt;
  }
  command.cycle = value;
  std::string action = spec.substr(0, at);
  if (const auto colon = action.find(':'); colon != std::string::npos) {
    const config::ChannelConfig* ch = machine.find_channel(action.substr(colon + 1));
    if (ch == nullptr) {
      return std::nullopt;
    }
    command.channel = static_cast<std::uint32_t>(ch->id);
    action.resize(colon);
  }
  // ACTION=VALUE for the overrides (percent).
  std::optional<double> amount;
  if (const auto eq = action.find('='); eq != std::string::npos) {
    const std::string text = action.substr(eq + 1);
    char* value_end = nullptr;
    errno = 0;
    amount = std::strtod(text.c_str(), &value_end);
    if (text.empty() || *value_end != '\0' || errno != 0 || !std::isfinite(*amount) ||
        *amount < 0.0) {
      return std::nullopt;
    }
    action.resize(eq);
  }
  static constexpr std::pair<const char*, OperatorAction> kPlain[] = {
      {"reset", OP_RESET}, {"cycle_start", OP_CYCLE_START}, {"feed_hold", OP_FEED_HOLD}};
  static constexpr std::pair<const char*, OperatorAction> kValued[] = {
      {"feed_override", OP_FEED_OVERRIDE},
      {"rapid_override", OP_RAPID_OVERRIDE},
      {"spindle_override", OP_SPINDLE_OVERRIDE}};
  for (const auto& [name, kind] : kPlain) {
    if (action == name && !amount) {
      command.action = kind;
      return command;
    }
  }
  for (const auto& [name, kind] : kValued) {
    if (action == name && amount) {
      command.action = kind;
      command.value = *amount;
      return command;
    }
  }
  return std::nullopt;
}

// What the run did, on stdout: each program's end, the alarms, the failure, the verdict.
void print_result(const config::MachineConfig& machine, const LaunchResult& result) {
  for (const auto& p : result.channels) {
    if (!p.has_program) {
      continue;
    }
    if (p.ended) {
      std::printf(
          "%s: program end M%02d, cycle time %.3f s, %u alarms\n", p.name.c_str(), p.end_code,
          static_cast<double>(p.end_cycle - p.run_start_cycle) * machine.cycle_s(), p.alarms);
    } else {
      std::printf("%s: did not end (%s), %u alarms\n", p.name.c_str(), to_string(p.state),
                  p.alarms);
    }
  }
  for (const auto& a : result.alarms) {
    std::printf("alarm: %s\n", a.c_str());
  }
  if (!result.failure.empty()) {
    std::printf("failed: %s\n", result.failure.c_str());
  }
  std::printf("%s after %llu cycles\n", result.exit_code == 0 ? "ok" : "FAILED",
              static_cast<unsigned long long>(result.cycles));
}

// How long the launcher's own DDS teardown may take once the run's processes are gone: it
// takes well under a second; Cyclone DDS 0.10's security teardown has hung for good
// (docs/operations.md, "Security"). Beyond it `mcnc run` stops the RouDi it started and leaves.
constexpr std::chrono::milliseconds kLauncherTeardownLimit{10'000};

}  // namespace

void add_run_options(CLI::App& app, RunArguments& args) {
  app.add_option("machine", args.machine_path, "machine file (YAML)")->required();
  app.add_option("--program", args.programs, "CH=FILE: the program a channel runs (repeatable)");
  app.add_option("--clock", args.clock, "lockstep (deterministic, default) or realtime")
      ->check(CLI::IsMember({"lockstep", "realtime"}));
  app.add_flag("--pace", args.pace, "lockstep: do not run ahead of real time");
  app.add_option("--trace", args.trace_path, "write the event trace (JSON lines) to FILE");
  app.add_option("--trace-pos-every", args.trace_pos_every, "a pos event every K cycles")
      ->check(CLI::PositiveNumber);
  app.add_option("--report", args.report_dir, "write a run report into DIR");
  app.add_option("--log-level", args.log_level, "log level of every process");
  app.add_option("--timeout", args.timeout_s, "E-stop the run after this many seconds (0: none)");
  app.add_option("--start-timeout", args.start_timeout_s,
                 "give up the start when a process is not ready after this many seconds "
                 "(default 60; a large secured machine's handshakes may need more)")
      ->check(CLI::PositiveNumber);
  app.add_option("--drive-fault", args.drive_faults,
                 "fault injection: BUS:NODE:KIND@SYNC, KIND overcurrent, following_error or "
                 "heartbeat_stop (repeatable)");
  app.add_option("--drive-refuse-sdo", args.drive_sdo_refusals,
                 "fault injection: BUS:NODE:INDEX, the drive refuses SDO access to that object "
                 "(repeatable)");
  app.add_option("--progdir", args.program_dir,
                 "where M98, G65 and G144 find programs by number (overrides the machine file's "
                 "program_dir)");
  app.add_option("--retained", args.retained_file,
                 "keep the shared retained macro variables #500-#999 in FILE between runs "
                 "(overrides the machine file's retained_file)");
  app.add_option("--hmi", args.hmi,
                 "serve the operator HMI (mcnc-hmi) while the machine runs, on HOST:PORT "
                 "(without a value: the machine file's hmi.listen, else 127.0.0.1:8080)")
      ->expected(0, 1)
      ->default_str("default");
  app.add_option("--host", args.host,
                 "a machine of several hosts (hosts:): start this host's processes only; the "
                 "first host's launcher runs the machine, the others follow it");
  app.add_flag("--serve", args.serve,
               "with --host: stay up as that host's launcher service, and run each run that "
               "`mcnc run --services` asks for from any host");
  app.add_flag("--services", args.services,
               "a machine of several hosts: ask every host's launcher service (--serve) to run "
               "it; print the coordinator's output and end with its exit code");
  app.add_flag("--manual-start", args.manual_start,
               "the channels load their programs and wait for CYCLE START (from the HMI or "
               "--operator)");
  app.add_option("--operator", args.operator_script,
                 "scripted operator: ACTION[=VALUE][:CHANNEL]@CYCLE, ACTION reset, cycle_start, "
                 "feed_hold, feed_override=P, rapid_override=P or spindle_override=P (percent), "
                 "for one channel or (without CHANNEL) the whole machine (repeatable)");
}

std::vector<std::string> run_argv(const RunArguments& args) {
  std::vector<std::string> argv;
  const auto option = [&](const char* name, const std::string& value) {
    if (!value.empty()) {
      argv.insert(argv.end(), {name, value});
    }
  };
  const auto each = [&](const char* name, const std::vector<std::string>& values) {
    for (const auto& v : values) {
      argv.insert(argv.end(), {name, v});
    }
  };
  each("--program", args.programs);
  option("--clock", args.clock);
  if (args.pace) {
    argv.emplace_back("--pace");
  }
  option("--trace", args.trace_path);
  option("--trace-pos-every", std::to_string(args.trace_pos_every));
  option("--report", args.report_dir);
  option("--log-level", args.log_level);
  if (args.timeout_s > 0) {
    option("--timeout", std::to_string(args.timeout_s));
  }
  if (args.start_timeout_s != RunArguments{}.start_timeout_s) {
    option("--start-timeout", std::to_string(args.start_timeout_s));
  }
  each("--drive-fault", args.drive_faults);
  each("--drive-refuse-sdo", args.drive_sdo_refusals);
  each("--operator", args.operator_script);
  option("--progdir", args.program_dir);
  option("--retained", args.retained_file);
  if (args.hmi == "default") {
    argv.emplace_back("--hmi");  // the machine file's address
  } else {
    option("--hmi", args.hmi);
  }
  if (args.manual_start) {
    argv.emplace_back("--manual-start");
  }
  return argv;
}

int execute_run(const RunArguments& args) {
  if (args.serve) {
    return serve_host(args);
  }
  if (args.services) {
    return request_run(args);
  }
  config::MachineConfig machine = process::load_machine_or_exit(args.machine_path);
  if (!args.program_dir.empty()) {
    std::error_code ec;
    if (!std::filesystem::is_directory(args.program_dir, ec)) {
      std::fprintf(stderr, "error: --progdir %s: no such directory\n", args.program_dir.c_str());
      return 2;
    }
    machine.program_dir = std::filesystem::absolute(args.program_dir).lexically_normal().string();
  }
  LaunchOptions options;
  options.machine_path = std::filesystem::absolute(args.machine_path).string();
  if (!args.host.empty()) {
    const bool known =
        std::any_of(machine.hosts.begin(), machine.hosts.end(),
                    [&](const config::HostConfig& h) { return h.name == args.host; });
    if (!known) {
      std::fprintf(stderr, "error: --host %s: %s names no such host%s\n", args.host.c_str(),
                   args.machine_path.c_str(),
                   machine.hosts.empty() ? " (it has no hosts: section)" : "");
      return 2;
    }
    options.host = args.host;
  }
  for (const auto& spec : args.programs) {
    const auto eq = spec.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == spec.size()) {
      std::fprintf(stderr, "error: --program %s: expected CHANNEL=FILE\n", spec.c_str());
      return 2;
    }
    const std::string channel = spec.substr(0, eq);
    const std::string file = spec.substr(eq + 1);
    const config::ChannelConfig* ch = machine.find_channel(channel);
    if (ch == nullptr) {
      std::fprintf(stderr, "error: --program %s: no channel %s in %s\n", spec.c_str(),
                   channel.c_str(), args.machine_path.c_str());
      return 2;
    }
    if (!std::filesystem::is_regular_file(file)) {
      std::fprintf(stderr, "error: --program %s: no such file %s\n", spec.c_str(), file.c_str());
      return 2;
    }
    if (options.programs.count(channel) != 0) {
      std::fprintf(stderr, "error: --program %s: channel %s already has a program\n", spec.c_str(),
                   channel.c_str());
      return 2;
    }
    if (!program_is_good(machine, *ch, file)) {
      return 2;
    }
    options.programs[channel] = std::filesystem::absolute(file).string();
  }
  options.clock = args.clock == "realtime" ? REALTIME_CLOCK : LOCKSTEP_CLOCK;
  options.pace = args.pace;
  if (!args.hmi.empty()) {
    options.hmi_listen = args.hmi == "default" ? machine.hmi.listen : args.hmi;
  }
  options.manual_start = args.manual_start;
  options.trace_path = args.trace_path;
  options.trace_pos_every = args.trace_pos_every;
  options.bin_dir = executable_dir();
  options.log_level = args.log_level;
  options.run_timeout_s = args.timeout_s;
  options.start_timeout_s = args.start_timeout_s;
  if (!args.program_dir.empty()) {
    options.program_dir = machine.program_dir;
  }
  if (!args.retained_file.empty()) {
    options.retained_file = std::filesystem::absolute(args.retained_file).string();
  }
  // Fault injection goes to the simulator of the named bus, which checks the rest.
  for (const auto& [specs, flag] : {std::pair{&args.drive_faults, "--fault"},
                                    std::pair{&args.drive_sdo_refusals, "--refuse-sdo"}}) {
    for (const std::string& spec : *specs) {
      const auto colon = spec.find(':');
      if (colon == std::string::npos || machine.find_bus(spec.substr(0, colon)) == nullptr) {
        std::fprintf(stderr, "error: %s %s: expected a bus of %s first (BUS:...)\n",
                     flag == std::string("--fault") ? "--drive-fault" : "--drive-refuse-sdo",
                     spec.c_str(), args.machine_path.c_str());
        return 2;
      }
      auto& extra = options.drivesim_args[spec.substr(0, colon)];
      extra.emplace_back(flag);
      extra.push_back(spec.substr(colon + 1));
    }
  }

  for (const std::string& spec : args.operator_script) {
    const auto command = parse_operator_command(machine, spec);
    if (!command) {
      std::fprintf(stderr,
                   "error: --operator %s: expected ACTION[:CHANNEL]@CYCLE with ACTION reset, "
                   "cycle_start, feed_hold, feed_override=PERCENT, rapid_override=PERCENT or "
                   "spindle_override=PERCENT, a channel of %s and a cycle > 0\n",
                   spec.c_str(), args.machine_path.c_str());
      return 2;
    }
    options.operator_script.push_back(*command);
  }

  if (!args.report_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(args.report_dir, ec);
    if (!std::filesystem::is_directory(args.report_dir)) {
      std::fprintf(stderr, "error: --report %s: cannot make the directory (%s)\n",
                   args.report_dir.c_str(), ec.message().c_str());
      return 2;
    }
    if (options.trace_path.empty()) {
      options.trace_path = args.report_dir + "/trace.jsonl";  // the report is made from it
    }
  }
  if (!options.trace_path.empty()) {
    const auto dir = std::filesystem::absolute(options.trace_path).parent_path();
    if (!std::filesystem::is_directory(dir)) {
      std::fprintf(stderr, "error: --trace %s: no such directory %s\n", options.trace_path.c_str(),
                   dir.c_str());
      return 2;
    }
  }
  const bool with_hmi = !options.hmi_listen.empty();
  if (!check_machine_security(machine, options.host, with_hmi) || !reserve_fixed_ports(machine)) {
    return 2;
  }
  // RouDi before any process, and stopped after the last (HostRoudi's destructor).
  std::optional<HostRoudi> roudi;
  if (needs_roudi(machine, with_hmi)) {
    try {
      roudi.emplace(dds_process_names(machine, with_hmi).size(), machine.roudi_running);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: %s; nothing started\n", e.what());
      return 2;
    }
  }
  options.watch_roudi = roudi.has_value();
  process::install_stop_signals();
  Launcher launcher(machine, options);
  std::map<std::string, std::string> last_line;
  LaunchResult result;
  std::optional<process::TeardownBound> teardown_bound;
  const auto bound_teardown = [&](const LaunchResult& ended) {
    teardown_bound.emplace(kLauncherTeardownLimit, ended.exit_code, [&, ended] {
      print_result(machine, ended);
      std::fprintf(stderr,
                   "error: the launcher's DDS teardown did not end within %lld s after the run "
                   "(or a stop signal came meanwhile); the run's processes are gone, stopping "
                   "RouDi and leaving with the run's exit code %d\n",
                   static_cast<long long>(kLauncherTeardownLimit.count() / 1000), ended.exit_code);
      std::fflush(stdout);
      if (roudi) {
        roudi->stop();
      }
      process::remove_stale_dds_shm_files();
    });
  };
  try {
    result = launcher.run(
        [&](const std::vector<ChannelProgress>& list) {
          for (const auto& p : list) {
            char line[160];
            std::snprintf(line, sizeof line, "%-4s block %u/%u  line %d  %s%s", p.name.c_str(),
                          p.block, p.block_total, p.line, to_string(p.state),
                          p.ended ? "  (program end)" : "");
            if (last_line[p.name] != line) {
              last_line[p.name] = line;
              std::printf("%s\n", line);
              std::fflush(stdout);
            }
          }
        },
        bound_teardown);
  } catch (const std::exception& e) {
    // The children are stopped by their handles; report and fail.
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  teardown_bound.reset();
  print_result(machine, result);
  if (!args.report_dir.empty()) {
    write_report(args.report_dir, machine, result, options.trace_path);
  }
  return result.exit_code;
}

}  // namespace mcnc::launch
