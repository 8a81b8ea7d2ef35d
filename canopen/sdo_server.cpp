#include "canopen/sdo_server.hpp"

#include "canopen/sdo_abort.hpp"
#include "canopen/sdo_client.hpp"
#include "canopen/sdo_frames.hpp"

#include <algorithm>

namespace mcnc::canopen {

can::CanFrame SdoServer::response(std::uint8_t command) const noexcept {
  return sdo::frame(kSdoResponseBase + node_, command, index_, sub_);
}

bool SdoServer::abort(std::uint16_t index, std::uint8_t sub, std::uint32_t code,
                      can::CanFrame& out) noexcept {
  out = sdo::frame(kSdoResponseBase + node_, sdo::kAbort, index, sub);
  sdo::put_u32_at4(out, code);
  state_ = State::idle;
  ++aborts_;
  return true;
}

bool SdoServer::on_frame(const can::CanFrame& in, can::CanFrame& out) noexcept {
  if (in.id != kSdoRequestBase + node_) {
    return false;
  }
  if (in.dlc != 8) {
    ++malformed_;
    return false;
  }
  const std::uint8_t ccs = sdo::specifier(in);
  switch (ccs) {
    case sdo::kDownloadInitiate: {
      index_ = sdo::index_of(in);
      sub_ = in.data[3];
      const bool expedited = (in.data[0] & 0x02) != 0;
      const bool sized = (in.data[0] & 0x01) != 0;
      if (expedited) {
        const std::size_t size = sized ? 4 - ((in.data[0] >> 2) & 0x03) : 4;
        const std::uint32_t code = objects_.write(index_, sub_, in.data.data() + 4, size);
        if (code != 0) {
          return abort(index_, sub_, code, out);
        }
        state_ = State::idle;
        out = response(0x60);
        return true;
      }
      expected_ = sized ? sdo::u32_at4(in) : 0;
      if (expected_ > kSdoMaxValue) {
        return abort(index_, sub_, sdo_abort::kOutOfMemory, out);
      }
      state_ = State::downloading;
      toggle_ = 0;
      value_.size = 0;
      out = response(0x60);
      return true;
    }
    case sdo::kDownloadSegment: {
      if (state_ != State::downloading) {
        return abort(index_, sub_, sdo_abort::kBadCommand, out);
      }
      const std::uint8_t t = (in.data[0] >> 4) & 1;
      if (t != toggle_) {
        return abort(index_, sub_, sdo_abort::kToggleBit, out);
      }
      const std::size_t chunk = 7 - ((in.data[0] >> 1) & 0x07);
      if (value_.size + chunk > kSdoMaxValue) {
        return abort(index_, sub_, sdo_abort::kOutOfMemory, out);
      }
      std::copy_n(in.data.begin() + 1, chunk,
                  value_.bytes.begin() + static_cast<std::ptrdiff_t>(value_.size));
      value_.size += chunk;
      if ((in.data[0] & 0x01) != 0) {
        if (expected_ != 0 && expected_ != value_.size) {
          return abort(index_, sub_, sdo_abort::kLengthMismatch, out);
        }
        const std::uint32_t code = objects_.write(index_, sub_, value_.bytes.data(), value_.size);
        if (code != 0) {
          return abort(index_, sub_, code, out);
        }
        state_ = State::idle;
      }
      out = can::CanFrame{};
      out.id = kSdoResponseBase + node_;
      out.dlc = 8;
      out.data[0] = static_cast<std::uint8_t>(0x20 | (t << 4));
      toggle_ ^= 1;
      return true;
    }
    case sdo::kUploadInitiate: {
      index_ = sdo::index_of(in);
      sub_ = in.data[3];
      const std::uint32_t code = objects_.read(index_, sub_, value_);
      if (code != 0) {
        return abort(index_, sub_, code, out);
      }
      if (value_.size <= 4) {
        out = response(static_cast<std::uint8_t>(0x43 | ((4 - value_.size) << 2)));
        std::copy_n(value_.bytes.begin(), value_.size, out.data.begin() + 4);
        state_ = State::idle;
        return true;
      }
      out = response(0x41);
      sdo::put_u32_at4(out, static_cast<std::uint32_t>(value_.size));
      state_ = State::uploading;
      toggle_ = 0;
      offset_ = 0;
      return true;
    }
    case sdo::kUploadSegment: {
      if (state_ != State::uploading) {
        return abort(index_, sub_, sdo_abort::kBadCommand, out);
      }
      const std::uint8_t t = (in.data[0] >> 4) & 1;
      if (t != toggle_) {
        return abort(index_, sub_, sdo_abort::kToggleBit, out);
      }
      const std::size_t chunk = std::min<std::size_t>(7, value_.size - offset_);
      const bool last = offset_ + chunk >= value_.size;
      out = can::CanFrame{};
      out.id = kSdoResponseBase + node_;
      out.dlc = 8;
      out.data[0] = static_cast<std::uint8_t>((t << 4) | ((7 - chunk) << 1) | (last ? 1 : 0));
      std::copy_n(value_.bytes.begin() + static_cast<std::ptrdiff_t>(offset_), chunk,
                  out.data.begin() + 1);
      offset_ += chunk;
      toggle_ ^= 1;
      if (last) {
        state_ = State::idle;
      }
      return true;
    }
    case sdo::kAbortSpecifier:
      state_ = State::idle;
      return false;
    default:
      return abort(sdo::index_of(in), in.data[3], sdo_abort::kBadCommand, out);
  }
}

}  // namespace mcnc::canopen
