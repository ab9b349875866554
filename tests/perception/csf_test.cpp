// FovVideoVDP's CSF: values the reference's shipped tables hold (pyfvvdp/csf_cache, release
// 1.2, k_cm 0.604562, 1.5 cycles), read with scipy at grid points; see docs/metrics.md.
#include <gtest/gtest.h>

#include <cmath>

#include "foveal/perception/csf.hpp"

namespace foveal::perception {
namespace {

TEST(Csf, MatchesTheReferenceTableAtGridPoints) {
  struct Point {
    double rho, omega, lum, ecc, log2_s;
  };
  // rho, omega, L and ecc on the reference's grid; log2 S as its table stores it.
  const Point pts[] = {
#include "data/csf_points.inc"
  };
  for (const Point& p : pts)
    EXPECT_NEAR(std::log2(csf_sensitivity(p.rho, p.omega, p.lum, p.ecc, -1.5, 0.604562)), p.log2_s, 2e-3)
        << "rho " << p.rho << " omega " << p.omega << " L " << p.lum << " ecc " << p.ecc;
}

TEST(Csf, TableReadsTheFormulaBetweenGridPoints) {
  const CsfTable t(0.0, -1.5, 0.604562);
  // Within a cell the table is linear in log2 S; at 4 cpd, 50 cd/m², 10° it is within 2%.
  const double exact = std::log2(csf_sensitivity(4.0, 0.0, 50.0, 10.0, -1.5, 0.604562));
  EXPECT_NEAR(t.log2_sensitivity(2.0f, static_cast<float>(std::log2(50.0)), static_cast<float>(std::sqrt(10.0))), exact, 0.03);
}

TEST(Csf, PeaksAtAFewCyclesAndFallsWithEccentricity) {
  const auto s = [](double rho, double ecc) { return csf_sensitivity(rho, 0.0, 100.0, ecc, -1.5, 0.604562); };
  EXPECT_GT(s(3.0, 0), s(0.25, 0));
  EXPECT_GT(s(3.0, 0), s(20.0, 0));
  EXPECT_GT(s(8.0, 0), s(8.0, 10));
  EXPECT_GT(s(8.0, 10), s(8.0, 30));
}

}  // namespace
}  // namespace foveal::perception
