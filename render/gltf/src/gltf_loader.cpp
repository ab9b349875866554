// Reading a glTF file within limits: the bytes (a regular file, size-bounded), the JSON
// (depth and size checked on the raw bytes, then the structure checks), then tinygltf
// with foveal's file reader and image decoder, then the checked build.
#include "foveal/render/gltf_loader.hpp"

#include <stb_image.h>

#include <cstring>
#include <filesystem>
#include <new>
#include <set>

#include "foveal/core/json_file.hpp"
#include "foveal/core/read_file.hpp"
#include "gltf_decode.hpp"
#include "gltf_extensions.hpp"
#include "gltf_internal.hpp"
#include "gltf_json_fixups.hpp"
#include "gltf_lights.hpp"

namespace foveal::render {

namespace {

// What tinygltf's callbacks need; the first error they meet is kept here, so the
// message is ours rather than tinygltf's.
struct LoadContext {
  const GltfLimits* limits = nullptr;
  std::string file, base_dir;
  detail::DecodeBudget* budget = nullptr;
  std::string error;
  void fail(std::string e) {
    if (error.empty()) error = std::move(e);
  }
};

// tinygltf looks for a referenced file under the model's directory, then under the
// current directory: only the first is meant.
bool file_exists(const std::string& path, void* user) {
  auto* ctx = static_cast<LoadContext*>(user);
  std::error_code ec;
  const std::string& dir = ctx->base_dir;
  const std::string prefix = !dir.empty() && dir.back() == '/' ? dir : dir + "/";
  return ctx->limits->external_files && path.rfind(prefix, 0) == 0 && std::filesystem::exists(path, ec);
}

std::string expand_path(const std::string& path, void*) { return path; }  // no ~ or $VAR expansion

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto* ctx = static_cast<LoadContext*>(user);
  if (!ctx->limits->external_files) {
    *err = "external files are not read";
    return false;
  }
  auto bytes = read_regular_file(path, ctx->limits->max_file_bytes, "file referenced by " + ctx->file);
  if (!bytes) {
    ctx->fail(bytes.error().message);
    *err = bytes.error().message;
    return false;
  }
  out->assign(bytes->begin(), bytes->end());
  return true;
}

bool no_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  *err = "writing is not supported";
  return false;
}

std::string image_name(const tinygltf::Image& image, int index) {
  std::string s = "images[" + std::to_string(index) + "]";
  if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0) s += " (" + image.uri + ")";
  else if (!image.name.empty()) s += " (" + image.name + ")";
  return s;
}

// Decodes one image to RGBA8 after checking the dimensions its header claims against
// the texture size limit and the memory bound, so nothing is allocated for a lie.
Status decode_image(tinygltf::Image& image, int index, const unsigned char* bytes, std::size_t size, LoadContext& ctx) {
  const std::string what = ctx.file + ": " + image_name(image, index);
  if (size == 0 || size > static_cast<std::size_t>(INT32_MAX)) return bad_input(what + ": empty or too large");
  const int n = static_cast<int>(size);
  const int max_side = ctx.limits->max_texture_size;
  auto too_large = [&](std::uint64_t w, std::uint64_t h) {
    return bad_input(what + ": " + std::to_string(w) + "×" + std::to_string(h) + " is larger than the texture size limit " +
                     std::to_string(max_side) + " (GL_MAX_TEXTURE_SIZE)");
  };
  // A PNG's size is read here too: stb_image refuses headers past 2^30 bytes as
  // "unknown image type", which would not say what is wrong.
  if (size >= 24 && std::memcmp(bytes, "\x89PNG\r\n\x1a\n", 8) == 0 && std::memcmp(bytes + 12, "IHDR", 4) == 0) {
    auto be32 = [](const unsigned char* p) {
      return std::uint64_t{p[0]} << 24 | std::uint64_t{p[1]} << 16 | std::uint64_t{p[2]} << 8 | std::uint64_t{p[3]};
    };
    const std::uint64_t pw = be32(bytes + 16), ph = be32(bytes + 20);
    if (pw > static_cast<std::uint64_t>(max_side) || ph > static_cast<std::uint64_t>(max_side)) return too_large(pw, ph);
    // Every chunk must fit in the bytes there are: stb_image sizes its buffer from a
    // chunk's length before reading it, so one claiming 2 GiB in a short file would
    // allocate 2 GiB first (found by fuzz_gltf).
    for (std::size_t at = 8; at + 12 <= size;) {
      const std::uint64_t length = be32(bytes + at);
      if (length > size - at - 12)
        return bad_input(what + ": PNG chunk at byte " + std::to_string(at) + " claims " + std::to_string(length) + " bytes, past the end of the image (" +
                         std::to_string(size) + " bytes)");
      if (std::memcmp(bytes + at + 4, "IEND", 4) == 0) break;
      at += 12 + static_cast<std::size_t>(length);
    }
  }
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(bytes, n, &w, &h, &comp))
    return bad_input(what + ": not an image stb_image can decode (" + std::string(stbi_failure_reason()) + ")");
  if (w <= 0 || h <= 0) return bad_input(what + ": " + std::to_string(w) + "×" + std::to_string(h) + " is empty");
  if (w > max_side || h > max_side) return too_large(static_cast<std::uint64_t>(w), static_cast<std::uint64_t>(h));
  const std::size_t rgba = static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4;
  if (rgba > ctx.limits->max_image_bytes)
    return bad_input(what + ": " + std::to_string(w) + "×" + std::to_string(h) + " needs " + std::to_string(rgba >> 20) +
                     " MiB decoded, more than the " + describe_bytes(ctx.limits->max_image_bytes) + " per image accepted");
  if (Status s = ctx.budget->take(rgba, what); !s) return s;
  int dw = 0, dh = 0;
  stbi_uc* data = stbi_load_from_memory(bytes, n, &dw, &dh, &comp, 4);
  if (!data) return bad_input(what + ": cannot decode (" + std::string(stbi_failure_reason()) + ")");
  if (dw != w || dh != h) {
    stbi_image_free(data);
    return bad_input(what + ": decodes to a size other than its header's");
  }
  image.width = w;
  image.height = h;
  image.component = 4;
  image.bits = 8;
  image.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image.image.assign(data, data + rgba);
  stbi_image_free(data);
  return {};
}

bool is_ktx2(const unsigned char* bytes, std::size_t size) {
  static const unsigned char kKtx2[] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB};
  return size >= 8 && std::memcmp(bytes, kKtx2, 8) == 0;
}

// tinygltf's image callback. Images in a buffer view are left for later: tinygltf 2.7
// passes &buffer.data[view.byteOffset] without checking the view against the buffer.
// KTX2 images (KHR_texture_basisu) stay undecoded: a texture with a PNG/JPEG fallback
// source uses that, one without is refused when the scene is built.
bool load_image(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                const unsigned char* bytes, int size, void* user) {
  auto* ctx = static_cast<LoadContext*>(user);
  if (image->bufferView >= 0 || is_ktx2(bytes, static_cast<std::size_t>(size < 0 ? 0 : size))) return true;
  if (Status s = decode_image(*image, index, bytes, static_cast<std::size_t>(size < 0 ? 0 : size), *ctx); !s) {
    ctx->fail(s.error().message);
    *err += s.error().message;
    return false;
  }
  return true;
}

Status decode_buffer_view_images(tinygltf::Model& model, LoadContext& ctx) {
  for (std::size_t i = 0; i < model.images.size(); ++i) {
    tinygltf::Image& image = model.images[i];
    if (image.bufferView < 0) continue;
    const tinygltf::BufferView& v = model.bufferViews.at(static_cast<std::size_t>(image.bufferView));
    const tinygltf::Buffer& b = model.buffers.at(static_cast<std::size_t>(v.buffer));
    std::size_t end = 0;
    if (__builtin_add_overflow(v.byteOffset, v.byteLength, &end) || end > b.data.size())
      return bad_input(ctx.file + ": bufferViews[" + std::to_string(image.bufferView) + "] (of images[" + std::to_string(i) +
                       "]) is past the end of its buffer");
    if (is_ktx2(b.data.data() + v.byteOffset, v.byteLength)) continue;
    if (Status s = decode_image(image, static_cast<int>(i), b.data.data() + v.byteOffset, v.byteLength, ctx); !s) return s;
  }
  return {};
}

// The JSON of a .glb: its first chunk, after the 12-byte header and 8-byte chunk header.
Result<std::string_view> glb_json(std::string_view bytes, const std::string& name) {
  if (bytes.size() < 20) return bad_input(name + ": too short for a .glb (" + std::to_string(bytes.size()) + " bytes)");
  std::uint32_t json_len = 0, json_type = 0;
  std::memcpy(&json_len, bytes.data() + 12, 4);
  std::memcpy(&json_type, bytes.data() + 16, 4);
  if (json_type != 0x4E4F534Au) return bad_input(name + ": the first .glb chunk is not JSON");
  if (json_len > bytes.size() - 20) return bad_input(name + ": the .glb JSON chunk runs past the end of the file");
  return bytes.substr(20, json_len);
}

}  // namespace

Result<GltfScene> load_gltf_bytes(std::string_view bytes, const std::string& name, const std::string& base_dir,
                                  const GltfLimits& limits, GltfSink& sink) {
  if (bytes.size() > limits.max_file_bytes)
    return bad_input(name + ": " + std::to_string(bytes.size()) + " bytes, more than the " + describe_bytes(limits.max_file_bytes) +
                     " accepted");
  const bool binary = bytes.size() >= 4 && bytes.substr(0, 4) == "glTF";
  std::string_view json_text = bytes;
  if (binary) {
    auto j = glb_json(bytes, name);
    if (!j) return j.error();
    json_text = *j;
  }
  // Depth and size first (tinygltf parses `extras` recursively), then the structure.
  auto root = parse_json(json_text, name, {limits.max_json_bytes, kMaxJsonDepth});
  if (!root) return root.error();
  if (Status s = detail::check_gltf_json(*root, name); !s) return s.error();
  std::vector<std::string> light_warnings;
  if (Status s = detail::check_gltf_lights(*root, name, light_warnings); !s) return s.error();
  // Draco and meshopt files need placeholders tinygltf accepts (gltf_json_fixups.hpp).
  std::string mended;
  if (detail::mend_for_tinygltf(*root, binary)) {
    mended = binary ? detail::glb_with_json(bytes, json_text, root->dump()) : root->dump();
    bytes = mended;
  }
  *root = nlohmann::json();  // free it before tinygltf builds its own

  detail::DecodeBudget budget(limits.max_decoded_bytes);
  LoadContext ctx{&limits, name, base_dir, &budget, {}};
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&file_exists, &expand_path, &read_whole_file, &no_write, &ctx});
  loader.SetImageLoader(&load_image, &ctx);
  std::string err, warn;
  bool ok = false;
  try {
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const auto size = static_cast<unsigned int>(bytes.size());
    ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, size, base_dir)
                : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), size, base_dir);
  } catch (const std::bad_alloc&) {
    return bad_input(name + ": cannot load glTF: out of memory");
  } catch (const std::exception& e) {
    return bad_input(name + ": cannot load glTF: " + e.what());
  }
  if (!ctx.error.empty()) return bad_input(ctx.error);  // also when tinygltf took it for a warning (images)
  if (!ok) {
    while (!err.empty() && err.back() == '\n') err.pop_back();
    return bad_input(name + ": cannot load glTF: " + (err.empty() ? "unknown error" : err));
  }
  std::vector<std::string> warnings;
  for (std::size_t a = 0, b; a < warn.size(); a = b + 1) {  // tinygltf's, one per line
    b = warn.find('\n', a);
    if (b == std::string::npos) b = warn.size();
    if (b > a) warnings.push_back(name + ": " + warn.substr(a, b - a));
  }
  if (Status s = detail::check_gltf_extensions(model, name, warnings); !s) return s.error();
  warnings.insert(warnings.end(), light_warnings.begin(), light_warnings.end());
  if (Status s = decode_buffer_view_images(model, ctx); !s) return s.error();
  if (Status s = detail::decode_gltf_model(model, name, limits, budget); !s) return s.error();
  auto scene = detail::build_gltf_scene(model, name, limits, budget, sink);
  if (scene) scene->warnings.insert(scene->warnings.begin(), warnings.begin(), warnings.end());
  return scene;
}

Result<GltfScene> load_gltf(const std::string& path, const GltfLimits& limits, GltfSink& sink) {
  auto bytes = read_regular_file(path, limits.max_file_bytes, "glTF file");
  if (!bytes) return bytes.error();
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return load_gltf_bytes(*bytes, path, dir.empty() ? "." : dir, limits, sink);
}

}  // namespace foveal::render
