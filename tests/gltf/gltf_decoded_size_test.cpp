// Compressed and sparse glTF data whose decoded size is a lie (issue 27, item 6): refused,
// or left undecoded when nothing reads it, before anything is allocated for it. The
// crafted files are the fuzz regressions of tests/fuzz/regressions/gltf/; here they load
// with the default limits (the fuzz target's are smaller). Also the texture-reference
// checks of item 7.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include "gltf_load_json.hpp"
#include "gltf_test_models.hpp"
#include "test_support.hpp"

using namespace foveal;
using nlohmann::json;

namespace {

long peak_rss_kb() {
  rusage u{};
  ::getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

Result<render::GltfScene> load_regression(const std::string& name) {
  test::NullGltfSink sink;
  const std::string bytes = test::read_file(test::source_path("tests/fuzz/regressions/gltf/" + name));
  return render::load_gltf_bytes(bytes, name, ".", {}, sink);
}

Result<render::GltfScene> load_json(const json& j) { return test::load_gltf_json(j, "crafted.gltf"); }

}  // namespace

TEST(GltfDecodedSize, AMeshoptViewClaimingMoreThanItsBytesCanHoldIsRefusedBeforeAllocation) {
  const long before = peak_rss_kb();
  // 924 bytes: a view of 2^26 × 16 bytes (1 GiB) decoded from 40 bytes; 1.1 GB was allocated.
  auto r = load_regression("meshopt_view_claims_1gib.gltf");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::bad_input);
  EXPECT_NE(r.error().message.find("meshopt_view_claims_1gib.gltf: buffer view 2 (EXT_meshopt_compression): count 67108864 × "
                                   "byteStride 16 = 1073741824 bytes cannot be decoded from 40 compressed bytes (mode ATTRIBUTES)"),
            std::string::npos)
      << r.error().message;
  EXPECT_LT(peak_rss_kb() - before, 100 * 1024) << "the loader allocated the claimed size";
}

TEST(GltfDecodedSize, UnusedSparseAccessorsAreNotDecoded) {
  const long before = peak_rss_kb();
  // 852 bytes: two sparse accessors of 2^26 VEC4 floats (1 GiB each) without a buffer
  // view, which no primitive reads; they were densified (2.1 GB) before the quad loaded.
  auto r = load_regression("sparse_unused_2gib.gltf");
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->triangles, 2u);
  EXPECT_LT(peak_rss_kb() - before, 100 * 1024) << "an unused sparse accessor was decoded";
}

TEST(GltfDecodedSize, ASparseAccessorWithoutAViewIsHeldToTheZeroAccessorCap) {
  const long before = peak_rss_kb();
  auto r = load_regression("sparse_position_without_view.gltf");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("sparse_position_without_view.gltf: accessor 0 (sparse): count 67108864 elements without a "
                                   "buffer view (all zeros) is more than the 1048576 accepted"),
            std::string::npos)
      << r.error().message;
  EXPECT_LT(peak_rss_kb() - before, 100 * 1024);
}

TEST(GltfTextureRefs, WrongTypesInTextureTransformAndHugeTexCoordsAreErrorsNamingTheMember) {
  json base = test::quad_model();
  base["materials"] = json::array({json::object()});
  base["meshes"][0]["primitives"][0]["material"] = 0;
  base["textures"] = json::array({json::object()});
  struct Case {
    json texture_info;
    std::string message;
  };
  const std::string t = "materials[0].pbrMetallicRoughness.baseColorTexture";
  const std::string x = t + ".extensions.KHR_texture_transform";
  const Case cases[] = {
      {{{"index", 0}, {"texCoord", 4294967297ull}}, t + ".texCoord: 4294967297 is out of range (0..2147483647)"},
      {{{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"offset", "a"}}}}}}, x + ".offset: must be an array of 2 numbers, got \"a\""},
      {{{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"scale", {1, "b"}}}}}}}, x + ".scale[1]: must be a number, got \"b\""},
      {{{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"rotation", true}}}}}}, x + ".rotation: must be a number, got true"},
      {{{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 4294967297ull}}}}}},
       x + ".texCoord: 4294967297 is out of range (0..2147483647)"},
      {{{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 1.5}}}}}}, x + ".texCoord: must be an integer, got 1.5"},
      {{{"index", 0}, {"extensions", {{"KHR_texture_transform", 7}}}}, x + ": must be an object, got 7"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.message);
    json j = base;
    j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = c.texture_info;
    auto r = load_json(j);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().kind, ErrorKind::bad_input);
    EXPECT_NE(r.error().message.find("crafted.gltf: " + c.message), std::string::npos) << r.error().message;
  }
  // The spec-gloss extension's textures are checked the same way.
  json j = base;
  j["materials"][0]["extensions"]["KHR_materials_pbrSpecularGlossiness"]["diffuseTexture"] = {{"index", 0}, {"texCoord", -1}};
  auto r = load_json(j);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("materials[0].extensions.KHR_materials_pbrSpecularGlossiness.diffuseTexture.texCoord: -1 is out of range"),
            std::string::npos)
      << r.error().message;
}
