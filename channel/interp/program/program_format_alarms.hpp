#pragma once
// Alarm numbers of the program splitter and the program store (listed with causes and remedies
// in docs/alarms.md, "Program files and the program store"). They sit in the program-format
// range 1001-1099 of channel/interp/program_alarms.hpp, in a block of their own: 1020-1029 for
// the text of one file, 1030-1039 for finding programs on disk.
namespace mcnc::interp::program::alarm {

inline constexpr int kProgramNumberMissing = 1020;     // `O` with no digits
inline constexpr int kProgramNumberFormat = 1021;      // `O-1`, `O1.5`, `O#1`
inline constexpr int kProgramNumberTooLong = 1022;     // more than 4 digits
inline constexpr int kDuplicateProgramNumber = 1023;   // one O number twice in a file
inline constexpr int kProgramNumberNotAtStart = 1024;  // `N10 O0001`, `/O0001`
inline constexpr int kWordsAfterProgramNumber = 1025;  // `O0001 G00 X0`
inline constexpr int kBlockOutsideProgram = 1026;      // a block before the first O line

inline constexpr int kProgramNotFound = 1030;
inline constexpr int kProgramAmbiguous = 1031;
inline constexpr int kFileUnreadable = 1032;
inline constexpr int kDirectoryUnreadable = 1033;
inline constexpr int kProgramNumberOutOfRange = 1034;
inline constexpr int kFileNameMismatch = 1035;  // O0012.nc holds O lines, none of them O0012
inline constexpr int kFileChanged = 1036;       // a running program's file no longer holds it

}  // namespace mcnc::interp::program::alarm
