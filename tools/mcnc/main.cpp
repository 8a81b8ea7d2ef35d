// mcnc: the user's command line.
#include "common/log/logging.hpp"
#include "launch/run_command.hpp"
#include "launch/status_command.hpp"
#include "tools/certs/certs_command.hpp"
#include "tools/mcnc/interp_command.hpp"

#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
  CLI::App app{"mcnc: multi-channel NC runtime"};
  app.require_subcommand(1);
  mcnc::launch::RunArguments run_args;
  CLI::App* run =
      app.add_subcommand("run", "bring up a machine, run programs to their end, report");
  mcnc::launch::add_run_options(*run, run_args);
  mcnc::tools::InterpArguments interp_args;
  CLI::App* interp = app.add_subcommand(
      "interp", "interpret a program and print its canonical commands as JSON lines");
  mcnc::tools::add_interp_options(*interp, interp_args);
  mcnc::launch::StatusArguments status_args;
  CLI::App* status = app.add_subcommand(
      "status", "print one line per channel and axis of a running machine (its DDS domain)");
  mcnc::launch::add_status_options(*status, status_args);
  mcnc::tools::CertsArguments certs_args;
  CLI::App* certs = app.add_subcommand(
      "certs", "make a machine's DDS Security: CA, an identity per process, signed permissions");
  mcnc::tools::add_certs_options(*certs, certs_args);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;  // bad command line is bad input
  }
  if (interp->parsed()) {
    return mcnc::tools::execute_interp(interp_args);
  }
  if (certs->parsed()) {
    return mcnc::tools::execute_certs(certs_args);
  }
  mcnc::log::setup("mcnc", run_args.log_level);
  if (run->parsed()) {
    return mcnc::launch::execute_run(run_args);
  }
  if (status->parsed()) {
    return mcnc::launch::execute_status(status_args);
  }
  return 2;
}
