// SDO client and server against frame sequences written from CiA 301 §7.2.4 (command
// specifiers, toggle bit, n and c bits, abort codes), and against each other.
#include "canopen/sdo_abort.hpp"
#include "canopen/sdo_client.hpp"
#include "canopen/sdo_frames.hpp"
#include "canopen/sdo_server.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace mcnc::canopen {
namespace {

using Bytes = std::array<std::uint8_t, 8>;

can::CanFrame frame(std::uint32_t id, const Bytes& bytes, std::uint8_t dlc = 8) {
  can::CanFrame f;
  f.id = id;
  f.dlc = dlc;
  f.data = bytes;
  return f;
}

// A small object dictionary: 0x6041 statusword (read only), 0x6060 modes of operation,
// 0x1008 device name (read only string), 0x2000:01 a writable domain.
class TestDictionary final : public ObjectAccess {
 public:
  TestDictionary() {
    objects_[{0x6041, 0}] = {{0x37, 0x06}, false};
    objects_[{0x6060, 0}] = {{0x00}, true};
    const std::string name = "mcnc drive";
    objects_[{0x1008, 0}] = {std::vector<std::uint8_t>(name.begin(), name.end()), false};
    objects_[{0x2000, 1}] = {{}, true};
  }
  std::uint32_t read(std::uint16_t index, std::uint8_t sub, SdoValue& out) noexcept override {
    const auto it = objects_.find({index, sub});
    if (it == objects_.end()) {
      return sdo_abort::kNoObject;
    }
    out.size = it->second.bytes.size();
    std::copy(it->second.bytes.begin(), it->second.bytes.end(), out.bytes.begin());
    return 0;
  }
  std::uint32_t write(std::uint16_t index, std::uint8_t sub, const std::uint8_t* data,
                      std::size_t size) noexcept override {
    const auto it = objects_.find({index, sub});
    if (it == objects_.end()) {
      return sdo_abort::kNoObject;
    }
    if (!it->second.writable) {
      return sdo_abort::kReadOnly;
    }
    it->second.bytes.assign(data, data + size);
    return 0;
  }
  struct Object {
    std::vector<std::uint8_t> bytes;
    bool writable = false;
  };
  std::map<std::pair<std::uint16_t, std::uint8_t>, Object> objects_;
};

constexpr std::uint8_t kNode = 5;
constexpr std::uint32_t kRequest = 0x605;
constexpr std::uint32_t kResponse = 0x585;

void expect_frame(const can::CanFrame& f, std::uint32_t id, const Bytes& bytes) {
  EXPECT_EQ(f.id, id);
  EXPECT_EQ(f.dlc, 8);
  for (std::size_t i = 0; i < 8; ++i) {
    EXPECT_EQ(f.data[i], bytes[i]) << "byte " << i;
  }
}

TEST(Sdo, ExpeditedDownloadOfOneByte) {
  TestDictionary od;
  SdoClient client(kNode, 100000);
  SdoServer server(kNode, od);
  can::CanFrame req;
  const std::uint8_t csp = 8;  // 0x6060 = 8: cyclic synchronous position
  ASSERT_TRUE(client.download(0x6060, 0, &csp, 1, 0, req));
  expect_frame(req, kRequest, {0x2F, 0x60, 0x60, 0x00, 0x08, 0, 0, 0});
  can::CanFrame resp;
  ASSERT_TRUE(server.on_frame(req, resp));
  expect_frame(resp, kResponse, {0x60, 0x60, 0x60, 0x00, 0, 0, 0, 0});
  can::CanFrame next;
  EXPECT_FALSE(client.on_frame(resp, 10, next));
  EXPECT_EQ(client.state(), SdoClient::State::done);
  const std::vector<std::uint8_t> expected{8};
  EXPECT_EQ(od.objects_[std::make_pair(std::uint16_t{0x6060}, std::uint8_t{0})].bytes, expected);
}

TEST(Sdo, ExpeditedUploadOfTwoBytes) {
  TestDictionary od;
  SdoClient client(kNode, 100000);
  SdoServer server(kNode, od);
  can::CanFrame req;
  ASSERT_TRUE(client.upload(0x6041, 0, 0, req));
  expect_frame(req, kRequest, {0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0});
  can::CanFrame resp;
  ASSERT_TRUE(server.on_frame(req, resp));
  expect_frame(resp, kResponse, {0x4B, 0x41, 0x60, 0x00, 0x37, 0x06, 0, 0});  // n = 2
  can::CanFrame next;
  EXPECT_FALSE(client.on_frame(resp, 10, next));
  ASSERT_EQ(client.state(), SdoClient::State::done);
  ASSERT_EQ(client.value().size, 2U);
  EXPECT_EQ(client.value().bytes[0], 0x37);
  EXPECT_EQ(client.value().bytes[1], 0x06);
}

TEST(Sdo, SegmentedDownloadTogglesAndMarksTheLastSegment) {
  TestDictionary od;
  SdoClient client(kNode, 100000);
  SdoServer server(kNode, od);
  const std::string text = "0123456789";
  const auto* data = reinterpret_cast<const std::uint8_t*>(text.data());
  can::CanFrame f;
  ASSERT_TRUE(client.download(0x2000, 1, data, text.size(), 0, f));
  expect_frame(f, kRequest, {0x21, 0x00, 0x20, 0x01, 0x0A, 0, 0, 0});  // size indicated: 10
  can::CanFrame r;
  ASSERT_TRUE(server.on_frame(f, r));
  expect_frame(r, kResponse, {0x60, 0x00, 0x20, 0x01, 0, 0, 0, 0});
  ASSERT_TRUE(client.on_frame(r, 1, f));
  expect_frame(f, kRequest, {0x00, '0', '1', '2', '3', '4', '5', '6'});  // t 0, n 0, c 0
  ASSERT_TRUE(server.on_frame(f, r));
  expect_frame(r, kResponse, {0x20, 0, 0, 0, 0, 0, 0, 0});
  ASSERT_TRUE(client.on_frame(r, 2, f));
  expect_frame(f, kRequest, {0x19, '7', '8', '9', 0, 0, 0, 0});  // t 1, n 4, c 1
  ASSERT_TRUE(server.on_frame(f, r));
  expect_frame(r, kResponse, {0x30, 0, 0, 0, 0, 0, 0, 0});
  EXPECT_FALSE(client.on_frame(r, 3, f));
  EXPECT_EQ(client.state(), SdoClient::State::done);
  EXPECT_EQ(
      std::string(od.objects_[{0x2000, 1}].bytes.begin(), od.objects_[{0x2000, 1}].bytes.end()),
      text);
}

TEST(Sdo, SegmentedUploadOfTheDeviceName) {
  TestDictionary od;
  SdoClient client(kNode, 100000);
  SdoServer server(kNode, od);
  can::CanFrame f;
  ASSERT_TRUE(client.upload(0x1008, 0, 0, f));
  can::CanFrame r;
  ASSERT_TRUE(server.on_frame(f, r));
  expect_frame(r, kResponse, {0x41, 0x08, 0x10, 0x00, 0x0A, 0, 0, 0});
  ASSERT_TRUE(client.on_frame(r, 1, f));
  expect_frame(f, kRequest, {0x60, 0, 0, 0, 0, 0, 0, 0});
  ASSERT_TRUE(server.on_frame(f, r));
  expect_frame(r, kResponse, {0x00, 'm', 'c', 'n', 'c', ' ', 'd', 'r'});
  ASSERT_TRUE(client.on_frame(r, 2, f));
  expect_frame(f, kRequest, {0x70, 0, 0, 0, 0, 0, 0, 0});
  ASSERT_TRUE(server.on_frame(f, r));
  expect_frame(r, kResponse, {0x19, 'i', 'v', 'e', 0, 0, 0, 0});
  EXPECT_FALSE(client.on_frame(r, 3, f));
  ASSERT_EQ(client.state(), SdoClient::State::done);
  EXPECT_EQ(
      std::string(client.value().bytes.begin(),
                  client.value().bytes.begin() + static_cast<std::ptrdiff_t>(client.value().size)),
      "mcnc drive");
}

TEST(Sdo, ServerAbortNamesTheReason) {
  TestDictionary od;
  SdoClient client(kNode, 100000);
  SdoServer server(kNode, od);
  can::CanFrame f;
  const std::uint8_t v[2] = {0, 0};
  ASSERT_TRUE(client.download(0x6041, 0, v, 2, 0, f));
  can::CanFrame r;
  ASSERT_TRUE(server.on_frame(f, r));
  expect_frame(r, kResponse, {0x80, 0x41, 0x60, 0x00, 0x02, 0x00, 0x01, 0x06});
  EXPECT_FALSE(client.on_frame(r, 1, f));
  EXPECT_EQ(client.state(), SdoClient::State::aborted);
  EXPECT_TRUE(client.aborted_by_server());
  EXPECT_EQ(client.abort_code(), sdo_abort::kReadOnly);
  EXPECT_STREQ(sdo_abort_text(client.abort_code()), "attempt to write a read only object");

  ASSERT_TRUE(client.upload(0x7000, 3, 2, f));
  ASSERT_TRUE(server.on_frame(f, r));
  expect_frame(r, kResponse, {0x80, 0x00, 0x70, 0x03, 0x00, 0x00, 0x02, 0x06});
  client.on_frame(r, 3, f);
  EXPECT_EQ(client.abort_code(), sdo_abort::kNoObject);
}

TEST(Sdo, ALateAnswerToAnotherObjectIsIgnoredNotTakenForAnError) {
  // Start-up sent the write of 0x6060 twice (the first answer was late); the server answered
  // both. The second answer arrives while the next request, the read of 0x6041, is under way.
  TestDictionary od;
  SdoClient client(kNode, 100000);
  SdoServer server(kNode, od);
  can::CanFrame write;
  const std::uint8_t csp = 8;
  ASSERT_TRUE(client.download(0x6060, 0, &csp, 1, 0, write));
  can::CanFrame first;
  can::CanFrame second;
  ASSERT_TRUE(server.on_frame(write, first));
  ASSERT_TRUE(server.on_frame(write, second));
  can::CanFrame out;
  EXPECT_FALSE(client.on_frame(first, 10, out));
  ASSERT_EQ(client.state(), SdoClient::State::done);

  can::CanFrame read;
  ASSERT_TRUE(client.upload(0x6041, 0, 20, read));
  EXPECT_FALSE(client.on_frame(second, 30, out));
  EXPECT_EQ(client.state(), SdoClient::State::uploading);
  EXPECT_EQ(client.stale(), 1U);
  // Nor is a late abort for another object.
  EXPECT_FALSE(
      client.on_frame(frame(kResponse, {0x80, 0x00, 0x70, 0x03, 0, 0, 0x02, 0x06}), 40, out));
  EXPECT_EQ(client.state(), SdoClient::State::uploading);
  can::CanFrame answer;
  ASSERT_TRUE(server.on_frame(read, answer));
  EXPECT_FALSE(client.on_frame(answer, 50, out));
  EXPECT_EQ(client.state(), SdoClient::State::done);
  EXPECT_EQ(client.value().size, 2U);
}

TEST(Sdo, ClientAbortsOnAToggleError) {
  SdoClient client(kNode, 100000);
  can::CanFrame f;
  ASSERT_TRUE(client.upload(0x1008, 0, 0, f));
  ASSERT_TRUE(client.on_frame(frame(kResponse, {0x41, 0x08, 0x10, 0x00, 0x0A, 0, 0, 0}), 1, f));
  // The first segment must carry toggle 0; this one says 1.
  ASSERT_TRUE(client.on_frame(frame(kResponse, {0x10, 'm', 'c', 'n', 'c', ' ', 'd', 'r'}), 2, f));
  expect_frame(f, kRequest, {0x80, 0x08, 0x10, 0x00, 0x00, 0x00, 0x03, 0x05});
  EXPECT_EQ(client.state(), SdoClient::State::aborted);
  EXPECT_FALSE(client.aborted_by_server());
  EXPECT_EQ(client.abort_code(), sdo_abort::kToggleBit);
}

TEST(Sdo, ServerAbortsOnAToggleErrorAndAnOutOfSequenceSegment) {
  TestDictionary od;
  SdoServer server(kNode, od);
  can::CanFrame r;
  // A download segment without an initiate.
  ASSERT_TRUE(server.on_frame(frame(kRequest, {0x01, 1, 2, 3, 4, 5, 6, 7}), r));
  EXPECT_EQ(r.data[0], 0x80);
  EXPECT_EQ(sdo::u32_at4(r), sdo_abort::kBadCommand);
  ASSERT_TRUE(server.on_frame(frame(kRequest, {0x21, 0x00, 0x20, 0x01, 0x0A, 0, 0, 0}), r));
  ASSERT_TRUE(server.on_frame(frame(kRequest, {0x10, 1, 2, 3, 4, 5, 6, 7}), r));  // toggle 1
  expect_frame(r, kResponse, {0x80, 0x00, 0x20, 0x01, 0x00, 0x00, 0x03, 0x05});
  EXPECT_EQ(server.aborts_sent(), 2U);
  // An unknown command specifier (7).
  ASSERT_TRUE(server.on_frame(frame(kRequest, {0xE0, 0x41, 0x60, 0, 0, 0, 0, 0}), r));
  EXPECT_EQ(sdo::u32_at4(r), sdo_abort::kBadCommand);
}

TEST(Sdo, TimeoutAbortsTheTransfer) {
  SdoClient client(kNode, 50000);  // 50 ms
  can::CanFrame f;
  ASSERT_TRUE(client.upload(0x6041, 0, 1000, f));
  EXPECT_FALSE(client.on_time(51000, f));  // exactly the timeout: not yet
  EXPECT_TRUE(client.busy());
  ASSERT_TRUE(client.on_time(51001, f));
  expect_frame(f, kRequest, {0x80, 0x41, 0x60, 0x00, 0x00, 0x00, 0x04, 0x05});
  EXPECT_EQ(client.abort_code(), sdo_abort::kTimeout);
  EXPECT_FALSE(client.on_time(90000, f));  // once
}

TEST(Sdo, TruncatedFramesAreCountedAndDropped) {
  TestDictionary od;
  SdoClient client(kNode, 100000);
  SdoServer server(kNode, od);
  can::CanFrame f;
  ASSERT_TRUE(client.upload(0x1008, 0, 0, f));
  can::CanFrame r;
  ASSERT_TRUE(server.on_frame(f, r));
  ASSERT_TRUE(client.on_frame(r, 1, f));
  ASSERT_TRUE(server.on_frame(f, r));
  // The segment arrives cut to 4 bytes: dropped, counted, the transfer still waits for it.
  can::CanFrame cut = r;
  cut.dlc = 4;
  can::CanFrame none;
  EXPECT_FALSE(client.on_frame(cut, 2, none));
  EXPECT_EQ(client.malformed(), 1U);
  EXPECT_TRUE(client.busy());
  EXPECT_TRUE(client.on_frame(r, 3, f));  // the whole one goes on
  // A request cut short at the server: no answer, counted.
  can::CanFrame short_request = f;
  short_request.dlc = 1;
  EXPECT_FALSE(server.on_frame(short_request, r));
  EXPECT_EQ(server.malformed(), 1U);
  // Frames of other nodes are not looked at.
  EXPECT_FALSE(client.on_frame(frame(0x586, {0x80, 0, 0, 0, 0, 0, 0, 0}), 4, none));
  EXPECT_TRUE(client.busy());
}

TEST(Sdo, RandomValuesRoundTrip) {
  std::mt19937 rng(7);
  TestDictionary od;
  SdoClient client(kNode, 100000);
  SdoServer server(kNode, od);
  for (int n = 0; n < 200; ++n) {
    const std::size_t size = std::uniform_int_distribution<std::size_t>(1, kSdoMaxValue)(rng);
    std::vector<std::uint8_t> value(size);
    for (auto& b : value) {
      b = static_cast<std::uint8_t>(rng());
    }
    can::CanFrame f;
    can::CanFrame r;
    ASSERT_TRUE(client.download(0x2000, 1, value.data(), size, 0, f));
    int frames = 0;
    bool more = true;
    while (more) {
      ASSERT_TRUE(server.on_frame(f, r));
      more = client.on_frame(r, 0, f);
      ASSERT_LT(++frames, 100);
    }
    ASSERT_EQ(client.state(), SdoClient::State::done) << size;
    ASSERT_TRUE(client.upload(0x2000, 1, 0, f));
    more = true;
    while (more) {
      ASSERT_TRUE(server.on_frame(f, r));
      more = client.on_frame(r, 0, f);
    }
    ASSERT_EQ(client.state(), SdoClient::State::done);
    ASSERT_EQ(client.value().size, size);
    EXPECT_TRUE(std::equal(value.begin(), value.end(), client.value().bytes.begin()));
  }
}

}  // namespace
}  // namespace mcnc::canopen
