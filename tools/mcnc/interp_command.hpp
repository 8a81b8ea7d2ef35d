#pragma once
// `mcnc interp`: runs the interpreter on a program file and prints its canonical commands as
// JSON lines (docs/canonical-commands.md). Exit 0 at the program end, 1 on an alarm (printed
// as the last line), 2 on a bad command line or parameter file.
#include <CLI/CLI.hpp>

#include <string>

namespace mcnc::tools {

struct InterpArguments {
  std::string system;  // "A" or "B"; empty: the parameter file's or A
  // A name of config::kDialectNames; empty: the parameter file's or dafeng. `--dialect` without
  // a name lists the dialects (list_dialects).
  std::string dialect;
  const CLI::Option* dialect_option = nullptr;
  int channel = 0;  // 0: the parameter file's or 1
  std::string param_file;
  std::string program_dir;
  std::string file;
};

void add_interp_options(CLI::App& app, InterpArguments& args);
int execute_interp(const InterpArguments& args);

}  // namespace mcnc::tools
