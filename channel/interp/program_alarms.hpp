#pragma once
// Program alarm numbers of the interpreter (listed with causes and remedies in docs/alarms.md).
// 1001-1099: program format (lexical and word syntax). 1100-1199: motion and code semantics.
namespace mcnc::interp::alarm {

inline constexpr int kUnexpectedCharacter = 1001;
inline constexpr int kUnknownAddress = 1002;
inline constexpr int kMalformedNumber = 1003;
inline constexpr int kIntegerExpected = 1004;
inline constexpr int kDuplicateAddress = 1005;
inline constexpr int kUnclosedComment = 1006;
inline constexpr int kValueOutOfRange = 1007;
inline constexpr int kProgramEndMissing = 1010;

inline constexpr int kUnsupportedG = 1101;
inline constexpr int kUnsupportedM = 1102;
inline constexpr int kGroupConflict = 1103;
inline constexpr int kAbsoluteAndIncremental = 1104;
inline constexpr int kFeedMissing = 1105;
inline constexpr int kNegativeFeed = 1106;
inline constexpr int kDwellTimeMissing = 1107;
inline constexpr int kNegativeDwell = 1108;
inline constexpr int kDwellTimeTwice = 1109;
inline constexpr int kAxisInDwell = 1110;
inline constexpr int kPWithoutDwell = 1111;

}  // namespace mcnc::interp::alarm
