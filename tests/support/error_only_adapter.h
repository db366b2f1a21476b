// An initialised Adapter with one criterion, the geometric error (the options' T and eps)
// everywhere: for measuring accuracy on scenes whose default would not bound it everywhere
// (the sphere's multi-criteria default leaves its x >= 0 half to an edge length, paper 4.3).
// Shared by the unit tests and bench/compare_openvdb.
#pragma once

#include <memory>

#include "core/adapt/adapter.h"
#include "core/adapt/criteria.h"

namespace dynamesh::test {

inline std::unique_ptr<Adapter> error_only_adapter(Surface& surface, const AdaptOptions& options) {
  CriterionList criteria;
  criteria.push_back(std::make_unique<GeometricErrorCriterion>(options.threshold, options.epsilon));
  auto adapter = std::make_unique<Adapter>(surface, options, std::move(criteria));
  adapter->initialize();
  return adapter;
}

}  // namespace dynamesh::test
