#include "tools/report/run_report.hpp"

#include "common/text/markup_escape.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>

namespace mcnc::report {
namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", v);
  return text;
}

std::string text_of(const nlohmann::json& e, const char* key) {
  const auto it = e.find(key);
  return it != e.end() && it->is_string() ? it->get<std::string>() : std::string();
}

std::uint64_t cycle_of(const nlohmann::json& e) {
  const auto it = e.find("cycle");
  return it != e.end() && it->is_number_unsigned() ? it->get<std::uint64_t>() : 0;
}

bool is(const nlohmann::json& e, const char* ev) {
  return text_of(e, "ev") == ev;
}

std::uint64_t last_cycle(const Trace& trace) {
  std::uint64_t last = 1;
  for (const auto& e : trace) {
    last = std::max(last, cycle_of(e));
  }
  return last;
}

// Timeline geometry.
constexpr double kWidth = 1000.0;
constexpr double kLeft = 70.0;
constexpr double kRight = 20.0;
constexpr double kTop = 10.0;
constexpr double kLane = 34.0;
constexpr double kGap = 10.0;

struct Interval {
  std::uint64_t from = 0;
  std::uint64_t to = 0;
  std::string what;  // a state, or a block's line
  std::string title;
};

std::string rect(const char* cls, double x0, double x1, double y, double h, const std::string& fill,
                 const std::string& data, const std::string& title) {
  return "<rect class=\"" + std::string(cls) + "\"" + data + " x=\"" + number(x0) + "\" y=\"" +
         number(y) + "\" width=\"" + number(std::max(x1 - x0, 0.5)) + "\" height=\"" + number(h) +
         "\" fill=\"" + fill + "\"><title>" + text::markup_escaped(title) + "</title></rect>\n";
}

}  // namespace

std::string timeline_svg(const config::MachineConfig& machine, const Trace& trace) {
  const std::uint64_t last = last_cycle(trace);
  const double scale = (kWidth - kLeft - kRight) / static_cast<double>(last);
  const auto x = [&](std::uint64_t c) { return kLeft + static_cast<double>(c) * scale; };
  const double height = kTop + static_cast<double>(machine.channels.size()) * (kLane + kGap) + 30.0;
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"timeline\" width=\"" +
                    number(kWidth) + "\" height=\"" + number(height) + "\" viewBox=\"0 0 " +
                    number(kWidth) + " " + number(height) +
                    "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  for (std::size_t lane = 0; lane < machine.channels.size(); ++lane) {
    const std::string& ch = machine.channels[lane].name;
    const double y = kTop + static_cast<double>(lane) * (kLane + kGap);
    svg += "<g data-channel=\"" + text::markup_escaped(ch) + "\">\n";
    svg += "<text x=\"4\" y=\"" + number(y + kLane / 2 + 4) + "\">" + text::markup_escaped(ch) +
           "</text>\n";
    svg += "<rect x=\"" + number(kLeft) + "\" y=\"" + number(y) + "\" width=\"" +
           number(kWidth - kLeft - kRight) + "\" height=\"" + number(kLane) +
           "\" fill=\"#f4f4f4\"/>\n";
    // Blocks: each from its start to the next one's, the last to the program end or the end
    // of the run.
    std::vector<Interval> blocks;
    std::vector<Interval> states;
    std::optional<std::uint64_t> ended;
    for (const auto& e : trace) {
      if (text_of(e, "ch") != ch) {
        continue;
      }
      const std::uint64_t c = cycle_of(e);
      if (is(e, "block")) {
        if (!blocks.empty() && blocks.back().to == 0) {
          blocks.back().to = c;
        }
        const int line = e.value("line", 0);
        blocks.push_back(
            Interval{c, 0, std::to_string(line),
                     text_of(e, "prog") + ":" + std::to_string(line) + " " + text_of(e, "text")});
      } else if (is(e, "state")) {
        if (!states.empty() && states.back().to == 0) {
          states.back().to = c;
        }
        states.push_back(Interval{c, 0, text_of(e, "state"), text_of(e, "state")});
        const std::string s = text_of(e, "state");
        if ((s == "idle" || s == "reset" || s == "alarm") && !blocks.empty() &&
            blocks.back().to == 0) {
          blocks.back().to = c;  // no block runs after the program stopped
        }
      } else if (is(e, "end")) {
        ended = c;
      }
    }
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      Interval& b = blocks[i];
      b.to = b.to != 0 ? b.to : ended.value_or(last);
      svg += rect("block", x(b.from), x(b.to), y + 4, kLane - 8, i % 2 == 0 ? "#a8cbff" : "#cfe3ff",
                  " data-line=\"" + b.what + "\"", b.title);
    }
    for (Interval& s : states) {
      s.to = s.to != 0 ? s.to : last;
      const char* fill = s.what == "waiting" ? "#f5c542"
                         : s.what == "hold"  ? "#9e9e9e"
                         : s.what == "alarm" ? "#e0454b"
                                             : nullptr;
      if (fill != nullptr) {
        svg += rect(s.what == "waiting" ? "wait" : s.what.c_str(), x(s.from), x(s.to),
                    y + kLane - 8, 8, fill, "", s.what);
      }
    }
    for (const auto& e : trace) {
      if (is(e, "sync_release") && text_of(e, "ch") == ch) {
        const double sx = x(cycle_of(e));
        const int p = e.value("p", 0);
        svg += "<g class=\"sync\" data-p=\"" + std::to_string(p) + "\"><line x1=\"" + number(sx) +
               "\" y1=\"" + number(y - 2) + "\" x2=\"" + number(sx) + "\" y2=\"" +
               number(y + kLane + 2) + "\" stroke=\"#7a3cc2\" stroke-width=\"2\"/><text x=\"" +
               number(sx + 2) + "\" y=\"" + number(y + 10) + "\" fill=\"#7a3cc2\">P" +
               std::to_string(p) + "</text><title>G04.1 P" + std::to_string(p) +
               " released</title></g>\n";
      }
      // An axis changing owner shows on the lane of the channel that took it (or gave it up).
      if (is(e, "owner") && e.contains("previous")) {
        const std::string owner = e["owner"].is_string() ? e["owner"].get<std::string>() : "";
        const std::string previous =
            e["previous"].is_string() ? e["previous"].get<std::string>() : "";
        if ((owner.empty() ? previous : owner) != ch) {
          continue;
        }
        const std::string axis = text_of(e, "axis");
        svg += "<circle class=\"owner\" data-axis=\"" + text::markup_escaped(axis) + "\" cx=\"" +
               number(x(cycle_of(e))) + "\" cy=\"" + number(y + kLane / 2) +
               "\" r=\"5\" fill=\"#1a9c5b\"><title>" +
               text::markup_escaped(axis + ": " + (previous.empty() ? "released" : previous) +
                                    " -> " + (owner.empty() ? "released" : owner)) +
               "</title></circle>\n";
      }
    }
    svg += "</g>\n";
  }
  // Time axis: ten ticks, in seconds of machine time.
  const double axis_y = kTop + static_cast<double>(machine.channels.size()) * (kLane + kGap);
  for (int t = 0; t <= 10; ++t) {
    const std::uint64_t c = last * static_cast<std::uint64_t>(t) / 10;
    svg += "<text x=\"" + number(x(c) - 8) + "\" y=\"" + number(axis_y + 14) + "\">" +
           number(static_cast<double>(c) * machine.cycle_s()) + "</text>\n";
  }
  svg += "<text x=\"4\" y=\"" + number(axis_y + 14) + "\">s</text>\n</svg>\n";
  return svg;
}

std::string toolpath_svg(const config::MachineConfig& machine, const Trace& trace,
                         const std::string& channel) {
  const config::ChannelConfig* ch = machine.find_channel(channel);
  if (ch == nullptr) {
    return "";
  }
  std::string x_axis;
  std::string z_axis;
  bool diameter = false;
  for (const std::string& name : ch->axes) {
    const config::AxisConfig* a = machine.find_axis(name);
    if (a->address == 'X') {
      x_axis = name;
      diameter = a->diameter;
    }
    z_axis = a->address == 'Z' ? name : z_axis;
  }
  if (x_axis.empty() || z_axis.empty()) {
    return "";
  }
  // The axis nodes sample at the same cycles: a point where both did.
  std::map<std::uint64_t, std::pair<std::optional<double>, std::optional<double>>> samples;
  for (const auto& e : trace) {
    if (!is(e, "pos")) {
      continue;
    }
    const std::string src = text_of(e, "src");
    if (src == x_axis || src == z_axis) {
      auto& s = samples[cycle_of(e)];
      (src == x_axis ? s.first : s.second) = e.value("cmd", 0.0);
    }
  }
  std::vector<std::pair<std::uint64_t, std::pair<double, double>>> points;  // cycle, (z, x)
  for (const auto& [cycle, s] : samples) {
    if (s.first && s.second) {
      points.push_back({cycle, {*s.second, *s.first}});
    }
  }
  if (points.empty()) {
    return "";
  }
  double zmin = std::numeric_limits<double>::max();
  double zmax = std::numeric_limits<double>::lowest();
  double xmin = zmin;
  double xmax = zmax;
  for (const auto& [cycle, p] : points) {
    zmin = std::min(zmin, p.first);
    zmax = std::max(zmax, p.first);
    xmin = std::min(xmin, p.second);
    xmax = std::max(xmax, p.second);
  }
  constexpr double kSize = 480.0;
  constexpr double kMargin = 20.0;
  const double span = std::max({zmax - zmin, xmax - xmin, 1e-3});
  const double s = (kSize - 2 * kMargin) / span;  // one scale for both: the picture keeps its shape
  const auto px = [&](double z) { return kMargin + (z - zmin) * s; };
  const auto py = [&](double x) { return kSize - kMargin - (x - xmin) * s; };
  std::string d;
  for (const auto& [cycle, p] : points) {
    d += (d.empty() ? "M" : " L") + number(px(p.first)) + " " + number(py(p.second));
  }
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"toolpath\" data-channel=\"" +
                    text::markup_escaped(channel) + "\" width=\"" + number(kSize) + "\" height=\"" +
                    number(kSize) + "\" viewBox=\"0 0 " + number(kSize) + " " + number(kSize) +
                    "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  svg += "<text x=\"4\" y=\"12\">" + text::markup_escaped(channel) + ": " +
         text::markup_escaped(z_axis) + " right, " + text::markup_escaped(x_axis) +
         (diameter ? " up (radius), " : " up, ") + number(zmin) + ".." + number(zmax) + " x " +
         number(xmin) + ".." + number(xmax) + "</text>\n";
  svg += "<path class=\"toolpath\" d=\"" + d +
         "\" fill=\"none\" stroke=\"#1f5fbf\" stroke-width=\"1.5\"/>\n";
  for (const auto& e : trace) {
    if (!is(e, "sync_release") || text_of(e, "ch") != channel) {
      continue;
    }
    const std::uint64_t c = cycle_of(e);
    const auto at = std::upper_bound(points.begin(), points.end(), c,
                                     [](std::uint64_t v, const auto& p) { return v < p.first; });
    const auto& p = (at == points.begin() ? at : std::prev(at))->second;
    const int sync_p = e.value("p", 0);
    svg += "<circle class=\"sync\" data-p=\"" + std::to_string(sync_p) + "\" cx=\"" +
           number(px(p.first)) + "\" cy=\"" + number(py(p.second)) +
           "\" r=\"4\" fill=\"#7a3cc2\"><title>G04.1 P" + std::to_string(sync_p) +
           "</title></circle>\n";
  }
  svg += "</svg>\n";
  return svg;
}

std::string report_html(const config::MachineConfig& machine, const Trace& trace) {
  std::string html =
      "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>mcnc run report: " +
      text::markup_escaped(machine.name) +
      "</title>\n<style>body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse}"
      "td,th{border:1px solid #ccc;padding:3px 8px;text-align:left}.ok{color:#1a7f37}"
      ".failed{color:#c62828}.legend span{display:inline-block;width:12px;height:12px;"
      "margin:0 4px 0 12px;vertical-align:middle}</style></head><body>\n";
  const nlohmann::json* summary = nullptr;
  for (const auto& e : trace) {
    summary = is(e, "summary") ? &e : summary;
  }
  const bool ok = summary != nullptr && summary->value("ok", false);
  html += "<h1>Run report: " + text::markup_escaped(machine.name) + "</h1>\n<p class=\"" +
          std::string(ok ? "ok" : "failed") + "\">" + (ok ? "ok" : "failed") + ", " +
          std::to_string(last_cycle(trace)) + " cycles of " + std::to_string(machine.cycle_us) +
          " &micro;s</p>\n<table><tr><th>channel</th><th>end</th><th>cycle time (s)</th>"
          "<th>alarms</th></tr>\n";
  for (const config::ChannelConfig& c : machine.channels) {
    const nlohmann::json* r = nullptr;
    if (summary != nullptr && summary->contains("channels") &&
        (*summary)["channels"].contains(c.name)) {
      r = &(*summary)["channels"][c.name];
    }
    const bool has_end = r != nullptr && r->contains("end") && (*r)["end"].is_number();
    html += "<tr><td>" + text::markup_escaped(c.name) + "</td><td>" +
            (r == nullptr ? std::string("no program")
             : has_end    ? "M" + std::to_string((*r)["end"].get<int>())
                          : std::string("did not end")) +
            "</td><td>" + (has_end ? number(r->value("cycle_time_s", 0.0)) : std::string()) +
            "</td><td>" + (r == nullptr ? std::string() : std::to_string(r->value("alarms", 0))) +
            "</td></tr>\n";
  }
  html += "</table>\n<h2>Alarms</h2>\n<ul class=\"alarms\">\n";
  int alarms = 0;
  for (const auto& e : trace) {
    if (is(e, "alarm")) {
      ++alarms;
      html += "<li>" + text::markup_escaped(text_of(e, "src")) + " " +
              std::to_string(e.value("number", 0)) + " " +
              text::markup_escaped(text_of(e, "text")) +
              (e.contains("line") ? " (line " + std::to_string(e.value("line", 0)) + ")" : "") +
              "</li>\n";
    }
  }
  html += alarms == 0 ? "<li>none</li>\n</ul>\n" : "</ul>\n";
  html +=
      "<h2>Timeline</h2>\n<p class=\"legend\"><span style=\"background:#a8cbff\"></span>blocks"
      "<span style=\"background:#f5c542\"></span>waiting<span style=\"background:#9e9e9e\">"
      "</span>feed hold<span style=\"background:#e0454b\"></span>alarm<span "
      "style=\"background:#7a3cc2\"></span>G04.1 sync point<span style=\"background:#1a9c5b\">"
      "</span>axis changes owner</p>\n";
  html += timeline_svg(machine, trace);
  html += "<h2>Toolpaths</h2>\n";
  for (const config::ChannelConfig& c : machine.channels) {
    const std::string svg = toolpath_svg(machine, trace, c.name);
    html += "<h3>" + text::markup_escaped(c.name) + "</h3>\n" +
            (svg.empty() ? "<p>no X and Z samples</p>\n" : svg);
  }
  html += "</body></html>\n";
  return html;
}

}  // namespace mcnc::report
