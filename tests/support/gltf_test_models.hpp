#pragma once
// Small glTF models built in the tests, for editing into crafted ones: one quad (4
// vertices, 6 indices) in a data: URI buffer.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace foveal::test {

inline std::string base64(const std::string& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(in[i]) << 16) | (static_cast<unsigned char>(in[i + 1]) << 8) |
                       static_cast<unsigned char>(in[i + 2]);
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
  }
  if (i + 1 == in.size()) {
    const unsigned v = static_cast<unsigned char>(in[i]) << 16;
    out += {k[v >> 18], k[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == in.size()) {
    const unsigned v = (static_cast<unsigned char>(in[i]) << 16) | (static_cast<unsigned char>(in[i + 1]) << 8);
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
  }
  return out;
}

inline std::string data_uri(const std::string& bytes, const char* mime = "application/octet-stream") {
  return std::string("data:") + mime + ";base64," + base64(bytes);
}

/// The quad's buffer: 4 float VEC3 positions (48 bytes), then 6 ushort indices (12 bytes).
inline std::string quad_buffer(const std::vector<std::uint16_t>& indices = {0, 1, 2, 0, 2, 3}) {
  const float pos[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  std::string b(reinterpret_cast<const char*>(pos), sizeof pos);
  std::string idx(12, '\0');
  std::memcpy(idx.data(), indices.data(), std::min<std::size_t>(12, indices.size() * 2));
  return b + idx;
}

inline nlohmann::json quad_model(const std::string& buffer = quad_buffer()) {
  return nlohmann::json{
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}}, {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 12}}}},
      {"buffers", {{{"byteLength", buffer.size()}, {"uri", data_uri(buffer)}}}},
  };
}

/// `depth` nested arrays: "[[[...]]]".
inline std::string nested_arrays(std::size_t depth) { return std::string(depth, '[') + std::string(depth, ']'); }

/// The first bytes of a PNG whose header (IHDR) claims width × height, RGBA8. stb_image
/// reads dimensions from the header alone; the CRC is not checked.
inline std::string png_header(std::uint32_t width, std::uint32_t height) {
  auto be32 = [](std::uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
  };
  std::string s = "\x89PNG\r\n\x1a\n";
  s += be32(13) + "IHDR" + be32(width) + be32(height) + std::string{8, 6, 0, 0, 0} + be32(0);
  s += be32(0) + "IEND" + be32(0xAE426082u);
  return s;
}

}  // namespace foveal::test
