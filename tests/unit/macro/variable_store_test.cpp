#include "channel/interp/macro/variable_store.hpp"
#include "channel/interp/macro/macro_alarms.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace mcnc::interp::macro {
namespace {

MacroValue v(double x) {
  return MacroValue::of(x);
}

MacroValue read_ok(const VariableStore& s, std::int64_t n) {
  const VariableRead r = s.read(n);
  EXPECT_FALSE(r.alarm) << "#" << n << ": " << r.alarm.text();
  return r.value;
}

MacroDialect gsk() {
  MacroDialect d;
  d.local_last = 33;
  d.common_last = 199;
  d.extended_common = false;
  return d;
}

TEST(VariableStore, EveryVariableStartsNull) {
  const VariableStore s;
  for (std::int64_t n : {0, 1, 99, 100, 499, 500, 999, 20000, 20999}) {
    EXPECT_TRUE(read_ok(s, n).is_null()) << n;
  }
}

TEST(VariableStore, ReadsBackWhatIsWrittenInEveryRange) {
  VariableStore s;
  for (std::int64_t n : {1, 99, 100, 499, 500, 999, 20000, 20999}) {
    EXPECT_FALSE(s.write(n, v(static_cast<double>(n) + 0.5)));
    EXPECT_EQ(read_ok(s, n), v(static_cast<double>(n) + 0.5));
  }
  // Assigning null makes the variable null again (dafeng L6447-6449).
  EXPECT_FALSE(s.write(100, MacroValue::null()));
  EXPECT_TRUE(read_ok(s, 100).is_null());
}

TEST(VariableStore, NullVariableIsReadOnly) {
  VariableStore s;
  const MacroAlarm a = s.write(0, v(5));
  EXPECT_EQ(a.number, alarm::kReadOnlyVariable);
  EXPECT_EQ(a.text(), "#0 is read-only (it is always null)");
  EXPECT_TRUE(read_ok(s, 0).is_null());
}

TEST(VariableStore, UndefinedNumbersAlarmOnReadAndWrite) {
  VariableStore s;
  for (std::int64_t n : {-1, 1000, 3101, 5001, 19999, 21000, 100000000}) {
    const VariableRead r = s.read(n);
    EXPECT_EQ(r.alarm.number, alarm::kUndefinedVariable) << n;
    EXPECT_EQ(s.write(n, v(1)).number, alarm::kUndefinedVariable) << n;
  }
  EXPECT_EQ(s.read(1000).alarm.text(), "variable #1000 does not exist");
}

TEST(VariableStore, GskDialectHasFanucRanges) {
  VariableStore s(gsk());
  EXPECT_FALSE(s.write(33, v(1)));
  EXPECT_FALSE(s.write(199, v(1)));
  EXPECT_EQ(s.write(34, v(1)).number, alarm::kUndefinedVariable);
  EXPECT_EQ(s.write(200, v(1)).number, alarm::kUndefinedVariable);
  EXPECT_EQ(s.read(250).alarm.number, alarm::kUndefinedVariable);
  EXPECT_EQ(s.read(20000).alarm.number, alarm::kUndefinedVariable);
  EXPECT_FALSE(s.write(995, v(1)));  // G31 writes #995-#999 through the store later
}

// Dafeng L6478-6486, gsk A.7.3: G65/G66 start a level of null locals; commons are shared.
TEST(VariableStore, LocalFramesAcrossPushAndPop) {
  VariableStore s;
  ASSERT_FALSE(s.write(1, v(5)));
  ASSERT_FALSE(s.write(99, v(6)));
  ASSERT_FALSE(s.write(100, v(7)));
  ASSERT_FALSE(s.push_level());
  EXPECT_EQ(s.level(), 1);
  EXPECT_TRUE(read_ok(s, 1).is_null());
  EXPECT_TRUE(read_ok(s, 99).is_null());
  EXPECT_EQ(read_ok(s, 100), v(7));
  ASSERT_FALSE(s.write(1, v(10)));
  ASSERT_FALSE(s.write(100, v(8)));
  ASSERT_FALSE(s.push_level());
  EXPECT_TRUE(read_ok(s, 1).is_null());
  ASSERT_FALSE(s.write(1, v(20)));
  ASSERT_FALSE(s.pop_level());
  EXPECT_EQ(read_ok(s, 1), v(10));
  ASSERT_FALSE(s.pop_level());
  EXPECT_EQ(s.level(), 0);
  EXPECT_EQ(read_ok(s, 1), v(5));
  EXPECT_EQ(read_ok(s, 99), v(6));
  EXPECT_EQ(read_ok(s, 100), v(8));
  // A level pushed again starts null, not with the values of the level popped before.
  ASSERT_FALSE(s.push_level());
  EXPECT_TRUE(read_ok(s, 1).is_null());
}

TEST(VariableStore, CallLevelLimits) {
  MacroDialect d;
  d.max_call_levels = 2;
  VariableStore s(d);
  EXPECT_EQ(s.pop_level().number, alarm::kNoCallLevel);
  EXPECT_FALSE(s.push_level());
  EXPECT_FALSE(s.push_level());
  const MacroAlarm a = s.push_level();
  EXPECT_EQ(a.number, alarm::kCallLevelTooDeep);
  EXPECT_EQ(a.text(), "more than 2 nested macro call levels");
  EXPECT_EQ(s.level(), 2);
}

TEST(VariableStore, ResetClearsLocalsAndKeepsCommons) {
  VariableStore s;
  s.write(1, v(1));
  s.write(100, v(2));
  s.write(500, v(3));
  s.write(20000, v(4));
  s.push_level();
  s.write(1, v(5));
  s.reset();
  EXPECT_EQ(s.level(), 0);
  EXPECT_TRUE(read_ok(s, 1).is_null());
  EXPECT_EQ(read_ok(s, 100), v(2));
  EXPECT_EQ(read_ok(s, 500), v(3));
  EXPECT_EQ(read_ok(s, 20000), v(4));
}

TEST(VariableStore, ResetClearsCommonsWhenTheDialectSaysSo) {
  MacroDialect d;
  d.commons_cleared_by_reset = true;
  VariableStore s(d);
  s.write(100, v(2));
  s.write(500, v(3));
  s.reset();
  EXPECT_TRUE(read_ok(s, 100).is_null());
  EXPECT_EQ(read_ok(s, 500), v(3));
}

// Dafeng L6488-6497, decision D25, gsk D3-10: power-on leaves only #500-#999.
TEST(VariableStore, PowerOnKeepsOnlyRetained) {
  VariableStore s;
  s.write(1, v(1));
  s.write(100, v(2));
  s.write(499, v(2));
  s.write(500, v(3));
  s.write(999, v(3));
  s.write(20000, v(4));
  s.push_level();
  s.power_on();
  EXPECT_EQ(s.level(), 0);
  EXPECT_TRUE(read_ok(s, 1).is_null());
  EXPECT_TRUE(read_ok(s, 100).is_null());
  EXPECT_TRUE(read_ok(s, 499).is_null());
  EXPECT_TRUE(read_ok(s, 20000).is_null());
  EXPECT_EQ(read_ok(s, 500), v(3));
  EXPECT_EQ(read_ok(s, 999), v(3));
}

// Dafeng L6431-6433, decision D26: #aa bbbbbb = aa * 1000000 + bbbbbb.
TEST(VariableStore, ChannelQualifiedNumbers) {
  MacroDialect d;
  d.channel = 2;
  VariableStore s(d);
  ASSERT_FALSE(s.write(2000500, v(42)));  // own channel: plain #500
  EXPECT_EQ(read_ok(s, 500), v(42));
  EXPECT_EQ(read_ok(s, 2000001), read_ok(s, 1));
  EXPECT_EQ(s.write(2000000, v(1)).number, alarm::kReadOnlyVariable);  // #0 of channel 2
  EXPECT_EQ(s.read(1000100).alarm.number, alarm::kUndefinedVariable);  // channel 1: no provider
  // #500-#999 and #20000-#20999 are the machine's: channel 1's #500 is this #500.
  EXPECT_EQ(read_ok(s, 1000500), v(42));
}

class FixedProvider final : public VariableProvider {
 public:
  VariableRead read(std::int64_t number) const override {
    if (number == 5021) {
      return VariableRead{{}, make_alarm(1, 0, "not readable while moving")};
    }
    return VariableRead{MacroValue::of(static_cast<double>(number) * 2), {}};
  }
};

TEST(VariableStore, ProvidersServeReadOnlyRanges) {
  VariableStore s;
  const FixedProvider positions;
  ASSERT_FALSE(s.add_provider(5001, 5100, positions));
  EXPECT_EQ(read_ok(s, 5001), v(10002));
  EXPECT_EQ(s.read(5021).alarm.text(), "not readable while moving");
  const MacroAlarm w = s.write(5001, v(1));
  EXPECT_EQ(w.number, alarm::kReadOnlyVariable);
  EXPECT_EQ(w.text(), "variable #5001 is read-only");
  EXPECT_EQ(s.read(5101).alarm.number, alarm::kUndefinedVariable);

  const MathConstantsProvider constants;
  ASSERT_FALSE(
      s.add_provider(MathConstantsProvider::kFirst, MathConstantsProvider::kLast, constants));
  EXPECT_EQ(read_ok(s, 3101), v(std::numbers::pi));  // dafeng L6569
  EXPECT_EQ(read_ok(s, 3102), v(std::numbers::e));   // dafeng L6571

  // Another channel's variables arrive through a provider for its number range.
  const FixedProvider channel3;
  ASSERT_FALSE(s.add_provider(3000000, 3999999, channel3));
  EXPECT_EQ(read_ok(s, 3000100), v(6000200));
}

TEST(VariableStore, ProviderRangesMayNotOverlap) {
  VariableStore s;
  const FixedProvider p;
  EXPECT_EQ(s.add_provider(900, 1100, p).number, alarm::kProviderOverlap);
  EXPECT_EQ(s.add_provider(20500, 20600, p).number, alarm::kProviderOverlap);
  EXPECT_EQ(s.add_provider(10, 5, p).number, alarm::kProviderOverlap);
  ASSERT_FALSE(s.add_provider(1000, 1100, p));
  EXPECT_EQ(s.add_provider(1100, 1200, p).number, alarm::kProviderOverlap);
  EXPECT_FALSE(s.add_provider(1101, 1200, p));
  VariableStore g(gsk());
  EXPECT_FALSE(g.add_provider(20000, 20999, p));  // free when the dialect has no #20000
}

TEST(VariableStore, RetainedSaveLoadRoundTrip) {
  VariableStore s;
  s.write(500, v(1.5));
  s.write(501, v(0.1));
  s.write(777, v(-123456.789012345));
  s.write(998, v(1e-30));
  s.write(999, v(0));
  s.write(100, v(9));  // not retained: not saved
  std::stringstream file;
  s.save_retained(file);
  EXPECT_EQ(file.str(), "#500=1.5\n#501=0.1\n#777=-123456.789012345\n#998=1e-30\n#999=0\n");

  VariableStore t;
  t.write(600, v(3));  // absent from the file: null after the load
  ASSERT_FALSE(t.load_retained(file));
  for (std::int64_t n = 500; n <= 999; ++n) {
    EXPECT_EQ(read_ok(t, n), read_ok(s, n)) << n;
  }
  EXPECT_TRUE(read_ok(t, 100).is_null());
}

TEST(VariableStore, RetainedLoadRejectsBadLinesAndChangesNothing) {
  const char* bad[] = {"#500=abc\n", "500=1\n", "#499=1\n",  "#1000=1\n",
                       "#5x0=1\n",   "#500\n",  "#500=1 2\n"};
  for (const char* text : bad) {
    VariableStore s;
    s.write(500, v(7));
    std::stringstream in(std::string("#501=2\n\n") + text);
    const MacroAlarm a = s.load_retained(in);
    EXPECT_EQ(a.number, alarm::kRetainedFileFormat) << text;
    EXPECT_EQ(a.text().substr(0, 27), "retained variables, line 3:") << text;
    EXPECT_EQ(read_ok(s, 500), v(7));
    EXPECT_TRUE(read_ok(s, 501).is_null());
  }
  VariableStore s;
  std::stringstream crlf("  #500=2.5\r\n");
  EXPECT_FALSE(s.load_retained(crlf));
  EXPECT_EQ(read_ok(s, 500), v(2.5));
}

TEST(VariableStore, RetainedFileRoundTrip) {
  const auto dir =
      std::filesystem::temp_directory_path() /
      ("mcnc_macro_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "retained.txt").string();
  VariableStore s;
  s.write(512, v(3.25));
  ASSERT_FALSE(s.save_retained_file(path));
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  s.write(512, v(4));
  ASSERT_FALSE(s.save_retained_file(path));  // replaces the file
  VariableStore t;
  ASSERT_FALSE(t.load_retained_file(path));
  EXPECT_EQ(read_ok(t, 512), v(4));
  EXPECT_EQ(t.load_retained_file((dir / "missing.txt").string()).number, alarm::kRetainedFileIo);
  EXPECT_EQ(s.save_retained_file((dir / "no" / "such" / "dir.txt").string()).number,
            alarm::kRetainedFileIo);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace mcnc::interp::macro

namespace mcnc::interp::macro {
namespace {

struct RecordingSink final : SharedWriteSink {
  void on_shared_write(std::int64_t number, MacroValue value) noexcept override {
    writes.emplace_back(number, value);
  }
  std::vector<std::pair<std::int64_t, MacroValue>> writes;
};

TEST(VariableStore, SharedVariablesAreTheMachinesAndEveryWriteIsTold) {
  VariableStore machine;  // the machine-wide copy
  RecordingSink sink;
  MacroDialect ch2_dialect;
  ch2_dialect.channel = 2;
  VariableStore ch1;
  VariableStore ch2(ch2_dialect);
  ch1.share(&machine, &sink);
  ch2.share(&machine, nullptr);
  ASSERT_EQ(ch1.write(500, v(7.0)).number, 0);
  ASSERT_EQ(ch1.write(20000, v(3.0)).number, 0);
  ASSERT_EQ(ch1.write(100, v(1.0)).number, 0);  // a common: the channel's own
  EXPECT_EQ(read_ok(ch2, 500), v(7.0));
  EXPECT_EQ(read_ok(ch2, 20000), v(3.0));
  EXPECT_TRUE(read_ok(ch2, 100).is_null());
  EXPECT_EQ(read_ok(machine, 500), v(7.0));
  // Only the shared ones are told, in order.
  ASSERT_EQ(sink.writes.size(), 2U);
  EXPECT_EQ(sink.writes[0].first, 500);
  EXPECT_EQ(sink.writes[1].first, 20000);
  // #aa bbbbbb: channel 1's #501 seen from channel 2 is the same #501.
  ASSERT_EQ(ch1.write(1000501, v(4.5)).number, 0);
  EXPECT_EQ(read_ok(ch2, 501), v(4.5));
  EXPECT_EQ(read_ok(ch2, 2000501), v(4.5));
  // A reset or power cycle of one channel leaves the machine's variables alone.
  ch2.reset();
  ch2.power_on();
  EXPECT_EQ(read_ok(ch1, 20000), v(3.0));
  EXPECT_EQ(read_ok(ch1, 500), v(7.0));
  // Null travels too.
  ASSERT_EQ(ch2.write(500, MacroValue::null()).number, 0);
  EXPECT_TRUE(read_ok(ch1, 500).is_null());
}

}  // namespace
}  // namespace mcnc::interp::macro
