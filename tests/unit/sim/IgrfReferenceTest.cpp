// SPDX-License-Identifier: Apache-2.0
// IGRF-14 against values of the official synthesis routine.
#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include "sim/SphericalHarmonicField.hpp"
#include "tests/support/ReferenceData.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;
using Catch::Matchers::Contains;

namespace {

struct Reference {
  double year;        // [yr]
  double height;      // [km] geodetic height, or geocentric radius
  double colat;       // [deg] geodetic or geocentric colatitude
  double elong;       // [deg] east longitude
  double x, y, z, f;  // [nT]
};

// Rows of test/IGRF14_test_geodetic.txt and test/IGRF14_test_geocentric.txt in
// JuliaSpace/SatelliteToolboxGeomagneticField.jl (commit 1e20190), written by the
// official IAGA Fortran routine igrf14syn through JuliaSpace/IGRF_Test igrf_test.f90,
// X/Y/Z/F printed to 1e-5 nT. Chosen to cover 1900–2030: the degree-10 era, the
// 1995–2000 ramp to degree 13, the 2025–2030 secular-variation span, the exact
// north pole (colatitude 0.00), the equator and heights from 22 to 1600 km. (The
// files hold the northern hemisphere only; the WMM test covers the southern.)
//
// The generator draws a geocentric radius r on a 10 m grid and uses the geodetic
// height h = r − 6378.137 km, but prints h to 10 m: the third decimal, always 3, is
// restored here (e.g. 6610.46 − 6378.137 = 232.323, printed 232.32). Without it the
// values differ by up to 0.07 nT, 3 m of height in a 20 nT/km gradient.
const Reference kGeodetic[] = {
    {1900.0, 232.323, 68.00, 165.11, 27505.75351, 3089.91355, 16985.87684, 32475.12977},
    {1900.3, 463.013, 89.99, 325.30, 22589.76491, -5901.50351, 8099.34021, 24712.84148},
    {1903.4, 97.363, 5.25, 324.81, 1922.85321, -4639.03205, 53694.13843, 53928.45710},
    {1904.8, 217.873, 87.60, 67.78, 31953.86497, -1115.01248, -8228.33404, 33015.12108},
    {1912.3, 461.203, 0.27, 149.15, 5.54379, 2869.14288, 47029.33285, 47116.77154},
    {1919.5, 985.463, 0.50, 331.50, -59.98400, -2314.93184, 38068.36404, 38138.73160},
    {1930.0, 386.283, 0.14, 161.21, -725.00436, 2503.17778, 47798.71664, 47869.70694},
    {1935.1, 764.313, 0.00, 236.90, -2138.10990, 163.93029, 41099.85692, 41155.76054},
    {1933.9, 1064.283, 0.43, 336.94, 132.95589, -1989.89795, 36651.72246, 36705.94135},
    {1939.5, 1560.933, 90.00, 359.67, 14356.36028, -3541.50609, -2801.11974, 15049.70490},
    {1949.3, 360.293, 89.92, 55.30, 28321.31444, -1639.25832, -9690.11452, 29978.03094},
    {1956.4, 1120.703, 53.01, 334.96, 14250.20463, -4216.15759, 22832.79720, 27242.99809},
    {1965.7, 1458.113, 81.83, 21.80, 16943.30709, -1453.81655, -260.93654, 17007.56672},
    {1971.9, 372.193, 4.23, 244.39, -1032.48029, 117.36753, 48759.11091, 48770.18236},
    {1985.1, 1008.023, 0.05, 0.32, 678.99083, -1271.85929, 37824.89930, 37852.36666},
    {1988.0, 138.163, 56.85, 318.49, 23164.89042, -7333.27843, 32808.52011, 40826.31642},
    {1990.6, 34.183, 34.51, 24.06, 16779.17251, 1244.60056, 46474.73203, 49426.61609},
    {1993.0, 1145.393, 88.84, 343.59, 16112.16708, -3907.33032, -3484.93100, 16941.48465},
    {1994.3, 1089.143, 8.77, 197.54, 2242.55459, 1405.39473, 36637.01333, 36732.47788},
    {1995.0, 979.913, 62.19, 26.54, 20126.66083, 185.56791, 16152.10630, 25807.12013},
    {1995.7, 402.693, 35.19, 351.32, 14802.33906, -2270.37986, 38564.20124, 41369.81367},
    {1997.7, 852.803, 44.17, 58.11, 15820.37474, 1266.69548, 31408.31025, 35190.49200},
    {1998.7, 72.513, 4.65, 187.94, 768.97585, 961.41929, 55186.78237, 55200.51268},
    {1999.9, 71.873, 27.35, 69.35, 11518.02511, 3662.80927, 54633.99162, 55954.92932},
    {2000.0, 1514.413, 27.01, 52.63, 7527.39723, 875.79145, 28511.48178, 29501.41205},
    {2002.0, 1087.423, 1.04, 286.16, -514.63887, -921.12626, 36586.52565, 36601.73747},
    {2007.8, 22.303, 56.50, 124.72, 31620.55412, -3493.11484, 36683.01698, 48556.20485},
    {2012.2, 77.183, 4.81, 190.69, 750.03774, 394.68103, 55395.16588, 55401.64919},
    {2015.7, 369.723, 0.63, 281.69, 36.69265, -1392.96459, 48605.28127, 48625.25130},
    {2017.3, 729.653, 82.62, 99.60, 28743.35898, -460.45708, -107.47262, 28747.24780},
    {2020.9, 717.063, 61.97, 73.14, 24211.79873, 357.81216, 22840.59828, 33287.11699},
    {2022.1, 829.103, 46.47, 114.85, 17590.40262, -1731.07191, 33147.28408, 37565.42714},
    {2024.4, 333.353, 87.10, 188.31, 27594.53690, 4669.21356, 1412.69184, 28022.41460},
    {2025.0, 1540.893, 42.00, 101.60, 11649.28961, -470.23265, 26494.12335, 28945.90885},
    {2025.1, 365.313, 70.32, 91.32, 32686.57992, -438.71103, 17847.05145, 37244.08973},
    {2025.6, 769.393, 34.06, 186.33, 13707.48134, 1229.10986, 34340.24473, 36995.38031},
    {2026.3, 1258.963, 0.12, 311.77, 261.32350, -519.90412, 34486.39062, 34491.29931},
    {2027.9, 139.863, 45.06, 138.29, 23759.41728, -4335.97718, 42511.80742, 48893.39810},
    {2028.4, 1034.243, 39.54, 296.89, 10825.08139, -2737.49034, 31481.89119, 33403.37877},
    {2029.9, 554.553, 47.36, 192.94, 18365.55340, 2412.51292, 29274.52518, 34642.62684},
    {2030.0, 397.343, 17.78, 246.22, 4642.74152, 854.57128, 48023.38690, 48254.85499},
};

const Reference kGeocentric[] = {
    // radius [km] in the second column
    {1900.0, 6610.46, 68.00, 165.11, 27405.59329, 3074.66838, 17132.54518, 32466.04740},
    {1971.9, 6750.33, 4.23, 244.39, -1045.63966, 128.93455, 48340.11401, 48351.59366},
    {1991.7, 7895.51, 34.52, 186.99, 9961.03296, 1855.53539, 25360.82131, 27310.00635},
    {2012.2, 6455.32, 4.81, 190.69, 716.25521, 404.85533, 54898.32179, 54904.48675},
    {1990.6, 6412.32, 34.51, 24.06, 16463.66462, 1223.60691, 46293.60423, 49149.23458},
    {1985.1, 7386.16, 0.05, 0.32, 664.68242, -1268.46751, 37518.62935, 37545.94999},
    {1949.3, 6738.43, 89.92, 55.30, 28321.59739, -1639.20107, -9689.29713, 29978.03092},
    {2027.9, 6518.00, 45.06, 138.29, 23401.96250, -4296.86589, 42525.97951, 48729.59920},
    {2027.0, 6480.13, 68.54, 277.27, 24526.15584, -2284.08774, 29399.38466, 38354.57202},
    {1904.8, 6596.01, 87.60, 67.78, 31959.65616, -1113.68047, -8199.89322, 33013.60560},
    {1926.2, 6418.11, 17.26, 353.96, 8894.94113, -3951.37650, 49889.25682, 50829.82688},
};

}  // namespace

TEST_CASE("IGRF-14 reproduces the official igrf14syn values", "[sim][geomag]") {
  // igrf14syn computes in single precision, ~1e-7 of 50 000 nT; the
  // agreement found is within 0.02 nT, the requirement 0.1 nT.
  const double tolerance_nT = 0.1;
  GIVEN("geodetic points from 1900 to 2030") {
    for (const Reference& row : kGeodetic) {
      const SphericalHarmonicField igrf = igrf14(kIgrfFile, row.year);
      const GeodeticPosition p{(90.0 - row.colat) * kDeg, row.elong * kDeg, row.height * 1e3};
      const MagneticElements e = igrf.elements(p);
      INFO("year " << row.year << ", h " << row.height << " km, colatitude " << row.colat << ", longitude "
                   << row.elong);
      CHECK(e.b_G_nT.x() == Approx(row.x).margin(tolerance_nT));
      CHECK(e.b_G_nT.y() == Approx(row.y).margin(tolerance_nT));
      CHECK(e.b_G_nT.z() == Approx(row.z).margin(tolerance_nT));
      CHECK(e.f_nT == Approx(row.f).margin(tolerance_nT));
    }
  }
  GIVEN("geocentric points") {
    for (const Reference& row : kGeocentric) {
      const SphericalHarmonicField igrf = igrf14(kIgrfFile, row.year);
      const Eigen::Vector3d b =
          igrf.b_C_nT(GeocentricPosition{row.height * 1e3, (90.0 - row.colat) * kDeg, row.elong * kDeg});
      INFO("year " << row.year << ", r " << row.height << " km, colatitude " << row.colat);
      CHECK(b.x() == Approx(row.x).margin(tolerance_nT));
      CHECK(b.y() == Approx(row.y).margin(tolerance_nT));
      CHECK(b.z() == Approx(row.z).margin(tolerance_nT));
      CHECK(b.norm() == Approx(row.f).margin(tolerance_nT));
    }
  }
  GIVEN("years past 2030, which igrf14syn extrapolates and IGRF-14 does not cover") {
    CHECK_THROWS_WITH(igrf14(kIgrfFile, 2030.1), Contains("2030.1") && Contains("outside [1900, 2030]"));
  }
}

TEST_CASE("IGRF-14 degree and secular variation follow the table", "[sim][geomag]") {
  CHECK(igrf14(kIgrfFile, 1900.0).coefficients().degree == 10);
  CHECK(igrf14(kIgrfFile, 1994.9).coefficients().degree == 10);
  CHECK(igrf14(kIgrfFile, 1995.0).coefficients().degree == 13);  // ramps from 0 towards 2000
  CHECK(igrf14(kIgrfFile, 2030.0).coefficients().degree == 13);

  // Values copied from the g 1 0 and h 13 13 rows of the file.
  const GaussCoefficients c2022 = igrf14(kIgrfFile, 2022.5).coefficients();
  CHECK(c2022.g_nT[1][0] == Approx((-29403.41 - 29350.0) / 2.0).epsilon(1e-13));
  CHECK(c2022.g_dot_nT_yr[1][0] == Approx((-29350.0 + 29403.41) / 5.0).epsilon(1e-12));
  CHECK(c2022.h_nT[13][13] == Approx((-0.60 - 0.5) / 2.0).epsilon(1e-13));
  const GaussCoefficients c2028 = igrf14(kIgrfFile, 2028.0).coefficients();
  CHECK(c2028.g_nT[1][0] == Approx(-29350.0 + 3.0 * 12.6).epsilon(1e-13));
  CHECK(c2028.g_dot_nT_yr[1][0] == 12.6);
  CHECK(c2028.h_nT[13][13] == -0.5);  // no SV beyond degree 8

  GIVEN("a point and a year inside a five-year segment and inside the SV span") {
    const GeodeticPosition p{-33.0 * kDeg, 18.0 * kDeg, 450e3};
    for (double year : {1952.3, 2012.6, 2027.4}) {
      const double dt = 0.5;
      const Eigen::Vector3d rate = igrf14(kIgrfFile, year).bDot_G_nT_yr(p);
      const Eigen::Vector3d difference =
          (igrf14(kIgrfFile, year + dt).b_G_nT(p) - igrf14(kIgrfFile, year - dt).b_G_nT(p)) / (2.0 * dt);
      THEN("the secular variation is the time derivative of the field, the model being linear there") {
        CHECK((rate - difference).norm() < 1e-8);
        CHECK(rate.norm() > 10.0);
      }
    }
  }
}
