// Typed settings: the scene's keys read once into Settings, with their declared defaults
// and with given values, and the substrate built from the drive settings.
#include <gtest/gtest.h>

#include "io/scene.hpp"
#include "io/settings.hpp"
#include "io/timeseries.hpp"

namespace bkq {
namespace {

TEST(Settings, DefaultsAreTheDeclaredOnes) {
  const Settings s = settings_from_scene(Scene());
  EXPECT_EQ(s.model.n, 100);
  EXPECT_EQ(s.drive.mode, DriveMode::Events);
  EXPECT_EQ(s.drive.schedule, Schedule::Constant);
  EXPECT_EQ(s.drive.speed, 0.01);
  EXPECT_EQ(s.run.events, 100000);
  EXPECT_EQ(s.run.transient_events, 1000);
  EXPECT_EQ(s.run.duration, 1000);
  EXPECT_EQ(s.run.seed, 20261121u);
  EXPECT_EQ(s.run.initial_disorder, 0.01);
  EXPECT_EQ(s.run.max_steps_per_event, 200000000);
  EXPECT_EQ(s.run.checkpoint_events, 0);
  EXPECT_EQ(s.run.checkpoint_seconds, 600);
  EXPECT_EQ(s.integrator.scheme, "rk4");
  EXPECT_EQ(s.integrator.dt, 0.01);
  EXPECT_EQ(s.integrator.tolerance, 1e-8);
  EXPECT_EQ(s.output.every, 1);
  EXPECT_FALSE(s.output.blocks);
  EXPECT_EQ(s.stats.bin_width, 0.2);
  EXPECT_FALSE(s.stats.mu_min.has_value());
  EXPECT_FALSE(s.stats.mu_max.has_value());
}

TEST(Settings, GivenValuesArriveTyped) {
  Scene scene;
  for (const auto& [k, v] :
       std::vector<std::pair<std::string, std::string>>{{"model.kind", "bkp"},
                                                        {"model.blocks", "12"},
                                                        {"drive.mode", "continuous"},
                                                        {"drive.schedule", "steps"},
                                                        {"drive.speed", "0.25"},
                                                        {"drive.step_increment", "0.5"},
                                                        {"drive.step_interval", "10"},
                                                        {"run.seed", "9223372036854775807"},
                                                        {"run.checkpoint_events", "7"},
                                                        {"integrator.scheme", "adaptive"},
                                                        {"integrator.tolerance", "1e-6"},
                                                        {"output.every", "0.5"},
                                                        {"output.blocks", "yes"},
                                                        {"stats.mu_min", "-3.5"},
                                                        {"stats.mu_max", "2"}})
    scene.set(k, v);
  scene.validate();
  const Settings s = settings_from_scene(scene);
  EXPECT_EQ(s.model.kind, ModelKind::BKP);
  EXPECT_EQ(s.model.n, 12);
  EXPECT_EQ(s.drive.mode, DriveMode::Continuous);
  EXPECT_EQ(s.drive.schedule, Schedule::Steps);
  EXPECT_EQ(s.run.seed, 9223372036854775807u);
  EXPECT_EQ(s.run.checkpoint_events, 7);
  EXPECT_EQ(s.integrator.scheme, "adaptive");
  EXPECT_EQ(s.integrator.tolerance, 1e-6);
  EXPECT_EQ(s.output.every, 0.5);
  EXPECT_TRUE(s.output.blocks);
  EXPECT_EQ(s.stats.mu_min, -3.5);
  EXPECT_EQ(s.stats.mu_max, 2.0);

  // The substrate follows the schedule: 0.25 until t = 10, then 0.75.
  const Substrate sub = substrate_of(s.drive);
  EXPECT_EQ(sub.kind(), Substrate::Kind::Steps);
  EXPECT_DOUBLE_EQ(sub.at(5).v, 0.25);
  EXPECT_DOUBLE_EQ(sub.at(15).v, 0.75);
  EXPECT_DOUBLE_EQ(sub.at(15).s, 0.25 * 10 + 0.75 * 5);
}

TEST(Settings, SubstrateOfEachSchedule) {
  DriveSettings d;
  d.speed = 2;
  EXPECT_EQ(substrate_of(d).kind(), Substrate::Kind::Constant);
  EXPECT_DOUBLE_EQ(substrate_of(d).at(3).s, 6);
  d.schedule = Schedule::Ramp;
  d.ramp_from = 0;
  d.ramp_to = 1;
  d.ramp_duration = 10;
  EXPECT_EQ(substrate_of(d).kind(), Substrate::Kind::Ramp);
  EXPECT_DOUBLE_EQ(substrate_of(d).at(5).v, 0.5);
}

TEST(TimeSeries, HeaderFollowsSchemaAndContract) {
  EXPECT_EQ(timeseries_header(), "t,speed,substrate,pad_x,pad_v,pad_friction,sliding");
  for (const auto& c : timeseries_schema()) EXPECT_STRNE(c.doc, "") << c.name;
  EXPECT_EQ(timeseries_row({0.5, 0.01, 0.005, -1e-3, 0, 2.5, 3}), "0.5,0.01,0.005,-0.001,0,2.5,3");
  EXPECT_EQ(blocks_header(0, 3), "t,u0,u1,u2,v0,v1,v2");
  EXPECT_EQ(blocks_row(1.5, {0.1, -2}), "1.5,0.1,-2");
}

}  // namespace
}  // namespace bkq
