// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// CSV output of the demo: node positions per frame and the spring list.

#include <string>
#include <vector>

#include "gencoord/deformable/mass_spring_system.hpp"

namespace gencoord::deformable::demo {

/// One saved frame: time and node positions (m), 2 x n.
struct Frame {
  double t = 0.0;
  Eigen::Matrix2Xd x;
};

/// Writes frames.csv (frame,time,node,x,y) and springs.csv (spring,i,j,broken_at) into
/// `folder`; broken_at is the time the spring broke (s), empty if it never did.
/// Throws std::runtime_error if a file cannot be written.
void write_csv(const std::string& folder, const std::vector<Frame>& frames,
               const MassSpringSystem<2>& final_state);

/// True if spring k is intact at time t (from the system's fracture events).
bool spring_intact_at(const MassSpringSystem<2>& s, int k, double t);

}  // namespace gencoord::deformable::demo
