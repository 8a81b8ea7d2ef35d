"""Random lathe programs in the subset that `mcnc interp` (FANUC/Dafeng system A, macro B) and
LinuxCNC's rs274 (G7 diameter mode, O-words) both read, rendered in both dialects.

A program is built statement by statement on a model machine: every candidate statement is run
on a copy of the model first and kept only if the run stays valid (no zero-length move, arcs with
a clear radius margin, coordinates inside the work envelope, conditions that are not decided by
rounding). So the model's output is what both interpreters must produce, and the generator never
emits a program whose result depends on a tolerance policy.

Numbers are exact (`fractions.Fraction`): a value that reaches an address word must have at most 3
decimals exactly, because `mcnc interp` truncates word values to 0.001 mm while rs274 keeps the
full double; both agree when the exact value already has 3 decimals.
"""
from __future__ import annotations

import copy
import math
import random
from dataclasses import dataclass, field
from fractions import Fraction as Q

# --- limits of the generated programs -------------------------------------------------------

X_DIAMETER_RANGE = (Q(0), Q(240))   # end points, diameter
Z_RANGE = (Q(-250), Q(60))
MIN_MOVE = Q(1, 100)                 # shorter moves are rejected: no near-zero-length moves
MIN_CHORD = Q(1)                     # arcs: chord at least 1 mm
R_MARGIN = Q(1, 20)                  # R arcs: |R| >= chord/2 + 0.05
MIN_COMPARE_GAP = 1e-6               # a comparison must not be decided by double rounding
MAX_ITERATIONS = 60
MAX_MOTIONS = 250
MAX_MAGNITUDE = Q(10) ** 6           # any intermediate macro value

# Pythagorean circles: integer points on circles of these radii give I/K arcs whose end point
# lies exactly on the circle (3-decimal coordinates), so no radius-mismatch tolerance is involved.
LATTICE_RADII = (5, 13, 25, 65, 85)


class Invalid(Exception):
    """The statement would make the program invalid or tolerance-dependent; try another."""


def decimals(q: Q, limit: int = 9) -> int | None:
    """Number of decimals of q if it terminates within `limit` digits, else None."""
    for k in range(limit + 1):
        if (q * 10**k).denominator == 1:
            return k
    return None


def fmt(q: Q, rng: random.Random | None = None) -> str:
    """Decimal text of q (which must terminate). With rng, picks among equivalent spellings that
    both dialects accept: `12` or `12.`, `0.5` or `.5`."""
    k = decimals(q)
    if k is None:
        raise ValueError(f"{q} has no short decimal form")
    sign = "-" if q < 0 else ""
    q = abs(q)
    if k == 0:
        text = str(q.numerator)
        if rng and rng.random() < 0.3:
            text += "."
        return sign + text
    scaled = str(q.numerator * 10**k // q.denominator).rjust(k + 1, "0")
    text = scaled[:-k] + "." + scaled[-k:]
    if text.startswith("0.") and rng and rng.random() < 0.3:
        text = text[1:]
    return sign + text


# --- expressions ----------------------------------------------------------------------------


@dataclass(frozen=True)
class Num:
    value: Q
    text: str


@dataclass(frozen=True)
class Var:
    n: int


@dataclass(frozen=True)
class Bin:
    op: str  # + - * /
    a: object
    b: object


@dataclass(frozen=True)
class Func:
    name: str  # SIN COS SQRT ABS
    arg: object


@dataclass(frozen=True)
class Group:
    """Explicit brackets that the precedence would not need."""
    inner: object


PRECEDENCE = {"+": 1, "-": 1, "*": 2, "/": 2}


def render(e) -> str:
    """Expression text; identical in both dialects (LinuxCNC only wants the outermost brackets
    of an assignment, see render_value)."""
    if isinstance(e, Num):
        return e.text
    if isinstance(e, Var):
        return f"#{e.n}"
    if isinstance(e, Func):
        return f"{e.name}[{render(e.arg)}]"
    if isinstance(e, Group):
        return f"[{render(e.inner)}]"
    left, right = render(e.a), render(e.b)
    p = PRECEDENCE[e.op]
    if isinstance(e.a, Bin) and PRECEDENCE[e.a.op] < p:
        left = f"[{left}]"
    if isinstance(e.b, Bin) and (PRECEDENCE[e.b.op] < p
                                 or (PRECEDENCE[e.b.op] == p and e.op in "-/")):
        right = f"[{right}]"
    return f"{left}{e.op}{right}"


def render_value(e) -> str:
    """An operand after an address letter or `=`: a number, a variable, or a bracketed
    expression (LinuxCNC needs the brackets; FANUC accepts them)."""
    if isinstance(e, (Num, Var, Group)):
        return render(e)
    return f"[{render(e)}]"


def evaluate(e, env):
    """Exact value (Fraction) of e, or a float when SIN/COS/an irrational SQRT took part."""
    if isinstance(e, Num):
        return e.value
    if isinstance(e, Var):
        if e.n not in env:
            raise Invalid(f"#{e.n} read before it is set")
        return env[e.n]
    if isinstance(e, Group):
        return evaluate(e.inner, env)
    if isinstance(e, Func):
        x = evaluate(e.arg, env)
        if e.name == "ABS":
            return abs(x)
        if e.name == "SQRT":
            if x < 0:
                raise Invalid("SQRT of a negative number")
            return exact_sqrt(x) if isinstance(x, Q) else math.sqrt(x)
        f = math.sin if e.name == "SIN" else math.cos
        return f(math.radians(float(x)))
    a, b = evaluate(e.a, env), evaluate(e.b, env)
    if isinstance(a, float) or isinstance(b, float):
        a, b = float(a), float(b)
    if e.op == "+":
        v = a + b
    elif e.op == "-":
        v = a - b
    elif e.op == "*":
        v = a * b
    else:
        if b == 0:
            raise Invalid("division by zero")
        v = a / b
    if abs(v) > MAX_MAGNITUDE:
        raise Invalid("value too large")
    return v


def exact_sqrt(x: Q):
    n, d = math.isqrt(x.numerator), math.isqrt(x.denominator)
    if n * n == x.numerator and d * d == x.denominator:
        return Q(n, d)
    return math.sqrt(x)


def integral(e, env) -> bool:
    """True when e is computed with integers only, so a double gets it exactly."""
    if isinstance(e, Num):
        return e.value.denominator == 1
    if isinstance(e, Var):
        v = env.get(e.n)
        return isinstance(v, Q) and v.denominator == 1
    if isinstance(e, Group):
        return integral(e.inner, env)
    if isinstance(e, Bin):
        return e.op != "/" and integral(e.a, env) and integral(e.b, env)
    return False


def word_value(e, env) -> Q:
    """The value of an address word: exact, at most 3 decimals (see the module comment)."""
    v = evaluate(e, env)
    if not isinstance(v, Q) or (v * 1000).denominator != 1:
        raise Invalid("address value is not an exact 3-decimal number")
    return v


COMPARE = {
    "EQ": lambda a, b: a == b, "NE": lambda a, b: a != b, "GT": lambda a, b: a > b,
    "GE": lambda a, b: a >= b, "LT": lambda a, b: a < b, "LE": lambda a, b: a <= b,
}
NEGATION = {"EQ": "NE", "NE": "EQ", "GT": "LE", "LE": "GT", "LT": "GE", "GE": "LT"}


@dataclass(frozen=True)
class Cond:
    lhs: object
    op: str
    rhs: object

    def holds(self, env) -> bool:
        a, b = evaluate(self.lhs, env), evaluate(self.rhs, env)
        exact = integral(self.lhs, env) and integral(self.rhs, env)
        if not exact and abs(float(a) - float(b)) < MIN_COMPARE_GAP:
            raise Invalid("comparison too close to call")
        return COMPARE[self.op](a, b)

    def text(self, negate: bool = False) -> str:
        op = NEGATION[self.op] if negate else self.op
        return f"{render(self.lhs)} {op} {render(self.rhs)}"


# --- the model machine ----------------------------------------------------------------------


@dataclass
class Motion:
    """One expected command, in the common frame: X as radius, mm."""
    op: str                      # rapid linear arc dwell
    x: float = 0.0
    z: float = 0.0
    cx: float = 0.0              # arc centre
    cz: float = 0.0
    dir: str = ""                # cw ccw
    feed: float = 0.0
    feed_mode: str = ""          # per_min per_rev
    seconds: float = 0.0
    origin: str = ""             # where it came from, for reports (not compared)


@dataclass
class Model:
    x: Q = Q(0)                  # radius
    z: Q = Q(0)
    feed: Q | None = None
    feed_mode: str = "per_min"
    globals: dict = field(default_factory=dict)
    frames: list = field(default_factory=lambda: [{}])
    out: list = field(default_factory=list)
    iterations: int = 0

    def clone(self) -> "Model":
        return copy.deepcopy(self)

    def env(self) -> dict:
        """Variables readable now: the current call level's locals and the commons."""
        return {**self.globals, **self.frames[-1]}

    def set(self, n: int, value) -> None:
        (self.frames[-1] if n < 100 else self.globals)[n] = value

    def emit(self, m: Motion) -> None:
        self.out.append(m)
        if len(self.out) > MAX_MOTIONS:
            raise Invalid("program too long")


def check_end(x: Q, z: Q) -> None:
    if not (X_DIAMETER_RANGE[0] <= 2 * x <= X_DIAMETER_RANGE[1] and Z_RANGE[0] <= z <= Z_RANGE[1]):
        raise Invalid("end point outside the envelope")


def r_arc_centre(sx, sz, ex, ez, r: float, cw: bool):
    """Centre of the R arc in the (Z, X) plane. G18 looks from +Y, where Z is the abscissa
    and X the ordinate: a minor (R > 0) clockwise arc has its centre right of the chord."""
    dz, dx = ez - sz, ex - sx
    chord = math.hypot(dz, dx)
    h = math.sqrt(r * r - chord * chord / 4)
    left_z, left_x = -dx / chord, dz / chord          # chord direction turned +90°
    side = (-1 if cw else 1) * (1 if r > 0 else -1)
    return (sx + ex) / 2 + side * h * left_x, (sz + ez) / 2 + side * h * left_z


# --- statements -----------------------------------------------------------------------------
# Each statement runs on the model (run), and renders itself in both dialects (ours, lcnc) as a
# list of lines. LinuxCNC lines that end a motion are followed by a DEBUG comment printing the
# exact end point, because rs274's canonical calls print only 4 decimals.

DEBUG_END = "(DEBUG,@ %.9f #5420 #5422)"


@dataclass
class Assign:
    var: int
    expr: object

    def run(self, m: Model) -> None:
        m.set(self.var, evaluate(self.expr, m.env()))

    def ours(self):
        return [f"#{self.var}={render(self.expr)}"]

    def lcnc(self):
        return [f"#{self.var} = {render_value(self.expr)}"]


@dataclass
class Move:
    g: int                         # 0 1 2 3
    gtext: str                     # how ours spells it: G1, G01
    show_g: bool                   # False: the G word is left to modality
    x: tuple | None = None         # ("X"|"U", expr): diameter, absolute or increment
    z: tuple | None = None         # ("Z"|"W", expr)
    radius: object = None          # R expr
    ik: tuple | None = None        # (I expr | None, K expr | None): radius values
    feed: Q | None = None          # F word
    feed_mode: str | None = None   # switch to per_min / per_rev in this block (with F)

    def run(self, m: Model) -> None:
        env = m.env()
        sx, sz = m.x, m.z
        ex, ez = sx, sz
        if self.x:
            v = word_value(self.x[1], env) / 2
            ex = v if self.x[0] == "X" else sx + v
        if self.z:
            v = word_value(self.z[1], env)
            ez = v if self.z[0] == "Z" else sz + v
        check_end(ex, ez)
        chord2 = (ex - sx) ** 2 + (ez - sz) ** 2
        if chord2 < MIN_MOVE**2:
            raise Invalid("move too short")
        if self.feed_mode:
            m.feed_mode = self.feed_mode
        if self.feed is not None:
            m.feed = self.feed
        if self.g == 0:
            m.emit(Motion("rapid", float(ex), float(ez)))
        elif self.g == 1:
            m.emit(Motion("linear", float(ex), float(ez), feed=float(m.feed),
                          feed_mode=m.feed_mode))
        else:
            cx, cz = self.arc_centre(sx, sz, ex, ez, chord2, env)
            m.emit(Motion("arc", float(ex), float(ez), cx, cz, "cw" if self.g == 2 else "ccw",
                          float(m.feed), m.feed_mode))
        m.x, m.z = ex, ez

    def arc_centre(self, sx, sz, ex, ez, chord2, env):
        if chord2 < MIN_CHORD**2:
            raise Invalid("arc chord too short")
        if self.radius is not None:
            r = word_value(self.radius, env)
            if abs(r) < R_MARGIN or (abs(r) - R_MARGIN) ** 2 < chord2 / 4:
                raise Invalid("R too close to half the chord")
            return r_arc_centre(float(sx), float(sz), float(ex), float(ez), float(r), self.g == 2)
        i = word_value(self.ik[0], env) if self.ik[0] is not None else Q(0)
        k = word_value(self.ik[1], env) if self.ik[1] is not None else Q(0)
        cx, cz = sx + i, sz + k
        if (sx - cx) ** 2 + (sz - cz) ** 2 != (ex - cx) ** 2 + (ez - cz) ** 2:
            raise Invalid("end point not on the I/K circle")
        return float(cx), float(cz)

    def ours(self):
        words = []
        if self.feed_mode:
            words.append("G98" if self.feed_mode == "per_min" else "G99")
        if self.show_g:
            words.append(self.gtext)
        for w in (self.x, self.z):
            if w:
                words.append(w[0] + render_value(w[1]))
        words += self.arc_words()
        if self.feed is not None:
            words.append("F" + fmt(self.feed))
        return [" ".join(words)]

    def lcnc(self):
        """U/W have no LinuxCNC form: a block with only increments runs in G91 (X increments
        are diameters under G7); a block mixing both reads the current position (#5420 is the
        X radius, #5422 is Z) to make the increment absolute."""
        words = []
        if self.feed_mode:
            words.append("G94" if self.feed_mode == "per_min" else "G95")
        incremental = [w for w in (self.x, self.z) if w and w[0] in "UW"]
        absolute = [w for w in (self.x, self.z) if w and w[0] in "XZ"]
        g91 = bool(incremental) and not absolute
        if g91:
            words.append("G91")
        if self.show_g or g91:
            words.append(f"G{self.g}")
        for w in (self.x, self.z):
            if not w:
                continue
            letter, e = w
            if g91 or letter in "XZ":
                words.append({"U": "X", "W": "Z"}.get(letter, letter) + render_value(e))
            elif letter == "U":
                words.append(f"X[#5420*2+{render_value(e)}]")
            else:
                words.append(f"Z[#5422+{render_value(e)}]")
        words += self.arc_words()
        if self.feed is not None:
            words.append("F" + fmt(self.feed))
        lines = [" ".join(words)]
        if g91:
            lines.append("G90")
        return lines + [DEBUG_END]

    def arc_words(self):
        if self.radius is not None:
            return ["R" + render_value(self.radius)]
        if self.ik:
            return [a + render_value(e) for a, e in zip("IK", self.ik) if e is not None]
        return []


@dataclass
class Dwell:
    seconds: Q
    word: str        # ours: "X" (seconds) or "P" (milliseconds)
    gtext: str

    def run(self, m: Model) -> None:
        m.emit(Motion("dwell", seconds=float(self.seconds)))

    def ours(self):
        if self.word == "P":
            return [f"{self.gtext} P{int(self.seconds * 1000)}"]
        return [f"{self.gtext} X{fmt(self.seconds)}"]

    def lcnc(self):
        return [f"G4 P{fmt(self.seconds)}"]


def run_all(body, m: Model) -> None:
    for s in body:
        s.run(m)


def indent(lines):
    return ["  " + line for line in lines]


@dataclass
class Loop:
    """`#c=init` then WHILE [cond] DOn ... `#c=#c+step` ENDn (LinuxCNC: o-while)."""
    init: Assign
    cond: Cond
    body: list
    step: Assign
    level: int       # DO1/DO2 within its program
    onum: int

    def run(self, m: Model) -> None:
        self.init.run(m)
        while self.cond.holds(m.env()):
            m.iterations += 1
            if m.iterations > MAX_ITERATIONS:
                raise Invalid("too many iterations")
            run_all(self.body, m)
            self.step.run(m)

    def ours(self):
        inner = [line for s in self.body for line in s.ours()] + self.step.ours()
        return (self.init.ours() + [f"WHILE [{self.cond.text()}] DO{self.level}"] + inner
                + [f"END{self.level}"])

    def lcnc(self):
        inner = [line for s in self.body for line in s.lcnc()] + self.step.lcnc()
        return (self.init.lcnc() + [f"o{self.onum} while [{self.cond.text()}]"] + indent(inner)
                + [f"o{self.onum} endwhile"])


@dataclass
class Skip:
    """Ours: IF [cond] GOTOn, body, Nn. LinuxCNC has no GOTO: o-if on the negated condition."""
    cond: Cond
    body: list
    label: int
    onum: int

    def run(self, m: Model) -> None:
        if not self.cond.holds(m.env()):
            run_all(self.body, m)

    def ours(self):
        inner = [line for s in self.body for line in s.ours()]
        return [f"IF [{self.cond.text()}] GOTO{self.label}"] + inner + [f"N{self.label}"]

    def lcnc(self):
        inner = [line for s in self.body for line in s.lcnc()]
        return ([f"o{self.onum} if [{self.cond.text(negate=True)}]"] + indent(inner)
                + [f"o{self.onum} endif"])


@dataclass
class Sub:
    """A subprogram: O<prog> ... M99 (ours), o<prog> sub ... endsub (LinuxCNC). `macro` ones
    are called by G65 with arguments in a new local level; the others by M98. M98 keeps the
    caller's locals in FANUC but not in LinuxCNC, so M98 bodies use common variables only."""
    prog: int
    macro: bool
    nargs: int
    body: list = field(default_factory=list)

    def ours(self):
        return [f"O{self.prog:04d}"] + [line for s in self.body for line in s.ours()] + ["M99"]

    def lcnc(self):
        inner = [line for s in self.body for line in s.lcnc()]
        return [f"o{self.prog} sub"] + indent(inner) + [f"o{self.prog} endsub"]


ARG_LETTERS = "ABCIJK"  # G65 type I arguments: #1 #2 #3 #4 #5 #6


@dataclass
class Call:
    sub: Sub
    args: list = field(default_factory=list)

    def run(self, m: Model) -> None:
        if self.sub.macro:
            env = m.env()
            m.frames.append({i + 1: word_value(a, env) for i, a in enumerate(self.args)})
            run_all(self.sub.body, m)
            m.frames.pop()
        else:
            run_all(self.sub.body, m)

    def ours(self):
        if not self.sub.macro:
            return [f"M98 P{self.sub.prog}"]
        words = [f"{letter}{render_value(a)}" for letter, a in zip(ARG_LETTERS, self.args)]
        return [f"G65 P{self.sub.prog} " + " ".join(words)]

    def lcnc(self):
        args = "".join(f" [{render(a)}]" for a in self.args)
        return [f"o{self.sub.prog} call{args}"]


@dataclass
class Program:
    feed_mode: str
    feed: Q
    g18: bool
    body: list
    subs: list
    expected: list     # Motion list of the model

    def ours(self) -> str:
        first = ("G18 " if self.g18 else "") + ("G98" if self.feed_mode == "per_min" else "G99")
        lines = ["%", "O0001", f"{first} F{fmt(self.feed)}"]
        lines += [line for s in self.body for line in s.ours()] + ["M30"]
        for sub in self.subs:
            lines += sub.ours()
        return "\n".join(lines + ["%"]) + "\n"

    def lcnc(self) -> str:
        lines = [line for sub in self.subs for line in sub.lcnc()]
        # S/M3: rs274 refuses feed per revolution with the spindle stopped.
        lines += ["G18 G7 G21 G90", "S1000 M3",
                  ("G94" if self.feed_mode == "per_min" else "G95") + f" F{fmt(self.feed)}"]
        lines += [line for s in self.body for line in s.lcnc()] + ["M2"]
        return "\n".join(lines) + "\n"


# --- the generator --------------------------------------------------------------------------


@dataclass
class Scope:
    """Which variables a body may use. main and macro: locals #10-#19 and commons #100-#109;
    an M98 subprogram: commons only (#110-#119), loop counters among the commons too."""
    kind: str                 # main macro sub

    def data_vars(self):
        if self.kind == "sub":
            return list(range(110, 120))
        return list(range(10, 20)) + list(range(100, 110))

    def counter(self, level: int) -> int:
        return 140 + level if self.kind == "sub" else 20 + level

    def readable(self, env):
        """Variables with a known exact value that this scope may read."""
        if self.kind == "sub":
            return [n for n, v in env.items() if n >= 100 and isinstance(v, Q)]
        return [n for n, v in env.items() if isinstance(v, Q)]


def lattice_points(r: int):
    return [(a, b) for a in range(-r, r + 1) for b in range(-r, r + 1) if a * a + b * b == r * r]


LATTICE = {r: lattice_points(r) for r in LATTICE_RADII}


class Generator:
    def __init__(self, rng: random.Random):
        self.rng = rng
        self.labels = 100      # N labels of IF/GOTO
        self.onums = 1000      # LinuxCNC o-numbers of loops and ifs
        self.progs = 100       # subprogram numbers
        self.subs: list[Sub] = []

    # programs and blocks

    def program(self) -> Program:
        rng = self.rng
        mode = rng.choice(["per_min", "per_min", "per_rev"])
        m = Model(feed=self.feed_value(mode), feed_mode=mode)
        feed = m.feed
        body, m = self.block(m, Scope("main"), level=0, count=rng.randint(6, 18), allow_calls=True)
        return Program(mode, feed, rng.random() < 0.5, body, self.subs, m.out)

    def block(self, m: Model, scope: Scope, level: int, count: int, allow_calls: bool):
        """`count` statements valid in sequence from state m; returns them and the new state."""
        body = []
        for _ in range(count):
            for _attempt in range(15):
                mark = len(self.subs)
                try:
                    stmt = self.statement(m, scope, level, body[-1] if body else None, allow_calls)
                    after = m.clone()
                    stmt.run(after)
                except Invalid:
                    del self.subs[mark:]   # subprograms written for a rejected statement
                    continue
                body.append(stmt)
                m = after
                break
        return body, m

    def statement(self, m, scope, level, previous, allow_calls):
        rng = self.rng
        kinds = (["rapid"] * 3 + ["linear"] * 6 + ["arc_r"] * 4 + ["arc_ik"] * 3
                 + ["assign"] * 3 + ["dwell"])
        if level < 2:
            kinds += ["loop"] * 2
        if level < 3:
            kinds += ["skip"]
        if allow_calls:
            kinds += ["m98", "g65"]
        kind = rng.choice(kinds)
        if kind == "assign":
            return self.assign(m, scope)
        if kind == "dwell":
            return self.dwell()
        if kind == "loop":
            return self.loop(m, scope, level)
        if kind == "skip":
            return self.skip(m, scope, level)
        if kind in ("m98", "g65"):
            return self.call(m, kind == "g65")
        return self.move(m, scope, kind, previous, in_loop=level > 0)

    # statements

    def assign(self, m, scope):
        rng = self.rng
        var = rng.choice(scope.data_vars())
        target = self.random_decimal(-50, 150)
        return Assign(var, self.expr(target, m.env(), scope, depth=3))

    def dwell(self):
        rng = self.rng
        seconds = Q(rng.randint(1, 5000), 1000)
        return Dwell(seconds, rng.choice("XP"), rng.choice(["G04", "G4"]))

    def loop(self, m, scope, level):
        rng = self.rng
        counter = scope.counter(level)
        n = rng.randint(1, 4)
        style = rng.randrange(3)
        if style == 0:    # 0, 1, ... while < n
            init, cond, step = Q(0), Cond(Var(counter), "LT", Num(Q(n), str(n))), 1
        elif style == 1:  # 1, 2, ... while <= n
            init, cond, step = Q(1), Cond(Var(counter), "LE", Num(Q(n), str(n))), 1
        else:             # n, n-1, ... while > 0
            init, cond, step = Q(n), Cond(Var(counter), "GT", Num(Q(0), "0")), -1
        init_stmt = Assign(counter, Num(init, fmt(init)))
        op = "+" if step > 0 else "-"
        step_stmt = Assign(counter, Bin(op, Var(counter), Num(Q(1), "1")))
        first = m.clone()
        init_stmt.run(first)
        body, _ = self.block(first, scope, level + 1, rng.randint(1, 4),
                             allow_calls=scope.kind == "main")
        if not body:
            raise Invalid("empty loop body")
        self.onums += 1
        return Loop(init_stmt, cond, body, step_stmt, level + 1, self.onums)

    def skip(self, m, scope, level):
        rng = self.rng
        cond = self.condition(m.env(), scope, rng.random() < 0.5)
        body, _ = self.block(m.clone(), scope, level + 1, rng.randint(1, 3),
                             allow_calls=scope.kind == "main")
        if not body:
            raise Invalid("empty IF body")
        self.labels += 1
        self.onums += 1
        return Skip(cond, body, self.labels, self.onums)

    def call(self, m, macro: bool):
        """Call an existing subprogram of that kind, or write a new one for this call site."""
        rng = self.rng
        known = [s for s in self.subs if s.macro == macro]
        if known and rng.random() < 0.5:
            sub = rng.choice(known)
            return Call(sub, self.call_args(m, sub.nargs))
        self.progs += 1
        sub = Sub(self.progs, macro, rng.randint(1, 4) if macro else 0)
        call = Call(sub, self.call_args(m, sub.nargs))
        inside = m.clone()
        if macro:
            env = m.env()
            inside.frames.append({i + 1: word_value(a, env) for i, a in enumerate(call.args)})
        scope = Scope("macro" if macro else "sub")
        sub.body, _ = self.block(inside, scope, 0, rng.randint(2, 6), allow_calls=False)
        if not sub.body:
            raise Invalid("empty subprogram")
        self.subs.append(sub)
        return call

    def call_args(self, m, nargs):
        env = m.env()
        scope = Scope("main")
        return [self.word_expr(self.random_decimal(-20, 80), env, scope) for _ in range(nargs)]

    # motion

    def move(self, m, scope, kind, previous, in_loop):
        rng = self.rng
        env = m.env()
        g = {"rapid": 0, "linear": 1}.get(kind, rng.choice([2, 3]))
        show_g = not (isinstance(previous, Move) and previous.g == g) or rng.random() < 0.5
        gtext = rng.choice([f"G{g}", f"G0{g}"])
        mv = Move(g, gtext, show_g)
        incremental = 0.6 if in_loop else 0.3
        if kind == "arc_ik":
            ex, ez, i, k = self.ik_arc(m)
            mv.ik = (self.maybe_zero(i, env, scope), self.maybe_zero(k, env, scope))
        else:
            ex, ez = self.end_point(m, kind)
        # Which words carry the end point: an axis that does not move may be left out.
        axes = rng.choice(["XZ", "XZ", "XZ", "X", "Z"])
        if ex != m.x and "X" not in axes:
            axes += "X"
        if ez != m.z and "Z" not in axes:
            axes += "Z"
        if "X" in axes:
            inc = rng.random() < incremental
            value = 2 * (ex - m.x) if inc else 2 * ex
            mv.x = ("U" if inc else "X", self.word_expr(value, env, scope))
        if "Z" in axes:
            inc = rng.random() < incremental
            value = ez - m.z if inc else ez
            mv.z = ("W" if inc else "Z", self.word_expr(value, env, scope))
        if kind == "arc_r":
            mv.radius = self.word_expr(self.arc_radius(m.x, m.z, ex, ez), env, scope)
        if g and rng.random() < 0.25:
            mode = m.feed_mode
            if rng.random() < 0.3:
                mode = "per_rev" if mode == "per_min" else "per_min"
                mv.feed_mode = mode
            mv.feed = self.feed_value(mode)
        return mv

    def end_point(self, m, kind):
        """A new end point (radius X, Z) with 3-decimal diameter and Z, near the current one."""
        rng = self.rng
        span = 40 if kind == "rapid" else 25
        while True:
            ex = m.x + self.random_decimal(-span, span) / 2
            ez = m.z + self.random_decimal(-span, span)
            if kind == "arc_r" or rng.random() < 0.7:
                pass
            elif rng.random() < 0.5:
                ex = m.x       # a pure Z move
            else:
                ez = m.z       # a pure X move
            ex = min(max(ex, Q(5)), Q(110))
            ez = min(max(ez, Q(-200)), Q(40))
            if (ex - m.x) ** 2 + (ez - m.z) ** 2 >= 1:
                return ex, ez

    def arc_radius(self, sx, sz, ex, ez) -> Q:
        """|R| a random 5-200 % above half the chord, 3 decimals, negative (> 180°) at times."""
        rng = self.rng
        half = math.sqrt(float((ex - sx) ** 2 + (ez - sz) ** 2)) / 2
        r = Q(round((half * rng.uniform(1.05, 3.0) + 0.06) * 1000), 1000)
        return -r if rng.random() < 0.35 else r

    def ik_arc(self, m):
        """End point and I/K (radius, from the start) of an arc whose start and end are two
        points of a Pythagorean circle: exact radii, no mismatch to tolerate."""
        rng = self.rng
        base = rng.choice(LATTICE_RADII)
        scale = rng.randint(math.ceil(1500 / base), 20000 // base)   # radius 1.5-20 mm
        pts = LATTICE[base]
        s = rng.choice(pts)
        e = rng.choice([p for p in pts if p != s])
        unit = Q(scale, 1000)
        cx, cz = m.x - s[0] * unit, m.z - s[1] * unit
        ex, ez = cx + e[0] * unit, cz + e[1] * unit
        return ex, ez, cx - m.x, cz - m.z

    def maybe_zero(self, v: Q, env, scope):
        """I0/K0 may be left out (an omitted I or K is 0 in both dialects)."""
        if v == 0 and self.rng.random() < 0.5:
            return None
        return self.word_expr(v, env, scope)

    def feed_value(self, mode) -> Q:
        rng = self.rng
        if mode == "per_min":
            return Q(rng.choice([rng.randint(20, 3000), rng.randint(200, 30000) / Q(10)]))
        return Q(rng.randint(20, 600), 1000)

    # expressions

    def random_decimal(self, lo, hi) -> Q:
        """A number in [lo, hi] with 0-3 decimals."""
        digits = self.rng.choice([0, 1, 2, 3, 3])
        scale = 10**digits
        return Q(self.rng.randint(lo * scale, hi * scale), scale)

    def word_expr(self, value: Q, env, scope):
        """A word's value: mostly a literal, sometimes macro arithmetic that gives it exactly."""
        if self.rng.random() < 0.3:
            return self.expr(value, env, scope, depth=2)
        return Num(value, fmt(value, self.rng))

    def literal(self, value: Q):
        """A literal inside an expression: not negative (a leading minus sign is spelled
        differently across dialects), at most 6 decimals."""
        if value < 0 or decimals(value, 6) is None:
            raise Invalid("no literal form")
        return Num(value, fmt(value, self.rng))

    def expr(self, target: Q, env, scope, depth: int):
        """An expression whose exact value is target, built from the readable variables."""
        rng = self.rng
        names = scope.readable(env)
        for _ in range(8):
            form = rng.choice(["var", "var", "scaled", "sum", "diff", "div", "abs", "sqrt",
                               "group"])
            if depth <= 0:
                form = "var"
            try:
                return self.expr_form(form, target, env, scope, depth, names)
            except Invalid:
                continue
        return self.literal(target) if target >= 0 else self.negative(-target)

    def negative(self, magnitude: Q):
        """-magnitude without a unary minus: `0-x`."""
        return Bin("-", self.literal(Q(0)), self.literal(magnitude))

    def expr_form(self, form, target, env, scope, depth, names):
        rng = self.rng
        sub = lambda t: self.expr(t, env, scope, depth - 1)
        if form == "var":
            if not names:
                raise Invalid("no variable to read")
            v = rng.choice(names)
            rest = target - env[v]
            if rest == 0:
                return Var(v)
            if rest > 0:
                return Bin("+", Var(v), self.literal(rest))
            return Bin("-", Var(v), self.literal(-rest))
        if form == "scaled":   # v*k + rest
            if not names:
                raise Invalid("no variable to read")
            v = rng.choice(names)
            k = Q(rng.choice([2, 3, 4, 5])) / rng.choice([1, 2])
            rest = target - env[v] * k
            term = Bin("*", Var(v), self.literal(k))
            return Bin("+", term, sub(rest)) if rest >= 0 else Bin("-", term, sub(-rest))
        if form == "sum":
            part = self.random_decimal(-30, 30)
            return Bin("+", sub(part), sub(target - part))
        if form == "diff":
            part = self.random_decimal(-30, 30)
            return Bin("-", sub(target + part), sub(part))
        if form == "div":
            d = rng.choice([2, 4, 5, 8, 10])
            return Bin("/", sub(target * d), self.literal(Q(d)))
        if form == "abs":
            if target < 0:
                raise Invalid("ABS is never negative")
            return Func("ABS", sub(-target if rng.random() < 0.5 else target))
        if form == "sqrt":
            if target <= 0:   # SQRT[a*a] with a = 0 computed inexactly may see -1e-30
                raise Invalid("SQRT only of clearly positive squares")
            if rng.random() < 0.5:
                return Func("SQRT", Bin("*", sub(target), sub(target)))
            return Func("SQRT", self.literal(target * target))
        return Group(sub(target))

    def condition(self, env, scope, want: bool) -> Cond:
        """A comparison that holds (want) or not, clearly away from equality."""
        rng = self.rng
        names = scope.readable(env)
        if not names:
            lhs = self.literal(self.random_decimal(0, 10))
        else:
            v = Var(rng.choice(names))
            lhs = rng.choice([v, v, Func("SIN", v), Func("COS", v), Func("SQRT", Func("ABS", v))])
        value = float(evaluate(lhs, env))
        trig = isinstance(lhs, Func) and lhs.name in ("SIN", "COS")
        gap = rng.choice([0.002, 0.01, 0.1, 0.3] if trig else [0.002, 0.01, 0.5, 3])
        if rng.random() < 0.5:
            rhs_value, holds_if_greater = value - gap, True
        else:
            rhs_value, holds_if_greater = value + gap, False
        rhs = Q(round(rhs_value * 1000), 1000)
        op = rng.choice(["GT", "GE"] if holds_if_greater == want else ["LT", "LE"])
        rhs_expr = self.literal(rhs) if rhs >= 0 else self.negative(-rhs)
        cond = Cond(lhs, op, rhs_expr)
        if cond.holds(env) != want:
            raise Invalid("condition construction")
        return cond


def generate(seed: str) -> Program:
    """The program of one seed string: the same seed gives the same program."""
    return Generator(random.Random(seed)).program()
