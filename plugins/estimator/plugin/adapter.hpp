// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The estimator plugin family (libmjf_estimator.so): one descriptor per file, each made by
// EstimatorPlugin<> (the destroy every estimator shares; its compute and report are its own).
#ifndef MJFORMATION_ESTIMATOR_PLUGIN_ADAPTER_HPP_
#define MJFORMATION_ESTIMATOR_PLUGIN_ADAPTER_HPP_

#include <mjformation/plugin.h>

#include <cstddef>
#include <mjformation/plugin_state.hpp>

namespace mjf::estimator::adapter {

template <typename Instance>
void EstimatorDestroy(void* instance) {
  delete static_cast<Instance*>(instance);
}

// The descriptor of an estimator plugin whose instance is Instance (no reset: an estimator
// starts again from create(); report: null for one with nothing to report).
template <typename Instance>
constexpr mjfPlugin EstimatorPlugin(const char* name, const char* doc, int n_attributes,
                                    const mjfAttribute* attributes,
                                    void* (*create)(const mjfCreateContext*),
                                    int (*compute)(void*, const mjfStepContext*),
                                    void (*report)(void*, mjfReportFn, void*) = nullptr) {
  static_assert(mjf::plugin::kHasVisitState<Instance>,
                "an estimator lists its state: template <typename Visit> void VisitState(Visit&) "
                "(mjformation/plugin_state.hpp)");
  return {MJF_ABI_VERSION,
          name,
          MJF_KIND_ESTIMATOR,
          doc,
          n_attributes,
          attributes,
          0,
          nullptr,
          create,
          compute,
          nullptr,
          EstimatorDestroy<Instance>,
          report,
          &mjf::plugin::StateSizeOf<Instance>,
          &mjf::plugin::GetStateOf<Instance>,
          &mjf::plugin::SetStateOf<Instance>};
}
template <typename Instance, size_t kAttributes>
constexpr mjfPlugin EstimatorPlugin(const char* name, const char* doc,
                                    const mjfAttribute (&attributes)[kAttributes],
                                    void* (*create)(const mjfCreateContext*),
                                    int (*compute)(void*, const mjfStepContext*),
                                    void (*report)(void*, mjfReportFn, void*) = nullptr) {
  return EstimatorPlugin<Instance>(name, doc, static_cast<int>(kAttributes), attributes, create,
                                   compute, report);
}

extern const mjfPlugin kPassthrough;  // plugin/passthrough.cc
extern const mjfPlugin kKfIns;        // plugin/kf_ins.cc

}  // namespace mjf::estimator::adapter

#endif  // MJFORMATION_ESTIMATOR_PLUGIN_ADAPTER_HPP_
