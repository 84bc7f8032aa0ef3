// SPDX-License-Identifier: Apache-2.0
#include "sim/OrbitPropagator.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/Constants.hpp"

namespace flatsat::sim {
namespace {

// DOP853 (Hairer, Nørsett & Wanner, §II.10; coefficients of their code dop853.f):
// nodes c_i, stage matrix a_ij (lower triangle) and the 8th-order weights b_i.
constexpr int kStages = 12;
constexpr std::array<double, kStages> kC = {
    0.0,
    0.526001519587677318785587544488e-01,
    0.789002279381515978178381316732e-01,
    0.118350341907227396726757197510,
    0.281649658092772603273242802490,
    0.333333333333333333333333333333,
    0.25,
    0.307692307692307692307692307692,
    0.651282051282051282051282051282,
    0.6,
    0.857142857142857142857142857142,
    1.0,
};
constexpr double kA[kStages][kStages] = {
    {},
    {5.26001519587677318785587544488e-2},
    {1.97250569845378994544595329183e-2, 5.91751709536136983633785987549e-2},
    {2.95875854768068491816892993775e-2, 0.0, 8.87627564304205475450678981324e-2},
    {2.41365134159266685502369798665e-1, 0.0, -8.84549479328286085344864962717e-1, 9.24834003261792003115737966543e-1},
    {3.7037037037037037037037037037e-2, 0.0, 0.0, 1.70828608729473871279604482173e-1,
     1.25467687566822425016691814123e-1},
    {3.7109375e-2, 0.0, 0.0, 1.70252211019544039314978060272e-1, 6.02165389804559606850219397283e-2, -1.7578125e-2},
    {3.70920001185047927108779319836e-2, 0.0, 0.0, 1.70383925712239993810214054705e-1,
     1.07262030446373284651809199168e-1, -1.53194377486244017527936158236e-2, 8.27378916381402288758473766002e-3},
    {6.24110958716075717114429577812e-1, 0.0, 0.0, -3.36089262944694129406857109825,
     -8.68219346841726006818189891453e-1, 2.75920996994467083049415600797e1, 2.01540675504778934086186788979e1,
     -4.34898841810699588477366255144e1},
    {4.77662536438264365890433908527e-1, 0.0, 0.0, -2.48811461997166764192642586468,
     -5.90290826836842996371446475743e-1, 2.12300514481811942347288949897e1, 1.52792336328824235832596922938e1,
     -3.32882109689848629194453265587e1, -2.03312017085086261358222928593e-2},
    {-9.3714243008598732571704021658e-1, 0.0, 0.0, 5.18637242884406370830023853209, 1.09143734899672957818500254654,
     -8.14978701074692612513997267357, -1.85200656599969598641566180701e1, 2.27394870993505042818970056734e1,
     2.49360555267965238987089396762, -3.0467644718982195003823669022},
    {2.27331014751653820792359768449, 0.0, 0.0, -1.05344954667372501984066689879e1, -2.00087205822486249909675718444,
     -1.79589318631187989172765950534e1, 2.79488845294199600508499808837e1, -2.85899827713502369474065508674,
     -8.87285693353062954433549289258, 1.23605671757943030647266201528e1, 6.43392746015763530355970484046e-1},
};
constexpr std::array<double, kStages> kB = {
    5.42937341165687622380535766363e-2,
    0.0,
    0.0,
    0.0,
    0.0,
    4.45031289275240888144113950566,
    1.89151789931450038304281599044,
    -5.8012039600105847814672114227,
    3.1116436695781989440891606237e-1,
    -1.52160949662516078556178806805e-1,
    2.01365400804030348374776537501e-1,
    4.47106157277725905176885569043e-2,
};

// Every violation at once, before any member is built from them.
const OrbitForceParams& checked(const OrbitForceParams& params, const UtcEpoch& epoch,
                                const OrbitPropagator::State& initial) {
  std::vector<std::string> errors = params.validate();
  for (const std::string& error : epoch.validate()) errors.push_back("epoch." + error);
  if (!initial.r_N_m.allFinite() || !initial.v_N_m_s.allFinite()) {
    errors.push_back("initial: position and velocity must be finite");
  } else if (initial.r_N_m.norm() <= kEarthEquatorialRadius_m * (1.0 - kEarthFlattening)) {
    errors.push_back("initial.r_N_m: inside the Earth");
  }
  if (!errors.empty()) {
    std::string message = "invalid OrbitPropagator set-up: " + errors.front();
    for (std::size_t i = 1; i < errors.size(); ++i) message += "; " + errors[i];
    throw std::invalid_argument(message);
  }
  return params;
}

}  // namespace

OrbitPropagator::OrbitPropagator(const OrbitForceParams& params, const UtcEpoch& epoch, const State& initial)
    : forces_(checked(params, epoch, initial)),
      jd_tt_epoch_(julianDate(epoch) + params.tt_minus_utc_s / kSecondsPerDay),
      state_(initial),
      bodies_(forces_.ephemeridesAt(jd_tt_epoch_)) {}

double OrbitPropagator::jdTt(double t_s) const { return jd_tt_epoch_ + t_s / kSecondsPerDay; }

Eigen::Vector3d OrbitPropagator::acceleration_N(double t_s, const State& state) const {
  return forces_.acceleration_N(state.r_N_m, state.v_N_m_s, forces_.ephemeridesAt(jdTt(t_s)));
}

void OrbitPropagator::restart(double t_s, const State& state) {
  t_s_ = t_s;
  state_ = state;
  bodies_ = forces_.ephemeridesAt(jdTt(t_s));
}

void OrbitPropagator::step(double dt_s) {
  if (dt_s == 0.0 || !std::isfinite(dt_s)) return;
  const Ephemerides start = bodies_;
  const Ephemerides end = forces_.ephemeridesAt(jdTt(t_s_ + dt_s));

  // y' = (v, a(t, r, v)); stage i sees y + dt Σ_j a_ij k_j.
  std::array<Eigen::Vector3d, kStages> k_r;  // dr/dt = v at each stage
  std::array<Eigen::Vector3d, kStages> k_v;  // dv/dt = a at each stage
  for (int i = 0; i < kStages; ++i) {
    Eigen::Vector3d r = state_.r_N_m;
    Eigen::Vector3d v = state_.v_N_m_s;
    for (int j = 0; j < i; ++j) {
      if (kA[i][j] == 0.0) continue;
      r += (dt_s * kA[i][j]) * k_r[j];
      v += (dt_s * kA[i][j]) * k_v[j];
    }
    Ephemerides bodies;
    bodies.sun_N_m = start.sun_N_m + kC[i] * (end.sun_N_m - start.sun_N_m);
    bodies.moon_N_m = start.moon_N_m + kC[i] * (end.moon_N_m - start.moon_N_m);
    bodies.earth_angle_rad = start.earth_angle_rad + kC[i] * std::remainder(end.earth_angle_rad - start.earth_angle_rad,
                                                                            2.0 * std::numbers::pi);
    k_r[i] = v;
    k_v[i] = forces_.acceleration_N(r, v, bodies);
  }
  for (int i = 0; i < kStages; ++i) {
    if (kB[i] == 0.0) continue;
    state_.r_N_m += (dt_s * kB[i]) * k_r[i];
    state_.v_N_m_s += (dt_s * kB[i]) * k_v[i];
  }
  t_s_ += dt_s;
  bodies_ = end;
}

}  // namespace flatsat::sim
