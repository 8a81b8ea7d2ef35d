#pragma once
// Alarm numbers of the macro B value model, variable store and expression evaluator (listed with
// causes in docs/macro.md). The spec's alarm appendix names conditions but no numbers, so they
// take the range 3101-3199; 3111 mirrors FANUC's P/S 111 ("calculation out of range"), which
// the GSK spec cites for ASIN/ACOS domain errors and results beyond 10^47.
namespace mcnc::interp::macro::alarm {

// Syntax (parse time).
inline constexpr int kBracketNotClosed = 3101;    // '[' without ']'
inline constexpr int kUnexpectedBracket = 3102;   // ']' without '['
inline constexpr int kMissingOperand = 3103;      // `1+`, `[]`, `*2`
inline constexpr int kUnknownWord = 3104;         // `FOO[1]`, `SINE[1]`
inline constexpr int kBadVariableSyntax = 3105;   // `#-1`, `#A`, `#1.5`, a lone `#`
inline constexpr int kOperatorExpected = 3106;    // `1 2`, `#1=2=3`, `[1]X`
inline constexpr int kBracketExpected = 3107;     // `SIN 30`
inline constexpr int kArgumentCount = 3108;       // `ATAN2[1]`, `SIN[1,2]`
inline constexpr int kTooComplex = 3109;          // nesting beyond the limit (spec L6906)
inline constexpr int kMalformedNumber = 3110;     // `1.2.3`, `.`, a literal beyond 10^47
inline constexpr int kAssignmentExpected = 3120;  // `#1 5`, `#1==5` as a statement

// Evaluation.
inline constexpr int kOutOfRange = 3111;      // domain error or result beyond 10^47
inline constexpr int kDivisionByZero = 3112;  // `/` or MOD by 0 (or by null, which counts as 0)

// Variables.
inline constexpr int kUndefinedVariable = 3113;         // no such variable (#-1, #250 under GSK)
inline constexpr int kReadOnlyVariable = 3114;          // #0, or a provider's range
inline constexpr int kVariableNumberNotInteger = 3115;  // #[1.5]
inline constexpr int kCallLevelTooDeep = 3116;          // more local levels than the dialect allows
inline constexpr int kNoCallLevel = 3117;               // pop at the main level
inline constexpr int kRetainedFileFormat = 3118;        // a bad line in the retained-variable file
inline constexpr int kRetainedFileIo = 3119;            // the file cannot be read or written
inline constexpr int kProviderOverlap = 3121;           // a provider range overlaps another range

}  // namespace mcnc::interp::macro::alarm
