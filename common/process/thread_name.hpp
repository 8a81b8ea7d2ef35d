#pragma once
// Names the calling thread (at most 15 characters), as /proc/<pid>/task/<tid>/comm, top -H and
// bench/thread_wakeups.py show it: the wake-ups and CPU of each thread of a process can then be
// told apart. A process's main thread keeps the program's name (the cycle runs there).
#include <pthread.h>

namespace mcnc::process {

inline void name_this_thread(const char* name) noexcept {
  (void)pthread_setname_np(pthread_self(), name);
}

}  // namespace mcnc::process
