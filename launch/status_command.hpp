#pragma once
// `mcnc status MACHINE.yaml`: joins the machine's DDS domain as a viewer (it publishes nothing),
// listens to the channels' status and the axes' feedback, and prints one line per channel and
// axis (docs/operations.md). For people at the machine without a browser.
#include <string>

namespace CLI {
class App;
}

namespace mcnc::launch {

struct StatusArguments {
  std::string machine_path;
  int wait_ms = 3000;  // how long to wait for every channel and axis to be heard
  bool watch = false;  // print again every `every_ms` until interrupted
  int every_ms = 500;
};

void add_status_options(CLI::App& app, StatusArguments& args);
// 0: every channel and axis was heard; 1: some were not (the machine does not run, or runs on
// another domain); 2: bad input.
int execute_status(const StatusArguments& args);

}  // namespace mcnc::launch
