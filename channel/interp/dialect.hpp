#pragma once
// Choosing a dialect: its name (common/config/dialect_names.hpp) and what it sets beside the G
// table: the G-code system, the macro variables' ranges and, for the mill, its axes.
#include "channel/interp/interp_config.hpp"

#include <optional>
#include <string_view>

namespace mcnc::interp {

// By its name or an alias (config::kDialectAliases: `fanuc-lathe` is the Dafeng dialect).
std::optional<Dialect> dialect_named(std::string_view name);
std::string_view dialect_name(Dialect d);

// Sets `c.dialect` and the settings that come with it: GSK and the mill take FANUC's macro
// ranges (#1-#33, #100-#199) and ROUND to a whole number; the mill programs X, Y and Z
// (`mill_axes`, unless the caller gives its own axes afterwards) in G-code system B's
// spelling (G90/G91, G92, G98/G99 as return levels).
void select_dialect(InterpreterConfig& c, Dialect d);

// The mill dialect's channel axes when none are configured: X, Y, Z, none a diameter.
std::vector<AxisConfig> mill_axes();

}  // namespace mcnc::interp
