#pragma once
// The macro variables of one channel (spec dafeng §4.1, gsk B.4):
//   #0                 null, read-only;
//   #1-#99             local, one frame per call level (G65/G66 push one, M98 shares the
//                      caller's); null when the level starts. GSK/FANUC: #1-#33 (local_last);
//   #100-#499          common, null at power-on, kept by reset unless the dialect says
//                      otherwise. GSK/FANUC: #100-#199 (common_last);
//   #500-#999          retained: kept across power-off through save_retained/load_retained;
//   #20000-#20999      extended common (Dafeng): like #100-#499 but volatile through power-off
//                      only (decision D25); shared between channels by the runtime later;
//   #aa bbbbbb         aa = 1..99 (numbers 1 000 000 and up, decision D26): the own channel's
//                      aa maps to #bbbbbb, other channels only through a provider;
//   anything else      through registered read-only providers (system variables), else an
//                      alarm for reads and writes alike.
// Reads and writes do not allocate and do not throw; alarms carry column 0 (the evaluator
// fills in the column of the reference).
#include "channel/interp/macro/macro_value.hpp"

#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

namespace mcnc::interp::macro {

struct MacroDialect {
  int local_last = 99;          // Dafeng L6478; GSK/FANUC 33
  int common_last = 499;        // Dafeng L6488; GSK/FANUC 199
  bool extended_common = true;  // #20000-#20999 (Dafeng L6658)
  // Dafeng and GSK clear commons at power-on only; FANUC-style controls may clear them on reset.
  bool commons_cleared_by_reset = false;
  int max_call_levels = 16;  // local levels above the main program (M98 nests 16, L6335)
  VacantOrdering vacant_ordering = VacantOrdering::kAsZero;
  // ROUND[x]: Dafeng rounds to 3 decimals (D16); FANUC/GSK to a whole number, halves away from 0.
  bool round_to_integer = false;
  int channel = 1;  // the value of CHN and the own channel of #aa bbbbbb
};

struct VariableRead {
  MacroValue value;
  MacroAlarm alarm;
};

// A read-only range of variables the store does not hold itself (positions, modal state...).
// A provider may refuse a read with an alarm (e.g. a position not readable while moving).
class VariableProvider {
 public:
  virtual ~VariableProvider() = default;
  virtual VariableRead read(std::int64_t number) const = 0;
  // Only called for ranges registered with add_writable_provider.
  virtual MacroAlarm write(std::int64_t number, MacroValue value);
};

// #3101 = π and #3102 = e (dafeng L6569-6571), ready to register.
class MathConstantsProvider final : public VariableProvider {
 public:
  static constexpr std::int64_t kFirst = 3101;
  static constexpr std::int64_t kLast = 3102;
  VariableRead read(std::int64_t number) const override;
};

// Told of every write a channel makes to the variables it shares with the other channels, so
// that they can be sent to them (ARCHITECTURE.md §5). Called from the interpreter: no
// allocation, no exceptions.
class SharedWriteSink {
 public:
  virtual ~SharedWriteSink() = default;
  virtual void on_shared_write(std::int64_t number, MacroValue value) noexcept = 0;
};

class VariableStore {
 public:
  static constexpr std::int64_t kCommonFirst = 100;
  static constexpr std::int64_t kRetainedFirst = 500;
  static constexpr std::int64_t kRetainedLast = 999;
  static constexpr std::int64_t kExtendedFirst = 20000;
  static constexpr std::int64_t kExtendedLast = 20999;
  static constexpr std::int64_t kChannelStride = 1000000;  // #aa bbbbbb

  explicit VariableStore(MacroDialect dialect = {});

  const MacroDialect& dialect() const { return dialect_; }

  VariableRead read(std::int64_t number) const;
  MacroAlarm write(std::int64_t number, MacroValue value);

  // Call levels: 0 is the main program. push_level starts a level with null locals.
  MacroAlarm push_level();
  MacroAlarm pop_level();
  int level() const { return level_; }

  // NC reset / program end: back to the main level with null locals; commons kept unless the
  // dialect clears them.
  void reset();
  // Power cycle: everything null except #500-#999.
  void power_on();

  // From now on #500-#999 and #20000-#20999 are those of `shared` (not owned; the machine-wide
  // copy this channel keeps, which outlives this store), and every write to them is also told
  // to `sink` (may be null). reset() and power_on() leave them alone: they belong to the
  // machine.
  void share(VariableStore* shared, SharedWriteSink* sink) noexcept {
    shared_ = shared;
    sink_ = sink;
  }
  [[nodiscard]] static bool is_shared(std::int64_t number) noexcept {
    return (number >= kRetainedFirst && number <= kRetainedLast) ||
           (number >= kExtendedFirst && number <= kExtendedLast);
  }

  // Registers `provider` (not owned; it must outlive the store) for [first, last]. The range may
  // not overlap #0-#999, #20000-#20999 or another provider.
  MacroAlarm add_provider(std::int64_t first, std::int64_t last, const VariableProvider& provider);
  // The same for a range whose variables may also be written (offsets, timers...).
  MacroAlarm add_writable_provider(std::int64_t first, std::int64_t last,
                                   VariableProvider& provider);

  // #500-#999 as text, one `#n=value` line per non-null variable, in number order; values
  // round-trip exactly. load replaces all of #500-#999 (absent = null) or, on an alarm, none.
  void save_retained(std::ostream& out) const;
  MacroAlarm load_retained(std::istream& in);
  // File forms: save writes a temporary file next to `path` and renames it over `path`, so a
  // crash leaves the old or the new file, never half of one.
  MacroAlarm save_retained_file(const std::string& path) const;
  MacroAlarm load_retained_file(const std::string& path);

 private:
  struct ProviderRange {
    std::int64_t first;
    std::int64_t last;
    const VariableProvider* provider;
    VariableProvider* writable;  // nullptr: read-only
  };
  // The slot of a variable the store holds (number already mapped by own_number), or nullptr.
  MacroValue* slot(std::int64_t number);
  const MacroValue* slot(std::int64_t number) const;
  const ProviderRange* provider_for(std::int64_t number) const;
  std::int64_t own_number(std::int64_t number) const;

  MacroDialect dialect_;
  int level_ = 0;
  std::vector<MacroValue> locals_;  // (max_call_levels + 1) frames of local_last values
  std::vector<MacroValue> commons_;
  std::vector<MacroValue> retained_;
  std::vector<MacroValue> extended_;
  std::vector<ProviderRange> providers_;
  VariableStore* shared_ = nullptr;
  SharedWriteSink* sink_ = nullptr;
};

}  // namespace mcnc::interp::macro
