// accuracy.csv's columns (written by `bkquake accuracy`, app/accuracy.cpp): one row per
// scheme and dt of the work-precision study. Declared here with the other file schemas so
// the header, the docs table and analysis/plot_work_precision.py agree.
#pragma once

#include "io/schema.hpp"

namespace bkq {

// Column order is the CSV column order.
const Schema& accuracy_schema();
// accuracy_orders.csv: the observed orders of each fixed-step scheme and transition mode.
const Schema& accuracy_orders_schema();

}  // namespace bkq
