// Event markers in the native gaze log: write-then-read, readers of samples unaffected,
// and the marker rows a reader refuses.
#include <gtest/gtest.h>

#include "foveal/core/gaze_log.hpp"
#include "foveal/core/gaze_log_stats.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

std::vector<GazeSample> some_samples(int n) {
  std::vector<GazeSample> out(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    out[static_cast<std::size_t>(i)].t_ns = i * 8'333'333;
    out[static_cast<std::size_t>(i)].eyes[0] = {kValidDirection, {0.01f * static_cast<float>(i), 0.0f, -1.0f}};
  }
  return out;
}

TEST(GazeMarkers, SurviveWriteThenReadAndLeaveTheSamplesAlone) {
  test::TempDir d;
  GazeLogHeader h;
  h.rate_hz = 120;
  const std::vector<GazeSample> samples = some_samples(10);
  const std::vector<GazeMarker> marks = {{-5, "before, the first sample"}, {8'333'333, "trial 1: start"},
                                         {8'333'333, "same time as a sample"}, {40'000'000, "trial 1 end ✓"},
                                         {75'000'000, "after the last sample"}};
  auto w = GazeLogWriter::create(d.path("m.csv"), h);
  ASSERT_TRUE(w);
  ASSERT_TRUE(w->mark(marks[0]));
  for (std::size_t i = 0; i < samples.size(); ++i) {
    ASSERT_TRUE(w->write(samples[i]));
    if (i == 1) {
      ASSERT_TRUE(w->mark(marks[1]));
      ASSERT_TRUE(w->mark(marks[2]));
    }
    if (i == 4) {
      ASSERT_TRUE(w->mark(marks[3]));
    }
  }
  ASSERT_TRUE(w->mark(marks[4]));
  ASSERT_TRUE(w->commit());

  std::vector<GazeMarker> read_marks;
  auto got = read_gaze_log(d.path("m.csv"), nullptr, &read_marks);
  ASSERT_TRUE(got) << got.error().message;
  EXPECT_EQ(*got, samples);  // bit-exact, and no marker among them
  EXPECT_EQ(read_marks, marks);
  const std::string text = test::read_file(d.path("m.csv"));
  EXPECT_NE(text.find("\n#mark,40000000,trial 1 end ✓\n"), std::string::npos);

  // A reader that only wants samples sees the same log as without the markers.
  auto stats = compute_gaze_log_stats(d.path("m.csv"));
  ASSERT_TRUE(stats) << stats.error().message;
  EXPECT_EQ(stats->samples, 10u);
  // Rewinding forgets the markers read so far; reading again finds them again.
  auto r = GazeLogReader::open(d.path("m.csv"));
  ASSERT_TRUE(r);
  GazeSample s;
  while (*r->next(s)) {
  }
  EXPECT_EQ(r->markers().size(), 5u);
  ASSERT_TRUE(r->rewind());
  EXPECT_TRUE(r->markers().empty());
  ASSERT_TRUE(*r->next(s));
  EXPECT_EQ(r->markers().size(), 1u);

  // Logs without markers are written exactly as before: no marker rows, nothing else.
  auto plain = GazeLogWriter::create(d.path("p.csv"), h);
  ASSERT_TRUE(plain);
  for (const auto& x : samples) ASSERT_TRUE(plain->write(x));
  ASSERT_TRUE(plain->commit());
  std::string stripped;
  for (std::size_t pos = 0; pos < text.size();) {
    const std::size_t eol = text.find('\n', pos) + 1;
    if (text.compare(pos, 6, "#mark,") != 0) stripped += text.substr(pos, eol - pos);
    pos = eol;
  }
  EXPECT_EQ(stripped, test::read_file(d.path("p.csv")));
}

TEST(GazeMarkers, AreTheSameInV2Logs) {
  test::TempDir d;
  GazeLogHeader h;
  h.rate_hz = 120;
  h.version = kGazeLogV2;
  std::vector<GazeSample> samples = some_samples(3);
  samples[1].head.valid = true;
  samples[1].head.pose.position_m = {0.1f, 1.2f, -0.3f};
  auto w = GazeLogWriter::create(d.path("v2.csv"), h);
  ASSERT_TRUE(w);
  ASSERT_TRUE(w->write(samples[0]));
  ASSERT_TRUE(w->mark({1, "in a v2 log"}));
  ASSERT_TRUE(w->write(samples[1]));
  ASSERT_TRUE(w->write(samples[2]));
  ASSERT_TRUE(w->commit());
  std::vector<GazeMarker> marks;
  GazeLogHeader back;
  auto got = read_gaze_log(d.path("v2.csv"), &back, &marks);
  ASSERT_TRUE(got) << got.error().message;
  EXPECT_EQ(back.version, kGazeLogV2);
  EXPECT_EQ(*got, samples);
  EXPECT_EQ(marks, (std::vector<GazeMarker>{{1, "in a v2 log"}}));
}

TEST(GazeMarkers, TheWriterKeepsRowsInTimeOrder) {
  test::TempDir d;
  GazeLogHeader h;
  h.rate_hz = 120;
  auto w = GazeLogWriter::create(d.path("m.csv"), h);
  ASSERT_TRUE(w);
  ASSERT_TRUE(w->write(some_samples(1)[0]));
  GazeSample later = some_samples(3)[2];
  ASSERT_TRUE(w->mark({later.t_ns + 1, "x"}));
  EXPECT_FALSE(w->write(later));  // earlier than the marker before it
  EXPECT_FALSE(w->mark({0, "y"}));  // earlier than the marker before it
  const auto bad = w->mark({later.t_ns + 5, "line\nend"});
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("mark: byte 5 of the text is a control character"), std::string::npos);
  EXPECT_FALSE(w->mark({later.t_ns + 5, ""}));
  EXPECT_FALSE(w->mark({later.t_ns + 5, std::string(kMaxMarkerBytes + 1, 'x')}));
  EXPECT_TRUE(w->mark({later.t_ns + 5, std::string(kMaxMarkerBytes, 'x')}));
}

TEST(GazeMarkers, BadMarkerRowsNameTheLineAndColumn) {
  test::TempDir d;
  const std::string head = "# foveal-gaze-log v1\n# rate_hz=120\n" + [] {
    std::string cols;
    for (const auto& c : gaze_log_columns()) cols += (cols.empty() ? "" : ",") + c;
    return cols + "\n";
  }();
  const std::string row0 = "0,0,,,,,,,,,0,,,,,,,,,0,,,,,,\n", row1 = "100,0,,,,,,,,,0,,,,,,,,,0,,,,,,\n";
  auto error_of = [&](const std::string& body) {
    test::write_file(d.path("b.csv"), head + body);
    auto r = read_gaze_log(d.path("b.csv"));
    return r ? std::string("(no error)") : r.error().message;
  };
  const std::string p = d.path("b.csv");
  ASSERT_EQ(error_of(row0 + "#mark,50,ok\n" + row1), "(no error)");
  EXPECT_EQ(error_of(row0 + "# a comment\n" + row1), p + ":5: a row starting with '#' is a marker row, '#mark,T_NS,TEXT'");
  EXPECT_EQ(error_of(row0 + "#mark,abc,x\n" + row1), p + ":5: t_ns: 'abc' is not an integer");
  EXPECT_EQ(error_of(row0 + "#mark,50\n" + row1), p + ":5: t_ns: the marker row has no text (expected #mark,T_NS,TEXT)");
  EXPECT_EQ(error_of(row0 + "#mark,50,\n" + row1), p + ":5: text: the text is empty");
  EXPECT_EQ(error_of(row0 + "#mark,50,a\tb\n" + row1), p + ":5: text: byte 2 of the text is a control character");
  EXPECT_EQ(error_of(row1 + "#mark,50,back\n"), p + ":5: t_ns: marker time 50 is earlier than the row before it (100)");
  EXPECT_EQ(error_of(row0 + "#mark,150,x\n" + row1), p + ":6: t_ns: 100 is earlier than the marker before it (150)");
  EXPECT_EQ(error_of(row0 + "#mark,50,cut"), p + ":5: truncated: the file ends inside this marker row");
  EXPECT_EQ(error_of("#mark,50,only a marker\n"), p + ": no samples: the log has a header only");
  // Held to the samples' range [-2^62, 2^62) (issue 27): a marker minus a sample never overflows.
  EXPECT_EQ(error_of("#mark,-9223372036854775808,x\n" + row0 + row1),
            p + ":4: t_ns: marker time -9223372036854775808 is out of range (timestamps are in [-2^62, 2^62) ns, ±146 years)");
  EXPECT_EQ(error_of(row0 + row1 + "#mark,4611686018427387904,x\n"),
            p + ":6: t_ns: marker time 4611686018427387904 is out of range (timestamps are in [-2^62, 2^62) ns, ±146 years)");
  EXPECT_EQ(error_of("#mark,-4611686018427387904,x\n" + row0 + "#mark,4611686018427387903,y\n"), "(no error)");
  EXPECT_EQ(error_of(row0 + "#mark," + std::string(1000, '7') + ",x\n" + row1),
            p + ":5: t_ns: '" + std::string(60, '7') + "…' is not an integer");
  // A streaming reader keeps a bounded number of markers.
  std::string many = row0;
  for (std::size_t i = 0; i <= kMaxGazeLogMarkers; ++i) many += "#mark,1,m\n";
  EXPECT_EQ(error_of(many + row1), p + ":" + std::to_string(4 + kMaxGazeLogMarkers + 1) + ": more than " +
                                        std::to_string(kMaxGazeLogMarkers) + " markers; a gaze log holds at most that many");
}

}  // namespace
}  // namespace foveal
