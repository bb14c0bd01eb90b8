#pragma once

// nlohmann
#include <nlohmann/json.hpp>

// Package
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_model.h"

namespace sphere_contact_estimator::cli
{
/// A finite number, or null (JSON has no inf/NaN).
nlohmann::ordered_json number(double x);

/// One cylinder steady state as the JSON object contact_eval prints. Forces and torques are totals
/// over the effective length L; the *_per_length fields carry the paper's per-unit-length values.
nlohmann::ordered_json toJson(const CylinderState& state, const CylinderModel& model);

}  // namespace sphere_contact_estimator::cli
