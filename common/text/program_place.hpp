#pragma once
// Where in a part program something is, written one way wherever it is shown (logs, `mcnc run`,
// the HMI): as compilers print it.
#include <string>
#include <string_view>

namespace mcnc::text {

// "FILE:LINE:COL"; "FILE:LINE" when the column is not known (0); "line LINE" without a file;
// "" without a line (0).
std::string program_place(std::string_view file, int line, int column);

}  // namespace mcnc::text
