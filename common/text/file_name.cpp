#include "common/text/file_name.hpp"

namespace mcnc::text {

bool is_plain_file_name(std::string_view name) noexcept {
  return !name.empty() && name.find('/') == std::string_view::npos &&
         name.find('\\') == std::string_view::npos && name != "." && name != "..";
}

}  // namespace mcnc::text
