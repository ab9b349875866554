// Checks udev/70-foveal.rules against the xr-hardware conventions (docs: DESIGN §9).
#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <sstream>

#include "test_support.hpp"

namespace foveal {
namespace {

struct Rules {
  std::vector<std::string> lines;  // without comments and blank lines
};

Rules load_rules() {
  Rules r;
  std::istringstream in(test::read_file(test::source_path("udev/70-foveal.rules")));
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') r.lines.push_back(line);
  return r;
}

TEST(UdevRules, NumberedBelow73SoUaccessApplies) {
  const std::string name = "70-foveal.rules";
  EXPECT_LT(std::stoi(name.substr(0, 2)), 73);
  EXPECT_FALSE(load_rules().lines.empty());
}

TEST(UdevRules, RemoveEventsSkipToTheEndLabel) {
  const Rules r = load_rules();
  ASSERT_GE(r.lines.size(), 2u);
  EXPECT_EQ(r.lines.front(), R"(ACTION=="remove", GOTO="foveal_end")");
  EXPECT_EQ(r.lines.back(), R"(LABEL="foveal_end")");
}

TEST(UdevRules, EverySupportedTrackerHasHidrawAndUsbLinesWithUaccess) {
  const Rules r = load_rules();
  const std::set<std::string> expected = {"2104:020f", "054c:0cde", "03f0:0680", "35bd:0202"};
  const std::regex device_line(
      R"re(SUBSYSTEM=="(hidraw|usb)", ATTRS\{idVendor\}=="([0-9a-f]{4})", ATTRS\{idProduct\}=="([0-9a-f]{4})", TAG\+="uaccess")re");
  std::set<std::string> hidraw, usb;
  for (std::size_t i = 1; i + 1 < r.lines.size(); ++i) {
    std::smatch m;
    ASSERT_TRUE(std::regex_match(r.lines[i], m, device_line)) << "unexpected rule: " << r.lines[i];
    (m[1] == "hidraw" ? hidraw : usb).insert(m[2].str() + ":" + m[3].str());
  }
  EXPECT_EQ(hidraw, expected);
  EXPECT_EQ(usb, expected);
}

TEST(UdevRules, NothingIsWorldWritable) {
  for (const std::string& line : load_rules().lines) {
    EXPECT_EQ(line.find("MODE"), std::string::npos) << line;
    EXPECT_EQ(line.find("0666"), std::string::npos) << line;
  }
}

}  // namespace
}  // namespace foveal
