#include <gtest/gtest.h>

#include "foveal/render/shader_loader.hpp"
#include "gl_support.hpp"
#include "test_support.hpp"

using namespace foveal;

TEST(ShaderLoader, ExpandsIncludesWithLineMarkers) {
  test::TempDir d;
  std::filesystem::create_directories(d.path("common"));
  test::write_file(d.path("common/a.glsl"), "float a() { return 1.0; }\n");
  test::write_file(d.path("main.frag"), "// top\n#include \"common/a.glsl\"\nvoid main() {}\n");
  gl::ShaderLoader loader(d.path());
  std::vector<std::string> files;
  auto text = loader.expand("main.frag", files);
  ASSERT_TRUE(text) << text.error().message;
  ASSERT_EQ(files.size(), 2u);
  EXPECT_NE(text->find("#line 1 1\nfloat a()"), std::string::npos);
  EXPECT_NE(text->find("#line 3 0\nvoid main()"), std::string::npos);
}

TEST(ShaderLoader, MapsMesaAndNvidiaLogsToFileAndLine) {
  const std::vector<std::string> files = {"shaders/x.frag", "shaders/common/y.glsl"};
  EXPECT_EQ(gl::map_info_log("1:7(12): error: `q' undeclared\n", files), "shaders/common/y.glsl:7: error: `q' undeclared\n");
  EXPECT_EQ(gl::map_info_log("0(3) : error C1008: undefined variable\n", files), "shaders/x.frag:3: error C1008: undefined variable\n");
  EXPECT_EQ(gl::map_info_log("something else\n", files), "something else\n");
}

TEST(ShaderLoader, MissingFileIsAnErrorNamingIt) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir d;
  gl::ShaderLoader loader(d.path());
  auto p = loader.program({{GL_FRAGMENT_SHADER, "absent.frag"}});
  ASSERT_FALSE(p);
  EXPECT_NE(p.error().message.find("absent.frag"), std::string::npos) << p.error().message;
  // An include of a missing file names the included file.
  test::write_file(d.path("inc.frag"), "#include \"gone.glsl\"\nvoid main() {}\n");
  auto q = loader.program({{GL_FRAGMENT_SHADER, "inc.frag"}});
  ASSERT_FALSE(q);
  EXPECT_NE(q.error().message.find("gone.glsl"), std::string::npos) << q.error().message;
}

TEST(ShaderLoader, CompileErrorNamesTheIncludedFileAndLine) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir d;
  test::write_file(d.path("bad.glsl"), "// one\n// two\nfloat broken() { return undeclared_name; }\n");
  test::write_file(d.path("main.frag"), "#include \"bad.glsl\"\nout vec4 c;\nvoid main() { c = vec4(broken()); }\n");
  gl::ShaderLoader loader(d.path());
  auto p = loader.program({{GL_FRAGMENT_SHADER, "main.frag"}});
  ASSERT_FALSE(p);
  EXPECT_NE(p.error().message.find(d.path("bad.glsl") + ":3:"), std::string::npos) << p.error().message;
}

TEST(ShaderLoader, TheShippedShadersCompile) {
  ASSERT_TRUE(test::gl_ready());
  auto c = render::Compositor::create({}, test::source_shaders());
  ASSERT_TRUE(c) << c.error().message;
}
