#include "channel/interp/macro/variable_store.hpp"

#include "channel/interp/macro/macro_alarms.hpp"

#include <charconv>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string_view>
#include <system_error>
#include <utility>

namespace mcnc::interp::macro {

namespace {

constexpr std::int64_t kLastChannelNumber = 99 * VariableStore::kChannelStride + 999999;

void fill_null(std::vector<MacroValue>& v, std::size_t first, std::size_t count) {
  for (std::size_t i = first; i < first + count && i < v.size(); ++i) {
    v[i] = MacroValue::null();
  }
}

long long as_ll(std::int64_t n) {
  return static_cast<long long>(n);
}

}  // namespace

MacroAlarm VariableProvider::write(std::int64_t number, MacroValue /*value*/) {
  return make_alarm(alarm::kReadOnlyVariable, 0, "variable #%lld is read-only", as_ll(number));
}

VariableRead MathConstantsProvider::read(std::int64_t number) const {
  return VariableRead{MacroValue::of(number == kFirst ? std::numbers::pi : std::numbers::e), {}};
}

VariableStore::VariableStore(MacroDialect dialect)
    : dialect_(dialect),
      locals_(static_cast<std::size_t>(dialect.max_call_levels + 1) *
              static_cast<std::size_t>(dialect.local_last)),
      commons_(static_cast<std::size_t>(dialect.common_last - kCommonFirst + 1)),
      retained_(static_cast<std::size_t>(kRetainedLast - kRetainedFirst + 1)),
      extended_(dialect.extended_common
                    ? static_cast<std::size_t>(kExtendedLast - kExtendedFirst + 1)
                    : 0) {}

std::int64_t VariableStore::own_number(std::int64_t number) const {
  // #aa bbbbbb with aa = this channel is the plain #bbbbbb (dafeng L6431-6433).
  // Another channel's #500-#999 or #20000-#20999 are the same machine-wide variables.
  if (number >= kChannelStride && number <= kLastChannelNumber &&
      (number / kChannelStride == dialect_.channel || is_shared(number % kChannelStride))) {
    return number % kChannelStride;
  }
  return number;
}

MacroValue* VariableStore::slot(std::int64_t n) {
  return const_cast<MacroValue*>(std::as_const(*this).slot(n));
}

const MacroValue* VariableStore::slot(std::int64_t n) const {
  if (n >= 1 && n <= dialect_.local_last) {
    return &locals_[static_cast<std::size_t>(level_ * dialect_.local_last + n - 1)];
  }
  if (n >= kCommonFirst && n <= dialect_.common_last) {
    return &commons_[static_cast<std::size_t>(n - kCommonFirst)];
  }
  if (n >= kRetainedFirst && n <= kRetainedLast) {
    return &retained_[static_cast<std::size_t>(n - kRetainedFirst)];
  }
  if (dialect_.extended_common && n >= kExtendedFirst && n <= kExtendedLast) {
    return &extended_[static_cast<std::size_t>(n - kExtendedFirst)];
  }
  return nullptr;
}

const VariableStore::ProviderRange* VariableStore::provider_for(std::int64_t n) const {
  for (const ProviderRange& p : providers_) {
    if (n >= p.first && n <= p.last) {
      return &p;
    }
  }
  return nullptr;
}

VariableRead VariableStore::read(std::int64_t number) const {
  const std::int64_t n = own_number(number);
  if (n == 0) {
    return {};
  }
  if (shared_ != nullptr && is_shared(n)) {
    return shared_->read(n);
  }
  if (const MacroValue* v = n > 0 ? slot(n) : nullptr) {
    return VariableRead{*v, {}};
  }
  if (const ProviderRange* p = n > 0 ? provider_for(n) : nullptr) {
    return p->provider->read(n);
  }
  return VariableRead{
      {}, make_alarm(alarm::kUndefinedVariable, 0, "variable #%lld does not exist", as_ll(number))};
}

MacroAlarm VariableStore::write(std::int64_t number, MacroValue value) {
  const std::int64_t n = own_number(number);
  if (n == 0) {
    return make_alarm(alarm::kReadOnlyVariable, 0, "#0 is read-only (it is always null)");
  }
  if (shared_ != nullptr && is_shared(n)) {
    const MacroAlarm a = shared_->write(n, value);
    if (a.number == 0 && sink_ != nullptr) {
      sink_->on_shared_write(n, value);
    }
    return a;
  }
  if (MacroValue* v = n > 0 ? slot(n) : nullptr) {
    *v = value;
    return {};
  }
  if (const ProviderRange* p = n > 0 ? provider_for(n) : nullptr) {
    if (p->writable != nullptr) {
      return p->writable->write(n, value);
    }
    return make_alarm(alarm::kReadOnlyVariable, 0, "variable #%lld is read-only", as_ll(number));
  }
  return make_alarm(alarm::kUndefinedVariable, 0, "variable #%lld does not exist", as_ll(number));
}

MacroAlarm VariableStore::push_level() {
  if (level_ >= dialect_.max_call_levels) {
    return make_alarm(alarm::kCallLevelTooDeep, 0, "more than %d nested macro call levels",
                      dialect_.max_call_levels);
  }
  ++level_;
  fill_null(locals_, static_cast<std::size_t>(level_ * dialect_.local_last),
            static_cast<std::size_t>(dialect_.local_last));
  return {};
}

MacroAlarm VariableStore::pop_level() {
  if (level_ == 0) {
    return make_alarm(alarm::kNoCallLevel, 0, "no macro call level to return from");
  }
  --level_;
  return {};
}

void VariableStore::reset() {
  level_ = 0;
  fill_null(locals_, 0, locals_.size());
  if (dialect_.commons_cleared_by_reset) {
    fill_null(commons_, 0, commons_.size());
  }
}

void VariableStore::power_on() {
  level_ = 0;
  fill_null(locals_, 0, locals_.size());
  fill_null(commons_, 0, commons_.size());
  fill_null(extended_, 0, extended_.size());
}

MacroAlarm VariableStore::add_provider(std::int64_t first, std::int64_t last,
                                       const VariableProvider& provider) {
  const auto overlaps = [&](std::int64_t a, std::int64_t b) { return first <= b && a <= last; };
  if (first < 1 || last < first) {
    return make_alarm(alarm::kProviderOverlap, 0, "provider range #%lld-#%lld is empty",
                      as_ll(first), as_ll(last));
  }
  if (overlaps(0, kRetainedLast) ||
      (dialect_.extended_common && overlaps(kExtendedFirst, kExtendedLast))) {
    return make_alarm(alarm::kProviderOverlap, 0,
                      "provider range #%lld-#%lld overlaps the store's variables", as_ll(first),
                      as_ll(last));
  }
  for (const ProviderRange& p : providers_) {
    if (overlaps(p.first, p.last)) {
      return make_alarm(alarm::kProviderOverlap, 0,
                        "provider range #%lld-#%lld overlaps #%lld-#%lld", as_ll(first),
                        as_ll(last), as_ll(p.first), as_ll(p.last));
    }
  }
  providers_.push_back(ProviderRange{first, last, &provider, nullptr});
  return {};
}

MacroAlarm VariableStore::add_writable_provider(std::int64_t first, std::int64_t last,
                                                VariableProvider& provider) {
  MacroAlarm a = add_provider(first, last, provider);
  if (!a) {
    providers_.back().writable = &provider;
  }
  return a;
}

void VariableStore::save_retained(std::ostream& out) const {
  for (std::size_t i = 0; i < retained_.size(); ++i) {
    if (retained_[i].is_null()) {
      continue;
    }
    // to_chars gives the shortest text that reads back to the same double, locale-free.
    char buf[64];
    const auto res = std::to_chars(buf, buf + sizeof buf, retained_[i].number());
    out << '#' << (kRetainedFirst + static_cast<std::int64_t>(i)) << '='
        << std::string_view(buf, static_cast<std::size_t>(res.ptr - buf)) << '\n';
  }
}

MacroAlarm VariableStore::load_retained(std::istream& in) {
  std::vector<MacroValue> loaded(retained_.size());
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    std::string_view s(line);
    while (!s.empty() && (s.back() == '\r' || s.back() == ' ' || s.back() == '\t')) {
      s.remove_suffix(1);
    }
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) {
      s.remove_prefix(1);
    }
    if (s.empty()) {
      continue;
    }
    const auto bad = [&](const char* why) {
      return make_alarm(alarm::kRetainedFileFormat, 0, "retained variables, line %d: %s",
                        line_number, why);
    };
    const std::size_t eq = s.find('=');
    if (s.front() != '#' || eq == std::string_view::npos) {
      return bad("expected #n=value");
    }
    std::int64_t number = 0;
    const auto num = std::from_chars(s.data() + 1, s.data() + eq, number);
    if (num.ec != std::errc() || num.ptr != s.data() + eq) {
      return bad("expected #n=value");
    }
    if (number < kRetainedFirst || number > kRetainedLast) {
      return bad("variable outside #500-#999");
    }
    double value = 0.0;
    const auto val = std::from_chars(s.data() + eq + 1, s.data() + s.size(), value);
    if (val.ec != std::errc() || val.ptr != s.data() + s.size()) {
      return bad("value is not a number");
    }
    loaded[static_cast<std::size_t>(number - kRetainedFirst)] = MacroValue::of(value);
  }
  if (in.bad()) {
    return make_alarm(alarm::kRetainedFileIo, 0, "retained variables could not be read");
  }
  retained_ = std::move(loaded);
  return {};
}

MacroAlarm VariableStore::save_retained_file(const std::string& path) const {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::trunc);
    if (!out) {
      return make_alarm(alarm::kRetainedFileIo, 0, "cannot write %s", temporary.c_str());
    }
    save_retained(out);
    out.flush();
    if (!out) {
      return make_alarm(alarm::kRetainedFileIo, 0, "cannot write %s", temporary.c_str());
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    return make_alarm(alarm::kRetainedFileIo, 0, "cannot replace %s", path.c_str());
  }
  return {};
}

MacroAlarm VariableStore::load_retained_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    return make_alarm(alarm::kRetainedFileIo, 0, "cannot read %s", path.c_str());
  }
  return load_retained(in);
}

}  // namespace mcnc::interp::macro
