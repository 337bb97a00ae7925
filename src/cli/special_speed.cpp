// `bkquake special-speed [SCENE]`: Ferre (2018, MSc thesis, NTNU) eq. 4.8 for a scene
// (app/special_speed.hpp).
#include <cmath>
#include <cstdio>
#include <iostream>

#include "app/special_speed.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "io/settings.hpp"

namespace bkq {

namespace {

int cmd_special_speed(const Args& args) {
  const Scene scene = scene_from_command_line(args);
  scene.validate();
  const ModelParams p = model_from_scene(scene);
  const SpecialSpeed s = special_speed(p);
  std::printf("t_death = %.6g\nv_special = %.6g\n", s.t_death, s.v_special);
  std::printf(
      "  (scene %s: m_u = %.6g, k_p = %.6g, F0 m_u = %.6g; rk4, dt = %.3g; constant\n"
      "   kinetic friction would give pi sqrt(m_u/k_p) = %.6g)\n",
      scene.origin.c_str(), p.m_u, p.k_p, p.threshold(), s.dt,
      3.14159265358979 * std::sqrt(p.m_u / p.k_p));
  return 0;
}

}  // namespace

Command special_speed_command_row() {
  return {"special-speed",
          "t_death and v_special = F0/(k_p t_death) of Ferre 2018 eq. 4.8",
          "[SCENE]",
          -1,
          "Releases the equally spaced chain from the slip threshold (substrate at rest, pad\n"
          "held) and prints t_death, the time until it is again at rest relative to the\n"
          "substrate, and v_special = F0 m_u / (k_p t_death) (Ferre 2018 eq. 4.8).\n",
          {scene_set_option()},
          cmd_special_speed};
}

}  // namespace bkq
