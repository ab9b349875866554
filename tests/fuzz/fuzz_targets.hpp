#pragma once
// The fuzz targets' bodies: called by the libFuzzer entry points (fuzz_*.cpp) and by
// the regression test, which replays every saved crash input in the normal build.
#include <sys/socket.h>
#include <sys/un.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <cstdlib>
#include <unistd.h>

#include "foveal/bench/bench_shard_file.hpp"
#include "foveal/core/display_model.hpp"
#include "foveal/core/gaze_log.hpp"
#include "foveal/core/gaze_log_stats.hpp"
#ifdef FOVEAL_HAVE_HID
#include "foveal/drivers/hid/report_decoder.hpp"
#endif
#ifdef FOVEAL_HAVE_USB
#include "foveal/drivers/psvr2/psvr2_gaze_packet.hpp"
#include "foveal/drivers/psvr2/psvr2_pose_records.hpp"
#endif
#ifdef FOVEAL_HAVE_VIVE
#include "foveal/drivers/vive/vive_config.hpp"
#include "foveal/drivers/vive/vive_display_model.hpp"
#endif
#include "foveal/import/importers.hpp"
#ifdef FOVEAL_HAVE_GLTF
#include "foveal/render/gltf_loader.hpp"
#include "foveal/render/view_file.hpp"
#endif
#include "foveal/runtime/control_server.hpp"
#include "foveal/runtime/profile.hpp"
#include "fuzz_file.hpp"

namespace foveal::fuzz {

// Native gaze-log reader: any bytes must give samples or a clean error, never a crash.
inline int gaze_log(const std::uint8_t* data, std::size_t size) {
  MemFile f(data, size);
  auto r = foveal::GazeLogReader::open(f.path());
  if (!r) return 0;
  foveal::GazeSample s;
  for (int i = 0; i < 100000; ++i) {
    auto got = r->next(s);
    if (!got || !*got) break;
    for (const auto& e : s.eyes)
      if (e.has(foveal::kValidDirection) && !std::isfinite(e.direction.x)) std::abort();  // never NaN
    if (s.head.valid && (!foveal::is_finite(s.head.pose) || !foveal::is_unit(s.head.pose.orientation))) std::abort();
  }
  (void)foveal::compute_gaze_log_stats(f.path());
  return 0;
}

// SRanipal and Pupil importers: clean error or a valid log, never a crash; a failed
// import leaves no output file.
inline int import(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  MemFile f(data + 1, size - 1);
  const std::string out = scratch_output();
  auto r = (data[0] & 1) ? foveal::import_pupil(f.path(), out) : foveal::import_sranipal(f.path(), out);
  if (!r && ::access(out.c_str(), F_OK) == 0) std::abort();  // partial output left behind
  ::unlink(out.c_str());
  return 0;
}

#ifdef FOVEAL_HAVE_HID
// HID report-descriptor parser and report decoder on arbitrary bytes.
inline int hid(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  // First byte: how much of the rest is the descriptor; the remainder is a report.
  const std::size_t desc_len = std::min<std::size_t>(size - 1, static_cast<std::size_t>(data[0]) * 4);
  std::span<const std::uint8_t> desc(data + 1, desc_len), report(data + 1 + desc_len, size - 1 - desc_len);
  auto d = foveal::hid::parse_report_descriptor(desc);
  if (!d) return 0;
  for (auto type : {foveal::hid::ReportType::input, foveal::hid::ReportType::feature})
    (void)foveal::hid::decode_report(*d, type, report);
  return 0;
}
#endif

// Profile reader: a hand-broken profile is an error, never a crash or a half-load.
inline int profile(const std::uint8_t* data, std::size_t size) {
  MemFile f(data, size);
  auto p = foveal::ProfileStore::load_file(f.path(), "fuzz");
  if (p && !p->validate("fuzz")) std::abort();  // loaded means valid
  return 0;
}

#ifdef FOVEAL_HAVE_USB
// PS VR2 gaze records: a clean error or a sample whose valid directions are finite.
inline int psvr2(const std::uint8_t* data, std::size_t size) {
  auto r = foveal::usb::parse_psvr2_gaze(std::span<const std::uint8_t>(data, size));
  if (!r) return 0;
  const foveal::GazeSample s = foveal::usb::psvr2_to_sample(*r);
  for (const auto& e : s.eyes)
    if (e.has(foveal::kValidDirection) && !(std::isfinite(e.direction.x) && std::isfinite(e.direction.y) && std::isfinite(e.direction.z)))
      std::abort();
  return 0;
}
#endif

// Control-socket messages through a real server on a Unix socket: the bytes go in as a
// client would send them (split into lines, over-long lines, bad JSON), requests are
// validated like foveald's `set` (a profile built from the request), and every request
// line gets a reply.
// The headsets' motion and lens-data reports (docs/headset.md). The first byte picks
// the parser: 0 PS VR2 status/IMU, 1 PS VR2 SLAM, 2 Vive IMU report, 3 Vive config
// feature reports (64 bytes each) assembled and inflated, 4 Vive config JSON converted
// to a display model. Any bytes: a value or a clean error, never a crash or a NaN pose.
#if defined(FOVEAL_HAVE_USB) && defined(FOVEAL_HAVE_VIVE)
inline int hmd(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::span<const std::uint8_t> rest(data + 1, size - 1);
  switch (data[0] % 5) {
    case 0:
      if (auto r = foveal::usb::parse_psvr2_status(rest); r)
        for (const auto& m : r->imu) {
          const foveal::ImuSample s = foveal::usb::psvr2_imu_to_sample(m);
          if (!std::isfinite(s.gyro_rad_s.x) || !std::isfinite(s.accel_m_s2.z)) std::abort();
        }
      break;
    case 1:
      if (auto r = foveal::usb::parse_psvr2_slam(rest); r)
        if (!foveal::is_finite(foveal::usb::psvr2_slam_to_pose(*r))) std::abort();
      break;
    case 2:
      if (auto r = foveal::vive::parse_imu_report(rest); r)
        if (foveal::vive::new_imu_samples(*r, std::nullopt).size() != 3) std::abort();
      break;
    case 3: {
      foveal::vive::ConfigAssembler a;
      for (std::size_t at = 0; at < rest.size() && !a.complete(); at += foveal::vive::kConfigReportBytes)
        if (!a.add(rest.subspan(at, std::min(foveal::vive::kConfigReportBytes, rest.size() - at)))) break;
      (void)a.json();
      break;
    }
    default:
      if (auto c = foveal::vive::parse_config(std::string(rest.begin(), rest.end())); c)
        if (auto m = foveal::vive::vive_display_model(*c); m)
          if (!m->validate("fuzz")) std::abort();
      break;
  }
  return 0;
}
#endif

// The Vive configuration JSON (`foveal devices --from-config`, the headset's own): a
// clean error or a config whose display model validates; never a crash, and no message
// longer than a few hundred bytes (values are quoted shortly).
#ifdef FOVEAL_HAVE_VIVE
inline int vive(const std::uint8_t* data, std::size_t size) {
  auto c = foveal::vive::parse_config(std::string(reinterpret_cast<const char*>(data), size), "fuzz");
  if (!c) {
    if (c.error().message.size() > 1000) std::abort();
    return 0;
  }
  if (auto m = foveal::vive::vive_display_model(*c); m && !m->validate("fuzz")) std::abort();
  return 0;
}
#endif

inline int control(const std::uint8_t* data, std::size_t size) {
  // The socket needs a private directory (docs/daemon.md), removed again at exit.
  static struct Served {
    std::string dir = "/dev/shm/foveal-fuzz-" + std::to_string(::getpid());
    std::unique_ptr<foveal::ControlServer> server;
    Served() {
      auto s = foveal::ControlServer::listen(dir + "/control.sock");
      if (!s) std::abort();
      server = std::make_unique<foveal::ControlServer>(std::move(*s));
    }
    ~Served() {
      server.reset();
      ::rmdir(dir.c_str());
    }
  } served;
  foveal::ControlServer* server = served.server.get();
  const auto handler = [](const nlohmann::json& req) -> nlohmann::json {
    nlohmann::json j = foveal::Profile{}.to_json();
    for (auto it = req.begin(); it != req.end(); ++it)
      if (it.key() != "cmd") j[it.key()] = it.value();
    auto p = foveal::Profile::from_json(j, "fuzz", "set");
    if (p && !p->validate("fuzz")) std::abort();  // accepted means valid
    return {{"ok", p.ok()}};
  };
  std::string msg(reinterpret_cast<const char*>(data), size);
  msg += '\n';
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", server->path().c_str());
  if (fd < 0 || ::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) std::abort();
  std::size_t sent = 0;
  for (int i = 0; i < 50; ++i) {  // interleave sending and serving: the server reads as we write
    if (sent < msg.size()) {
      const ssize_t n = ::send(fd, msg.data() + sent, msg.size() - sent, MSG_NOSIGNAL | MSG_DONTWAIT);
      if (n > 0) sent += static_cast<std::size_t>(n);
    }
    server->poll(sent < msg.size() ? 1 : 0, handler);
    char buf[4096];
    while (::recv(fd, buf, sizeof buf, MSG_DONTWAIT) > 0) {
    }
    if (sent == msg.size() && i > 2) break;
  }
  ::close(fd);
  server->poll(0, handler);  // sees the hang-up
  return 0;
}

// Display models and view files: a clean error or a model that validates (a view pose
// that is finite), never a crash. The first byte picks the parser.
inline int display(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  MemFile f(data + 1, size - 1);
  if (data[0] & 1) {
#ifdef FOVEAL_HAVE_GLTF
    auto v = foveal::render::read_view_file(f.path());
    if (v)
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
          if (!std::isfinite(v->head_to_world[c][r])) std::abort();  // accepted means usable
#endif
    return 0;
  }
  auto m = foveal::DisplayModel::load(f.path());
  if (m && !m->validate("fuzz")) std::abort();  // loaded means valid
  return 0;
}

#ifdef FOVEAL_HAVE_GLTF
// glTF bytes through foveal's loader (tinygltf + the checks), CPU only, no external
// files: a clean error or triangles whose indices are in range and whose positions are
// finite, textures within the limits.
class CheckingSink : public foveal::render::GltfSink {
 public:
  explicit CheckingSink(const foveal::render::GltfLimits& l) : limits_(l) {}
  int add_texture(const foveal::render::GltfTexture& t) override {
    if (!t.rgba || t.width <= 0 || t.height <= 0 || t.width > limits_.max_texture_size || t.height > limits_.max_texture_size)
      std::abort();
    (void)t.rgba[static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height) * 4 - 1];  // readable to the end
    return textures++;
  }
  int add_primitive(const std::vector<foveal::render::GltfVertex>& v, const std::vector<std::uint32_t>& idx, int) override {
    if (idx.size() % 3 != 0) std::abort();
    for (std::uint32_t i : idx)
      if (i >= v.size()) std::abort();
    for (const auto& x : v)
      for (float p : x.position)
        if (!std::isfinite(p)) std::abort();
    return primitives++;
  }
  int textures = 0, primitives = 0;

 private:
  foveal::render::GltfLimits limits_;
};

inline int gltf(const std::uint8_t* data, std::size_t size) {
  foveal::render::GltfLimits limits;
  limits.external_files = false;
  limits.max_texture_size = 4096;
  limits.max_image_bytes = std::size_t{16} << 20;
  limits.max_decoded_bytes = std::size_t{64} << 20;
  CheckingSink sink(limits);
  auto s = foveal::render::load_gltf_bytes(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.gltf",
                                           "/nonexistent", limits, sink);
  if (!s) return 0;
  for (const auto& d : s->draws)
    if (d.primitive < 0 || d.primitive >= sink.primitives) std::abort();
  for (const auto& m : s->materials)
    for (int t : {m.base_color_tex, m.metal_rough_tex, m.normal_tex, m.occlusion_tex, m.emissive_tex})
      if (t < -1 || t >= sink.textures) std::abort();
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(s->bounds.min[i]) || !std::isfinite(s->bounds.max[i])) std::abort();
  return 0;
}
#endif

// foveal bench merge's shard.json reader (foveal/bench/bench_shard_file.hpp): a clean
// error or a shard naming only its kind's tables, whose merge (alone) writes nothing else;
// never a crash or an allocation sized by a field (N of 2e9 shards, say).
inline int shard(const std::uint8_t* data, std::size_t size) {
  MemFile f(data, size);
  auto s = foveal::bench::read_shard_file(f.path());
  if (!s) {
    if (s.error().message.size() > 1000) std::abort();  // messages quote input shortly
    return 0;
  }
  const foveal::bench::Kind* kind = foveal::bench::find_kind(s->kind);
  if (!kind) std::abort();
  for (const std::string& t : s->rows.tables())
    if (std::find(kind->tables.begin(), kind->tables.end(), t) == kind->tables.end()) std::abort();
  if (auto m = foveal::bench::SweepRows::merge({s->rows}, {s->path}); m)
    for (const std::string& t : m->tables()) (void)m->csv(t);
  return 0;
}

}  // namespace foveal::fuzz
