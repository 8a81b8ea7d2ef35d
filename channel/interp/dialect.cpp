#include "channel/interp/dialect.hpp"

#include "common/config/dialect_names.hpp"

namespace mcnc::interp {

static_assert(config::kDialectNames.size() == static_cast<std::size_t>(Dialect::fanuc_mill) + 1,
              "one name per dialect, in the order of Dialect");

std::optional<Dialect> dialect_named(std::string_view name) {
  const std::string_view canonical = config::canonical_dialect_name(name);
  for (std::size_t i = 0; i < config::kDialectNames.size(); ++i) {
    if (!canonical.empty() && config::kDialectNames[i] == canonical) {
      return static_cast<Dialect>(i);
    }
  }
  return std::nullopt;
}

std::string_view dialect_name(Dialect d) {
  return config::kDialectNames[static_cast<std::size_t>(d)];
}

std::vector<AxisConfig> mill_axes() {
  return {AxisConfig{'X', false}, AxisConfig{'Y', false}, AxisConfig{'Z', false}};
}

void select_dialect(InterpreterConfig& c, Dialect d) {
  c.dialect = d;
  if (d == Dialect::dafeng) {
    return;
  }
  c.macro.local_last = 33;
  c.macro.common_last = 199;
  c.macro.extended_common = false;
  c.macro.round_to_integer = true;
  if (d == Dialect::gsk) {
    c.macro.vacant_ordering = macro::VacantOrdering::kLiteralGskTable;
    return;
  }
  // The mill: G90/G91, G92 and G98/G99 as return levels are system B's spelling (gsk Part C).
  c.system = GCodeSystem::b;
  c.axes = mill_axes();
}

}  // namespace mcnc::interp
