// SPDX-License-Identifier: Apache-2.0
#include "components/sun_sensor/SunSensorNode.hpp"

#include "components/Processes.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::sun_sensor {

EmulatorParams<SunSensorParams> readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                           const bus::NodeArgs& args, bus::ConfigProblems& problems) {
  return readEmulatorParams<SunSensorParams>(
      scenario, args.name, 3, "-", problems, [&](bus::ParamReader& r, SunSensorParams& m) {
    m.boresight_B = vehicle.truth.sensors.sun_sensor_boresight_B;
    m.boresight_onboard_B = vehicle.onboard.sensors.sun_sensor_boresight_B;
    vehicle::refuseMovedKeys(r, {{"boresight_body", "spacecraft.sensors.sun_sensor.boresight_body"}});
    r.read("noise_rad", m.noise_rad, "rad");
    r.read("fov_half_angle_rad", m.fov_half_angle_rad, "rad");
    r.read("min_illumination", m.min_illumination, "-");
    std::string type = "fine";
    r.read("type", type);
    if (type == "coarse_cosine") {
      m.kind = SunSensorKind::kCoarseCosine;
    } else if (type != "fine") {
      r.problem("type", "'" + type + "' is neither fine nor coarse_cosine");
    }
    if (r.has("cells")) {
      m.cell_normals_B.clear();
      for (auto& cell : r.list("cells")) {
        Eigen::Vector3d normal = Eigen::Vector3d::Zero();
        cell.read("normal_body", normal, "-");
        m.cell_normals_B.push_back(normal);
        cell.finish();
      }
    }
    r.read("cell_noise", m.cell_noise, "-");
    r.read("min_output", m.min_output, "-");
    if (r.has("albedo")) {
      sim::AlbedoParams albedo;
      r.read("albedo", albedo.albedo, "-");
      m.albedo = albedo;
    }
    for (const char* key : {"cells", "cell_noise", "min_output", "albedo"}) {
      if (r.has(key) && m.kind != SunSensorKind::kCoarseCosine) r.problem(key, "only with type: coarse_cosine");
    }
      });
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<SunSensorNode>(argc, argv, "sun_sensor", vehicle::withVehicle(readParams));
}

}  // namespace flatsat::sun_sensor

namespace flatsat {
template class EmulatorNode<sun_sensor::SunSensorModel, bus::topics::kSunSensor, sun_sensor::toInput,
                            sun_sensor::toMessage, &sun_sensor::SunSensorOutput::sun_B_unit>;
}  // namespace flatsat
