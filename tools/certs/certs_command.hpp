#pragma once
// `mcnc certs MACHINE.yaml DIR`: a machine's DDS Security (docs/operations.md, "Security").
#include <string>

namespace CLI {
class App;
}

namespace mcnc::tools {

struct CertsArguments {
  std::string machine_path;
  std::string dir;
  int days = 730;
  std::string protection = "sign";
};

void add_certs_options(CLI::App& app, CertsArguments& args);
// 0 when every file was made; 2 on bad input (machine file, a directory that already holds a
// machine's CA), nothing written; 1 when OpenSSL or the file system failed.
int execute_certs(const CertsArguments& args);

}  // namespace mcnc::tools
