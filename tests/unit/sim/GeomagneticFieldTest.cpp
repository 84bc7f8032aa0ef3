// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <unistd.h>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "sim/GeomagneticField.hpp"

using namespace flatsat::sim;
using Catch::Matchers::Contains;

namespace {

// The repository root, from this file's absolute path (…/tests/unit/sim/GeomagneticFieldTest.cpp).
std::string igrfFile() {
  const std::filesystem::path root =
      std::filesystem::path(__FILE__).parent_path().parent_path().parent_path().parent_path();
  return (root / "data" / "igrf" / "igrf14coeffs.txt").string();
}

// A scratch coefficient file, removed when the test ends.
struct TempFile {
  explicit TempFile(const std::string& text)
      : path((std::filesystem::temp_directory_path() / ("flatsat_igrf_" + std::to_string(::getpid()) + ".txt"))
                 .string()) {
    std::ofstream(path) << text;
  }
  ~TempFile() { std::filesystem::remove(path); }
  std::string path;
};

const char* kHeader = "g/h n m 2000.0 2005.0 2005-10\n";

}  // namespace

TEST_CASE("igrfDipoleAt reads the IGRF-14 table", "[sim][field]") {
  const std::string file = igrfFile();
  // Expected values copied from the g 1 0, g 1 1 and h 1 1 rows of the file.
  GIVEN("an epoch of the table") {
    const DipoleCoefficients c2025 = igrfDipoleAt(file, 2025.0);
    CHECK(c2025.g10_nT == -29350.0);
    CHECK(c2025.g11_nT == -1410.3);
    CHECK(c2025.h11_nT == 4545.5);
    const DipoleCoefficients c2020 = igrfDipoleAt(file, 2020.0);
    CHECK(c2020.g10_nT == -29403.41);
    CHECK(c2020.g11_nT == -1451.37);
    CHECK(c2020.h11_nT == 4653.35);
    const DipoleCoefficients c1900 = igrfDipoleAt(file, 1900.0);
    CHECK(c1900.g10_nT == -31543.0);
    CHECK(c1900.h11_nT == 5922.0);
  }
  GIVEN("a year between two epochs") {
    THEN("the coefficients are interpolated linearly") {
      const DipoleCoefficients c = igrfDipoleAt(file, 2022.5);
      CHECK(c.g10_nT == Approx((-29403.41 + -29350.0) / 2.0).epsilon(1e-12));
      CHECK(c.g11_nT == Approx((-1451.37 + -1410.3) / 2.0).epsilon(1e-12));
      CHECK(c.h11_nT == Approx((4653.35 + 4545.5) / 2.0).epsilon(1e-12));
      CHECK(igrfDipoleAt(file, 1902.0).g10_nT == Approx(-31543.0 + 0.4 * (-31464.0 + 31543.0)).epsilon(1e-12));
    }
  }
  GIVEN("a year after the last epoch") {
    THEN("the secular variation extrapolates from 2025.0") {
      const DipoleCoefficients c = igrfDipoleAt(file, 2027.5);
      CHECK(c.g10_nT == Approx(-29350.0 + 2.5 * 12.6).epsilon(1e-12));
      CHECK(c.g11_nT == Approx(-1410.3 + 2.5 * 10.0).epsilon(1e-12));
      CHECK(c.h11_nT == Approx(4545.5 + 2.5 * -21.5).epsilon(1e-12));
      CHECK(igrfDipoleAt(file, 2030.0).g10_nT == Approx(-29350.0 + 5.0 * 12.6).epsilon(1e-12));
    }
  }
}

TEST_CASE("igrfDipoleAt reports bad files and years", "[sim][field]") {
  const std::string file = igrfFile();
  CHECK_THROWS_AS(igrfDipoleAt(file, 2030.5), std::runtime_error);
  CHECK_THROWS_WITH(igrfDipoleAt(file, 2030.5),
                    Contains("igrf14coeffs.txt") && Contains("2030.5") && Contains("outside [1900, 2030]"));
  CHECK_THROWS_WITH(igrfDipoleAt(file, 1899.9), Contains("outside [1900, 2030]"));
  CHECK_THROWS_WITH(igrfDipoleAt(file, std::nan("")), Contains("outside"));
  CHECK_THROWS_WITH(igrfDipoleAt("/nonexistent/igrf.txt", 2025.0), Contains("/nonexistent/igrf.txt: cannot open"));

  WHEN("a value is not a number") {
    const TempFile f(std::string("# comment\n") + kHeader + "g 1 0 -29619.4 x12 10.0\n");
    CHECK_THROWS_WITH(igrfDipoleAt(f.path, 2001.0), Contains(f.path + ":3:") && Contains("\"x12\" is not a number"));
  }
  WHEN("a row has too few columns") {
    const TempFile f(std::string(kHeader) + "g 1 0 -29619.4 10.0\n");
    CHECK_THROWS_WITH(igrfDipoleAt(f.path, 2001.0), Contains(":2:") && Contains("expected 3 values"));
  }
  WHEN("a dipole row is missing") {
    const TempFile f(std::string(kHeader) + "g 1 0 -29619.4 -29554.63 11.0\ng 1 1 -1728.2 -1669.05 8.0\n");
    CHECK_THROWS_WITH(igrfDipoleAt(f.path, 2001.0), Contains("no \"h 1 1\" row"));
  }
  WHEN("the header is missing") {
    const TempFile f("g 1 0 -29619.4 -29554.63 11.0\n");
    CHECK_THROWS_WITH(igrfDipoleAt(f.path, 2001.0), Contains(":1:") && Contains("before the \"g/h n m\" header"));
  }
  WHEN("a row has an unknown type") {
    const TempFile f(std::string(kHeader) + "q 1 0 1 2 3\n");
    CHECK_THROWS_WITH(igrfDipoleAt(f.path, 2001.0), Contains(":2:") && Contains("neither g nor h"));
  }
  WHEN("a small well-formed table") {
    // Degree-2 rows (complete, as the full parser requires) do not disturb the dipole.
    const TempFile f(std::string(kHeader) + "g 1 0 -100 -200 -10\ng 1 1 10 20 1\nh 1 1 30 60 2\ng 2 0 1 2 3\n" +
                     "g 2 1 1 2 3\nh 2 1 1 2 3\ng 2 2 1 2 3\nh 2 2 1 2 3\n");
    THEN("it is read and interpolated with its own epochs") {
      const DipoleCoefficients c = igrfDipoleAt(f.path, 2001.0);
      CHECK(c.g10_nT == Approx(-120.0));
      CHECK(c.g11_nT == Approx(12.0));
      CHECK(c.h11_nT == Approx(36.0));
      CHECK(igrfDipoleAt(f.path, 2008.0).g10_nT == Approx(-230.0));
      CHECK_THROWS_WITH(igrfDipoleAt(f.path, 2010.5), Contains("outside [2000, 2010]"));
    }
  }
}

TEST_CASE("TiltedDipoleField is the degree-1 spherical harmonic field", "[sim][field]") {
  const double a = kIgrfReferenceRadius_m;

  GIVEN("a centred axial dipole, g10 = −30000 nT") {
    const TiltedDipoleField field(DipoleCoefficients{-30000.0, 0.0, 0.0});
    const double r = a + 560e3;
    const double scale = std::pow(a / r, 3);
    WHEN("at the geographic north pole") {
      const Eigen::Vector3d b = field.b_E_T(Eigen::Vector3d(0.0, 0.0, r));
      THEN("B = 2 g10 (a/r)³, pointing down") {
        CHECK((b - Eigen::Vector3d(0.0, 0.0, 2.0 * -30000e-9 * scale)).norm() < 1e-18);
        CHECK(b.z() < 0.0);
      }
    }
    WHEN("on the equator") {
      const Eigen::Vector3d b = field.b_E_T(Eigen::Vector3d(r * std::cos(1.0), r * std::sin(1.0), 0.0));
      THEN("B has half the polar magnitude and points north") {
        CHECK((b - Eigen::Vector3d(0.0, 0.0, 30000e-9 * scale)).norm() < 1e-18);
      }
    }
  }

  GIVEN("the IGRF-14 2025 dipole") {
    const DipoleCoefficients c{-29350.0, -1410.3, 4545.5};
    const TiltedDipoleField field(c);
    const Eigen::Vector3d g(c.g11_nT, c.h11_nT, c.g10_nT);
    const double r = kEarthEquatorialRadius_m + 560e3;
    const double pole_T = 2.0 * g.norm() * 1e-9 * std::pow(a / r, 3);

    THEN("|B| is twice as large at the dipole poles as on the dipole equator") {
      CHECK(field.b_E_T(r * g.normalized()).norm() == Approx(pole_T).epsilon(1e-13));
      const Eigen::Vector3d on_equator = g.unitOrthogonal();
      CHECK(field.b_E_T(r * on_equator).norm() == Approx(0.5 * pole_T).epsilon(1e-13));
    }
    THEN("|B| at 560 km altitude lies between 20 and 50 µT everywhere") {
      for (double lat = -1.5; lat <= 1.5; lat += 0.1) {
        for (double lon = -3.1; lon <= 3.1; lon += 0.2) {
          const Eigen::Vector3d r_E =
              r * Eigen::Vector3d(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
          const double magnitude = field.b_E_T(r_E).norm();
          CHECK(magnitude > 2e-5);
          CHECK(magnitude < 5e-5);
        }
      }
    }
    THEN("B = −∇V with V = a (a/r)² [g10 cos θ + (g11 cos φ + h11 sin φ) sin θ]") {
      const auto potential = [&](const Eigen::Vector3d& p) {
        const double rr = p.norm();
        const double theta = std::acos(p.z() / rr);
        const double phi = std::atan2(p.y(), p.x());
        return a * std::pow(a / rr, 2) *
               (c.g10_nT * std::cos(theta) + (c.g11_nT * std::cos(phi) + c.h11_nT * std::sin(phi)) * std::sin(theta));
      };
      const Eigen::Vector3d p(3.1e6, -4.2e6, 4.4e6);
      const double h = 1.0;
      Eigen::Vector3d minus_grad;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d dp = h * Eigen::Vector3d::Unit(k);
        minus_grad(k) = -(potential(p + dp) - potential(p - dp)) / (2.0 * h) * 1e-9;
      }
      CHECK((field.b_E_T(p) - minus_grad).norm() < 1e-6 * minus_grad.norm());
    }
  }
}
