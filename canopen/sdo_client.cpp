#include "canopen/sdo_client.hpp"

#include "canopen/sdo_abort.hpp"
#include "canopen/sdo_frames.hpp"

#include <algorithm>

namespace mcnc::canopen {

can::CanFrame SdoClient::request(std::uint8_t command) const noexcept {
  return sdo::frame(kSdoRequestBase + node_, command, index_, sub_);
}

// Segment requests carry only the command byte: bytes 1-7 are reserved.
can::CanFrame SdoClient::segment_request(std::uint8_t command) const noexcept {
  can::CanFrame f;
  f.id = kSdoRequestBase + node_;
  f.dlc = 8;
  f.data[0] = command;
  return f;
}

bool SdoClient::fail(std::uint32_t code, can::CanFrame& out) noexcept {
  out = request(sdo::kAbort);
  sdo::put_u32_at4(out, code);
  state_ = State::aborted;
  abort_code_ = code;
  by_server_ = false;
  return true;
}

bool SdoClient::download(std::uint16_t index, std::uint8_t sub, const std::uint8_t* data,
                         std::size_t size, std::uint64_t now_us, can::CanFrame& out) noexcept {
  if (busy() || size > kSdoMaxValue || (size > 0 && data == nullptr)) {
    return false;
  }
  index_ = index;
  sub_ = sub;
  value_.size = size;
  std::copy_n(data, size, value_.bytes.begin());
  abort_code_ = 0;
  by_server_ = false;
  offset_ = 0;
  toggle_ = 0;
  initiated_ = false;
  last_us_ = now_us;
  state_ = State::downloading;
  segmented_ = size > 4 || size == 0;
  if (!segmented_) {
    // Expedited, size indicated: e = 1, s = 1, n = 4 - size bytes without data.
    out = request(static_cast<std::uint8_t>(0x23 | ((4 - size) << 2)));
    std::copy_n(value_.bytes.begin(), size, out.data.begin() + 4);
  } else {
    out = request(0x21);  // segmented, size indicated in bytes 4-7
    sdo::put_u32_at4(out, static_cast<std::uint32_t>(size));
  }
  return true;
}

bool SdoClient::upload(std::uint16_t index, std::uint8_t sub, std::uint64_t now_us,
                       can::CanFrame& out) noexcept {
  if (busy()) {
    return false;
  }
  index_ = index;
  sub_ = sub;
  value_.size = 0;
  abort_code_ = 0;
  by_server_ = false;
  offset_ = 0;
  expected_ = 0;
  toggle_ = 0;
  initiated_ = false;
  segmented_ = false;
  last_us_ = now_us;
  state_ = State::uploading;
  out = request(0x40);
  return true;
}

void SdoClient::next_download_segment(can::CanFrame& out) noexcept {
  const std::size_t chunk = std::min<std::size_t>(7, value_.size - offset_);
  const bool last = offset_ + chunk >= value_.size;
  out = segment_request(
      static_cast<std::uint8_t>((toggle_ << 4) | ((7 - chunk) << 1) | (last ? 1 : 0)));
  std::copy_n(value_.bytes.begin() + static_cast<std::ptrdiff_t>(offset_), chunk,
              out.data.begin() + 1);
  last_chunk_ = chunk;
}

bool SdoClient::on_frame(const can::CanFrame& in, std::uint64_t now_us,
                         can::CanFrame& out) noexcept {
  if (in.id != kSdoResponseBase + node_ || !busy()) {
    return false;
  }
  if (in.dlc != 8) {
    ++malformed_;
    return false;
  }
  const std::uint8_t scs = sdo::specifier(in);
  const bool multiplexed = scs == sdo::kUploadInitiateResponse ||
                           scs == sdo::kDownloadInitiateResponse || scs == sdo::kAbortSpecifier;
  if (multiplexed && (sdo::index_of(in) != index_ || in.data[3] != sub_)) {
    // The late answer to an earlier request that was sent again (start-up retries): the
    // server answered both. Not this request's: it neither ends it nor restarts its timeout.
    ++stale_;
    return false;
  }
  last_us_ = now_us;
  if (scs == sdo::kAbortSpecifier) {
    state_ = State::aborted;
    abort_code_ = sdo::u32_at4(in);
    by_server_ = true;
    return false;
  }
  if (state_ == State::downloading) {
    if (!initiated_) {
      if (scs != sdo::kDownloadInitiateResponse) {
        return fail(sdo_abort::kBadCommand, out);
      }
      initiated_ = true;
      if (!segmented_) {
        state_ = State::done;
        return false;
      }
      next_download_segment(out);
      return true;
    }
    if (scs != sdo::kDownloadSegmentResponse) {
      return fail(sdo_abort::kBadCommand, out);
    }
    if (((in.data[0] >> 4) & 1) != toggle_) {
      return fail(sdo_abort::kToggleBit, out);
    }
    offset_ += last_chunk_;
    if (offset_ >= value_.size) {
      state_ = State::done;
      return false;
    }
    toggle_ ^= 1;
    next_download_segment(out);
    return true;
  }
  // Uploading.
  if (!initiated_) {
    if (scs != sdo::kUploadInitiateResponse) {
      return fail(sdo_abort::kBadCommand, out);
    }
    initiated_ = true;
    const bool expedited = (in.data[0] & 0x02) != 0;
    const bool sized = (in.data[0] & 0x01) != 0;
    if (expedited) {
      value_.size = sized ? 4 - ((in.data[0] >> 2) & 0x03) : 4;
      std::copy_n(in.data.begin() + 4, value_.size, value_.bytes.begin());
      state_ = State::done;
      return false;
    }
    expected_ = sized ? sdo::u32_at4(in) : 0;
    if (expected_ > kSdoMaxValue) {
      return fail(sdo_abort::kOutOfMemory, out);
    }
    segmented_ = true;
    out = segment_request(static_cast<std::uint8_t>(0x60 | (toggle_ << 4)));
    return true;
  }
  if (scs != sdo::kUploadSegmentResponse) {
    return fail(sdo_abort::kBadCommand, out);
  }
  if (((in.data[0] >> 4) & 1) != toggle_) {
    return fail(sdo_abort::kToggleBit, out);
  }
  const std::size_t chunk = 7 - ((in.data[0] >> 1) & 0x07);
  if (value_.size + chunk > kSdoMaxValue) {
    return fail(sdo_abort::kOutOfMemory, out);
  }
  std::copy_n(in.data.begin() + 1, chunk,
              value_.bytes.begin() + static_cast<std::ptrdiff_t>(value_.size));
  value_.size += chunk;
  if ((in.data[0] & 0x01) != 0) {
    if (expected_ != 0 && value_.size != expected_) {
      return fail(sdo_abort::kLengthMismatch, out);
    }
    state_ = State::done;
    return false;
  }
  toggle_ ^= 1;
  out = segment_request(static_cast<std::uint8_t>(0x60 | (toggle_ << 4)));
  return true;
}

bool SdoClient::on_time(std::uint64_t now_us, can::CanFrame& out) noexcept {
  if (!busy() || now_us - last_us_ <= timeout_us_) {
    return false;
  }
  return fail(sdo_abort::kTimeout, out);
}

}  // namespace mcnc::canopen
