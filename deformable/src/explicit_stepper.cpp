// SPDX-License-Identifier: BSD-3-Clause
// Symplectic Euler steps that validate the object and compute the CFL limit only when what
// they depend on may have changed (explicit_stepper.hpp).
#include "gencoord/deformable/explicit_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

#include "explicit_step.hpp"
#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/validate.hpp"

namespace gencoord::deformable {

// named, not anonymous: a member of ExplicitStepper<Dim>::Kept, which has external linkage
namespace detail {

// What the validation and the CFL limit depend on, short of every value: counts, events and
// the few settings a user changes between steps.
template <int Dim>
struct Signature {
  const MassSpringSystem<Dim>* object = nullptr;
  std::vector<std::size_t> counts;
  std::size_t fractures = 0;
  std::vector<double> settings;
  std::vector<char> pinned;

  explicit Signature(const MassSpringSystem<Dim>& s)
      : object(&s), fractures(s.fractures.size()), pinned(s.pinned) {
    counts = {static_cast<std::size_t>(s.x.cols()),
              static_cast<std::size_t>(s.v.cols()),
              static_cast<std::size_t>(s.mass.size()),
              s.springs.size(),
              s.elements.size(),
              s.quadratic_elements.size(),
              s.volume_terms.size(),
              s.hinges.size(),
              s.ground.has_value(),
              s.collisions.has_value()};
    settings = {s.wave_speed, s.inelastic.fracture_strain, s.inelastic.yield_strain,
                s.inelastic.plastic_fraction};
    for (int d = 0; d < Dim; ++d) settings.push_back(s.gravity(d));
    if (s.ground)
      settings.insert(settings.end(), {s.ground->height, s.ground->omega, s.ground->damping_ratio});
    if (s.collisions) {
      const ContactParams& p = s.collisions->params;
      settings.insert(settings.end(), {p.omega, p.damping_ratio, p.friction, p.thickness});
      counts.insert(counts.end(), {s.collisions->spheres.size(), s.collisions->boxes.size(),
                                   s.collisions->surface.size(), s.collisions->two_sided.size(),
                                   s.collisions->surface_thickness.size()});
      settings.insert(settings.end(), s.collisions->surface_thickness.begin(),
                      s.collisions->surface_thickness.end());
    }
  }
  // NaN settings compare unequal, so an object with one is validated (and refused) again
  bool operator==(const Signature& o) const {
    return fractures == o.fractures && same_but_fractures(o);
  }
  // a fracture only removes stiffness, so it lowers every frequency: the last estimate holds
  bool same_but_fractures(const Signature& o) const {
    return object == o.object && counts == o.counts && settings == o.settings && pinned == o.pinned;
  }
};

}  // namespace detail

template <int Dim>
struct ExplicitStepper<Dim>::Kept {
  ExplicitOptions options;
  std::optional<detail::Signature<Dim>> validated;  // the object as last validated
  double limit = 0.0;
  // stable_step_limit() and cfl_limit() when it was computed, for plasticity's steps
  double estimated = 0.0, conservative = 0.0;
};

template <int Dim>
ExplicitStepper<Dim>::ExplicitStepper(const ExplicitOptions& options)
    : kept_(std::make_unique<Kept>()) {
  kept_->options = options;
}

template <int Dim>
ExplicitStepper<Dim>::~ExplicitStepper() = default;
template <int Dim>
ExplicitStepper<Dim>::ExplicitStepper(ExplicitStepper&&) noexcept = default;
template <int Dim>
ExplicitStepper<Dim>& ExplicitStepper<Dim>::operator=(ExplicitStepper&&) noexcept = default;

template <int Dim>
double ExplicitStepper<Dim>::cfl_limit() const {
  return kept_->limit;
}

template <int Dim>
void ExplicitStepper<Dim>::invalidate() {
  kept_->validated.reset();
}

template <int Dim>
void ExplicitStepper<Dim>::step(MassSpringSystem<Dim>& s, double dt) {
  validate_time_step(dt);
  Kept& k = *kept_;
  detail::Signature<Dim> now(s);
  const bool plastic = std::isfinite(s.inelastic.yield_strain);
  if (!k.validated || !(*k.validated == now)) {
    const bool fractured = k.validated && k.validated->same_but_fractures(now);
    k.validated.reset();
    validate_object(s);
    if (fractured) {
      k.limit = std::max(deformable::cfl_limit(s), k.limit);
    } else {
      k.limit = k.estimated = stable_step_limit(s);
      k.conservative = deformable::cfl_limit(s);
    }
    k.validated = std::move(now);
  } else if (plastic) {
    // yielding changes rest lengths: the estimate (too costly to repeat every step) follows
    // the change of L_min / c_s when that shrinks, and never grows
    const double conservative = deformable::cfl_limit(s);
    k.limit = std::max(conservative, k.estimated * std::min(1.0, conservative / k.conservative));
  }
  detail::check_cfl(s, dt, k.limit, k.options, /*estimated=*/true);
  try {
    detail::take_symplectic_euler_step(s, dt);
  } catch (const ObjectError&) {
    // a value changed in place since the validation may be the cause: name it if so
    k.validated.reset();
    validate_object(s);
    throw;
  }
  // a fracture changes the signature (its event), so the next step checks again
}

template class ExplicitStepper<1>;
template class ExplicitStepper<2>;
template class ExplicitStepper<3>;

}  // namespace gencoord::deformable
