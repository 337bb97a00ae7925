// The files of `bkquake stability` (app/stability.cpp): stability.csv (every eigenvalue at
// every swept value), stability_summary.csv (one row per swept value) and modes.csv (the
// mode shapes asked for with --modes). Columns declared once here; the writer, the reference docs
// tables and analysis/plot_stability.py use these names.
#pragma once

#include <string>

#include "io/schema.hpp"

namespace bkq {

const Schema& stability_schema();
const Schema& stability_summary_schema();
const Schema& modes_schema();

}  // namespace bkq
