#include "hmi_bridge/core/client_stream.hpp"

#include <gtest/gtest.h>

#include <string>

namespace mcnc::hmi {
namespace {

// A masked client frame header announcing `length` bytes (the shortest encoding).
std::string header(std::uint64_t length, unsigned char opcode = 0x81) {
  std::string h(1, static_cast<char>(opcode));
  if (length < 126) {
    h += static_cast<char>(0x80 | length);
  } else if (length <= 0xFFFF) {
    h += static_cast<char>(0x80 | 126);
    h += static_cast<char>(length >> 8);
    h += static_cast<char>(length & 0xFF);
  } else {
    h += static_cast<char>(0x80 | 127);
    for (int shift = 56; shift >= 0; shift -= 8) {
      h += static_cast<char>((length >> shift) & 0xFF);
    }
  }
  return h + std::string("\x11\x22\x33\x44", 4);
}

TEST(ClientStream, TheRequestHeadEndsAfterItsBlankLine) {
  EXPECT_EQ(request_head_end("GET / HTTP/1.1\r\nHost: a\r\n"), std::string_view::npos);
  const std::string head = "GET / HTTP/1.1\r\nHost: a\r\n\r\n";
  EXPECT_EQ(request_head_end(head + "\x81\x85"), head.size());
}

TEST(ClientStream, OnlyAnUpgradeHeaderNamingWebsocketAsksForTheSocket) {
  EXPECT_TRUE(asks_websocket("GET /ws HTTP/1.1\r\nHost: a\r\nUpgrade: websocket\r\n\r\n"));
  EXPECT_TRUE(asks_websocket("GET /ws HTTP/1.1\r\nupgrade: WebSocket\r\n\r\n"));
  EXPECT_FALSE(asks_websocket("GET /ws HTTP/1.1\r\nHost: a\r\n\r\n"));
  EXPECT_FALSE(asks_websocket("GET /websocket HTTP/1.1\r\nX-Upgrade: websocket\r\n\r\n"));
}

TEST(ClientStream, AFrameAnnouncedLargerThanTheMostIsRefusedFromItsHeaderAlone) {
  FrameScanner scanner;
  const std::string one_gb = header(1ULL << 30);
  // Byte by byte: nothing until its header is complete, then refused, with nothing of it read.
  for (std::size_t i = 0; i + 1 < one_gb.size(); ++i) {
    EXPECT_EQ(scanner.scan(one_gb.substr(i, 1)), 0U) << i;
  }
  EXPECT_EQ(scanner.scan(one_gb.substr(one_gb.size() - 1)), 1ULL << 30);
  EXPECT_EQ(scanner.scan(header(3) + "abc"), 1ULL << 30);  // it stays refused
}

TEST(ClientStream, FramesUpToTheMostPassAcrossReadsOfAnySize) {
  std::string stream;
  for (const std::uint64_t length :
       std::initializer_list<std::uint64_t>{0, 5, 125, 126, 5000, kMaxFrameBytes}) {
    stream += header(length) + std::string(length, 'x');
  }
  stream += header(kMaxFrameBytes + 1);
  for (std::size_t chunk : {1UL, 7UL, 4096UL, 1UL << 20}) {
    FrameScanner scanner;
    std::uint64_t refused = 0;
    for (std::size_t at = 0; at < stream.size() && refused == 0; at += chunk) {
      refused = scanner.scan(std::string_view(stream).substr(at, chunk));
    }
    EXPECT_EQ(refused, kMaxFrameBytes + 1) << chunk;
  }
  // A payload that looks like a header is payload: 127 in its second byte is not a length.
  FrameScanner scanner;
  EXPECT_EQ(scanner.scan(header(14) + "\x81\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff"),
            0U);
}

}  // namespace
}  // namespace mcnc::hmi
