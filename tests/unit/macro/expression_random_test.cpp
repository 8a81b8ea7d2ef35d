// Random expression trees, printed as program text, parsed and evaluated, against a direct
// evaluation of the tree. This checks the parser's precedence and associativity, the printer's
// bracket rules and the evaluator's null and alarm rules against one another.
#include "channel/interp/macro/expression.hpp"
#include "channel/interp/macro/macro_alarms.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace mcnc::interp::macro {
namespace {

struct Node {
  enum class Kind { kNumber, kVariable, kIndirect, kUnary, kBinary, kCall } kind = Kind::kNumber;
  double number = 0.0;  // kNumber value, kVariable number
  OpCode op = OpCode::kAdd;
  Function function = Function::kAbs;
  std::vector<std::unique_ptr<Node>> kids;
};

constexpr OpCode kBinaryOps[] = {OpCode::kAdd, OpCode::kSub,    OpCode::kMul,   OpCode::kDiv,
                                 OpCode::kMod, OpCode::kEq,     OpCode::kNe,    OpCode::kGt,
                                 OpCode::kGe,  OpCode::kLt,     OpCode::kLe,    OpCode::kAnd,
                                 OpCode::kOr,  OpCode::kBitAnd, OpCode::kBitOr, OpCode::kBitXor};
constexpr OpCode kUnaryOps[] = {OpCode::kNegate, OpCode::kPlus, OpCode::kNot, OpCode::kBitNot};
constexpr Function kFunctions[] = {
    Function::kAbs, Function::kSin,   Function::kCos,  Function::kFix,   Function::kFup,
    Function::kInt, Function::kRound, Function::kSqrt, Function::kAtan2, Function::kRound2};

int level_of(OpCode op) {
  switch (op) {
    case OpCode::kBitAnd:
    case OpCode::kBitOr:
    case OpCode::kBitXor:
      return 1;
    case OpCode::kAnd:
    case OpCode::kOr:
      return 2;
    case OpCode::kEq:
    case OpCode::kNe:
    case OpCode::kGt:
    case OpCode::kGe:
    case OpCode::kLt:
    case OpCode::kLe:
      return 3;
    case OpCode::kAdd:
    case OpCode::kSub:
      return 4;
    default:
      return 5;
  }
}

// Binding strength of a printed node: 1-5 binary levels, 6 unary, 7 operand.
int strength(const Node& n) {
  if (n.kind == Node::Kind::kBinary) {
    return level_of(n.op);
  }
  return n.kind == Node::Kind::kUnary ? 6 : 7;
}

class Generator {
 public:
  explicit Generator(std::uint32_t seed) : rng_(seed) {}

  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }
  bool chance(double p) { return std::bernoulli_distribution(p)(rng_); }

  std::unique_ptr<Node> tree(int depth) {
    auto n = std::make_unique<Node>();
    if (depth == 0 || chance(0.2)) {
      leaf(*n);
      return n;
    }
    const int k = pick(10);
    if (k < 6) {
      n->kind = Node::Kind::kBinary;
      n->op = kBinaryOps[pick(std::size(kBinaryOps))];
      n->kids.push_back(tree(depth - 1));
      n->kids.push_back(tree(depth - 1));
    } else if (k < 8) {
      n->kind = Node::Kind::kUnary;
      n->op = kUnaryOps[pick(std::size(kUnaryOps))];
      n->kids.push_back(tree(depth - 1));
    } else {
      n->kind = Node::Kind::kCall;
      n->function = kFunctions[pick(std::size(kFunctions))];
      n->kids.push_back(tree(depth - 1));
      if (function_info(n->function).min_args == 2) {
        if (n->function == Function::kRound2) {
          auto digits = std::make_unique<Node>();
          digits->number = pick(5);
          n->kids.push_back(std::move(digits));
        } else {
          n->kids.push_back(tree(depth - 1));
        }
      }
    }
    return n;
  }

 private:
  void leaf(Node& n) {
    const int k = pick(10);
    if (k < 5) {
      n.kind = Node::Kind::kNumber;
      n.number = pick(81) / 4.0;  // exact in decimal and in binary
    } else if (k < 8) {
      n.kind = Node::Kind::kVariable;
      n.number = 1 + pick(10);
    } else {
      // #[n], #[#20] (#20 holds a variable number) or #[#[#21]] (#21 holds 20).
      n.kind = Node::Kind::kIndirect;
      auto index = std::make_unique<Node>();
      const int form = pick(3);
      if (form == 0) {
        index->number = 1 + pick(10);
      } else if (form == 1) {
        index->kind = Node::Kind::kVariable;
        index->number = 20;
      } else {
        index->kind = Node::Kind::kIndirect;
        auto inner = std::make_unique<Node>();
        inner->number = 21;
        index->kids.push_back(std::move(inner));
      }
      n.kids.push_back(std::move(index));
    }
  }

  std::mt19937 rng_;
};

const char* spelling(OpCode op, bool word) {
  switch (op) {
    case OpCode::kAdd:
      return "+";
    case OpCode::kSub:
      return "-";
    case OpCode::kMul:
      return "*";
    case OpCode::kDiv:
      return "/";
    case OpCode::kMod:
      return " MOD ";
    case OpCode::kEq:
      return word ? " EQ " : "==";
    case OpCode::kNe:
      return word ? " NE " : "!=";
    case OpCode::kGt:
      return word ? " GT " : ">";
    case OpCode::kGe:
      return word ? " ge " : ">=";
    case OpCode::kLt:
      return word ? " LT " : "<";
    case OpCode::kLe:
      return word ? " LE " : "<=";
    case OpCode::kAnd:
      return word ? " AND " : "&&";
    case OpCode::kOr:
      return word ? " or " : "||";
    case OpCode::kBitAnd:
      return "&";
    case OpCode::kBitOr:
      return "|";
    case OpCode::kBitXor:
      return word ? " XOR " : "^";
    case OpCode::kNegate:
      return "-";
    case OpCode::kPlus:
      return "+";
    case OpCode::kNot:
      return "!";
    case OpCode::kBitNot:
      return "~";
    default:
      return "?";
  }
}

class Printer {
 public:
  explicit Printer(Generator& g) : g_(g) {}

  std::string print(const Node& n) {
    std::string s = bare(n);
    if (g_.chance(0.1)) {
      s = "[" + s + "]";  // redundant brackets change nothing
    }
    return s;
  }

 private:
  std::string wrapped(const Node& n, bool need) {
    const std::string s = print(n);
    return need ? "[" + s + "]" : s;
  }

  std::string bare(const Node& n) {
    char buf[32];
    switch (n.kind) {
      case Node::Kind::kNumber:
        std::snprintf(buf, sizeof buf, "%.2f", n.number);
        return buf;
      case Node::Kind::kVariable:
        std::snprintf(buf, sizeof buf, "#%d", static_cast<int>(n.number));
        return buf;
      case Node::Kind::kIndirect:
        return "#[" + print(*n.kids[0]) + "]";
      case Node::Kind::kUnary:
        return spelling(n.op, false) + wrapped(*n.kids[0], strength(*n.kids[0]) < 6);
      case Node::Kind::kBinary: {
        const int level = level_of(n.op);
        // Left-associative: the right operand needs brackets at the same level too.
        return wrapped(*n.kids[0], strength(*n.kids[0]) < level) + spelling(n.op, g_.chance(0.5)) +
               wrapped(*n.kids[1], strength(*n.kids[1]) <= level);
      }
      case Node::Kind::kCall: {
        std::string s(function_info(n.function).name);
        s += "[" + print(*n.kids[0]);
        if (n.kids.size() > 1) {
          s += ", " + print(*n.kids[1]);
        }
        return s + "]";
      }
    }
    return "?";
  }

  Generator& g_;
};

struct Outcome {
  MacroValue value;
  int alarm = 0;
};

// The direct evaluation of a tree: the macro rules written out once more, in tree form.
Outcome reference(const Node& n, const VariableStore& store) {
  const auto checked = [](double r) {
    if (!std::isfinite(r) || std::fabs(r) > kMaxMagnitude) {
      return Outcome{{}, alarm::kOutOfRange};
    }
    return Outcome{MacroValue::of(r + 0.0), 0};
  };
  switch (n.kind) {
    case Node::Kind::kNumber:
      return Outcome{MacroValue::of(n.number), 0};
    case Node::Kind::kVariable:
      return Outcome{store.read(static_cast<std::int64_t>(n.number)).value, 0};
    case Node::Kind::kIndirect: {
      const Outcome index = reference(*n.kids[0], store);
      if (index.alarm) {
        return index;
      }
      return Outcome{store.read(static_cast<std::int64_t>(index.value.number())).value, 0};
    }
    case Node::Kind::kUnary: {
      const Outcome a = reference(*n.kids[0], store);
      if (a.alarm) {
        return a;
      }
      const double x = a.value.number();
      switch (n.op) {
        case OpCode::kNegate:
          return checked(-x);
        case OpCode::kPlus:
          return checked(x);
        case OpCode::kNot:
          return checked(x == 0.0 ? 1.0 : 0.0);
        default:
          return checked(static_cast<double>(~static_cast<std::int64_t>(round_half_away(x))));
      }
    }
    case Node::Kind::kCall: {
      double args[2] = {0.0, 0.0};
      for (std::size_t i = 0; i < n.kids.size(); ++i) {
        const Outcome a = reference(*n.kids[i], store);
        if (a.alarm) {
          return a;
        }
        args[i] = a.value.number();
      }
      const MathResult r = apply_function(n.function, args, static_cast<int>(n.kids.size()));
      if (!r.ok()) {
        return Outcome{{}, alarm::kOutOfRange};
      }
      return checked(r.value);
    }
    case Node::Kind::kBinary:
      break;
  }
  const Outcome l = reference(*n.kids[0], store);
  if (l.alarm) {
    return l;
  }
  const Outcome r = reference(*n.kids[1], store);
  if (r.alarm) {
    return r;
  }
  const double x = l.value.number();
  const double y = r.value.number();
  const auto truth = [](bool b) { return Outcome{MacroValue::of(b ? 1.0 : 0.0), 0}; };
  const auto bits = [](double v) { return static_cast<std::int64_t>(round_half_away(v)); };
  const VacantOrdering o = store.dialect().vacant_ordering;
  switch (n.op) {
    case OpCode::kAdd:
      return checked(x + y);
    case OpCode::kSub:
      return checked(x - y);
    case OpCode::kMul:
      return checked(x * y);
    case OpCode::kDiv:
      return y == 0.0 ? Outcome{{}, alarm::kDivisionByZero} : checked(x / y);
    case OpCode::kMod:
      return y == 0.0 ? Outcome{{}, alarm::kDivisionByZero} : checked(std::fmod(x, y));
    case OpCode::kEq:
      return truth(compare(CompareOp::kEq, l.value, r.value, o));
    case OpCode::kNe:
      return truth(compare(CompareOp::kNe, l.value, r.value, o));
    case OpCode::kGt:
      return truth(compare(CompareOp::kGt, l.value, r.value, o));
    case OpCode::kGe:
      return truth(compare(CompareOp::kGe, l.value, r.value, o));
    case OpCode::kLt:
      return truth(compare(CompareOp::kLt, l.value, r.value, o));
    case OpCode::kLe:
      return truth(compare(CompareOp::kLe, l.value, r.value, o));
    case OpCode::kAnd:
      return truth(x != 0.0 && y != 0.0);
    case OpCode::kOr:
      return truth(x != 0.0 || y != 0.0);
    case OpCode::kBitAnd:
      return checked(static_cast<double>(bits(x) & bits(y)));
    case OpCode::kBitOr:
      return checked(static_cast<double>(bits(x) | bits(y)));
    default:
      return checked(static_cast<double>(bits(x) ^ bits(y)));
  }
}

void run_random_trees(VacantOrdering ordering, std::uint32_t seed) {
  MacroDialect d;
  d.vacant_ordering = ordering;
  VariableStore store(d);
  Generator gen(seed);
  Printer printer(gen);
  int values = 0;
  int nulls = 0;
  int alarms = 0;
  for (int round = 0; round < 4000; ++round) {
    // Fresh variables every 100 trees: some null, some 0, some negative or fractional.
    if (round % 100 == 0) {
      for (int v = 1; v <= 10; ++v) {
        const int k = gen.pick(6);
        const MacroValue value = k == 0   ? MacroValue::null()
                                 : k == 1 ? MacroValue::of(0.0)
                                          : MacroValue::of((gen.pick(161) - 80) / 8.0);
        ASSERT_FALSE(store.write(v, value));
      }
      ASSERT_FALSE(store.write(20, MacroValue::of(1 + gen.pick(10))));
      ASSERT_FALSE(store.write(21, MacroValue::of(20)));
    }
    const auto tree = gen.tree(1 + gen.pick(6));
    const std::string text = printer.print(*tree);
    const ParseResult p = parse_expression(text, 1, ParseMode::kWhole, ParseLimits{64});
    ASSERT_FALSE(p.alarm) << text << ": " << p.alarm.text() << " at " << p.alarm.column;
    const EvalResult got = evaluate(p.expression, store);
    const Outcome want = reference(*tree, store);
    ASSERT_EQ(got.alarm.number, want.alarm) << text << ": " << got.alarm.text();
    if (want.alarm) {
      ++alarms;
      continue;
    }
    ASSERT_EQ(got.value.is_null(), want.value.is_null()) << text;
    ASSERT_EQ(got.value.number(), want.value.number()) << text;
    ++(want.value.is_null() ? nulls : values);
  }
  // The trees exercise all three outcomes.
  EXPECT_GT(values, 2000);
  EXPECT_GT(nulls, 20);
  EXPECT_GT(alarms, 20);
}

TEST(ExpressionRandom, PrintedTreesEvaluateLikeTheTreesDafengOrdering) {
  run_random_trees(VacantOrdering::kAsZero, 20240604u);
}

TEST(ExpressionRandom, PrintedTreesEvaluateLikeTheTreesGskOrdering) {
  run_random_trees(VacantOrdering::kLiteralGskTable, 6437u);
}

}  // namespace
}  // namespace mcnc::interp::macro
