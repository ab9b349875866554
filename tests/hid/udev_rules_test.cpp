// Checks udev/70-foveal.rules against the xr-hardware conventions (docs: DESIGN §9).
#include <gtest/gtest.h>

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

// Splits 'SUBSYSTEM=="usb", ATTRS{idVendor}=="054c", ATTRS{idProduct}=="0cde", TAG+="uaccess"'
// into subsystem and vendor:product; false if the line has any other shape.
bool parse_device_line(const std::string& line, std::string& subsystem, std::string& id) {
  auto quoted_after = [&](const std::string& key, std::size_t from, std::size_t& end) -> std::string {
    const std::size_t k = line.find(key, from);
    if (k == std::string::npos) return {};
    const std::size_t b = k + key.size();
    end = line.find('"', b);
    return end == std::string::npos ? std::string() : line.substr(b, end - b);
  };
  std::size_t e1 = 0, e2 = 0, e3 = 0;
  subsystem = quoted_after("SUBSYSTEM==\"", 0, e1);
  const std::string vendor = quoted_after(", ATTRS{idVendor}==\"", e1, e2);
  const std::string product = quoted_after(", ATTRS{idProduct}==\"", e2, e3);
  const bool hex4 = vendor.size() == 4 && product.size() == 4 &&
                    (vendor + product).find_first_not_of("0123456789abcdef") == std::string::npos;
  id = vendor + ":" + product;
  return line.rfind("SUBSYSTEM==\"", 0) == 0 && (subsystem == "hidraw" || subsystem == "usb") && hex4 &&
         line.substr(e3 + 1) == ", TAG+=\"uaccess\"";
}

TEST(UdevRules, EverySupportedTrackerHasHidrawAndUsbLinesWithUaccess) {
  const Rules r = load_rules();
  // The eye trackers, and the Vive / Vive Pro sensor devices `--head vive` opens.
  const std::set<std::string> expected = {"2104:020f", "054c:0cde", "03f0:0680", "35bd:0202", "28de:2000", "28de:2300"};
  std::set<std::string> hidraw, usb;
  for (std::size_t i = 1; i + 1 < r.lines.size(); ++i) {
    std::string subsystem, id;
    ASSERT_TRUE(parse_device_line(r.lines[i], subsystem, id)) << "unexpected rule: " << r.lines[i];
    (subsystem == "hidraw" ? hidraw : usb).insert(id);
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
