#include "foveal/study/study_conditions.hpp"

#include "foveal/import/table_reader.hpp"

namespace foveal {

Result<std::map<std::string, PredictedJod>> read_predicted_jod(const std::string& path) {
  auto table = TableReader::open(path, ',');
  if (!table) return table.error();
  TableReader& t = *table;
  std::size_t col[5];
  const char* const names[5] = {"condition", "method", "sigma_d", "f", "predicted_jod"};
  for (int i = 0; i < 5; ++i) {
    auto c = t.column(names[i]);
    if (!c) return c.error();
    col[i] = *c;
  }
  const long left = t.find_column("predicted_jod_left"), right = t.find_column("predicted_jod_right");
  const long sigma_nd = t.find_column("sigma_nd");
  // Sums first; divided by the rows each label got at the end.
  std::map<std::string, PredictedJod> out;
  for (;;) {
    auto got = t.next();
    if (!got) return got.error();
    if (!*got) break;
    PredictedJod row{0, 0, 0, 1};
    auto jod = t.number<double>(col[4]);
    if (!jod) return jod.error();
    row.jod = *jod;
    double* eyes[2] = {&row.left, &row.right};
    const long eye_cols[2] = {left, right};
    for (int e = 0; e < 2; ++e) {
      *eyes[e] = row.jod;
      if (eye_cols[e] < 0) continue;
      auto v = t.number<double>(static_cast<std::size_t>(eye_cols[e]));
      if (!v) return v.error();
      *eyes[e] = *v;
    }
    for (std::size_t c : {col[0], col[1], col[2]})
      if (t.field(c).empty()) return t.field_error(c, "empty");
    const std::string label(t.field(col[0]));
    const std::string two_afc =
        std::string(t.field(col[1])) + " sigma=" + std::string(t.field(col[2])) + " f=" + std::string(t.field(col[3]));
    auto add = [&](const std::string& l) {
      PredictedJod& p = out[l];
      p.jod += row.jod, p.left += row.left, p.right += row.right, ++p.scenes;
    };
    add(label);
    // Only a uniform condition can be a 2AFC side; its RMFR label is that form already.
    const bool uniform = sigma_nd < 0 || t.field(static_cast<std::size_t>(sigma_nd)) == t.field(col[2]);
    if (uniform && two_afc != label) add(two_afc);
  }
  if (out.empty()) return bad_input(path + ": no conditions: the file has a header only");
  for (auto& [label, p] : out) p.jod /= p.scenes, p.left /= p.scenes, p.right /= p.scenes;
  return out;
}

}  // namespace foveal
