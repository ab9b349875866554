#include "foveal/drivers/vive/vive_reports.hpp"

#include <zlib.h>

#include <cmath>

namespace foveal::vive {
namespace {

Error at(const char* what, std::size_t offset, const std::string& why) {
  return bad_input(std::string("vive ") + what + ": byte " + std::to_string(offset) + ": " + why);
}

std::int16_t i16(std::span<const std::uint8_t> d, std::size_t at) {
  return static_cast<std::int16_t>(d[at] | d[at + 1] << 8);
}

std::uint32_t u32(std::span<const std::uint8_t> d, std::size_t at) {
  return static_cast<std::uint32_t>(d[at]) | static_cast<std::uint32_t>(d[at + 1]) << 8 |
         static_cast<std::uint32_t>(d[at + 2]) << 16 | static_cast<std::uint32_t>(d[at + 3]) << 24;
}

/// The slot holding the oldest of three consecutive sequence numbers, if they are.
std::optional<std::size_t> oldest_slot(const ImuReport& r) {
  for (std::size_t i = 0; i < 3; ++i) {
    const std::uint8_t s0 = r.samples[i].seq;
    if (r.samples[(i + 1) % 3].seq == static_cast<std::uint8_t>(s0 + 1) &&
        r.samples[(i + 2) % 3].seq == static_cast<std::uint8_t>(s0 + 2))
      return i;
  }
  return std::nullopt;
}

}  // namespace

Result<ImuReport> parse_imu_report(std::span<const std::uint8_t> data) {
  if (data.empty()) return at("IMU report", 0, "empty");
  if (data[0] != kImuReportId) return at("IMU report", 0, "report id " + std::to_string(data[0]) + " is not 0x20");
  if (data.size() != kImuReportBytes)
    return at("IMU report", data.size() < kImuReportBytes ? data.size() : kImuReportBytes,
              (data.size() < kImuReportBytes ? "truncated: " : "too long: ") + std::to_string(data.size()) + " of " +
                  std::to_string(kImuReportBytes) + " bytes");
  ImuReport r;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t o = 1 + i * kImuSampleBytes;
    ImuRawSample& s = r.samples[i];
    for (std::size_t k = 0; k < 3; ++k) {
      s.accel[k] = i16(data, o + 2 * k);
      s.gyro[k] = i16(data, o + 6 + 2 * k);
    }
    s.time = u32(data, o + 12);
    s.seq = data[o + 16];
  }
  if (!oldest_slot(r)) return at("IMU report", 17, "the three sequence numbers are not consecutive");
  return r;
}

std::vector<ImuRawSample> new_imu_samples(const ImuReport& r, std::optional<std::uint8_t> last_seq) {
  std::vector<ImuRawSample> out;
  const std::size_t first = oldest_slot(r).value_or(0);
  for (std::size_t k = 0; k < 3; ++k) {
    const ImuRawSample& s = r.samples[(first + k) % 3];
    // Seen already: the newest handled one or up to two before it.
    if (last_seq && static_cast<std::uint8_t>(*last_seq - s.seq) < 3) continue;
    out.push_back(s);
  }
  return out;
}

Result<ImuRange> parse_range_report(std::span<const std::uint8_t> data) {
  if (data.size() < 3) return at("IMU range report", data.size(), "truncated: " + std::to_string(data.size()) + " bytes");
  if (data[0] != kRangeReportId) return at("IMU range report", 0, "report id " + std::to_string(data[0]) + " is not 0x01");
  if (data[1] > 4 || data[2] > 4)
    return at("IMU range report", data[1] > 4 ? 1 : 2, "range code " + std::to_string(data[data[1] > 4 ? 1 : 2]) + " is not 0-4");
  ImuRange r;
  r.gyro_rad_s = 3.14159265358979323846 / 180.0 * (250 << data[1]);
  r.accel_m_s2 = 9.80665 * (2 << data[2]);
  return r;
}

Status ConfigAssembler::add(std::span<const std::uint8_t> report) {
  if (complete_) return at("config report", 0, "the configuration already ended (a report with length 0 came)");
  if (report.size() < 2) return at("config report", report.size(), "truncated: " + std::to_string(report.size()) + " bytes");
  if (report[0] != kConfigReadReportId)
    return at("config report", 0, "report id " + std::to_string(report[0]) + " is not 0x11");
  const std::size_t len = report[1];
  if (len > kConfigPayloadMax) return at("config report", 1, "payload length " + std::to_string(len) + " is over 62");
  if (2 + len > report.size())
    return at("config report", report.size(),
              "truncated: payload length " + std::to_string(len) + " in a " + std::to_string(report.size()) + "-byte report");
  if (data_.size() + len > kConfigCompressedMax)
    return at("config report", 1, "the configuration is over " + std::to_string(kConfigCompressedMax) + " bytes");
  if (len == 0) complete_ = true;
  data_.insert(data_.end(), report.begin() + 2, report.begin() + 2 + static_cast<std::ptrdiff_t>(len));
  return {};
}

Result<std::string> ConfigAssembler::json() const {
  if (!complete_) return bad_input("vive config: incomplete (no report with length 0 ended it)");
  return inflate_zlib(data_, kConfigJsonMax);
}

Result<std::string> inflate_zlib(std::span<const std::uint8_t> data, std::size_t max_out) {
  z_stream z{};
  if (inflateInit(&z) != Z_OK) return Error{ErrorKind::internal, "zlib: inflateInit failed"};
  std::string out;
  z.next_in = const_cast<Bytef*>(data.data());  // zlib's API is not const-correct
  z.avail_in = static_cast<uInt>(data.size());
  char buf[16384];
  int rc = Z_OK;
  while (rc == Z_OK) {
    z.next_out = reinterpret_cast<Bytef*>(buf);
    z.avail_out = sizeof buf;
    rc = inflate(&z, Z_NO_FLUSH);
    out.append(buf, sizeof buf - z.avail_out);
    if (out.size() > max_out) {
      inflateEnd(&z);
      return bad_input("vive config: inflates to more than " + std::to_string(max_out) + " bytes");
    }
    if (rc == Z_BUF_ERROR && z.avail_in == 0) break;  // input ended before the stream did
  }
  const std::string msg = z.msg ? z.msg : "";
  inflateEnd(&z);
  if (rc != Z_STREAM_END)
    return bad_input("vive config: not a complete zlib stream (" + (msg.empty() ? "truncated" : msg) + ", " +
                     std::to_string(data.size()) + " bytes)");
  return out;
}

std::vector<std::uint8_t> deflate_zlib(const std::string& text) {
  uLongf n = compressBound(static_cast<uLong>(text.size()));
  std::vector<std::uint8_t> out(n);
  if (compress2(out.data(), &n, reinterpret_cast<const Bytef*>(text.data()), static_cast<uLong>(text.size()), 9) != Z_OK)
    return {};
  out.resize(n);
  return out;
}

}  // namespace foveal::vive
