// The name of every scene key as a constant, for the code that reads, sets or checks one: a
// misspelt key::drive_mode does not compile, where a misspelt "drive.mode" would fail only
// when that line runs. Everything else about a key (type, default, range, units, doc, the
// member it fills, when it applies) is its row in io/scene_table.cpp, which takes this
// constant; a new key is one constant here and one row there.
#pragma once

#include <string>

namespace bkq {

// A key's name ("section.key"). Converts to the text the Scene's accessors and messages take.
struct Key {
  const char* name;
  operator std::string() const { return name; }  // NOLINT(google-explicit-constructor)
};

namespace key {
// [model]
inline constexpr Key model_kind{"model.kind"};
inline constexpr Key model_parameterisation{"model.parameterisation"};
inline constexpr Key model_blocks{"model.blocks"};
inline constexpr Key model_boundary{"model.boundary"};
inline constexpr Key model_rows{"model.rows"};
inline constexpr Key model_boundary_y{"model.boundary_y"};
inline constexpr Key model_coupling{"model.coupling"};
inline constexpr Key model_range{"model.range"};
inline constexpr Key model_coupling_exponent{"model.coupling_exponent"};
inline constexpr Key model_viscosity{"model.viscosity"};
inline constexpr Key model_l{"model.l"};
inline constexpr Key model_l_y{"model.l_y"};
inline constexpr Key model_pad_mass{"model.pad_mass"};
inline constexpr Key model_caliper_stiffness{"model.caliper_stiffness"};
inline constexpr Key model_damping_ratio{"model.damping_ratio"};
inline constexpr Key model_s_m{"model.s_m"};
inline constexpr Key model_s_p{"model.s_p"};
inline constexpr Key model_s_c{"model.s_c"};
inline constexpr Key model_s_c_y{"model.s_c_y"};
inline constexpr Key model_rayleigh_alpha{"model.rayleigh_alpha"};
inline constexpr Key model_rayleigh_beta{"model.rayleigh_beta"};
inline constexpr Key model_stiffness{"model.stiffness"};
inline constexpr Key model_coupling_stiffness{"model.coupling_stiffness"};
inline constexpr Key model_coupling_stiffness_y{"model.coupling_stiffness_y"};
inline constexpr Key model_dynamics{"model.dynamics"};
inline constexpr Key model_shear_modulus{"model.shear_modulus"};
inline constexpr Key model_shear_wave_speed{"model.shear_wave_speed"};
inline constexpr Key model_mass_per_area{"model.mass_per_area"};

// [ofc]
inline constexpr Key ofc_alpha{"ofc.alpha"};
inline constexpr Key ofc_order{"ofc.order"};
inline constexpr Key ofc_relaxation_time{"ofc.relaxation_time"};
inline constexpr Key ofc_relaxation_alpha{"ofc.relaxation_alpha"};

// [friction]
inline constexpr Key friction_law{"friction.law"};
inline constexpr Key friction_F0{"friction.F0"};
inline constexpr Key friction_sigma{"friction.sigma"};
inline constexpr Key friction_alpha{"friction.alpha"};
inline constexpr Key friction_vc{"friction.vc"};
inline constexpr Key friction_table{"friction.table"};

// [rsf]
inline constexpr Key rsf_a{"rsf.a"};
inline constexpr Key rsf_b{"rsf.b"};
inline constexpr Key rsf_dc{"rsf.dc"};
inline constexpr Key rsf_mu0{"rsf.mu0"};
inline constexpr Key rsf_v0{"rsf.v0"};
inline constexpr Key rsf_state_law{"rsf.state_law"};
inline constexpr Key rsf_form{"rsf.form"};
inline constexpr Key rsf_normal_stress{"rsf.normal_stress"};
inline constexpr Key rsf_v_threshold{"rsf.v_threshold"};
inline constexpr Key rsf_v_init{"rsf.v_init"};
inline constexpr Key rsf_theta_init{"rsf.theta_init"};
inline constexpr Key rsf_blocks{"rsf.blocks"};
inline constexpr Key rsf_slow_slip_threshold{"rsf.slow_slip_threshold"};
inline constexpr Key rsf_pattern{"rsf.pattern"};
inline constexpr Key rsf_handover_speed{"rsf.handover_speed"};
inline constexpr Key rsf_creep_quantum{"rsf.creep_quantum"};
inline constexpr Key rsf_event_integration{"rsf.event_integration"};
inline constexpr Key rsf_alone_speed{"rsf.alone_speed"};
inline constexpr Key rsf_alone_tolerance{"rsf.alone_tolerance"};
inline constexpr Key rsf_pattern_period{"rsf.pattern_period"};
inline constexpr Key rsf_pattern_width{"rsf.pattern_width"};

// [drive]
inline constexpr Key drive_mode{"drive.mode"};
inline constexpr Key drive_speed{"drive.speed"};
inline constexpr Key drive_schedule{"drive.schedule"};
inline constexpr Key drive_step_increment{"drive.step_increment"};
inline constexpr Key drive_step_interval{"drive.step_interval"};
inline constexpr Key drive_ramp_from{"drive.ramp_from"};
inline constexpr Key drive_ramp_to{"drive.ramp_to"};
inline constexpr Key drive_ramp_duration{"drive.ramp_duration"};

// [run]
inline constexpr Key run_events{"run.events"};
inline constexpr Key run_transient_events{"run.transient_events"};
inline constexpr Key run_duration{"run.duration"};
inline constexpr Key run_seed{"run.seed"};
inline constexpr Key run_initial_disorder{"run.initial_disorder"};
inline constexpr Key run_start{"run.start"};
inline constexpr Key run_start_mode{"run.start_mode"};
inline constexpr Key run_start_mode_index{"run.start_mode_index"};
inline constexpr Key run_start_amplitude{"run.start_amplitude"};
inline constexpr Key run_max_steps_per_event{"run.max_steps_per_event"};
inline constexpr Key run_checkpoint_events{"run.checkpoint_events"};
inline constexpr Key run_checkpoint_seconds{"run.checkpoint_seconds"};
inline constexpr Key run_accuracy{"run.accuracy"};

// [integrator]
inline constexpr Key integrator_scheme{"integrator.scheme"};
inline constexpr Key integrator_dt{"integrator.dt"};
inline constexpr Key integrator_transitions{"integrator.transitions"};
inline constexpr Key integrator_tolerance{"integrator.tolerance"};
inline constexpr Key integrator_theta{"integrator.theta"};

// [output]
inline constexpr Key output_every{"output.every"};
inline constexpr Key output_blocks{"output.blocks"};
inline constexpr Key output_block_first{"output.block_first"};
inline constexpr Key output_block_count{"output.block_count"};
inline constexpr Key output_status{"output.status"};
inline constexpr Key output_energy{"output.energy"};
inline constexpr Key output_energy_window{"output.energy_window"};
inline constexpr Key output_energy_tol{"output.energy_tol"};
inline constexpr Key output_catalog{"output.catalog"};
inline constexpr Key output_event_slip{"output.event_slip"};
inline constexpr Key output_segment_blocks{"output.segment_blocks"};

// [stats]
inline constexpr Key stats_bin_width{"stats.bin_width"};
inline constexpr Key stats_mu_min{"stats.mu_min"};
inline constexpr Key stats_mu_max{"stats.mu_max"};
}  // namespace key

}  // namespace bkq
