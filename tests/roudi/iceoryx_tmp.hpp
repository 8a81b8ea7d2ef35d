// iceoryx 2.0 keeps RouDi's socket and locks, and each runtime's socket, in /tmp, a path fixed
// when iceoryx is built. A test host of its own (a mount namespace, a QEMU guest) needs a /tmp
// where none of another host's iceoryx files shows but everything else still does: a build
// tree and a test's machine files may lie in /tmp.
#pragma once

#include <string>

namespace mcnc::test {

// Covers the folder `tmp` (a /tmp, seen from where the caller stands) with a tmpfs and binds
// each of its folders and regular files back, the iceoryx files (sockets, roudi*, iox-*,
// iceoryx_*) excepted. The caller must be in a mount namespace of its own, or be a guest's
// init. Returns "" on success, else what failed and why; on failure part of it may be done.
std::string cover_iceoryx_files(const std::string& tmp);

}  // namespace mcnc::test
