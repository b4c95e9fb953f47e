// Output: VTK files that ParaView reads (well-formed counts), histories with centred-difference accelerations,
// the JSON run report.

#include <doctest/doctest.h>

#include <filesystem>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "../file_contents.hpp"
#include "../approx.hpp"
#include "../integrate/fixtures.hpp"
#include "blockdem/contact/elastic.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/integrate/run.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "blockdem/io/history.hpp"
#include "blockdem/integrate/run_report.hpp"
#include "blockdem/io/vtk.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_output {

TEST_CASE("output: VTK blocks and contact points, histories and the run report") {
  auto s = test::block_on_base(1, 1, 1);
  s.model.gravity = Vec3::Zero();
  s.model.bodies.fixity[s.block] = model::Fixity::translation_x | model::Fixity::translation_y | model::Fixity::all_rotations;
  s.model.bodies.velocity[s.block] = Vec3(0, 0, 1e-3);
  const double omega = 2 * 3.141592653589793 * 5.0;
  Simulation<damping::None, contact::Elastic> sim(s.model, damping::None{},
                                                  [&](int, int) { return contact::Elastic::Parameters(2000 * omega * omega, 1e8); });
  sim.set_timestep(1e-3);
  io::HistoryRecorder history;
  history.add_point(s.model, "top", s.block, Vec3(0, 0, 1));
  const auto run = run_for(sim, 0.2, [&] { history.record(s.model, sim.time()); }, RunOptions{false, "test"});
  CHECK(run.steps == 200);
  CHECK_FALSE(run.interrupted);
  // u(t) = (v0/omega) sin(omega t): the recorded velocity and centred-difference acceleration follow it.
  const std::size_t k = 30;  // omega t = 0.97 rad, away from a zero crossing
  const double t = history.time(k);
  CHECK(history.displacement(k, 0).z() == test::approx(1e-3 / omega * std::sin(omega * (t - 0.5e-3))).epsilon(0.03));  // leapfrog phase
  CHECK(history.acceleration(k, 0).z() == test::approx(-1e-3 * omega * std::sin(omega * t - 1e-3 * omega)).epsilon(0.02));

  io::write_blocks_vtu((std::filesystem::temp_directory_path() / "blockdem_test_blocks.vtu").string(), s.model, {{"mass", {s.model.bodies.mass[0], s.model.bodies.mass[1]}}});
  const auto blocks = test::file_contents((std::filesystem::temp_directory_path() / "blockdem_test_blocks.vtu").string());
  CHECK(blocks.find("NumberOfPoints=\"16\" NumberOfCells=\"12\"") != std::string::npos);
  CHECK(blocks.find("Name=\"mass\"") != std::string::npos);
  io::write_contacts_vtu((std::filesystem::temp_directory_path() / "blockdem_test_contacts.vtu").string(), sim);
  const auto contacts = test::file_contents((std::filesystem::temp_directory_path() / "blockdem_test_contacts.vtu").string());
  CHECK(contacts.find("NumberOfPoints=\"4\" NumberOfCells=\"4\"") != std::string::npos);
  CHECK(contacts.find("Name=\"normal_stress\"") != std::string::npos);
  CHECK_THROWS_AS(io::write_blocks_vtu("/no/such/dir/x.vtu", s.model), InvalidArgument);

  const std::string report = io::run_report(sim, run).str();
  for (const char* field : {"\"dt\"", "\"steps\": 200", "\"wall_seconds\"", "\"ns_per_cp_step\"", "\"energy_balance_error\""})
    CHECK(report.find(field) != std::string::npos);
  history.write_csv((std::filesystem::temp_directory_path() / "blockdem_test_history.csv").string());
  CHECK(test::file_contents((std::filesystem::temp_directory_path() / "blockdem_test_history.csv").string()).rfind("time_s,top_ux,top_uy,top_uz,top_vx", 0) == 0);
}

}  // namespace test_output
