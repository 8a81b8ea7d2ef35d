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
inline constexpr int kUnsupportedStatement = 1011;  // DPRNT, SPSV, ... as statements
inline constexpr int kStructureMismatch = 1012;     // END without WHILE, ENDIF without IF, ...
inline constexpr int kNestingTooDeep = 1013;        // WHILE > 5, IF blocks > 10
inline constexpr int kWordsAfterStatement = 1014;   // `GOTO 10 X5`, `ELSE 3`
inline constexpr int kBadBlockSkip = 1015;          // `/#2 G00`, `/0`

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
inline constexpr int kArcGeometry = 1112;           // end point off the circle, R too small
inline constexpr int kArcFullCircleWithR = 1113;    // start = end with R
inline constexpr int kSequenceNotFound = 1115;      // GOTO / M99 P / M98 Q target missing
inline constexpr int kCallNestingTooDeep = 1117;    // M98 > 16, G65/G66 > 5
inline constexpr int kSubprogramEndMissing = 1118;  // subprogram without M99
inline constexpr int kWrongChannel = 1119;          // CH n in another channel
inline constexpr int kBadWordValue = 1120;          // a value out of its range for this word
inline constexpr int kWordNotAllowed = 1121;        // a word this code does not take
inline constexpr int kNotInThisVersion = 1122;      // canned cycles, threading, G41/G42 ...
inline constexpr int kReleasedAxis = 1123;          // an axis released by G140 is programmed
inline constexpr int kStatementLimit = 1125;        // endless macro loop without a command
inline constexpr int kSyncForm = 1126;              // G04.1 Q forms
inline constexpr int kMustBeAlone = 1128;           // a code that needs its own block
inline constexpr int kUserAlarmRange = 1129;        // #3000 = n with n outside 0-200
inline constexpr int kLoopControl = 1130;           // BREAK outside WHILE, END without WHILE ...
inline constexpr int kNoPlaneAxis = 1131;           // arc in a plane whose axes are missing
// C1 mode (M18/M17, GSK M14/M15): C moved under speed control, M03/M04/M19 under position
// control, position control asked while the spindle turns.
inline constexpr int kSpindleControl = 1132;
inline constexpr int kNoSuchSpindle = 1133;  // S_ P4, S4=, M303, SP4 naming a spindle not there
// Canned cycles, threading, corners and tool-nose compensation (issue 4).
inline constexpr int kContourNotMonotonic = 1140;    // G71/G72 contour against its type's rule
inline constexpr int kContourStart = 1141;           // first contour block not G00/G01 (or arc)
inline constexpr int kContourTooLong = 1142;         // more than 100 contour blocks
inline constexpr int kCycleValue = 1143;             // a cycle amount out of its range
inline constexpr int kContourMissing = 1144;         // P/Q not found, empty or in wrong order
inline constexpr int kContourForbidden = 1145;       // M98/M99/G65 ... inside the contour
inline constexpr int kThreadLead = 1146;             // lead <= 0, G34 lead reaching 0
inline constexpr int kCornerDoesNotFit = 1147;       // ,C ,R / L D larger than the moves
inline constexpr int kAngleProgramming = 1148;       // ,A / Q: angle and coordinate contradict
inline constexpr int kCompensationLookahead = 1149;  // too many blocks without motion in G41/G42
inline constexpr int kCompensationGeometry = 1150;   // the offset path cannot be made
inline constexpr int kCompensationStart = 1151;      // start-up or cancel on an arc, ...
inline constexpr int kCycleWordMissing = 1152;       // G74 X without P, G75 Z without Q, ...
// Coordinate transformations (issue 24).
// G28, G52, G5x, a plane change ... under G68.1/G51.1; an increment of a mirrored axis.
inline constexpr int kFrameRestriction = 1153;
// G00, G50, T ... in polar (G12.1) or cylindrical (G07.1) interpolation; G12.1 under G42 ...
inline constexpr int kInterpolationModeRestriction = 1154;
// G27: the point reached is not the reference point; G29 without a G28/G30 before it.
inline constexpr int kReferencePoint = 1155;
// G22: a move would enter the forbidden area of the stored stroke check 2, or G22 is given
// where the tool stands in it.
inline constexpr int kStrokeLimit = 1156;
// G31: no skip input (param 5510 = 0 and no L, K or I), or one wired to no axis of the block.
inline constexpr int kSkipInput = 1157;
// G04 I: the input port the block names is no input of the machine's PLC (port of plc.signals).
inline constexpr int kInputPort = 1158;
// Inclined-axis control: its inclined or orthogonal axis exchanged (G140/G141) or made a G51.4
// slave, or an arc thread to be made on them (spec dafeng L4653-4767).
inline constexpr int kInclinedAxisRestriction = 1159;
// GSK G92 P1 / G92.1 P1 thread repair: no position recorded, or its Z outside the thread.
inline constexpr int kThreadRepair = 1160;
// G81.1 / G80.1 oscillation: an axis not enabled for it (param 5700.1), an oscillating axis
// programmed, G81.1 on an axis that oscillates, G80.1 on one that does not, the program's end
// while an axis oscillates.
inline constexpr int kOscillation = 1161;

// #3000 = n (text): alarm 3000 + n (n = 0-200), as the FANUC 0i numbers macro alarms. 3101-3121
// are also the interpreter's own macro alarms (macro_alarms.hpp); the text tells them apart.
inline constexpr int kUserAlarmBase = 3000;
inline constexpr int kUserAlarmMaxN = 200;  // the largest n

}  // namespace mcnc::interp::alarm
