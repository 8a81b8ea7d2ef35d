// mcnc-hmi: the operator station. Serves the browser HMI and carries what the machine's status
// topics say to it, and the operator's commands back as DDS operator commands (docs/hmi.md).
// Wiring only: the protocol is in hmi_bridge/core, the server and DDS in hmi_bridge/server.
#include "common/process/process_node.hpp"
#include "common/process/startup.hpp"
#include "hmi_bridge/core/access_policy.hpp"
#include "hmi_bridge/server/hmi_server.hpp"
#include "hmi_bridge/server/machine_feed.hpp"

#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <exception>
#include <map>
#include <thread>

using namespace mcnc;

int main(int argc, char** argv) {
  CLI::App app{"mcnc operator HMI: the browser screens of the machine and its operator commands"};
  process::ShellOptions shell;
  process::add_shell_options(app, shell);
  std::string listen;
  std::string web_dir = MCNC_HMI_WEB_DIR;
  std::string token;
  std::string viewer_token;
  std::vector<std::string> origins;
  double rate = 25.0;
  std::vector<std::string> program_args;
  std::string progdir;
  app.add_option("--listen", listen,
                 "HOST:PORT to serve on (default: the machine file's hmi.listen, else "
                 "127.0.0.1:8080; port 0: any free port)");
  app.add_option("--web", web_dir, "the folder of the web HMI's files")
      ->check(CLI::ExistingDirectory);
  app.add_option("--token", token,
                 "the operator token (default: hmi.operator_token, else one generated and "
                 "printed once)");
  app.add_option("--viewer-token", viewer_token,
                 "the viewer token (default: hmi.viewer_token, else viewing needs no token)");
  app.add_option("--origin", origins,
                 "another origin whose pages may open the WebSocket (repeatable), e.g. "
                 "http://cell-7.local:8080");
  app.add_option("--rate", rate, "state updates per second")->check(CLI::Range(1.0, 100.0));
  app.add_option("--program", program_args, "CH=FILE: the program a channel runs (repeatable)");
  app.add_option("--progdir", progdir,
                 "where the channels find programs by name (default: the machine file's "
                 "program_dir)");
  CLI11_PARSE(app, argc, argv);

  const config::MachineConfig machine = process::load_machine_or_exit(shell.machine_path);
  std::map<std::string, std::string> programs;
  for (const std::string& arg : program_args) {
    const std::size_t eq = arg.find('=');
    if (eq == std::string::npos || machine.find_channel(arg.substr(0, eq)) == nullptr) {
      std::fprintf(stderr, "error: --program %s: expected CH=FILE with a channel of %s\n",
                   arg.c_str(), machine.name.c_str());
      return 2;
    }
    programs[arg.substr(0, eq)] = arg.substr(eq + 1);
  }
  process::start_process("hmi", shell);
  process::require_roudi_or_exit(machine, "HMI");
  std::optional<security::IdentityFiles> identity =
      process::resolve_security_or_exit(machine, "hmi");

  try {
    const bool generated = token.empty() && machine.hmi.operator_token.empty();
    if (token.empty()) {
      token = generated ? hmi::generate_token() : machine.hmi.operator_token;
    }
    if (viewer_token.empty()) {
      viewer_token = machine.hmi.viewer_token;
    }
    if (viewer_token == token) {
      std::fprintf(stderr, "error: the viewer token must differ from the operator token\n");
      return 2;
    }
    hmi::MachineFeed feed(machine, process::resolve_domain(machine), programs,
                          progdir.empty() ? machine.program_dir : progdir, std::move(identity));
    hmi::HmiServerConfig config;
    config.listen = listen.empty() ? machine.hmi.listen : listen;
    const std::size_t colon = config.listen.rfind(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == config.listen.size()) {
      std::fprintf(stderr, "error: --listen %s: expected HOST:PORT, e.g. 127.0.0.1:8080\n",
                   config.listen.c_str());
      return 2;
    }
    config.web_dir = web_dir;
    config.extra_origins = origins;
    config.rate_hz = rate;
    hmi::HmiServer server(config, machine, hmi::AccessPolicy(token, viewer_token), feed);
    // The address on standard output, the token too when it was made here (only here: it is
    // not logged).
    std::printf("HMI at %s\n", server.address().c_str());
    if (generated) {
      std::printf("operator token: %s\n", token.c_str());
    }
    std::fflush(stdout);
    while (process::g_stop_signal == 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    const hmi::HmiCounters c = server.counters();
    spdlog::info("stopped: {} commands sent, {} refused, {} malformed messages, {} foreign origins",
                 c.commands, c.refused, c.malformed, c.origin_refused);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
