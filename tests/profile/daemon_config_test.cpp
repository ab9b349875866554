// foveald's options file (foveal/runtime/daemon_config.hpp): what it accepts, what it
// refuses and how it names it, and that what set() writes parses back the same.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include "foveal/runtime/daemon_config.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

TEST(DaemonConfig, ParsesKeysValuesCommentsAndBlankLines) {
  auto c = DaemonConfig::parse("# mine\n\n  source =  hid  \nquality=jod:9.5\r\n", "f.conf");
  ASSERT_TRUE(c) << c.error().message;
  ASSERT_EQ(c->entries().size(), 2u);
  EXPECT_EQ(*c->get("source"), "hid");
  EXPECT_EQ(*c->get("quality"), "jod:9.5");
  EXPECT_EQ(c->get("head"), nullptr);
}

TEST(DaemonConfig, RefusesWhatItCannotReadNamingTheLine) {
  struct Case {
    const char* text;
    const char* says;
  } cases[] = {{"source = hid\nfrobnicate = 3\n", "f.conf:2: unknown key 'frobnicate'"},
               {"source\n", "f.conf:1: expected `key = value`"},
               {"source =\n", "f.conf:1: source: no value"},
               {"head = auto\nhead = static\n", "f.conf:2: head: given twice"}};
  for (const Case& k : cases) {
    auto c = DaemonConfig::parse(k.text, "f.conf");
    ASSERT_FALSE(c) << k.text;
    EXPECT_EQ(c.error().kind, ErrorKind::bad_input);
    EXPECT_NE(c.error().message.find(k.says), std::string::npos) << c.error().message;
  }
}

TEST(DaemonConfig, SetReplacesUnsetRemovesAndTheTextParsesBack) {
  DaemonConfig c;
  ASSERT_TRUE(c.set("source", "hid"));
  ASSERT_TRUE(c.set("quality", "jod:9"));
  ASSERT_TRUE(c.set("source", " psvr2 "));
  EXPECT_FALSE(c.set("nope", "1"));
  EXPECT_FALSE(c.set("head", "a\nsource = x"));
  EXPECT_FALSE(c.set("head", "  "));
  auto back = DaemonConfig::parse(c.text(), "t");
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->entries(), c.entries());
  EXPECT_EQ(*back->get("source"), "psvr2");
  EXPECT_TRUE(c.unset("quality"));
  EXPECT_FALSE(c.unset("quality"));
  EXPECT_EQ(c.entries().size(), 1u);
}

TEST(DaemonConfig, EveryKeyIsDocumented) {
  ASSERT_FALSE(daemon_config_keys().empty());
  for (const auto& k : daemon_config_keys()) {
    DaemonConfig c;
    EXPECT_TRUE(c.set(k.name, "x")) << k.name;
    EXPECT_GT(std::string(k.help).size(), 5u) << k.name;
  }
}

TEST(DaemonConfig, AMissingFileIsEmptyAndAFifoIsRefusedWithoutBlocking) {
  test::TempDir d;
  auto none = DaemonConfig::load(d.path("foveald.conf"));
  ASSERT_TRUE(none) << none.error().message;
  EXPECT_TRUE(none->entries().empty());
  ASSERT_EQ(::mkfifo(d.path("fifo").c_str(), 0600), 0);
  auto fifo = DaemonConfig::load(d.path("fifo"));
  ASSERT_FALSE(fifo);
  EXPECT_NE(fifo.error().message.find(d.path("fifo")), std::string::npos) << fifo.error().message;
}

}  // namespace
}  // namespace foveal
