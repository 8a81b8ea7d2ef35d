#pragma once
// `mcnc interp --param FILE`: the interpreter parameters as YAML (docs/canonical-commands.md,
// "Parameter file"). Unknown keys and bad values are errors naming the key.
#include "channel/interp/interp_config.hpp"

#include <stdexcept>
#include <string>

namespace mcnc::tools {

struct ParamError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Applies the file's settings on top of `config`; throws ParamError.
void load_interp_params(const std::string& path, interp::InterpreterConfig& config);

}  // namespace mcnc::tools
