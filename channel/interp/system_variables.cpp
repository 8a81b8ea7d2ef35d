// The system variables of spec dafeng §4.1 that the interpreter itself holds: tool offsets
// (#2001-#2964, #10001-#19064), timers (#3001/#3002), date and time (#3011/#3012), part
// counters (#3901/#3902), modal information (#4000-#4330), positions (#5001-#5200) and work
// offsets (#5201-#5340, #7001-#7999). #3000 and #3006 are statements (program_run.cpp).
#include "channel/interp/macro/macro_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <span>

namespace mcnc::interp {

namespace {

using macro::MacroAlarm;
using macro::MacroValue;
using macro::VariableRead;

enum class ToolField : std::uint8_t { x, z, y, radius, tip };

struct ToolVariable {
  bool found = false;
  bool geometry = false;
  ToolField field = ToolField::x;
  int offset = 0;
};

struct ToolRange {
  std::int64_t first;
  int count;
  bool geometry;
  ToolField field;
};

// The mill's H and D values (FANUC 0i-M, tool compensation memory C): #10001+ H wear, #11001+
// H geometry, #12001+ D wear, #13001+ D geometry; H is the table's Z, D its radius.
constexpr ToolRange kMillRanges[] = {
    {10001, 64, false, ToolField::z},
    {11001, 64, true, ToolField::z},
    {12001, 64, false, ToolField::radius},
    {13001, 64, true, ToolField::radius},
};

// #2001-#2964 (64 offsets; Y only 49) and the extended #10001-#19064 (spec L6520-6656); the
// mill's kMillRanges.
ToolVariable tool_variable(std::int64_t n, Dialect dialect) {
  static constexpr ToolRange kRanges[] = {
      {2001, 64, false, ToolField::x},      {2101, 64, false, ToolField::z},
      {2201, 64, false, ToolField::radius}, {2301, 64, true, ToolField::tip},
      {2401, 49, false, ToolField::y},      {2451, 49, true, ToolField::y},
      {2701, 64, true, ToolField::x},       {2801, 64, true, ToolField::z},
      {2901, 64, true, ToolField::radius},  {10001, 64, false, ToolField::x},
      {11001, 64, false, ToolField::z},     {12001, 64, false, ToolField::radius},
      {13001, 64, true, ToolField::tip},    {14001, 64, false, ToolField::y},
      {15001, 64, true, ToolField::x},      {16001, 64, true, ToolField::z},
      {17001, 64, true, ToolField::radius}, {19001, 64, true, ToolField::y},
  };
  for (const ToolRange& r : dialect == Dialect::fanuc_mill ? std::span<const ToolRange>(kMillRanges)
                                                           : std::span<const ToolRange>(kRanges)) {
    if (n >= r.first && n < r.first + r.count) {
      return ToolVariable{true, r.geometry, r.field, static_cast<int>(n - r.first) + 1};
    }
  }
  return {};
}

double* tool_slot(ToolOffsetValues& t, ToolField f) {
  switch (f) {
    case ToolField::x:
      return &t.x;
    case ToolField::z:
      return &t.z;
    case ToolField::y:
      return &t.y;
    case ToolField::radius:
      return &t.radius;
    case ToolField::tip:
      return nullptr;
  }
  return nullptr;
}

VariableRead value(double v) {
  return VariableRead{MacroValue::of(v), {}};
}

VariableRead undefined(std::int64_t n) {
  return VariableRead{
      {},
      macro::make_alarm(macro::alarm::kUndefinedVariable, 0, "variable #%lld does not exist",
                        static_cast<long long>(n))};
}

}  // namespace

VariableRead ProgramRun::read(std::int64_t n) const {
  const int axes = static_cast<int>(config_.axes.size());
  if (const ToolVariable tv = tool_variable(n, config_.dialect); tv.found) {
    const ToolOffsetValues& t = tools_.values(tv.geometry, tv.offset);
    if (tv.field == ToolField::tip) {
      return value(t.tip);
    }
    return value(tv.field == ToolField::x   ? t.x
                 : tv.field == ToolField::z ? t.z
                 : tv.field == ToolField::y ? t.y
                                            : t.radius);
  }
  switch (n) {
    case 3000:
    case 3006:
      return VariableRead{};  // statements, not values
    case 3001:
      return value(environment_->milliseconds() - timer_ms_base_);
    case 3002:
      return value((environment_->milliseconds() - timer_hours_base_) / 3.6e6);
    case 3011:
      return value(environment_->date());
    case 3012:
      return value(environment_->time_of_day());
    case 3901:
      return value(parts_done_);
    case 3902:
      return value(parts_required_);
    case 4000:
      return value(main_number_);
    default:
      break;
  }
  // #4001-#4030 look-ahead modal state and #4201-#4230 the executing block's: the same for a
  // pull-based interpreter, whose last pulled block is the one executing.
  if ((n >= 4001 && n <= 4030) || (n >= 4201 && n <= 4230)) {
    // The mill numbers its groups as FANUC 0i-M does (#4002 the plane, #4009 the hole cycle).
    const int slot = config_.dialect == Dialect::fanuc_mill
                         ? mill_group_slot(static_cast<int>(n % 100))
                         : static_cast<int>(n % 100);
    return value(slot < 0 ? 0.0 : modal_.codes[static_cast<std::size_t>(slot)]);
  }
  if (n == 4109 || n == 4309) {
    return value(modal_.feed / (modal_.metric ? 1.0 : 25.4));
  }
  if (n == 4119 || n == 4319) {
    return value(spindles_.rpm[1]);
  }
  if (n == 4120 || n == 4320) {
    return value(tools_.t_value);
  }
  if (n == 4115) {
    const Frame& f = frames_.back();
    return value(f.program->number.value_or(0));
  }
  if (n >= 5001 && n <= 5200) {
    const int range = static_cast<int>((n - 5001) / 20);
    const int axis = static_cast<int>((n - 5001) % 20);
    if (axis >= axes) {
      return VariableRead{};  // no such axis in this channel: null
    }
    const auto i = static_cast<std::size_t>(axis);
    switch (range) {
      case 0:  // #5001: workpiece position at the end of the block
      case 2:  // #5041: current workpiece position (decision D20)
        return value(program_position(axis));
      case 1:  // #5021: machine position, in programmed units (X as a diameter)
        return value(machine_reading(i, machine()[i]));
      case 3:  // #5061: the last G31's skip position (null before the first)
        return skip_known_ ? value(skip_position_[i]) : VariableRead{};
      case 6:  // #5121: handwheel interrupt
      case 9:  // #5181: distance to go (the interpreter's position is the block end)
        return value(0.0);
      default:
        return undefined(n);
    }
  }
  if (n >= 5201 && n <= 5340) {
    const int system = static_cast<int>((n - 5201) / 20);  // 0 = EXT, 1-6 = G54-G59
    const int axis = static_cast<int>((n - 5201) % 20);
    if (axis >= axes) {
      return VariableRead{};
    }
    return value(physical_to_data(axis, coordinates_.offset(system, axis)));
  }
  if (n >= 7001 && n <= 7999) {
    const int set = static_cast<int>((n - 7001) / 20) + 1;  // G54.1 P1-P50
    const int axis = static_cast<int>((n - 7001) % 20);
    if (axis >= axes) {
      return VariableRead{};
    }
    return value(physical_to_data(axis, coordinates_.offset(6 + set, axis)));
  }
  return undefined(n);
}

MacroAlarm ProgramRun::write(std::int64_t n, MacroValue v) {
  const double x = v.number();
  if (const ToolVariable tv = tool_variable(n, config_.dialect); tv.found) {
    ToolOffsetValues& t = tools_.values(tv.geometry, tv.offset);
    if (tv.field == ToolField::tip) {
      t.tip = static_cast<int>(x);
    } else {
      *tool_slot(t, tv.field) = x;
    }
    return {};
  }
  switch (n) {
    case 3001:
      timer_ms_base_ = environment_->milliseconds() - x;
      return {};
    case 3002:
      timer_hours_base_ = environment_->milliseconds() - x * 3.6e6;
      return {};
    case 3901:
      parts_done_ = x;
      return {};
    case 3902:
      parts_required_ = x;
      return {};
    default:
      break;
  }
  if (n >= 5201 && n <= 5340) {
    const int system = static_cast<int>((n - 5201) / 20);
    const int axis = static_cast<int>((n - 5201) % 20);
    if (axis >= static_cast<int>(config_.axes.size())) {
      return macro::make_alarm(macro::alarm::kUndefinedVariable, 0,
                               "variable #%lld: channel %d has no axis %d",
                               static_cast<long long>(n), config_.channel, axis + 1);
    }
    coordinates_.offset(system, axis) = data_to_physical(axis, x);
    return {};
  }
  if (read(n).alarm) {
    return undefined(n).alarm;
  }
  return macro::make_alarm(macro::alarm::kReadOnlyVariable, 0, "variable #%lld is read-only",
                           static_cast<long long>(n));
}

double ProgramRun::machine_reading(std::size_t axis, double physical) const {
  const AxisConfig& a = config_.axes[axis];
  const double v = physical * (a.diameter ? 2.0 : 1.0);
  return !a.rotary && !modal_.metric ? v / 25.4 : v;
}

}  // namespace mcnc::interp
