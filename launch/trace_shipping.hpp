#pragma once
// Trace parts across hosts (docs/multichannel.md "Hosts"): a follower's launcher sends its
// host's parts to the coordinator once its processes have stopped, and the coordinator writes
// them into its own parts directory before the merge, so hosts need not share a directory.
// A part is sent in pieces (TraceChunk); the coordinator confirms each host (TraceReceipt).
#include "idl/dds_participant.hpp"

#include <chrono>
#include <condition_variable>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

namespace mcnc::launch {

class TracePartSender {
 public:
  TracePartSender(dds::Participant& participant, std::string host);
  // Sends the files `paths` (a missing one as empty) and waits until the coordinator confirms
  // them, at most `timeout`. False when no confirmation came.
  bool send(const std::vector<std::string>& paths, std::chrono::seconds timeout);

 private:
  std::string host_;
  std::mutex mutex_;
  std::condition_variable confirmed_cv_;
  bool confirmed_ = false;
  dds::Writer<TraceChunk> writer_;
  dds::Reader<TraceReceipt> receipts_;
};

class TracePartReceiver {
 public:
  // Writes the parts it receives into `parts_dir`.
  TracePartReceiver(dds::Participant& participant, std::string parts_dir);
  // Until every host of `hosts` has sent all its parts, at most `timeout`; returns the hosts
  // whose parts did not all come.
  std::vector<std::string> wait_for(const std::vector<std::string>& hosts,
                                    std::chrono::seconds timeout);

 private:
  std::string parts_dir_;
  std::mutex mutex_;
  std::condition_variable done_cv_;
  std::map<std::string, std::ofstream> open_;  // by part name
  std::set<std::string> done_;
  dds::Writer<TraceReceipt> receipt_writer_;
  dds::Reader<TraceChunk> reader_;
};

}  // namespace mcnc::launch
