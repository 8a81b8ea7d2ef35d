#include "channel/interp/parse/parsed_program.hpp"

#include "channel/interp/parse/line_parser.hpp"
#include "channel/interp/program_alarms.hpp"

#include <string>

namespace mcnc::interp::parse {

namespace {

struct Open {
  int line = 0;  // index
  StatementKind kind = StatementKind::empty;
  int label = 0;
  int last_branch = 0;  // IF: the latest IF/ELIF/ELSE line of the chain
  bool seen_else = false;
};

ProgramAlarm alarm_at(const ParsedProgram& p, int index, int number, std::string text) {
  const Line& l = p.lines[static_cast<std::size_t>(index)];
  return ProgramAlarm{number, std::move(text), p.file, l.line, l.statement.column};
}

std::optional<ProgramAlarm> match_structure(ParsedProgram& p, StructureLimits limits) {
  const int count = static_cast<int>(p.lines.size());
  p.partner.assign(p.lines.size(), -1);
  p.endif_of.assign(p.lines.size(), -1);
  p.loop_of.assign(p.lines.size(), -1);
  std::vector<Open> open;
  int whiles = 0;
  int ifs = 0;
  for (int i = 0; i < count; ++i) {
    for (auto it = open.rbegin(); it != open.rend(); ++it) {
      if (it->kind == StatementKind::while_do) {
        p.loop_of[static_cast<std::size_t>(i)] = it->line;
        break;
      }
    }
    const Statement& s = p.lines[static_cast<std::size_t>(i)].statement;
    switch (s.kind) {
      case StatementKind::while_do:
        if (++whiles > limits.max_while_nesting) {
          return alarm_at(
              p, i, alarm::kNestingTooDeep,
              "WHILE loops nested deeper than " + std::to_string(limits.max_while_nesting));
        }
        for (const Open& o : open) {
          if (o.kind == StatementKind::while_do && o.label == s.label) {
            return alarm_at(
                p, i, alarm::kStructureMismatch,
                "WHILE ... DO" + std::to_string(s.label) + " inside a loop with the same label");
          }
        }
        if (limits.max_loop_label > 0 && s.label > limits.max_loop_label) {
          return alarm_at(p, i, alarm::kBadWordValue,
                          "DO" + std::to_string(s.label) + ": loop labels are 1-" +
                              std::to_string(limits.max_loop_label));
        }
        open.push_back(Open{i, StatementKind::while_do, s.label, i, false});
        break;
      case StatementKind::loop_end: {
        if (open.empty() || open.back().kind != StatementKind::while_do ||
            open.back().label != s.label) {
          const bool in_if = !open.empty() && open.back().kind == StatementKind::if_block;
          return alarm_at(
              p, i, alarm::kStructureMismatch,
              "END" + std::to_string(s.label) +
                  (in_if ? " inside an IF block that is not closed"
                         : " without a matching WHILE ... DO" + std::to_string(s.label)));
        }
        const int w = open.back().line;
        p.partner[static_cast<std::size_t>(w)] = i;
        p.partner[static_cast<std::size_t>(i)] = w;
        open.pop_back();
        --whiles;
        break;
      }
      case StatementKind::if_block:
        if (++ifs > limits.max_if_nesting) {
          return alarm_at(p, i, alarm::kNestingTooDeep,
                          "IF blocks nested deeper than " + std::to_string(limits.max_if_nesting));
        }
        open.push_back(Open{i, StatementKind::if_block, 0, i, false});
        break;
      case StatementKind::elif:
      case StatementKind::else_branch: {
        const char* name = s.kind == StatementKind::elif ? "ELIF" : "ELSE";
        if (open.empty() || open.back().kind != StatementKind::if_block) {
          return alarm_at(p, i, alarm::kStructureMismatch,
                          std::string(name) + " without an open IF block");
        }
        if (open.back().seen_else) {
          return alarm_at(p, i, alarm::kStructureMismatch, std::string(name) + " after ELSE");
        }
        p.partner[static_cast<std::size_t>(open.back().last_branch)] = i;
        open.back().last_branch = i;
        open.back().seen_else = s.kind == StatementKind::else_branch;
        break;
      }
      case StatementKind::endif: {
        if (open.empty() || open.back().kind != StatementKind::if_block) {
          return alarm_at(p, i, alarm::kStructureMismatch, "ENDIF without an open IF block");
        }
        p.partner[static_cast<std::size_t>(open.back().last_branch)] = i;
        // Every ELIF/ELSE of this IF jumps to this ENDIF when reached in sequence.
        for (int j = open.back().line; j != i && j >= 0;) {
          const int next = p.partner[static_cast<std::size_t>(j)];
          if (j != open.back().line) {
            p.endif_of[static_cast<std::size_t>(j)] = i;
          }
          j = next;
        }
        open.pop_back();
        --ifs;
        break;
      }
      default:
        break;
    }
  }
  if (!open.empty()) {
    const Open& o = open.back();
    return alarm_at(p, o.line, alarm::kStructureMismatch,
                    o.kind == StatementKind::while_do ? "WHILE ... DO" + std::to_string(o.label) +
                                                            " without END" + std::to_string(o.label)
                                                      : std::string("IF block without ENDIF"));
  }
  return std::nullopt;
}

}  // namespace

ParsedProgramResult parse_program(const program::Program& program, StructureLimits limits) {
  ParsedProgramResult out;
  ParsedProgram p;
  p.number = program.number;
  p.file = program.file;
  p.source = program.source;
  p.lines.reserve(program.lines.size());
  p.arena.words.reserve(program.lines.size() * 3);
  for (const program::ProgramLine& pl : program.lines) {
    LineParse parsed = parse_line(pl.text, pl.line, p.arena);
    if (parsed.error) {
      out.alarm = ProgramAlarm{parsed.error->number, parsed.error->text, program.file, pl.line,
                               parsed.error->column};
      return out;
    }
    if (parsed.line.sequence >= 0) {
      p.sequence_lines[parsed.line.sequence].push_back(static_cast<int>(p.lines.size()));
    }
    parsed.line.text = pl.text;
    p.lines.push_back(std::move(parsed.line));
  }
  if (auto a = match_structure(p, limits)) {
    out.alarm = std::move(a);
    return out;
  }
  out.program = std::move(p);
  return out;
}

}  // namespace mcnc::interp::parse
