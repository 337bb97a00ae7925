// Dieterich-Ruina rate-and-state friction (Dieterich 1979; Ruina 1983): a friction law with
// state, on its own path. It is not in model/law_list.hpp's list of rate-only laws (the event
// kernels are instantiated per law there); the cycle integrator (engine/rsf_cycle.hpp) and the
// stability analysis (stats/rsf_stability.hpp) call it directly.
//
//   log form          f(V, theta) = mu* + a ln(V/V*) + b_rsf ln(V* theta/D_c)
//   regularised form  f(V, theta) = a asinh[V/(2V*) exp(psi/a)], psi = mu* + b_rsf ln(V* theta/D_c)
//                     (Rice & Ben-Zion 1996; Lapusta et al. 2000): finite at V -> 0, equal to
//                     the log form to O(exp(-2 f/a)) where f >> a.
//   aging law         d theta/dt = 1 - V theta/D_c                 (Dieterich 1979; Ruina 1983)
//   slip law          d theta/dt = -(V theta/D_c) ln(V theta/D_c)   (Ruina 1983)
//
// The state is carried as ln theta and the slip rate as ln V (both laws are smooth and O(1)
// in these). b_rsf is the law's "rate-and-state b", never the Gutenberg-Richter b.
// Everything here is a pure function of one block's parameters, so an event-driven engine
// (Dieterich 1995 nucleation times) can reuse it.
#pragma once

#include <cmath>

namespace bkq::rsf {

enum class StateLaw { Aging, Slip };
enum class Form { Log, Regularised };

// One block's law, SI units.
struct Params {
  double a = 0.01;       // direct effect
  double b_rsf = 0.015;  // rate-and-state b (evolution effect), not Gutenberg-Richter's b
  double dc = 1e-5;      // critical slip distance D_c [m]
  double mu0 = 0.6;      // reference friction mu* at V*
  double v0 = 1e-6;      // reference slip rate V* [m/s]
};

// f and its logarithmic derivatives f_lnv = V df/dV, f_lntheta = theta df/dtheta (both
// forms): what the quasi-dynamic balance differentiated in time needs.
struct FrictionValue {
  double f = 0, f_lnv = 0, f_lntheta = 0;
};

// One block's law with its logarithms computed once (the integrators call it per step).
class Law {
 public:
  Law() : Law(Params{}) {}
  explicit Law(const Params& p)
      : p_(p),
        ln_v0_(std::log(p.v0)),
        ln_dc_(std::log(p.dc)),
        psi0_(p.mu0 + p.b_rsf * std::log(p.v0 / p.dc)) {}
  const Params& params() const { return p_; }

  FrictionValue friction(Form form, double ln_v, double ln_theta) const {
    const double psi = psi0_ + p_.b_rsf * ln_theta;
    if (form == Form::Log) return {psi + p_.a * (ln_v - ln_v0_), p_.a, p_.b_rsf};
    // x = V/(2V*) e^{psi/a}; f = a asinh x; V df/dV = a x/sqrt(1+x^2), theta df/dtheta = b that.
    const double x = 0.5 * std::exp(ln_v - ln_v0_ + psi / p_.a);
    const double s = x > 1 ? 1 / std::sqrt(1 + 1 / (x * x)) : x / std::sqrt(1 + x * x);
    return {p_.a * std::asinh(x), p_.a * s, p_.b_rsf * s};
  }

  // d ln(theta)/dt at slip rate exp(ln_v).
  double dlntheta_dt(StateLaw law, double ln_v, double ln_theta) const {
    return dlntheta_dt_at(law, std::exp(ln_v - ln_dc_), ln_v, ln_theta);
  }
  // The same with V = exp(ln_v) known already: one exponential fewer (the active-block
  // integrator's; rounds differently from the form above).
  double dlntheta_dt(StateLaw law, double v, double ln_v, double ln_theta) const {
    return dlntheta_dt_at(law, v / p_.dc, ln_v, ln_theta);
  }

  // Steady state at slip rate V: theta_ss = D_c/V (both state laws), and its friction.
  double steady_ln_theta(double v) const { return ln_dc_ - std::log(v); }
  double steady_friction(Form form, double v) const {
    return friction(form, std::log(v), steady_ln_theta(v)).f;
  }

 private:
  // Both state laws at omega = V/D_c.
  double dlntheta_dt_at(StateLaw law, double omega, double ln_v, double ln_theta) const {
    if (law == StateLaw::Aging) return std::exp(-ln_theta) - omega;  // 1/theta - V/D_c
    return -omega * (ln_v + ln_theta - ln_dc_);                      // -(V/D_c) ln(V theta/D_c)
  }

  Params p_;
  double ln_v0_, ln_dc_, psi0_;
};

// The quasi-static spring-slider's critical stiffness k_crit = sigma (b_rsf - a)/D_c (Ruina
// 1983; Rice & Ruina 1983): steady sliding is unstable below it (when b_rsf > a).
inline double critical_stiffness(const Params& p, double sigma) {
  return sigma * (p.b_rsf - p.a) / p.dc;
}

}  // namespace bkq::rsf
