#include "channel/interp/output/command_json.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string_view>

namespace mcnc::interp::output {

namespace {

// One JSON object built in a local buffer and appended to the caller's string in a few pieces
// (flush() at its end): std::string's append costs more than the few bytes of most pieces. A
// piece longer than the buffer (a long message) goes straight through. The fast paths are small
// enough to be inlined, so that the pieces of known length are copied without a library call.
class Writer {
 public:
  explicit Writer(std::string& text) : text_(text) {}
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  Writer& operator+=(char c) {
    if (used_ == kSize) {
      flush();
    }
    buffer_[used_++] = c;
    return *this;
  }
  Writer& operator+=(std::string_view s) {
    append(s.data(), s.size());
    return *this;
  }
  Writer& operator+=(const char* s) { return *this += std::string_view(s); }
  Writer& operator+=(const std::string& s) { return *this += std::string_view(s); }
  [[gnu::always_inline]] void append(const char* s, std::size_t n) {
    if (n <= kSize - used_) {
      std::memcpy(buffer_.data() + used_, s, n);
      used_ += n;
      return;
    }
    append_long(s, n);
  }
  void append(std::string_view s) { append(s.data(), s.size()); }
  void append(const char* begin, const char* end) {
    append(begin, static_cast<std::size_t>(end - begin));
  }
  // Room for `n` bytes written in place (n <= kSize), then taken with commit(end).
  char* room(std::size_t n) {
    if (n > kSize - used_) {
      flush();
    }
    return buffer_.data() + used_;
  }
  void commit(const char* end) { used_ = static_cast<std::size_t>(end - buffer_.data()); }
  void flush() {
    text_.append(buffer_.data(), used_);
    used_ = 0;
  }

 private:
  static constexpr std::size_t kSize = 512;

  void append_long(const char* s, std::size_t n) {
    flush();
    if (n > kSize) {
      text_.append(s, n);
      return;
    }
    std::memcpy(buffer_.data(), s, n);
    used_ = n;
  }

  std::string& text_;
  std::array<char, kSize> buffer_;
  std::size_t used_ = 0;
};

// std::round(x) and std::nearbyint(y) (y >= 0, the default rounding mode) without a library
// call each: a double below 2^52 in magnitude is truncated exactly by a conversion to an integer,
// and 2^52 added and taken away again rounds it to the nearest, ties to even; from 2^52 on a
// double is a whole number already. These run for every number printed.
constexpr double kTwoPow52 = 4503599627370496.0;

double round_half_away(double x) {
  if (!(std::fabs(x) < kTwoPow52)) {
    return std::round(x);  // whole already, or not finite
  }
  const double t = static_cast<double>(static_cast<std::int64_t>(x));
  const double frac = x - t;  // exact
  if (frac >= 0.5) {
    return t + 1.0;
  }
  if (frac <= -0.5) {
    return t - 1.0;
  }
  return t == 0.0 ? std::copysign(0.0, x) : t;
}

double nearest_even(double y) {
  if (y < kTwoPow52) {
    return (y + kTwoPow52) - kTwoPow52;  // IEEE arithmetic: never folded to y
  }
  return y;
}

constexpr std::array<double, 10> kPowersOfTen{1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};

// The text std::to_chars(first, last, v) writes (shortest round trip, fixed unless scientific
// is shorter), found without its general algorithm for what programs print most: |v| below
// 1e12 with at most 9 decimals. Such a v is N / 10^k for one integer N at the smallest k that
// divides back to v: below 1e13 the values that round to v span less than 1/100 at that scale,
// so no other N of as few digits exists. nullptr: not such a value, or scientific is shorter.
char* fixed_shortest(char* out, double v) {
  const double a = std::fabs(v);
  if (!(a < 1e12)) {
    return nullptr;
  }
  for (std::size_t k = 0; k < kPowersOfTen.size(); ++k) {
    const double scaled = nearest_even(a * kPowersOfTen[k]);
    if (scaled >= 1e13) {
      return nullptr;
    }
    if (scaled / kPowersOfTen[k] != a) {
      continue;
    }
    char digits[16];
    const auto end =
        std::to_chars(digits, digits + sizeof digits, static_cast<std::uint64_t>(scaled));
    const int length = static_cast<int>(end.ptr - digits);
    const int decimals = static_cast<int>(k);
    int significant = length;  // without an integer's trailing zeros
    while (significant > 1 && digits[significant - 1] == '0') {
      --significant;
    }
    const int exponent = length - 1 - decimals;  // of the leading digit
    const int magnitude = exponent < 0 ? -exponent : exponent;
    const int scientific = significant + (significant > 1 ? 1 : 0) + 2 + (magnitude >= 100 ? 3 : 2);
    const int fixed = exponent < 0 ? 1 - exponent + length : length + (decimals > 0 ? 1 : 0);
    if (scientific < fixed) {
      return nullptr;
    }
    if (v < 0.0) {
      *out++ = '-';
    }
    if (exponent < 0) {
      *out++ = '0';
      *out++ = '.';
      for (int z = -1; z > exponent; --z) {
        *out++ = '0';
      }
      return std::copy(digits, digits + length, out);
    }
    out = std::copy(digits, digits + length - decimals, out);
    if (decimals > 0) {
      *out++ = '.';
      out = std::copy(digits + length - decimals, digits + length, out);
    }
    return out;
  }
  return nullptr;
}

// The decimal digits of `u` at `out` (room for 10); the end.
char* digits_of(char* out, std::uint32_t u) {
  return std::to_chars(out, out + 10, u).ptr;
}

// A whole number below 1e5 prints as its digits: fixed_shortest's text, as five digits are
// never longer than the scientific form. nullptr: `r` is not such a number.
char* small_whole_at(char* at, double r) {
  if (!(std::fabs(r) < 1e5)) {
    return nullptr;
  }
  const auto whole = static_cast<std::int32_t>(r);
  if (static_cast<double>(whole) != r) {
    return nullptr;
  }
  if (whole < 0) {
    *at++ = '-';
  }
  return digits_of(at, static_cast<std::uint32_t>(whole < 0 ? -whole : whole));
}

// The text of `v` at `at` (room for kNumberRoom bytes), its end: the shortest round-trip form,
// after rounding to 1e-9 so that binary noise (0.30000000000000004) does not reach the output;
// -0 prints as 0.
constexpr std::size_t kNumberRoom = 40;
char* number_at(char* at, double v) {
  // A whole v below 1e5 first: v * 1e9 is then a whole number below 2^53, exact, so the
  // rounding below would give v back (and -0 prints as 0 either way).
  if (char* end = small_whole_at(at, v)) {
    return end;
  }
  double r = round_half_away(v * 1e9) / 1e9;
  if (r == 0.0 || !std::isfinite(r)) {
    r = 0.0;
  }
  if (char* end = small_whole_at(at, r)) {
    return end;
  }
  if (char* end = fixed_shortest(at, r)) {
    return end;
  }
  return std::to_chars(at, at + kNumberRoom, r).ptr;
}

void number(Writer& out, double v) {
  out.commit(number_at(out.room(kNumberRoom), v));
}

void integer(Writer& out, long long v) {
  char* const buf = out.room(24);
  if (v >= 0 && v <= 0xFFFFFFFFLL) {
    out.commit(digits_of(buf, static_cast<std::uint32_t>(v)));
    return;
  }
  out.commit(std::to_chars(buf, buf + 24, v).ptr);
}

void string(Writer& out, const std::string& s) {
  out += '"';
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  out += '"';
}

// `,"k":` with the length of `k` known at compile time (this runs a few times per command).
template <std::size_t N>
void key(Writer& out, const char (&k)[N]) {
  out.append(",\"", 2);
  out.append(k, N - 1);
  out.append("\":", 2);
}

void key(Writer& out, std::string_view k) {
  out.append(",\"", 2);
  out.append(k);
  out.append("\":", 2);
}

// The `axis` field: an axis's letter.
void axis_name(Writer& out, char axis) {
  key(out, "axis");
  out += '"';
  out += axis;
  out += '"';
}

void positions(Writer& out, const AxisVector& v, const std::vector<AxisConfig>& axes) {
  out += '{';
  for (std::size_t i = 0; i < axes.size(); ++i) {
    // The separator, the name and the number in one piece of room: this runs per axis.
    char* at = out.room(5 + kNumberRoom);
    if (i > 0) {
      *at++ = ',';
    }
    at[0] = '"';
    at[1] = axes[i].name;
    at[2] = '"';
    at[3] = ':';
    out.commit(number_at(at + 4, v[i]));
  }
  out += '}';
}

// {axis: value} of the axes whose bit `shown` has (the torque data of G31 P98/P99, G10 L14).
void axis_values(Writer& out, const AxisVector& v, std::uint32_t shown,
                 const std::vector<AxisConfig>& axes) {
  out += '{';
  bool first = true;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    if (((shown >> i) & 1U) != 0) {
      out += first ? "\"" : ",\"";
      out += axes[i].name;
      out += "\":";
      number(out, v[i]);
      first = false;
    }
  }
  out += '}';
}

void feed(Writer& out, const Command& c) {
  key(out, "feed");
  number(out, c.feed);
  key(out, "feed_mode");
  out += c.feed_mode == FeedMode::per_min ? "\"per_min\"" : "\"per_rev\"";
  if (c.exact_stop) {
    key(out, "exact_stop");
    out += "true";
  }
}

// center, dir and plane of an arc (or arc thread).
void arc_fields(Writer& out, const Command& c, const std::vector<AxisConfig>& axes) {
  key(out, "center");
  out += "{\"";
  out += axes[static_cast<std::size_t>(c.center_axes[0])].name;
  out += "\":";
  number(out, c.center[0]);
  out += ",\"";
  out += axes[static_cast<std::size_t>(c.center_axes[1])].name;
  out += "\":";
  number(out, c.center[1]);
  out += '}';
  key(out, "dir");
  out += c.direction == ArcDirection::cw ? "\"cw\"" : "\"ccw\"";
  key(out, "plane");
  out += c.plane == Plane::xy ? "\"XY\"" : c.plane == Plane::zx ? "\"ZX\"" : "\"YZ\"";
}

// G10 L14 P7/P8: a hole cycle's in-feed watched for overload, what follows one and where to.
void overload_fields(Writer& out, const Command& c, const std::vector<AxisConfig>& axes) {
  if (c.overload_axes == 0) {
    return;
  }
  key(out, "overload");
  out += "{\"p\":";
  integer(out, c.overload_p);
  out += ",\"loads\":";
  axis_values(out, c.overload_loads, c.overload_axes, axes);
  out += ",\"filter\":";
  number(out, c.overload_filter_s);
  out += ",\"retract\":";
  number(out, c.overload_retract);
  out += ",\"then\":";
  switch (c.overload_outcome) {
    case Command::Overload::stop:
      out += "\"stop\"";
      break;
    case Command::Overload::alarm:
      out += "\"alarm\"";
      break;
    case Command::Overload::go_on:
      out += "\"go_on\"";
      break;
    case Command::Overload::retry:
      out += "\"retry\"";
      break;
  }
  if (c.overload_variable != 0) {
    out += ",\"variable\":";
    integer(out, c.overload_variable);
  }
  out += '}';
}

const char* op_name(Op op) {
  switch (op) {
    case Op::rapid:
      return "rapid";
    case Op::linear:
      return "linear";
    case Op::arc:
      return "arc";
    case Op::dwell:
      return "dwell";
    case Op::spindle:
      return "spindle";
    case Op::spindle_select:
      return "spindle_select";
    case Op::tool:
      return "tool";
    case Op::aux:
      return "aux";
    case Op::wait_input:
      return "wait_input";
    case Op::wait_spindle:
      return "wait_spindle";
    case Op::stop:
      return "stop";
    case Op::end:
      return "end";
    case Op::sync:
      return "sync";
    case Op::axis_release:
      return "axis_release";
    case Op::axis_acquire:
      return "axis_acquire";
    case Op::axis_restore:
      return "axis_restore";
    case Op::axis_couple:
      return "axis_couple";
    case Op::axis_decouple:
      return "axis_decouple";
    case Op::spindle_sync:
      return "spindle_sync";
    case Op::spindle_unsync:
      return "spindle_unsync";
    case Op::polygon:
      return "polygon";
    case Op::polygon_off:
      return "polygon_off";
    case Op::cam:
      return "cam";
    case Op::cam_off:
      return "cam_off";
    case Op::egb:
      return "egb";
    case Op::egb_off:
      return "egb_off";
    case Op::subcall:
      return "subcall";
    case Op::subcall_release:
      return "subcall_release";
    case Op::message:
      return "message";
    case Op::thread:
      return "thread";
    case Op::spindle_mode:
      return "spindle_mode";
    case Op::oscillate:
      return "oscillate";
    case Op::oscillate_end:
      return "oscillate_end";
    case Op::torque_limit:
      return "torque_limit";
    case Op::load_watch:
      return "load_watch";
    case Op::load_timer_check:
      return "load_timer_check";
    case Op::torque_mode:
      return "torque_mode";
  }
  return "?";
}

const char* direction_name(SpindleDirection d) {
  switch (d) {
    case SpindleDirection::cw:
      return "\"cw\"";
    case SpindleDirection::ccw:
      return "\"ccw\"";
    case SpindleDirection::stop:
      return "\"stop\"";
    case SpindleDirection::orient:
      return "\"orient\"";
    case SpindleDirection::keep:
      return "\"keep\"";
  }
  return "\"?\"";
}

}  // namespace

void append_json(std::string& text, const Command& c, const std::vector<AxisConfig>& axes,
                 const std::string& main_file) {
  Writer out(text);
  out += "{\"n\":";
  integer(out, static_cast<long long>(c.n));
  key(out, "line");
  integer(out, c.line);
  if (c.file != nullptr && *c.file != main_file) {
    key(out, "file");
    string(out, *c.file);
  }
  key(out, "op");
  out += '"';
  out += op_name(c.op);
  out += '"';
  switch (c.op) {
    case Op::rapid:
      key(out, "to");
      positions(out, c.to, axes);
      break;
    case Op::linear:
      key(out, "to");
      positions(out, c.to, axes);
      feed(out, c);
      if (c.skip) {  // G31: the move ends where this input switches
        key(out, "skip");
        if (c.skip_signal != 0) {  // G31 P: the PLC's signal G0014.(P-1)
          out += "{\"plc_signal\":";
          integer(out, c.skip_signal);
        } else {
          out += "{\"input\":";
          integer(out, c.input);
        }
        out += c.input_on ? ",\"state\":\"on\"" : ",\"state\":\"off\"";
        if (c.multi_skip) {  // G31.8: on past each signal, up to this many
          out += ",\"max_signals\":";
          integer(out, c.max_signals);
        }
        out += '}';
      }
      if (c.load_skip) {  // G31 P98/P99: the load ratio of each axis watched
        key(out, "load_skip");
        std::uint32_t watched = 0;
        for (std::size_t i = 0; i < axes.size() && i < 32; ++i) {
          watched |= c.load_ratio[i] > 0.0 ? 1U << i : 0U;
        }
        axis_values(out, c.load_ratio, watched, axes);
      }
      overload_fields(out, c, axes);
      if (c.torque_skip) {  // G160: the axis's torque limit (-1: cancelled) and the skip's error
        key(out, "torque_skip");
        out += "{\"limit\":";
        number(out, c.torque_limit);
        out += ",\"deviation\":";
        number(out, c.deviation);
        out += '}';
      }
      break;
    case Op::arc:
      key(out, "to");
      positions(out, c.to, axes);
      arc_fields(out, c, axes);
      if (c.turns > 0) {
        key(out, "turns");
        integer(out, c.turns);
      }
      feed(out, c);
      break;
    case Op::thread:
      key(out, "to");
      positions(out, c.to, axes);
      key(out, "lead");
      number(out, c.lead);
      key(out, "lead_change");
      number(out, c.lead_change);
      key(out, "start_angle");
      number(out, c.start_angle);
      key(out, "spindle");
      integer(out, c.spindle);
      if (c.continuous) {
        key(out, "continuous");
        out += "true";
      }
      if (c.rpm > 0.0) {
        key(out, "rpm");
        number(out, c.rpm);
      }
      if (c.left_hand) {
        key(out, "left_hand");
        out += "true";
      }
      if (c.thread_arc) {
        arc_fields(out, c, axes);
      }
      overload_fields(out, c, axes);
      break;
    case Op::dwell:
      key(out, std::string_view(c.in_revs ? "revs" : "seconds"));
      number(out, c.seconds);
      break;
    case Op::spindle_mode:
      key(out, "spindle");
      integer(out, c.spindle);
      key(out, "mode");
      out += c.position_control ? "\"position\"" : "\"speed\"";
      break;
    case Op::spindle:
      if (c.channel != 0) {
        key(out, "channel");
        integer(out, c.channel);
      }
      key(out, "spindle");
      integer(out, c.spindle);
      key(out, "dir");
      out += direction_name(c.spindle_direction);
      if (c.css) {
        key(out, "css");
        out += "{\"surface\":";
        number(out, c.surface);
        out += ",\"max_rpm\":";
        if (c.max_rpm > 0.0) {
          number(out, c.max_rpm);
        } else {
          out += "null";
        }
        out += '}';
      } else {
        key(out, "rpm");
        number(out, c.rpm);
      }
      if (c.has_angle) {
        key(out, "angle");
        number(out, c.angle);
      }
      if (c.divisions > 0) {
        key(out, "divisions");
        integer(out, c.divisions);
      }
      break;
    case Op::spindle_select:
      if (c.channel != 0) {
        key(out, "channel");
        integer(out, c.channel);
      }
      key(out, "spindle");
      integer(out, c.spindle);
      break;
    case Op::tool:
      key(out, "tool");
      integer(out, c.tool);
      key(out, "offset");
      integer(out, c.offset);
      break;
    case Op::aux:
      key(out, "code");
      integer(out, c.code);
      break;
    case Op::wait_input:
      key(out, "input");
      integer(out, c.input);
      key(out, "state");
      out += c.input_on ? "\"on\"" : "\"off\"";
      if (c.timeout_s >= 0.0) {
        key(out, "timeout");
        number(out, c.timeout_s);
      }
      if (c.width_s >= 0.0) {
        key(out, "width");
        number(out, c.width_s);
      }
      if (c.dwell_s >= 0.0) {
        key(out, "seconds");
        number(out, c.dwell_s);
      }
      break;
    case Op::wait_spindle:
      key(out, "spindle");
      integer(out, c.spindle);
      key(out, "rpm");
      number(out, c.rpm);
      if (c.dwell_s >= 0.0) {
        key(out, "seconds");
        number(out, c.dwell_s);
      }
      break;
    case Op::stop:
      key(out, "code");
      out += c.code == 1 ? "\"M01\"" : "\"M00\"";
      break;
    case Op::end:
      key(out, "code");
      out += c.code == 2 ? "\"M02\"" : (c.code == 99 ? "\"M99\"" : "\"M30\"");
      break;
    case Op::sync:
      if (c.has_p) {
        key(out, "p");
        integer(out, c.p);
        key(out, "channels");
        if (c.all_channels) {
          out += "\"all\"";
        } else {
          out += '[';
          bool first = true;
          for (int ch = 1; ch <= 255; ++ch) {
            if (c.has_channel(ch)) {
              if (!first) {
                out += ',';
              }
              first = false;
              integer(out, ch);
            }
          }
          out += ']';
        }
      }
      break;
    case Op::axis_release:
    case Op::axis_acquire:
      axis_name(out, c.axis);
      key(out, "exchange");
      integer(out, c.exchange);
      if (c.op == Op::axis_acquire) {
        key(out, "force");
        out += c.force ? "true" : "false";
      }
      break;
    case Op::oscillate:
      axis_name(out, c.axis);
      key(out, "top");
      number(out, c.top);
      key(out, "bottom");
      number(out, c.bottom);
      key(out, "feed");
      number(out, c.feed);
      break;
    case Op::oscillate_end:
      axis_name(out, c.axis);
      key(out, "to");
      positions(out, c.to, axes);
      break;
    case Op::axis_couple:
      if (c.master != 0) {
        key(out, "master");
        integer(out, c.master);
      }
      key(out, "slave");
      integer(out, c.slave);
      break;
    case Op::axis_decouple:
      key(out, "slave");
      integer(out, c.slave);
      break;
    case Op::spindle_sync:
    case Op::polygon:  // a polygon axis has no group K
      key(out, "p");
      integer(out, c.sync_p);
      key(out, "q");
      integer(out, c.sync_q);
      if (c.op == Op::spindle_sync) {
        key(out, "k");
        integer(out, c.sync_k);
      }
      key(out, "r");
      number(out, c.sync_r);
      break;
    case Op::polygon_off:
    case Op::egb_off:
      key(out, "wait");
      out += c.wait ? "true" : "false";
      break;
    case Op::cam:
      key(out, "shape");
      out += c.cam_shape == 1 ? "\"ellipse\"" : c.cam_shape == 2 ? "\"eccentric\"" : "\"table\"";
      if (c.cam_shape == 0) {
        key(out, "first");
        integer(out, c.cam_first);
        key(out, "lift");
        out += '[';
        for (std::size_t i = 0; i < c.cam_lift.size(); ++i) {
          if (i > 0) {
            out += ',';
          }
          number(out, c.cam_lift[i]);
        }
        out += ']';
      } else {
        key(out, c.cam_shape == 1 ? "a" : "d");
        number(out, c.cam_a);
        key(out, c.cam_shape == 1 ? "b" : "p");
        number(out, c.cam_b);
      }
      key(out, "r");
      number(out, c.sync_r);
      break;
    case Op::egb:  // P and Q only for a helical gear, R only when the phase is matched
      key(out, "t");
      integer(out, c.egb_teeth);
      key(out, "l");
      integer(out, c.egb_threads);
      if (c.egb_helix != 0.0) {
        key(out, "p");
        number(out, c.egb_helix);
        key(out, "q");
        number(out, c.egb_module);
      }
      if (c.egb_phase) {
        key(out, "r");
        number(out, c.sync_r);
      }
      break;
    case Op::subcall: {
      key(out, "channel");
      integer(out, c.channel);
      key(out, "program");
      integer(out, c.program);
      key(out, "wait");
      out += c.wait ? "true" : "false";
      key(out, "repeat");
      integer(out, c.repeat);
      key(out, "args");
      out += '{';
      bool first = true;
      for (const auto& [var, value] : c.args) {
        if (!first) {
          out += ',';
        }
        first = false;
        out += '"';
        integer(out, var);
        out += "\":";
        number(out, value);
      }
      out += '}';
      break;
    }
    case Op::message:
      key(out, "text");
      string(out, c.text);
      break;
    case Op::load_watch:  // G10 L14 P0/P1: the moves watched, J, each axis's reference load
      key(out, "moves");
      out += c.every_move ? "\"all\"" : "\"feed\"";
      key(out, "filter");
      number(out, c.filter_s);
      key(out, "loads");
      axis_values(out, c.torque_data, c.torque_data_axes, axes);
      if (c.load_timer != 0) {  // P2-P5: the load timer it starts
        key(out, "timer");
        integer(out, c.load_timer);
      }
      break;
    case Op::torque_mode:  // G10 L14 P10/P11/P12: what it sets, per axis named
      key(out, "set");
      out += c.torque_mode_p == 10   ? "\"torque\""
             : c.torque_mode_p == 11 ? "\"speed\""
                                     : "\"position\"";
      key(out, c.torque_mode_p == 10 ? "torques" : c.torque_mode_p == 11 ? "speeds" : "limits");
      axis_values(out, c.torque_data, c.torque_data_axes, axes);
      break;
    case Op::load_timer_check:  // G10 L14 P20-P51: the timer, the condition, each axis's time
      key(out, "timer");
      integer(out, c.load_timer);
      key(out, "condition");
      out += c.timer_longer ? "\"longer\"" : "\"shorter\"";
      key(out, "seconds");
      axis_values(out, c.torque_data, c.torque_data_axes, axes);
      if (c.timer_variable != 0) {
        key(out, "variable");
        integer(out, c.timer_variable);
      }
      break;
    case Op::torque_limit:  // G10 L14 P9: each axis it sets, 0 cancelled
      key(out, "limits");
      axis_values(out, c.torque_data, c.torque_data_axes, axes);
      break;
    case Op::axis_restore:
    case Op::spindle_unsync:
    case Op::subcall_release:
    case Op::cam_off:
      break;
  }
  if (c.barrier) {
    key(out, "barrier");
    out += "true";
  }
  out += "}\n";
  out.flush();
}

void append_json(std::string& text, const ProgramAlarm& a) {
  Writer out(text);
  out += "{\"op\":\"alarm\",\"number\":";
  integer(out, a.number);
  key(out, "text");
  string(out, a.text);
  key(out, "file");
  string(out, a.program);
  key(out, "line");
  integer(out, a.line);
  key(out, "col");
  integer(out, a.column);
  out += "}\n";
  out.flush();
}

}  // namespace mcnc::interp::output
