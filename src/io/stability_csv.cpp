// Schemas of the stability outputs; see stability_csv.hpp.
#include "io/stability_csv.hpp"

namespace bkq {

const Schema& stability_schema() {
  static const Schema schema = {
      {"value", "", "value of the swept key (drive.speed without a sweep)"},
      {"mode", "", "family:index (chain:q, pad:0, 1dof:0)", kText},
      {"re", "1/time", "growth rate Re lambda (> 0: the mode grows)"},
      {"im", "1/time", "Im lambda >= 0 (a complex pair is listed once)"},
      {"frequency", "1/time", "Im lambda / 2 pi"},
      {"unstable", "", "1 when Re lambda > 0", kInteger},
  };
  return schema;
}

const Schema& stability_summary_schema() {
  static const Schema schema = {
      {"value", "", "value of the swept key (drive.speed without a sweep)"},
      {"speed", "length/time", "disc speed v of the sliding equilibrium"},
      {"phi", "force/mass", "kinetic friction phi(v) per unit block mass"},
      {"phi_slope", "force time/(mass length)", "phi'(v): friction damping per unit block mass"},
      {"pad_x", "length", "pad position at equilibrium (0 unless bkp)"},
      {"modes", "", "eigenvalues listed (complex pairs once)", kInteger},
      {"unstable_modes", "", "eigenvalues with Re lambda > 0", kInteger},
      {"max_re", "1/time", "largest Re lambda"},
      {"max_re_frequency", "1/time", "frequency Im lambda / 2 pi of the mode with the largest Re"},
      {"max_re_mode", "", "family:index of that mode (the first of tied chain modes)", kText},
      {"pad_re", "1/time", "largest Re lambda of the pad family (bkp; nan otherwise)"},
      {"pad_frequency", "1/time", "its frequency (bkp; nan otherwise)"},
  };
  return schema;
}

const Schema& modes_schema() {
  static const Schema schema = {
      {"value", "", "value of the swept key (drive.speed without a sweep)"},
      {"mode", "", "family:index", kText},
      {"lambda_re", "1/time", "Re lambda of the mode"},
      {"lambda_im", "1/time", "Im lambda of the mode"},
      {"dof", "", "block index 0..N-1, or N for the pad", kInteger},
      {"re", "length", "real part of the displacement amplitude (largest amplitude 1)"},
      {"im", "length", "imaginary part of the displacement amplitude"},
  };
  return schema;
}

}  // namespace bkq
